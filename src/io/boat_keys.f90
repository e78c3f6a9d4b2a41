!> The &boat group: the lifeboat of Section III.B (its mass, inertia and initial state), its
!> strip hull, water-load model and wind loads, every key checked and documented as the
!> other groups' (davit_io_config reads it into config_type%boat).
module davit_io_boat_keys
  use davit_kinds, only: wp
  use davit_boat_wind_loads, only: lift_form_names
  use davit_io_deck_reader, only: deck_reader_type
  implicit none
  private
  public :: boat_config, read_boat


  !> Lifeboat of Section III.B (review F5) and its initial state.
  type :: boat_config
    !> Mass [kg] and principal moments of inertia [kg m^2].
    real(wp) :: mass, inertia(3)
    !> Initial CG position (inertial) [m], Euler angles roll, pitch, yaw [rad], CG velocity
    !> (inertial) [m/s], angular velocity [rad/s].
    real(wp) :: position(3), euler(3), velocity(3), angular_velocity(3)
    !> Strip hull (review G25) and water loads (eqs. 18-25).
    real(wp) :: length, beam, height, keel, breadth_exponent, drag_coefficients(3)
    !> Hull GM_T [m]; linear heave, roll, pitch damping fractions of critical.
    real(wp) :: metacentric_height, zeta(3)
    !> Number of strips n (eq. 18).
    integer :: strips
    !> Roll stiffness ('hull' | 'paper').
    character(len=:), allocatable :: roll_restoring
    !> Wind on the boat (eqs. 15-16, review §1.4, G27).
    real(wp) :: wind_areas(3), wind_drag_coefficient, lift_coefficient, lift_diameter
    !> Lift law: 'symmetric' or 'literal' (eq. 16).
    character(len=:), allocatable :: lift_form
    !> Water-load model (issue 18): 'bem' (pressure-integrated strips plus added mass,
    !> radiation memory, diffraction and viscous roll damping from the hull's BEM database),
    !> 'pressure' (the pressure-integrated strips alone) or 'paper' (the paper's strips).
    character(len=:), allocatable :: water_model, database
    !> Viscous roll damping, fraction of critical; fraction of V_0 wet at full immersion.
    real(wp) :: roll_damping, full_immersion
  end type boat_config

contains

  subroutine read_boat(r, b)
    !> The deck's reader, positioned at the &boat group.
    type(deck_reader_type), intent(inout) :: r
    !> The &boat values, defaults in, the deck's read over them.
    type(boat_config), intent(inout) :: b
    character(len=*), parameter :: g = "boat"
    call r%real(g, "mass", b%mass, 8500.0_wp, 0.0_wp, 1.0e6_wp, "kg", &
                "Lifeboat mass (paper III.B).", lo_open=.true.)
    call r%real_vec(g, "inertia", b%inertia, [25020.0_wp, 51745.0_wp, 51745.0_wp], &
                    0.0_wp, 1.0e9_wp, "kg m^2", &
                    "Principal moments of inertia about b1, b2, b3 (paper III.B).", &
                    lo_open=.true.)
    call r%real_vec(g, "position", b%position, [0.0_wp, 13.3_wp, -15.0_wp], -1.0e4_wp, &
                    1.0e4_wp, "m", "Initial CG position in the inertial frame (x along "// &
                    "N1, y starboard, z down; 15 m above the still water).")
    call r%real_vec(g, "euler", b%euler, [0.0_wp, 0.0_wp, 0.0_wp], -1.5_wp, 1.5_wp, "rad", &
                    "Initial roll, pitch, yaw (ZYX, eq. 2; x forward, y starboard, "// &
                    "z down: roll starboard down, pitch bow up, yaw bow to starboard).")
    call r%real_vec(g, "velocity", b%velocity, [0.0_wp, 0.0_wp, 0.0_wp], -100.0_wp, &
                    100.0_wp, "m/s", "Initial CG velocity in the inertial frame.")
    call r%real_vec(g, "angular_velocity", b%angular_velocity, [0.0_wp, 0.0_wp, 0.0_wp], &
                    -10.0_wp, 10.0_wp, "rad/s", &
                    "Initial angular velocity in body components (u1..u3).")
    call r%real(g, "length", b%length, 11.5_wp, 0.1_wp, 100.0_wp, "m", &
                "Hull length l_b of the strips and the lift cylinder (paper III.B).")
    call r%real(g, "beam", b%beam, 2.8_wp, 0.01_wp, 50.0_wp, "m", "Hull beam B (III.B).")
    call r%real(g, "height", b%height, 3.1_wp, 0.01_wp, 50.0_wp, "m", &
                "Hull section height H (III.B).")
    call r%real(g, "keel", b%keel, 1.1_wp, -50.0_wp, 50.0_wp, "m", &
                "Keel below the CG along b3 (CG 1.1 m above the keel).")
    call r%real(g, "breadth_exponent", b%breadth_exponent, 4.3_wp, 1.0_wp, 100.0_wp, "-", &
                "p in b(x) = B (1 - |2x/L|^p) (4.3 gives the waterplane area A3 = 26.2 m^2).")
    call r%int(g, "strips", b%strips, 20, 1, 400, "-", "Number of strips n (eq. 18).")
    call r%real_vec(g, "drag_coefficients", b%drag_coefficients, [1.2_wp, 1.2_wp, 1.2_wp], &
                    0.0_wp, 10.0_wp, "-", "Water drag coefficients c_D1..3 (paper C_fluid).")
    call r%choice(g, "roll_restoring", b%roll_restoring, "hull", &
                  [character(len=5) :: "hull", "paper"], "Roll stiffness: 'hull' (GM_T = "// &
                  "KB + BM - KG of the plan shape with KG = keel, 0.766 m) or 'paper' "// &
                  "(metacentric_height, eq. 24).")
    call r%real(g, "metacentric_height", b%metacentric_height, 2.0_wp, 0.0_wp, 20.0_wp, "m", &
                "h_m of the roll restoring moment with roll_restoring = 'paper' "// &
                "(eq. 24, paper III.B).")
    call r%real_vec(g, "zeta", b%zeta, [0.0_wp, 0.0_wp, 0.0_wp], 0.0_wp, 2.0_wp, "-", &
                    "Linear heave, roll, pitch damping on the water, fraction of critical "// &
                    "(0.1 is typical; the paper gives none).")
    call r%real_vec(g, "wind_areas", b%wind_areas, [8.5_wp, 26.2_wp, 26.2_wp], 0.0_wp, &
                    1.0e4_wp, "m^2", "Projected areas normal to b1, b2, b3 (III.B).")
    call r%real(g, "wind_drag_coefficient", b%wind_drag_coefficient, 0.5_wp, 0.0_wp, &
                10.0_wp, "-", "Wind drag coefficient C_w (paper C_air).")
    call r%real(g, "lift_coefficient", b%lift_coefficient, 1.2_wp, 0.0_wp, 10.0_wp, "-", &
                "Wind lift coefficient C_L (paper).")
    call r%real(g, "lift_diameter", b%lift_diameter, 3.29_wp, 0.0_wp, 50.0_wp, "m", &
                "Lift cylinder diameter D_b (the circle of the frontal area).")
    call r%choice(g, "lift_form", b%lift_form, "symmetric", &
                  lift_form_names, "Wind lift: 'symmetric' "// &
                  "(upward, from the lateral cross-flow) or eq. 16 'literal'.")
    call read_boat_water(r, b)
  end subroutine read_boat

  !> The boat's water-load model (issue 18, README "Boat on the water").
  subroutine read_boat_water(r, b)
    type(deck_reader_type), intent(inout) :: r
    type(boat_config), intent(inout) :: b
    character(len=*), parameter :: g = "boat"
    call r%choice(g, "water_model", b%water_model, "bem", &
                  [character(len=8) :: "bem", "pressure", "paper"], "Water loads: 'bem' "// &
                  "(the pressure strips plus A(inf), radiation memory, diffraction and "// &
                  "viscous roll damping from the hull's BEM database, scaled with "// &
                  "immersion), 'pressure' (sections clipped by the local surface's tangent "// &
                  "plane, wave pressure integrated over the wet bottom and sides, alone) or "// &
                  "'paper' (centre-line strips with the metacentric roll moment, eqs. 18-25).")
    call r%string(g, "database", b%database, "boat_bem.nc", &
                  "BEM database of the boat's hull (water_model = 'bem'), looked up in "// &
                  "the deck's folder, then DAVIT_PATH, unless absolute.")
    call r%real(g, "roll_damping", b%roll_damping, 0.1_wp, 0.0_wp, 2.0_wp, "-", &
                "Viscous roll damping (water_model = 'bem'), fraction of critical at the "// &
                "roll resonance with A44(w): eddy making at the sharp bilges, which "// &
                "potential flow lacks (Ikeda; ~0.05-0.15 for small craft at zero speed).")
    call r%real(g, "full_immersion", b%full_immersion, 0.5_wp, 0.0_wp, 1.0_wp, "-", &
                "Immersion s = min(1, V_wet/(f V_0)) scales the BEM terms; f is this key: "// &
                "they reach full strength once f of the displacement V_0 = m/rho is wet.", &
                lo_open=.true.)
  end subroutine read_boat_water

end module davit_io_boat_keys
