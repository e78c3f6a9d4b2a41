!> Minimal in-tree unit-test harness (pFUnit cannot be installed here): suites register
!> cases; checks with absolute or relative tolerances fail on NaN; the runner prints
!> `N passed, N failed` and the program exits non-zero on any failure or when nothing ran.
module harness
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use, intrinsic :: iso_fortran_env, only: output_unit
  use davit_kinds, only: wp
  implicit none
  private
  public :: test_case, new_case, case_state, check, check_close, check_true, run_suites
  public :: suite_type, note

  !> Result of one case: failures collected as messages.
  type :: case_state
    integer :: checks = 0, failures = 0
    character(len=:), allocatable :: messages
    !> Measured values worth reporting, printed under the case.
    character(len=:), allocatable :: notes
  end type case_state

  abstract interface
    subroutine test_interface(state)
      import :: case_state
      type(case_state), intent(inout) :: state
    end subroutine test_interface
  end interface

  type :: test_case
    character(len=:), allocatable :: name
    procedure(test_interface), pointer, nopass :: run => null()
  end type test_case

  type :: suite_type
    character(len=:), allocatable :: name
    type(test_case), allocatable :: cases(:)
  end type suite_type

  interface check
    module procedure check_close
  end interface check

contains

  function new_case(name, run) result(c)
    character(len=*), intent(in) :: name
    procedure(test_interface) :: run
    type(test_case) :: c
    c%name = name
    c%run => run
  end function new_case

  !> |actual - expected| <= max(abs_tol, rel_tol |expected|); NaN always fails.
  subroutine check_close(state, actual, expected, what, abs_tol, rel_tol)
    type(case_state), intent(inout) :: state
    real(wp), intent(in) :: actual, expected
    character(len=*), intent(in) :: what
    real(wp), intent(in), optional :: abs_tol, rel_tol
    real(wp) :: tol
    character(len=200) :: buf
    tol = 0.0_wp
    if (present(abs_tol)) tol = max(tol, abs_tol)
    if (present(rel_tol)) tol = max(tol, rel_tol*abs(expected))
    state%checks = state%checks + 1
    if (ieee_is_nan(actual) .or. ieee_is_nan(expected) .or. abs(actual - expected) > tol) then
      write (buf, "(a,es23.15,a,es23.15,a,es10.3,a)") ": got ", actual, ", expected ", &
        expected, " (tol ", tol, ")"
      call add_failure(state, what//trim(buf))
    end if
  end subroutine check_close

  subroutine check_true(state, condition, what)
    type(case_state), intent(inout) :: state
    logical, intent(in) :: condition
    character(len=*), intent(in) :: what
    state%checks = state%checks + 1
    if (.not. condition) call add_failure(state, what)
  end subroutine check_true

  !> Report a measured value (printed after the case's PASS/FAIL line).
  subroutine note(state, what, value)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: what
    real(wp), intent(in) :: value
    character(len=32) :: buf
    write (buf, "(es14.6)") value
    if (.not. allocated(state%notes)) state%notes = ""
    state%notes = state%notes//"      "//what//" = "//trim(adjustl(buf))//new_line("a")
  end subroutine note

  subroutine add_failure(state, message)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: message
    state%failures = state%failures + 1
    if (.not. allocated(state%messages)) state%messages = ""
    state%messages = state%messages//"      "//message//new_line("a")
  end subroutine add_failure

  !> Run every case of every suite (or only suites/cases whose name contains `filter`).
  subroutine run_suites(suites, filter, npass, nfail)
    type(suite_type), intent(in) :: suites(:)
    character(len=*), intent(in) :: filter
    integer, intent(out) :: npass, nfail
    type(case_state) :: state
    integer :: i, j
    character(len=:), allocatable :: full
    npass = 0
    nfail = 0
    do i = 1, size(suites)
      do j = 1, size(suites(i)%cases)
        full = suites(i)%name//"/"//suites(i)%cases(j)%name
        if (len(filter) > 0 .and. index(full, filter) == 0) cycle
        state = case_state()
        call suites(i)%cases(j)%run(state)
        if (state%failures == 0 .and. state%checks > 0) then
          npass = npass + 1
          write (output_unit, "(a)") "  PASS "//full
        else
          nfail = nfail + 1
          write (output_unit, "(a)") "  FAIL "//full
          if (state%checks == 0) write (output_unit, "(a)") "      (no checks ran)"
          if (allocated(state%messages)) write (output_unit, "(a)", advance="no") state%messages
        end if
        if (allocated(state%notes)) write (output_unit, "(a)", advance="no") state%notes
        flush (output_unit)
      end do
    end do
  end subroutine run_suites

end module harness
