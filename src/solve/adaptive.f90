!> The one adaptive step driver of dopri5, RODAS3 and Rosenbrock-W (issues 19 and 23): the
!> fixed-step branch, the starting step, and the loop of trial steps with error control,
!> rejection and step-size update. A method extends `adaptive_integrator` with its trial
!> step (`attempt`) and, where it needs them, the hooks below; its own policies (FSAL, the
!> Jacobian or W and its reuse, the step-size rule) stay in the method's module.
!>
!> The controller follows Hairer, Norsett & Wanner, Solving ODEs I, sec. II.4: the error
!> of the embedded pair in the RMS norm (eq. 4.11), accepted when <= 1, and a new step
!> h min(fac_max, max(fac_min, safety err^(-1/p))) for a method of order p whose embedded
!> solution has order p - 1 (eq. 4.13; dopri5 overrides it with its PI controller). After a
!> rejection the next accepted step may not grow (HNW I, sec. II.4: facmax = 1 right after
!> a rejection, after Shampine & Watts 1979).
module davit_solve_adaptive
  use davit_kinds, only: wp, i8
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_solve_step_control, only: error_norm, initial_step, record_failure, stretch_to, &
                                      is_finite_real, substep_allowed
  implicit none
  private
  public :: adaptive_integrator, adaptive_step

  type, abstract, extends(integrator_type) :: adaptive_integrator
    !> Mixed error tolerance: |e_i| <= atol + rtol |y_i| in the RMS sense.
    real(wp) :: rtol = 1.0e-6_wp
    !> Absolute tolerance atol (in the units of each state).
    real(wp) :: atol = 1.0e-9_wp
    !> Relative step floor: h < h_min max(1, |t|) is a step-size collapse (failure).
    real(wp) :: h_min = 1.0e-12_wp
    !> Most internal steps (accepted or rejected) in one macro step before failing.
    integer :: max_substeps = 100000
    !> No error control: exactly one internal step of size dt per call (order studies).
    logical :: fixed_step = .false.
    !> The controller: safety factor and shrink/growth limits of h_new/h.
    real(wp) :: safety = 0.9_wp
    !> Smallest factor h_new/h.
    real(wp) :: fac_min = 0.2_wp
    !> Largest factor h_new/h.
    real(wp) :: fac_max = 6.0_wp
    !> Classical order p of the propagated solution (the embedded one has p - 1), set by
    !> the method's init.
    integer :: order = 0
    !> Proposed internal step (0: choose by the starting heuristic on the next call).
    real(wp) :: h = 0.0_wp
    !> Rejected trial steps (error above tolerance, non-finite, or a singular matrix).
    integer(i8) :: rejections = 0
    !> f(t, y) at the start of the trial step; a trial's result and its error vector;
    !> work arrays for stage states and RHS values.
    real(wp), allocatable :: f0(:), ynew(:), yerr(:), ytmp(:), fcn(:)
  contains
    procedure :: step => adaptive_step
    procedure(attempt_interface), deferred :: attempt
    procedure(start_interface), deferred :: start
    procedure :: prepare => no_prepare
    procedure :: next_step => i_controller
    procedure :: on_acceptance => no_acceptance
    procedure :: on_rejection => no_rejection
    procedure :: init_work
  end type adaptive_integrator

  abstract interface
    !> One trial step of size h from (t, y) with f0 = f(t, y) (and `prepare` done): ynew,
    !> and, when with_error, the error vector yerr.
    subroutine attempt_interface(self, problem, t, y, h, with_error)
      import :: adaptive_integrator, ode_problem, wp
      !> The integrator; ynew (and yerr) written.
      class(adaptive_integrator), intent(inout) :: self
      !> The problem y' = f(t, y).
      class(ode_problem), intent(in) :: problem
      !> Time t [s] and state y at the trial's start, and the trial step h [s].
      real(wp), intent(in) :: t, y(:), h
      !> True to form the error vector yerr too.
      logical, intent(in) :: with_error
    end subroutine attempt_interface

    !> At a new point (t, y): f0 = f(t, y) and what else the method forms once per point.
    !> `first`: the call's first point; the problem may have changed since the last call
    !> (after_step), so nothing carried from it (FSAL) is valid.
    subroutine start_interface(self, problem, t, y, first)
      import :: adaptive_integrator, ode_problem, wp
      !> The integrator; f0 written.
      class(adaptive_integrator), intent(inout) :: self
      !> The problem y' = f(t, y).
      class(ode_problem), intent(in) :: problem
      !> Time t [s] and state y of the new point.
      real(wp), intent(in) :: t, y(:)
      !> True at the call's first point (nothing carried from the last call is valid).
      logical, intent(in) :: first
    end subroutine start_interface
  end interface

contains

  !> Allocate the shared work arrays for a state of size n, set the method's order and
  !> reset the statistics, the failure and the proposed step (each method's init calls it
  !> first).
  subroutine init_work(self, n, order)
    !> The integrator whose work arrays are allocated.
    class(adaptive_integrator), intent(inout) :: self
    !> Size of the state vector; the method's classical order p.
    integer, intent(in) :: n, order
    self%order = order
    if (allocated(self%f0)) deallocate (self%f0, self%ynew, self%yerr, self%ytmp, self%fcn)
    allocate (self%f0(n), self%ynew(n), self%yerr(n), self%ytmp(n), self%fcn(n))
    self%steps = 0
    self%rhs_evaluations = 0
    self%rejections = 0
    self%failed = .false.
    if (allocated(self%failure)) deallocate (self%failure)
    self%h = 0.0_wp
  end subroutine init_work

  !> Advance y from t to t + dt by adaptive internal steps (one accepted step with
  !> single_step; exactly one step of dt without error control with fixed_step). On a
  !> failure (see substep_allowed, or a singular matrix with fixed_step) y stays at the
  !> last accepted state and t at its time.
  subroutine adaptive_step(self, problem, t, y, dt)
    !> The integrator (work arrays, statistics, proposed step, failure record).
    class(adaptive_integrator), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time [s], advanced.
    real(wp), intent(inout) :: t
    !> State vector, advanced.
    real(wp), intent(inout) :: y(:)
    !> Macro step [s] (with single_step, the largest step).
    real(wp), intent(in) :: dt
    real(wp) :: t_end, tc, h, h_new
    integer :: tries
    logical :: last, rejected, ok

    if (self%failed) return
    t_end = t + dt
    call self%start(problem, t, y, .true.)
    if (self%fixed_step) then  ! one step of dt, no error control
      call self%prepare(problem, t, y, dt, ok)
      if (.not. ok) then
        call record_failure(self, t, dt, "singular iteration matrix")
        return
      end if
      call self%attempt(problem, t, y, dt, .false.)
      y = self%ynew
      t = t + dt
      self%steps = self%steps + 1
      return
    end if
    if (self%h <= 0.0_wp) then
      self%h = initial_step(problem, t, y, self%f0, self%order, self%atol, self%rtol, &
                            abs(dt), self%ytmp, self%fcn)
      self%rhs_evaluations = self%rhs_evaluations + 1
    end if

    tc = t
    rejected = .false.
    tries = 0
    do
      last = stretch_to(self%h, t_end - tc)
      h = merge(t_end - tc, self%h, last)
      tries = tries + 1
      if (.not. substep_allowed(self, tries, self%max_substeps, tc, h, self%h_min)) exit
      call trial(self, problem, tc, y, h, rejected, h_new)
      if (rejected) cycle
      y = self%ynew
      self%steps = self%steps + 1
      if (last) then
        ! A clipped final step says little about growth; only let it shrink h.
        self%h = min(self%h, h_new)
        exit
      end if
      tc = tc + h
      self%h = h_new
      if (self%single_step) then
        t = tc
        return
      end if
      call self%start(problem, tc, y, .false.)
    end do
    t = merge(t_end, tc, .not. self%failed)
  end subroutine adaptive_step

  !> One trial step of size h from (t, y), judged by its error norm (HNW I, eq. 4.11).
  !> `rejected` comes in as whether the previous trial was rejected and goes out as
  !> whether this one is: then self%h is the step to retry with; else ynew is the new
  !> state and h_new the next step, not above h right after a rejection.
  subroutine trial(self, problem, t, y, h, rejected, h_new)
    !> The integrator; on a rejection self%h is the step to retry with.
    class(adaptive_integrator), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> In, the previous trial was rejected; out, this one is.
    logical, intent(inout) :: rejected
    !> The next step after an accepted trial [s].
    real(wp), intent(out) :: h_new
    real(wp) :: err
    logical :: ok
    h_new = h
    call self%prepare(problem, t, y, h, ok)
    if (.not. ok) then
      ! a singular iteration matrix: prepare has proposed a smaller step
      call reject(self, rejected)
      return
    end if
    call self%attempt(problem, t, y, h, .true.)
    err = error_norm(self%yerr, y, self%ynew, self%atol, self%rtol)
    if (.not. is_finite_real(err)) then
      ! A non-finite trial (overflow in a stage) is a rejection with the strongest
      ! shrink; a persistent one ends in the h_min failure of substep_allowed.
      self%h = h*self%fac_min
      call reject(self, rejected)
      return
    end if
    if (err > 1.0_wp) then
      self%h = self%next_step(h, err, .false.)
      call reject(self, rejected)
      return
    end if
    h_new = self%next_step(h, err, .true.)
    if (rejected) h_new = min(h_new, h)
    call self%on_acceptance(err)
    rejected = .false.
  end subroutine trial

  !> Book a rejected trial (self%h already set to the retry step) and tell the method.
  subroutine reject(self, rejected)
    !> The integrator, its rejection count advanced.
    class(adaptive_integrator), intent(inout) :: self
    !> Set true.
    logical, intent(out) :: rejected
    self%rejections = self%rejections + 1
    call self%on_rejection()
    rejected = .true.
  end subroutine reject

  !> Before each trial step of size h from (t, y): form and factor what the method solves
  !> with. ok = .false. (the matrix is singular) with self%h set to the step to retry
  !> with. Explicit methods have nothing to prepare.
  subroutine no_prepare(self, problem, t, y, h, ok)
    !> The integrator.
    class(adaptive_integrator), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> False when the iteration matrix is singular.
    logical, intent(out) :: ok
    ok = .true.
  end subroutine no_prepare

  !> The next step after a trial step h with error err (accepted: err <= 1): HNW I,
  !> eq. 4.13 with q + 1 = p.
  pure function i_controller(self, h, err, accepted) result(h_new)
    !> The integrator (its controller factors and order).
    class(adaptive_integrator), intent(in) :: self
    !> Trial step h [s] and its error norm err.
    real(wp), intent(in) :: h, err
    !> True when the trial was accepted.
    logical, intent(in) :: accepted
    real(wp) :: h_new
    h_new = h*min(self%fac_max, max(self%fac_min, self%safety/max(err, 1.0e-10_wp)** &
                                                  (1.0_wp/real(self%order, wp))))
  end function i_controller

  !> After an accepted trial step with error err (y = ynew already).
  subroutine no_acceptance(self, err)
    !> The integrator.
    class(adaptive_integrator), intent(inout) :: self
    !> Error norm of the accepted step.
    real(wp), intent(in) :: err
  end subroutine no_acceptance

  !> After a rejected trial step (the new self%h already set), whatever the reason.
  subroutine no_rejection(self)
    !> The integrator.
    class(adaptive_integrator), intent(inout) :: self
  end subroutine no_rejection

end module davit_solve_adaptive
