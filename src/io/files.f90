!> What a path is before davit opens it, and the reads and writes that must not block or
!> leave half a file: Fortran's OPEN waits forever on a FIFO nobody writes to, and
!> INQUIRE(SIZE=) is 0 or -1 for a pipe, so decks from `<(...)` or /dev/stdin read as
!> empty. The POSIX calls are in posix_files.c (stat's layout and errno are C's).
module davit_io_files
  use, intrinsic :: iso_c_binding, only: c_int, c_long, c_char, c_null_char
  use davit_kinds, only: i8
  use davit_error, only: error_type, fatal_error
  implicit none
  private
  public :: file_kind, kind_name, same_file, read_stream, write_whole, create_empty, name_max, &
            errno_text, exists_already, remove_file
  public :: kind_none, kind_regular, kind_folder, kind_pipe, kind_char_device

  !> What file_kind returns (posix_files.c numbers them the same).
  integer, parameter :: kind_none = 0, kind_regular = 1, kind_folder = 2, kind_pipe = 3, &
                        kind_char_device = 4, kind_block_device = 5, kind_socket = 6, &
                        kind_other = 7

  !> write_whole's status when the file to create exists already.
  integer, parameter :: exists_already = -1

  !> Bytes read per call; the buffer doubles as it fills.
  integer, parameter :: chunk = 65536

  interface
    function c_file_kind(path, err) bind(C, name="davit_file_kind") result(kind)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: err
      integer(c_int) :: kind
    end function c_file_kind
    function c_same_file(a, b) bind(C, name="davit_same_file") result(same)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: a(*), b(*)
      integer(c_int) :: same
    end function c_same_file
    function c_open_read(path, err) bind(C, name="davit_open_read") result(fd)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: err
      integer(c_int) :: fd
    end function c_open_read
    function c_read(fd, buf, n, err) bind(C, name="davit_read") result(got)
      import :: c_int, c_long, c_char
      integer(c_int), value :: fd
      ! an array of single characters that read(2) fills, not assumed length (C072 is for
      ! assumed-length text)
      ! allow(C072)
      character(kind=c_char), intent(inout) :: buf(*)
      integer(c_long), value :: n
      integer(c_int), intent(out) :: err
      integer(c_long) :: got
    end function c_read
    function c_close(fd) bind(C, name="davit_close") result(status)
      import :: c_int
      integer(c_int), value :: fd
      integer(c_int) :: status
    end function c_close
    function c_write_whole(path, tmp, text, n, replace) bind(C, name="davit_write_whole") &
      result(status)
      import :: c_int, c_long, c_char
      character(kind=c_char), intent(in) :: path(*), tmp(*), text(*)
      integer(c_long), value :: n
      integer(c_int), value :: replace
      integer(c_int) :: status
    end function c_write_whole
    function c_create_empty(path) bind(C, name="davit_create_empty") result(status)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: status
    end function c_create_empty
    function c_name_max(dir) bind(C, name="davit_name_max") result(n)
      import :: c_long, c_char
      character(kind=c_char), intent(in) :: dir(*)
      integer(c_long) :: n
    end function c_name_max
    function c_unlink(path) bind(C, name="unlink") result(status)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: status
    end function c_unlink
    subroutine c_errno_text(err, buf, n) bind(C, name="davit_errno_text")
      import :: c_int, c_char
      integer(c_int), value :: err, n
      ! an array of single characters that strerror_r fills (as above)
      ! allow(C072)
      character(kind=c_char), intent(out) :: buf(*)
    end subroutine c_errno_text
  end interface

contains

  !> What `path` is (links followed): kind_none when absent or not reachable.
  integer function file_kind(path)
    !> Path of the file or folder.
    character(len=*), intent(in) :: path
    integer(c_int) :: err
    file_kind = int(c_file_kind(path//c_null_char, err))
  end function file_kind

  !> "a folder", "a FIFO or pipe", ... for messages.
  function kind_name(kind) result(name)
    !> A kind from file_kind (kind_none, kind_regular, kind_folder, ...).
    integer, intent(in) :: kind
    character(len=:), allocatable :: name
    select case (kind)
    case (kind_none)
      name = "missing"
    case (kind_regular)
      name = "a regular file"
    case (kind_folder)
      name = "a folder"
    case (kind_pipe)
      name = "a FIFO (named pipe) or pipe"
    case (kind_char_device)
      name = "a character device"
    case (kind_block_device)
      name = "a block device"
    case (kind_socket)
      name = "a socket"
    case default
      name = "not a regular file"
    end select
  end function kind_name

  !> Whether `a` and `b` both exist and are one file (device and inode: `./x.h5`, `x.h5`,
  !> `$PWD/x.h5`, links).
  logical function same_file(a, b)
    !> The two paths.
    character(len=*), intent(in) :: a, b
    same_file = c_same_file(a//c_null_char, b//c_null_char) == 1
  end function same_file

  !> The whole of `path` read to its end, whatever it is (a regular file, a pipe, a FIFO,
  !> a device): the open never waits for a writer, and more than `cap` bytes is an error
  !> (/dev/zero would never end). `what` names the file in messages ("input deck").
  subroutine read_stream(path, what, cap, text, error)
    !> Path of the file; what it is, for messages ("input deck").
    character(len=*), intent(in) :: path, what
    !> Largest number of bytes accepted.
    integer(i8), intent(in) :: cap
    !> The file's whole text.
    character(len=:), allocatable, intent(out) :: text
    !> Set when the file cannot be opened or read, or holds more than cap bytes.
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: buf
    integer(c_int) :: fd, err, closed
    integer(c_long) :: got
    integer(i8) :: n
    fd = c_open_read(path//c_null_char, err)
    if (fd < 0) then
      call fatal_error(error, "cannot open "//what//" '"//path//"': "//errno_text(err))
      return
    end if
    allocate (character(len=chunk) :: buf)
    n = 0
    do
      if (len(buf, i8) - n < chunk) call grow(buf, n)
      got = c_read(fd, buf(n + 1:), int(chunk, c_long), err)
      if (got <= 0) exit
      n = n + got
      if (n > cap) exit
    end do
    closed = c_close(fd)  ! nothing is lost when closing what was only read
    if (got < 0) then
      call fatal_error(error, "cannot read "//what//" '"//path//"': "//errno_text(err))
    else if (n > cap) then
      call fatal_error(error, what//" '"//path//"' is larger than "//mib(cap)// &
                       " (decks are kilobytes; is it the right file?)")
    else
      text = buf(1:n)
    end if
  end subroutine read_stream

  !> `buf` twice as long, its first n characters kept.
  subroutine grow(buf, n)
    character(len=:), allocatable, intent(inout) :: buf
    integer(i8), intent(in) :: n
    character(len=:), allocatable :: bigger
    allocate (character(len=2*len(buf)) :: bigger)
    bigger(1:n) = buf(1:n)
    call move_alloc(bigger, buf)
  end subroutine grow

  !> "64 MiB" for a byte count that is a whole number of MiB.
  function mib(bytes) result(text)
    integer(i8), intent(in) :: bytes
    character(len=:), allocatable :: text
    character(len=24) :: digits
    write (digits, "(i0)") bytes/1048576_i8
    text = trim(digits)//" MiB"
  end function mib

  !> `path` holding `text`, whole or not at all (written to the private file `tmp` first):
  !> created only if absent, or replacing it (atomically) when `replace`. `status` is 0,
  !> exists_already, or the errno value that says why not (errno_text).
  integer function write_whole(path, tmp, text, replace) result(status)
    !> Path of the file; the private temporary file beside it; the text written.
    character(len=*), intent(in) :: path, tmp, text
    !> Replace an existing file (else an existing one gives exists_already).
    logical, intent(in) :: replace
    status = int(c_write_whole(path//c_null_char, tmp//c_null_char, text, &
                               len(text, c_long), merge(1_c_int, 0_c_int, replace)))
  end function write_whole

  !> Create the empty file `path` (exclusively): 0, or the errno value that says why not.
  integer function create_empty(path) result(status)
    !> Path of the file.
    character(len=*), intent(in) :: path
    status = int(c_create_empty(path//c_null_char))
  end function create_empty

  !> Remove `path` if it exists (a file, a FIFO, a link; never a folder).
  subroutine remove_file(path)
    !> Path of the file.
    character(len=*), intent(in) :: path
    integer(c_int) :: status
    status = c_unlink(path//c_null_char)
  end subroutine remove_file

  !> The longest file name allowed in folder `dir` (255 on most file systems; -1 unknown).
  integer function name_max(dir)
    !> Path of the folder.
    character(len=*), intent(in) :: dir
    name_max = int(c_name_max(dir//c_null_char))
  end function name_max

  !> The C library's text of errno value `err` ("No space left on device").
  function errno_text(err) result(text)
    !> An errno value.
    integer, intent(in) :: err
    character(len=:), allocatable :: text
    character(kind=c_char, len=200) :: buf
    call c_errno_text(int(err, c_int), buf, len(buf, c_int))
    text = trim(buf)
  end function errno_text

end module davit_io_files
