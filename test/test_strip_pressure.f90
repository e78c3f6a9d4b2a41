!> Pressure-integrated strips (issue 18, davit_boat_strip_pressure): calm-water roll
!> stiffness against GM_T = KB + BM - KG of the plan shape, the wave pressure on one section
!> in a beam sea against its linear integral (heave force and roll moment), energy of the
!> undamped free boat, continuous first contact and a drop test's entry depth.
module test_strip_pressure
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_io_config, only: config_type
  use davit_core_rotation, only: rotation_matrix
  use davit_sea_wave_field, only: wave_field_type, wave_airy, new_calm_sea, new_regular_wave, &
                                  new_irregular_sea
  use davit_core_random, only: rng_type, new_rng
  use davit_core_quadrature, only: gauss8_x, gauss8_w
  use davit_boat_hull, only: boat_hull_type, new_boat_hull, hull_waterplane_area, &
                             section_immersion, section_wet_type
  use davit_boat_strip_pressure, only: section_wave_loads
  use davit_boat_strip_loads, only: strip_model_type, new_strip_model, strip_loads, &
                                    strip_potential
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, deck_config
  use davit_solve_rk4, only: rk4_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_strip_pressure

  real(wp), parameter :: mass = 8500.0_wp, inertia(3) = [25020.0_wp, 51745.0_wp, 51745.0_wp]
  !> A free boat on calm water, no drag, no damping, no wind, no slings.
  character(len=*), parameter :: still_deck = "&slings attached = .false. / "// &
                                 "&wind speed = 0.0 / &contact enabled = .false. / "// &
                                 "&sea wave_type = 'calm' / "

contains

  function collect_strip_pressure() result(suite)
    type(suite_type) :: suite
    suite%name = "strip_pressure"
    suite%cases = [new_case("calm_heel_moment_vs_gm_kb_bm_kg", calm_heel), &
                   new_case("beam_wave_heave_force_vs_linear_integral", beam_heave), &
                   new_case("beam_wave_roll_moment_vs_linear_integral", beam_roll), &
                   new_case("undamped_free_boat_conserves_energy", energy), &
                   new_case("first_contact_is_continuous", first_contact), &
                   new_case("drop_from_1m_entry_depth_vs_energy", drop_test), &
                   new_case("irregular_section_load_vs_edge_quadrature", irregular_section), &
                   new_case("section_load_derivatives_vs_central_differences", section_sens), &
                   new_case("calm_horizontal_drag_is_morison", calm_drag)]
  end function collect_strip_pressure

  !> The III.B hull (G25) as strips: 11.5 x 2.8 m, H = 3.1 m, keel 1.1 m below G.
  function paper_hull(n) result(h)
    integer, intent(in) :: n
    type(boat_hull_type) :: h
    h = new_boat_hull(11.5_wp, 2.8_wp, 3.1_wp, 1.1_wp, 4.3_wp, n)
  end function paper_hull

  !> Heeled by phi at the equilibrium draught T = V/A_wp: M1 = -m g GM_T sin(phi) with
  !> GM_T = T/2 + sum b^3 t_s/(12 V) - KG for the strips (wall-sided sections: exact to
  !> O(phi^2); the wall-sided formula's BM tan^2(phi)/2 is 1e-4 of GM at 0.01 rad), and
  !> within 1 % of the plan shape's GM_T = T/2 + int b^3 dx/(12 V) - KG (1e5-point
  !> midpoint rule: the continuous hull, 0.766 m).
  subroutine calm_heel(state)
    type(case_state), intent(inout) :: state
    type(strip_model_type) :: s
    type(wave_field_type) :: calm
    real(wp), parameter :: phi = 0.01_wp
    real(wp) :: f(6), v, t0, gm_strips, gm_plan, x, ib, area
    integer :: i
    integer, parameter :: nq = 100000
    s = new_strip_model(paper_hull(20), [0.0_wp, 0.0_wp, 0.0_wp], 2.0_wp, [0.0_wp, 0.0_wp, &
                        0.0_wp], mass, inertia)
    call new_calm_sea(calm)
    t0 = (mass/rho_water)/hull_waterplane_area(s%hull)
    call strip_loads(s, calm, 0.0_wp, rotation_matrix([phi, 0.0_wp, 0.0_wp]), &
                     [0.0_wp, 0.0_wp, t0 - 1.1_wp], [(0.0_wp, i = 1, 6)], f, v)
    gm_strips = t0/2 + sum(s%hull%breadth**3)*s%hull%thickness/(12*mass/rho_water) - 1.1_wp
    ib = 0.0_wp
    area = 0.0_wp
    do i = 1, nq
      x = -5.75_wp + (i - 0.5_wp)*11.5_wp/nq
      ib = ib + (2.8_wp*(1.0_wp - abs(2*x/11.5_wp)**4.3_wp))**3*11.5_wp/nq
      area = area + 2.8_wp*(1.0_wp - abs(2*x/11.5_wp)**4.3_wp)*11.5_wp/nq
    end do
    gm_plan = 0.5_wp*(mass/rho_water)/area + ib/(12*mass/rho_water) - 1.1_wp
    call note(state, "GM_T of the strips (m)", gm_strips)
    call note(state, "GM_T of the plan shape (m)", gm_plan)
    call note(state, "-M1/(m g sin phi) (m)", -f(1)/(mass*gravity*sin(phi)))
    call check(state, -f(1)/(mass*gravity*sin(phi)), gm_strips, "roll moment vs strips' GM", &
               rel_tol=1e-3_wp)
    call check(state, -f(1)/(mass*gravity*sin(phi)), gm_plan, "roll moment vs plan GM", &
               rel_tol=1e-2_wp)
    call check(state, s%gm_hull, gm_strips, "model's GM_T", rel_tol=1e-12_wp)
  end subroutine calm_heel

  !> One section (a 1-strip hull: b = B, t_s = L) upright at draught T in a beam sea of
  !> amplitude a = 1e-5 m (linear) and the wave loads less the calm ones, at 8 phases:
  !> load (F3, M1) per unit rho g a t_s. Linear theory on the still-water hull:
  !>   F3 = -b e^{-kT} sinc(k b/2) cos(theta0)                       (bottom)
  !>   M1 = -e^{-kT} sin(theta0) 2 (sin(kh)/k^2 - h cos(kh)/k)        (bottom, h = b/2)
  !>        + 2 sin(theta0) sin(kh) [z0 (1 - e^{-kT})/k + 1/k^2 - e^{-kT}(T/k + 1/k^2)]
  !>                                                          (sides, z0 = KG - T below G)
  subroutine section_in_beam_wave(omega, f3, m1, f3_lin, m1_lin)
    real(wp), intent(in) :: omega
    real(wp), intent(out) :: f3(8), m1(8), f3_lin(8), m1_lin(8)
    real(wp), parameter :: a = 1.0e-5_wp, tdraft = 0.3175_wp, keel = 1.1_wp
    type(strip_model_type) :: s
    type(wave_field_type) :: wave, calm
    real(wp) :: f(6), f0(6), v, k, h, th, c(3, 3), r(3), u(6), scale, t
    integer :: j
    s = new_strip_model(new_boat_hull(11.5_wp, 2.8_wp, 3.1_wp, keel, 4.3_wp, 1), &
                        [0.0_wp, 0.0_wp, 0.0_wp], 2.0_wp, [0.0_wp, 0.0_wp, 0.0_wp], mass, inertia)
    call new_calm_sea(calm)
    call new_regular_wave(wave, wave_airy, 2*a, 2*pi/omega, pi/2, 0.0_wp, 0.0_wp)
    k = omega**2/gravity
    h = 1.4_wp
    c = rotation_matrix([0.0_wp, 0.0_wp, 0.0_wp])
    r = [0.0_wp, 0.0_wp, tdraft - keel]
    u = 0.0_wp
    scale = rho_water*gravity*a*s%hull%thickness
    call strip_loads(s, calm, 0.0_wp, c, r, u, f0, v)
    do j = 1, 8
      t = (j - 1)*(2*pi/omega)/8
      th = omega*t
      call strip_loads(s, wave, t, c, r, u, f, v)
      f3(j) = (f(6) - f0(6))/scale
      m1(j) = (f(1) - f0(1))/scale
      f3_lin(j) = -2*h*exp(-k*tdraft)*sin(k*h)/(k*h)*cos(th)
      m1_lin(j) = -exp(-k*tdraft)*sin(th)*2*(sin(k*h)/k**2 - h*cos(k*h)/k) + &
                  2*sin(th)*sin(k*h)*((keel - tdraft)*(1 - exp(-k*tdraft))/k + 1/k**2 - &
                                      exp(-k*tdraft)*(tdraft/k + 1/k**2))
    end do
  end subroutine section_in_beam_wave

  !> Heave force of a section in a beam sea at 2 and 6 rad/s (depth decay and breadth
  !> averaging) against the linear integral, to 1e-4 of rho g a b t_s.
  subroutine beam_heave(state)
    type(case_state), intent(inout) :: state
    real(wp) :: f3(8), m1(8), f3_lin(8), m1_lin(8)
    integer :: i
    real(wp), parameter :: omegas(2) = [2.0_wp, 6.0_wp]
    do i = 1, 2
      call section_in_beam_wave(omegas(i), f3, m1, f3_lin, m1_lin)
      call note(state, "heave force / (rho g a b t_s) at w = "// &
                merge("2", "6", i == 1)//" rad/s", maxval(abs(f3))/2.8_wp)
      call check(state, maxval(abs(f3 - f3_lin))/2.8_wp, 0.0_wp, "F3 vs linear integral", &
                 abs_tol=1e-4_wp)
    end do
  end subroutine beam_heave

  !> Roll moment of a section in a beam sea (bottom pressure across the breadth, sides)
  !> against the linear integral, to 1e-4 of rho g a b^2 t_s.
  subroutine beam_roll(state)
    type(case_state), intent(inout) :: state
    real(wp) :: f3(8), m1(8), f3_lin(8), m1_lin(8)
    integer :: i
    real(wp), parameter :: omegas(3) = [1.0_wp, 2.0_wp, 6.0_wp]
    do i = 1, 3
      call section_in_beam_wave(omegas(i), f3, m1, f3_lin, m1_lin)
      call note(state, "roll moment / (rho g a t_s) (m^2)", maxval(abs(m1)))
      call check_true(state, maxval(abs(m1_lin)) > 0.05_wp, "a beam sea rolls the section")
      call check(state, maxval(abs(m1 - m1_lin))/2.8_wp**2, 0.0_wp, "M1 vs linear integral", &
                 abs_tol=1e-4_wp)
    end do
  end subroutine beam_roll

  !> Kinetic energy plus rho g int z dV - m g z_G (strip_potential) of the free boat.
  real(wp) function boat_energy(sys, y) result(e)
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: y(:)
    real(wp) :: c(3, 3), r(3)
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    e = 0.5_wp*mass*sum(y(10:12)**2) + 0.5_wp*sum(inertia*y(7:9)**2) + &
        strip_potential(sys%par%water, c, r) - mass*gravity*r(3)
  end function boat_energy

  !> Released at its equilibrium draught heeled 0.1 rad, no drag or damping, 30 s of RK4
  !> (dt = 2e-3 s): the energy drifts by < 1e-4 of the heel's potential energy and roll
  !> stays within 0.1 rad, with the hull's GM and with the paper's h_m (its conservative
  !> roll-heave coupling). Heave stays within 2 (KG + h_m - GM_T)(1 - cos 0.1) (+5 %):
  !> heeled about G the wall-sided hull sits KG (1 - cos phi) = 5.5 mm higher (the paper's
  !> coupling adds (h_m - GM_T)(1 - cos phi)), a bounded oscillation about that. (The paper
  !> level's metacentric moment grew the roll
  !> to 0.17 rad and heave to 77 mm, issue 18.)
  subroutine energy(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t, e0, e_eq, drift, roll, heave, z0, t0, r(3)
    integer :: i, j
    character(len=5), parameter :: option(2) = ["hull ", "paper"]
    do j = 1, 2
      cfg = deck_config(still_deck//"&boat water_model = 'pressure' drag_coefficients = "// &
                        "0.0, 0.0, 0.0 zeta = 0, 0, 0 "// &
                        "roll_restoring = '"//trim(option(j))//"' /")
      t0 = (mass/rho_water)/hull_waterplane_area(paper_hull(20))
      cfg%boat%position = [0.0_wp, 0.0_wp, t0 - 1.1_wp]
      y = new_test_system(sys, cfg)
      e_eq = boat_energy(sys, y)
      cfg%boat%euler = [0.1_wp, 0.0_wp, 0.0_wp]
      y = new_test_system(sys, cfg)
      e0 = boat_energy(sys, y)
      z0 = t0 - 1.1_wp
      call rk%init(size(y))
      t = 0.0_wp
      drift = 0.0_wp
      roll = 0.0_wp
      heave = 0.0_wp
      do i = 1, 15000
        call rk%step(sys, t, y, 2.0e-3_wp)
        call sys%after_step(t, y)
        drift = max(drift, abs(boat_energy(sys, y) - e0))
        roll = max(roll, abs(y(1)))
        r = matmul(rotation_matrix(y(1:3)), y(4:6))
        heave = max(heave, abs(r(3) - z0))
      end do
      call note(state, trim(option(j))//": heel energy (J)", e0 - e_eq)
      call note(state, trim(option(j))//": energy drift / heel energy", drift/(e0 - e_eq))
      call note(state, trim(option(j))//": max roll (rad)", roll)
      call note(state, trim(option(j))//": max heave (m)", heave)
      call check(state, drift/(e0 - e_eq), 0.0_wp, "energy conserved", abs_tol=1e-4_wp)
      call check_true(state, roll <= 0.1_wp*(1 + 1e-6_wp), "roll stays within 0.1 rad")
      call check_true(state, heave < 1.05_wp*2*(1.1_wp + sys%par%water%metacentric_height - &
                                                 sys%par%water%gm_hull)*(1 - cos(0.1_wp)), &
                      "heave stays bounded")
    end do
  end subroutine energy

  !> The upright boat lowered at 0.5 m/s through the calm surface (keel from 5 mm above to
  !> 20 mm below, 0.1 mm steps; drag on): the vertical load grows by no more than the
  !> buoyancy and bottom-drag increments of a step (rho g A_wp dz and the drag area's growth
  !> over T_0), with no jump at first wetting. (The paper level's D3 jumps to
  !> 1/2 rho c_D A_wp v^2, 4 kN, at first contact.)
  subroutine first_contact(state)
    type(case_state), intent(inout) :: state
    type(strip_model_type) :: s
    type(wave_field_type) :: calm
    real(wp) :: f(6), v, prev, jump, dz, awp, t0, bound, u(6), first
    integer :: i
    s = new_strip_model(paper_hull(20), [1.2_wp, 1.2_wp, 1.2_wp], 2.0_wp, &
                        [0.0_wp, 0.0_wp, 0.0_wp], mass, inertia)
    call new_calm_sea(calm)
    awp = hull_waterplane_area(s%hull)
    t0 = (mass/rho_water)/awp
    dz = 1.0e-4_wp
    u = [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.5_wp]
    bound = rho_water*gravity*awp*dz + 0.5_wp*rho_water*1.2_wp*awp*0.25_wp*dz/t0
    prev = 0.0_wp
    jump = 0.0_wp
    first = 0.0_wp
    do i = 0, 250
      call strip_loads(s, calm, 0.0_wp, rotation_matrix([0.0_wp, 0.0_wp, 0.0_wp]), &
                       [0.0_wp, 0.0_wp, -5.0e-3_wp + i*dz - 1.1_wp], u, f, v)
      if (first == 0.0_wp .and. f(6) /= 0.0_wp) first = abs(f(6))
      jump = max(jump, abs(f(6) - prev))
      prev = f(6)
    end do
    call note(state, "largest step in F3 over 0.1 mm (N)", jump)
    call note(state, "F3 at first wetting (N)", first)
    call check_true(state, jump <= 1.01_wp*bound, "no jump in the vertical load")
    call check_true(state, first <= 1.01_wp*bound, "first wetting starts from zero")
  end subroutine first_contact

  !> Dropped upright from rest with its keel h = 1 m above calm water, no drag or damping:
  !> energy m g (h + z) = rho g A_wp z^2/2 (wall-sided hull, constant A_wp; no added mass,
  !> which issue 18's radiation model adds) gives the deepest keel immersion
  !> z_max = T0 (1 + sqrt(1 + 2 h/T0)), T0 = m/(rho A_wp): 1.175 m. Within 0.2 %.
  subroutine drop_test(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t, t0, zmax, expected, z
    integer :: i
    cfg = deck_config(still_deck//"&boat water_model = 'pressure' drag_coefficients = "// &
                      "0.0, 0.0, 0.0 zeta = 0, 0, 0 /")
    cfg%boat%position = [0.0_wp, 0.0_wp, -1.0_wp - 1.1_wp]
    y = new_test_system(sys, cfg)
    t0 = (mass/rho_water)/hull_waterplane_area(paper_hull(20))
    expected = t0*(1 + sqrt(1 + 2*1.0_wp/t0))
    call rk%init(size(y))
    t = 0.0_wp
    zmax = -huge(1.0_wp)
    do i = 1, 2500
      call rk%step(sys, t, y, 1.0e-3_wp)
      call sys%after_step(t, y)
      z = y(6) + 1.1_wp
      zmax = max(zmax, z)
    end do
    call note(state, "energy estimate z_max (m)", expected)
    call note(state, "simulated z_max (m)", zmax)
    call check(state, zmax, expected, "entry depth vs energy balance", rel_tol=2e-3_wp)
  end subroutine drop_test

  !> Dynamic section load p' of many components (the vectorised blocks, both window ends in
  !> one pass) against the pressure integrated here along each wet hull edge: composite
  !> 8-point Gauss-Legendre, 16 panels per edge, of, per component,
  !>   p' = rho g a [exp(-k d) cos(theta_c - phi) - cos theta_c - sin theta_c phi]
  !> (d = d0 + gy y + gz z the tangent-plane depth, phi = k . dx the phase lag of the point's
  !> horizontal offset dx from the strip centre, theta_c the phase there) and its time
  !> derivative -rho g a w [exp(-k d) sin(theta_c - phi) - sin theta_c + cos theta_c phi];
  !> force -t_s int p' n dl with n the outward normal (pointing away from the wet centroid),
  !> M1 = int (y dF3 - z dF2). Per panel |z|/16 < 0.85 (|z| < 13 here): the rule's error
  !> is far below 1e-16.
  !> The Level 5 sea (1300 components: ten full blocks and a partial one) and a short-wave
  !> band 3-6 rad/s, on a rectangle, a triangle and a pentagon (heeled) of the 2.8 m section
  !> of a rotated boat; both edge branches (series below |z| = 0.5, closed form above) are
  !> exercised (checked). Agreement to 1e-12 of the largest load term.
  subroutine irregular_section(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    type(boat_hull_type) :: h
    type(section_wet_type) :: wet
    real(wp), parameter :: shapes(3, 3) = reshape([-0.6_wp, 0.02_wp, 1.0_wp, &
                                                   -0.3_wp, 0.8_wp, 0.6_wp, &
                                                   1.0_wp, 0.8_wp, 0.6_wp], [3, 3])
    integer, parameter :: vertices(3) = [4, 3, 5]
    real(wp), parameter :: times(2) = [37.3_wp, 37.35_wp], pk(3) = [1.7_wp, 13.3_wp, -0.4_wp]
    real(wp) :: c(3, 3), load(3, 2), rate(3, 2), ref_load(3, 2), ref_rate(3, 2), err, zmin, zmax
    integer :: is, ish, j
    c = rotation_matrix([0.1_wp, 0.05_wp, 0.3_wp])
    h = paper_hull(20)
    err = 0.0_wp
    zmin = huge(1.0_wp)
    zmax = 0.0_wp
    do is = 1, 2
      rng = new_rng(11)
      if (is == 1) then
        call new_irregular_sea(field, 4.0_wp, pi/2, 2, pi/2, 100, 13, 0.3_wp, 3.0_wp, &
                               .true., .true., rng, 0.0_wp)
      else
        call new_irregular_sea(field, 4.0_wp, 0.7_wp, 2, pi/2, 40, 13, 3.0_wp, 6.0_wp, &
                               .true., .true., rng, 0.0_wp)
      end if
      do ish = 1, 3
        associate (d0 => shapes(1, ish), gy => shapes(2, ish), gz => shapes(3, ish))
          wet = section_immersion(h, 10, d0, gy, gz)
          call check_true(state, wet%m == vertices(ish), "wet polygon has the planned corners")
          call section_wave_loads(field, times, h, wet, c, pk, d0, gy, gz, load, rate)
          do j = 1, 2
            call quadrature_load(field, times(j), h%thickness, wet, c, pk, d0, gy, gz, &
                                 ref_load(:, j), ref_rate(:, j), zmin, zmax)
            err = max(err, maxval(abs(load(:, j) - ref_load(:, j)))/maxval(abs(ref_load(:, j))), &
                      maxval(abs(rate(:, j) - ref_rate(:, j)))/maxval(abs(ref_rate(:, j))))
          end do
        end associate
      end do
    end do
    call note(state, "smallest edge |z|", zmin)
    call note(state, "largest edge |z|", zmax)
    call note(state, "largest error / largest load term", err)
    call check_true(state, zmin < 0.5_wp .and. zmax > 0.5_wp, "both edge branches exercised")
    call check(state, err, 0.0_wp, "section load vs edge quadrature", abs_tol=1e-12_wp)
  end subroutine irregular_section

  !> The section load's first derivatives (section_wave_loads' sens, with which the strips'
  !> window expands the load about its sampled geometry) against central differences of the
  !> load with the wet polygon found again at each perturbed geometry: the section's
  !> immersion d0, its centre's horizontal travel, the tangent plane's slopes gy, gz across
  !> it (the fixed polygon's depths and the waterline moving along the hull's sides) and the
  !> horizontal parts of the rotation's columns b2, b3 (the lags of its points); e = 1e-5,
  !> so the differences' truncation is ~1e-9 of a derivative. The Level 5 sea (1300
  !> components) on the section heeled so that the surface cuts both sides; agreement to
  !> 1e-6 of each derivative's largest term. Dropping the waterline's share fails the
  !> immersion and slope rows (0.060, 0.054, 0.045), the rotation's the last four (1.0).
  subroutine section_sens(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    type(boat_hull_type) :: h
    real(wp), parameter :: times(2) = [37.3_wp, 37.45_wp], e = 1.0e-5_wp
    real(wp) :: c(3, 3), load(3, 2), sens(3, 9, 2), lp(3, 2), lm(3, 2)
    real(wp) :: fd(3, 9, 2), err, g(9), dg(9)
    character(len=*), parameter :: names(9) = [character(len=9) :: "immersion", "x-travel", &
                                                "y-travel", "gy-slope", "gz-slope", "c12", &
                                                "c22", "c13", "c23"]
    integer :: i
    c = rotation_matrix([0.1_wp, 0.05_wp, 0.3_wp])
    h = paper_hull(20)
    rng = new_rng(11)
    call new_irregular_sea(field, 4.0_wp, pi/2, 2, pi/2, 100, 13, 0.3_wp, 3.0_wp, &
                           .true., .true., rng, 0.0_wp)
    g = [0.6_wp, 1.7_wp, 13.3_wp, 0.3_wp, 0.95_wp, c(1:2, 2), c(1:2, 3)]
    call loads_at(g, load, sens)
    do i = 1, 9
      dg = 0.0_wp
      dg(i) = e
      call loads_at(g + dg, lp)
      call loads_at(g - dg, lm)
      fd(:, i, :) = (lp - lm)/(2.0_wp*e)
      err = maxval(abs(sens(:, i, :) - fd(:, i, :)))/maxval(abs(fd(:, i, :)))
      call check(state, err, 0.0_wp, trim(names(i))//" derivative vs differences", &
                 abs_tol=1e-6_wp)
    end do
    call note(state, "immersion derivative, largest term (N/m/m)", maxval(abs(fd(:, 1, :))))
    call note(state, "gy-slope derivative, largest term (N/m)", maxval(abs(fd(:, 4, :))))
  contains
    subroutine loads_at(geo, out, ds)
      real(wp), intent(in) :: geo(9)
      real(wp), intent(out) :: out(3, 2)
      real(wp), intent(out), optional :: ds(3, 9, 2)
      type(section_wet_type) :: wet
      real(wp) :: cg(3, 3), rate(3, 2)
      cg = c
      cg(1:2, 2) = geo(6:7)
      cg(1:2, 3) = geo(8:9)
      wet = section_immersion(h, 10, geo(1), geo(4), geo(5))
      call section_wave_loads(field, times, h, wet, cg, [geo(2), geo(3), -0.4_wp], geo(1), &
                              geo(4), geo(5), out, rate, sens=ds)
    end subroutine loads_at
  end subroutine section_sens

  !> The reference of irregular_section: p' summed per component at the quadrature points of
  !> each wet hull edge (the waterline, both ends cut, is no hull); zmin, zmax track the
  !> edges' exponent |z| = |k (d_B - d_A)| + i (phi_B - phi_A)|.
  subroutine quadrature_load(field, t, ts, wet, c, pk, d0, gy, gz, load, rate, zmin, zmax)
    type(wave_field_type), intent(in) :: field
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: t, ts, c(3, 3), pk(3), d0, gy, gz
    real(wp), intent(out) :: load(3), rate(3)
    real(wp), intent(inout) :: zmin, zmax
    integer, parameter :: panels = 16
    real(wp) :: a(2), b(2), n(2), len, y(2), dx(2), d, phi, thc, p, dp, s, wq, za, zb
    integer :: v, e, i, ip, ig
    load = 0.0_wp
    rate = 0.0_wp
    do v = 1, wet%m
      e = merge(1, v + 1, v == wet%m)
      if (wet%cut(v) .and. wet%cut(e)) cycle
      a = wet%poly(:, v)
      b = wet%poly(:, e)
      len = norm2(b - a)
      n = [b(2) - a(2), a(1) - b(1)]/len
      if (dot_product(n, 0.5_wp*(a + b) - wet%centroid) < 0.0_wp) n = -n
      do i = 1, field%n
        associate (k => field%k(i), kx => field%kx(i), ky => field%ky(i))
          za = dot_product([kx, ky], c(1:2, 2)*a(1) + c(1:2, 3)*a(2))
          zb = dot_product([kx, ky], c(1:2, 2)*b(1) + c(1:2, 3)*b(2))
          d = k*(gy*(b(1) - a(1)) + gz*(b(2) - a(2)))
          zmin = min(zmin, hypot(d, zb - za))
          zmax = max(zmax, hypot(d, zb - za))
          thc = field%omega(i)*t + field%phase(i) - kx*pk(1) - ky*pk(2)
          do ip = 1, panels
            do ig = 1, 8
              s = (ip - 1 + 0.5_wp*(gauss8_x(ig) + 1.0_wp))/panels
              wq = 0.5_wp*gauss8_w(ig)/panels
              y = a + s*(b - a)
              dx = c(1:2, 2)*y(1) + c(1:2, 3)*y(2)
              phi = kx*dx(1) + ky*dx(2)
              d = d0 + gy*y(1) + gz*y(2)
              p = rho_water*gravity*field%amplitude(i)*(exp(-k*d)*cos(thc - phi) - cos(thc) - &
                                                         sin(thc)*phi)
              dp = -rho_water*gravity*field%amplitude(i)*field%omega(i)* &
                   (exp(-k*d)*sin(thc - phi) - sin(thc) + cos(thc)*phi)
              load = load - ts*len*wq*p*[n(1), n(2), y(1)*n(2) - y(2)*n(1)]
              rate = rate - ts*len*wq*dp*[n(1), n(2), y(1)*n(2) - y(2)*n(1)]
            end do
          end do
        end associate
      end do
    end do
  end subroutine quadrature_load

  !> Quadratic drag (eq. 22) on the upright boat at its equilibrium draught T in calm
  !> water, moving at (vx, vy) with no rotation: every other load is vertical or cancels
  !> (tangent-plane pressure along n3, no dynamic pressure, heave damping on a zero
  !> relative heave, the symmetric hull's yaw moment), so the horizontal force is Morison's
  !> -rho C_D A v|v|/2 per direction with the review's areas: surge on the largest wet
  !> section b_max T, sway on the wet side L_wet T (each strip's t_s T). Distinct C_D per
  !> direction and both signs of v, so a changed factor, sign, area or index fails.
  subroutine calm_drag(state)
    type(case_state), intent(inout) :: state
    type(strip_model_type) :: s
    type(wave_field_type) :: calm
    real(wp), parameter :: cd(3) = [1.1_wp, 0.9_wp, 1.3_wp]
    real(wp) :: f(6), v, t0, vx, vy, fx, fy, side
    integer :: j
    s = new_strip_model(paper_hull(20), cd, 2.0_wp, [0.0_wp, 0.0_wp, 0.0_wp], mass, inertia)
    call new_calm_sea(calm)
    t0 = (mass/rho_water)/hull_waterplane_area(s%hull)
    side = s%hull%thickness*t0*real(count(s%hull%breadth > 0.0_wp), wp)
    do j = 1, 2
      vx = merge(0.7_wp, -1.3_wp, j == 1)
      vy = merge(-0.4_wp, 0.25_wp, j == 1)
      call strip_loads(s, calm, 0.0_wp, rotation_matrix([0.0_wp, 0.0_wp, 0.0_wp]), &
                       [0.0_wp, 0.0_wp, t0 - 1.1_wp], [0.0_wp, 0.0_wp, 0.0_wp, vx, vy, &
                                                       0.0_wp], f, v)
      fx = -0.5_wp*rho_water*cd(1)*maxval(s%hull%breadth)*t0*abs(vx)*vx
      fy = -0.5_wp*rho_water*cd(2)*side*abs(vy)*vy
      call note(state, "surge drag (N)", f(4))
      call note(state, "sway drag (N)", f(5))
      call check(state, f(4), fx, "surge: -rho C_D1 b_max T vx|vx|/2", rel_tol=1e-9_wp)
      call check(state, f(5), fy, "sway: -rho C_D2 L_wet T vy|vy|/2", rel_tol=1e-9_wp)
      call check(state, f(3), 0.0_wp, "no yaw moment on the symmetric hull", &
                 abs_tol=1e-9_wp*abs(fy))
    end do
  end subroutine calm_drag

end module test_strip_pressure
