!> Typed, range-checked access to a parsed deck, with one call per key. The same calls also
!> produce the key documentation (README tables, `davit keys`), so the documented defaults
!> and ranges are the ones the code enforces.
module davit_io_deck_reader
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: nml_deck, to_lower, int_to_str, find_entry, shown, parse_deck
  use davit_io_text, only: count_range, optional_text, join_ints, join_logicals, is_number, &
                           is_integer, &
                           unquote, join_reals, fmt_real
  implicit none
  private
  public :: deck_reader_type, key_doc, fmt_real

  type :: key_doc
    !> The key's group and name, its default, allowed range, units and description, as `davit keys`
    !> prints them.
    character(len=:), allocatable :: group, key, default, allowed, units, description
  end type key_doc

  type :: deck_reader_type
    !> The parsed deck (groups, keys, values, lines).
    type(nml_deck) :: deck
    !> Known groups, in order of first use.
    character(len=64), allocatable :: known(:)
    !> Every key read so far, documented (what `davit keys` prints).
    type(key_doc), allocatable :: docs(:)
    !> The first error found (file, line, group, key).
    type(error_type), allocatable :: error
  contains
    procedure :: init => reader_init
    procedure :: init_defaults => reader_init_defaults
    procedure :: real => get_real
    procedure :: real_vec => get_real_vec
    procedure :: real_list => get_real_list
    procedure :: int => get_int
    procedure :: logical => get_logical
    procedure :: choice => get_choice
    procedure :: string => get_string
    procedure :: int_list => get_int_list
    procedure :: logical_list => get_logical_list
    procedure :: choice_list => get_choice_list
    procedure :: has => reader_has
    procedure :: fail => reader_fail
    procedure :: finish => reader_finish
  end type deck_reader_type

contains

  subroutine reader_init(self, deck)
    !> The reader, reset.
    class(deck_reader_type), intent(inout) :: self
    !> The parsed deck.
    type(nml_deck), intent(in) :: deck
    self%deck = deck
    allocate (self%known(0), self%docs(0))
    if (allocated(self%error)) deallocate (self%error)
  end subroutine reader_init

  !> The reader over an empty deck: every key read takes its default and is documented
  !> (the key tables of `davit keys` and the README).
  subroutine reader_init_defaults(self)
    !> The reader, reset.
    class(deck_reader_type), intent(inout) :: self
    type(nml_deck) :: deck
    type(error_type), allocatable :: error
    call parse_deck("(defaults)", "", deck, error)
    call self%init(deck)
  end subroutine reader_init_defaults

  !> Real scalar with range lo..hi (open at an end where lo_open/hi_open).
  !> `default_text` documents a default that depends on other keys.
  subroutine get_real(self, group, key, x, default, lo, hi, units, description, lo_open, &
                      hi_open, default_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; units ("-" for none); the key's description.
    character(len=*), intent(in) :: group, key, units, description
    !> The value read (the default when the key is absent).
    real(wp), intent(out) :: x
    !> Default value; smallest and largest value allowed.
    real(wp), intent(in) :: default, lo, hi
    !> Whether lo, hi themselves are refused (default: allowed).
    logical, intent(in), optional :: lo_open, hi_open
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    real(wp) :: v(1)
    call get_real_vec(self, group, key, v, [default], lo, hi, units, description, &
                      lo_open, hi_open, default_text)
    x = v(1)
  end subroutine get_real

  !> Real list of min_count..max_count values, each in the range.
  subroutine get_real_list(self, group, key, x, default, lo, hi, units, description, &
                           min_count, max_count, default_text, lo_open)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; units ("-" for none); the key's description.
    character(len=*), intent(in) :: group, key, units, description
    !> The values read (the default when the key is absent).
    real(wp), allocatable, intent(out) :: x(:)
    !> Default values; smallest and largest value allowed.
    real(wp), intent(in) :: default(:), lo, hi
    !> Fewest and most values allowed.
    integer, intent(in) :: min_count, max_count
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    !> Whether lo itself is refused (default: allowed).
    logical, intent(in), optional :: lo_open
    character(len=:), allocatable :: value, items(:)
    integer :: line, n
    x = default
    if (.not. lookup(self, group, key, value, line)) then
      call get_real_vec(self, group, key, x, default, lo, hi, units, description, &
                        count_text=int_to_str(min_count)//"-"//int_to_str(max_count), &
                        default_text=default_text, lo_open=lo_open)
      return
    end if
    call split_items(value, items)
    n = size(items)
    if (n < min_count .or. n > max_count) then
      call self_doc(self, group, key, join_reals(default), "", units, description)
      call self%fail(line, group, key, value, "expects "//int_to_str(min_count)//" to "// &
                     int_to_str(max_count)//" values, got "//int_to_str(n), &
                     int_to_str(min_count)//"-"//int_to_str(max_count)//" values", units)
      return
    end if
    deallocate (x)
    allocate (x(n))
    call get_real_vec(self, group, key, x, [(default(1), line = 1, n)], lo, hi, units, &
                      description, count_text=int_to_str(min_count)//"-"//int_to_str(max_count), &
                      default_text=default_text, lo_open=lo_open)
  end subroutine get_real_list

  !> Real vector of fixed size(x); every component must be in the range.
  subroutine get_real_vec(self, group, key, x, default, lo, hi, units, description, &
                          lo_open, hi_open, default_text, count_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; units ("-" for none); the key's description.
    character(len=*), intent(in) :: group, key, units, description
    !> The values read, size(x) of them (the default when the key is absent).
    real(wp), intent(inout) :: x(:)
    !> Default values; smallest and largest value allowed.
    real(wp), intent(in) :: default(:), lo, hi
    !> Whether lo, hi themselves are refused (default: allowed).
    logical, intent(in), optional :: lo_open, hi_open
    !> The default as documented, when it depends on other keys; the count as documented.
    character(len=*), intent(in), optional :: default_text, count_text
    character(len=:), allocatable :: allowed, value
    character(len=:), allocatable :: items(:)
    logical :: lop, hop
    integer :: i, ios, line
    lop = .false.; hop = .false.
    if (present(lo_open)) lop = lo_open
    if (present(hi_open)) hop = hi_open
    allowed = fmt_real(lo)//trim(merge(" < ", " <=", lop))//" "//key// &
              trim(merge(" < ", " <=", hop))//" "//fmt_real(hi)
    if (present(count_text)) then
      allowed = allowed//" ("//count_text//" values)"
    else if (size(x) > 1) then
      allowed = allowed//" ("//int_to_str(size(x))//" values)"
    end if
    call self_doc(self, group, key, optional_text(default_text, join_reals(default)), &
                  allowed, units, description)
    x = default
    if (.not. lookup(self, group, key, value, line)) return
    call split_items(value, items)
    if (size(items) /= size(x)) then
      call self%fail(line, group, key, value, "expects "//int_to_str(size(x))// &
                     " real value(s), got "//int_to_str(size(items)), allowed, units)
      return
    end if
    do i = 1, size(x)
      ios = 1
      if (is_number(items(i))) read (items(i), *, iostat=ios) x(i)
      if (ios /= 0) then
        if (size(x) == 1) then
          call self%fail(line, group, key, value, "not a real number", allowed, units)
        else
          call self%fail(line, group, key, value, "item "//int_to_str(i)//" ('"// &
                         shown(trim(items(i)))//"') is not a real number", allowed, units)
        end if
        return
      end if
      if (.not. ieee_is_finite(x(i))) then
        ! a well-formed number beyond the largest real
        call self%fail(line, group, key, value, "out of range", allowed, units)
        return
      end if
      if (x(i) < lo .or. x(i) > hi .or. (lop .and. x(i) == lo) .or. (hop .and. x(i) == hi)) then
        call self%fail(line, group, key, value, "out of range", allowed, units)
        return
      end if
    end do
  end subroutine get_real_vec

  subroutine get_int(self, group, key, n, default, lo, hi, units, description, default_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; units ("-" for none); the key's description.
    character(len=*), intent(in) :: group, key, units, description
    !> The value read (the default when the key is absent).
    integer, intent(out) :: n
    !> Default value; smallest and largest value allowed.
    integer, intent(in) :: default, lo, hi
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    character(len=:), allocatable :: allowed, value, problem
    integer :: line
    allowed = int_to_str(lo)//" <= "//key//" <= "//int_to_str(hi)//" (integer)"
    call self_doc(self, group, key, optional_text(default_text, int_to_str(default)), &
                  allowed, units, description)
    n = default
    if (.not. lookup(self, group, key, value, line)) return
    problem = int_problem(value, lo, hi, n)
    if (len(problem) > 0) call self%fail(line, group, key, value, problem, allowed, units)
  end subroutine get_int

  subroutine get_logical(self, group, key, flag, default, description)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; the key's description.
    character(len=*), intent(in) :: group, key, description
    !> The value read (the default when the key is absent).
    logical, intent(out) :: flag
    !> Default value.
    logical, intent(in) :: default
    character(len=:), allocatable :: value
    integer :: line
    call self_doc(self, group, key, trim(merge(".true. ", ".false.", default)), &
                  ".true. or .false.", "-", description)
    flag = default
    if (.not. lookup(self, group, key, value, line)) return
    if (.not. parse_logical(value, flag)) call self%fail(line, group, key, value, &
                                                         "not a logical", ".true. or .false.", "-")
  end subroutine get_logical

  !> String restricted to a list of choices (case-insensitive, quotes optional).
  subroutine get_choice(self, group, key, s, default, choices, description, default_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; default value; the key's description.
    character(len=*), intent(in) :: group, key, default, description
    !> The values allowed.
    character(len=*), intent(in) :: choices(:)
    !> The value read, unquoted (the default when the key is absent).
    character(len=:), allocatable, intent(out) :: s
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    character(len=:), allocatable :: value, allowed
    integer :: line, i
    allowed = "one of"//quoted_list(choices)
    call self_doc(self, group, key, optional_text(default_text, "'"//default//"'"), &
                  allowed, "-", description)
    s = default
    if (.not. lookup(self, group, key, value, line)) return
    s = to_lower(unquote(value))
    do i = 1, size(choices)
      if (s == trim(choices(i))) return
    end do
    call self%fail(line, group, key, value, "unknown choice", allowed, "-")
  end subroutine get_choice

  !> Free text (quotes optional), e.g. a file name; must not be empty.
  subroutine get_string(self, group, key, s, default, description)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; default value; the key's description.
    character(len=*), intent(in) :: group, key, default, description
    !> The value read, unquoted (the default when the key is absent).
    character(len=:), allocatable, intent(out) :: s
    character(len=:), allocatable :: value
    integer :: line
    if (len(default) == 0) then
      call self_doc(self, group, key, "none (required)", "text", "-", description)
    else
      call self_doc(self, group, key, "'"//default//"'", "text", "-", description)
    end if
    s = default
    if (.not. lookup(self, group, key, value, line)) return
    s = unquote(value)
    if (len_trim(s) == 0) call self%fail(line, group, key, value, "must not be empty", &
                                         "text", "-")
  end subroutine get_string

  !> Integer list of min_count..max_count values, each in lo..hi.
  subroutine get_int_list(self, group, key, x, default, lo, hi, units, description, &
                          min_count, max_count, default_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; units ("-" for none); the key's description.
    character(len=*), intent(in) :: group, key, units, description
    !> The values read (the default when the key is absent).
    integer, allocatable, intent(out) :: x(:)
    !> Default values; smallest and largest value allowed; fewest and most values.
    integer, intent(in) :: default(:), lo, hi, min_count, max_count
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    character(len=:), allocatable :: allowed, value, items(:), problem
    integer :: i, line
    allowed = int_to_str(lo)//" <= "//key//" <= "//int_to_str(hi)//" (integers, "// &
              count_range(min_count, max_count)//" values)"
    call self_doc(self, group, key, optional_text(default_text, join_ints(default)), &
                  allowed, units, description)
    x = default
    if (.not. list_items(self, group, key, min_count, max_count, allowed, units, value, &
                         items, line)) return
    deallocate (x)
    allocate (x(size(items)))
    do i = 1, size(items)
      problem = int_problem(trim(items(i)), lo, hi, x(i))
      if (problem == "not an integer") problem = "item "//int_to_str(i)//" ('"// &
                                                 shown(trim(items(i)))//"') is not an integer"
      if (len(problem) > 0) then
        call self%fail(line, group, key, value, problem, allowed, units)
        return
      end if
    end do
  end subroutine get_int_list

  !> Logical list of min_count..max_count values.
  subroutine get_logical_list(self, group, key, x, default, description, min_count, &
                              max_count, default_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; the key's description.
    character(len=*), intent(in) :: group, key, description
    !> The values read (the default when the key is absent).
    logical, allocatable, intent(out) :: x(:)
    !> Default values.
    logical, intent(in) :: default(:)
    !> Fewest and most values allowed.
    integer, intent(in) :: min_count, max_count
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    character(len=:), allocatable :: allowed, value, items(:)
    integer :: i, line
    allowed = ".true. or .false. ("//count_range(min_count, max_count)//" values)"
    call self_doc(self, group, key, optional_text(default_text, join_logicals(default)), &
                  allowed, "-", description)
    x = default
    if (.not. list_items(self, group, key, min_count, max_count, allowed, "-", value, &
                         items, line)) return
    deallocate (x)
    allocate (x(size(items)))
    do i = 1, size(items)
      if (.not. parse_logical(trim(items(i)), x(i))) then
        call self%fail(line, group, key, value, "item "//int_to_str(i)//" ('"// &
                       shown(trim(items(i)))//"') is not a logical", allowed, "-")
        return
      end if
    end do
  end subroutine get_logical_list

  !> List of min_count..max_count strings, each one of `choices` (case-insensitive, quotes
  !> optional).
  subroutine get_choice_list(self, group, key, s, default, choices, description, min_count, &
                             max_count, default_text)
    !> The reader; the key is marked used and documented.
    class(deck_reader_type), intent(inout) :: self
    !> Group and key; the key's description.
    character(len=*), intent(in) :: group, key, description
    !> Default values; the values allowed.
    character(len=*), intent(in) :: default(:), choices(:)
    !> The values read, unquoted (the default when the key is absent).
    character(len=len(choices)), allocatable, intent(out) :: s(:)
    !> Fewest and most values allowed.
    integer, intent(in) :: min_count, max_count
    !> The default as documented, when it depends on other keys.
    character(len=*), intent(in), optional :: default_text
    character(len=:), allocatable :: allowed, value, items(:), defaults, item
    integer :: i, line
    allowed = "each one of"//quoted_list(choices)//" ("//count_range(min_count, max_count)// &
              " values)"
    defaults = ""
    do i = 1, size(default)
      defaults = defaults//trim(merge(", ", "  ", i > 1))//" '"//trim(default(i))//"'"
    end do
    call self_doc(self, group, key, optional_text(default_text, adjustl(defaults)), allowed, &
                  "-", description)
    allocate (s(size(default)))
    s = default
    if (.not. list_items(self, group, key, min_count, max_count, allowed, "-", value, &
                         items, line)) return
    deallocate (s)
    allocate (s(size(items)))
    do i = 1, size(items)
      item = to_lower(unquote(items(i)))
      s(i) = item
      if (.not. any(choices == item)) then
        call self%fail(line, group, key, value, "item "//int_to_str(i)//" ('"// &
                       trim(unquote(items(i)))//"') is an unknown choice", allowed, "-")
        return
      end if
    end do
  end subroutine get_choice_list

  !> Whether the deck sets group/key (without marking it used).
  logical function reader_has(self, group, key) result(found)
    !> The reader.
    class(deck_reader_type), intent(in) :: self
    !> Group and key.
    character(len=*), intent(in) :: group, key
    found = find_entry(self%deck, group, key) > 0
  end function reader_has

  !> The items of a list key if the deck sets it with an allowed count; false if it is
  !> absent or the count is wrong (then the error is recorded).
  logical function list_items(self, group, key, min_count, max_count, allowed, units, value, &
                              items, line) result(found)
    type(deck_reader_type), intent(inout) :: self
    character(len=*), intent(in) :: group, key, allowed, units
    integer, intent(in) :: min_count, max_count
    character(len=:), allocatable, intent(out) :: value, items(:)
    integer, intent(out) :: line
    found = lookup(self, group, key, value, line)
    if (.not. found) return
    call split_items(value, items)
    if (size(items) < min_count .or. size(items) > max_count) then
      call self%fail(line, group, key, value, "expects "//int_to_str(min_count)//" to "// &
                     int_to_str(max_count)//" values, got "//int_to_str(size(items)), &
                     allowed, units)
      found = .false.
    end if
  end function list_items

  !> A deck's logical (.true., t, .t., true or the .false. forms, any case); false when
  !> `text` is none of them.
  logical function parse_logical(text, flag) result(ok)
    character(len=*), intent(in) :: text
    logical, intent(inout) :: flag
    ok = .true.
    select case (to_lower(text))
    case (".true.", "t", ".t.", "true")
      flag = .true.
    case (".false.", "f", ".f.", "false")
      flag = .false.
    case default
      ok = .false.
    end select
  end function parse_logical

  !> What is wrong with an integer item ("" when it reads and lies in lo..hi): not an
  !> integer, or out of range (also a well-formed one beyond the default integer).
  function int_problem(text, lo, hi, n) result(problem)
    character(len=*), intent(in) :: text
    integer, intent(in) :: lo, hi
    integer, intent(inout) :: n
    character(len=:), allocatable :: problem
    integer :: ios
    problem = ""
    if (.not. is_integer(text)) then
      problem = "not an integer"
      return
    end if
    read (text, *, iostat=ios) n
    if (ios /= 0 .or. n < lo .or. n > hi) problem = "out of range"
  end function int_problem

  !> The choices, each quoted, each after a blank: " 'a' 'b'".
  pure function quoted_list(choices) result(s)
    character(len=*), intent(in) :: choices(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ""
    do i = 1, size(choices)
      s = s//" '"//trim(choices(i))//"'"
    end do
  end function quoted_list

  !> Record the first error with file, line, group and key.
  subroutine reader_fail(self, line, group, key, value, problem, allowed, units)
    !> The reader.
    class(deck_reader_type), intent(inout) :: self
    !> Line of the deck (0: none).
    integer, intent(in) :: line
    !> Group and key; the value given; what is wrong; what is allowed; units.
    character(len=*), intent(in) :: group, key, value, problem, allowed, units
    character(len=:), allocatable :: msg
    if (allocated(self%error)) return
    msg = self%deck%filename//":"//int_to_str(line)//": &"//group//": "//key//" = "// &
          shown(value)//": "//problem//"; allowed: "//allowed
    if (units /= "-" .and. len(units) > 0) msg = msg//" ["//units//"]"
    call fatal_error(self%error, msg)
  end subroutine reader_fail

  !> Reject unknown groups and keys; return the first error found.
  subroutine reader_finish(self, error)
    !> The reader.
    class(deck_reader_type), intent(inout) :: self
    !> The first error found, or one for an unknown group or key.
    type(error_type), allocatable, intent(out) :: error
    integer :: i, k
    character(len=:), allocatable :: names
    if (allocated(self%error)) then
      call move_alloc(self%error, error)
      return
    end if
    do i = 1, size(self%deck%groups)
      if (.not. any(self%known == self%deck%groups(i))) then
        call fatal_error(error, self%deck%filename//":"// &
                         int_to_str(self%deck%group_lines(i))//": unknown namelist group &"// &
                         trim(self%deck%groups(i))//"; allowed groups: "//group_list(self))
        return
      end if
    end do
    do i = 1, size(self%deck%entries)
      associate (e => self%deck%entries(i))
        if (e%used) cycle
        names = ""
        do k = 1, size(self%docs)
          if (self%docs(k)%group == e%group) names = names//" "//self%docs(k)%key
        end do
        call fatal_error(error, self%deck%filename//":"//int_to_str(e%line)//": &"// &
                         e%group//": unknown key '"//e%key//"'; allowed keys:"//names)
        return
      end associate
    end do
  end subroutine reader_finish

  function group_list(self) result(s)
    type(deck_reader_type), intent(in) :: self
    character(len=:), allocatable :: s
    integer :: i
    s = ""
    do i = 1, size(self%known)
      if (i > 1) s = s//", "
      s = s//"&"//trim(self%known(i))
    end do
  end function group_list

  subroutine self_doc(self, group, key, default, allowed, units, description)
    type(deck_reader_type), intent(inout) :: self
    character(len=*), intent(in) :: group, key, default, allowed, units, description
    type(key_doc) :: d
    if (.not. any(self%known == group)) self%known = [character(len=64) :: self%known, group]
    d%group = group
    d%key = key
    d%default = default
    d%allowed = allowed
    d%units = units
    d%description = description
    self%docs = [self%docs, d]
  end subroutine self_doc

  !> Find group/key in the deck; mark it used. False if absent or an error is pending.
  logical function lookup(self, group, key, value, line) result(found)
    type(deck_reader_type), intent(inout) :: self
    character(len=*), intent(in) :: group, key
    character(len=:), allocatable, intent(out) :: value
    integer, intent(out) :: line
    integer :: i
    found = .false.
    line = 0
    value = ""
    if (allocated(self%error)) return
    i = find_entry(self%deck, group, key)
    if (i == 0) return
    self%deck%entries(i)%used = .true.
    value = self%deck%entries(i)%value
    line = self%deck%entries(i)%line
    found = .true.
  end function lookup

  !> Split a value list on commas and blanks (two passes: count and widest item, then fill).
  subroutine split_items(value, items)
    character(len=*), intent(in) :: value
    character(len=:), allocatable, intent(out) :: items(:)
    integer :: i, n, start, width, pass
    character(len=len(value) + 1) :: v
    v = value
    do i = 1, len(v)
      if (v(i:i) == ",") v(i:i) = " "
    end do
    width = 1
    do pass = 1, 2
      if (pass == 2) allocate (character(len=width) :: items(n))
      n = 0
      i = 1
      do while (i <= len(v))
        if (v(i:i) == " ") then
          i = i + 1
          cycle
        end if
        start = i
        do while (i <= len(v))
          if (v(i:i) == " ") exit
          i = i + 1
        end do
        n = n + 1
        if (pass == 1) width = max(width, i - start)
        if (pass == 2) items(n) = v(start:i - 1)
      end do
    end do
  end subroutine split_items
end module davit_io_deck_reader
