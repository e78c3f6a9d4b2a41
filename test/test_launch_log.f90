!> The launch log (issue 12): the occupant filter against its analytic response, the seat's
!> acceleration against rigid-body kinematics, the wire limits against rope catalogue
!> values and the static sling load, the derived end time (review G24) and the outcome.
module test_launch_log
  use davit_kinds, only: wp, pi, gravity
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_io_limits_keys, only: minimum_breaking_load
  use davit_core_filters, only: phaseless_lowpass
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, deck_config
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use davit_run_launch_log, only: launch_log, new_launch_log
  use davit_run_seat_trace, only: seat_trace
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_launch_log

contains

  function collect_launch_log() result(suite)
    type(suite_type) :: suite
    suite%name = "launch_log"
    suite%cases = [new_case("filter_minus_3db_at_cutoff_no_phase", filter_response), &
                   new_case("seat_centripetal_acceleration", seat_rotation), &
                   new_case("rope_mbl_catalogue_and_static_swl", wire_limits), &
                   new_case("end_time_derived_g24", end_time), &
                   new_case("outcome_still_lowering", outcome_lowering)]
  end function collect_launch_log


  !> Amplitude of a filtered sine in the middle of a long record: the 2-pole magnitude
  !> squared by the two passes, 1/(1 + (f/f0)^4) with f0 = 1.2465 fc: 1/sqrt(2) at the
  !> cut-off, ~1 at a tenth of it, ~1/100 at 4 times it; and no shift of the crest.
  subroutine filter_response(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: dt = 1.0e-3_wp, fc = 20.0_wp
    real(wp) :: ratios(3), gain, expected(3), w0
    integer :: i
    ratios = [1.0_wp, 0.1_wp, 4.0_wp]
    ! bilinear transform: the digital section's magnitude at f is the analog one at
    ! tan(pi f dt)/(pi dt); each pass has its corner at f0 = 1.2465 fc
    w0 = tan(pi*1.24650_wp*fc*dt)
    expected = 1.0_wp/(1.0_wp + (tan(pi*ratios*fc*dt)/w0)**4)
    do i = 1, 3
      gain = middle_amplitude(ratios(i)*fc, dt, fc)
      call note(state, "gain at f/fc", gain)
      call check(state, gain, expected(i), "gain", rel_tol=1e-2_wp)
    end do
    call check(state, crest_shift(dt, fc), 0.0_wp, "crest not shifted (s)", abs_tol=dt)
  end subroutine filter_response

  real(wp) function middle_amplitude(f, dt, fc) result(a)
    real(wp), intent(in) :: f, dt, fc
    real(wp) :: x(20000), y(20000)
    integer :: k
    x = [(sin(2.0_wp*pi*f*k*dt), k = 1, 20000)]
    y = phaseless_lowpass(x, dt, fc)
    a = maxval(abs(y(5000:15000)))
  end function middle_amplitude

  !> Time of the filtered crest of a 10 Hz sine minus the input's, in the middle.
  real(wp) function crest_shift(dt, fc) result(s)
    real(wp), intent(in) :: dt, fc
    real(wp) :: x(4000), y(4000)
    integer :: k, i1, i2
    x = [(cos(2.0_wp*pi*10.0_wp*(k - 2000)*dt), k = 1, 4000)]
    y = phaseless_lowpass(x, dt, fc)
    i1 = maxloc(x(1950:2050), 1)
    i2 = maxloc(y(1950:2050), 1)
    s = (i2 - i1)*dt
  end function crest_shift

  !> A seat 2 m from an axis turning at 1 rev/s: its acceleration is the centripetal
  !> omega^2 r = 79 m/s^2, raw (step means) and after the 20 Hz filter, from steps of
  !> uneven size (1 ms and 0.1 ms, as near a contact).
  subroutine seat_rotation(state)
    type(case_state), intent(inout) :: state
    type(seat_trace) :: tr
    real(wp), parameter :: w = 2.0_wp*pi, r = 2.0_wp
    real(wp), allocatable :: a(:, :)
    real(wp) :: t, h, eye(3, 3)
    integer :: k
    eye = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], &
                  [3, 3])
    t = 0.0_wp
    call tr%add(t, w*r*[0.0_wp, 1.0_wp, 0.0_wp], eye)
    k = 0
    do while (t < 3.0_wp - 1.0e-12_wp)
      k = k + 1
      h = merge(1.0e-4_wp, 1.0e-3_wp, mod(k/200, 2) == 1)
      t = t + h
      call tr%add(t, w*r*[-sin(w*t), cos(w*t), 0.0_wp], eye)
    end do
    a = tr%filtered()
    call note(state, "raw peak (m/s^2)", tr%raw_peak)
    call check(state, tr%raw_peak, w**2*r, "raw = omega^2 r", rel_tol=1e-5_wp)
    call check(state, maxval(norm2(a(:, 1000:2000), dim=1)), w**2*r, "filtered max", &
               rel_tol=2e-3_wp)
    call check(state, minval(norm2(a(:, 1000:2000), dim=1)), w**2*r, "filtered min", &
               rel_tol=2e-3_wp)
  end subroutine seat_rotation

  !> EN 12385-4 catalogue values of 20 mm 6x36WS-IWRC: 279 kN (1960) and 252 kN (1770).
  !> The III.B boat (8500 kg) hangs at rest with W/2 = 41.7 kN per sling: below the SWL
  !> 279/6 = 46.5 kN of 20 mm slings, above the 26.2 kN of 15 mm ones from the first step.
  subroutine wire_limits(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(launch_log) :: log
    real(wp) :: ea
    cfg = deck_config("&simulation t_end = 0.1 /")
    call check(state, minimum_breaking_load(cfg%limits, 0.02_wp), 279.0e3_wp, &
               "MBL 20 mm 1960", rel_tol=2e-3_wp)
    cfg%limits%grade = 1770.0e6_wp
    call check(state, minimum_breaking_load(cfg%limits, 0.02_wp), 252.0e3_wp, &
               "MBL 20 mm 1770", rel_tol=2e-3_wp)
    ! slings of length 3 m less their static stretch under W/2: the boat hangs at rest
    ea = 200.0e9_wp*pi*0.02_wp**2/4.0_wp
    log = hang(state, "&simulation t_end = 0.1 / &wind speed = 0.0 / &slings length = "// &
               real_text(3.0_wp/(1.0_wp + 0.5_wp*8500.0_wp*gravity/ea))//" /")
    call check(state, log%loads%sling(1), 0.5_wp*8500.0_wp*gravity, "peak = W/2", &
               rel_tol=1e-6_wp)
    call check(state, log%loads%swl%first, -1.0_wp, "20 mm: SWL never exceeded", abs_tol=0.0_wp)
    ea = 200.0e9_wp*pi*0.015_wp**2/4.0_wp
    log = hang(state, "&simulation t_end = 0.1 / &wind speed = 0.0 / &slings diameter = "// &
               "0.015, length = "//real_text(3.0_wp/(1.0_wp + 0.5_wp*8500.0_wp*gravity/ea))//" /")
    call check(state, log%loads%swl%value, 0.356_wp*0.015_wp**2*1960.0e6_wp/6.0_wp, &
               "15 mm SWL", rel_tol=1e-12_wp)
    call check(state, log%loads%swl%first, 0.0_wp, "15 mm: SWL exceeded from t = 0", &
               abs_tol=0.0_wp)
    call check(state, log%loads%swl%duration, 0.1_wp, "... all the time", rel_tol=1e-9_wp)
    call check(state, log%loads%mbl%first, -1.0_wp, "MBL never exceeded", abs_tol=0.0_wp)
  end subroutine wire_limits

  function real_text(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=32) :: buf
    write (buf, "(es24.16)") x
    text = trim(adjustl(buf))
  end function real_text

  !> The hanging boat of `text`, integrated with its launch log.
  function hang(state, text) result(log)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: text
    type(launch_log) :: log
    type(config_type) :: cfg
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    cfg = deck_config(text)
    y = new_test_system(sys, cfg)
    log = new_launch_log(cfg, sys)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, log)
    call check_true(state, .not. (allocated(error) .or. allocated(run_error)), "run completes")
  end function hang

  !> Review G24: winch start + ramp + 1.3 (CG height)/(boat speed) + after_release; the boat
  !> runs at a quarter of the drum speed with reeving A, half with B.
  subroutine end_time(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    cfg = deck_config("&simulation scene = 'launch' / &rigging drum_speed = 0.7, "// &
                      "ramp_time = 1.0 /")
    call check(state, cfg%simulation%t_end, 1.0_wp + 1.3_wp*15.0_wp/0.175_wp + 5.0_wp, &
               "reeving A", rel_tol=1e-12_wp)
    cfg = deck_config("&simulation scene = 'lowering', after_release = 2.0 / &rigging "// &
                      "reeving = 'b', drum_speed = 0.7, ramp_time = 1.0, winch_start = 3.0 /")
    call check(state, cfg%simulation%t_end, 4.0_wp + 1.3_wp*15.0_wp/0.35_wp + 2.0_wp, &
               "reeving B", rel_tol=1e-12_wp)
    cfg = deck_config("&simulation scene = 'hanging_boat' /")
    call check(state, cfg%simulation%t_end, 60.0_wp, "other scenes 60 s", rel_tol=0.0_wp)
    cfg = deck_config("&simulation scene = 'launch', t_end = 30.0 /")
    call check(state, cfg%simulation%t_end, 30.0_wp, "a given t_end", rel_tol=0.0_wp)
  end subroutine end_time

  !> A lowering cut off after 2 s is reported as still lowering, not as a launch that
  !> failed for another cause.
  subroutine outcome_lowering(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    type(launch_log) :: log
    real(wp), allocatable :: y(:)
    character(len=:), allocatable :: text
    cfg = deck_config("&simulation scene = 'lowering', t_end = 2.0 / &wind speed = 0.0 /")
    y = new_test_system(sys, cfg)
    log = new_launch_log(cfg, sys)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, log)
    text = log%outcome(sys)
    call check_true(state, index(text, "not waterborne by t = 2") == 1 .and. &
                    index(text, "still lowering") > 0, "outcome: "//text)
    ! the causes at the water, by their stated thresholds (shares of the last ~10 s)
    log%lowest = 0.5_wp
    log%contact_share = 0.31_wp
    call check_true(state, index(log%outcome(sys), "pinned against the ship's side") > 0, &
                    "contact 31 %: pinned")
    log%contact_share = 0.29_wp
    log%slack_share = 0.21_wp
    call check_true(state, index(log%outcome(sys), "slack, snatching falls") > 0, &
                    "slack 21 %: riding the waves")
    log%slack_share = 0.19_wp
    call check_true(state, index(log%outcome(sys), "taut falls") > 0, "otherwise: taut")
  end subroutine outcome_lowering

end module test_launch_log
