!> Deck keys of the rigging (group "rigging"): lumped-mass slings (paper §II.D, eqs. 47-65),
!> the cable-pulley system (§II.E, eqs. 66-82) and the winch. Defaults follow the review's
!> gaps G4-G8 and G26 and its baseline plan (§4.4: n = 0 lumps, quasi-static sheaves).
!> Positions of the davit hardware are in the ship frame s (x fwd, y stbd, z down, origin at
!> the ship CG); with the ship at rest at the origin they equal inertial positions.
module davit_io_rigging_keys
  use davit_kinds, only: wp
  use davit_io_deck_reader, only: deck_reader_type
  use davit_io_shared_keys, only: read_fore_aft, read_wire_rope
  implicit none
  private
  public :: rigging_config, read_rigging

  type :: rigging_config
    !> 'a' = one continuous cable over both falls (paper Fig. 8); 'b' = one wire per fall.
    character(len=:), allocatable :: reeving
    !> 'rotating' (sheave DOFs, eq. 71 corrected) or 'quasi_static' (one tension per cable).
    character(len=:), allocatable :: sheaves
    !> 'massive' (3 translational DOFs per block) or 'quasi_static' (no block inertia).
    character(len=:), allocatable :: blocks
    !> 'drum' (drum_speed is the rope speed) or 'boat' (lowering_speed is the boat's).
    character(len=:), allocatable :: winch_mode
    !> 'equilibrium' (pre-stretched, static) or 'unstretched' (Fig. 13 transient).
    character(len=:), allocatable :: initial
    !> Lumped masses per sling (0: a massless tension-only spring).
    integer :: lumps
    !> Unstretched sling length [m], sling mass per metre [kg/m], wire diameter [m], Young's
    !> modulus of the wire [Pa].
    real(wp) :: sling_length, sling_mass_per_length, wire_diameter, youngs_modulus
    !> Absolute axial dashpots of the slings and of each cable segment [N s/m].
    real(wp) :: sling_damping, cable_damping
    !> Wire damping ratio of every axial spring's own block mode, and whether the absolute
    !> dashpot keys were given (then they are used as given).
    real(wp) :: wire_damping_ratio
    !> Whether sling_damping and cable_damping were given in the deck.
    logical :: sling_damping_given = .false., cable_damping_given = .false.
    !> Height of a block's centre above its hook when it rests on it [m] (0: no stop).
    real(wp) :: block_stop
    !> Fore and aft davit heads [m], the spacing of a head's two cable nodes [m], lead sheave [m],
    !> drum [m], all ship frame.
    real(wp) :: head_fore(3), head_aft(3), head_spacing, lead_sheave(3), drum_position(3)
    !> Sheave radius [m], sheave polar inertia [kg m^2], block mass [kg], drum radius [m].
    real(wp) :: sheave_radius, sheave_inertia, block_mass, drum_radius
    !> Drum pay-out speed [m/s], boat lowering speed [m/s], winch start [s], speed ramp [s], brake
    !> start [s], braking time [s].
    real(wp) :: drum_speed, lowering_speed, winch_start, ramp_time, stop_time, brake_time
    !> Coulomb bearing moment of a rotating sheave [N m]; T_out/T_in over a quasi-static sheave.
    real(wp) :: bearing_friction, friction_ratio
    !> Hook release once waterborne (SOLAS: both hooks at once), after release_delay [s].
    logical :: release
    !> Delay of the release after the boat is waterborne [s].
    real(wp) :: release_delay
  end type rigging_config

contains

  subroutine read_rigging(r, s)
    !> The deck's reader, positioned at the &rigging group.
    type(deck_reader_type), intent(inout) :: r
    !> The &rigging values, defaults in, the deck's read over them.
    type(rigging_config), intent(inout) :: s
    call read_topology(r, s)
    call read_wire(r, s)
    call read_geometry(r, s)
    call read_hardware(r, s)
    call read_winch(r, s)
  end subroutine read_rigging

  subroutine read_topology(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rigging_config), intent(inout) :: s
    character(len=*), parameter :: g = "rigging"
    call r%choice(g, "reeving", s%reeving, "a", [character(len=1) :: "a", "b"], &
                  "'a': one cable drum-lead-fore head-block 1-aft head-block 2-dead end "// &
                  "(paper Fig. 8, boat speed = drum/4); 'b': one wire per fall (drum/2).")
    call r%choice(g, "sheaves", s%sheaves, "quasi_static", &
                  [character(len=12) :: "rotating", "quasi_static"], &
                  "'rotating': sheave DOFs with torque r (f_out - f_in) (eq. 71, c_gamma = 1); "// &
                  "'quasi_static': one tension per cable, no sheave DOFs.")
    call r%choice(g, "blocks", s%blocks, "massive", &
                  [character(len=12) :: "massive", "quasi_static"], &
                  "'massive': each movable block a 3-DOF mass (eqs. 74-82); 'quasi_static': "// &
                  "no block inertia (eq. 82 dropped, weight kept), the position solved from "// &
                  "the balance of eqs. 78-81 at every evaluation (removes the ~200 Hz mode).")
    call r%int(g, "lumps", s%lumps, 0, 0, 20, "-", &
               "Lumped masses per sling; 0 = massless tension-only spring.")
    call r%choice(g, "initial", s%initial, "equilibrium", &
                  [character(len=11) :: "equilibrium", "unstretched"], &
                  "Initial rigging: static equilibrium for the hanging boat, or unstretched "// &
                  "(gives the Fig. 13 tension transient).")
  end subroutine read_topology

  subroutine read_wire(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rigging_config), intent(inout) :: s
    character(len=*), parameter :: g = "rigging"
    call r%real(g, "sling_length", s%sling_length, 1.0_wp, 0.01_wp, 100.0_wp, "m", &
                "Unstretched sling length, block to hook.")
    call r%real(g, "sling_mass_per_length", s%sling_mass_per_length, 1.6_wp, 0.0_wp, &
                100.0_wp, "kg/m", "Sling mass per metre, shared by the lumps (20 mm 6x36).")
    call read_wire_rope(r, g, "wire_diameter", s%wire_diameter, s%youngs_modulus, &
                   "Wire diameter of slings and cable; EA = E pi d^2/4 (paper III.B).", &
                   "Young's modulus of slings and cable (paper III.B).")
    ! Wire damping (review §1.6, G26): a stranded rope's inter-wire friction is a
    ! hysteretic loss, about the same fraction of the strain energy per cycle at every
    ! frequency, so it is stated as one damping ratio. G26 reads zeta ~ 0.02 off the
    ! paper's Fig. 13 (the bounce settles in ~2.5 s); the same ratio then holds for the
    ! block's own mode on each wire (~200 Hz), which is what rings after a snatch.
    call r%real(g, "wire_damping_ratio", s%wire_damping_ratio, 0.02_wp, 0.0_wp, 1.0_wp, "-", &
                "Damping ratio of the wire (loss factor / 2): each sling and cable "// &
                "segment gets at least c = 2 zeta sqrt(k m_b), k its EA/L0, m_b the block.")
    s%sling_damping_given = r%has(g, "sling_damping")
    s%cable_damping_given = r%has(g, "cable_damping")
    call r%real(g, "sling_damping", s%sling_damping, 0.0_wp, 0.0_wp, 1.0e8_wp, "N s/m", &
                "Absolute axial dashpot of a whole sling (corrected eq. 63), used as given; "// &
                "each of the lumps+1 segments gets (lumps+1) times this.", &
                default_text="2 zeta sqrt(EA m_b/l)")
    ! The bounce mode is damped in the cable, not the sling: the 1 m sling is ~8x stiffer
    ! than the falls, so a sling dashpot sees little motion (review §4.1). 1e4 N s/m per
    ! cable segment gives the bounce zeta ~ 0.02 (G26), above the wire's block-mode floor.
    call r%real(g, "cable_damping", s%cable_damping, 1.0e4_wp, 0.0_wp, 1.0e8_wp, "N s/m", &
                "Absolute axial dashpot of each cable segment on its stretch rate "// &
                "(bounce zeta ~ 0.02); if not given, at least the wire's floor.")
  end subroutine read_wire

  subroutine read_geometry(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rigging_config), intent(inout) :: s
    character(len=*), parameter :: g = "rigging"
    call read_fore_aft(r, g, "head", s%head_fore, s%head_aft, &
                       reshape([4.6_wp, 13.3_wp, -20.55_wp, -4.6_wp, 13.3_wp, -20.55_wp], &
                               [3, 2]), 1.0e3_wp, &
                       "Fore davit head, midway between its sheave pair (A) or head sheave "// &
                       "and dead end (B), ship frame; 3 m above the block.", &
                       "Aft davit head, as head_fore.")
    call r%real(g, "head_spacing", s%head_spacing, 0.32_wp, 0.0_wp, 10.0_wp, "m", &
                "Distance along x between the two cable nodes at each head (2 sheave radii).")
    call r%real_vec(g, "lead_sheave", s%lead_sheave, [0.0_wp, 11.5_wp, -21.0_wp], -1.0e3_wp, &
                    1.0e3_wp, "m", "Lead sheave, ship frame; in option B each wire's guide "// &
                    "sheave is here with x set to its head's x.")
    call r%real_vec(g, "drum_position", s%drum_position, [0.0_wp, 8.0_wp, -16.5_wp], &
                    -1.0e3_wp, 1.0e3_wp, "m", "Drum (cable leaves here), ship frame; in "// &
                    "option B each wire leaves the barrel at its head's x.")
  end subroutine read_geometry

  subroutine read_hardware(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rigging_config), intent(inout) :: s
    character(len=*), parameter :: g = "rigging"
    call r%real(g, "sheave_radius", s%sheave_radius, 0.16_wp, 0.01_wp, 5.0_wp, "m", &
                "Radius of every sheave, fixed and movable (D/d = 16).")
    call r%real(g, "sheave_inertia", s%sheave_inertia, 0.19_wp, 1.0e-4_wp, 1.0e4_wp, &
                "kg m^2", "Polar inertia of every sheave (15 kg disc).")
    call r%real(g, "block_mass", s%block_mass, 50.0_wp, 0.01_wp, 1.0e4_wp, "kg", &
                "Translational mass of each movable block, sheave included.")
    call r%real(g, "block_stop", s%block_stop, 0.3_wp, 0.0_wp, 10.0_wp, "m", &
                "Height of a block's centre above its hook when it rests on it (slack "// &
                "fall): sheave radius + becket and hook eye; 0 = no stop.")
    call r%real(g, "drum_radius", s%drum_radius, 0.25_wp, 0.01_wp, 5.0_wp, "m", &
                "Drum radius; only for the drum angle s/r_d (speed-controlled drum).")
    call r%real(g, "bearing_friction", s%bearing_friction, 0.0_wp, 0.0_wp, 1.0e4_wp, "N m", &
                "Coulomb bearing moment of each rotating sheave (eq. 71); 0 = none.")
    call r%real(g, "friction_ratio", s%friction_ratio, 1.0_wp, 1.0_wp, 2.0_wp, "-", &
                "Quasi-static sheaves: T_out/T_in over each sheave in the running direction.")
  end subroutine read_hardware

  subroutine read_winch(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rigging_config), intent(inout) :: s
    character(len=*), parameter :: g = "rigging"
    call r%choice(g, "winch_mode", s%winch_mode, "drum", [character(len=4) :: "drum", "boat"], &
                  "'drum': drum_speed is the rope pay-out speed (paper text); 'boat': "// &
                  "lowering_speed is the boat's and the drum runs 4x (A) or 2x (B) (§1.12).")
    call r%real(g, "drum_speed", s%drum_speed, 0.7_wp, 0.0_wp, 10.0_wp, "m/s", &
                "Steady rope pay-out speed at the drum (paper III.B).")
    call r%real(g, "lowering_speed", s%lowering_speed, 0.7_wp, 0.0_wp, 10.0_wp, "m/s", &
                "Steady boat lowering speed when winch_mode = 'boat' (SOLAS 0.4 + 0.02 H).")
    call r%real(g, "winch_start", s%winch_start, 0.0_wp, 0.0_wp, 1.0e5_wp, "s", &
                "Time at which the drum starts paying out.")
    call r%real(g, "ramp_time", s%ramp_time, 1.0_wp, 0.0_wp, 100.0_wp, "s", &
                "Linear ramp of the pay-out speed from 0 to full.")
    call r%real(g, "stop_time", s%stop_time, 1.0e5_wp, 0.0_wp, 1.0e5_wp, "s", &
                "Time at which the brake starts to stop the drum.")
    call r%real(g, "brake_time", s%brake_time, 0.5_wp, 0.0_wp, 100.0_wp, "s", &
                "Linear ramp of the pay-out speed from full to 0 once braking.")
    call r%logical(g, "release", s%release, .true., "Release both hooks at once (SOLAS) "// &
                   "release_delay after the boat is waterborne.")
    call r%real(g, "release_delay", s%release_delay, 0.0_wp, 0.0_wp, 1.0e4_wp, "s", &
                "Delay between waterborne and hook release.")
  end subroutine read_winch

end module davit_io_rigging_keys
