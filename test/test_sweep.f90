!> Sweeps (issue "7. Sweeps"): case seeds (SplitMix64 reference vectors), the Cartesian
!> product and the level presets, the clearance geometry (the boat still hangs in
!> equilibrium), and the in-run metrics on cases whose answer is known (a fender impact, the
!> end of the lowering).
module test_sweep
  use davit_kinds, only: wp, i8, pi, gravity
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, deck_config, system_hertz_peak
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use davit_run_launch_log, only: new_launch_log
  use davit_sweep_keys, only: sweep_config, parse_sweep
  use davit_sweep_cases, only: sweep_case, build_cases, case_config, initial_clearance, &
                               splitmix64, case_seed
  use davit_sweep_metrics, only: launch_metrics, case_result
  use davit_sweep_driver, only: longest_first
  use davit_sweep_shards, only: shard_spec, parse_shard, shard_mask
  use davit_sweep_row_codec, only: encode_row, decode_row
  use davit_sweep_progress, only: fmt_duration
  use davit_sweep_result_columns, only: result_columns, case_columns, real_fields, set_reals, &
                                        case_fields, set_case_fields
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_negative_inf
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_sweep

  !> The III.B launch deck the sweep decks start from (tests run in the project root).
  character(len=*), parameter :: sweep_file = "input/test_sweep.nml"

contains

  function collect_sweep() result(suite)
    type(suite_type) :: suite
    suite%name = "sweep"
    suite%cases = [new_case("splitmix64_reference_vectors", splitmix_vectors), &
                   new_case("cartesian_product_and_level_presets", product_and_presets), &
                   new_case("clearance_in_boat_widths_hangs_in_equilibrium", clearances), &
                   new_case("metrics_fender_impact_hertz", impact_metrics), &
                   new_case("metrics_window_ends_at_release", release_window), &
                   new_case("dearest_cases_first", dearest_first), &
                   new_case("shards_deal_the_dearest_order_round_robin", shards_round_robin), &
                   new_case("shard_argument_k_of_n", shard_argument), &
                   new_case("row_message_round_trip_bitwise", row_round_trip), &
                   new_case("row_message_refuses_wrong_length", row_wrong_length), &
                   new_case("summary_columns_name_their_fields", column_names), &
                   new_case("progress_durations_in_hours_minutes_seconds", durations)]
  end function collect_sweep

  function sweep_from_text(text) result(s)
    character(len=*), intent(in) :: text
    type(sweep_config) :: s
    type(error_type), allocatable :: error
    call parse_sweep(sweep_file, text, s, error)
    if (allocated(error)) error stop "test sweep deck rejected: "//error%message
  end function sweep_from_text


  !> SplitMix64 started at 1234567: the first five outputs of Vigna's reference
  !> implementation (as signed 64-bit patterns); a case seed is the top 31 bits.
  subroutine splitmix_vectors(state)
    type(case_state), intent(inout) :: state
    integer(i8), parameter :: expected(5) = [6457827717110365317_i8, 3203168211198807973_i8, &
                                             -8629252141511181193_i8, 4593380528125082431_i8, &
                                             -2037821214251327795_i8]
    integer :: n
    do n = 1, 5
      call check_true(state, splitmix64(1234567_i8, int(n, i8)) == expected(n), &
                      "SplitMix64(1234567) output "//achar(48 + n))
    end do
    call check_true(state, case_seed(1234567, 3) == int(ishft(expected(3), -33)), &
                    "case seed = top 31 bits")
    call check_true(state, all([(case_seed(7, n), n = 1, 50)] >= 0), "seeds in 0..2^31-1")
  end subroutine splitmix_vectors

  !> 2 levels x 3 angles x 2 clearances x 3 realisations = 36 cases, each combination once,
  !> realisations fastest; level presets (review G18, G19): Level 4 H 2.5 m, T_p 10.06 s,
  !> wind 8 m/s along the waves; Level 5 H 4 m, 12.72 s, 10 m/s; the base deck's ramp of 2
  !> periods follows the period.
  subroutine product_and_presets(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    type(config_type) :: cfg
    integer :: i, j, n
    s = sweep_from_text("&sweep base_deck = 'iiib_level5_090.nml', levels = 4, 5, "// &
                        "angles_deg = 45, 90, 135, clearances_b = 1.0, 2.0, "// &
                        "realisations = 3 /")
    call build_cases(s, 1.5_wp, cases)
    call check_true(state, size(cases) == 36, "36 cases")
    call check_true(state, all(cases%index == [(i, i = 1, 36)]), "indices 1..36")
    call check_true(state, all(cases%realisation == [((j, j = 1, 3), i = 1, 12)]), &
                    "realisations vary fastest")
    n = 0
    do i = 1, 36
      do j = i + 1, 36
        if (cases(i)%level == cases(j)%level .and. cases(i)%angle_deg == cases(j)%angle_deg &
            .and. cases(i)%clearance_b == cases(j)%clearance_b .and. &
            cases(i)%realisation == cases(j)%realisation) n = n + 1
      end do
    end do
    call check_true(state, n == 0, "every combination once")
    call check_true(state, size(unique_seeds(cases%seed)) == 36, "36 distinct seeds")
    associate (c4 => cases(1), c5 => cases(36))
      call check(state, c4%wave_height, 2.5_wp, "Level 4 H", abs_tol=1e-12_wp)
      call check(state, c4%wave_period, 10.06_wp, "Level 4 T_p (G18)", abs_tol=0.01_wp)
      call check(state, c4%wind_speed, 8.0_wp, "Level 4 wind", abs_tol=1e-12_wp)
      call check(state, c5%wave_height, 4.0_wp, "Level 5 H", abs_tol=1e-12_wp)
      call check(state, c5%wave_period, 12.72_wp, "Level 5 T_p (G18)", abs_tol=0.01_wp)
      call check(state, c5%wind_speed, 10.0_wp, "Level 5 wind", abs_tol=1e-12_wp)
      call case_config(s, c4, 1.5_wp, cfg)
      call check(state, cfg%sea%direction, 45.0_wp*pi/180.0_wp, "encounter angle", &
                 abs_tol=1e-15_wp)
      call check(state, cfg%wind%direction, cfg%sea%direction, "wind along the waves", &
                 abs_tol=1e-15_wp)
      call check(state, cfg%sea%ramp_time, 2.0_wp*c4%wave_period, "ramp 2 periods", &
                 rel_tol=1e-14_wp)
      call check_true(state, cfg%simulation%seed == c4%seed, "case seed in the run")
      call check_true(state, cfg%sea%wave_type == "stokes2", "base deck wave type")
      call check_true(state, cfg%simulation%integrator == "rk4" .and. &
                      cfg%simulation%dt == 1.0e-3_wp, "base deck integrator and step")
    end associate
    call check_true(state, any(abs(cases(1:3)%phase_deg - cases(2)%phase_deg) > 1.0_wp), &
                    "realisations draw different phases")
    ! the numerics of every case from the sweep deck (its own integrator, substeps, step)
    s = sweep_from_text("&sweep base_deck = 'iiib_level5_090.nml', integrator = 'mri2', "// &
                        "substeps = 5, dts = 0.01 /")
    call build_cases(s, 1.5_wp, cases)
    call case_config(s, cases(1), 1.5_wp, cfg)
    call check_true(state, cfg%simulation%integrator == "mri2" .and. &
                    cfg%simulation%substeps == 5 .and. cfg%simulation%dt == 0.01_wp, &
                    "sweep deck's integrator, substeps and dts in the run")
  end subroutine product_and_presets

  !> Cases run dearest first (irregular seas: 1300 components; a smaller dt): a sweep of
  !> 2 wave types x 2 dts x 2 realisations is taken as the irregular cases at 1e-4 s, then
  !> the irregular at 1e-3 s, then the regular ones at 1e-4 s and 1e-3 s, each group in
  !> its index order (stable).
  subroutine dearest_first(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    integer, allocatable :: order(:)
    integer :: i
    s = sweep_from_text("&sweep base_deck = 'iiib_level5_090.nml', "// &
                        "wave_types = 'stokes2', 'irregular', dts = 1.0e-3, 1.0e-4, "// &
                        "realisations = 2 /")
    call build_cases(s, 1.5_wp, cases)
    order = [(i, i = 1, size(cases))]
    call longest_first(s, cases, order)
    call check_true(state, size(cases) == 8, "8 cases")
    call check_true(state, all(cases(order(1:2))%wave_type == 3) .and. &
                    all(cases(order(1:2))%dt == 1.0e-4_wp), "irregular at 1e-4 s first")
    call check_true(state, all(cases(order(3:4))%wave_type == 3) .and. &
                    all(cases(order(3:4))%dt == 1.0e-3_wp), "then irregular at 1e-3 s")
    call check_true(state, all(cases(order(5:6))%wave_type /= 3) .and. &
                    all(cases(order(5:6))%dt == 1.0e-4_wp), "then regular at 1e-4 s")
    call check_true(state, order(1) < order(2) .and. order(3) < order(4) .and. &
                    order(5) < order(6) .and. order(7) < order(8), "index order within groups")
  end subroutine dearest_first

  !> The deck of dearest_first (4 irregular cases, then 4 regular) in 4 shards: each shard
  !> gets one irregular and one regular case (balanced cost); in 3 shards, 3, 3 and 2 cases,
  !> shard 1 holding the dearest. Every case lies in exactly one shard.
  subroutine shards_round_robin(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    logical :: mine(8, 4)
    integer :: k, n, order(8)
    s = sweep_from_text("&sweep base_deck = 'iiib_level5_090.nml', "// &
                        "wave_types = 'stokes2', 'irregular', dts = 1.0e-3, 1.0e-4, "// &
                        "realisations = 2 /")
    call build_cases(s, 1.5_wp, cases)
    order = [(k, k = 1, 8)]
    call longest_first(s, cases, order)
    do n = 3, 4
      mine = .false.
      do k = 1, n
        mine(:, k) = shard_mask(s, cases, shard_spec(k, n))
      end do
      call check_true(state, all(count(mine(:, 1:n), dim=2) == 1), "a partition")
      if (n == 3) then
        call check_true(state, all(count(mine(:, 1:3), dim=1) == [3, 3, 2]), "3, 3, 2 cases")
        call check_true(state, mine(order(1), 1) .and. mine(order(4), 1) .and. &
                        mine(order(7), 1), "shard 1 of 3: dearest cases 1, 4, 7")
      else
        do k = 1, 4
          call check_true(state, count(mine(:, k) .and. cases%wave_type == 3) == 1 .and. &
                          count(mine(:, k)) == 2, "one irregular, one regular case")
        end do
      end if
    end do
    call check_true(state, all(shard_mask(s, cases, shard_spec())), "whole sweep: all")
  end subroutine shards_round_robin

  !> --shard K/N: 1 <= K <= N, digits only.
  subroutine shard_argument(state)
    type(case_state), intent(inout) :: state
    type(shard_spec) :: shard
    type(error_type), allocatable :: error
    character(len=6), parameter :: bad(7) = [character(len=6) :: "0/3", "4/3", "x", "1/0", &
                                             "/3", "1/3/5", "-1/3"]
    integer :: k
    call parse_shard("2/8", shard, error)
    call check_true(state, .not. allocated(error) .and. shard%index == 2 .and. &
                    shard%count == 8, "2/8")
    do k = 1, size(bad)
      call parse_shard(trim(bad(k)), shard, error)
      call check_true(state, allocated(error), "refused: "//trim(bad(k)))
    end do
  end subroutine shard_argument

  !> The progress line's times: 7500 s = 2 h 5 min (the seconds dropped), 201 s =
  !> 3 min 21 s, 42.4 s rounds to 42 s, 59.6 s to 60 s = 1 min 0 s, a negative time is 0 s.
  subroutine durations(state)
    type(case_state), intent(inout) :: state
    call check_true(state, fmt_duration(7500.0_wp) == "2 h 5 min", "7500 s")
    call check_true(state, fmt_duration(201.0_wp) == "3 min 21 s", "201 s")
    call check_true(state, fmt_duration(42.4_wp) == "42 s", "42.4 s")
    call check_true(state, fmt_duration(59.6_wp) == "1 min 0 s", "59.6 s")
    call check_true(state, fmt_duration(-3.0_wp) == "0 s", "-3 s")
  end subroutine durations

  pure function unique_seeds(seeds) result(u)
    integer, intent(in) :: seeds(:)
    integer, allocatable :: u(:)
    integer :: i
    u = [integer ::]
    do i = 1, size(seeds)
      if (.not. any(u == seeds(i))) u = [u, seeds(i)]
    end do
  end function unique_seeds

  !> Clearances of 1, 1.5 and 2 boat widths (G3: 2.8, 4.2, 5.6 m) measured by the model
  !> itself at t = 0; boat and davit heads moved together, so on the 'lowering' scene in calm
  !> air with the drum held the boat stays in its static equilibrium (a boat moved without
  !> its heads would swing on inclined falls).
  subroutine clearances(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    type(config_type) :: cfg
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    real(wp) :: clearance0, clearance, speed
    integer :: i
    s = sweep_from_text("&sweep base_deck = 'lowering.nml', clearances_b = 1.0, 1.5, 2.0 /")
    s%base%rigging%drum_speed = 0.0_wp
    s%base%simulation%t_end = 1.0_wp
    s%base%simulation%output_interval = 0.01_wp
    call initial_clearance(s%base, clearance0, error)
    call check(state, clearance0, 1.4_wp, "base deck: 13.3 - 1.4 - 10.5 m (F12)", abs_tol=1e-12_wp)
    call build_cases(s, clearance0, cases)
    do i = 1, size(cases)
      call case_config(s, cases(i), clearance0, cfg)
      call initial_clearance(cfg, clearance, error)
      call check(state, clearance, cases(i)%clearance_b*2.8_wp, "clearance = c B", &
                 abs_tol=1e-12_wp)
    end do
    y = new_test_system(sys, cfg)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error)
    speed = maxval(norm2(rec%velocity(:, 1:rec%n), 1))
    call note(state, "largest boat speed over 1 s at 2 B (m/s)", speed)
    call check(state, speed, 0.0_wp, "at rest at 2 B", abs_tol=1e-6_wp)
  end subroutine clearances

  !> A free boat at 1 m/s onto the ship's side, both fenders at once, far above the water,
  !> without air loads: one impact; the deepest indentation and the peak horizontal
  !> acceleration are those of the Hertz impact of m/2 per fender (delta_m, 2 f_m/m); the
  !> vertical acceleration is that of free fall, g.
  subroutine impact_metrics(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(launch_metrics) :: metrics
    type(run_summary) :: summary
    type(case_result) :: r
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    real(wp) :: dm, fm
    cfg = deck_config("&simulation t_end = 0.03, dt = 2.0e-6, output_interval = 0.001 / "// &
                      "&slings attached = .false. / &wind speed = 0.0 / "// &
                      "&contact law = 'hertz_elastoplastic', fender_z = 0.0, 0.0 / "// &
                      "&boat position = 0.0, 11.91, -100.0, velocity = 0.0, -1.0, 0.0, "// &
                      "wind_drag_coefficient = 0.0, lift_coefficient = 0.0 /")
    y = new_test_system(sys, cfg)
    metrics%log = new_launch_log(cfg, sys)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, metrics)
    r = metrics%result(sys)
    call system_hertz_peak(sys, 0.5_wp*cfg%boat%mass, 1.0_wp, dm, fm)
    call note(state, "peak horizontal acceleration (m/s^2)", r%peak_horizontal_acceleration)
    call note(state, "min clearance (m)", r%min_clearance)
    call check_true(state, .not. allocated(run_error), "run completes")
    call check_true(state, r%collided == 1 .and. r%impacts == 1, "one impact")
    call check(state, r%first_contact_time, 0.01_wp, "first contact after 0.01 m at 1 m/s", &
               abs_tol=2.0_wp*cfg%simulation%dt)
    call check(state, r%min_clearance, -dm, "deepest indentation = Hertz delta_m", &
               rel_tol=1e-3_wp)
    call check(state, r%peak_horizontal_acceleration, 2.0_wp*fm/cfg%boat%mass, &
               "peak horizontal acceleration = 2 f_m/m", rel_tol=1e-3_wp)
    call check(state, r%peak_vertical_acceleration, gravity, "free fall", rel_tol=1e-9_wp)
    call check(state, r%peak_segment_tension, 0.0_wp, "no slings", abs_tol=0.0_wp)
    ! The launch log's events: both fenders hit at once at the boat's 1 m/s, each with the
    ! Hertz peak of half the boat's mass; nothing reaches the 3.5 m/s limit.
    associate (ev => metrics%log%impacts)
      call check_true(state, ev%n == 2, "two impact events, one per fender")
      call check(state, ev%events(1)%speed, 1.0_wp, "impact speed", rel_tol=1e-3_wp)
      call check(state, ev%events(2)%peak_force, fm, "event peak force = Hertz f_m", &
                 rel_tol=1e-3_wp)
      call check(state, ev%events(1)%time, 0.01_wp, "event onset", &
                 abs_tol=2.0_wp*cfg%simulation%dt)
    end associate
    call check(state, r%max_impact_speed, 1.0_wp, "fastest impact", rel_tol=1e-3_wp)
    call check(state, r%impact_speed_exceeded_time, -1.0_wp, "3.5 m/s not exceeded", &
               abs_tol=0.0_wp)
  end subroutine impact_metrics

  !> The lowering deck with the boat starting 2 m above calm water (heads, lead sheave and
  !> drum raised with it): the lowering window ends, and the run stops, when the hooks open,
  !> 1 s (the waterborne hold, G24) after the boat became waterborne.
  subroutine release_window(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(launch_metrics) :: metrics
    type(run_summary) :: summary
    type(case_result) :: r
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    cfg = deck_config("&simulation scene = 'lowering', t_end = 30.0, dt = 2.0e-4, "// &
                      "output_interval = 0.02 / &boat position = 0.0, 13.3, -2.0, "// &
                      "zeta = 0.1, 0.1, 0.1 / &wind speed = 0.0 / &sea wave_type = 'calm' / "// &
                      "&rigging head_fore = 4.6, 13.3, -7.55, head_aft = -4.6, 13.3, -7.55, "// &
                      "lead_sheave = 0.0, 11.5, -8.0, drum_position = 0.0, 8.0, -3.5 /")
    y = new_test_system(sys, cfg)
    metrics%log = new_launch_log(cfg, sys)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, metrics)
    r = metrics%result(sys)
    call note(state, "waterborne (s)", r%waterborne_time)
    call note(state, "end of the lowering window (s)", r%end_time)
    call check_true(state, r%waterborne_time > 0.0_wp, "waterborne")
    call check(state, r%end_time, sys%hist%release_time, "window ends at release", abs_tol=0.0_wp)
    call check(state, r%end_time, r%waterborne_time + 1.0_wp, "release 1 s after waterborne", &
               abs_tol=2.0_wp*cfg%simulation%dt)
    call check(state, rec%time(rec%n), r%end_time, "run stopped there", abs_tol=0.0_wp)
    call check_true(state, summary%steps == nint(r%end_time/cfg%simulation%dt), &
                    "no step after the release")
  end subroutine release_window

  !> A row through the MPI message bytes comes back bit for bit: NaN payloads, -0, an
  !> infinity, extreme integers, text with blanks and an unallocated message.
  subroutine row_round_trip(state)
    type(case_state), intent(inout) :: state
    type(case_result) :: row, back
    type(error_type), allocatable :: error
    integer :: c
    row%status = 2
    row%min_clearance = -0.0_wp
    row%peak_horizontal_acceleration = ieee_value(1.0_wp, ieee_quiet_nan)
    row%peak_vertical_acceleration = ieee_value(1.0_wp, ieee_negative_inf)
    row%peak_segment_tension = 1.0_wp/3.0_wp
    row%impact_speed_exceeded_time = tiny(1.0_wp)
    row%wall_time = huge(1.0_wp)
    row%outcome = "  run diverged at t = 0.5 s: x  "
    row%collided = 1
    row%impacts = -7
    row%steps = huge(1_i8)
    row%rhs_evaluations = -huge(1_i8)
    call decode_row(encode_row(123456, row), c, back, error)
    call check_true(state, .not. allocated(error), "decoded")
    call check_true(state, c == 123456, "case index")
    call check_true(state, all(transfer(reals_of(back), [0_i8]) == &
                               transfer(reals_of(row), [0_i8])), "reals bit for bit")
    call check_true(state, back%status == 2 .and. back%collided == 1 .and. &
                    back%impacts == -7, "integers")
    call check_true(state, back%steps == huge(1_i8) .and. &
                    back%rhs_evaluations == -huge(1_i8), "64-bit counters")
    call check_true(state, .not. allocated(back%message), "message stays unallocated")
    call check_true(state, back%outcome == row%outcome .and. &
                    len(back%outcome) == len(row%outcome), "outcome with its blanks")
  end subroutine row_round_trip

  !> Bytes cut short or with a byte too many are an error, not a row.
  subroutine row_wrong_length(state)
    type(case_state), intent(inout) :: state
    type(case_result) :: row, back
    type(error_type), allocatable :: error
    character(len=:), allocatable :: buf
    integer :: c
    row%message = "abc"
    buf = encode_row(5, row)
    call decode_row(buf(:len(buf) - 1), c, back, error)
    call check_true(state, allocated(error), "one byte short")
    call decode_row(buf//"x", c, back, error)
    call check_true(state, allocated(error), "one byte too many")
    call decode_row(buf(:10), c, back, error)
    call check_true(state, allocated(error), "header cut")
  end subroutine row_wrong_length

  !> Each summary column's name is the field its values come from and go back to: a row
  !> (and a case) whose fields hold their own declaration index is listed by real_fields
  !> (case_fields) as 1, 2, 3, ..., under the names written out here from the type's
  !> declaration, and set_reals (set_case_fields) puts every value back into its field.
  subroutine column_names(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: names(15) = [character(len=28) :: "min_clearance", &
      "peak_horizontal_acceleration", "peak_vertical_acceleration", "peak_segment_tension", &
      "first_contact_time", "waterborne_time", "end_time", "wall_time", &
      "peak_sling_tension", "peak_fall_tension", "max_impact_speed", &
      "peak_seat_acceleration", "swl_exceeded_time", "mbl_exceeded_time", &
      "impact_speed_exceeded_time"]
    character(len=*), parameter :: case_names(7) = [character(len=11) :: "wind_speed", &
      "wave_height", "wave_period", "angle_deg", "clearance_b", "dt", "phase_deg"]
    type(case_result) :: row, back
    type(sweep_case) :: c, c_back
    real(wp), allocatable :: x(:)
    integer :: k, nc
    row = case_result(min_clearance=1.0_wp, peak_horizontal_acceleration=2.0_wp, &
                      peak_vertical_acceleration=3.0_wp, peak_segment_tension=4.0_wp, &
                      first_contact_time=5.0_wp, waterborne_time=6.0_wp, end_time=7.0_wp, &
                      wall_time=8.0_wp, peak_sling_tension=9.0_wp, peak_fall_tension=10.0_wp, &
                      max_impact_speed=11.0_wp, peak_seat_acceleration=12.0_wp, &
                      swl_exceeded_time=13.0_wp, mbl_exceeded_time=14.0_wp, &
                      impact_speed_exceeded_time=15.0_wp)
    nc = size(row%check_value)
    row%check_value = [(100.0_wp + k, k = 1, nc)]
    row%check_limit = [(200.0_wp + k, k = 1, nc)]
    row%check_margin = [(300.0_wp + k, k = 1, nc)]
    x = real_fields(row)
    call check_true(state, all(x(1:15) == [(real(k, wp), k = 1, 15)]), "reals in order")
    call check_true(state, all(x(16:) == [row%check_value, row%check_limit, &
                                          row%check_margin]), "then the checks")
    do k = 1, 15
      call check_true(state, trim(result_columns(k)%name) == trim(names(k)), &
                      "result column "//trim(names(k)))
    end do
    call set_reals(back, x)
    call check_true(state, all(real_fields(back) == x), "set_reals puts each back")
    call check_true(state, back%wall_time == 8.0_wp .and. back%end_time == 7.0_wp .and. &
                    back%check_margin(nc) == 300.0_wp + nc, "into its own field")
    c = sweep_case(wind_speed=1.0_wp, wave_height=2.0_wp, wave_period=3.0_wp, &
                   angle_deg=4.0_wp, clearance_b=5.0_wp, dt=6.0_wp, phase_deg=7.0_wp)
    call check_true(state, all(case_fields(c) == [(real(k, wp), k = 1, 7)]), &
                    "case reals in order")
    do k = 1, 7
      call check_true(state, trim(case_columns(k)%name) == trim(case_names(k)), &
                      "case column "//trim(case_names(k)))
    end do
    call set_case_fields(c_back, case_fields(c))
    call check_true(state, c_back%dt == 6.0_wp .and. c_back%phase_deg == 7.0_wp .and. &
                    c_back%wind_speed == 1.0_wp, "set_case_fields puts each back")
  end subroutine column_names

  function reals_of(r) result(x)
    type(case_result), intent(in) :: r
    real(wp) :: x(15)
    x = [r%min_clearance, r%peak_horizontal_acceleration, r%peak_vertical_acceleration, &
         r%peak_segment_tension, r%first_contact_time, r%waterborne_time, r%end_time, &
         r%wall_time, r%peak_sling_tension, r%peak_fall_tension, r%max_impact_speed, &
         r%peak_seat_acceleration, r%swl_exceeded_time, r%mbl_exceeded_time, &
         r%impact_speed_exceeded_time]
  end function reals_of

end module test_sweep
