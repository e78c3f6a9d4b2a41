!> A session's whole state as bytes, and back. The run is deterministic, so its state at
!> any pass is fixed by the deck, the controls (with the passes they came before) and the
!> number of passes: the snapshot holds these, and the time and state vector it reached as
!> a check. A restore rebuilds the session from the deck and replays it (the integrator's,
!> the history's, the ship's slow caches and the launch log's state all come back as they
!> were), then refuses a result that differs from the check in any bit. It costs the
!> replayed run's time (1.3 s for the default launch's 87 s).
module davit_capi_snapshot
  use, intrinsic :: iso_fortran_env, only: int8
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type, parse_config
  use davit_io_text, only: int_text
  use davit_capi_session, only: session_type, session_open, session_replay
  implicit none
  private
  public :: snapshot_bytes, snapshot_restore

  character(len=8), parameter :: magic = "DAVITSV1"
  !> The header after the magic: the lengths of name and text, the passes, the controls,
  !> the state.
  integer, parameter :: n_head = 5

contains

  !> The bytes of session `s`.
  function snapshot_bytes(s) result(b)
    !> The session whose state is written.
    type(session_type), intent(in) :: s
    integer(int8), allocatable :: b(:)
    integer :: n
    n = s%n_ctrl
    b = [transfer(magic, [0_int8]), &
         transfer([int(len(s%deck_name), i8), int(len(s%deck_text), i8), s%passes, &
                   int(n, i8), int(size(s%y), i8)], [0_int8]), &
         transfer(s%deck_name, [0_int8]), transfer(s%deck_text, [0_int8])]
    if (n > 0) b = [b, transfer(s%ctrl_pass(1:n), [0_int8]), &
                    transfer(int(s%ctrl_kind(1:n), i8), [0_int8]), &
                    transfer(s%ctrl_value(:, 1:n), [0_int8])]
    b = [b, transfer([s%t, s%y], [0_int8])]
  end function snapshot_bytes

  !> The session the bytes `b` describe, replayed from its deck.
  subroutine snapshot_restore(b, s, error)
    !> The snapshot's bytes.
    integer(int8), intent(in) :: b(:)
    !> The session rebuilt from the deck and replayed.
    type(session_type), intent(out) :: s
    !> Set when the bytes are not a snapshot, the deck fails, or the replay differs from the
    !> stored check.
    type(error_type), allocatable, intent(out) :: error
    integer(i8) :: head(n_head), pos, need, n, ny
    integer(i8), allocatable :: ctrl_pass(:), kinds(:)
    real(wp), allocatable :: values(:, :), check(:)
    character(len=:), allocatable :: name, text
    type(config_type) :: cfg
    if (size(b) < 8 + 8*n_head) then
      call fatal_error(error, "snapshot: too short ("//int_text(size(b, kind=i8))//" bytes)")
      return
    end if
    if (transfer(b(1:8), magic) /= magic) then
      call fatal_error(error, "snapshot: not a davit snapshot (no "//magic//" at its start)")
      return
    end if
    head = transfer(b(9:8 + 8*n_head), head)
    if (any(head < 0) .or. any(head([1, 2, 4, 5]) > size(b, kind=i8))) then
      call fatal_error(error, "snapshot: corrupt header")
      return
    end if
    n = head(4)
    ny = head(5)
    need = 8 + 8*n_head + head(1) + head(2) + 32*n + 8*(ny + 1)
    if (need /= size(b, kind=i8)) then
      call fatal_error(error, "snapshot: "//int_text(size(b, kind=i8))//" bytes where its "// &
                       "header asks for "//int_text(need))
      return
    end if
    pos = 8 + 8*n_head
    allocate (character(len=head(1)) :: name)
    allocate (character(len=head(2)) :: text)
    if (head(1) > 0) name = transfer(b(pos + 1:pos + head(1)), name)
    pos = pos + head(1)
    if (head(2) > 0) text = transfer(b(pos + 1:pos + head(2)), text)
    pos = pos + head(2)
    allocate (ctrl_pass(n), kinds(n), values(2, n), check(ny + 1))
    if (n > 0) then
      ctrl_pass = transfer(b(pos + 1:pos + 8*n), ctrl_pass)
      kinds = transfer(b(pos + 8*n + 1:pos + 16*n), kinds)
      values = reshape(transfer(b(pos + 16*n + 1:pos + 32*n), [0.0_wp]), [2_i8, n])
    end if
    pos = pos + 32*n
    check = transfer(b(pos + 1:pos + 8*(ny + 1)), check)
    call parse_config(name, text, cfg, error)
    if (allocated(error)) return
    call session_open(s, cfg, name, text, error)
    if (allocated(error)) return
    if (size(s%y, kind=i8) /= ny) then
      call fatal_error(error, "snapshot: its state has "//int_text(ny)//" components, the "// &
                       "deck's "//int_text(size(s%y, kind=i8)))
      return
    end if
    call session_replay(s, head(3), ctrl_pass, int(kinds), values, error)
    if (allocated(error)) return
    if (any(transfer([s%t, s%y], [0_i8]) /= transfer(check, [0_i8]))) then
      call fatal_error(error, "snapshot: the replay of '"//name//"' did not reach the "// &
                       "saved state (another build or machine of davit?)")
    end if
  end subroutine snapshot_restore

end module davit_capi_snapshot
