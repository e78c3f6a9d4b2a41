!> Small shared pieces tested directly: the cubic Hermite basis of the slow clocks, the
!> named state layout, the step controller's error norm and stretch rule, the wind's
!> direction convention.
module test_core
  use davit_kinds, only: wp, pi
  use davit_core_hermite, only: hermite_weights
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_solve_step_control, only: error_norm, stretch_to, is_finite_real
  use davit_sea_wind, only: new_wind, wind_velocity
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_core

contains

  function collect_core() result(suite)
    type(suite_type) :: suite
    suite%name = "core"
    suite%cases = [new_case("hermite_reproduces_cubics", hermite_cubics), &
                   new_case("layout_ranges_by_hand", layout_ranges), &
                   new_case("error_norm_and_stretch_by_hand", step_rules), &
                   new_case("wind_blows_towards_its_direction", wind_direction)]
  end function collect_core

  !> A cubic's values and rates at the ends of a window give it back everywhere inside
  !> (the basis is exact for cubics); for the quartic t^4 on [0, 1] the Hermite remainder
  !> f - p = f''''/4! s^2 (1-s)^2 h^4 is 1/16 at s = 1/2.
  subroutine hermite_cubics(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: c(4) = [0.7_wp, -1.3_wp, 2.1_wp, 0.45_wp], w(2) = [1.3_wp, 1.8_wp]
    real(wp) :: hw(4), t, worst
    integer :: i
    worst = 0.0_wp
    do i = 0, 10
      t = w(1) + 0.05_wp*i
      hw = hermite_weights(w, t)
      worst = max(worst, abs(hw(1)*f(w(1)) + hw(2)*df(w(1)) + hw(3)*f(w(2)) + &
                             hw(4)*df(w(2)) - f(t)))
    end do
    call check(state, worst, 0.0_wp, "cubic reproduced", abs_tol=1.0e-12_wp)
    hw = hermite_weights([0.0_wp, 1.0_wp], 0.5_wp)
    call check(state, 0.5_wp**4 - (hw(3) + 4.0_wp*hw(4)), 1.0_wp/16.0_wp, &
               "quartic remainder s^2 (1-s)^2 at s = 1/2", abs_tol=1.0e-14_wp)
  contains
    pure real(wp) function f(x)
      real(wp), intent(in) :: x
      f = c(1) + x*(c(2) + x*(c(3) + x*c(4)))
    end function f
    pure real(wp) function df(x)
      real(wp), intent(in) :: x
      df = c(2) + x*(2.0_wp*c(3) + 3.0_wp*x*c(4))
    end function df
  end subroutine hermite_cubics

  !> Parts are appended q block then u block: [boat q 6, u 6][drum q 1][sub: a q 2 u 2]
  !> gives boat q 1-6 u 7-12, drum q 13 (no speeds), a q 14-15 u 16-17; n = 17, nu = 8.
  subroutine layout_ranges(state)
    type(case_state), intent(inout) :: state
    type(state_layout_type) :: lay, sub
    type(state_part_type) :: p
    integer :: offset
    call lay%add("boat", 6, 6)
    call lay%add("drum", 1, 0)
    call sub%add("a", 2, 2)
    call lay%append(sub, offset)
    call check_true(state, lay%n == 17 .and. lay%nu == 8 .and. offset == 13, "n, nu, offset")
    p = lay%part("boat")
    call check_true(state, all(p%q == [1, 6]) .and. all(p%u == [7, 12]), "boat ranges")
    p = lay%part("drum")
    call check_true(state, all(p%q == [13, 13]) .and. p%u(2) == p%u(1) - 1, "drum: q only")
    p = lay%part("a")
    call check_true(state, all(p%q == [14, 15]) .and. all(p%u == [16, 17]), "appended part")
    p = lay%part("none")
    call check_true(state, p%q(2) < p%q(1) .and. p%u(2) < p%u(1), "unknown part is empty")
  end subroutine layout_ranges

  !> err = sqrt(mean((e_i/(atol + rtol max|y|))^2)) by hand; a step within 1 % of the
  !> target is stretched onto it, one short by more is not; NaN is not finite.
  subroutine step_rules(state)
    type(case_state), intent(inout) :: state
    real(wp) :: expected
    expected = sqrt(((1.0e-6_wp/2.001e-3_wp)**2 + (2.0e-6_wp/5.01e-4_wp)**2)/2.0_wp)
    call check(state, error_norm([1.0e-6_wp, -2.0e-6_wp], [1.0_wp, 0.0_wp], &
                                 [2.0_wp, -0.5_wp], 1.0e-6_wp, 1.0e-3_wp), expected, &
               "error norm", rel_tol=1.0e-14_wp)
    call check_true(state, stretch_to(1.0_wp, 1.0099_wp), "stretched within 1 %")
    call check_true(state, .not. stretch_to(1.0_wp, 1.0101_wp), "not stretched beyond 1 %")
    call check_true(state, .not. is_finite_real(ieee_value(1.0_wp, ieee_quiet_nan)), &
                    "NaN is not finite")
  end subroutine step_rules

  !> The direction is where the wind blows towards, from N1 to N2: 0 -> +N1, pi/2 -> +N2.
  subroutine wind_direction(state)
    type(case_state), intent(inout) :: state
    real(wp) :: v(3)
    v = wind_velocity(new_wind(10.0_wp, 0.0_wp))
    call check(state, norm2(v - [10.0_wp, 0.0_wp, 0.0_wp]), 0.0_wp, "towards N1", &
               abs_tol=1.0e-12_wp)
    v = wind_velocity(new_wind(10.0_wp, 0.5_wp*pi))
    call check(state, norm2(v - [0.0_wp, 10.0_wp, 0.0_wp]), 0.0_wp, "towards N2", &
               abs_tol=1.0e-12_wp)
  end subroutine wind_direction

end module test_core
