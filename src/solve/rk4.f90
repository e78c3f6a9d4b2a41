!> Classical fixed-step fourth-order Runge-Kutta (the paper's integrator), written as
!> whole-array stage arithmetic on the full state with preallocated stages.
module davit_solve_rk4
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem, integrator_type
  implicit none
  private
  public :: rk4_type

  type, extends(integrator_type) :: rk4_type
    !> Stage derivatives k1..k4 and the stage state, of the state's size.
    real(wp), allocatable :: k1(:), k2(:), k3(:), k4(:), ytmp(:)
  contains
    procedure :: init => rk4_init
    procedure :: step => rk4_step
  end type rk4_type

contains

  subroutine rk4_init(self, n)
    !> The integrator.
    class(rk4_type), intent(inout) :: self
    !> Size of the state vector.
    integer, intent(in) :: n
    if (allocated(self%k1)) deallocate (self%k1, self%k2, self%k3, self%k4, self%ytmp)
    allocate (self%k1(n), self%k2(n), self%k3(n), self%k4(n), self%ytmp(n))
    self%steps = 0
    self%rhs_evaluations = 0
    self%method = "rk4"
  end subroutine rk4_init

  subroutine rk4_step(self, problem, t, y, dt)
    !> The integrator (stages, statistics).
    class(rk4_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time [s], advanced by dt.
    real(wp), intent(inout) :: t
    !> State vector, advanced by one step.
    real(wp), intent(inout) :: y(:)
    !> Step [s].
    real(wp), intent(in) :: dt
    real(wp) :: half
    half = 0.5_wp*dt
    call problem%rhs(t, y, self%k1)
    self%ytmp = y + half*self%k1
    call problem%rhs(t + half, self%ytmp, self%k2)
    self%ytmp = y + half*self%k2
    call problem%rhs(t + half, self%ytmp, self%k3)
    self%ytmp = y + dt*self%k3
    call problem%rhs(t + dt, self%ytmp, self%k4)
    y = y + (dt/6.0_wp)*(self%k1 + 2.0_wp*(self%k2 + self%k3) + self%k4)
    t = t + dt
    self%steps = self%steps + 1
    self%rhs_evaluations = self%rhs_evaluations + 4
  end subroutine rk4_step

end module davit_solve_rk4
