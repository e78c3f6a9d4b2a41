!> Text of the deck reader's messages and documentation: numbers as a person writes them,
!> lists joined, quotes stripped.
module davit_io_text
  use davit_kinds, only: wp
  use davit_io_namelist, only: int_to_str
  implicit none
  private
  public :: count_range, optional_text, join_ints, join_logicals, is_number, unquote, &
            join_reals, fmt_real

contains

  pure function count_range(min_count, max_count) result(s)
    integer, intent(in) :: min_count, max_count
    character(len=:), allocatable :: s
    s = int_to_str(min_count)//"-"//int_to_str(max_count)
  end function count_range

  pure function optional_text(text, fallback) result(s)
    character(len=*), intent(in), optional :: text
    character(len=*), intent(in) :: fallback
    character(len=:), allocatable :: s
    if (present(text)) then
      s = text
    else
      s = fallback
    end if
  end function optional_text

  pure function join_ints(x) result(s)
    integer, intent(in) :: x(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ""
    do i = 1, size(x)
      if (i > 1) s = s//", "
      s = s//int_to_str(x(i))
    end do
  end function join_ints

  pure function join_logicals(x) result(s)
    logical, intent(in) :: x(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ""
    do i = 1, size(x)
      if (i > 1) s = s//", "
      s = s//trim(merge(".true. ", ".false.", x(i)))
    end do
  end function join_logicals

  !> A plain decimal or exponent number (list-directed READ alone would accept 'T' etc.).
  pure logical function is_number(s)
    character(len=*), intent(in) :: s
    is_number = verify(trim(s), "+-.0123456789eEdD") == 0 .and. scan(s, "0123456789") > 0
  end function is_number

  pure function unquote(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    integer :: n
    r = trim(adjustl(s))
    n = len(r)
    if (n >= 2) then
      if ((r(1:1) == "'" .and. r(n:n) == "'") .or. (r(1:1) == '"' .and. r(n:n) == '"')) &
        r = r(2:n - 1)
    end if
  end function unquote

  pure function join_reals(x) result(s)
    real(wp), intent(in) :: x(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ""
    do i = 1, size(x)
      if (i > 1) s = s//", "
      s = s//fmt_real(x(i))
    end do
  end function join_reals

  !> Shortest readable form of a real (no trailing zeros).
  pure function fmt_real(x) result(s)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=40) :: buf
    integer :: p, e
    if (x == 0.0_wp) then
      s = "0"
      return
    end if
    if (abs(x) >= 1.0e-3_wp .and. abs(x) < 1.0e6_wp) then
      write (buf, "(f0.8)") x
      s = trim(buf)
      do while (s(len(s):len(s)) == "0")
        s = s(1:len(s) - 1)
      end do
      if (s(len(s):len(s)) == ".") s = s(1:len(s) - 1)
      if (s(1:1) == ".") s = "0"//s
      if (s(1:min(2, len(s))) == "-.") s = "-0"//s(2:)
    else
      write (buf, "(es20.8)") x
      s = trim(adjustl(buf))
      e = index(s, "E")
      p = e - 1
      do while (s(p:p) == "0")
        p = p - 1
      end do
      if (s(p:p) == ".") p = p - 1
      s = s(1:p)//"e"//trim(adjustl(int_str_exp(s(e + 1:))))
    end if
  end function fmt_real

  pure function int_str_exp(e) result(s)
    character(len=*), intent(in) :: e
    character(len=:), allocatable :: s
    integer :: n, ios
    read (e, *, iostat=ios) n
    if (ios /= 0) n = 0
    s = int_to_str(n)
  end function int_str_exp

end module davit_io_text
