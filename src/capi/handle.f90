!> The C ABI's handle (include/davit.h): one session, its last error code and message.
!> Each handle owns everything it touches, so threads may each step their own; nothing
!> is global. The functions here create and destroy handles, step them, take controls and
!> save and restore them; davit_capi_getters reads them.
module davit_capi_handle
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_loc, &
                                         c_f_pointer, c_int, c_double, c_char, c_size_t, &
                                         c_int8_t, c_null_char
  use, intrinsic :: iso_fortran_env, only: int8
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type
  use davit_io_config, only: config_type, read_config, parse_config
  use davit_io_files, only: read_stream
  use davit_capi_session, only: session_type, session_open, session_advance_to, &
                                session_control, ctrl_winch, ctrl_brake, ctrl_release, &
                                ctrl_heading
  use davit_capi_snapshot, only: snapshot_bytes, snapshot_restore
  implicit none
  private
  public :: capi_handle, handle_of, c_string, copy_c_string, fail
  public :: e_ok, e_input, e_run, e_arg, e_snapshot
  public :: davit_create_file, davit_create_text, davit_destroy, davit_error_code
  public :: davit_error_message, davit_advance, davit_advance_to, davit_set_winch_speed
  public :: davit_brake, davit_release, davit_set_heading, davit_save_size, davit_save
  public :: davit_restore, ready_handle

  !> Error codes (davit.h's DAVIT_OK ... DAVIT_E_SNAPSHOT).
  integer(c_int), parameter :: e_ok = 0, e_input = 1, e_run = 2, e_arg = 3, e_snapshot = 4

  type :: capi_handle
    !> Whether the session opened (a failed handle only carries its error).
    logical :: ready = .false.
    !> The session the handle owns.
    type(session_type) :: s
    !> Last error code (e_ok ... e_snapshot).
    integer(c_int) :: code = e_ok
    !> Last error message ("" when none).
    character(len=:), allocatable :: message
  end type capi_handle

  !> Largest deck file read [bytes] (as davit run's).
  integer(i8), parameter :: max_deck_bytes = 64_i8*1048576_i8

contains

  !> The handle behind `h`, or null.
  function handle_of(h) result(p)
    !> The C handle (may be null).
    type(c_ptr), intent(in) :: h
    type(capi_handle), pointer :: p
    p => null()
    if (c_associated(h)) call c_f_pointer(h, p)
  end function handle_of

  !> The NUL-terminated C string at `s` (at most `cap` characters).
  function c_string(s, cap) result(text)
    !> The C string.
    character(kind=c_char), intent(in) :: s(*)
    !> Most characters read.
    integer(i8), intent(in) :: cap
    character(len=:), allocatable :: text
    integer(i8) :: n, i
    n = 0
    do while (n < cap)
      if (s(n + 1) == c_null_char) exit
      n = n + 1
    end do
    allocate (character(len=n) :: text)
    do i = 1, n
      text(i:i) = s(i)
    end do
  end function c_string

  !> `text` into the C buffer `buf` of `len` bytes, NUL-terminated, cut to len - 1.
  subroutine copy_c_string(text, buf, len)
    !> Text to copy.
    character(len=*), intent(in) :: text
    !> The C buffer.
    type(c_ptr), intent(in) :: buf
    !> Size of the buffer [bytes].
    integer(c_size_t), intent(in) :: len
    character(kind=c_char, len=1), pointer :: out(:)
    integer(c_size_t) :: i, k
    if (len < 1 .or. .not. c_associated(buf)) return
    call c_f_pointer(buf, out, [len])
    k = min(int(len_trim(text), c_size_t), len - 1)
    do i = 1, k
      out(i) = text(i:i)
    end do
    out(k + 1) = c_null_char
  end subroutine copy_c_string

  !> Note `code` and `message` in the handle; returns the code.
  integer(c_int) function fail(p, code, message) result(rc)
    !> The handle.
    type(capi_handle), intent(inout) :: p
    !> Error code (e_ok ... e_snapshot).
    integer(c_int), intent(in) :: code
    !> Error message.
    character(len=*), intent(in) :: message
    p%code = code
    p%message = message
    rc = code
  end function fail

  !> A new handle in `out` (always, unless out of memory: a failed one carries the error).
  integer(c_int) function new_handle(cfg, name, text, error, out) result(rc)
    !> The deck's run configuration.
    type(config_type), intent(in) :: cfg
    !> The deck's name (for messages) and its text.
    character(len=*), intent(in) :: name, text
    !> An error from reading the deck, if any (then the handle carries it).
    type(error_type), allocatable, intent(inout) :: error
    !> The new handle.
    type(c_ptr), intent(out) :: out
    type(capi_handle), pointer :: p
    allocate (p)
    out = c_loc(p)
    rc = e_ok
    p%message = ""
    if (allocated(error)) then
      rc = fail(p, e_input, error%message)
      return
    end if
    call session_open(p%s, cfg, name, text, error)
    if (allocated(error)) then
      rc = fail(p, e_input, error%message)
      return
    end if
    p%ready = .true.
  end function new_handle

  integer(c_int) function davit_create_file(path, out) bind(c) result(rc)
    !> Path of the deck file (NUL-terminated).
    character(kind=c_char), intent(in) :: path(*)
    !> The new handle (set even on failure: destroy it either way).
    type(c_ptr), intent(out) :: out
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    character(len=:), allocatable :: name, text
    name = c_string(path, 4096_i8)
    text = ""
    call read_config(name, cfg, error)
    if (.not. allocated(error)) call read_stream(name, "input deck", max_deck_bytes, text, error)
    rc = new_handle(cfg, name, text, error, out)
  end function davit_create_file

  integer(c_int) function davit_create_text(name, text, out) bind(c) result(rc)
    !> The deck's name (for messages) and its text (NUL-terminated).
    character(kind=c_char), intent(in) :: name(*), text(*)
    !> The new handle (set even on failure: destroy it either way).
    type(c_ptr), intent(out) :: out
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    character(len=:), allocatable :: n, t
    n = c_string(name, 4096_i8)
    t = c_string(text, max_deck_bytes)
    call parse_config(n, t, cfg, error)
    rc = new_handle(cfg, n, t, error, out)
  end function davit_create_text

  subroutine davit_destroy(h) bind(c)
    !> The handle to destroy (null is ignored).
    type(c_ptr), value, intent(in) :: h
    type(capi_handle), pointer :: p
    p => handle_of(h)
    if (associated(p)) deallocate (p)
  end subroutine davit_destroy

  integer(c_int) function davit_error_code(h) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    type(capi_handle), pointer :: p
    p => handle_of(h)
    rc = e_arg
    if (associated(p)) rc = p%code
  end function davit_error_code

  !> Copies the last message (NUL-terminated, cut to len - 1); returns its full length.
  integer(c_size_t) function davit_error_message(h, buf, len) bind(c) result(n)
    !> The handle, and the C buffer receiving the message.
    type(c_ptr), value, intent(in) :: h, buf
    !> Size of the buffer [bytes].
    integer(c_size_t), value, intent(in) :: len
    type(capi_handle), pointer :: p
    character(len=:), allocatable :: m
    p => handle_of(h)
    m = "null handle"
    if (associated(p)) m = p%message
    n = int(len_trim(m), c_size_t)
    call copy_c_string(m, buf, len)
  end function davit_error_message

  !> The handle ready to run, or null with the code set; a call whose arguments fail its
  !> condition `valid` is refused (e_arg) with the message `why`.
  function ready_handle(h, rc, valid, why) result(p)
    !> The C handle.
    type(c_ptr), intent(in) :: h
    !> Error code (e_ok, or e_arg for a null handle or refused arguments, or the failed
    !> handle's code).
    integer(c_int), intent(out) :: rc
    !> Whether the call's other arguments are acceptable (absent: they are).
    logical, intent(in), optional :: valid
    !> What is wrong with them when not `valid`.
    character(len=*), intent(in), optional :: why
    type(capi_handle), pointer :: p
    p => handle_of(h)
    rc = e_arg
    if (.not. associated(p)) return
    if (.not. p%ready) then
      rc = p%code
      if (rc == e_ok) rc = fail(p, e_arg, "handle has no session")
      p => null()
      return
    end if
    rc = e_ok
    p%code = e_ok
    p%message = ""
    if (present(valid)) then
      if (.not. valid) then
        rc = fail(p, e_arg, why)
        p => null()
      end if
    end if
  end function ready_handle

  integer(c_int) function davit_advance_to(h, t) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Time to step to [s].
    real(c_double), value, intent(in) :: t
    type(capi_handle), pointer :: p
    type(error_type), allocatable :: error
    p => ready_handle(h, rc, abs(t) < huge(1.0_wp), &
                      "advance_to: the time is not a finite number")
    if (.not. associated(p)) return
    call session_advance_to(p%s, real(t, wp), error)
    if (allocated(error)) rc = fail(p, e_run, error%message)
  end function davit_advance_to

  integer(c_int) function davit_advance(h, dt) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Time to step by [s].
    real(c_double), value, intent(in) :: dt
    type(capi_handle), pointer :: p
    p => ready_handle(h, rc, dt >= 0.0_c_double .and. dt < huge(1.0_wp), &
                      "advance: dt must be a finite number >= 0")
    if (.not. associated(p)) return
    rc = davit_advance_to(h, p%s%t + dt)
  end function davit_advance

  !> Control `kind` with `v1`, `v2` on handle `h`.
  integer(c_int) function control(h, kind, v1, v2) result(rc)
    !> The handle.
    type(c_ptr), intent(in) :: h
    !> Control kind (ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading).
    integer, intent(in) :: kind
    !> Control values (see the control kinds).
    real(c_double), intent(in) :: v1, v2
    type(capi_handle), pointer :: p
    type(error_type), allocatable :: error
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    call session_control(p%s, kind, [real(v1, wp), real(v2, wp)], error)
    if (allocated(error)) rc = fail(p, e_arg, error%message)
  end function control

  integer(c_int) function davit_set_winch_speed(h, speed, ramp) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Drum speed set-point [m/s] in [-10, 10] (pay-out > 0), reached over ramp [s].
    real(c_double), value, intent(in) :: speed, ramp
    rc = control(h, ctrl_winch, speed, ramp)
  end function davit_set_winch_speed

  integer(c_int) function davit_brake(h, time) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Time for the drum to come to rest [s].
    real(c_double), value, intent(in) :: time
    rc = control(h, ctrl_brake, time, 0.0_c_double)
  end function davit_brake

  integer(c_int) function davit_release(h) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    rc = control(h, ctrl_release, 0.0_c_double, 0.0_c_double)
  end function davit_release

  integer(c_int) function davit_set_heading(h, heading) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Heading set-point of the ship [rad].
    real(c_double), value, intent(in) :: heading
    rc = control(h, ctrl_heading, heading, 0.0_c_double)
  end function davit_set_heading

  !> Bytes davit_save writes (0 for a handle without session).
  integer(c_size_t) function davit_save_size(h) bind(c) result(n)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    type(capi_handle), pointer :: p
    integer(c_int) :: rc
    n = 0
    p => ready_handle(h, rc)
    if (associated(p)) n = size(snapshot_bytes(p%s), kind=c_size_t)
  end function davit_save_size

  integer(c_int) function davit_save(h, buf, len) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Buffer receiving the snapshot's bytes.
    integer(c_int8_t), intent(out) :: buf(*)
    !> Size of the buffer [bytes] (at least davit_save_size).
    integer(c_size_t), value, intent(in) :: len
    type(capi_handle), pointer :: p
    integer(int8), allocatable :: b(:)
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    b = snapshot_bytes(p%s)
    if (size(b, kind=c_size_t) > len) then
      rc = fail(p, e_arg, "save: the buffer holds fewer bytes than davit_save_size")
      return
    end if
    buf(1:size(b)) = b
  end function davit_save

  !> Replace the handle's session by the one saved in `buf`; on failure it stays as it was.
  integer(c_int) function davit_restore(h, buf, len) bind(c) result(rc)
    !> The handle whose session is replaced.
    type(c_ptr), value, intent(in) :: h
    !> The snapshot's bytes.
    integer(c_int8_t), intent(in) :: buf(*)
    !> Number of bytes.
    integer(c_size_t), value, intent(in) :: len
    type(capi_handle), pointer :: p
    type(session_type), allocatable :: s
    type(error_type), allocatable :: error
    p => handle_of(h)
    rc = e_arg
    if (.not. associated(p)) return
    allocate (s)
    call snapshot_restore(buf(1:len), s, error)
    if (allocated(error)) then
      rc = fail(p, e_snapshot, error%message)
      return
    end if
    p%s = s
    p%ready = .true.
    rc = e_ok
    p%code = e_ok
    p%message = ""
  end function davit_restore

end module davit_capi_handle
