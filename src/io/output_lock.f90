!> Where a davit output may go and who writes it: the checks made before an output file is
!> created (not a folder, FIFO or device; never an existing file that is not a davit
!> output; a name short enough for the temporary file beside it) and the advisory lock
!> `OUT.h5.lock` (written whole, holding the writer's process id and its temporary file,
!> taken over from a process that no longer runs), shared by runs, sweeps and merges.
module davit_io_output_lock
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: iso_c_binding, only: c_int
  use hdf5, only: hid_t, h5fopen_f, h5fclose_f, h5aexists_by_name_f, H5F_ACC_RDONLY_F
  use davit_kinds, only: i8
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_reader, only: h5_start
  use davit_io_namelist, only: int_to_str
  use davit_io_files, only: file_kind, kind_name, kind_none, kind_regular, kind_folder, &
                            read_stream, write_whole, exists_already, name_max, errno_text, &
                            remove_file
  implicit none
  private
  public :: check_output_path, acquire_lock, release_lock, note_tmp, tmp_suffix, create_cause

  !> The longest suffix of a temporary file, ".tmp.<pid>.<n>".
  integer, parameter :: tmp_suffix_max = 19

  interface
    function c_getpid() bind(C, name="getpid") result(pid)
      import :: c_int
      integer(c_int) :: pid
    end function c_getpid
    function c_kill(pid, sig) bind(C, name="kill") result(status)
      import :: c_int
      integer(c_int), value :: pid, sig
      integer(c_int) :: status
    end function c_kill
  end interface

contains

  !> ".tmp.<pid>.<n>": the temporary file's suffix (at most tmp_suffix_max characters).
  function tmp_suffix() result(suffix)
    character(len=:), allocatable :: suffix
    integer(i8) :: count
    call system_clock(count)
    suffix = ".tmp."//int_to_str(int(c_getpid()))//"."// &
             int_to_str(int(modulo(count, 1000000_i8)))
  end function tmp_suffix

  !> Why a file could not be created: the C library's words, or HDF5's failure.
  function create_cause(status) result(cause)
    !> 0 for HDF5's failure, else an errno value.
    integer, intent(in) :: status
    character(len=:), allocatable :: cause
    if (status /= 0) then
      cause = errno_text(status)
    else
      cause = "HDF5 cannot create it (disk full or not writable?)"
    end if
  end function create_cause

  !> Refuse an output that is a folder, a FIFO or device, an existing file that is not a
  !> davit output (an input deck, a database, anything else), or a name too long for the
  !> temporary file beside it: davit never replaces those, and never opens a FIFO (the
  !> open would wait for a reader forever).
  subroutine check_output_path(path, error)
    !> Path of the output.
    character(len=*), intent(in) :: path
    !> Set when the path is refused, with why.
    type(error_type), allocatable, intent(out) :: error
    integer(hid_t) :: file
    integer :: hdferr, kind
    logical :: has_version
    if (len(path) == 0) then
      call fatal_error(error, "the output file name is empty")
      return
    end if
    kind = file_kind(path)
    if (kind == kind_folder .or. path(len(path):) == "/") then
      call fatal_error(error, "the output '"//path//"' is a folder; name a file in it")
      return
    else if (kind /= kind_none .and. kind /= kind_regular) then
      call fatal_error(error, "the output '"//path//"' is "//kind_name(kind)// &
                       ", not a regular file; davit writes HDF5 files: name a regular file")
      return
    end if
    call check_name_length(path, error)
    if (allocated(error) .or. kind == kind_none) return
    call h5_start()
    has_version = .false.
    call h5fopen_f(path, H5F_ACC_RDONLY_F, file, hdferr)
    if (hdferr == 0) then
      call h5aexists_by_name_f(file, "/", "davit_version", has_version, hdferr)
      if (hdferr /= 0) has_version = .false.
      call h5fclose_f(file, hdferr)
    end if
    if (.not. has_version) call fatal_error(error, "refusing to overwrite '"//path// &
      "': it exists and is not a davit output (an input deck or a database?); "// &
      "choose another output name")
  end subroutine check_output_path

  !> The output's name plus the suffix of its temporary file must fit the file system's
  !> limit on one name (NAME_MAX, 255 bytes on most), or the run would fail only when it
  !> creates that file, for a reason nobody could guess.
  subroutine check_name_length(path, error)
    character(len=*), intent(in) :: path
    type(error_type), allocatable, intent(out) :: error
    integer :: slash, limit, longest
    slash = index(path, "/", back=.true.)
    limit = 255
    if (slash > 1) limit = name_max(path(1:slash - 1))
    if (slash <= 1) limit = name_max(merge("/", ".", slash == 1))
    if (limit <= 0) limit = 255
    longest = len(path) - slash + tmp_suffix_max
    if (longest <= limit) return
    call fatal_error(error, "the output name '"//path(slash + 1:)//"' is "// &
                     int_to_str(len(path) - slash)//" bytes long; with the suffix of its "// &
                     "temporary file ('.tmp.<process>.<n>', up to "// &
                     int_to_str(tmp_suffix_max)//" bytes) it passes the file system's "// &
                     "limit of "//int_to_str(limit)//" bytes per name: use a name of at "// &
                     "most "//int_to_str(limit - tmp_suffix_max)//" bytes")
  end subroutine check_name_length

  !> Take the advisory lock `path.lock` (created whole, holding this process id: a full
  !> disk leaves none). `owned` is false when this process already holds it (the caller
  !> then keeps it). A stale lock (its process no longer runs, or empty or unreadable: an
  !> older davit's on a full disk) is taken over with a note on stderr.
  subroutine acquire_lock(path, owned, error)
    !> Path of the output (the lock is path.lock).
    character(len=*), intent(in) :: path
    !> False when this process held the lock already.
    logical, intent(out) :: owned
    !> Set when another running davit holds the lock or it cannot be created.
    type(error_type), allocatable, intent(out) :: error
    integer :: attempt, pid, status
    character(len=:), allocatable :: lock, text
    lock = path//".lock"
    owned = .false.
    pid = 0
    do attempt = 1, 3
      status = write_whole(lock, lock//"."//int_to_str(int(c_getpid())), &
                           int_to_str(int(c_getpid()))//new_line("a"), replace=.false.)
      if (status == 0) then
        owned = .true.
        return
      end if
      ! a lock there decides before a failure to write ours (a full disk, read-only folder)
      if (file_kind(lock) /= kind_none) status = exists_already
      if (status /= exists_already) then
        call fatal_error(error, "cannot create output file '"//path//"' (its lock '"// &
                         lock//"'): "//errno_text(status)//"; any earlier '"//path// &
                         "' is left as it was")
        return
      end if
      call read_lock(lock, text, pid, error)
      if (allocated(error)) return
      if (pid == c_getpid()) return
      if (pid > 0) then
        if (process_runs(pid)) exit
      end if
      call take_over(lock, text, pid)
    end do
    call fatal_error(error, "another davit run (process "//int_to_str(pid)// &
                     ") is writing '"//path//"' (lock '"//lock//"'); wait for it, "// &
                     "choose another output name, or remove the lock if no davit runs")
  end subroutine acquire_lock

  !> Remove the stale lock `lock` (read as `text`, of process `pid`, 0 if none) and the
  !> temporary file it notes, unless another davit took it over meanwhile.
  subroutine take_over(lock, text, pid)
    character(len=*), intent(in) :: lock, text
    integer, intent(in) :: pid
    character(len=:), allocatable :: now
    type(error_type), allocatable :: error
    integer :: owner
    call read_lock(lock, now, owner, error)
    if (allocated(error) .or. now /= text) return  ! changed: the next attempt decides
    if (pid > 0) then
      write (error_unit, "(a)") "davit: note: taking over the stale lock '"//lock// &
        "' of process "//int_to_str(pid)//", which no longer runs"
    else
      write (error_unit, "(a)") "davit: note: taking over the stale lock '"//lock// &
        "', which names no process (left by a run that could not write it, e.g. on a "// &
        "full disk)"
    end if
    call remove_if_named(lock_tmp(lock, text))
    call remove_if_named(lock)
  end subroutine take_over

  !> The text of lock file `lock` and the process id on its first line (0 if none). A
  !> lock that is not a regular file (a FIFO, a folder) is refused: davit made none such.
  subroutine read_lock(lock, text, pid, error)
    character(len=*), intent(in) :: lock
    character(len=:), allocatable, intent(out) :: text
    integer, intent(out) :: pid
    type(error_type), allocatable, intent(out) :: error
    type(error_type), allocatable :: unread
    integer :: kind, ios, eol
    pid = 0
    text = ""
    kind = file_kind(lock)
    if (kind == kind_none) return  ! released meanwhile
    if (kind /= kind_regular) then
      call fatal_error(error, "the lock '"//lock//"' is "//kind_name(kind)// &
                       ", not a davit lock; remove it")
      return
    end if
    call read_stream(lock, "lock", 65536_i8, text, unread)
    if (allocated(unread)) text = ""
    eol = index(text//new_line("a"), new_line("a"))
    if (eol < 2 .or. eol > 10) return
    if (verify(text(1:eol - 1), "0123456789") /= 0) return
    read (text(1:eol - 1), *, iostat=ios) pid
    if (ios /= 0) pid = 0
  end subroutine read_lock

  !> Whether process `pid` runs (kill 0 succeeds, or it runs under another user: /proc).
  logical function process_runs(pid)
    integer, intent(in) :: pid
    process_runs = c_kill(int(pid, c_int), 0_c_int) == 0
    if (.not. process_runs) inquire (file="/proc/"//int_to_str(pid)//"/.", &
                                     exist=process_runs)
  end function process_runs

  !> Remove the lock `path.lock` if this process holds it.
  subroutine release_lock(path)
    !> Path of the output (the lock is path.lock).
    character(len=*), intent(in) :: path
    if (lock_owner(path//".lock") == c_getpid()) call remove_if_named(path//".lock")
  end subroutine release_lock

  !> Note the temporary file in the lock (line 2) so that whoever takes over a stale
  !> lock can remove what a killed run left. The lock is replaced whole (a full disk
  !> keeps the one-line lock rather than emptying it).
  subroutine note_tmp(path, tmp)
    !> Path of the output (the lock is path.lock); the temporary file.
    character(len=*), intent(in) :: path, tmp
    character(len=:), allocatable :: lock
    integer :: status
    lock = path//".lock"
    if (lock_owner(lock) /= c_getpid()) return
    status = write_whole(lock, lock//"."//int_to_str(int(c_getpid())), &
                         int_to_str(int(c_getpid()))//new_line("a")//tmp//new_line("a"), &
                         replace=.true.)
  end subroutine note_tmp

  !> The temporary file noted in lock `lock` (text `text`; empty if none), in the lock's
  !> folder however either was spelled (`out.h5`, `./out.h5`, `$PWD/out.h5`): only a
  !> temporary file of this lock's output, never anything else.
  function lock_tmp(lock, text) result(tmp)
    character(len=*), intent(in) :: lock, text
    character(len=:), allocatable :: tmp, noted, output
    integer :: eol, slash
    tmp = ""
    eol = index(text, new_line("a"))
    if (eol == 0) return
    noted = text(eol + 1:)
    eol = index(noted, new_line("a"))
    if (eol > 0) noted = noted(1:eol - 1)
    noted = noted(index(noted, "/", back=.true.) + 1:)
    slash = index(lock, "/", back=.true.)
    output = lock(slash + 1:len(lock) - 5)
    if (index(noted, output//".tmp.") /= 1 .or. len(noted) == len(output) + 5) return
    if (verify(noted(len(output) + 6:), "0123456789.") /= 0) return
    tmp = lock(1:slash)//noted
  end function lock_tmp

  !> Process id written in lock file `lock`; 0 if none can be read.
  integer function lock_owner(lock) result(pid)
    character(len=*), intent(in) :: lock
    character(len=:), allocatable :: text
    type(error_type), allocatable :: error
    call read_lock(lock, text, pid, error)
  end function lock_owner

  !> Remove `path` if it names a file (never opened: a FIFO put under that name cannot
  !> block).
  subroutine remove_if_named(path)
    character(len=*), intent(in) :: path
    if (len(path) > 0) call remove_file(path)
  end subroutine remove_if_named

end module davit_io_output_lock
