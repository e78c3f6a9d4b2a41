!> The integrators behind davit_solve_integrator: convergence order with fixed steps,
!> tolerance proportionality of the error control, a stiff two-mass spring pair (the sling
!> and cable modes of review sec. 4 in miniature), the exact macro-step contract with a
!> non-smooth contact RHS, and failure reporting on a finite-time blow-up.
module test_integrators
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp, pi
  use davit_error, only: error_type
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_solve_rk4, only: rk4_type
  use davit_solve_dopri5, only: dopri5_type
  use davit_solve_rosenbrock, only: rosenbrock_type
  use davit_solve_rosenbrock_w, only: rosenbrock_w_type
  use davit_solve_factory, only: new_integrator
  use test_problems, only: oscillator, ball, ball_energy, blowup
  use test_step_driver, only: step_driver_cases
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_integrators

  !> y' = -50 (y - cos t), y(0) = 0 (HNW II's mildly stiff example).
  type, extends(ode_problem) :: relaxation
  contains
    procedure :: rhs => relaxation_rhs
  end type relaxation

  !> Heavy mass (m1, ground spring k1) carrying a light mass (m2) on a very stiff spring k2
  !> with dashpot c2: y = (x1, x2, v1, v2).
  type, extends(ode_problem) :: stiff_pair
    real(wp) :: m1 = 1.0_wp, k1 = 1.0_wp, m2 = 1.0e-4_wp, k2 = 1.0e4_wp, c2 = 0.1_wp
  contains
    procedure :: rhs => stiff_pair_rhs
  end type stiff_pair

  !> The pair with the light mass's states (x2, v2) named stiff and the heavy mass's
  !> coupled: the Rosenbrock-W method's W is the light mass's rows only.
  type, extends(stiff_pair) :: stiff_pair_w
  contains
    procedure :: stiff_states => pair_stiff_states
    procedure :: coupled_states => pair_coupled_states
  end type stiff_pair_w

  !> x'' = -x with both states stiff (W = the exact Jacobian) or none (W = 0).
  type, extends(oscillator) :: oscillator_w
    logical :: with_w = .true.
  contains
    procedure :: stiff_states => oscillator_stiff_states
  end type oscillator_w

contains

  function collect_integrators() result(suite)
    type(suite_type) :: suite
    suite%name = "integrators"
    suite%cases = [new_case("dopri5_fixed_step_order_5", dopri5_order), &
                   new_case("rosenbrock_fixed_step_order_3", rosenbrock_order), &
                   new_case("rosw_order_3_for_any_w", rosw_order), &
                   new_case("rosw_stiff_pair_with_partial_w", rosw_stiff_pair), &
                   new_case("tolerance_proportionality", tolerance_proportionality), &
                   new_case("stiff_spring_pair", stiff_spring_pair), &
                   new_case("exact_macro_step", exact_macro_step), &
                   new_case("bouncing_ball_contact", bouncing_ball_contact), &
                   new_case("blowup_sets_failed", blowup_sets_failed), &
                   new_case("factory_names_and_tolerances", factory_names), &
                   step_driver_cases()]
  end function collect_integrators

  ! ---------------------------------------------------------------- problems

  subroutine relaxation_rhs(self, t, y, dydt)
    class(relaxation), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = -50.0_wp*(y(1) - cos(t))
  end subroutine relaxation_rhs

  pure real(wp) function relaxation_exact(t) result(y)
    real(wp), intent(in) :: t
    y = (2500.0_wp*cos(t) + 50.0_wp*sin(t) - 2500.0_wp*exp(-50.0_wp*t))/2501.0_wp
  end function relaxation_exact

  subroutine stiff_pair_rhs(self, t, y, dydt)
    class(stiff_pair), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: f
    f = self%k2*(y(2) - y(1)) + self%c2*(y(4) - y(3))
    dydt(1:2) = y(3:4)
    dydt(3) = (-self%k1*y(1) + f)/self%m1
    dydt(4) = -f/self%m2
  end subroutine stiff_pair_rhs

  ! ---------------------------------------------------------------- helpers

  !> The driver's loop: nsteps macro steps of dt from t = 0, after_step after each; stops
  !> early on failure or a non-finite state (returns the macro steps done).
  function integrate(integ, problem, y, dt, nsteps) result(done)
    class(integrator_type), intent(inout) :: integ
    class(ode_problem), intent(inout) :: problem
    real(wp), intent(inout) :: y(:)
    real(wp), intent(in) :: dt
    integer, intent(in) :: nsteps
    integer :: done
    real(wp) :: t
    t = 0.0_wp
    do done = 1, nsteps
      call integ%step(problem, t, y, dt)
      if (integ%failed .or. .not. all(ieee_is_finite(y))) return
      call problem%after_step(t, y)
    end do
    done = nsteps
  end function integrate

  !> Global error at t = 10 of x'' = -x with fixed steps dt and dt/2 (error ratio).
  function oscillator_ratio(integ, dt) result(ratio)
    class(integrator_type), intent(inout) :: integ
    real(wp), intent(in) :: dt
    real(wp) :: ratio, err(2), y(2)
    type(oscillator) :: p
    integer :: i, n
    do i = 1, 2
      n = nint(10.0_wp/dt)*2**(i - 1)
      y = [1.0_wp, 0.0_wp]
      call integ%init(2)
      n = integrate(integ, p, y, 10.0_wp/real(n, wp), n)
      err(i) = hypot(y(1) - cos(10.0_wp), y(2) + sin(10.0_wp))
    end do
    ratio = err(1)/err(2)
  end function oscillator_ratio

  pure function pair_stiff_states(self) result(idx)
    class(stiff_pair_w), intent(in) :: self
    integer, allocatable :: idx(:)
    idx = [2, 4]
  end function pair_stiff_states

  !> The heavy mass's position and speed pull on the light one through the stiff spring.
  pure function pair_coupled_states(self) result(idx)
    class(stiff_pair_w), intent(in) :: self
    integer, allocatable :: idx(:)
    idx = [1, 3]
  end function pair_coupled_states

  pure function oscillator_stiff_states(self) result(idx)
    class(oscillator_w), intent(in) :: self
    integer, allocatable :: idx(:)
    if (self%with_w) then
      idx = [1, 2]
    else
      allocate (idx(0))
    end if
  end function oscillator_stiff_states

  ! ---------------------------------------------------------------- cases

  !> ROS34PW2 is a W-method: third order whatever W is. Fixed steps on x'' = -x to t = 10
  !> with W the exact Jacobian and with W = 0 (every row explicit): halving dt divides the
  !> global error by 2^3 = 8 either way.
  subroutine rosw_order(state)
    type(case_state), intent(inout) :: state
    type(rosenbrock_w_type) :: integ
    type(oscillator_w) :: p
    real(wp) :: err(2), y(2), ratio
    integer :: i, k, n
    do k = 1, 2
      p%with_w = k == 1
      do i = 1, 2
        n = 200*2**(i - 1)
        y = [1.0_wp, 0.0_wp]
        call integ%init(2)
        integ%fixed_step = .true.
        n = integrate(integ, p, y, 10.0_wp/real(n, wp), n)
        err(i) = hypot(y(1) - cos(10.0_wp), y(2) + sin(10.0_wp))
      end do
      ratio = err(1)/err(2)
      call note(state, merge("W = J: error ratio dt=0.05 -> 0.025 (expect 8)", &
                             "W = 0: error ratio dt=0.05 -> 0.025 (expect 8)", k == 1), ratio)
      call check(state, ratio, 8.0_wp, "rosw fixed-step error ratio", rel_tol=0.2_wp)
    end do
  end subroutine rosw_order

  !> The stiff pair (fast mode ~1e4 rad/s) with W on the light mass's states only: the
  !> Rosenbrock-W method steps over the fast mode at the 1e-2 s macro step (where RK4
  !> blows up, test stiff_spring_pair), keeps the slow mode within 1 % at 10 s and needs
  !> far fewer RHS evaluations than dopri5, which sits at its stability boundary.
  subroutine rosw_stiff_pair(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: dt = 1.0e-2_wp, t_end = 10.0_wp
    type(stiff_pair_w) :: p
    type(rosenbrock_w_type) :: rw
    type(dopri5_type) :: dp
    complex(wp) :: ls, lf
    real(wp) :: y(4), y0(4), ye(4), dev, w
    integer :: n, done
    ls = pair_eigenvalue(p%stiff_pair, cmplx(0.0_wp, sqrt(p%k1/(p%m1 + p%m2)), wp))
    lf = pair_eigenvalue(p%stiff_pair, cmplx(-0.5_wp*p%c2/p%m2, sqrt(p%k2/p%m2), wp))
    y0 = pair_exact(p%stiff_pair, ls, lf, 0.0_wp)
    ye = pair_exact(p%stiff_pair, ls, lf, t_end)
    n = nint(t_end/dt)
    w = aimag(ls)
    call rw%init(4)
    rw%rtol = 1.0e-6_wp
    rw%atol = 1.0e-9_wp
    y = y0
    done = integrate(rw, p, y, dt, n)
    dev = hypot(y(1) - ye(1), (y(3) - ye(3))/w)/hypot(ye(1), ye(3)/w)
    call note(state, "rosw slow-mode deviation / amplitude at 10 s", dev)
    call note(state, "rosw RHS evaluations", real(rw%rhs_evaluations, wp))
    call note(state, "rosw W formed", real(rw%jacobians, wp))
    call check_true(state, done == n .and. .not. rw%failed, "rosw completes")
    call check_true(state, dev < 1.0e-2_wp, "rosw slow mode within 1 % at 10 s")
    call dp%init(4)
    dp%rtol = 1.0e-6_wp
    dp%atol = 1.0e-9_wp
    y = y0
    done = integrate(dp, p, y, dt, n)
    call note(state, "dopri5 RHS evaluations", real(dp%rhs_evaluations, wp))
    call check_true(state, rw%rhs_evaluations*5 < dp%rhs_evaluations, &
                    "rosw needs < 1/5 of dopri5's RHS evaluations")
  end subroutine rosw_stiff_pair

  !> One fixed Dormand-Prince step per macro step is fifth order: halving dt divides the
  !> global error by 2^5 = 32.
  subroutine dopri5_order(state)
    type(case_state), intent(inout) :: state
    type(dopri5_type) :: integ
    real(wp) :: ratio
    integ%fixed_step = .true.
    ratio = oscillator_ratio(integ, 0.2_wp)
    call note(state, "error ratio dt=0.2 -> 0.1 (expect 32)", ratio)
    call check(state, ratio, 32.0_wp, "dopri5 fixed-step error ratio", rel_tol=0.2_wp)
  end subroutine dopri5_order

  !> RODAS3 is third order: halving dt divides the global error by 2^3 = 8.
  subroutine rosenbrock_order(state)
    type(case_state), intent(inout) :: state
    type(rosenbrock_type) :: integ
    real(wp) :: ratio
    integ%fixed_step = .true.
    ratio = oscillator_ratio(integ, 0.1_wp)
    call note(state, "error ratio dt=0.1 -> 0.05 (expect 8)", ratio)
    call check(state, ratio, 8.0_wp, "rosenbrock fixed-step error ratio", rel_tol=0.2_wp)
  end subroutine rosenbrock_order

  !> Both schemes propagate the higher-order solution, so the global error of an
  !> error-per-step controller scales like rtol^1 (HNW I, sec. II.4); it must also stay
  !> within 100 rtol. Problem: y' = -50 (y - cos t) to t = 5 with macro steps of 0.5 s.
  subroutine tolerance_proportionality(state)
    type(case_state), intent(inout) :: state
    type(dopri5_type) :: dp
    type(rosenbrock_type) :: ro
    real(wp), parameter :: tols(2) = [1.0e-5_wp, 1.0e-8_wp]
    real(wp) :: err(2, 2), evals(2, 2), slope
    integer :: m, i
    do m = 1, 2
      do i = 1, 2
        if (m == 1) then
          call run_relaxation(dp, tols(i), err(i, m), evals(i, m))
        else
          call run_relaxation(ro, tols(i), err(i, m), evals(i, m))
        end if
        call check_true(state, err(i, m) <= 100.0_wp*tols(i), &
                        method_name(m)//": global error within 100 rtol")
      end do
      slope = log(err(1, m)/err(2, m))/log(tols(1)/tols(2))
      call note(state, method_name(m)//" error at rtol 1e-5", err(1, m))
      call note(state, method_name(m)//" error at rtol 1e-8", err(2, m))
      call note(state, method_name(m)//" RHS evaluations at rtol 1e-5", evals(1, m))
      call note(state, method_name(m)//" RHS evaluations at rtol 1e-8", evals(2, m))
      call note(state, method_name(m)//" d log(err)/d log(rtol) (expect 1)", slope)
      call check(state, slope, 1.0_wp, method_name(m)//": tolerance proportionality", &
                 abs_tol=0.3_wp)
    end do
  end subroutine tolerance_proportionality

  pure function method_name(m) result(s)
    integer, intent(in) :: m
    character(len=:), allocatable :: s
    s = trim(merge("dopri5    ", "rosenbrock", m == 1))
  end function method_name

  subroutine run_relaxation(integ, tol, err, evals)
    class(integrator_type), intent(inout) :: integ
    real(wp), intent(in) :: tol
    real(wp), intent(out) :: err, evals
    type(relaxation) :: p
    real(wp) :: y(1)
    integer :: n
    call integ%init(1)
    select type (integ)
    type is (dopri5_type)
      integ%rtol = tol
      integ%atol = 1.0e-3_wp*tol
    type is (rosenbrock_type)
      integ%rtol = tol
      integ%atol = 1.0e-3_wp*tol
    end select
    y = 0.0_wp
    n = integrate(integ, p, y, 0.5_wp, 10)
    err = abs(y(1) - relaxation_exact(5.0_wp))
    evals = real(integ%rhs_evaluations, wp)
  end subroutine run_relaxation

  !> Root of det(m1 l^2 + c2 l + k1 + k2, -(c2 l + k2); -(c2 l + k2), m2 l^2 + c2 l + k2)
  !> by complex Newton from l0: an eigenvalue of the damped pair.
  function pair_eigenvalue(p, l0) result(l)
    type(stiff_pair), intent(in) :: p
    complex(wp), intent(in) :: l0
    complex(wp) :: l, a, b, q, f, df
    integer :: it
    l = l0
    do it = 1, 60
      a = p%m1*l**2 + p%c2*l + p%k1 + p%k2
      b = p%m2*l**2 + p%c2*l + p%k2
      q = p%c2*l + p%k2
      f = a*b - q**2
      df = (2*p%m1*l + p%c2)*b + a*(2*p%m2*l + p%c2) - 2*p%c2*q
      l = l - f/df
    end do
  end function pair_eigenvalue

  !> Analytic state at t: slow mode (x1 amplitude 1) plus a fast mode (x2 amplitude 1 mm).
  function pair_exact(p, ls, lf, t) result(y)
    type(stiff_pair), intent(in) :: p
    complex(wp), intent(in) :: ls, lf
    real(wp), intent(in) :: t
    real(wp) :: y(4)
    complex(wp) :: vs(2), vf(2), zs, zf
    vs = [(1.0_wp, 0.0_wp), (p%c2*ls + p%k2)/(p%m2*ls**2 + p%c2*ls + p%k2)]
    vf = 1.0e-3_wp*[(p%m2*lf**2 + p%c2*lf + p%k2)/(p%c2*lf + p%k2), (1.0_wp, 0.0_wp)]
    zs = exp(ls*t)
    zf = exp(lf*t)
    y(1:2) = real(vs*zs + vf*zf, wp)
    y(3:4) = real(ls*vs*zs + lf*vf*zf, wp)
  end function pair_exact

  !> The light mass rings at ~1e4 rad/s (zeta 0.05), the heavy one at 1 rad/s. RK4 at
  !> dt = 1e-2 (omega dt = 100 >> 2.8) blows up; RODAS3 with the same macro step stays
  !> bounded and reproduces the slow mode to 1 % at t = 10 s, with fewer RHS evaluations than
  !> dopri5 (stability-limited to h ~ 3/omega) at the same tolerance.
  subroutine stiff_spring_pair(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: dt = 1.0e-2_wp, t_end = 10.0_wp
    type(stiff_pair) :: p
    type(rk4_type) :: rk
    type(dopri5_type) :: dp
    type(rosenbrock_type) :: ro
    complex(wp) :: ls, lf
    real(wp) :: y(4), y0(4), ye(4), dev, w
    integer :: n, done
    ls = pair_eigenvalue(p, cmplx(0.0_wp, sqrt(p%k1/(p%m1 + p%m2)), wp))
    lf = pair_eigenvalue(p, cmplx(-0.5_wp*p%c2/p%m2, sqrt(p%k2/p%m2), wp))
    call note(state, "slow mode omega (rad/s)", aimag(ls))
    call note(state, "fast mode omega (rad/s)", aimag(lf))
    y0 = pair_exact(p, ls, lf, 0.0_wp)
    ye = pair_exact(p, ls, lf, t_end)
    n = nint(t_end/dt)

    call rk%init(4)
    y = y0
    done = integrate(rk, p, y, dt, n)
    call note(state, "rk4 dt=1e-2: macro steps before non-finite state", real(done, wp))
    call check_true(state, done < n .or. maxval(abs(y)) > 1.0e6_wp, "rk4 at dt = 1e-2 blows up")

    call ro%init(4)
    y = y0
    done = integrate(ro, p, y, dt, n)
    w = aimag(ls)
    dev = hypot(y(1) - ye(1), (y(3) - ye(3))/w)/hypot(ye(1), ye(3)/w)
    call note(state, "rosenbrock slow-mode deviation / amplitude at 10 s", dev)
    call note(state, "rosenbrock RHS evaluations", real(ro%rhs_evaluations, wp))
    call note(state, "rosenbrock accepted steps", real(ro%steps, wp))
    call check_true(state, done == n .and. .not. ro%failed, "rosenbrock completes")
    call check_true(state, dev < 1.0e-2_wp, "rosenbrock slow mode within 1 % at 10 s")
    call check_true(state, abs(y(2) - y(1)) < 1.0e-3_wp, "light mass follows the heavy one")

    call dp%init(4)
    y = y0
    done = integrate(dp, p, y, dt, n)
    dev = hypot(y(1) - ye(1), (y(3) - ye(3))/w)/hypot(ye(1), ye(3)/w)
    call note(state, "dopri5 slow-mode deviation / amplitude at 10 s", dev)
    call note(state, "dopri5 RHS evaluations", real(dp%rhs_evaluations, wp))
    call note(state, "dopri5 accepted steps", real(dp%steps, wp))
    call check_true(state, done == n .and. dev < 1.0e-2_wp, "dopri5 completes, slow mode 1 %")
    call check_true(state, ro%rhs_evaluations < dp%rhs_evaluations, &
                    "rosenbrock needs fewer RHS evaluations than dopri5")
  end subroutine stiff_spring_pair

  !> After step(t, y, dt), t is bitwise the old t + dt, whatever the internal steps were.
  subroutine exact_macro_step(state)
    type(case_state), intent(inout) :: state
    type(dopri5_type) :: dp
    type(rosenbrock_type) :: ro
    type(oscillator) :: p
    real(wp) :: t, t_old, y(2)
    real(wp), parameter :: dts(4) = [1.0e-3_wp, 0.7_wp, 3.3e-2_wp, 1.234567e-4_wp]
    integer :: i, j
    logical :: exact
    call dp%init(2)
    call ro%init(2)
    exact = .true.
    do j = 1, 2
      t = 0.1_wp
      y = [1.0_wp, 0.0_wp]
      do i = 1, 40
        t_old = t
        if (j == 1) call dp%step(p, t, y, dts(mod(i, 4) + 1))
        if (j == 2) call ro%step(p, t, y, dts(mod(i, 4) + 1))
        exact = exact .and. t == t_old + dts(mod(i, 4) + 1)
      end do
      call check(state, y(1), cos(t - 0.1_wp), method_name(j)//": x after mixed steps", &
                 abs_tol=1.0e-5_wp)
    end do
    call check_true(state, exact, "t advanced by exactly dt on every call")
    call check_true(state, .not. (dp%failed .or. ro%failed), "no failure")
  end subroutine exact_macro_step

  !> Ball dropped from 1 m onto a 1e6 N/m ground spring (omega = 1e3 rad/s), macro step
  !> 1 ms: dopri5 must get through the switching RHS without failing. Elastic contact keeps
  !> the energy; with a dashpot (zeta = 0.1) the rebound keeps e^2 of it, e = exp(-zeta pi /
  !> sqrt(1 - zeta^2)) = 0.729 for a linear spring-dashpot (gravity during the 3 ms contact
  !> shifts this by ~0.2 %).
  subroutine bouncing_ball_contact(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: zeta = 0.1_wp
    type(dopri5_type) :: dp
    type(ball) :: b
    real(wp) :: y(2), e0, ratio, e_r
    integer :: done, k
    do k = 1, 2
      b = ball()
      if (k == 2) b%c = 2.0_wp*zeta*sqrt(b%k)
      call dp%init(2)
      y = [1.0_wp, 0.0_wp]
      e0 = ball_energy(b, y)
      done = integrate(dp, b, y, 1.0e-3_wp, 1000)
      call check_true(state, done == 1000 .and. .not. dp%failed, "dopri5 passes the contact")
      call check_true(state, b%impacts == 1, "one impact in the first second")
      ratio = ball_energy(b, y)/e0
      if (k == 1) then
        call note(state, "elastic: E(1 s)/E0", ratio)
        call note(state, "elastic: RHS evaluations", real(dp%rhs_evaluations, wp))
        call check(state, ratio, 1.0_wp, "elastic contact conserves energy", abs_tol=1.0e-4_wp)
      else
        e_r = exp(-zeta*pi/sqrt(1.0_wp - zeta**2))
        call note(state, "damped: E(1 s)/E0 (expect e^2 = 0.532)", ratio)
        call check(state, ratio, e_r**2, "damped contact keeps e^2 of the energy", &
                   rel_tol=0.02_wp)
      end if
    end do
  end subroutine bouncing_ball_contact

  !> y' = y^2 from y(0) = 1 in macro steps of 0.3 to t = 2.1. dopri5 must stop at the
  !> singularity t = 1 (within its tolerance) with failed set and a message, y finite and
  !> large; it must not stop the program. RODAS3 is linearly implicit and y' = y^2 is a
  !> Riccati equation: its rational stages follow y = 1/(1 - t) through the pole onto the
  !> negative branch (the projective continuation) with small error and no failure. That is
  !> asserted as observed: a finite-time blow-up can be jumped silently by the Rosenbrock
  !> method, so the caller's own divergence checks (driver speed limit) still matter.
  !> A step limit of 5 per macro step fails cleanly for both methods.
  subroutine blowup_sets_failed(state)
    type(case_state), intent(inout) :: state
    type(dopri5_type) :: dp
    type(rosenbrock_type) :: ro
    type(blowup) :: p
    real(wp) :: y(1)
    integer :: done
    call dp%init(1)
    y = 1.0_wp
    done = integrate(dp, p, y, 0.3_wp, 7)
    call check_true(state, dp%failed, "dopri5: failed is set")
    call check_true(state, allocated(dp%failure), "dopri5: failure message")
    call check_true(state, done == 4, "dopri5: fails in the macro step over t = 1")
    call check_true(state, ieee_is_finite(y(1)) .and. y(1) > 1.0e6_wp, &
                    "dopri5: y finite and large at the last accepted state")
    call note(state, "dopri5: y at failure", y(1))
    call note(state, "dopri5: RHS evaluations", real(dp%rhs_evaluations, wp))

    call ro%init(1)
    y = 1.0_wp
    done = integrate(ro, p, y, 0.3_wp, 7)
    call note(state, "rosenbrock: y(2.1) (continuation -1/1.1)", y(1))
    call check_true(state, done == 7 .and. .not. ro%failed, "rosenbrock: runs through")
    call check(state, y(1), -1.0_wp/1.1_wp, "rosenbrock: continuation branch", &
               rel_tol=1.0e-4_wp)

    call dp%init(1)
    dp%max_substeps = 5
    call limited_substeps(state, dp)
    call ro%init(1)
    ro%max_substeps = 5
    call limited_substeps(state, ro)
  end subroutine blowup_sets_failed

  !> One macro step 0 -> 0.99 of y' = y^2 cannot be done in 5 internal steps at rtol 1e-6.
  subroutine limited_substeps(state, integ)
    type(case_state), intent(inout) :: state
    class(integrator_type), intent(inout) :: integ
    type(blowup) :: p
    real(wp) :: y(1), t
    y = 1.0_wp
    t = 0.0_wp
    call integ%step(p, t, y, 0.99_wp)
    call check_true(state, integ%failed, integ%name()//": max_substeps = 5 fails")
    if (allocated(integ%failure)) then
      call check_true(state, index(integ%failure, "max_substeps") > 0, &
                      integ%name()//": message names the limit")
    end if
    call check_true(state, t < 0.99_wp .and. ieee_is_finite(y(1)), &
                    integ%name()//": t, y at the last accepted state")
    call check(state, y(1), 1.0_wp/(1.0_wp - t), integ%name()//": y at the last accepted t", &
               rel_tol=1.0e-3_wp)
  end subroutine limited_substeps

  !> The factory knows every name of &simulation integrator and each product reports that
  !> name (the output's integrator attribute; the multirate family tells its four tableaux
  !> apart), passes tolerances and fixed_step on, rejects unknown names.
  subroutine factory_names(state)
    type(case_state), intent(inout) :: state
    class(integrator_type), allocatable :: integ
    type(error_type), allocatable :: error
    character(len=10), parameter :: names(8) = [character(len=10) :: "rk4", "dopri5", &
                                                "rosenbrock", "rosw", "multirate", &
                                                "multirate2", "mri2", "mri2b"]
    integer :: i
    do i = 1, size(names)
      call new_integrator(trim(names(i)), 3, integ, error)
      call check_true(state, .not. allocated(error), trim(names(i))//" is known")
      if (allocated(integ)) call check_true(state, integ%name() == trim(names(i)), &
                                            "name() of "//trim(names(i)))
    end do
    call new_integrator("dopri5", 3, integ, error, rtol=1.0e-8_wp, atol=1.0e-12_wp)
    select type (integ)
    type is (dopri5_type)
      call check(state, integ%rtol, 1.0e-8_wp, "rtol passed", rel_tol=0.0_wp)
      call check(state, integ%atol, 1.0e-12_wp, "atol passed", rel_tol=0.0_wp)
    class default
      call check_true(state, .false., "dopri5 type")
    end select
    ! The deck's &simulation fixed_step reaches both adaptive methods (off by default).
    call new_integrator("dopri5", 3, integ, error, fixed_step=.true.)
    select type (integ)
    type is (dopri5_type)
      call check_true(state, integ%fixed_step, "dopri5: fixed_step passed")
    end select
    call new_integrator("rosenbrock", 3, integ, error, fixed_step=.true.)
    select type (integ)
    type is (rosenbrock_type)
      call check_true(state, integ%fixed_step, "rosenbrock: fixed_step passed")
    end select
    call new_integrator("rosenbrock", 3, integ, error)
    select type (integ)
    type is (rosenbrock_type)
      call check_true(state, .not. integ%fixed_step, "rosenbrock: adaptive by default")
    end select
    call new_integrator("rk4", 3, integ, error, fixed_step=.true.)
    call check_true(state, .not. allocated(error), "rk4 accepts (ignores) fixed_step")
    call new_integrator("euler", 3, integ, error)
    call check_true(state, allocated(error), "unknown name is an error")
  end subroutine factory_names

end module test_integrators
