!> Event location on the integrator's dense output (issue 14): instead of limiting the
!> step near a switch (a fender touching, its compression turning, a link going slack),
!> take the step, and if the problem's discrete modes differ at its two ends, find the
!> first time they change on the cubic Hermite interpolant through (t0, y0, f0) and
!> (t1, y1, f1) (Hairer, Norsett & Wanner I, sec. II.6: fourth-order accurate, two extra
!> RHS evaluations, paid only at events), by bisection on the modes themselves (they are
!> what the after-step hook switches on, so the located time is that of the switch, not
!> of a proxy), then redo the step from t0 to the end of the final bracket. The after-step
!> hook then switches on a state that is exactly at the event, to within `time_tol`.
module davit_solve_event_location
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_core_hermite, only: hermite_interpolate
  implicit none
  private
  public :: event_stepper_type

  !> Events are located to within time_tol max(1, |t|) [s] (bisection halvings: ~30 from
  !> a 1e-2 s step, each an evaluation of the modes only).
  real(wp), parameter :: time_tol = 1.0e-10_wp
  integer, parameter :: max_bisections = 80
  !> Brackets tried on ever shorter steps before the switch is crossed where it is.
  integer, parameter :: max_passes = 6
  !> Against chattering: events closer than chatter_gap [s] to the one before,
  !> max_chatter of them in a row (a link at zero tension switching taut and slack at
  !> every crossing step, found in a Level 3 launch at the water: 3e-9 s apart, without
  !> end); the next step is then taken whole, its switches made at its end as without
  !> event location.
  real(wp), parameter :: chatter_gap = 1.0e-7_wp
  integer, parameter :: max_chatter = 20

  !> Work arrays of the located step and what it found.
  type :: event_stepper_type
    !> The step's start state y0, the slopes f0, f1 at its ends, an interpolated state ym.
    real(wp), allocatable :: y0(:), f0(:), f1(:), ym(:)
    !> The modes at the step's start m0, at its end m1, at a bisection point mm.
    integer, allocatable :: m0(:), m1(:), mm(:)
    !> The modes at the end of the last step taken without an event, and that state: the
    !> next step starts from them unless the caller moved (t, y) since. (The after-step
    !> hook may still switch a history mode there; a start whose modes are then stale is
    !> a switch at the start, located as any other, and the next step takes fresh ones.)
    real(wp), allocatable :: y_last(:)
    !> Time of the cached state y_last [s].
    real(wp) :: t_last = -huge(1.0_wp)
    !> True while m1 and (t_last, y_last) hold the last event-free step's end.
    logical :: cached = .false.
    !> Events located so far (steps cut at an event); the last one's time, how many came
    !> in a row within chatter_gap of each other, and steps taken whole because of it.
    integer :: located = 0, chatter = 0, unlocated = 0
    !> Time of the last located event [s].
    real(wp) :: t_event = -huge(1.0_wp)
  contains
    procedure :: init => stepper_init
    procedure :: step => located_step
  end type event_stepper_type

contains

  subroutine stepper_init(self, n, n_modes)
    !> The stepper whose work arrays are allocated.
    class(event_stepper_type), intent(inout) :: self
    !> Size of the state vector n and number of discrete modes n_modes.
    integer, intent(in) :: n, n_modes
    allocate (self%y0(n), self%f0(n), self%f1(n), self%ym(n), self%y_last(n))
    self%cached = .false.
    allocate (self%m0(n_modes), self%m1(n_modes), self%mm(n_modes))
    self%located = 0
    self%chatter = 0
    self%unlocated = 0
    self%t_event = -huge(1.0_wp)
  end subroutine stepper_init

  !> Advance (t, y) to t_new with `integ` (t = t_new exactly on return, or where a
  !> single-step integrator ended its one step); where the modes change inside the step,
  !> stop just past their first change instead (event = .true.). A failed integrator step
  !> returns at once (integ%failed).
  subroutine located_step(self, integ, problem, t, y, t_new, event)
    !> The stepper (work arrays, cached modes, event counts).
    class(event_stepper_type), intent(inout) :: self
    !> The integrator that takes the steps.
    class(integrator_type), intent(inout) :: integ
    !> The problem, with its discrete modes.
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y, advanced.
    real(wp), intent(inout) :: t, y(:)
    !> Time to reach [s].
    real(wp), intent(in) :: t_new
    !> True when the step stopped just past a mode change before t_new.
    logical, intent(out) :: event
    real(wp) :: t0, t1
    event = .false.
    if (size(self%m0) == 0 .or. self%chatter >= max_chatter) then
      if (self%chatter >= max_chatter) self%unlocated = self%unlocated + 1
      self%chatter = 0
      self%cached = .false.
      call advance(integ, problem, t, y, t_new)
      return
    end if
    t0 = t
    self%y0 = y
    if (self%cached) self%cached = t0 == self%t_last .and. all(y == self%y_last)
    if (self%cached) then
      self%m0 = self%m1
    else
      call problem%modes(t0, y, self%m0)
    end if
    self%cached = .false.
    call advance(integ, problem, t, y, t_new)
    if (integ%failed) return
    call problem%modes(t, y, self%m1)
    if (all(self%m1 == self%m0)) then
      self%cached = .true.
      self%t_last = t
      self%y_last = y
      return
    end if
    integ%rhs_evaluations = integ%rhs_evaluations + 1
    call problem%rhs(t0, self%y0, self%f0)
    t1 = t
    call refine(self, integ, problem, t0, t, y)
    event = t < t1
    if (.not. event) return
    self%located = self%located + 1
    self%chatter = merge(self%chatter + 1, 0, t - self%t_event < chatter_gap)
    self%t_event = t
  end subroutine located_step

  !> One step of `integ` towards t_new; t lands exactly on t_new when the step reached
  !> it (t0 + (t_new - t0) may round an ulp away), else where a single step ended.
  subroutine advance(integ, problem, t, y, t_new)
    !> The integrator that takes the step.
    class(integrator_type), intent(inout) :: integ
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y, advanced.
    real(wp), intent(inout) :: t, y(:)
    !> Time to reach [s].
    real(wp), intent(in) :: t_new
    call integ%step(problem, t, y, t_new - t)
    if (abs(t - t_new) <= 4.0_wp*epsilon(1.0_wp)*max(1.0_wp, abs(t_new))) t = t_new
  end subroutine advance

  !> The step [t0, t1] (y = y(t1)) crossed a mode change. Bracket it on the interpolant,
  !> redo the step to the bracket's near end ta (still the old modes: the right-hand side
  !> was smooth over it, so the step keeps its order even where the switch makes the
  !> right-hand side jump) and cross with one step of at most time_tol to tb. Where the
  !> redone step finds the modes already changed at ta (the interpolant, built over a
  !> step that crossed a kink, put the switch late), bracket again over [t0, ta], now on
  !> the redone end: each pass shrinks the step that crosses the switch. On return
  !> (t, y) is just past the switch, or at the step's end if the switch was not found
  !> again inside it. A single-step integrator redoes each part as one step (it is
  !> given exactly that span, within its proposed step or not).
  subroutine refine(self, integ, problem, t0, t, y)
    !> The stepper (y0, f0 and m0 of the step's start).
    class(event_stepper_type), intent(inout) :: self
    !> The integrator that redoes the step.
    class(integrator_type), intent(inout) :: integ
    !> The problem, with its discrete modes.
    class(ode_problem), intent(in) :: problem
    !> Start of the step [s].
    real(wp), intent(in) :: t0
    !> End of the step t [s] and its state y on entry; just past the switch on return.
    real(wp), intent(inout) :: t, y(:)
    real(wp) :: ta, tb, t1
    integer :: pass
    logical :: single
    ! the redone parts must end exactly at ta and tb
    single = integ%single_step
    integ%single_step = .false.
    t1 = t
    do pass = 1, max_passes
      call problem%rhs(t1, y, self%f1)
      integ%rhs_evaluations = integ%rhs_evaluations + 1
      call bisect(self, problem, t0, t1, y, ta, tb)
      t = t0
      y = self%y0
      if (ta > t0) call integ%step(problem, t, y, ta - t0)
      t = ta
      call problem%modes(t, y, self%mm)
      if (any(self%mm /= self%m0) .and. pass < max_passes .and. ta > t0) then
        t1 = ta
        cycle
      end if
      if (all(self%mm == self%m0)) then
        call integ%step(problem, t, y, tb - ta)
        t = tb
      end if
      exit
    end do
    integ%single_step = single
  end subroutine refine

  !> The bracket [ta, tb] of the first mode change on the interpolant over [t0, t1].
  subroutine bisect(self, problem, t0, t1, y1, ta, tb)
    !> The stepper (y0, f0, f1, m0; ym, mm used as work).
    class(event_stepper_type), intent(inout) :: self
    !> The problem, with its discrete modes.
    class(ode_problem), intent(in) :: problem
    !> Ends t0, t1 of the step [s] and the state y1 at t1.
    real(wp), intent(in) :: t0, t1, y1(:)
    !> The bracket [ta, tb] of the first mode change [s].
    real(wp), intent(out) :: ta, tb
    real(wp) :: tm
    integer :: it
    ta = t0
    tb = t1
    do it = 1, max_bisections
      if (tb - ta <= time_tol*max(1.0_wp, abs(tb))) exit
      tm = 0.5_wp*(ta + tb)
      self%ym = hermite_interpolate([t0, t1], self%y0, self%f0, y1, self%f1, tm)
      call problem%modes(tm, self%ym, self%mm)
      if (all(self%mm == self%m0)) then
        ta = tm
      else
        tb = tm
      end if
    end do
  end subroutine bisect

end module davit_solve_event_location
