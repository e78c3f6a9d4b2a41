!> One summary row (case_result) and its case index as a flat byte string, so that a row
!> travels between processes (MPI ranks) in one message and arrives bit for bit: the reals
!> and integers are copied as raw bytes (transfer), never formatted, so the receiver stores
!> exactly what the sender computed. Layout: 8 integer(i8) (case, status, collided, impacts,
!> steps, RHS evaluations, message and outcome lengths, -1 = unallocated), the 15 reals in
!> declaration order and the rule checks' values, limits and margins, then the message and
!> outcome text.
module davit_sweep_row_codec
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_sweep_metrics, only: case_result
  use davit_sweep_result_columns, only: nreal_fields, real_fields, set_reals
  implicit none
  private
  public :: encode_row, decode_row

  integer, parameter :: nint_fields = 8
  integer, parameter :: int_bytes = nint_fields*storage_size(0_i8)/8
  integer, parameter :: real_bytes = nreal_fields*storage_size(0.0_wp)/8

contains

  !> The bytes of row `row` of case `c` (c = 0 with a default row is a worker's "ready").
  function encode_row(c, row) result(buf)
    !> Case index (0 with a default row for a worker's "ready").
    integer, intent(in) :: c
    !> The summary row to encode.
    type(case_result), intent(in) :: row
    character(len=:), allocatable :: buf
    character(len=int_bytes) :: ints
    character(len=real_bytes) :: reals
    integer(i8) :: header(nint_fields)
    header = [int(c, i8), int(row%status, i8), int(row%collided, i8), &
              int(row%impacts, i8), row%steps, row%rhs_evaluations, &
              text_length(row%message), text_length(row%outcome)]
    ints = transfer(header, ints)
    reals = transfer(real_fields(row), reals)
    buf = ints//reals//text(row%message)//text(row%outcome)
  end function encode_row

  !> Case index and row back from `buf`; an error if the bytes are not a whole row.
  subroutine decode_row(buf, c, row, error)
    !> The bytes of one encoded row.
    character(len=*), intent(in) :: buf
    !> Case index decoded from the bytes (0 on error).
    integer, intent(out) :: c
    !> The summary row decoded from the bytes.
    type(case_result), intent(out) :: row
    !> Set when the bytes are not a whole row.
    type(error_type), allocatable, intent(out) :: error
    integer(i8) :: header(nint_fields)
    real(wp) :: x(nreal_fields)
    integer :: at, nm, no
    c = 0
    if (len(buf) < int_bytes + real_bytes) then
      call fatal_error(error, "sweep row message too short")
      return
    end if
    header = transfer(buf(:int_bytes), header)
    nm = int(max(header(7), 0_i8))
    no = int(max(header(8), 0_i8))
    if (len(buf) /= int_bytes + real_bytes + nm + no) then
      call fatal_error(error, "sweep row message of the wrong length")
      return
    end if
    x = transfer(buf(int_bytes + 1:int_bytes + real_bytes), x)
    c = int(header(1))
    row%status = int(header(2))
    row%collided = int(header(3))
    row%impacts = int(header(4))
    row%steps = header(5)
    row%rhs_evaluations = header(6)
    call set_reals(row, x)
    at = int_bytes + real_bytes
    if (header(7) >= 0) row%message = buf(at + 1:at + nm)
    if (header(8) >= 0) row%outcome = buf(at + nm + 1:at + nm + no)
  end subroutine decode_row

  pure integer(i8) function text_length(s) result(n)
    !> Text, possibly unallocated.
    character(len=:), allocatable, intent(in) :: s
    n = -1
    if (allocated(s)) n = len(s, i8)
  end function text_length

  pure function text(s) result(t)
    !> Text, possibly unallocated (then "").
    character(len=:), allocatable, intent(in) :: s
    character(len=:), allocatable :: t
    t = ""
    if (allocated(s)) t = s
  end function text

end module davit_sweep_row_codec
