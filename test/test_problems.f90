!> Small ODE problems with analytic solutions shared by the test suites.
module test_problems
  use davit_kinds, only: wp, gravity
  use davit_solve_integrator, only: ode_problem
  implicit none
  private
  public :: oscillator, ball, ball_energy, blowup

  !> x'' = -x as y = (x, v): with y(0) = (1, 0), x = cos t.
  type, extends(ode_problem) :: oscillator
  contains
    procedure :: rhs => oscillator_rhs
  end type oscillator

  !> Ball of unit mass on a linear spring-dashpot ground contact, y = (x, v). The contact
  !> force switches on at x = 0 (a jump of c v with damping); after_step counts impacts.
  type, extends(ode_problem) :: ball
    real(wp) :: k = 1.0e6_wp, c = 0.0_wp
    logical :: in_contact = .false.
    integer :: impacts = 0
  contains
    procedure :: rhs => ball_rhs
    procedure :: after_step => ball_after_step
  end type ball

  !> y' = y^2, y(0) = 1: y = 1/(1 - t) blows up at t = 1.
  type, extends(ode_problem) :: blowup
  contains
    procedure :: rhs => blowup_rhs
  end type blowup

contains

  subroutine oscillator_rhs(self, t, y, dydt)
    class(oscillator), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = -y(1)
  end subroutine oscillator_rhs

  subroutine ball_rhs(self, t, y, dydt)
    class(ball), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = -gravity
    if (y(1) < 0.0_wp) dydt(2) = dydt(2) - self%k*y(1) - self%c*y(2)
  end subroutine ball_rhs

  subroutine ball_after_step(self, t, y)
    class(ball), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    if (y(1) < 0.0_wp .and. .not. self%in_contact) self%impacts = self%impacts + 1
    self%in_contact = y(1) < 0.0_wp
  end subroutine ball_after_step

  pure real(wp) function ball_energy(b, y) result(e)
    type(ball), intent(in) :: b
    real(wp), intent(in) :: y(:)
    e = 0.5_wp*y(2)**2 + gravity*y(1) + 0.5_wp*b%k*min(y(1), 0.0_wp)**2
  end function ball_energy

  subroutine blowup_rhs(self, t, y, dydt)
    class(blowup), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(1)**2
  end subroutine blowup_rhs

end module test_problems
