!> Error handling: routines in src/ never stop; they return an error_type that the caller
!> checks and passes up. Only app/ turns an error into an exit code.
module davit_error
  implicit none
  private
  public :: error_type, fatal_error

  type :: error_type
    !> Human-readable message, naming file, group, key and allowed range where they apply.
    character(len=:), allocatable :: message
  end type error_type

contains

  !> Allocate `error` with `message`.
  pure subroutine fatal_error(error, message)
    !> The error, allocated.
    type(error_type), allocatable, intent(out) :: error
    !> What went wrong, for the user (file, group, key, value, what is allowed).
    character(len=*), intent(in) :: message
    allocate (error)
    error%message = message
  end subroutine fatal_error

end module davit_error
