!> Small ODE problems with analytic solutions shared by the test suites.
module test_problems
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem
  implicit none
  private
  public :: oscillator

  !> x'' = -x as y = (x, v): with y(0) = (1, 0), x = cos t.
  type, extends(ode_problem) :: oscillator
  contains
    procedure :: rhs => oscillator_rhs
  end type oscillator

contains

  subroutine oscillator_rhs(self, t, y, dydt)
    class(oscillator), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = -y(1)
  end subroutine oscillator_rhs

end module test_problems
