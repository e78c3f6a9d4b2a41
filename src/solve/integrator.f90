!> The one integrator interface. A problem is anything with a right-hand side
!> y' = f(t, y); the integrator owns its work arrays, so many integrations can run on many
!> threads with nothing shared.
module davit_solve_integrator
  use davit_kinds, only: wp, i8
  implicit none
  private
  public :: ode_problem, integrator_type, part_slow, part_fast

  !> The two parts of the multirate split f = f_slow + f_fast that `rhs_part` evaluates.
  integer, parameter :: part_slow = 1, part_fast = 2

  !> An ODE y' = f(t, y). The system state (parameters, layout) lives in the extension.
  type, abstract :: ode_problem
  contains
    procedure(rhs_interface), deferred :: rhs
    !> Hook for the time loop after each accepted step (e.g. refreshing slowly varying
    !> coefficients outside the RHS); does nothing by default.
    procedure :: after_step => no_after_step
    !> Largest step the problem allows from state (t, y) when the deck's step is dt (e.g.
    !> a smaller one near a contact switch); dt by default.
    procedure :: max_step => no_max_step
    !> Discrete modes of the state (contact phases, slack or taut links): a change between
    !> the ends of a step is an event the time loop locates (davit_solve_event_location)
    !> and steps onto, so after_step switches there; none by default.
    !> The states whose own Jacobian block holds the stiff modes (the Rosenbrock-W
    !> method's W, davit_solve_rosenbrock_w); none by default.
    procedure :: stiff_states => no_stiff_states
    !> The other states the stiff rows depend on stiffly (a block's acceleration on its
    !> hook's position): W holds the stiff rows' columns for them too.
    procedure :: coupled_states => no_stiff_states
    procedure :: n_modes => no_n_modes
    procedure :: modes => no_modes
    !> The multirate split f = f_slow + f_fast (davit_solve_multirate), one part
    !> (part_slow, part_fast) at a time: the slow part is evaluated once per stage of the
    !> macro step, the fast part at every substep. By default everything is fast
    !> (f_slow = 0), and the multirate method is RK4 at the substep.
    procedure :: rhs_part => all_fast
  end type ode_problem

  abstract interface
    subroutine rhs_interface(self, t, y, dydt)
      import :: ode_problem, wp
      !> The problem.
      class(ode_problem), intent(in) :: self
      !> Time [s].
      real(wp), intent(in) :: t
      !> State vector (the problem's layout).
      real(wp), intent(in) :: y(:)
      !> Its time derivative y' = f(t, y).
      real(wp), intent(out) :: dydt(:)
    end subroutine rhs_interface
  end interface

  !> Base of every integrator: statistics and the step contract.
  type, abstract :: integrator_type
    !> Accepted steps taken.
    integer(i8) :: steps = 0
    !> Right-hand side evaluations made.
    integer(i8) :: rhs_evaluations = 0
    !> Set (and `failure` explained: time, step size, reason) when an adaptive integrator
    !> cannot complete a step; y is then left at the last accepted state. Never stops.
    logical :: failed = .false.
    !> What made the integrator fail (time, step size, reason); allocated once failed.
    character(len=:), allocatable :: failure
    !> Adaptive integrators: return after ONE accepted internal step (t < t + dt possible)
    !> instead of reaching t + dt, so that the time loop's after-step hook, its monitors
    !> and event location see every step, and dt is only the largest step (issue 14).
    logical :: single_step = .false.
    !> The method's name as &simulation integrator gives it (each method's init sets it).
    character(len=:), allocatable :: method
  contains
    procedure(init_interface), deferred :: init
    procedure(step_interface), deferred :: step
    procedure :: name => integrator_name
    procedure :: stiff_step => whole_step
  end type integrator_type

  abstract interface
    !> Allocate the work arrays for a state of size n (the only allocation).
    subroutine init_interface(self, n)
      import :: integrator_type
      !> The integrator whose work arrays are allocated.
      class(integrator_type), intent(inout) :: self
      !> Size of the state vector.
      integer, intent(in) :: n
    end subroutine init_interface

    !> Advance y from t to t + dt (with single_step, by one accepted step of at most
    !> dt); t is updated.
    subroutine step_interface(self, problem, t, y, dt)
      import :: integrator_type, ode_problem, wp
      !> The integrator (work arrays, statistics, failure record).
      class(integrator_type), intent(inout) :: self
      !> The problem y' = f(t, y).
      class(ode_problem), intent(in) :: problem
      !> Time [s], advanced.
      real(wp), intent(inout) :: t
      !> State vector, advanced from t to the new t.
      real(wp), intent(inout) :: y(:)
      !> Step to take [s] (with single_step, the largest step).
      real(wp), intent(in) :: dt
    end subroutine step_interface
  end interface

contains

  !> The method's name (empty before init).
  pure function integrator_name(self) result(name)
    !> The integrator.
    class(integrator_type), intent(in) :: self
    character(len=:), allocatable :: name
    name = ""
    if (allocated(self%method)) name = self%method
  end function integrator_name

  subroutine all_fast(self, t, y, dydt, part)
    !> The problem.
    class(ode_problem), intent(in) :: self
    !> Time [s].
    real(wp), intent(in) :: t
    !> State vector.
    real(wp), intent(in) :: y(:)
    !> The part of y' asked for: zero for the slow part, the whole right-hand side for the
    !> fast part.
    real(wp), intent(out) :: dydt(:)
    !> part_slow or part_fast.
    integer, intent(in) :: part
    if (part == part_slow) then
      dydt = 0.0_wp
    else
      call self%rhs(t, y, dydt)
    end if
  end subroutine all_fast

  subroutine no_after_step(self, t, y)
    !> The problem, its history updated after the step.
    class(ode_problem), intent(inout) :: self
    !> Time [s] and state vector at the end of the accepted step.
    real(wp), intent(in) :: t, y(:)
  end subroutine no_after_step

  pure function no_stiff_states(self) result(idx)
    !> The problem.
    class(ode_problem), intent(in) :: self
    integer, allocatable :: idx(:)
    allocate (idx(0))
  end function no_stiff_states

  pure integer function no_n_modes(self)
    !> The problem.
    class(ode_problem), intent(in) :: self
    no_n_modes = 0
  end function no_n_modes

  !> The mode of each of the n_modes discrete switches at (t, y), as the after-step hook
  !> would set them from the current history.
  subroutine no_modes(self, t, y, m)
    !> The problem.
    class(ode_problem), intent(in) :: self
    !> Time [s] and state vector.
    real(wp), intent(in) :: t, y(:)
    !> Mode of each discrete switch.
    integer, intent(out) :: m(:)
    m = 0
  end subroutine no_modes

  pure real(wp) function no_max_step(self, t, y, dt) result(h)
    !> The problem.
    class(ode_problem), intent(in) :: self
    !> Time [s], state vector and the deck's step dt [s].
    real(wp), intent(in) :: t, y(:), dt
    h = dt
  end function no_max_step

  !> The step the stiffest explicit stage takes when the macro step is h (what a
  !> divergence message names): h itself, but for the multirate methods' fast substeps.
  pure real(wp) function whole_step(self, h) result(hs)
    !> The integrator.
    class(integrator_type), intent(in) :: self
    !> Macro step [s].
    real(wp), intent(in) :: h
    hs = h
  end function whole_step

end module davit_solve_integrator
