!> The rule checks (issue 16), each on a constructed run whose answer is known: the
!> lowering speed of a drum paying out at a set speed through four parts, an impact thrown
!> at 3.6 m/s, an emergency stop against the analytic snatch of a mass on a spring, the hook
!> load at a waterborne release; the occupant's dynamic response model against its step
!> response; the margins' signs.
module test_assess
  use davit_kinds, only: wp, pi, gravity
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, deck_config
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use davit_run_launch_log, only: launch_log, new_launch_log
  use davit_run_seat_trace, only: seat_trace
  use davit_assess_rules, only: n_checks, rule_check, new_check, check_passes, &
                                check_lowering_speed, check_impact_speed, check_fall_swl, &
                                check_brake_load, check_release_load, check_seat_dri
  use davit_assess_occupant, only: response_peaks
  use davit_io_config, only: parse_config
  use davit_ship_ship_model, only: ship_system_type
  use davit_run_ship_scene, only: build_ship_scene
  use davit_solve_rk4, only: rk4_type
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
  use davit_io_text, only: fmt_real, fmt_fixed
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_assess

contains

  function collect_assess() result(suite)
    type(suite_type) :: suite
    suite%name = "assess"
    suite%cases = [new_case("margins_lower_and_upper_limits", margins), &
                   new_case("dri_step_response_overshoot", dri_step), &
                   new_case("seat_axes_turn_with_the_boat", seat_axes), &
                   new_case("lowering_speed_drum_over_four_parts", lowering_speed), &
                   new_case("emergency_stop_snatch_of_mass_on_spring", emergency_stop), &
                   new_case("impact_at_3p6_flagged", impact_speed), &
                   new_case("release_load_waterborne", release_load), &
                   new_case("solas_list_trim_equilibrium_bem_ship", list_trim), &
                   new_case("diagnostic_numbers", numbers)]
  end function collect_assess

  !> Lower limit: 0.175 against 0.811 fails by (0.175 - 0.811)/0.811; upper limit: 3.6
  !> against 3.5 fails by (3.5 - 3.6)/3.5; equal values pass.
  subroutine margins(state)
    type(case_state), intent(inout) :: state
    type(rule_check) :: c
    c = new_check(check_lowering_speed, 0.175_wp, 0.811_wp)
    call check(state, c%margin, (0.175_wp - 0.811_wp)/0.811_wp, "lower-limit margin", &
               rel_tol=1e-14_wp)
    call check_true(state, .not. check_passes(c), "too slow fails")
    c = new_check(check_impact_speed, 3.6_wp, 3.5_wp)
    call check(state, c%margin, -0.1_wp/3.5_wp, "upper-limit margin", rel_tol=1e-12_wp)
    call check_true(state, .not. check_passes(c), "too fast fails")
    call check_true(state, check_passes(new_check(check_impact_speed, 3.5_wp, 3.5_wp)), &
                    "at the limit passes")
  end subroutine margins

  !> A step of seat acceleration a0 from rest: the spine model overshoots to
  !> DRI = (a0/g)(1 + exp(-zeta pi/sqrt(1 - zeta^2))) (1.486 a0/g at zeta = 0.224), to
  !> 2 a0/g undamped; a slow ramp is followed quasi-statically, DRI -> a/g.
  subroutine dri_step(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: dt = 1.0e-3_wp, w = 52.9_wp, zeta = 0.224_wp, a0 = 5.0_wp*gravity
    real(wp) :: a(2000), peaks(2)
    integer :: k
    a = a0
    a(1) = 0.0_wp
    peaks = response_peaks(a, dt, w, zeta)
    call check(state, peaks(1), 5.0_wp*(1.0_wp + exp(-zeta*pi/sqrt(1.0_wp - zeta**2))), &
               "damped overshoot", rel_tol=2e-3_wp)
    call note(state, "DRI of a 5 g step", peaks(1))
    peaks = response_peaks(a, dt, w, 0.0_wp)
    call check(state, peaks(1), 10.0_wp, "undamped: twice the step", rel_tol=2e-3_wp)
    a = [(a0*min(1.0_wp, k*dt/1.0_wp), k = 1, 2000)]
    peaks = response_peaks(a, dt, w, zeta)
    ! a ramp over 1 s is followed with a lag and an overshoot at its end of order
    ! (da/dt)/(omega a) = 1/52.9 = 2 %
    call check(state, peaks(1), 5.0_wp, "slow ramp: quasi-static", rel_tol=0.02_wp)
    call check(state, peaks(2), 0.0_wp, "no rebound below zero", abs_tol=1e-6_wp)
  end subroutine dri_step

  !> A seat 2 m off the axis of a boat yawing at 1 rev/s: in the boat's axes its
  !> centripetal acceleration is fixed, -omega^2 r along the radius (boat x), 0 across.
  subroutine seat_axes(state)
    type(case_state), intent(inout) :: state
    type(seat_trace) :: tr
    real(wp), parameter :: w = 2.0_wp*pi, r = 2.0_wp
    real(wp), allocatable :: a(:, :)
    real(wp) :: t
    integer :: k
    do k = 0, 3000
      t = k*1.0e-3_wp
      call tr%add(t, w*r*[-sin(w*t), cos(w*t), 0.0_wp], yaw(w*t))
    end do
    a = tr%body_filtered()
    call check(state, sum(a(1, 1000:2000))/1001.0_wp, -w**2*r, "radial (boat x)", &
               rel_tol=2e-3_wp)
    call check(state, maxval(abs(a(2:3, 1000:2000))), 0.0_wp, "across (boat y, z)", &
               abs_tol=0.05_wp*w**2*r)
  end subroutine seat_axes

  pure function yaw(psi) result(c)
    real(wp), intent(in) :: psi
    real(wp) :: c(3, 3)
    c = reshape([cos(psi), sin(psi), 0.0_wp, -sin(psi), cos(psi), 0.0_wp, 0.0_wp, 0.0_wp, &
                 1.0_wp], [3, 3])
  end function yaw

  !> The log of the calm lowering deck (reeving A: 4 parts, drum 0.7 m/s after 1 s) with
  !> `extra` deck text, run to t_end.
  subroutine lowering_run(extra, rig_extra, log, sys, cfg)
    character(len=*), intent(in) :: extra, rig_extra
    type(launch_log), intent(out) :: log
    type(system_type), intent(out) :: sys
    type(config_type), intent(out) :: cfg
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    cfg = deck_config("&simulation scene = 'lowering', dt = 1.0e-3, output_interval = "// &
                      "0.1 "//extra//" / &wind speed = 0.0 / &sea wave_type = 'calm' / "// &
                      "&rigging blocks = 'quasi_static'"//rig_extra//" /")
    y = new_test_system(sys, cfg)
    log = new_launch_log(cfg, sys)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, log)
  end subroutine lowering_run

  !> Rope kinematics: the boat comes down at 0.7/4 = 0.175 m/s (0.14 % faster: the falls
  !> lean in by a, half the heads' 0.32 m spacing over ~3 m, so the blocks drop by the
  !> paid-out length over cos a); H = 20.55 m, the heads' height above the still water of
  !> the ship at rest: limit 0.4 + 0.02 H = 0.811 m/s.
  subroutine lowering_speed(state)
    type(case_state), intent(inout) :: state
    type(launch_log) :: log
    type(system_type) :: sys
    type(config_type) :: cfg
    type(rule_check) :: c(n_checks)
    call lowering_run(", t_end = 12.0", "", log, sys, cfg)
    c = log%checks()
    call check(state, c(check_lowering_speed)%value, 0.7_wp/4.0_wp, "speed = drum / 4", &
               rel_tol=3e-3_wp)
    call check(state, c(check_lowering_speed)%limit, 0.4_wp + 0.02_wp*20.55_wp, &
               "limit 0.4 + 0.02 H", rel_tol=1e-9_wp)
    call check_true(state, .not. check_passes(c(check_lowering_speed)), "0.175 m/s fails")
    ! The falls' SWL from a published breaking load, not the code's formula: EN 12385-4
    ! tabulates 279 kN for a 20 mm 6x36WS-IWRC rope of grade 1960 (the deck's defaults);
    ! the table is rounded to the kN. LSA Code 6.1.1: SWL = MBL/6.
    call check(state, cfg%rigging%wire_diameter, 0.02_wp, "20 mm wire (deck default)", &
               abs_tol=1e-12_wp)
    call check(state, c(check_fall_swl)%limit, 279.0e3_wp/6.0_wp, "SWL = 279 kN/6", &
               rel_tol=2e-3_wp)
  end subroutine lowering_speed

  !> The drum stopped from full speed over T = 0.02 s: the boat (mass M on the falls and
  !> slings, bounce omega = sqrt(k/M), quasi-static blocks) is decelerated at a0 = v/T from
  !> v = 0.175 m/s. Mass on a spring whose support decelerates uniformly: past the ramp
  !> (omega T < pi) the spring force swings by M a0 2 sin(omega T/2) about the static load;
  !> shared by the 4 parts of the falls, each segment's peak is the load before the stop plus
  !> a quarter of it (light damping: ~2 % lower).
  subroutine emergency_stop(state)
    type(case_state), intent(inout) :: state
    type(launch_log) :: log
    type(system_type) :: sys
    type(config_type) :: cfg
    type(rule_check) :: c(n_checks)
    real(wp) :: omega, snatch, before
    call lowering_run(", t_end = 10.3", ", stop_time = 8.0, brake_time = 0.02", log, sys, &
                      cfg)
    c = log%checks()
    omega = bounce_omega(cfg, 8.0_wp)
    snatch = 2.0_wp*cfg%boat%mass*(0.175_wp/0.02_wp)*sin(0.5_wp*omega*0.02_wp)
    before = c(check_brake_load)%limit/1.1_wp
    call note(state, "bounce omega [rad/s]", omega)
    call note(state, "fall load before the stop [N]", before)
    call note(state, "peak after the stop [N]", c(check_brake_load)%value)
    call check(state, c(check_brake_load)%value - before, 0.25_wp*snatch, &
               "segment snatch = (2 M a0 sin(omega T/2))/4", rel_tol=0.06_wp)
    call check(state, before, 0.25_wp*(cfg%boat%mass + 2.0_wp*cfg%rigging%block_mass)* &
               gravity, "load before = weight of boat and blocks / 4 parts", rel_tol=0.02_wp)
    call check_true(state, .not. check_passes(c(check_brake_load)), "snatch > 1.1 fails")
  end subroutine emergency_stop

  !> The boat's bounce on the two slings (EA/l_s each, in parallel) in series with the
  !> falls through the blocks, (4 cos a)^2 EA/L0 (the rigging suite's static_blocks_modes),
  !> at the stop: the cable paid out by 0.7 (t_stop - ramp/2) beyond its start length.
  real(wp) function bounce_omega(cfg, t_stop) result(omega)
    type(config_type), intent(in) :: cfg
    real(wp), intent(in) :: t_stop
    type(system_type) :: sys
    real(wp), allocatable :: y(:)
    real(wp) :: ea, k_s, k_c, l0, br(3, 2), drop, cosa, paid
    y = new_test_system(sys, cfg)
    paid = cfg%rigging%drum_speed*(t_stop - 0.5_wp*cfg%rigging%ramp_time)
    br = sys%par%rig%block_positions(y(13:))
    drop = br(3, 1) - cfg%rigging%head_fore(3) + 0.25_wp*paid
    cosa = drop/hypot(drop, 0.5_wp*cfg%rigging%head_spacing)
    ea = sys%par%rig%cables(1)%ea
    l0 = sys%par%rig%unstretched_length(y(13:), 1) + paid
    k_s = ea/cfg%rigging%sling_length
    k_c = (2.0_wp*cosa)**2*ea/l0
    omega = sqrt(1.0_wp/(1.0_wp/(2.0_wp*k_s) + 1.0_wp/(4.0_wp*k_c))/cfg%boat%mass)
  end function bounce_omega

  !> The fender test thrown at 3.6 m/s: one impact at 3.6 m/s, beyond LSA's 3.5 m/s.
  subroutine impact_speed(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    type(launch_log) :: log
    type(rule_check) :: c(n_checks)
    real(wp), allocatable :: y(:)
    cfg = deck_config("&simulation t_end = 0.3, dt = 1.0e-4, output_interval = 0.01 / "// &
                      "&boat position = 0.0, 11.801, -15.0, velocity = 0.0, -3.6, 0.0 / "// &
                      "&slings anchor_fore = 4.6, 11.801, -46.55, anchor_aft = -4.6, "// &
                      "11.801, -46.55, length = 29.9801 / &wind speed = 0.0 / "// &
                      "&contact law = 'rubber_fender', side_y = 10.4 /")
    y = new_test_system(sys, cfg)
    log = new_launch_log(cfg, sys)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, log)
    c = log%checks()
    call check(state, c(check_impact_speed)%value, 3.6_wp, "impact speed", rel_tol=2e-3_wp)
    call check(state, c(check_impact_speed)%limit, 3.5_wp, "LSA 3.5 m/s", rel_tol=1e-14_wp)
    call check_true(state, .not. check_passes(c(check_impact_speed)), "3.6 m/s flagged")
  end subroutine impact_speed

  !> A calm lowering to the water: the hooks let go once the boat floats (hook load below
  !> 1 % of the weight for 1 s, review G24), so the load at release is under 1 % of the
  !> weight, against 1.1 x the weight.
  subroutine release_load(state)
    type(case_state), intent(inout) :: state
    type(launch_log) :: log
    type(system_type) :: sys
    type(config_type) :: cfg
    type(rule_check) :: c(n_checks)
    call lowering_run(", t_end = 90.0, integrator = 'dopri5', rtol = 1e-6", "", log, sys, &
                      cfg)
    c = log%checks()
    call note(state, "hook load at release [N]", c(check_release_load)%value)
    call check(state, c(check_release_load)%limit, 1.1_wp*cfg%boat%mass*gravity, &
               "limit 1.1 M g", rel_tol=1e-14_wp)
    call check_true(state, c(check_release_load)%value >= 0.0_wp .and. &
                    c(check_release_load)%value < 0.01_wp*cfg%boat%mass*gravity, &
                    "released afloat: load < 1 % of the weight")
    call check(state, c(check_seat_dri)%value, 0.0_wp, "calm lowering: DRI ~ 0", &
               abs_tol=0.5_wp)
    ! the calm lowering stays upright; a boat tilted past 90 deg is reported overturned
    call check(state, log%tilt, 0.0_wp, "upright (rad)", abs_tol=1e-3_wp)
    call check_true(state, index(log%outcome(sys), "released at t = ") == 1, "released")
    log%tilt = 1.7_wp
    call check_true(state, index(log%outcome(sys), "overturned on its falls (tilted 97 "// &
                    "deg") == 1, "overturned: "//log%outcome(sys))
  end subroutine release_load

  !> SOLAS III/16 / LSA 6.1.1.1's launch envelope on the BEM ship: listed 20 deg to
  !> starboard and trimmed 10 deg by the head, in calm water and still air, the ship is in
  !> static equilibrium (the list and trim are those of the heeling and trimming moments
  !> the deck stands for): after 200 s nothing has moved.
  subroutine list_trim(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:), y0(:)
    real(wp) :: t
    integer :: i
    call parse_config("ship.nml", "&simulation scene = 'ship' / &ship model = 'bem', "// &
                      "list_deg = 20, trim_deg = -10 / &wind speed = 0 / &sea wave_type "// &
                      "= 'calm' /", cfg, error)
    if (.not. allocated(error)) call build_ship_scene(cfg, ship, y, error)
    call check_true(state, .not. allocated(error), "BEM ship built")
    if (allocated(error)) return
    y0 = y
    call rk%init(size(y))
    t = 0.0_wp
    do i = 1, 10000
      call rk%step(ship, t, y, 0.02_wp)
      call ship%after_step(t, y)
    end do
    call check(state, y(1), 20.0_wp*pi/180.0_wp, "list held", abs_tol=1e-9_wp)
    call check(state, y(2), -10.0_wp*pi/180.0_wp, "trim held", abs_tol=1e-9_wp)
    call check(state, maxval(abs(y(3:6) - y0(3:6))), 0.0_wp, "no yaw, drift or sinkage", &
               abs_tol=1e-9_wp)
    call check(state, maxval(abs(y(7:12))), 0.0_wp, "at rest", abs_tol=1e-9_wp)
  end subroutine list_trim

  !> A diverged state is named as such in diagnostics ("boat roll = NaN", was "= e0"), and
  !> the report's fixed-point numbers keep their leading zero.
  subroutine numbers(state)
    type(case_state), intent(inout) :: state
    real(wp) :: nan, inf
    nan = ieee_value(nan, ieee_quiet_nan)
    inf = ieee_value(inf, ieee_positive_inf)
    call check_true(state, fmt_real(nan) == "NaN", "NaN: "//fmt_real(nan))
    call check_true(state, fmt_real(inf) == "Inf", "Inf: "//fmt_real(inf))
    call check_true(state, fmt_real(-inf) == "-Inf", "-Inf: "//fmt_real(-inf))
    call check_true(state, fmt_fixed(0.0812_wp, 4) == "0.0812", fmt_fixed(0.0812_wp, 4))
    call check_true(state, fmt_fixed(-0.5_wp, 1) == "-0.5", fmt_fixed(-0.5_wp, 1))
    call check_true(state, fmt_fixed(22.46_wp, 1) == "22.5", fmt_fixed(22.46_wp, 1))
  end subroutine numbers

end module test_assess
