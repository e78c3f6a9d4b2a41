!> Deck keys of the ship (group "ship"): Table 1 and the review's gaps G9-G15, the level
!> of detail of its hydrodynamics (the paper's box or a BEM database) and its heading
!> keeping.
module davit_io_ship_keys
  use davit_kinds, only: wp, pi
  use davit_io_deck_reader, only: deck_reader_type
  use davit_io_namelist, only: find_entry
  use davit_io_mmg_keys, only: read_mmg
  use davit_ship_mmg, only: mmg_type
  use davit_ship_rudder, only: rudder_type
  implicit none
  private
  public :: ship_config, read_ship

  !> Ship of Table 1 and the review's gaps G9-G15 (derived quantities in davit_ship_hull).
  type :: ship_config
    !> Length overall, on the waterline, between perpendiculars, beam, draught, depth, GM [m]; CG x
    !> and z [m]; block and waterplane coefficients; displacement [kg] (Table 1).
    real(wp) :: loa, lwl, lpp, beam, draught, depth, gm, cg_x, cg_z, cb, cwp, displacement
    !> Heave, roll and pitch damping as fractions of critical; quadratic roll damping [N m s^2];
    !> cross-flow drag coefficient.
    real(wp) :: zeta_heave, zeta_roll, zeta_pitch, roll_quadratic, crossflow_cd
    !> Frontal and lateral windage areas [m^2], height of the lateral wind force above G [m], list
    !> and trim [rad] (the deck gives degrees).
    real(wp) :: area_front, area_lateral, wind_height, list, trim
    !> Initial CG position (inertial) [m], heading [rad] (the deck gives degrees), headway [m/s].
    real(wp) :: position(3), heading, headway
    !> Hold the ship fixed.
    logical :: frozen
    !> Where the phase of the ship's wave loads is taken: 'initial' or 'current' position.
    character(len=:), allocatable :: wave_phase
    !> 'fk_box' (the paper's box) or 'bem' (Cummins' equation from `database`).
    character(len=:), allocatable :: model, database
    !> BEM ship's wave drift: 'none', 'mean' or 'newman' (davit_ship_wave_drift).
    character(len=:), allocatable :: drift
    !> BEM ship making way: forward-speed terms of its radiation, 'none' (zero-speed
    !> kernels), 'heave_pitch' or 'stf' (Salvesen-Tuck-Faltinsen's heave-pitch terms, or
    !> those and the sway-yaw ones; davit_ship_bem_loads).
    character(len=:), allocatable :: speed_terms
    !> Heading keeping and station keeping: natural periods [s] (0 = off), damping ratio.
    real(wp) :: heading_period, heading_damping, station_period
    !> BEM ship: roll radius of gyration in place of the database's [m] (0 = the database's).
    real(wp) :: roll_gyradius
    !> 'deck' (cross-flow drag, surge resistance, manoeuvring derivatives and windage from
    !> the deck's dimensions) or 'off' (none of them: the potential-flow ship alone).
    character(len=:), allocatable :: empirical_loads
    !> Restrained DOFs (surge, sway, heave, roll, pitch, yaw), as a tank test restrains a
    !> model: their accelerations are held at zero.
    logical :: restrained(6) = .false.
    !> Horizontal-plane manoeuvring: 'kijima' (linear derivatives, cross-flow drag,
    !> constant thrust) or 'mmg' (group &mmg: hull, propeller at `rps`, rudder steered by
    !> `rudder`).
    character(len=:), allocatable :: manoeuvring
    !> The MMG coefficients (group &mmg).
    type(mmg_type) :: mmg
    !> The rudder's steering (group &mmg).
    type(rudder_type) :: rudder
    !> Propeller revolutions [1/s] (0: the self-propulsion point at headway).
    real(wp) :: rps = 0.0_wp
  end type ship_config

contains

  subroutine read_ship(r, s)
    !> The deck's reader, positioned at the &ship group.
    type(deck_reader_type), intent(inout) :: r
    !> The &ship values, defaults in, the deck's read over them.
    type(ship_config), intent(inout) :: s
    character(len=*), parameter :: g = "ship"
    real(wp), parameter :: deg = pi/180.0_wp
    call r%real(g, "length_overall", s%loa, 139.8_wp, 0.1_wp, 500.0_wp, "m", &
                "Length over all, L_oa (Table 1; wind yaw moment, eq. 46).")
    call r%real(g, "length_waterline", s%lwl, 130.55_wp, 0.1_wp, 500.0_wp, "m", &
                "Waterline length L_wl (Table 1); box length l = sqrt(C_b) L_wl.")
    call r%real(g, "length_pp", s%lpp, 126.0_wp, 0.1_wp, 500.0_wp, "m", &
                "Length between perpendiculars (Table 1; radii of gyration, cross-flow drag).")
    call r%real(g, "beam", s%beam, 20.8_wp, 0.01_wp, 100.0_wp, "m", "Beam B (Table 1).")
    call r%real(g, "draught", s%draught, 4.4_wp, 0.005_wp, 30.0_wp, "m", "Draught d (Table 1).")
    call r%real(g, "depth", s%depth, 11.4_wp, 0.01_wp, 50.0_wp, "m", &
                "Moulded depth (Table 1); the side plane spans the freeboard above the water.")
    call r%real(g, "gm", s%gm, 5.57_wp, 0.001_wp, 20.0_wp, "m", &
                "Transverse metacentric height (Table 1): C44 = Delta g GM.")
    call r%real(g, "cg_x", s%cg_x, 0.0_wp, -100.0_wp, 100.0_wp, "m", &
                "CG forward of midship. Table 1's '2.3 m between centre of gravity and "// &
                "centre' is ambiguous; 0 keeps the paper's CG at the origin.")
    call r%real(g, "cg_z", s%cg_z, 0.0_wp, -20.0_wp, 20.0_wp, "m", &
                "CG below the still waterline (z down); 0 = on the waterline, as the paper "// &
                "places the ship CG at (0, 0, 0).")
    call r%real(g, "block_coefficient", s%cb, 0.68_wp, 0.3_wp, 1.0_wp, "-", &
                "C_b (Table 1).")
    call r%real(g, "waterplane_coefficient", s%cwp, 0.83_wp, 0.3_wp, 1.0_wp, "-", &
                "C_wp (Table 1; reported only, the box uses l B).")
    call r%real(g, "displacement", s%displacement, 7.55e6_wp, 0.1_wp, 1.0e9_wp, "kg", &
                "Mass Delta (Table 1).")
    call r%real(g, "zeta_heave", s%zeta_heave, 0.2_wp, 0.0_wp, 2.0_wp, "-", &
                "Linear heave damping as a fraction of critical.")
    call r%real(g, "zeta_roll", s%zeta_roll, 0.05_wp, 0.0_wp, 2.0_wp, "-", &
                "Linear roll damping as a fraction of critical; with model = "// &
                "'bem' the viscous part added to the radiation damping, at the roll "// &
                "resonance of the database.")
    call r%real(g, "zeta_pitch", s%zeta_pitch, 0.2_wp, 0.0_wp, 2.0_wp, "-", &
                "Linear pitch damping as a fraction of critical.")
    call r%real(g, "roll_quadratic", s%roll_quadratic, 0.0_wp, 0.0_wp, 1.0e12_wp, &
                "N m s^2", "Quadratic roll damping B44q |p| p (0 = off).")
    call r%real(g, "crossflow_cd", s%crossflow_cd, 0.8_wp, 0.0_wp, 5.0_wp, "-", &
                "Cross-flow drag coefficient for sway and yaw at zero speed.")
    call r%real(g, "area_front", s%area_front, 400.0_wp, 0.0_wp, 1.0e5_wp, "m^2", &
                "Frontal windage area A_F.")
    call r%real(g, "area_lateral", s%area_lateral, 1600.0_wp, 0.0_wp, 1.0e5_wp, "m^2", &
                "Lateral windage area A_L.")
    call r%real(g, "wind_height", s%wind_height, 7.0_wp, 0.0_wp, 100.0_wp, "m", &
                "Height h_z of the lateral wind force above G (eq. 46).")
    call r%real(g, "list_deg", s%list, 0.0_wp, -20.0_wp, 20.0_wp, "deg", &
                "Static list (equilibrium roll), positive to starboard (SOLAS/LSA: 20 deg).")
    s%list = s%list*deg
    call r%real(g, "trim_deg", s%trim, 0.0_wp, -10.0_wp, 10.0_wp, "deg", &
                "Static trim (equilibrium pitch), positive bow up (SOLAS/LSA: 10 deg).")
    s%trim = s%trim*deg
    call r%real_vec(g, "position", s%position, [0.0_wp, 0.0_wp, 0.0_wp], -1.0e5_wp, &
                    1.0e5_wp, "m", "Initial CG position in the inertial frame (paper: origin).")
    call r%real(g, "heading_deg", s%heading, 0.0_wp, -360.0_wp, 360.0_wp, "deg", &
                "Initial heading psi: the bow's direction (s1), from N1 "// &
                "towards N2 (90 = bow towards N2); wave and wind directions are not relative "// &
                "to it.")
    s%heading = s%heading*deg
    call r%real(g, "headway", s%headway, 0.0_wp, 0.0_wp, 15.0_wp, "m/s", &
                "Initial forward speed, held by a constant thrust equal to the resistance "// &
                "(manoeuvring = 'kijima') or by the propeller (manoeuvring = 'mmg', "// &
                "whose seakeeping frame moves at it: encounter frequencies); "// &
                "SOLAS/LSA launching with headway up to 5 kn = 2.57 m/s.")
    call r%logical(g, "frozen", s%frozen, .false., &
                   "Hold the ship fixed (III.A's fixed platform; or to isolate the boat).")
    call r%choice(g, "wave_phase", s%wave_phase, "initial", &
                  [character(len=8) :: "initial", "current"], &
                  "Where the wave phase of the ship's wave loads is taken: at the initial "// &
                  "position (linear seakeeping) or the current one (drift feeds back).")
    call read_ship_model(r, s)
  end subroutine read_ship

  !> The ship's level of detail and its heading keeping.
  subroutine read_ship_model(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(ship_config), intent(inout) :: s
    character(len=*), parameter :: g = "ship"
    call r%choice(g, "model", s%model, "fk_box", [character(len=8) :: "fk_box", "bem"], &
                  "Ship hydrodynamics: the paper's Froude-Krylov box with constant "// &
                  "strip-theory added masses ('fk_box'), or Cummins' equation from a BEM "// &
                  "database ('bem': A(inf), radiation memory, diffraction, mesh "// &
                  "hydrostatics and mass; displacement and gm are then the database's).")
    call r%string(g, "database", s%database, "ship_bem.nc", &
                  "BEM database of model = 'bem' (davit-post bem build), relative "// &
                  "to the deck's folder unless absolute.")
    call r%choice(g, "drift", s%drift, "none", [character(len=8) :: "none", "mean", "newman"], &
                  "Second-order wave drift of the BEM ship (model = 'bem'; surge, sway, yaw) "// &
                  "from the database's mean drift coefficients D(omega, beta): none; the mean "// &
                  "load sum D a^2 ('mean'); or Newman's approximation of the slowly varying "// &
                  "load in irregular seas ('newman', the same constant in a regular wave). "// &
                  "Off by default: the lifeboat has no drift load, and the ship's alone "// &
                  "would drive the two apart.")
    call read_speed_terms(r, s)
    call r%real(g, "roll_gyradius", s%roll_gyradius, 0.0_wp, 0.0_wp, 50.0_wp, "m", &
                "BEM ship: roll radius of gyration about the CG in place of the "// &
                "database's (0 = the database's, 0.38 B for input/ship_bem.nc): the roll "// &
                "inertia, hence the roll period, that the paper does not give.")
    call r%real(g, "heading_period", s%heading_period, 30.0_wp, 0.0_wp, 1000.0_wp, "s", &
                "Heading keeping in the 'launch' scene (autopilot or DP: a PD yaw moment "// &
                "on the ship towards its initial heading): natural period of the held "// &
                "yaw; 0 = the ship yaws freely (the paper).")
    call r%real(g, "heading_damping", s%heading_damping, 0.7_wp, 0.0_wp, 2.0_wp, "-", &
                "Damping ratio of the heading (and station) keeping.")
    call r%real(g, "station_period", s%station_period, 0.0_wp, 0.0_wp, 10000.0_wp, "s", &
                "Station keeping in the 'launch' scene (DP-like horizontal springs on the "// &
                "CG towards its initial position): natural period; 0 = off.")
    call read_ship_terms(r, s)
    call r%choice(g, "manoeuvring", s%manoeuvring, "kijima", &
                  [character(len=8) :: "kijima", "mmg"], &
                  "Horizontal-plane forces: linear Kijima hull derivatives, cross-flow "// &
                  "drag and a constant thrust ('kijima'), or the standard MMG model with "// &
                  "propeller and rudder of group &mmg ('mmg'; on the BEM ship the seakeeping "// &
                  "frame moves with the headway: encounter frequencies).")
    call read_mmg(r, s%mmg, s%rps, s%rudder)
  end subroutine read_ship_model

  !> The BEM ship's forward-speed radiation terms (after `model`: they need the memory).
  subroutine read_speed_terms(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(ship_config), intent(inout) :: s
    character(len=*), parameter :: g = "ship"
    integer :: k
    call r%choice(g, "speed_terms", s%speed_terms, "none", &
                  [character(len=11) :: "none", "heave_pitch", "stf"], &
                  "Forward-speed terms of the BEM ship's radiation (model = 'bem', at the "// &
                  "seakeeping frame's speed `headway`; doc/theory/ship.md): 'none' "// &
                  "(zero-speed kernels fed the motions about the steady forward motion), "// &
                  "'heave_pitch' (Salvesen, Tuck & Faltinsen 1970's U-terms of the heave-"// &
                  "pitch added mass and damping, in the time domain; the sway-yaw ones left "// &
                  "to the manoeuvring model's derivatives, which hold their low-frequency "// &
                  "part) or 'stf' (the heave-pitch and the sway-yaw terms).")
    if (s%speed_terms /= "none" .and. s%model /= "bem") then
      k = find_entry(r%deck, g, "speed_terms")
      call r%fail(r%deck%entries(k)%line, g, "speed_terms", s%speed_terms, &
                  "needs model = 'bem' (its radiation memory)", "'none' with model = '"// &
                  s%model//"'", "-")
    end if
  end subroutine read_speed_terms

  !> Which of the deck's empirical loads act, and which DOFs are restrained.
  subroutine read_ship_terms(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(ship_config), intent(inout) :: s
    character(len=*), parameter :: g = "ship"
    character(len=*), parameter :: dofs(6) = [character(len=5) :: "surge", "sway", "heave", &
                                               "roll", "pitch", "yaw"]
    character(len=5), allocatable :: restrain(:)
    integer :: k
    call r%choice(g, "empirical_loads", s%empirical_loads, "deck", &
                  [character(len=4) :: "deck", "off"], &
                  "The ship's empirical loads: cross-flow drag (crossflow_cd), surge "// &
                  "resistance, the linear manoeuvring derivatives and the windage "// &
                  "(area_front, area_lateral, wind_height), all sized by this group's "// &
                  "dimensions ('deck'), or none of them ('off': the potential-flow ship "// &
                  "alone, e.g. a model-scale BEM hull against `davit-post bem rao`).")
    call r%choice_list(g, "restrain", restrain, [character(len=5) :: "none"], &
                       [character(len=5) :: "none", dofs], &
                       "Degrees of freedom held fixed, as a tank test restrains a model "// &
                       "(e.g. 'surge', 'sway', 'yaw'): their accelerations in ship axes "// &
                       "are zero, so their speeds keep their initial values (the CG's "// &
                       "inertial motion in them is then of second order, e.g. pitch times "// &
                       "surge); 'none' = a free ship.", 1, 6)
    do k = 1, 6
      s%restrained(k) = any(restrain == dofs(k))
    end do
  end subroutine read_ship_terms

end module davit_io_ship_keys
