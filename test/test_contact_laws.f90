!> The fender contact laws as extensions of contact_law_type: the factory builds each from
!> its deck name and refuses an unknown one; each law's force against its closed form, so
!> that a changed coefficient, exponent or sign fails (eqs. 27-28, review §1.7, README
!> "### Fenders"). The same factory for the boat's wind lift forms (eq. 16; their forces
!> against eqs. 15-16 by hand are test_boat's wind_drag_and_lift_eqs_15_16).
module test_contact_laws
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: contact_config, boat_config
  use davit_boat_contact_law, only: contact_law_type, fender_state_type, phase_free, &
                                    phase_compression, phase_restitution, phase_separated
  use davit_boat_contact, only: hertz_elastoplastic_law_type, lankarani_nikravesh_law_type
  use davit_boat_rubber_fender_law, only: rubber_fender_law_type
  use davit_boat_wind_loads, only: boat_wind_type, symmetric_lift_wind_type, &
                                   literal_lift_wind_type
  use davit_system_law_factory, only: new_contact_law, new_boat_wind
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_contact_laws

  !> Hertz stiffness of the review's §1.7 pair by hand: E* = 1/((1 - 0.45^2)/55 GPa +
  !> (1 - 0.3^2)/200 GPa) = 5.24934e10 Pa, K = 4/3 E* sqrt(R): R = 0.25 m (flat side)
  !> 3.49956e10 N/m^1.5; R = 0.25 x 0.5/0.75 m (R_s = 0.5 m) 2.85738e10 N/m^1.5.
  real(wp), parameter :: k_flat = 3.49956e10_wp, k_curved = 2.85738e10_wp

contains

  function collect_contact_laws() result(suite)
    type(suite_type) :: suite
    suite%name = "contact_laws"
    suite%cases = [new_case("factory_builds_each_law_from_its_deck_name", factory_laws), &
                   new_case("factory_refuses_an_unknown_law", factory_unknown), &
                   new_case("hertz_elastoplastic_force_closed_form", elastoplastic), &
                   new_case("lankarani_nikravesh_force_closed_form", lankarani), &
                   new_case("rubber_fender_force_closed_form", rubber), &
                   new_case("factory_builds_each_lift_form", factory_lift), &
                   new_case("factory_refuses_an_unknown_lift_form", factory_lift_unknown)]
  end function collect_contact_laws

  !> A &contact group as the deck reader leaves it, with the law `name`.
  function deck_contact(name, radius_ship) result(k)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: radius_ship
    type(contact_config) :: k
    k%enabled = .true.
    k%law = name
    k%youngs_boat = 55.0e9_wp
    k%poisson_boat = 0.45_wp
    k%youngs_ship = 200.0e9_wp
    k%poisson_ship = 0.3_wp
    k%radius_boat = 0.25_wp
    k%radius_ship = radius_ship
    k%restitution = 0.7_wp
    k%fender_diameter = 1.2_wp
    k%fender_reaction = 250.0e3_wp
    k%fender_x = [3.0_wp, -3.0_wp]
    k%fender_y = -1.4_wp
    k%fender_z = [-0.8_wp, 0.2_wp]
    k%side_y = 10.4_wp
    k%fender_points = 3
  end function deck_contact

  !> Each deck name gives its extension, with the deck's data: the rubber fender's D, R_r
  !> and e_r; the Hertz laws' K from the two materials (the hand values above, flat and
  !> curved side) and e_r.
  subroutine factory_laws(state)
    type(case_state), intent(inout) :: state
    class(contact_law_type), allocatable :: law
    type(error_type), allocatable :: error
    logical :: ok
    call new_contact_law(deck_contact("rubber_fender", 0.0_wp), law, error)
    ok = .false.
    select type (law)
    type is (rubber_fender_law_type)
      ok = .true.
      call check(state, law%diameter, 1.2_wp, "rubber: D", rel_tol=1e-15_wp)
      call check(state, law%rated_reaction, 250.0e3_wp, "rubber: R_r", rel_tol=1e-15_wp)
    end select
    call check_true(state, ok .and. .not. allocated(error), "rubber_fender -> rubber law")
    call check(state, law%restitution, 0.7_wp, "rubber: e_r", rel_tol=1e-15_wp)
    call new_contact_law(deck_contact("hertz_elastoplastic", 0.0_wp), law, error)
    ok = .false.
    select type (law)
    type is (hertz_elastoplastic_law_type)
      ok = .true.
      call check(state, law%k, k_flat, "elastoplastic: K (flat side)", rel_tol=1e-5_wp)
    end select
    call check_true(state, ok .and. .not. allocated(error), &
                    "hertz_elastoplastic -> elastoplastic Hertz law")
    call check(state, law%restitution, 0.7_wp, "elastoplastic: e_r", rel_tol=1e-15_wp)
    call new_contact_law(deck_contact("lankarani_nikravesh", 0.5_wp), law, error)
    ok = .false.
    select type (law)
    type is (lankarani_nikravesh_law_type)
      ok = .true.
      call check(state, law%k, k_curved, "LN: K (R_s = 0.5 m)", rel_tol=1e-5_wp)
    end select
    call check_true(state, ok .and. .not. allocated(error), &
                    "lankarani_nikravesh -> Lankarani-Nikravesh law")
  end subroutine factory_laws

  !> An unknown name is an error naming the group, the key, the name and every allowed law.
  subroutine factory_unknown(state)
    type(case_state), intent(inout) :: state
    class(contact_law_type), allocatable :: law
    type(error_type), allocatable :: error
    call new_contact_law(deck_contact("hunt_crossley", 0.0_wp), law, error)
    call check_true(state, allocated(error), "an error")
    if (.not. allocated(error)) return
    call check_true(state, .not. allocated(law), "no law")
    call check_true(state, index(error%message, "&contact law") > 0, "names group and key: " &
                    //error%message)
    call check_true(state, index(error%message, "'hunt_crossley'") > 0, "names the value")
    call check_true(state, index(error%message, "rubber_fender") > 0 .and. &
                    index(error%message, "hertz_elastoplastic") > 0 .and. &
                    index(error%message, "lankarani_nikravesh") > 0, "lists the allowed laws")
  end subroutine factory_unknown

  !> K = 1e9 N/m^1.5, e_r = 0.8: compression f = K delta^1.5 (1 mm: 31622.78 N), from the
  !> dent at 0.5 mm the same at 1.5 mm; restitution from delta_max = 2 mm (f_max = K
  !> delta_max^1.5 = 89442.72 N) with delta_p = delta_max (1 - e^2) = 0.72 mm:
  !> f = f_max ((delta - delta_p)/(delta_max - delta_p))^1.5 = 42547.29 N at 1.5 mm; 0 at
  !> the permanent set and while separated; 0 out of contact. The hand values: a python
  !> one-liner of the formulas (in the test's comment, not the code under test).
  subroutine elastoplastic(state)
    type(case_state), intent(inout) :: state
    type(hertz_elastoplastic_law_type) :: law
    type(fender_state_type) :: s
    law = hertz_elastoplastic_law_type(restitution=0.8_wp, k=1.0e9_wp)
    s = fender_state_type()
    call check(state, law%force(s, 1.0e-3_wp, 0.3_wp), 31622.7766_wp, "free: K delta^1.5", &
               rel_tol=1e-8_wp)
    call check(state, law%force(s, -1.0e-3_wp, 0.3_wp), 0.0_wp, "out of contact", &
               abs_tol=0.0_wp)
    s = fender_state_type(phase=phase_compression, v0=1.0_wp, offset=5.0e-4_wp)
    call check(state, law%force(s, 1.5e-3_wp, 0.3_wp), 31622.7766_wp, &
               "compression from the dent", rel_tol=1e-8_wp)
    s = fender_state_type(phase=phase_restitution, v0=1.0_wp, delta_max=2.0e-3_wp, &
                          f_max=89442.7191_wp)
    call check(state, law%force(s, 1.5e-3_wp, -0.3_wp), 42547.2939_wp, "restitution", &
               rel_tol=1e-8_wp)
    call check(state, law%force(s, 7.0e-4_wp, -0.3_wp), 0.0_wp, "below delta_p", &
               abs_tol=0.0_wp)
    s%phase = phase_separated
    call check(state, law%force(s, 1.5e-3_wp, 0.3_wp), 0.0_wp, "separated", abs_tol=0.0_wp)
  end subroutine elastoplastic

  !> K = 1e9 N/m^1.5, e_r = 0.8, v0 = 1 m/s, delta = 1 mm: f = K delta^1.5 (1 + 3/4 (1 -
  !> e^2) delta_dot/v0) = 31622.78 x 1.135 = 35891.85 N approaching at 0.5 m/s, x 0.46 =
  !> 14546.48 N leaving at 2 m/s, 0 (clipped) leaving at 5 m/s; plain Hertz before v0 is
  !> recorded.
  subroutine lankarani(state)
    type(case_state), intent(inout) :: state
    type(lankarani_nikravesh_law_type) :: law
    type(fender_state_type) :: s
    law = lankarani_nikravesh_law_type(restitution=0.8_wp, k=1.0e9_wp)
    s = fender_state_type(phase=phase_compression, v0=1.0_wp)
    call check(state, law%force(s, 1.0e-3_wp, 0.5_wp), 35891.8514_wp, "approaching", &
               rel_tol=1e-8_wp)
    s%phase = phase_restitution
    call check(state, law%force(s, 1.0e-3_wp, -2.0_wp), 14546.4772_wp, "leaving", &
               rel_tol=1e-8_wp)
    call check(state, law%force(s, 1.0e-3_wp, -5.0_wp), 0.0_wp, "clipped at zero", &
               abs_tol=0.0_wp)
    s = fender_state_type(phase=phase_free)
    call check(state, law%force(s, 1.0e-3_wp, 0.5_wp), 31622.7766_wp, "no v0: plain Hertz", &
               rel_tol=1e-8_wp)
    call check(state, law%force(s, -1.0e-3_wp, 0.5_wp), 0.0_wp, "out of contact", &
               abs_tol=0.0_wp)
  end subroutine lankarani

  !> D = 1 m, R_r = 182 kN (ISO 17357-1 table, README "### Fenders"): loading at 32.5 %
  !> of D is halfway between the table's 0.25 and 0.32: 0.285 R_r = 51870 N; unloading from
  !> f_m = R_r/2 with p = 2 at 30 % (R = 0.25 R_r): f_m (R/f_m)^2 = 0.125 R_r = 22750 N.
  subroutine rubber(state)
    type(case_state), intent(inout) :: state
    type(rubber_fender_law_type) :: law
    type(fender_state_type) :: s
    law%diameter = 1.0_wp
    law%rated_reaction = 182.0e3_wp
    law%restitution = 0.8_wp
    s = fender_state_type(phase=phase_compression, v0=1.0_wp)
    call check(state, law%force(s, 0.325_wp, 0.5_wp), 51870.0_wp, "loading", rel_tol=1e-12_wp)
    s = fender_state_type(phase=phase_restitution, v0=1.0_wp, delta_max=0.45_wp, &
                          f_max=91.0e3_wp, exponent=2.0_wp)
    call check(state, law%force(s, 0.3_wp, -0.5_wp), 22750.0_wp, "unloading", rel_tol=1e-12_wp)
    s%phase = phase_free
    call check(state, law%force(s, -0.01_wp, 0.5_wp), 0.0_wp, "out of contact", &
               abs_tol=0.0_wp)
  end subroutine rubber

  !> A &boat group with the wind data and the lift form `name`.
  function deck_boat(name) result(b)
    character(len=*), intent(in) :: name
    type(boat_config) :: b
    b%lift_form = name
    b%wind_areas = [5.0_wp, 20.0_wp, 30.0_wp]
    b%wind_drag_coefficient = 0.5_wp
    b%lift_coefficient = 1.2_wp
    b%lift_diameter = 3.0_wp
    b%length = 10.0_wp
  end function deck_boat

  !> Each lift form's name gives its extension with the deck's data; a beam wind of 10 m/s
  !> from the other side (v2 = -10 m/s) tells them apart: eq. 16's lift
  !> 1/2 rho D l C_L v2^2 = 0.5*1.225*3*10*1.2*100 = 2205 N, upward (f3 < 0, b3 down) for
  !> 'symmetric', downward for 'literal'.
  subroutine factory_lift(state)
    type(case_state), intent(inout) :: state
    class(boat_wind_type), allocatable :: air
    type(error_type), allocatable :: error
    real(wp) :: f(3)
    logical :: ok
    call new_boat_wind(deck_boat("symmetric"), air, error)
    ok = .false.
    select type (air)
    type is (symmetric_lift_wind_type)
      ok = .true.
    end select
    call check_true(state, ok .and. .not. allocated(error), "symmetric -> symmetric lift")
    call check(state, air%length, 10.0_wp, "l_b from &boat length", rel_tol=1e-15_wp)
    call check(state, air%diameter, 3.0_wp, "D_b from &boat lift_diameter", rel_tol=1e-15_wp)
    f = air%force([0.0_wp, -10.0_wp, 0.0_wp], 1.0_wp)
    call check(state, f(3), -2205.0_wp, "symmetric: upward", rel_tol=1e-12_wp)
    call new_boat_wind(deck_boat("literal"), air, error)
    ok = .false.
    select type (air)
    type is (literal_lift_wind_type)
      ok = .true.
    end select
    call check_true(state, ok .and. .not. allocated(error), "literal -> eq. 16 lift")
    f = air%force([0.0_wp, -10.0_wp, 0.0_wp], 1.0_wp)
    call check(state, f(3), 2205.0_wp, "literal: downward", rel_tol=1e-12_wp)
  end subroutine factory_lift

  !> An unknown lift form is an error naming the group, key, value and allowed forms.
  subroutine factory_lift_unknown(state)
    type(case_state), intent(inout) :: state
    class(boat_wind_type), allocatable :: air
    type(error_type), allocatable :: error
    call new_boat_wind(deck_boat("kutta"), air, error)
    call check_true(state, allocated(error), "an error")
    if (.not. allocated(error)) return
    call check_true(state, .not. allocated(air), "no wind loads")
    call check_true(state, index(error%message, "&boat lift_form") > 0 .and. &
                    index(error%message, "'kutta'") > 0, "names key and value: "//error%message)
    call check_true(state, index(error%message, "symmetric") > 0 .and. &
                    index(error%message, "literal") > 0, "lists the allowed forms")
  end subroutine factory_lift_unknown

end module test_contact_laws
