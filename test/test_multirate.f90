!> The multirate infinitesimal step methods (davit_solve_multirate) on a slow-fast pair of
!> oscillators with a closed-form solution, and the launch system's split of its
!> right-hand side into the slow and fast parts they integrate.
module test_multirate
  use davit_kinds, only: wp, pi
  use davit_error, only: error_type
  use davit_solve_integrator, only: ode_problem, integrator_type, part_slow, part_fast
  use davit_solve_rk4, only: rk4_type
  use davit_solve_factory, only: new_integrator
  use davit_solve_multirate, only: multirate_type
  use davit_system_model, only: system_type
  use test_problems, only: oscillator
  use system_fixture, only: new_test_system, deck_config
  use harness, only: suite_type, new_case, case_state, check_true, note
  implicit none
  private
  public :: collect_multirate

  !> A heavy mass m1 on a soft ground spring k1 (its ~1 Hz mode: the slow part) carrying a
  !> light mass m2 on a stiff spring k2 (the ~200 Hz mode, as the movable block on its
  !> sling: the fast part, with the kinematics): y = (x1, x2, v1, v2), undamped.
  type, extends(ode_problem) :: slow_fast_pair
    real(wp) :: m1 = 1.0_wp, m2 = 0.01_wp, k1 = 4.0_wp*pi**2, k2 = 0.01_wp*(400.0_wp*pi)**2
  contains
    procedure :: rhs => pair_rhs
    procedure :: rhs_part => pair_rhs_part
  end type slow_fast_pair

contains

  function collect_multirate() result(suite)
    type(suite_type) :: suite
    suite%name = "multirate"
    suite%cases = [new_case("multirate_order_2_on_slow_fast_pair", multirate_order), &
                   new_case("multirate_energy_error_order_2", multirate_energy), &
                   new_case("multirate_without_slow_part_is_rk4", multirate_all_fast), &
                   new_case("launch_split_slow_plus_fast_is_rhs", launch_split)]
  end function collect_multirate

  ! ---------------------------------------------------------------- the pair

  subroutine pair_rhs(self, t, y, dydt)
    class(slow_fast_pair), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: slow(4)
    call pair_rhs_part(self, t, y, dydt, part_fast)
    call pair_rhs_part(self, t, y, slow, part_slow)
    dydt = dydt + slow
  end subroutine pair_rhs

  !> The slow part: the ground spring on m1; the fast part: the kinematics and the stiff
  !> spring between the masses.
  subroutine pair_rhs_part(self, t, y, dydt, part)
    class(slow_fast_pair), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    integer, intent(in) :: part
    real(wp) :: f
    if (part == part_slow) then
      dydt = [0.0_wp, 0.0_wp, -self%k1*y(1)/self%m1, 0.0_wp]
    else
      f = self%k2*(y(2) - y(1))
      dydt = [y(3), y(4), f/self%m1, -f/self%m2]
    end if
  end subroutine pair_rhs_part

  !> The closed form: the natural frequencies w_j solve
  !> m1 m2 w^4 - (k1 m2 + k2 m1 + k2 m2) w^2 + k1 k2 = 0, mode j has x2/x1 = k2/(k2 - w_j^2 m2);
  !> released from rest in the slow mode (x1 = 1), y(t) = that mode times cos(w_1 t).
  pure function pair_exact(p, t) result(y)
    type(slow_fast_pair), intent(in) :: p
    real(wp), intent(in) :: t
    real(wp) :: y(4), a, b, c, w2, ratio
    a = p%m1*p%m2
    b = p%k1*p%m2 + p%k2*p%m1 + p%k2*p%m2
    c = p%k1*p%k2
    ! the smaller root, without cancellation
    w2 = 2.0_wp*c/(b + sqrt(b*b - 4.0_wp*a*c))
    ratio = p%k2/(p%k2 - w2*p%m2)
    y = [cos(sqrt(w2)*t), ratio*cos(sqrt(w2)*t), -sqrt(w2)*sin(sqrt(w2)*t), &
         -ratio*sqrt(w2)*sin(sqrt(w2)*t)]
  end function pair_exact

  pure real(wp) function pair_energy(p, y) result(e)
    type(slow_fast_pair), intent(in) :: p
    real(wp), intent(in) :: y(4)
    e = 0.5_wp*(p%m1*y(3)**2 + p%m2*y(4)**2 + p%k1*y(1)**2 + p%k2*(y(2) - y(1))**2)
  end function pair_energy

  !> Integrate the pair over [0, t_end] in macro steps h with substeps of 1e-4 s (the inner
  !> RK4's error at 200 Hz is then far below the macro step's); the largest position error
  !> and the largest relative energy error at the macro steps.
  subroutine run_pair(method, h, t_end, err, energy_err)
    character(len=*), intent(in) :: method
    real(wp), intent(in) :: h, t_end
    real(wp), intent(out) :: err, energy_err
    type(slow_fast_pair) :: p
    class(integrator_type), allocatable :: integ
    type(error_type), allocatable :: error
    real(wp) :: t, y(4), e0
    integer :: k
    call new_integrator(method, 4, integ, error, substeps=nint(h/1.0e-4_wp))
    if (allocated(error)) error stop "multirate test: "//error%message
    y = pair_exact(p, 0.0_wp)
    e0 = pair_energy(p, y)
    energy_err = 0.0_wp
    err = 0.0_wp
    t = 0.0_wp
    do k = 1, nint(t_end/h)
      call integ%step(p, t, y, h)
      energy_err = max(energy_err, abs(pair_energy(p, y)/e0 - 1.0_wp))
      err = max(err, norm2(y(1:2) - pair_exact(p, t)))
    end do
  end subroutine run_pair

  !> The MIS methods are of order 2 (Wensch, Knoth & Galant 2009): halving the macro step
  !> (12, 6, 3 ms: never a whole number of the 4.98 ms fast periods, where the stages'
  !> restarts resonate with the fast mode, see doc/benchmarks/multirate.md) divides the
  !> largest position error over 1 s by 2^1.8 to 2^2.3 (observed 2^2.0), for both
  !> tableaux and for the chained MRI-GARK-ERK22a and ERK22b ('mri2', 'mri2b', Sandu
  !> 2019); an order-1 coupling (stages fed the tendency of y_n, or 'mri2' with gamma =
  !> [[1/2, 0], [0, 1/2]], or 'mri2b' without its last stage's correction: forward Euler
  !> in the slow part) fails this.
  subroutine multirate_order(state)
    type(case_state), intent(inout) :: state
    character(len=10), parameter :: methods(4) = [character(len=10) :: "multirate", &
                                                  "multirate2", "mri2", "mri2b"]
    real(wp) :: err(3), de
    integer :: i, j
    do j = 1, size(methods)
      do i = 1, 3
        call run_pair(trim(methods(j)), 0.012_wp/2.0_wp**(i - 1), 1.008_wp, err(i), de)
      end do
      call note(state, trim(methods(j))//" observed order, 12 -> 6 ms", &
                log(err(1)/err(2))/log(2.0_wp))
      call note(state, trim(methods(j))//" observed order, 6 -> 3 ms", &
                log(err(2)/err(3))/log(2.0_wp))
      call check_true(state, all(log(err(1:2)/err(2:3))/log(2.0_wp) > 1.8_wp) .and. &
                      all(log(err(1:2)/err(2:3))/log(2.0_wp) < 2.3_wp), &
                      trim(methods(j))//": observed order in [1.8, 2.3]")
      call note(state, trim(methods(j))//" error at 3 ms [m]", err(3))
      call check_true(state, err(3) < 1.0e-4_wp, trim(methods(j))//": error at 3 ms "// &
                      "below 1e-4 m of 1 m (closed form)")
    end do
  end subroutine multirate_order

  !> The undamped pair conserves energy exactly; the methods keep it to O(H^2): over 10 s
  !> (10 slow periods) the largest relative energy error falls 4x per halving of H = 12 ms
  !> (observed order in [1.8, 2.2]) and stays below 1e-3 at H = 12 ms. A macro step of
  !> one fast period (H = 5 ms, the fast period 4.98 ms) resonates with the stages'
  !> restarts: its energy error exceeds that of the larger step 6 ms (the limit
  !> doc/benchmarks/multirate.md states).
  subroutine multirate_energy(state)
    type(case_state), intent(inout) :: state
    real(wp) :: err, de(3), order
    call run_pair("multirate", 0.012_wp, 10.008_wp, err, de(1))
    call run_pair("multirate", 0.006_wp, 10.008_wp, err, de(2))
    call run_pair("multirate", 0.005_wp, 10.008_wp, err, de(3))
    order = log(de(1)/de(2))/log(2.0_wp)
    call note(state, "energy error at H = 12 ms", de(1))
    call note(state, "energy error at H = 6 ms", de(2))
    call note(state, "energy error at H = 5 ms (one fast period)", de(3))
    call note(state, "energy error order", order)
    call check_true(state, de(1) < 1.0e-3_wp, "energy error below 1e-3 at H = 12 ms")
    call check_true(state, order > 1.8_wp .and. order < 2.2_wp, "energy error of order 2")
    call check_true(state, de(3) > de(2), "resonance at a macro step of one fast period")
  end subroutine multirate_energy

  !> A problem with no slow part (the default split) is RK4 at the substep: x'' = -x over
  !> 1 s in 10 macro steps of 10 substeps equals RK4 at 1e-2 s to rounding, and cos(1) to
  !> RK4's 1e-9. The cost the page states: per macro step 3 slow evaluations and
  !> 4 (3 + 5 + 10) = 72 fast ones (stages of round(m/3), m/2 and m substeps).
  subroutine multirate_all_fast(state)
    type(case_state), intent(inout) :: state
    type(oscillator) :: p
    type(rk4_type) :: rk4
    class(integrator_type), allocatable :: integ
    type(error_type), allocatable :: error
    real(wp) :: t, ta, y(2), ya(2)
    integer :: k
    call new_integrator("multirate", 2, integ, error, substeps=10)
    if (allocated(error)) error stop "multirate test: "//error%message
    call rk4%init(2)
    y = [1.0_wp, 0.0_wp]
    ya = y
    t = 0.0_wp
    ta = 0.0_wp
    do k = 1, 10
      call integ%step(p, t, y, 0.1_wp)
    end do
    do k = 1, 100
      call rk4%step(p, ta, ya, 0.01_wp)
    end do
    call check_true(state, maxval(abs(y - ya)) < 1.0e-14_wp, "equal to RK4 at the substep")
    call check_true(state, abs(y(1) - cos(1.0_wp)) < 1.0e-9_wp, "cos(1) to RK4's error")
    call check_true(state, abs(t - 1.0_wp) < 1.0e-14_wp, "t advanced by the macro steps")
    select type (integ)
    type is (multirate_type)
      call check_true(state, integ%slow_evaluations == 30 .and. &
                      integ%fast_evaluations == 720, "3 slow and 72 fast evaluations a step")
    class default
      call check_true(state, .false., "the factory's 'multirate' is a multirate_type")
    end select
  end subroutine multirate_all_fast

  !> The launch's split is a partition of its right-hand side: slow + fast = rhs (to
  !> rounding) on the davit over the 6-DOF ship in a regular sea, the boat at the water
  !> and moving, its BEM immersion state 0.5; each part alone is nonzero.
  subroutine launch_split(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    real(wp), allocatable :: y(:), f(:), fs(:), ff(:)
    real(wp) :: scale
    y = new_test_system(sys, deck_config("&simulation scene = 'launch' /"// &
                                         "&boat position = 0.0, 13.3, 0.3 /"// &
                                         "&sea level = 5, wave_type = 'airy' /"// &
                                         "&ship model = 'bem' /"))
    associate (b => sys%par%boat_part, x => sys%par%radiation_part%q)
      y(b%u(1):b%u(2)) = [0.05_wp, -0.03_wp, 0.02_wp, 0.4_wp, -0.6_wp, 0.3_wp]
      if (x(2) >= x(1)) y(x(1)) = 0.5_wp
    end associate
    allocate (f(size(y)), fs(size(y)), ff(size(y)))
    call sys%rhs(3.0_wp, y, f)
    call sys%rhs_part(3.0_wp, y, fs, part_slow)
    call sys%rhs_part(3.0_wp, y, ff, part_fast)
    scale = maxval(abs(f))
    call note(state, "max |slow + fast - rhs| / max |rhs|", maxval(abs(fs + ff - f))/scale)
    call check_true(state, maxval(abs(fs + ff - f)) <= 1.0e-12_wp*scale, "slow + fast = rhs")
    associate (b => sys%par%boat_part, s => sys%par%ship_slice)
      call check_true(state, any(abs(fs(b%u(1):b%u(2))) > 1.0e-6_wp), "slow loads on the boat")
      call check_true(state, any(abs(ff(b%u(1):b%u(2))) > 1.0e-6_wp), "fast loads on the boat")
      call check_true(state, all(ff(s(1):s(2)) == 0.0_wp), "the ship is slow only")
      call check_true(state, any(fs(s(1):s(2)) /= 0.0_wp), "the ship moves in the slow part")
    end associate
  end subroutine launch_split

end module test_multirate
