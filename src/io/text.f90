!> Text of the deck reader's messages and documentation: numbers as a person writes them,
!> lists joined, quotes stripped.
module davit_io_text
  use davit_kinds, only: wp, i8
  use davit_io_namelist, only: int_to_str, int_text
  implicit none
  private
  public :: int_text, join_text
  public :: count_range, optional_text, join_ints, join_logicals, is_number, is_integer, unquote, &
            join_reals, fmt_real, fmt_fixed

contains

  pure function count_range(min_count, max_count) result(s)
    !> Smallest and largest count.
    integer, intent(in) :: min_count, max_count
    character(len=:), allocatable :: s
    s = int_to_str(min_count)//"-"//int_to_str(max_count)
  end function count_range

  pure function optional_text(text, fallback) result(s)
    !> The text, when given.
    character(len=*), intent(in), optional :: text
    !> What to return when text is absent.
    character(len=*), intent(in) :: fallback
    character(len=:), allocatable :: s
    if (present(text)) then
      s = text
    else
      s = fallback
    end if
  end function optional_text

  !> The items, each without its trailing blanks, separated by `sep` ("1, 2, 3").
  pure function join_text(items, sep) result(s)
    !> The items; the separator.
    character(len=*), intent(in) :: items(:), sep
    character(len=:), allocatable :: s
    integer :: i
    s = ""
    do i = 1, size(items)
      if (i > 1) s = s//sep
      s = s//trim(items(i))
    end do
  end function join_text

  pure function join_ints(x) result(s)
    !> The integers.
    integer, intent(in) :: x(:)
    character(len=:), allocatable :: s
    character(len=12) :: items(size(x))
    if (size(x) > 0) write (items, "(i0)") x  ! one record, an item, per value
    s = join_text(items, ", ")
  end function join_ints

  pure function join_logicals(x) result(s)
    !> The logicals.
    logical, intent(in) :: x(:)
    character(len=:), allocatable :: s
    character(len=7) :: items(size(x))
    items = merge(".true. ", ".false.", x)
    s = join_text(items, ", ")
  end function join_logicals

  !> A real number in one of the forms a person writes: [sign] digits [. [digits]] or
  !> [sign] . digits, then optionally e|E|d|D [sign] digits. List-directed READ alone would
  !> accept more ('T', '1-3' read as 1e-3, '-15-1' as -1.5), so anything else is refused.
  pure logical function is_number(s)
    !> The text.
    character(len=*), intent(in) :: s
    integer :: i, n, mant, frac, k
    is_number = .false.
    n = len_trim(s)
    i = 1
    if (n == 0) return
    if (s(i:i) == "+" .or. s(i:i) == "-") i = i + 1
    call skip_digits(s(1:n), i, mant)
    frac = 0
    if (i <= n) then
      if (s(i:i) == ".") then
        i = i + 1
        call skip_digits(s(1:n), i, frac)
      end if
    end if
    if (mant + frac == 0) return
    if (i <= n) then
      if (index("eEdD", s(i:i)) == 0) return
      i = i + 1
      if (i <= n) then
        if (s(i:i) == "+" .or. s(i:i) == "-") i = i + 1
      end if
      call skip_digits(s(1:n), i, k)
      if (k == 0) return
    end if
    is_number = i > n
  end function is_number

  !> An integer: [sign] digits.
  pure logical function is_integer(s)
    !> The text.
    character(len=*), intent(in) :: s
    integer :: i, n, k
    n = len_trim(s)
    i = 1
    is_integer = .false.
    if (n == 0) return
    if (s(i:i) == "+" .or. s(i:i) == "-") i = i + 1
    call skip_digits(s(1:n), i, k)
    is_integer = k > 0 .and. i > n
  end function is_integer

  !> k = number of decimal digits from s(i:) on; advances i past them.
  pure subroutine skip_digits(s, i, k)
    character(len=*), intent(in) :: s
    integer, intent(inout) :: i
    integer, intent(out) :: k
    k = 0
    do while (i <= len(s))
      if (s(i:i) < "0" .or. s(i:i) > "9") exit
      i = i + 1
      k = k + 1
    end do
  end subroutine skip_digits


  pure function unquote(s) result(r)
    !> The text, quoted or not.
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    integer :: n
    r = trim(adjustl(s))
    n = len(r)
    if (n >= 2) then
      if ((r(1:1) == "'" .and. r(n:n) == "'") .or. (r(1:1) == '"' .and. r(n:n) == '"')) then
        r = r(2:n - 1)
      end if
    end if
  end function unquote

  pure function join_reals(x) result(s)
    !> The reals.
    real(wp), intent(in) :: x(:)
    character(len=:), allocatable :: s
    character(len=40) :: items(size(x))  ! fmt_real's longest
    integer :: i
    do i = 1, size(x)
      items(i) = fmt_real(x(i))
    end do
    s = join_text(items, ", ")
  end function join_reals

  !> x with `decimals` digits after the point, a zero before it ("0.0812", "-0.5").
  pure function fmt_fixed(x, decimals) result(s)
    !> The number.
    real(wp), intent(in) :: x
    !> Digits after the point.
    integer, intent(in) :: decimals
    character(len=:), allocatable :: s
    character(len=40) :: buf
    character(len=12) :: form
    write (form, "(a,i0,a)") "(f0.", decimals, ")"
    write (buf, form) x
    s = trim(adjustl(buf))
    if (s(1:1) == ".") s = "0"//s
    if (s(1:min(2, len(s))) == "-.") s = "-0"//s(2:)
  end function fmt_fixed

  !> Shortest readable form of a real (no trailing zeros).
  pure function fmt_real(x) result(s)
    !> The number.
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=40) :: buf
    integer :: p, e
    if (x == 0.0_wp) then
      s = "0"
      return
    end if
    if (x /= x .or. abs(x) > huge(x)) then
      ! NaN or infinite (a diverged state): the processor's own word for it
      write (buf, "(g0)") x
      s = trim(adjustl(buf))
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
