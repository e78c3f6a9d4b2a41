!> Run configuration: every deck key with its default (SI units), range and description.
!> config_type is plain data; nothing here knows about the integrator or the output file.
module davit_io_config
  use davit_kinds, only: wp, pi
  use davit_sea_spectrum, only: spectrum_peak_omega
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: nml_deck, read_deck, parse_deck, key_at
  use davit_io_deck_reader, only: deck_reader_type, key_doc, fmt_real
  use davit_io_rigging_keys, only: rigging_config, read_rigging
  use davit_io_ship_keys, only: ship_config, read_ship
  use davit_io_sea_keys, only: sea_grid_config, read_sea_grid
  use davit_io_limits_keys, only: limits_config, read_limits
  use davit_io_contact_keys, only: contact_config, read_contact
  use davit_io_boat_keys, only: boat_config, read_boat
  use davit_io_shared_keys, only: read_fore_aft, read_wire_rope, read_integrator
  implicit none
  private
  public :: config_type, simulation_config, boat_config, slings_config, sea_config
  public :: wind_config, ship_config, rao_config, contact_config, rigging_config
  public :: read_config, parse_config, document_keys
  public :: level_wave_height, level_wind_speed

  type :: simulation_config
    !> End time [s], time step [s], output interval [s], step limit in contact [s], slow-clock
    !> interval of the wave loads [s].
    real(wp) :: t_end, dt, output_interval, dt_contact, wave_update
    !> Time the run goes on after the hooks are released [s] (review G24).
    real(wp) :: after_release
    !> Integrator name; scene ('hanging_boat', 'lowering', 'launch', 'sea', 'ship'); how contact
    !> limits the step.
    character(len=:), allocatable :: integrator, scene, contact_approach
    !> Seed of the irregular sea's random phases.
    integer :: seed
    !> RK4 substeps of the fast part per macro step dt (integrator 'multirate', 'multirate2').
    integer :: substeps = 10
    !> Relative and absolute tolerances of the adaptive integrators.
    real(wp) :: rtol, atol
    !> Adaptive integrators without error control: one step of dt per macro step.
    logical :: fixed_step
    !> Memory the run may hold [GiB]; 0 = 80 % of physical memory (davit_run_budget).
    real(wp) :: max_memory = 0.0_wp
  end type simulation_config

  !> Sea state (paper eqs. 43-45, review §1.9, G18-G22). Angles are stored in radians.
  type :: sea_config
    !> Sea-state level (presets), spreading exponent s, number of frequencies and of directions.
    integer :: level, spreading_s, n_frequencies, n_directions
    !> Wave type ('calm', 'airy', 'stokes2', 'irregular') and the irregular sea's summation
    !> ('double', 'single_equal_energy', 'single_random').
    character(len=:), allocatable :: wave_type, summation
    !> Height [m], period [s], direction travelled towards [rad], phase [rad], spreading window
    !> [rad], lowest and highest frequency [rad/s].
    real(wp) :: height, period, direction, phase, spread_window, omega_min, omega_max
    !> Time over which the waves ramp up from calm [s].
    real(wp) :: ramp_time
    !> Where height and period came from ("deck", "level 4 preset", ...): printed and
    !> stored with the run's scenario (davit_run_scenario).
    character(len=:), allocatable :: height_source, period_source
    !> Jitter the frequencies within their bins; each direction draws its own frequency.
    logical :: jitter, independent_frequencies
    !> Wave probes' x and y (inertial) [m].
    real(wp), allocatable :: probes_x(:), probes_y(:)
    !> Precomputed-grid kinematics (&sea kinematics and the grid's keys).
    type(sea_grid_config) :: grid
  end type sea_config

  !> Response amplitude operators of the ship (`davit rao`).
  type :: rao_config
    !> Wave frequencies [rad/s] and headings relative to the ship [rad] of the RAO runs.
    real(wp), allocatable :: omegas(:), headings(:)
    !> Wave amplitude [m], settling time before measuring [s], time step [s].
    real(wp) :: amplitude, settle_time, dt
    !> Wave periods measured after settling.
    integer :: measure_periods
  end type rao_config

  !> Steady wind for the force models (eq. 15, 46); direction it blows towards [rad].
  type :: wind_config
    !> Wind speed [m/s] and the direction it blows towards [rad].
    real(wp) :: speed, direction
    !> Where speed and direction came from ("deck", "level 5 preset", ...): a deck copied
    !> with another level keeps a pinned speed, so the run says which it used.
    character(len=:), allocatable :: speed_source, direction_source
  end type wind_config

  !> Two massless elastic slings from fixed anchors to the hooks (foundation rigging).
  type :: slings_config
    !> Hook and anchor positions, fore and aft, inertial [m].
    real(wp) :: hook_fore(3), hook_aft(3), anchor_fore(3), anchor_aft(3)
    !> Unstretched sling length [m], wire diameter [m], Young's modulus [Pa], axial dashpot [N
    !> s/m].
    real(wp) :: length, diameter, youngs_modulus, damping
    !> Whether the slings hold the boat.
    logical :: attached
  end type slings_config

  type :: config_type
    !> Path of the deck read.
    character(len=:), allocatable :: filename
    !> The deck text as read, stored in the output file.
    character(len=:), allocatable :: deck_text
    !> &simulation: scene, integrator, times, tolerances.
    type(simulation_config) :: simulation
    !> &boat: the lifeboat and its loads.
    type(boat_config) :: boat
    !> &slings: the foundation slings.
    type(slings_config) :: slings
    !> &sea: the sea state.
    type(sea_config) :: sea
    !> &wind: the steady wind.
    type(wind_config) :: wind
    !> &ship (and &mmg): the ship.
    type(ship_config) :: ship
    !> &rao: the RAO runs.
    type(rao_config) :: rao
    !> &contact: fenders and contact law.
    type(contact_config) :: contact
    !> &rigging: falls, slings, winch.
    type(rigging_config) :: rigging
    !> &limits: rule limits and the occupant model.
    type(limits_config) :: limits
  end type config_type

contains

  !> Read, validate and return the configuration of deck file `filename`.
  subroutine read_config(filename, cfg, error)
    !> Path of the deck.
    character(len=*), intent(in) :: filename
    !> The configuration, every key checked.
    type(config_type), intent(out) :: cfg
    !> Set for the first unreadable line or refused key (file, line, group, key, range).
    type(error_type), allocatable, intent(out) :: error
    type(nml_deck) :: deck
    call read_deck(filename, deck, error)
    if (allocated(error)) return
    call config_from_deck(deck, cfg, error)
  end subroutine read_config

  !> Same as read_config for deck text in memory (tests).
  subroutine parse_config(filename, text, cfg, error)
    !> Name used in messages; the deck text.
    character(len=*), intent(in) :: filename, text
    !> The configuration, every key checked.
    type(config_type), intent(out) :: cfg
    !> Set for the first unreadable line or refused key (file, line, group, key, range).
    type(error_type), allocatable, intent(out) :: error
    type(nml_deck) :: deck
    call parse_deck(filename, text, deck, error)
    if (allocated(error)) return
    call config_from_deck(deck, cfg, error)
  end subroutine parse_config

  !> The documentation of every key (defaults of an empty deck).
  subroutine document_keys(docs)
    !> Every key of every group with its default, range, units and description.
    type(key_doc), allocatable, intent(out) :: docs(:)
    type(config_type) :: cfg
    type(deck_reader_type) :: reader
    call reader%init_defaults()
    call read_all(reader, cfg)
    docs = reader%docs
  end subroutine document_keys

  subroutine config_from_deck(deck, cfg, error)
    type(nml_deck), intent(in) :: deck
    type(config_type), intent(out) :: cfg
    type(error_type), allocatable, intent(out) :: error
    type(deck_reader_type) :: reader
    call reader%init(deck)
    call read_all(reader, cfg)
    call reader%finish(error)
    if (allocated(error)) return
    cfg%filename = deck%filename
    cfg%deck_text = deck%text
    call check_consistency(cfg, deck, error)
  end subroutine config_from_deck

  subroutine read_all(r, cfg)
    type(deck_reader_type), intent(inout) :: r
    type(config_type), intent(inout) :: cfg
    call read_simulation(r, cfg%simulation)
    call read_boat(r, cfg%boat)
    call read_slings(r, cfg%slings)
    call read_sea(r, cfg%sea)
    call read_wind(r, cfg%wind, cfg%sea)
    call read_ship(r, cfg%ship)
    call read_rao(r, cfg%rao)
    call read_contact(r, cfg%contact, cfg%ship%beam)
    call read_rigging(r, cfg%rigging)
    call read_limits(r, cfg%limits)
    if (cfg%simulation%t_end == 0.0_wp) cfg%simulation%t_end = default_end_time(cfg)
  end subroutine read_all

  !> The run's end when the deck gives none: for a launch, review G24's hard limit, the
  !> lowering (CG height above the still water over the boat's lowering speed) with a 30 %
  !> margin after the winch has started and ramped up, plus the time kept after release;
  !> 60 s for the other scenes.
  pure real(wp) function default_end_time(cfg) result(t)
    type(config_type), intent(in) :: cfg
    real(wp) :: speed
    t = 60.0_wp
    if (cfg%simulation%scene /= "launch" .and. cfg%simulation%scene /= "lowering") return
    associate (rig => cfg%rigging)
      if (rig%winch_mode == "boat") then
        speed = rig%lowering_speed
      else
        speed = rig%drum_speed/merge(4.0_wp, 2.0_wp, rig%reeving == "a")
      end if
      if (speed <= 0.0_wp) return
      t = rig%winch_start + rig%ramp_time + 1.3_wp*max(-cfg%boat%position(3), 1.0_wp)/speed + &
          cfg%simulation%after_release
    end associate
  end function default_end_time

  subroutine read_rao(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rao_config), intent(inout) :: s
    character(len=*), parameter :: g = "rao"
    integer :: i
    call r%real_list(g, "omegas", s%omegas, [(0.3_wp + 0.05_wp*i, i = 0, 26)], 0.01_wp, &
                     10.0_wp, "rad/s", "Wave frequencies of the RAO runs (default "// &
                     "0.3 to 1.6 in steps of 0.05).", 1, 500)
    call r%real_list(g, "headings_deg", s%headings, [0.0_wp, 45.0_wp, 90.0_wp, 135.0_wp, &
                     180.0_wp], -360.0_wp, 360.0_wp, "deg", "Wave directions relative to "// &
                     "the ship's heading (0 = following, 90 = from port, 180 = head).", 1, 72)
    s%headings = s%headings*pi/180.0_wp
    call r%real(g, "amplitude", s%amplitude, 0.05_wp, 0.0_wp, 5.0_wp, "m", &
                "Regular-wave amplitude of each run (responses are divided by it).", &
                lo_open=.true.)
    call r%real(g, "settle_time", s%settle_time, 250.0_wp, 0.0_wp, 1.0e4_wp, "s", &
                "Time after the 2-period ramp before the response is measured.")
    call r%int(g, "measure_periods", s%measure_periods, 10, 1, 1000, "-", &
               "Whole wave periods over which amplitude and phase are fitted.")
    call r%real(g, "dt", s%dt, 0.05_wp, 1.0e-4_wp, 1.0_wp, "s", &
                "RK4 step of the RAO runs (ship alone).")
  end subroutine read_rao

  subroutine read_simulation(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(simulation_config), intent(inout) :: s
    character(len=*), parameter :: g = "simulation"
    call r%real(g, "t_end", s%t_end, 0.0_wp, 0.0_wp, 1.0e5_wp, "s", &
                "Simulated time span from t = 0; 0 = derived: 'launch' and 'lowering' "// &
                "end at the derived limit, winch start + ramp + 1.3 x (CG height above "// &
                "the water)/(boat lowering speed) + after_release; other scenes 60 s.", &
                default_text="0 (derived)")
    call r%real(g, "after_release", s%after_release, 5.0_wp, 0.0_wp, 1.0e4_wp, "s", &
                "A launch ends this long after the hooks are released.")
    call r%real(g, "dt", s%dt, 1.0e-3_wp, 0.0_wp, 1.0_wp, "s", &
                "Integrator time step (fixed-step methods).", lo_open=.true.)
    call r%real(g, "dt_contact", s%dt_contact, 0.0_wp, 0.0_wp, 1.0_wp, "s", &
                "Step while a fender touches the ship's side or is predicted to within "// &
                "two steps (event location by step limiting); 0: always dt.")
    call r%real(g, "wave_update", s%wave_update, 0.0_wp, 0.0_wp, 1.0_wp, "s", &
                "Slow clock of the wave loads: the ship's Froude-Krylov loads and (irregular "// &
                "seas) the water at the boat's strips are sampled at this interval with "// &
                "their rates and interpolated (cubic Hermite; strips also expanded to first "// &
                "order in space about their position at the sample); 0: exact at every stage.")
    call r%choice(g, "scene", s%scene, "hanging_boat", &
                  [character(len=16) :: "hanging_boat", "lowering", "launch", "sea", "ship"], &
                  "What to simulate: 'hanging_boat' (boat on two slings from fixed points), "// &
                  "'lowering' (boat on the full &rigging from the davit of the ship at "// &
                  "rest in its &ship pose), 'launch' (the same from the 6-DOF ship moving "// &
                  "in the &sea and &wind), 'sea' (the wave field alone, recorded at &sea "// &
                  "probes) or 'ship' (the ship alone in the sea and wind).")
    call read_integrator(r, g, s%integrator, s%substeps, &
                         "Time integrator: classical fixed-step Runge-Kutta 4 (the paper's), "// &
                         "adaptive Dormand-Prince 5(4), the linearly implicit, L-stable "// &
                         "Rosenbrock RODAS3 (full finite-difference Jacobian every step), "// &
                         "the Rosenbrock-W ROS34PW2 implicit in the rigging only (its "// &
                         "Jacobian block kept for many steps), or the multirate "// &
                         "infinitesimal step methods of order 2 ('multirate': "// &
                         "Wicker-Skamarock stages 1/3, 1/2, 1; 'multirate2': midpoint stages "// &
                         "1/2, 1; 'mri2': MRI-GARK-ERK22a, the stages chained so that the "// &
                         "fast part sweeps each step once; 'mri2b': MRI-GARK-ERK22b, one "// &
                         "fast sweep of the whole step and the slow part's trapezoidal "// &
                         "correction) with dt their macro step: the ship and the boat's "// &
                         "water and wind loads once per stage, the rest (falls, hooks, "// &
                         "fenders, gravity) at `substeps` RK4 substeps per dt; the adaptive "// &
                         "ones take substeps inside each dt.", &
                         "RK4 substeps of the fast part per macro step dt (integrator = "// &
                         "'multirate', 'multirate2', 'mri2' or 'mri2b'; each stage takes its "// &
                         "share rounded to a whole number: 'mri2' nint(substeps/2) per half "// &
                         "step, so 5 runs 3 + 3; 'mri2b' exactly substeps; the substep must "// &
                         "keep the falls' ~200 Hz mode stable: 2e-3 s does, 2.5e-3 s does "// &
                         "not); other integrators ignore it.")
    call r%real(g, "rtol", s%rtol, 1.0e-6_wp, 0.0_wp, 1.0_wp, "-", &
                "Relative error tolerance of the adaptive integrators.", lo_open=.true.)
    call r%real(g, "atol", s%atol, 1.0e-9_wp, 0.0_wp, 1.0_wp, "-", &
                "Absolute error tolerance of the adaptive integrators (state units).")
    call r%logical(g, "fixed_step", s%fixed_step, .false., &
                   "dopri5 and rosenbrock take exactly one step of size dt per dt, with no "// &
                   "error control (rtol, atol unused; convergence-order studies); rk4 "// &
                   "ignores it.")
    call r%real(g, "output_interval", s%output_interval, 0.01_wp, 0.0_wp, 1.0e3_wp, "s", &
                "Interval between recorded samples; rounded to a whole number of steps.", &
                lo_open=.true.)
    call r%int(g, "seed", s%seed, 12345, 0, huge(1), "-", &
               "Random seed, recorded in the output (used by random seas).")
    call r%real(g, "max_memory", s%max_memory, 0.0_wp, 0.0_wp, 1.0e6_wp, "GiB", &
                "Memory the run may hold (recorded samples, the seat's 1 kHz trace, the "// &
                "wave components; estimated before the run, which is refused beyond it); "// &
                "0 = 80 % of the machine's physical memory.", default_text="0 (80 % of RAM)")
    call r%choice(g, "contact_approach", s%contact_approach, "window", &
                  [character(len=8) :: "window", "graded", "event"], &
                  "Steps before a fender reaches the ship's side: 'window' takes dt_contact "// &
                  "once contact is predicted within two steps of dt; 'graded' takes half "// &
                  "the predicted time to contact (at least dt_contact), so the approach costs "// &
                  "~log2(dt/dt_contact) steps instead of 2 dt/dt_contact; 'event' takes dt and "// &
                  "locates each fender phase switch and each sling or cable segment going "// &
                  "slack or taut on the integrator's dense output, cutting the step there.")
  end subroutine read_simulation

  subroutine read_slings(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(slings_config), intent(inout) :: s
    character(len=*), parameter :: g = "slings"
    call read_fore_aft(r, g, "hook", s%hook_fore, s%hook_aft, &
                       reshape([4.6_wp, 0.0_wp, -1.55_wp, -4.6_wp, 0.0_wp, -1.55_wp], [3, 2]), &
                       50.0_wp, "Fore hook point in the boat frame.", &
                       "Aft hook point in the boat frame.")
    call read_fore_aft(r, g, "anchor", s%anchor_fore, s%anchor_aft, &
                       reshape([4.6_wp, 13.3_wp, -19.55_wp, -4.6_wp, 13.3_wp, -19.55_wp], &
                               [3, 2]), 1.0e4_wp, &
                       "Fixed upper end of the fore sling, inertial frame.", &
                       "Fixed upper end of the aft sling, inertial frame.")
    call r%real(g, "length", s%length, 3.0_wp, 0.01_wp, 1000.0_wp, "m", &
                "Unstretched sling length.")
    call read_wire_rope(r, g, "diameter", s%diameter, s%youngs_modulus, &
                   "Wire diameter; EA = E pi d^2/4 (20 mm, paper III.B).", &
                   "Young's modulus of the wire (paper III.B).")
    call r%real(g, "damping", s%damping, 1.0e4_wp, 0.0_wp, 1.0e8_wp, "N s/m", &
                "Absolute axial dashpot per sling; 0 = undamped.")
    call r%logical(g, "attached", s%attached, .true., &
                   "Hang the boat on the slings; .false. = a free boat (floating tests).")
  end subroutine read_slings

  subroutine read_sea(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(sea_config), intent(inout) :: s
    character(len=*), parameter :: g = "sea"
    real(wp) :: preset_height, deg
    deg = pi/180.0_wp
    call r%int(g, "level", s%level, 5, 3, 5, "-", &
               "Sea-state preset: 3 = H 1.25 m, wind 5.5 m/s; 4 = "// &
               "H 2.5 m, wind 8 m/s; 5 = H 4 m, wind 10 m/s.")
    preset_height = level_wave_height(s%level)
    s%height_source = source(r%has(g, "height"), "level "//digit(s%level)//" preset")
    s%period_source = source(r%has(g, "period"), "peak period of eq. 44 for the height")
    call r%choice(g, "wave_type", s%wave_type, "calm", &
                  [character(len=10) :: "calm", "airy", "stokes2", "irregular"], &
                  "'calm', regular 'airy' (linear) or 'stokes2' (second order), or "// &
                  "short-crested 'irregular' (eqs. 43-45).")
    call r%real(g, "height", s%height, preset_height, 0.0_wp, 20.0_wp, "m", &
                "Regular: wave height 2a. Irregular: H of eq. 44 (Hs = 0.9971 H).", &
                lo_open=.true., default_text="level preset (4)")
    call r%real(g, "period", s%period, 2.0_wp*pi/spectrum_peak_omega(s%height), 1.0_wp, &
                40.0_wp, "s", "Regular-wave period; default the peak period of eq. 44 "// &
                "for the height (10.06 s at 2.5 m, 12.72 s at 4 m).", &
                default_text="peak period (12.72)")
    call r%real(g, "direction_deg", s%direction, 90.0_wp, -360.0_wp, 360.0_wp, "deg", &
                "Direction the waves travel towards (mean direction if irregular), from "// &
                "N1 towards N2 (N1 the ship's heading at heading_deg = 0, N2 starboard, N3 "// &
                "down); the encounter angle chi: 0 = following seas, 90 = from "// &
                "port (travelling towards the starboard side, where the boat hangs), 180 = "// &
                "head seas, 270 = from starboard.")
    s%direction = s%direction*deg
    call r%real(g, "phase_deg", s%phase, 0.0_wp, -360.0_wp, 360.0_wp, "deg", &
                "Phase epsilon of a regular wave at the origin at t = 0.")
    s%phase = s%phase*deg
    call r%int(g, "spreading_s", s%spreading_s, 1, 1, 30, "-", &
               "Exponent s of the cos-2s spreading, eq. 45.")
    call r%real(g, "spread_window_deg", s%spread_window, 30.0_wp, 0.0_wp, 90.0_wp, "deg", &
                "Directions span mean +- this; weights renormalised to sum to one.", &
                lo_open=.true.)
    s%spread_window = s%spread_window*deg
    call r%int(g, "n_frequencies", s%n_frequencies, 100, 1, 5000, "-", &
               "Number of frequency bins.")
    call r%int(g, "n_directions", s%n_directions, 13, 1, 361, "-", &
               "Number of directions, endpoints of the window included (1 = long-crested).")
    call r%real(g, "omega_min", s%omega_min, 0.3_wp, 0.0_wp, 20.0_wp, "rad/s", &
                "Lower end of the frequency band.", lo_open=.true.)
    call r%real(g, "omega_max", s%omega_max, 3.0_wp, 0.0_wp, 20.0_wp, "rad/s", &
                "Upper end of the frequency band.", lo_open=.true.)
    call r%logical(g, "jitter", s%jitter, .true., &
                   "Draw each frequency uniformly inside its bin (no repeat period); "// &
                   ".false. = bin centres.")
    call r%logical(g, "independent_frequencies", s%independent_frequencies, .true., &
                   "Each direction draws its own frequency in the bin (an ergodic sea); "// &
                   ".false. = the directions of a bin share one frequency, as eq. 43 is "// &
                   "printed (point variance then scatters ~3x more between seeds).")
    call r%choice(g, "summation", s%summation, "double", &
                  [character(len=19) :: "double", "single_equal_energy", "single_random"], &
                  "Irregular: 'double' = eq. 43, n_frequencies x n_directions components; "// &
                  "'single_equal_energy' = one direction per frequency (n_frequencies "// &
                  "components, each of the n_directions equal-energy sectors of the "// &
                  "spreading once per n_directions frequencies); 'single_random' = one "// &
                  "direction per frequency drawn from the spreading. Same Hs and spectrum.")
    call r%real(g, "ramp_periods", s%ramp_time, 2.0_wp, 0.0_wp, 100.0_wp, "-", &
                "Smooth start: forcing ramped by (1 - cos)/2 over this many (peak) periods.")
    s%ramp_time = s%ramp_time*s%period
    call r%real_list(g, "probes_x", s%probes_x, [0.0_wp], -1.0e5_wp, 1.0e5_wp, "m", &
                     "x of the wave probes recorded by the 'sea' scene.", 1, 1000)
    call r%real_list(g, "probes_y", s%probes_y, [0.0_wp], -1.0e5_wp, 1.0e5_wp, "m", &
                     "y of the wave probes (as many as probes_x).", 1, 1000)
    call read_sea_grid(r, s%grid)
  end subroutine read_sea

  subroutine read_wind(r, w, sea)
    type(deck_reader_type), intent(inout) :: r
    type(wind_config), intent(inout) :: w
    type(sea_config), intent(in) :: sea
    character(len=*), parameter :: g = "wind"
    w%speed_source = source(r%has(g, "speed"), "level "//digit(sea%level)//" preset")
    w%direction_source = source(r%has(g, "direction_deg"), &
                                "&sea direction_deg: along the waves")
    call r%real(g, "speed", w%speed, level_wind_speed(sea%level), 0.0_wp, &
                80.0_wp, "m/s", "Steady wind speed for the force models (not the "// &
                "spectrum's U = 6.28 sqrt(H)); without it the &sea level's preset "// &
                "(3: 5.5, 4: 8, 5: 10 m/s) and every run prints which it used.", &
                default_text="level preset (10)")
    call r%real(g, "direction_deg", w%direction, sea%direction*180.0_wp/pi, -360.0_wp, &
                360.0_wp, "deg", "Direction the wind blows towards (not from), from N1 "// &
                "towards N2 as &sea direction_deg: 0 = from astern, 90 = from port, 180 = "// &
                "from ahead.", &
                default_text="&sea direction_deg")
    w%direction = w%direction*pi/180.0_wp
  end subroutine read_wind

  !> "deck" where the deck sets the key, else `default` (the preset it falls back on).
  pure function source(in_deck, default) result(text)
    logical, intent(in) :: in_deck
    character(len=*), intent(in) :: default
    character(len=:), allocatable :: text
    if (in_deck) then
      text = "deck"
    else
      text = default
    end if
  end function source

  !> The digit of a sea-state level (3-5).
  pure function digit(level) result(text)
    integer, intent(in) :: level
    character(len=1) :: text
    text = achar(iachar("0") + modulo(level, 10))
  end function digit

  !> Wave height H of a sea-state level's preset [m] (review G19: upper bounds of the level;
  !> Level 3, added for the operability tables, likewise: sea state 3 is 0.5-1.25 m).
  pure real(wp) function level_wave_height(level)
    !> Sea-state level.
    integer, intent(in) :: level
    real(wp), parameter :: height(3:5) = [1.25_wp, 2.5_wp, 4.0_wp]
    level_wave_height = height(preset_level(level))
  end function level_wave_height

  !> Wind speed of a sea-state level's preset [m/s] (review G19; Level 3: the upper bound of
  !> Beaufort 3, 5.4 m/s, rounded as G19 rounds 7.9 to 8).
  pure real(wp) function level_wind_speed(level)
    !> Sea-state level.
    integer, intent(in) :: level
    real(wp), parameter :: speed(3:5) = [5.5_wp, 8.0_wp, 10.0_wp]
    level_wind_speed = speed(preset_level(level))
  end function level_wind_speed

  !> The preset a level takes: 3 and 4 their own, any other the Level 5 one.
  pure integer function preset_level(level)
    integer, intent(in) :: level
    preset_level = merge(level, 5, level == 3 .or. level == 4)
  end function preset_level

  !> Checks that involve more than one key.
  !> Each message names the line of one of the keys involved (the first the deck sets).
  subroutine check_consistency(cfg, deck, error)
    type(config_type), intent(in) :: cfg
    type(nml_deck), intent(in) :: deck
    type(error_type), allocatable, intent(out) :: error
    associate (s => cfg%simulation)
      if (s%output_interval < s%dt) then
        call fatal_error(error, at("simulation", "output_interval", "dt")// &
                         "&simulation: output_interval = "//fmt_real(s%output_interval)// &
                         " must be >= dt = "//fmt_real(s%dt))
        return
      end if
      if (s%t_end < s%dt) then
        call fatal_error(error, at("simulation", "t_end", "dt")//"&simulation: t_end = "// &
                         fmt_real(s%t_end)//" must be >= dt = "//fmt_real(s%dt))
        return
      end if
    end associate
    if (cfg%sea%omega_min >= cfg%sea%omega_max) then
      call fatal_error(error, at("sea", "omega_min", "omega_max")//"&sea: omega_min = "// &
                       fmt_real(cfg%sea%omega_min)//" must be < omega_max = "// &
                       fmt_real(cfg%sea%omega_max))
      return
    end if
    if (size(cfg%sea%probes_x) /= size(cfg%sea%probes_y)) then
      call fatal_error(error, at("sea", "probes_x", "probes_y")// &
                       "&sea: probes_x and probes_y must have the same number of values")
      return
    end if
    if (cfg%contact%fender_z(1) > cfg%contact%fender_z(2)) then
      call fatal_error(error, at("contact", "fender_z", "fender_z")//"&contact: fender_z = "// &
                       fmt_real(cfg%contact%fender_z(1))//", "// &
                       fmt_real(cfg%contact%fender_z(2))//" must be (lower, upper) with "// &
                       "lower <= upper")
      return
    end if
    if (norm2(cfg%slings%hook_fore - cfg%slings%hook_aft) < 1.0e-6_wp) then
      call fatal_error(error, at("slings", "hook_fore", "hook_aft")// &
                       "&slings: hook_fore and hook_aft must differ")
    end if

  contains

    function at(group, key1, key2) result(where)
      character(len=*), intent(in) :: group, key1, key2
      character(len=:), allocatable :: where
      where = key_at(deck, group, [character(len=max(len(key1), len(key2))) :: key1, key2])
    end function at

  end subroutine check_consistency

end module davit_io_config
