!> The one adaptive step driver (davit_solve_adaptive) through all three methods that use
!> it: its step-size rules against HNW I's formulas, the methods' orders seen through the
!> error control, the rejection path on a sudden stiff change, a singular iteration matrix,
!> single_step and the stretch rule, and the h_min failure.
module test_step_driver
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
  use davit_kinds, only: wp, i8
  use davit_solve_integrator, only: ode_problem
  use davit_solve_adaptive, only: adaptive_integrator
  use davit_solve_dopri5, only: dopri5_type
  use davit_solve_rosenbrock, only: rosenbrock_type
  use davit_solve_rosenbrock_w, only: rosenbrock_w_type
  use test_problems, only: oscillator
  use harness, only: test_case, new_case, case_state, check, check_true, note
  implicit none
  private
  public :: step_driver_cases

  !> The three methods on the shared driver, and their classical orders.
  character(len=*), parameter :: methods(3) = [character(len=10) :: "dopri5", "rosenbrock", &
                                               "rosw"]
  integer, parameter :: orders(3) = [5, 3, 3]

  !> x'' = -x with both states in rosw's W (its exact Jacobian).
  type, extends(oscillator) :: oscillator_all_stiff
  contains
    procedure :: stiff_states => all_stiff
  end type oscillator_all_stiff

  !> y' = -lambda(t) (y - 1), y(0) = 0, lambda = 1 before t_s and lambda_s after: the
  !> stiffness jumps by lambda_s at t_s. Exact: y = 1 - exp(-t) before, then
  !> 1 - exp(-t_s) exp(-lambda_s (t - t_s)).
  type, extends(ode_problem) :: stiff_switch
    real(wp) :: t_s = 0.3125_wp, lambda_s = 1.0e4_wp
  contains
    procedure :: rhs => switch_rhs
    procedure :: stiff_states => switch_stiff
  end type stiff_switch

  !> y' = lambda (y - 1) from y = 1 (at rest), lambda chosen so that the first trial's
  !> I/(h gamma) - J is exactly singular; J's forward difference at y = 1 is exactly lambda.
  type, extends(ode_problem) :: singular_at_h
    real(wp) :: lambda = 0.0_wp
  contains
    procedure :: rhs => singular_rhs
    procedure :: stiff_states => singular_stiff
  end type singular_at_h

  !> y' = 1 before t = 0.5, NaN from there: every trial across 0.5 is non-finite.
  type, extends(ode_problem) :: nan_wall
  contains
    procedure :: rhs => nan_rhs
  end type nan_wall

contains

  function step_driver_cases() result(cases)
    type(test_case), allocatable :: cases(:)
    cases = [new_case("driver_step_size_rules", step_size_rules), &
             new_case("driver_order_through_error_control", order_through_control), &
             new_case("driver_stiff_switch_rejections", stiff_switch_rejections), &
             new_case("driver_singular_matrix_retry", singular_retry), &
             new_case("driver_single_step_and_stretch", single_step_and_stretch), &
             new_case("driver_nan_collapses_h", nan_collapse)]
  end function step_driver_cases

  ! ---------------------------------------------------------------- problems

  pure function all_stiff(self) result(idx)
    class(oscillator_all_stiff), intent(in) :: self
    integer, allocatable :: idx(:)
    idx = [1, 2]
  end function all_stiff

  pure function switch_stiff(self) result(idx)
    class(stiff_switch), intent(in) :: self
    integer, allocatable :: idx(:)
    idx = [1]
  end function switch_stiff

  pure function singular_stiff(self) result(idx)
    class(singular_at_h), intent(in) :: self
    integer, allocatable :: idx(:)
    idx = [1]
  end function singular_stiff

  subroutine switch_rhs(self, t, y, dydt)
    class(stiff_switch), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = -merge(self%lambda_s, 1.0_wp, t >= self%t_s)*(y(1) - 1.0_wp)
  end subroutine switch_rhs

  pure real(wp) function switch_exact(p, t) result(y)
    type(stiff_switch), intent(in) :: p
    real(wp), intent(in) :: t
    if (t < p%t_s) then
      y = 1.0_wp - exp(-t)
    else
      y = 1.0_wp - exp(-p%t_s)*exp(-p%lambda_s*(t - p%t_s))
    end if
  end function switch_exact

  subroutine singular_rhs(self, t, y, dydt)
    class(singular_at_h), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = self%lambda*(y(1) - 1.0_wp)
  end subroutine singular_rhs

  subroutine nan_rhs(self, t, y, dydt)
    class(nan_wall), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = 1.0_wp
    if (t >= 0.5_wp) dydt(1) = ieee_value(1.0_wp, ieee_quiet_nan)
  end subroutine nan_rhs

  ! ---------------------------------------------------------------- helpers

  !> A fresh integrator of method m for n states at tolerance tol (atol = tol).
  subroutine new_method(m, n, tol, integ)
    integer, intent(in) :: m, n
    real(wp), intent(in) :: tol
    class(adaptive_integrator), allocatable, intent(out) :: integ
    select case (m)
    case (1)
      allocate (dopri5_type :: integ)
    case (2)
      allocate (rosenbrock_type :: integ)
    case default
      allocate (rosenbrock_w_type :: integ)
    end select
    call integ%init(n)
    integ%rtol = tol
    integ%atol = tol
  end subroutine new_method

  !> Macro steps of dt from t = 0 to t_end (the run driver's loop without events).
  subroutine run_to(integ, problem, y, dt, t_end)
    class(adaptive_integrator), intent(inout) :: integ
    class(ode_problem), intent(inout) :: problem
    real(wp), intent(inout) :: y(:)
    real(wp), intent(in) :: dt, t_end
    real(wp) :: t
    t = 0.0_wp
    do while (t < t_end - 0.5_wp*dt .and. .not. integ%failed)
      call integ%step(problem, t, y, dt)
    end do
  end subroutine run_to

  ! ---------------------------------------------------------------- cases

  !> The step-size rules at known points. I controller (HNW I, eq. 4.13), order 3:
  !> err = 1 -> safety; err = 8 -> safety/2; err -> 0 -> fac_max; err = 1e6 -> fac_min.
  !> dopri5's PI controller (HNW II, sec. IV.2, as in DOPRI5; err_old = 1e-4 after init):
  !> accepted err = 1 -> safety err_old^beta, rejected err = 10 -> safety 10^-(1/5 - 0.75
  !> beta), bounded by 1/fac_max and 1/fac_min.
  subroutine step_size_rules(state)
    type(case_state), intent(inout) :: state
    class(adaptive_integrator), allocatable :: integ
    real(wp) :: s, b
    integer :: m
    do m = 2, 3
      call new_method(m, 1, 1.0e-6_wp, integ)
      s = integ%safety
      call check(state, integ%next_step(2.0_wp, 1.0_wp, .true.), 2.0_wp*s, &
                 trim(methods(m))//": err = 1", rel_tol=1.0e-14_wp)
      call check(state, integ%next_step(2.0_wp, 8.0_wp, .false.), 2.0_wp*s/2.0_wp, &
                 trim(methods(m))//": err = 8 halves safety h", rel_tol=1.0e-14_wp)
      call check(state, integ%next_step(2.0_wp, 1.0e-30_wp, .true.), 2.0_wp*integ%fac_max, &
                 trim(methods(m))//": growth capped at fac_max", rel_tol=1.0e-14_wp)
      call check(state, integ%next_step(2.0_wp, 1.0e6_wp, .false.), 2.0_wp*integ%fac_min, &
                 trim(methods(m))//": shrink capped at fac_min", rel_tol=1.0e-14_wp)
    end do
    call new_method(1, 1, 1.0e-6_wp, integ)
    select type (integ)
    type is (dopri5_type)
      s = integ%safety
      b = integ%beta
      call check(state, integ%next_step(1.0_wp, 1.0_wp, .true.), s*1.0e-4_wp**b, &
                 "dopri5: PI accepted err = 1", rel_tol=1.0e-14_wp)
      call check(state, integ%next_step(1.0_wp, 10.0_wp, .false.), &
                 s*10.0_wp**(-(0.2_wp - 0.75_wp*b)), "dopri5: rejected err = 10", &
                 rel_tol=1.0e-14_wp)
      call check(state, integ%next_step(1.0_wp, 1.0e-30_wp, .true.), integ%fac_max, &
                 "dopri5: growth capped at fac_max", rel_tol=1.0e-14_wp)
      call check(state, integ%next_step(1.0_wp, 1.0e30_wp, .false.), integ%fac_min, &
                 "dopri5: shrink capped at fac_min", rel_tol=1.0e-14_wp)
    end select
  end subroutine step_size_rules

  !> x'' = -x to t = 10 in one macro step at two tolerances 1000x apart. With error per
  !> step controlled, the global error falls like N^-p with the accepted steps N for a
  !> method of order p (HNW I, sec. II.4 and the work-precision diagrams of II.10), and
  !> like rtol (tolerance proportionality). A smooth problem after a good starting step
  !> needs few rejections.
  subroutine order_through_control(state)
    type(case_state), intent(inout) :: state
    class(adaptive_integrator), allocatable :: integ
    type(oscillator_all_stiff) :: p
    real(wp), parameter :: tols(2) = [1.0e-6_wp, 1.0e-9_wp]
    real(wp) :: err(2), steps(2), y(2), slope
    integer :: m, i
    do m = 1, 3
      do i = 1, 2
        call new_method(m, 2, tols(i), integ)
        y = [1.0_wp, 0.0_wp]
        call run_to(integ, p, y, 10.0_wp, 10.0_wp)
        err(i) = hypot(y(1) - cos(10.0_wp), y(2) + sin(10.0_wp))
        steps(i) = real(integ%steps, wp)
        call check_true(state, .not. integ%failed, trim(methods(m))//": no failure")
        call check_true(state, integ%rejections <= 3_i8 + integ%steps/10_i8, &
                        trim(methods(m))//": few rejections on a smooth problem")
      end do
      slope = log(err(1)/err(2))/log(steps(2)/steps(1))
      call note(state, trim(methods(m))//": accepted steps at rtol 1e-6", steps(1))
      call note(state, trim(methods(m))//": accepted steps at rtol 1e-9", steps(2))
      call note(state, trim(methods(m))//": -d log(err)/d log(N) (expect its order)", slope)
      call check(state, slope, real(orders(m), wp), trim(methods(m))// &
                 ": error ~ N^-p with the method's order", abs_tol=0.6_wp)
      call check(state, log10(err(1)/err(2)), 3.0_wp, trim(methods(m))// &
                 ": error ~ rtol", abs_tol=0.9_wp)
    end do
  end subroutine order_through_control

  !> The stiffness jumps from 1 to 1e4 1/s at t = 0.3125, inside a 0.01 s macro step. All
  !> three methods must reject there (a trial across the switch misses the transient),
  !> follow the exact solution to within their tolerance, and finish. After the transient
  !> dopri5 is held at its stability limit (|h lambda| <= 3.3: >= 1800 steps over the
  !> last 0.6 s, rejecting as it probes above it), while the L-stable Rosenbrock methods
  !> grow back to the macro step. With single_step each accepted step is seen: the step
  !> proposed after one that followed a rejection is no larger than it.
  subroutine stiff_switch_rejections(state)
    type(case_state), intent(inout) :: state
    class(adaptive_integrator), allocatable :: integ
    type(stiff_switch) :: p
    real(wp), parameter :: dt = 0.01_wp, tol = 1.0e-6_wp
    real(wp) :: y(1), t, t_old, dev
    integer(i8) :: steps(3), rejections(3), r_old
    integer :: m
    logical :: no_growth
    do m = 1, 3
      call new_method(m, 1, tol, integ)
      integ%single_step = .true.
      y = 0.0_wp
      t = 0.0_wp
      dev = 0.0_wp
      no_growth = .true.
      do while (t < 1.0_wp .and. .not. integ%failed)
        t_old = t
        r_old = integ%rejections
        call integ%step(p, t, y, min(dt, 1.0_wp - t))
        dev = max(dev, abs(y(1) - switch_exact(p, t)))
        ! the accepted step is t - t_old up to the rounding of t; RODAS3 runs each call to
        ! its end (several accepted steps): not observable there
        if (m /= 2 .and. integ%rejections > r_old) then
          no_growth = no_growth .and. integ%h <= (t - t_old) + 2.0_wp*spacing(t)
        end if
      end do
      steps(m) = integ%steps
      rejections(m) = integ%rejections
      call note(state, trim(methods(m))//": accepted steps", real(steps(m), wp))
      call note(state, trim(methods(m))//": rejections", real(rejections(m), wp))
      call note(state, trim(methods(m))//": largest deviation", dev)
      call check_true(state, .not. integ%failed .and. t == 1.0_wp, &
                      trim(methods(m))//": reaches t = 1")
      call check_true(state, rejections(m) > 0_i8, trim(methods(m))// &
                      ": rejects at the stiffness switch")
      call check_true(state, dev < 100.0_wp*tol, trim(methods(m))// &
                      ": within 100 rtol of the exact solution")
      call check_true(state, no_growth, trim(methods(m))// &
                      ": no growth right after a rejection")
    end do
    call check_true(state, steps(1) >= 1800_i8, "dopri5: held at its stability limit")
    call check_true(state, rejections(1) > 10_i8, "dopri5: rejects at the stability limit")
    call check_true(state, steps(2) < steps(1)/5_i8 .and. steps(3) < steps(1)/5_i8, &
                    "Rosenbrock methods: under 1/5 of dopri5's steps")
  end subroutine stiff_switch_rejections

  !> A first trial whose I/(h gamma) - J is exactly singular (gamma = 1/2 for RODAS3,
  !> 0.4358665215084590 for ROS34PW2): the adaptive driver retries at a smaller step and
  !> completes the macro step; with fixed_step the call fails with the message the run
  !> driver reports.
  subroutine singular_retry(state)
    type(case_state), intent(inout) :: state
    class(adaptive_integrator), allocatable :: integ
    type(singular_at_h) :: p
    real(wp), parameter :: h = 0.25_wp, gammas(2:3) = [0.5_wp, 4.3586652150845900e-1_wp]
    real(wp) :: y(1), t
    integer :: m, k
    do m = 2, 3
      p%lambda = 1.0_wp/(h*gammas(m))
      do k = 1, 2
        call new_method(m, 1, 1.0e-6_wp, integ)
        integ%fixed_step = k == 2
        integ%h = h
        y = 1.0_wp
        t = 0.0_wp
        call integ%step(p, t, y, h)
        if (k == 1) then
          call check_true(state, .not. integ%failed .and. t == h .and. y(1) == 1.0_wp, &
                          trim(methods(m))//": completes the step at rest")
          call check_true(state, integ%rejections == 1_i8, trim(methods(m))// &
                          ": one rejection for the singular matrix")
        else
          call check_true(state, integ%failed .and. t == 0.0_wp, trim(methods(m))// &
                          ": fixed step fails")
          if (allocated(integ%failure)) call check_true(state, &
            index(integ%failure, trim(methods(m))//": singular iteration matrix") == 1, &
            trim(methods(m))//": message names the singular matrix")
        end if
      end do
    end do
  end subroutine singular_retry

  !> single_step: dopri5 and rosw return after one accepted step short of t + dt; RODAS3
  !> runs every call to t + dt (as it always has). A proposed step within 1 % of the rest
  !> of the macro step is stretched onto its end (one step, t bitwise t + dt) and h does
  !> not grow after that clipped step.
  subroutine single_step_and_stretch(state)
    type(case_state), intent(inout) :: state
    class(adaptive_integrator), allocatable :: integ
    type(oscillator_all_stiff) :: p
    real(wp), parameter :: dt = 1.0e-3_wp
    real(wp) :: y(2), t, t0
    integer :: m
    do m = 1, 3
      call new_method(m, 2, 1.0e-6_wp, integ)
      integ%single_step = .true.
      y = [1.0_wp, 0.0_wp]
      t = 0.0_wp
      call integ%step(p, t, y, 1.0_wp)
      if (m == 2) then
        call check_true(state, t == 1.0_wp .and. integ%steps > 1_i8, &
                        "rosenbrock: runs to t + dt despite single_step")
      else
        call check_true(state, t < 1.0_wp .and. integ%steps == 1_i8, trim(methods(m))// &
                        ": single_step returns after one accepted step")
      end if
      call check(state, y(1), cos(t), trim(methods(m))//": x at the returned t", &
                 abs_tol=1.0e-5_wp)
      call new_method(m, 2, 1.0e-6_wp, integ)
      y = [1.0_wp, 0.0_wp]
      t0 = 0.1_wp
      t = t0
      integ%h = 0.995_wp*dt
      call integ%step(p, t, y, dt)
      call check_true(state, t == t0 + dt .and. integ%steps == 1_i8, trim(methods(m))// &
                      ": a step 0.5 % short is stretched onto t + dt")
      call check_true(state, integ%h <= 0.995_wp*dt, trim(methods(m))// &
                      ": no growth after the clipped step")
    end do
  end subroutine single_step_and_stretch

  !> Every trial across t = 0.5 is non-finite: each is rejected with the strongest shrink
  !> until h collapses below h_min; the failure names the method and the reason, y and t
  !> stay at the last accepted state (y = t on y' = 1).
  subroutine nan_collapse(state)
    type(case_state), intent(inout) :: state
    class(adaptive_integrator), allocatable :: integ
    type(nan_wall) :: p
    real(wp) :: y(1), t
    integer :: m
    do m = 1, 3
      call new_method(m, 1, 1.0e-6_wp, integ)
      y = 0.0_wp
      t = 0.0_wp
      call integ%step(p, t, y, 1.0_wp)
      call check_true(state, integ%failed, trim(methods(m))//": failed is set")
      if (allocated(integ%failure)) call check_true(state, &
        index(integ%failure, trim(methods(m))//": step size collapsed below h_min") == 1, &
        trim(methods(m))//": message names the collapse")
      call check_true(state, t < 0.5_wp .and. t > 0.49_wp .and. ieee_is_finite(y(1)), &
                      trim(methods(m))//": t just short of the wall")
      call check(state, y(1), t, trim(methods(m))//": y = t at the last accepted state", &
                 abs_tol=1.0e-9_wp)
      call check_true(state, integ%rejections > 10_i8, trim(methods(m))// &
                      ": the trials were rejected")
    end do
  end subroutine nan_collapse

end module test_step_driver
