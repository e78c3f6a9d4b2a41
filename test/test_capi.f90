!> The library's Fortran side (davit_capi_session, davit_capi_snapshot) and the winch's
!> operator set-point: a session stepped in pieces is the driver's run, a snapshot's replay
!> is the run it was taken from, the set-point ramps as stated. The C ABI and the Python
!> package over it: test/python/test_library.py.
module test_capi
  use, intrinsic :: iso_fortran_env, only: int8
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_rigging_winch, only: winch_type, winch_speed, winch_command
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use davit_system_model, only: system_type
  use davit_capi_session, only: session_type, session_open, session_advance_to, &
                                session_control, ctrl_winch, ctrl_release
  use davit_capi_snapshot, only: snapshot_bytes, snapshot_restore
  use system_fixture, only: new_test_system, deck_config
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_capi

  character(len=*), parameter :: nl = new_line("a")
  !> A short launch from the davit over a box ship in a regular sea.
  character(len=*), parameter :: deck = &
    "&simulation scene = 'launch', t_end = 2.0, dt = 1.0e-3, output_interval = 0.02 /"//nl// &
    "&boat position = 0.0, 13.3, -15.0 /"//nl// &
    "&rigging reeving = 'a', sheaves = 'quasi_static', lumps = 0, drum_speed = 0.7 /"//nl// &
    "&sea level = 4, wave_type = 'stokes2', direction_deg = 60.0 /"//nl

contains

  function collect_capi() result(suite)
    type(suite_type) :: suite
    suite%name = "capi"
    suite%cases = [new_case("winch_set_point_ramp", winch_set_point), &
                   new_case("session_pieces_equal_driver_run", session_equals_driver), &
                   new_case("snapshot_replay_restores_bitwise", snapshot_roundtrip)]
  end function collect_capi

  !> From 0.7 m/s (the deck's, after its 1 s ramp) to 1.2 m/s over 2 s from t = 5 s:
  !> continuous at 5 s, halfway (0.95) at 6 s, 1.2 from 7 s on; a brake (to 0 over 0.5 s)
  !> at 10 s: 0.6 at 10.25 s, at rest from 10.5 s.
  subroutine winch_set_point(state)
    type(case_state), intent(inout) :: state
    type(winch_type) :: w
    w%speed = 0.7_wp
    call winch_command(w, 5.0_wp, 1.2_wp, 2.0_wp)
    call check(state, winch_speed(w, 5.0_wp), 0.7_wp, "continuous at the command", &
               abs_tol=1.0e-15_wp)
    call check(state, winch_speed(w, 4.0_wp), 0.7_wp, "deck's profile before it", &
               abs_tol=1.0e-15_wp)
    call check(state, winch_speed(w, 6.0_wp), 0.95_wp, "halfway up the ramp", &
               abs_tol=1.0e-15_wp)
    call check(state, winch_speed(w, 9.0_wp), 1.2_wp, "set-point reached", &
               abs_tol=1.0e-15_wp)
    call winch_command(w, 10.0_wp, 0.0_wp, 0.5_wp)
    call check(state, winch_speed(w, 10.25_wp), 0.6_wp, "braking halfway", abs_tol=1.0e-15_wp)
    call check(state, winch_speed(w, 11.0_wp), 0.0_wp, "at rest", abs_tol=0.0_wp)
  end subroutine winch_set_point

  !> The driver's run of the deck, recorded every 0.02 s, against a session stepped in
  !> 0.02 s pieces: the same positions and sling tensions, bit for bit (one executable).
  subroutine session_equals_driver(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: run_error, error
    type(session_type) :: s
    real(wp), allocatable :: y(:)
    real(wp) :: pos(3), e(3), v(3), w(3), a(3)
    integer :: k
    logical :: same
    cfg = deck_config(deck)
    ! the session first: it sets OpenBLAS to one thread, as davit's main program does, so
    ! that both runs sum their small matrix products in the same order
    call session_open(s, cfg, "test.nml", deck, error)
    call check_true(state, .not. allocated(error), "session opens")
    if (allocated(error)) return
    y = new_test_system(sys, cfg)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error)
    call check_true(state, .not. allocated(error) .and. .not. allocated(run_error), &
                    "driver's run completes")
    same = .true.
    do k = 2, rec%n
      call session_advance_to(s, s%t + 0.02_wp, error)
      if (allocated(error)) exit
      call s%sys%observe(s%t, s%y, pos, e, v, w, a)
      same = same .and. s%t == rec%time(k) .and. all(pos == rec%position(:, k))
    end do
    call check_true(state, rec%n == 101, "101 samples over 2 s")
    call check_true(state, .not. allocated(error), "session steps to the end")
    call check_true(state, same, "every sample equal to the driver's")
  end subroutine session_equals_driver

  !> A winch command at 0.5 s, snapshot at 1 s, release at 1.5 s, on to 2 s; the restore,
  !> with the same release, reaches the same state; a flipped bit is refused.
  subroutine snapshot_roundtrip(state)
    type(case_state), intent(inout) :: state
    type(session_type) :: s, r
    type(error_type), allocatable :: error
    integer(int8), allocatable :: b(:)
    real(wp), allocatable :: y_end(:)
    call session_open(s, deck_config(deck), "test.nml", deck, error)
    call session_advance_to(s, 0.5_wp, error)
    call session_control(s, ctrl_winch, [1.0_wp, 0.5_wp], error)
    call session_advance_to(s, 1.0_wp, error)
    b = snapshot_bytes(s)
    call finish(s)
    y_end = s%y
    call snapshot_restore(b, r, error)
    call check_true(state, .not. allocated(error), "snapshot restores")
    if (allocated(error)) return
    call check(state, r%t, 1.0_wp, "at the snapshot's time", abs_tol=1.0e-12_wp)
    call finish(r)
    call check_true(state, all(r%y == y_end) .and. r%t == s%t, "same state at 2 s")
    call check_true(state, r%sys%hist%release_time == s%sys%hist%release_time .and. &
                    s%sys%hist%release_time > 0.0_wp, "same release")
    b(size(b)) = ieor(b(size(b)), 1_int8)
    call snapshot_restore(b, r, error)
    call check_true(state, allocated(error), "a flipped bit of the check is refused")
  contains
    subroutine finish(x)
      type(session_type), intent(inout) :: x
      call session_advance_to(x, 1.5_wp, error)
      call session_control(x, ctrl_release, [0.0_wp, 0.0_wp], error)
      call session_advance_to(x, 2.0_wp, error)
    end subroutine finish
  end subroutine snapshot_roundtrip

end module test_capi
