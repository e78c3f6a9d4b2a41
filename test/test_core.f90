!> Small shared pieces tested directly: the cubic Hermite basis and the slow clock's two
!> window rules, the named state layout, the step controller's error norm and stretch
!> rule, the wind's direction convention.
module test_core
  use davit_kinds, only: wp, pi
  use davit_core_hermite, only: hermite_weights, hermite_interpolate, hermite_max
  use davit_core_slow_clock, only: slow_clock_type, new_slow_clock, clock_grid, clock_reach, &
                                   clock_kept, clock_shifted, clock_renewed
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_solve_step_control, only: error_norm, stretch_to, is_finite_real
  use davit_sea_wind, only: new_wind, wind_velocity
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_core

contains

  function collect_core() result(suite)
    type(suite_type) :: suite
    suite%name = "core"
    suite%cases = [new_case("hermite_reproduces_cubics", hermite_cubics), &
                   new_case("hermite_interpolate_cubics_and_quartic", interpolate_cubics), &
                   new_case("hermite_max_of_cubics_by_hand", cubic_maxima), &
                   new_case("slow_clock_windows_by_hand", clock_windows), &
                   new_case("slow_clock_sine_error_bound_and_order4", clock_sine), &
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

  !> hermite_max against maxima worked by hand: t^3 - 3 t on [-2, 1.5] peaks inside at
  !> t = -1 (2; the ends give -2 and -1.125); -(t - 1)^2 on [0, 2] at t = 1 (0; ends -1);
  !> 2 - (t - 1)^2 on [0, 1.5] at t = 1 (2, near the end: 1.75); monotone t^3 + t on
  !> [-1, 2] at its right end (10); a straight line (the derivative's quadratic
  !> degenerate) at its larger end.
  subroutine cubic_maxima(state)
    type(case_state), intent(inout) :: state
    call check(state, hermite_max([-2.0_wp, 1.5_wp], -2.0_wp, 9.0_wp, -1.125_wp, 3.75_wp), &
               2.0_wp, "t^3 - 3 t on [-2, 1.5]", abs_tol=1.0e-13_wp)
    call check(state, hermite_max([0.0_wp, 2.0_wp], -1.0_wp, 2.0_wp, -1.0_wp, -2.0_wp), &
               0.0_wp, "-(t - 1)^2 on [0, 2]", abs_tol=1.0e-13_wp)
    call check(state, hermite_max([0.0_wp, 1.5_wp], 1.0_wp, 2.0_wp, 1.75_wp, -1.0_wp), &
               2.0_wp, "2 - (t - 1)^2 on [0, 1.5]", abs_tol=1.0e-13_wp)
    call check(state, hermite_max([-1.0_wp, 2.0_wp], -2.0_wp, 4.0_wp, 10.0_wp, 13.0_wp), &
               10.0_wp, "t^3 + t on [-1, 2]", abs_tol=1.0e-13_wp)
    call check(state, hermite_max([0.0_wp, 1.0_wp], 3.0_wp, -2.0_wp, 1.0_wp, -2.0_wp), &
               3.0_wp, "3 - 2 t on [0, 1]", abs_tol=1.0e-13_wp)
  end subroutine cubic_maxima

  !> hermite_interpolate on vectors: two cubics through their values and rates at the ends
  !> of [1.3, 1.8] come back everywhere inside (1e-12), and for t^4 on [0, 2] the remainder
  !> f''''/4! s^2 (1-s)^2 h^4 = 16/16 = 1 at s = 1/2, so the interpolant is 1 - 1 = 0 there.
  subroutine interpolate_cubics(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: w(2) = [1.3_wp, 1.8_wp]
    real(wp) :: p(2), t, worst
    integer :: i
    worst = 0.0_wp
    do i = 0, 10
      t = w(1) + 0.05_wp*i
      p = hermite_interpolate(w, f(w(1)), df(w(1)), f(w(2)), df(w(2)), t)
      worst = max(worst, maxval(abs(p - f(t))))
    end do
    call check(state, worst, 0.0_wp, "two cubics reproduced", abs_tol=1.0e-12_wp)
    p(1:1) = hermite_interpolate([0.0_wp, 2.0_wp], [0.0_wp], [0.0_wp], [16.0_wp], [32.0_wp], &
                                 1.0_wp)
    call check(state, p(1), 0.0_wp, "t^4 on [0, 2] at t = 1: 1 - remainder 1", &
               abs_tol=1.0e-14_wp)
  contains
    pure function f(x) result(v)
      real(wp), intent(in) :: x
      real(wp) :: v(2)
      v = [0.7_wp + x*(-1.3_wp + x*(2.1_wp + x*0.45_wp)), -2.0_wp + x*x*x]
    end function f
    pure function df(x) result(v)
      real(wp), intent(in) :: x
      real(wp) :: v(2)
      v = [-1.3_wp + x*(4.2_wp + 1.35_wp*x), 3.0_wp*x*x]
    end function df
  end subroutine interpolate_cubics

  !> The two window rules, by hand. clock_grid, h = 0.25: t = 0.3 opens [0.25, 0.5] (both
  !> ends new); 0.4 keeps it; 0.55 shifts it to [0.5, 0.75] (one new end); 1.6 jumps to
  !> [1.5, 1.75] (both new), and after invalidate the same t samples both ends again.
  !> clock_reach, h = 0.1: due at the first step (no window); open(0) gives [0, 0.1]; a
  !> step to 0.01 reaches 0.01 + 2 (0.01) = 0.03 <= 0.1 (not due), one to 0.05 reaches
  !> 0.05 + 2 (0.04) = 0.13 > 0.1 (due), one to 0.09 is due and, not opened, leaves the old
  !> window covering 0.09; a step back before t1 is due.
  subroutine clock_windows(state)
    type(case_state), intent(inout) :: state
    type(slow_clock_type) :: clock, off
    integer :: action
    clock = new_slow_clock(0.25_wp, clock_grid)
    call check_true(state, clock%enabled() .and. .not. clock%covers(0.3_wp), "no window yet")
    call clock%tick(0.3_wp, action)
    call check_true(state, action == clock_renewed, "first window: both ends")
    call check(state, clock%window(1), 0.25_wp, "grid window start", abs_tol=0.0_wp)
    call check(state, clock%window(2), 0.5_wp, "grid window end", abs_tol=0.0_wp)
    call clock%tick(0.4_wp, action)
    call check_true(state, action == clock_kept, "inside: kept")
    call clock%tick(0.55_wp, action)
    call check_true(state, action == clock_shifted, "next interval: shifted")
    call check(state, clock%window(1), 0.5_wp, "shifted start", abs_tol=0.0_wp)
    call check(state, clock%window(2), 0.75_wp, "shifted end", abs_tol=0.0_wp)
    call check_true(state, clock%covers(0.5_wp) .and. clock%covers(0.75_wp) .and. &
                    .not. clock%covers(0.76_wp), "covers its closed window only")
    call clock%tick(1.6_wp, action)
    call check_true(state, action == clock_renewed, "jump: renewed")
    call check(state, clock%window(1), 1.5_wp, "jump start", abs_tol=0.0_wp)
    call clock%invalidate()
    call clock%tick(1.6_wp, action)
    call check_true(state, action == clock_renewed, "invalidated: renewed")
    off = new_slow_clock(0.0_wp, clock_grid)
    call check_true(state, .not. off%enabled(), "interval 0: off")
    clock = new_slow_clock(0.1_wp, clock_reach)
    call clock%tick(0.0_wp, action)
    call check_true(state, action == clock_renewed, "reach: due without a window")
    call clock%open(0.0_wp)
    call check(state, clock%window(2), 0.1_wp, "reach: window [t, t + h]", abs_tol=0.0_wp)
    call clock%tick(0.01_wp, action)
    call check_true(state, action == clock_kept, "reach: short step stays inside")
    call clock%tick(0.05_wp, action)
    call check_true(state, action == clock_renewed, "reach: next step may leave the window")
    call clock%tick(0.09_wp, action)
    call check_true(state, action == clock_renewed .and. clock%covers(0.09_wp), &
                    "reach: not opened, the old window stays")
    call clock%open(0.05_wp)
    call clock%tick(0.04_wp, action)
    call check_true(state, action == clock_renewed, "reach: a step back before t1")
  end subroutine clock_windows

  !> sin(w t) sampled with its rate on the grid windows of the clock and interpolated at
  !> interior times: the error is within the Hermite bound (w h)^4/384 and falls by ~16
  !> when h halves (order 4).
  subroutine clock_sine(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: w = 1.7_wp
    type(slow_clock_type) :: clock
    real(wp) :: h, t, e(2), f(1, 2), d(1, 2), p(1)
    integer :: i, j, action
    do j = 1, 2
      h = 0.2_wp/real(j, wp)
      clock = new_slow_clock(h, clock_grid)
      e(j) = 0.0_wp
      do i = 1, 400
        t = 0.0137_wp*real(i, wp)
        call clock%tick(t, action)
        f(1, :) = sin(w*clock%window)
        d(1, :) = w*cos(w*clock%window)
        p = clock%interpolate(f(:, 1), d(:, 1), f(:, 2), d(:, 2), t)
        e(j) = max(e(j), abs(p(1) - sin(w*t)))
      end do
      call check_true(state, e(j) <= (w*h)**4/384.0_wp, "within (w h)^4/384")
    end do
    call note(state, "largest error at h = 0.1 s", e(2))
    call check(state, log(e(1)/e(2))/log(2.0_wp), 4.0_wp, "order in h", abs_tol=0.3_wp)
  end subroutine clock_sine

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
