!> Integrator selection by name (the `&simulation integrator` key).
module davit_solve_factory
  use davit_error, only: error_type, fatal_error
  use davit_solve_integrator, only: integrator_type
  use davit_solve_rk4, only: rk4_type
  implicit none
  private
  public :: new_integrator

contains

  subroutine new_integrator(name, n, integrator, error)
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    class(integrator_type), allocatable, intent(out) :: integrator
    type(error_type), allocatable, intent(out) :: error
    select case (name)
    case ("rk4")
      allocate (rk4_type :: integrator)
    case default
      call fatal_error(error, "unknown integrator '"//name//"'")
      return
    end select
    call integrator%init(n)
  end subroutine new_integrator

end module davit_solve_factory
