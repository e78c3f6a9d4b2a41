!> A namelist-deck parser that keeps line numbers, so that every error can point at the
!> file, the group, the key and the line (Fortran's own namelist READ reports none of these).
!>
!> Syntax accepted: `&group key = value, key = value /`, across any number of lines; `!`
!> starts a comment outside quotes; a group ends with `/` or `&end`. Values are kept as
!> text; typed parsing and range checks live in davit_io_deck_reader.
module davit_io_namelist
  use davit_kinds, only: i8
  use davit_error, only: error_type, fatal_error
  use davit_io_files, only: file_kind, read_stream, kind_none, kind_folder, kind_pipe
  use davit_io_namelist_entries, only: nml_entry, probe, rehash, move_entry, str_hash
  implicit none
  private
  public :: nml_entry, nml_deck, read_deck, parse_deck, to_lower, int_to_str, find_entry, key_at, &
            shown, int_text, line_end

  type :: nml_deck
    !> Path of the deck, for messages.
    character(len=:), allocatable :: filename
    !> The full deck text, stored verbatim in every output file.
    character(len=:), allocatable :: text
    !> Every key = value of the deck, in order.
    type(nml_entry), allocatable :: entries(:)
    !> The groups, in order.
    character(len=64), allocatable :: groups(:)
    !> Line that opens each group.
    integer, allocatable :: group_lines(:)
    !> Open-addressing hash of (group, key) -> index in entries (0 = empty slot), so that
    !> parsing and every lookup stay linear in the deck size.
    integer, allocatable :: slot(:)
  end type nml_deck

  !> The largest deck read (decks are kilobytes; the parser's own tests reach 8 MiB): a
  !> device such as /dev/zero is refused at this size instead of filling the memory.
  integer(i8), parameter :: max_deck_bytes = 64_i8*1048576_i8

  character(len=*), parameter :: ident_chars = "abcdefghijklmnopqrstuvwxyz0123456789_"

contains

  !> Read and parse the deck file `filename`: a regular file, or a pipe, FIFO or device
  !> read to its end (`davit run <(...)`, `... | davit run /dev/stdin`). A deck with no
  !> namelist group is refused: an empty read (a pipe that gave nothing, a FIFO nobody
  !> writes to) must not run the all-defaults scenario silently.
  subroutine read_deck(filename, deck, error)
    !> Path of the deck.
    character(len=*), intent(in) :: filename
    !> The parsed deck.
    type(nml_deck), intent(out) :: deck
    !> Set when the file cannot be read or its text does not parse.
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: kind
    kind = file_kind(filename)
    if (kind == kind_none) then
      call fatal_error(error, "cannot open input deck '"//filename//"': no such file")
      return
    else if (kind == kind_folder) then
      call fatal_error(error, "cannot read input deck '"//filename//"': it is a folder")
      return
    end if
    call read_stream(filename, "input deck", max_deck_bytes, text, error)
    if (allocated(error)) return
    call parse_deck(filename, text, deck, error)
    if (allocated(error)) return
    if (size(deck%groups) == 0) call fatal_error(error, "input deck '"//filename// &
      "' is empty (no namelist group in its "//int_to_str(len(text))//" bytes"// &
      pipe_note(kind)//"); a deck of defaults needs one group, e.g. &simulation /")
  end subroutine read_deck

  !> Why a pipe's deck may be empty (its writer failed or never came).
  function pipe_note(kind) result(note)
    integer, intent(in) :: kind
    character(len=:), allocatable :: note
    note = ""
    if (kind == kind_pipe) note = "; nothing came through the pipe or FIFO"
  end function pipe_note

  !> Parse deck text; `filename` is only used in messages.
  subroutine parse_deck(filename, text, deck, error)
    !> Name used in messages; the deck text.
    character(len=*), intent(in) :: filename, text
    !> The parsed deck.
    type(nml_deck), intent(out) :: deck
    !> Set for the first line that does not parse (file, line, what is wrong).
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: body, group
    integer, allocatable :: body_line(:)
    integer :: pos, line, eol, open_line, nb
    character(len=:), allocatable :: raw
    type(nml_entry), allocatable :: entries(:)
    character(len=64), allocatable :: groups(:)
    integer, allocatable :: group_lines(:), group_slot(:)
    integer :: nentry, ngroup, k

    deck%filename = filename
    deck%text = text
    nentry = 0
    ngroup = 0
    allocate (entries(64), groups(16), group_lines(16), group_slot(64), deck%slot(128))
    group_slot = 0
    deck%slot = 0
    allocate (character(len=len(text)) :: body)
    allocate (body_line(len(text) + 1))
    pos = 1
    ! a UTF-8 byte-order mark, as some editors write, is not deck text
    if (len(text) >= 3) then
      if (text(1:3) == achar(239)//achar(187)//achar(191)) pos = 4
    end if
    line = 0
    nb = 0
    group = ""
    open_line = 0
    do while (pos <= len(text))
      eol = line_end(text, pos)
      line = line + 1
      raw = strip_comment(text(pos:eol - 1))
      pos = eol + 1
      call scan_line(raw, line)
      if (allocated(error)) exit
    end do
    if (len(group) > 0 .and. .not. allocated(error)) then
      call fatal_error(error, at_line(open_line)//"group &"//group// &
                       " is not closed: end it with '/'")
    end if
    allocate (deck%entries(nentry))
    do k = 1, nentry
      call move_entry(entries(k), deck%entries(k))
    end do
    deallocate (entries)
    deck%groups = groups(1:ngroup)
    deck%group_lines = group_lines(1:ngroup)

  contains

    !> Index of group g among the groups seen so far, or 0; `h` returns its hash slot.
    integer function find_group(g, h) result(k)
      character(len=*), intent(in) :: g
      integer, intent(out) :: h
      k = 0
      h = iand(str_hash(g, ""), size(group_slot) - 1) + 1
      do while (group_slot(h) /= 0)
        if (groups(group_slot(h)) == g) then
          k = group_slot(h)
          return
        end if
        h = merge(1, h + 1, h == size(group_slot))
      end do
    end function find_group

    subroutine add_group(g, lineno)
      character(len=*), intent(in) :: g
      integer, intent(in) :: lineno
      character(len=64), allocatable :: gtmp(:)
      integer, allocatable :: ltmp(:)
      integer :: h, k
      if (ngroup == size(groups)) then
        allocate (gtmp(2*ngroup), ltmp(2*ngroup))
        gtmp(1:ngroup) = groups
        ltmp(1:ngroup) = group_lines
        call move_alloc(gtmp, groups)
        call move_alloc(ltmp, group_lines)
      end if
      ngroup = ngroup + 1
      groups(ngroup) = g
      group_lines(ngroup) = lineno
      if (2*ngroup > size(group_slot)) then
        deallocate (group_slot)
        allocate (group_slot(4*size(groups)))
        group_slot = 0
        do k = 1, ngroup
          if (find_group(groups(k), h) == 0) group_slot(h) = k
        end do
      else
        if (find_group(g, h) == 0) group_slot(h) = ngroup
      end if
    end subroutine add_group

    !> Feed one comment-free line to the group state machine.
    subroutine scan_line(str, lineno)
      character(len=*), intent(in) :: str
      integer, intent(in) :: lineno
      integer :: i, j, k, h
      logical :: in_quote, outside
      character :: quote
      i = 1
      in_quote = .false.
      quote = " "
      do while (i <= len(str))
        if (len(group) == 0) then
          ! outside any group: only blanks or the start of a group
          if (str(i:i) == " " .or. str(i:i) == achar(9) .or. str(i:i) == achar(13)) then
            i = i + 1
            cycle
          end if
          if (str(i:i) /= "&") then
            call fatal_error(error, at_line(lineno)//"text outside a namelist group: '"// &
                             shown(trim(adjustl(str(i:))))//"' (groups start with &name)")
            return
          end if
          j = i + 1
          do while (j <= len(str))
            if (index(ident_chars, to_lower(str(j:j))) == 0) exit
            j = j + 1
          end do
          if (j == i + 1) then
            call fatal_error(error, at_line(lineno)//"'&' must be followed by a group name")
            return
          end if
          group = to_lower(str(i + 1:j - 1))
          if (len(group) > len(groups)) then
            call fatal_error(error, at_line(lineno)//"group name '&"//group// &
                             "' is longer than "//int_to_str(len(groups))//" characters")
            return
          end if
          k = find_group(group, h)
          if (k > 0) then
            call fatal_error(error, at_line(lineno)//"group &"//group// &
                             " appears twice (first at line "// &
                             int_to_str(group_lines(k))//")")
            return
          end if
          call add_group(group, lineno)
          open_line = lineno
          nb = 0
          i = j
          cycle
        end if
        ! inside a group
        call track_quotes(str(i:i), in_quote, quote, outside)
        if (outside .and. str(i:i) == "/") then
          call close_group()
          if (allocated(error)) return
          i = i + 1
          cycle
        else if (outside .and. str(i:i) == "&") then
          if (to_lower(str(i:min(len(str), i + 3))) == "&end") then
            call close_group()
            if (allocated(error)) return
            i = i + 4
            cycle
          end if
          call fatal_error(error, at_line(lineno)//"group &"//group//" (opened at line "// &
                           int_to_str(open_line)//") is not closed before a new group")
          return
        end if
        nb = nb + 1
        body(nb:nb) = str(i:i)
        body_line(nb) = lineno
        i = i + 1
      end do
      if (len(group) > 0) then
        ! line break acts as a separator
        nb = nb + 1
        body(nb:nb) = " "
        body_line(nb) = lineno
        if (in_quote) then
          call fatal_error(error, at_line(lineno)//"&"//group//": unterminated string")
          return
        end if
      end if
    end subroutine scan_line

    subroutine close_group()
      call split_assignments(body(1:nb), body_line(1:nb))
      group = ""
      nb = 0
    end subroutine close_group

    !> Split "k1 = v1, k2 = v2" into entries, keeping the line of each key.
    subroutine split_assignments(b, bline)
      character(len=*), intent(in) :: b
      integer, intent(in) :: bline(:)
      integer, allocatable :: eq(:), kstart(:)
      integer :: i, n, ks, ke, vs, ve, pass
      logical :: in_quote, outside
      character :: quote
      character(len=:), allocatable :: key, value
      ! two passes: count the '=' outside quotes, then record them
      n = 0
      do pass = 1, 2
        if (pass == 2) allocate (eq(n))
        n = 0
        in_quote = .false.
        quote = " "
        do i = 1, len(b)
          call track_quotes(b(i:i), in_quote, quote, outside)
          if (outside .and. b(i:i) == "=") then
            n = n + 1
            if (pass == 2) eq(n) = i
          end if
        end do
      end do
      allocate (kstart(n))
      do i = 1, n
        ke = eq(i) - 1
        do while (ke >= 1)
          if (b(ke:ke) /= " ") exit
          ke = ke - 1
        end do
        ks = ke
        do while (ks >= 1)
          if (index(ident_chars, to_lower(b(ks:ks))) == 0) exit
          ks = ks - 1
        end do
        ks = ks + 1
        if (ks > ke) then
          call fatal_error(error, at_line(bline(max(1, eq(i) - 1)))//"&"//group// &
                           ": '=' without a key name before it")
          return
        end if
        kstart(i) = ks
      end do
      if (n == 0) then
        if (len_trim(b) > 0) then
          call fatal_error(error, at_line(first_line(b, bline))//"&"//group// &
                           ": expected 'key = value', found '"//shown(trim(adjustl(b)))//"'")
        end if
        return
      end if
      if (len_trim(b(1:kstart(1) - 1)) > 0) then
        call fatal_error(error, at_line(first_line(b, bline))//"&"//group// &
                         ": expected 'key = value', found '"// &
                         shown(trim(adjustl(b(1:kstart(1) - 1))))//"'")
        return
      end if
      do i = 1, n
        ke = eq(i) - 1
        key = to_lower(trim(b(kstart(i):ke)))
        vs = eq(i) + 1
        if (i < n) then
          ve = kstart(i + 1) - 1
        else
          ve = len(b)
        end if
        value = trim(adjustl(b(vs:ve)))
        if (len(value) > 0) then
          if (value(len(value):len(value)) == ",") value = trim(value(1:len(value) - 1))
        end if
        if (len(value) == 0) then
          call fatal_error(error, at_line(bline(kstart(i)))//"&"//group//": "//key// &
                           " has no value")
          return
        end if
        call add_entry(key, value, bline(kstart(i)))
        if (allocated(error)) return
      end do
    end subroutine split_assignments

    subroutine add_entry(key, value, lineno)
      character(len=*), intent(in) :: key, value
      integer, intent(in) :: lineno
      type(nml_entry), allocatable :: etmp(:)
      integer :: k, h
      k = probe(deck%slot, entries, group, key, h)
      if (k > 0) then
        call fatal_error(error, at_line(lineno)//"&"//group//": "//key// &
                         " is given twice (first at line "//int_to_str(entries(k)%line)//")")
        return
      end if
      if (nentry == size(entries)) then
        allocate (etmp(2*nentry))
        do k = 1, nentry
          call move_entry(entries(k), etmp(k))
        end do
        call move_alloc(etmp, entries)
      end if
      nentry = nentry + 1
      entries(nentry)%group = group
      entries(nentry)%key = key
      entries(nentry)%value = value
      entries(nentry)%line = lineno
      if (2*nentry > size(deck%slot)) then
        call rehash(deck%slot, entries(1:nentry), 4*size(entries))
      else
        deck%slot(h) = nentry
      end if
    end subroutine add_entry

    pure function at_line(lineno) result(s)
      integer, intent(in) :: lineno
      character(len=:), allocatable :: s
      s = filename//":"//int_to_str(lineno)//": "
    end function at_line

  end subroutine parse_deck

  !> Index of (group, key) in the deck's entries, or 0 if the deck does not set it.
  integer function find_entry(deck, group, key) result(k)
    !> The parsed deck.
    type(nml_deck), intent(in) :: deck
    !> Group and key, lower case.
    character(len=*), intent(in) :: group, key
    integer :: h
    k = 0
    if (.not. allocated(deck%slot) .or. .not. allocated(deck%entries)) return
    k = probe(deck%slot, deck%entries, group, key, h)
  end function find_entry

  !> "file:LINE: " for a message about several keys of `group`: the line of the first of
  !> `keys` the deck sets, else the line that opens the group, else "file: " (all defaults).
  function key_at(deck, group, keys) result(s)
    !> The parsed deck.
    type(nml_deck), intent(in) :: deck
    !> The group; its keys of interest.
    character(len=*), intent(in) :: group, keys(:)
    character(len=:), allocatable :: s
    integer :: i, k
    do i = 1, size(keys)
      k = find_entry(deck, group, trim(keys(i)))
      if (k > 0) then
        s = deck%filename//":"//int_to_str(deck%entries(k)%line)//": "
        return
      end if
    end do
    if (allocated(deck%groups)) then
      do i = 1, size(deck%groups)
        if (deck%groups(i) == group) then
          s = deck%filename//":"//int_to_str(deck%group_lines(i))//": "
          return
        end if
      end do
    end if
    s = deck%filename//": "
  end function key_at

  !> Text quoted in a message: control and non-ASCII bytes as '?', cut to 80 characters.
  pure function shown(str) result(s)
    !> The text.
    character(len=*), intent(in) :: str
    character(len=:), allocatable :: s
    integer :: i, c
    if (len(str) > 80) then
      s = str(1:72)//" ... "
    else
      s = str
    end if
    do i = 1, len(s)
      c = iachar(s(i:i))
      if (c < 32 .or. c > 126) s(i:i) = "?"
    end do
  end function shown

  !> Line of the first non-blank character of b.
  pure integer function first_line(b, bline) result(l)
    character(len=*), intent(in) :: b
    integer, intent(in) :: bline(:)
    integer :: i
    l = bline(1)
    do i = 1, len(b)
      if (b(i:i) /= " ") then
        l = bline(i)
        return
      end if
    end do
  end function first_line

  !> Where the line of `text` that starts at pos ends: its newline, or one past the text.
  pure integer function line_end(text, pos) result(eol)
    !> The text.
    character(len=*), intent(in) :: text
    !> Index where the line starts.
    integer, intent(in) :: pos
    eol = index(text(pos:), new_line("a"))
    if (eol == 0) then
      eol = len(text) + 1
    else
      eol = pos + eol - 1
    end if
  end function line_end

  !> Advance the quote state (in_quote, and the quote character that opened the string) by
  !> character c of a deck line; outside: c stands outside any quoted string and is not a
  !> quote itself (an '=', '!', '/' or '&' there has its namelist meaning).
  pure subroutine track_quotes(c, in_quote, quote, outside)
    character, intent(in) :: c
    logical, intent(inout) :: in_quote
    character, intent(inout) :: quote
    logical, intent(out) :: outside
    outside = .false.
    if (in_quote) then
      if (c == quote) in_quote = .false.
    else if (c == "'" .or. c == '"') then
      in_quote = .true.
      quote = c
    else
      outside = .true.
    end if
  end subroutine track_quotes

  !> Remove a trailing `!` comment (outside quotes) and carriage returns.
  pure function strip_comment(str) result(s)
    character(len=*), intent(in) :: str
    character(len=:), allocatable :: s
    integer :: i
    logical :: in_quote, outside
    character :: quote
    in_quote = .false.
    quote = " "
    s = str
    do i = 1, len(str)
      call track_quotes(str(i:i), in_quote, quote, outside)
      if (outside .and. str(i:i) == "!") then
        s = str(1:i - 1)
        exit
      end if
    end do
    do i = 1, len(s)
      if (s(i:i) == achar(13) .or. s(i:i) == achar(9)) s(i:i) = " "
    end do
  end function strip_comment

  pure function to_lower(str) result(s)
    !> The text.
    character(len=*), intent(in) :: str
    character(len=len(str)) :: s
    integer :: i, c
    s = str
    do i = 1, len(str)
      c = iachar(str(i:i))
      if (c >= iachar("A") .and. c <= iachar("Z")) s(i:i) = achar(c + 32)
    end do
  end function to_lower

  pure function int_to_str(i) result(s)
    !> The integer.
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    s = int_text(int(i, i8))
  end function int_to_str

  !> An 8-byte integer as text (counts of steps, rows, RHS evaluations; davit_io_text
  !> passes it on).
  pure function int_text(n) result(s)
    !> The integer.
    integer(i8), intent(in) :: n
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write (buf, "(i0)") n
    s = trim(buf)
  end function int_text

end module davit_io_namelist
