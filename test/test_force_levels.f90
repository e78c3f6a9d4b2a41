!> The levels of detail chosen at build as types (davit_ship_ship_hydro,
!> davit_ship_manoeuvring, davit_boat_water_terms): each deck builds its extension, and
!> each extension's bindings give the closed forms of its law (Table 1's hydrostatics, the
!> BEM database's stiffness and added mass, cross-flow drag, surge resistance) or add
!> nothing where the level has no such term.
module test_force_levels
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_core_rotation, only: rotation_matrix
  use davit_core_slow_clock, only: new_slow_clock, clock_reach
  use davit_ship_bem_database, only: bem_database_type, read_bem_database
  use davit_ship_ship_model, only: ship_system_type
  use davit_ship_ship_hydro, only: box_hydro_type, bem_hydro_type
  use davit_ship_manoeuvring, only: kijima_type, mmg_manoeuvring_type
  use davit_ship_rudder, only: rudder_type
  use davit_boat_water_terms, only: strips_alone_type, bem_terms_type
  use davit_boat_bem_water, only: diffraction_cache_type
  use davit_system_model, only: system_type
  use davit_run_ship_scene, only: build_ship_scene
  use system_fixture, only: new_test_system, deck_config, is_bem_ship, is_mmg_ship, &
                            ship_rps, boat_bem
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_force_levels

  character(len=*), parameter :: ship_db = "input/ship_bem.nc", boat_db = "input/boat_bem.nc"

contains

  function collect_force_levels() result(suite)
    type(suite_type) :: suite
    suite%name = "force_levels"
    suite%cases = [new_case("ship_levels_built_from_the_deck", ship_levels), &
                   new_case("box_still_water_is_table_1_hydrostatics", box_still_water), &
                   new_case("bem_still_water_is_the_database_stiffness", bem_still_water), &
                   new_case("kijima_crossflow_and_resistance_closed_form", kijima_loads), &
                   new_case("unsteered_and_mmg_add_nothing_where_they_have_no_term", &
                            empty_terms), &
                   new_case("boat_water_terms_strips_alone_and_bem", boat_terms)]
  end function collect_force_levels

  !> A ship of the deck's &ship model and manoeuvring.
  subroutine deck_ship(keys, ship)
    character(len=*), intent(in) :: keys
    type(ship_system_type), intent(out) :: ship
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp), allocatable :: y(:)
    call parse_config("t.nml", "&simulation scene = 'ship' / &ship "//keys// &
                      " / &sea wave_type = 'calm' / &wind speed = 0 /", cfg, error)
    if (allocated(error)) error stop error%message
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop error%message
  end subroutine deck_ship

  !> 'fk_box' and 'bem' build the box's and the BEM ship's hydrodynamics; 'kijima' and
  !> 'mmg' the two manoeuvring models, the MMG one at its self-propulsion revolutions.
  subroutine ship_levels(state)
    type(case_state), intent(inout) :: state
    type(ship_system_type) :: ship
    call deck_ship("model = 'fk_box'", ship)
    call check_true(state, same_type_as(ship%par%hydro, box_hydro_type()), "fk_box: the box")
    call check_true(state, same_type_as(ship%par%manoeuvring, kijima_type()), "kijima")
    call deck_ship("model = 'bem', database = '"//ship_db//"', manoeuvring = 'mmg', "// &
                   "headway = 2.0", ship)
    call check_true(state, is_bem_ship(ship), "bem: the BEM ship")
    call check_true(state, is_mmg_ship(ship), "mmg: the MMG model")
    call check_true(state, ship_rps(ship) > 0.0_wp, "propeller turning at 2 m/s headway")
  end subroutine ship_levels

  !> Table 1's box (C_b 0.68, L_wl 130.55 m, B 20.8 m, Delta 7.55e6 kg, GM 5.57 m): 0.1 m
  !> deeper, Z = -rho g l B dz with the box length l = sqrt(C_b) L_wl; heeled 0.02 rad,
  !> K = -Delta g GM phi; at rest no damping.
  subroutine box_still_water(state)
    type(case_state), intent(inout) :: state
    type(ship_system_type) :: ship
    real(wp) :: q(6), load(6), u(6)
    call deck_ship("model = 'fk_box'", ship)
    u = 0.0_wp
    q = [0.02_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, ship%par%z_eq + 0.1_wp]
    load = ship%par%hydro%still_water(ship%par%hull, ship%par%z_eq, q, u, &
                                      rotation_matrix(q(1:3)))
    associate (c => rotation_matrix(q(1:3)))
      call check(state, dot_product(c(3, :), load(1:3)), &
                 -rho_water*gravity*sqrt(0.68_wp)*130.55_wp*20.8_wp*0.1_wp, &
                 "heave restoring rho g A_wp dz", rel_tol=1.0e-12_wp)
    end associate
    call check(state, load(4), -7.55e6_wp*gravity*5.57_wp*0.02_wp, "roll restoring", &
               rel_tol=1.0e-12_wp)
  end subroutine box_still_water

  !> The BEM ship level, 0.1 m deeper: Z = -C33 dz from the database's hydrostatic
  !> stiffness (Capytaine's), as read from the file.
  subroutine bem_still_water(state)
    type(case_state), intent(inout) :: state
    type(ship_system_type) :: ship
    type(bem_database_type) :: db
    type(error_type), allocatable :: error
    real(wp) :: q(6), load(6), u(6)
    call read_bem_database(ship_db, db, error)
    if (allocated(error)) error stop error%message
    call deck_ship("model = 'bem', database = '"//ship_db//"'", ship)
    q = [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, ship%par%z_eq + 0.1_wp]
    u = 0.0_wp
    load = ship%par%hydro%still_water(ship%par%hull, ship%par%z_eq, q, u, &
                                      rotation_matrix(q(1:3)))
    call check(state, load(3), -db%stiffness(3, 3)*0.1_wp, "heave restoring -C33 dz", &
               rel_tol=1.0e-12_wp)
    call check(state, maxval(abs(load([1, 2, 6]))), 0.0_wp, "no surge, sway or yaw", &
               abs_tol=1.0e-9_wp*abs(load(3)))
  end subroutine bem_still_water

  !> Kijima's model at zero headway drifting sideways at 0.5 m/s: the cross-flow drag
  !> Y = -1/2 rho d C_D L_pp |v| v (the integrand is constant along the hull), no yaw
  !> moment, the derivatives idle (they scale with |u|); surging at 2 m/s: the resistance
  !> X = -1/2 rho S C_T u^2 with Mumford's S = 1.7 L d + V/d and C_T 0.003.
  subroutine kijima_loads(state)
    type(case_state), intent(inout) :: state
    type(kijima_type) :: kijima
    type(ship_system_type) :: ship
    real(wp) :: load(6), s
    call deck_ship("model = 'fk_box', crossflow_cd = 0.8", ship)
    load = 0.0_wp
    call kijima%add_hull_loads(ship%par%hull, ship%par%wetted, 0.0_wp, &
                               [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp], load)
    call check(state, load(2), -0.5_wp*rho_water*4.4_wp*0.8_wp*126.0_wp*0.25_wp, &
               "cross-flow drag", rel_tol=1.0e-12_wp)
    call check(state, load(6), 0.0_wp, "no yaw moment", abs_tol=1.0e-9_wp*abs(load(2)))
    load = 0.0_wp
    call kijima%add_hull_loads(ship%par%hull, ship%par%wetted, 1.0e3_wp, &
                               [0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp], load)
    s = 1.7_wp*126.0_wp*4.4_wp + 7.55e6_wp/rho_water/4.4_wp
    call check(state, load(1), 1.0e3_wp - 0.5_wp*rho_water*s*0.003_wp*4.0_wp, &
               "surge resistance plus the thrust", rel_tol=1.0e-12_wp)
    call check(state, maxval(abs(load([2, 6]))), 0.0_wp, "no sway or yaw", abs_tol=0.0_wp)
  end subroutine kijima_loads

  !> The MMG hull forces come with its steering, so its hull loads add nothing; Kijima's
  !> model has no rudder: its steering adds no load and writes no rate.
  subroutine empty_terms(state)
    type(case_state), intent(inout) :: state
    type(ship_system_type) :: ship
    type(mmg_manoeuvring_type) :: mmg
    type(kijima_type) :: kijima
    type(rudder_type) :: steer
    real(wp) :: load(6), dydt(12), u(6), y(12), q(6)
    call deck_ship("model = 'fk_box'", ship)
    u = [0.01_wp, 0.02_wp, 0.03_wp, 2.0_wp, 0.5_wp, 0.1_wp]
    load = [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp]
    call mmg%add_hull_loads(ship%par%hull, ship%par%wetted, 1.0e3_wp, u, load)
    call check(state, maxval(abs(load - [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp])), &
               0.0_wp, "MMG: no separate hull loads", abs_tol=0.0_wp)
    dydt = -7.0_wp
    y = 0.0_wp
    q = 0.0_wp
    call kijima%add_steering(ship%par%hull, ship%par%hydro, steer, ship%par%rudder, &
                             ship%par%autopilot, 0.0_wp, q, u, &
                             rotation_matrix([0.0_wp, 0.0_wp, 0.0_wp]), y, load, dydt)
    call check(state, maxval(abs(load - [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp])), &
               0.0_wp, "Kijima: no steering load", abs_tol=0.0_wp)
    call check(state, maxval(abs(dydt + 7.0_wp)), 0.0_wp, "Kijima: no steering rate", &
               abs_tol=0.0_wp)
  end subroutine empty_terms

  !> The strips alone add no force, mass, energy or immersion and keep no diffraction
  !> window. The BEM terms: the immersion is the first state; at s = 1 the modal masses
  !> are 1 + lambda_k with sum(lambda) = trace(M^-1 A(inf)) = sum A_ii / M_ii, and a boat
  !> surging at 1 m/s carries 1/2 s A_11 of kinetic energy, A from the database file.
  subroutine boat_terms(state)
    type(case_state), intent(inout) :: state
    type(strips_alone_type) :: none
    type(system_type) :: sys
    type(bem_terms_type) :: bem
    type(bem_database_type) :: db
    type(diffraction_cache_type) :: cache
    type(error_type), allocatable :: error
    real(wp), allocatable :: y(:), x(:), xdot(:)
    real(wp) :: f(6), v(6), e, u(6), m(6), trace
    integer :: i
    u = [0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp]
    f = 1.0_wp
    v = 1.0_wp
    e = 5.0_wp
    allocate (x(0), xdot(0))
    call none%add_loads(new_sea(), 0.0_wp, rotation_matrix([0.0_wp, 0.0_wp, 0.0_wp]), &
                        [0.0_wp, 0.0_wp, 0.0_wp], 0.0_wp, u, 1.0_wp, x, cache, xdot, f, v)
    call none%modal_masses(x, v)
    call none%add_kinetic_energy(x, u, e)
    call check(state, maxval(abs(f - 1.0_wp)) + maxval(abs(v - 1.0_wp)) + abs(e - 5.0_wp), &
               0.0_wp, "strips alone: no force, mass or energy", abs_tol=0.0_wp)
    call check(state, none%immersion(x), 0.0_wp, "strips alone: no immersion", abs_tol=0.0_wp)
    cache%clock = new_slow_clock(0.05_wp, clock_reach)
    call cache%clock%open(1.0_wp)
    call none%refresh(new_sea(), cache%clock, [0.0_wp, 0.0_wp, 0.0_wp], 0.0_wp, .true., cache)
    call check_true(state, .not. cache%clock%covers(1.01_wp), "strips alone: window closed")
    y = new_test_system(sys, deck_config("&slings attached = .false. / &wind speed = 0.0 "// &
                        "/ &contact enabled = .false. / &sea wave_type = 'calm' / &boat "// &
                        "database = '"//boat_db//"' /"))
    call check_true(state, same_type_as(sys%par%water_terms, bem_terms_type()), &
                    "database given: the BEM terms")
    bem%bem = boat_bem(sys)
    call read_bem_database(boat_db, db, error)
    if (allocated(error)) error stop error%message
    deallocate (x)
    allocate (x(db%nrad + 1))
    x = 0.0_wp
    x(1) = 1.0_wp
    call check(state, bem%immersion(x), 1.0_wp, "immersion is the first state", abs_tol=0.0_wp)
    call bem%modal_masses(x, v)
    m = [sys%par%boat%inertia, (sys%par%boat%mass, i = 1, 3)]
    trace = sum([(db%added_mass_inf(i, i), i = 4, 6)]/m(1:3)) + &
            sum([(db%added_mass_inf(i, i), i = 1, 3)]/m(4:6))
    call check(state, sum(v) - 6.0_wp, trace, "sum of lambda = trace(M^-1 A(inf))", &
               rel_tol=1.0e-10_wp)
    e = 0.0_wp
    x(1) = 0.5_wp
    call bem%add_kinetic_energy(x, u, e)
    call check(state, e, 0.25_wp*db%added_mass_inf(1, 1), "1/2 s A11 u^2 at s = 0.5", &
               rel_tol=1.0e-10_wp)
  end subroutine boat_terms

  !> A calm sea.
  function new_sea() result(sea)
    use davit_sea_wave_field, only: wave_field_type
    type(wave_field_type) :: sea
  end function new_sea

end module test_force_levels
