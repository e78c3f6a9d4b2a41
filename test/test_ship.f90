!> Ship: Froude-Krylov box loads in closed form (review §1.8) against direct pressure
!> integration over the box faces, and their long-wave limits (review A3).
module test_ship
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_ship_froude_krylov, only: box_type, fk_box_load, fk_transfer
  use davit_ship_wind_load, only: ship_wind_type, ship_wind_load
  use davit_kinds, only: rho_air
  use davit_ship_section_added_mass, only: section_added_mass, rectangle_contour, &
                                           ellipse_contour
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_ship_hull, only: hull_type, new_hull, hull_natural_periods
  use davit_ship_ship_model, only: ship_system_type
  use davit_run_ship_scene, only: build_ship_scene
  use davit_system_build, only: ship_initial_state
  use davit_solve_rk4, only: rk4_type
  use davit_run_rao, only: rao_case
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_ship

  real(wp), parameter :: zero12(12) = 0.0_wp

contains

  function collect_ship() result(suite)
    type(suite_type) :: suite
    suite%name = "ship"
    suite%cases = [new_case("fk_closed_form_vs_quadrature", fk_quadrature), &
                   new_case("fk_long_wave_limits_A3", fk_long_wave), &
                   new_case("beam_wind_pushes_and_heels_to_port", wind_signs), &
                   new_case("section_added_mass_exact_shapes", section_exact), &
                   new_case("hull_derived_quantities_G9_G11", hull_derived), &
                   new_case("calm_water_rest_600s", calm_rest), &
                   new_case("free_decay_periods", free_decay), &
                   new_case("beam_wind_motion", beam_wind_motion), &
                   new_case("rao_long_wave_heave_and_roll_peak", rao_checks), &
                   new_case("headway_held_straight", headway), &
                   new_case("oblique_roll_rao_follows_excitation", oblique_roll), &
                   new_case("heading_keeping_period_and_integral", heading_keeping)]
  end function collect_ship

  !> Gauss-Legendre nodes and weights on (-1, 1) by Newton iteration on P_n.
  subroutine gauss_legendre(n, x, w)
    integer, intent(in) :: n
    real(wp), intent(out) :: x(n), w(n)
    real(wp) :: z, p0, p1, p2, dp
    integer :: i, j, it
    do i = 1, n
      z = cos(pi*(i - 0.25_wp)/(n + 0.5_wp))
      do it = 1, 100
        p0 = 1.0_wp; p1 = z
        do j = 2, n
          p2 = ((2*j - 1)*z*p1 - (j - 1)*p0)/j
          p0 = p1; p1 = p2
        end do
        dp = n*(z*p1 - p0)/(z*z - 1.0_wp)
        if (abs(p1/dp) < 1e-16_wp) exit
        z = z - p1/dp
      end do
      x(i) = z
      w(i) = 2.0_wp/((1.0_wp - z*z)*dp*dp)
    end do
  end subroutine gauss_legendre

  !> Composite Gauss rule on (a, b): npan panels of ng points.
  subroutine composite(a, b, npan, ng, x, w)
    real(wp), intent(in) :: a, b
    integer, intent(in) :: npan, ng
    real(wp), allocatable, intent(out) :: x(:), w(:)
    real(wp) :: gx(ng), gw(ng), h
    integer :: p
    call gauss_legendre(ng, gx, gw)
    allocate (x(npan*ng), w(npan*ng))
    h = (b - a)/npan
    do p = 1, npan
      x((p - 1)*ng + 1:p*ng) = a + (p - 0.5_wp)*h + 0.5_wp*h*gx
      w((p - 1)*ng + 1:p*ng) = 0.5_wp*h*gw
    end do
  end subroutine composite

  !> -integral of p n dS and its moment about O', over the five wetted faces.
  function quadrature_load(box, zeta, k, chi, phi) result(load)
    type(box_type), intent(in) :: box
    real(wp), intent(in) :: zeta, k, chi, phi
    real(wp) :: load(6)
    real(wp), allocatable :: xs(:), wx(:), ys(:), wy(:), zs(:), wz(:)
    real(wp) :: l, b, d, r(3), n(3), df(3)
    integer :: i, j, face
    l = box%length; b = box%beam; d = box%draught
    call composite(-l/2, l/2, 24, 16, xs, wx)
    call composite(-b/2, b/2, 6, 16, ys, wy)
    call composite(0.0_wp, d, 2, 16, zs, wz)
    load = 0.0_wp
    ! bottom z = d, outward normal +z
    do i = 1, size(xs)
      do j = 1, size(ys)
        r = [xs(i), ys(j), d]; n = [0.0_wp, 0.0_wp, 1.0_wp]
        call add(r, n, wx(i)*wy(j))
      end do
    end do
    ! sides y = -+B/2
    do face = -1, 1, 2
      do i = 1, size(xs)
        do j = 1, size(zs)
          r = [xs(i), face*b/2, zs(j)]; n = [0.0_wp, real(face, wp), 0.0_wp]
          call add(r, n, wx(i)*wz(j))
        end do
      end do
    end do
    ! ends x = -+l/2
    do face = -1, 1, 2
      do i = 1, size(ys)
        do j = 1, size(zs)
          r = [face*l/2, ys(i), zs(j)]; n = [real(face, wp), 0.0_wp, 0.0_wp]
          call add(r, n, wy(i)*wz(j))
        end do
      end do
    end do
  contains
    subroutine add(r, n, weight)
      real(wp), intent(in) :: r(3), n(3), weight
      real(wp) :: p
      p = rho_water*gravity*zeta*exp(-k*r(3))*cos(phi - k*r(1)*cos(chi) - k*r(2)*sin(chi))
      df = -p*n*weight
      load(1:3) = load(1:3) + df
      load(4:6) = load(4:6) + [r(2)*df(3) - r(3)*df(2), r(3)*df(1) - r(1)*df(3), &
                               r(1)*df(2) - r(2)*df(1)]
    end subroutine add
  end function quadrature_load

  !> Table 1 box: l = sqrt(C_b) L_wl = 107.65 m, B = 20.8 m, d = 4.4 m; headings 0-180 deg
  !> and a random one, wave periods 5-16 s. Each component to 1e-8 of its scale
  !> (rho g zeta l B for forces, times l for moments).
  subroutine fk_quadrature(state)
    type(case_state), intent(inout) :: state
    type(box_type) :: box
    real(wp), parameter :: chis(7) = [0.0_wp, 45.0_wp, 90.0_wp, 135.0_wp, 180.0_wp, &
                                      -63.0_wp, 17.3_wp]
    real(wp), parameter :: periods(3) = [5.0_wp, 9.0_wp, 16.0_wp]
    real(wp) :: exact(6), quad(6), k, scale, worst, phi
    integer :: i, j, c
    box = box_type(107.65_wp, 20.8_wp, 4.4_wp)
    worst = 0.0_wp
    do i = 1, size(chis)
      do j = 1, size(periods)
        k = (2*pi/periods(j))**2/gravity
        phi = 0.3_wp + i + 2*j
        exact = fk_box_load(box, 1.3_wp, k, chis(i)*pi/180, phi)
        quad = quadrature_load(box, 1.3_wp, k, chis(i)*pi/180, phi)
        do c = 1, 6
          scale = rho_water*gravity*1.3_wp*box%length*box%beam
          if (c > 3) scale = scale*box%length
          call check(state, exact(c), quad(c), "FK component", abs_tol=1e-8_wp*scale)
          worst = max(worst, abs(exact(c) - quad(c))/scale)
        end do
      end do
    end do
    call note(state, "max |closed - quadrature|/scale", worst)
  end subroutine fk_quadrature

  !> Long waves: Z -> -rho g zeta l B cos(Phi); in beam seas the roll moment about G tends
  !> to the wave-slope excitation -rho g V GM_box k zeta sin(Phi), with the box's own
  !> metacentric height for G on the waterline (z_G = 0): KB = d/2, BM = B^2/(12 d),
  !> GM = BM + KB - KG = B^2/(12 d) - d/2.
  subroutine fk_long_wave(state)
    type(case_state), intent(inout) :: state
    type(box_type) :: box
    real(wp) :: k, load(6), vol, gm, phi, zeta
    box = box_type(107.65_wp, 20.8_wp, 4.4_wp)
    k = 1.0e-6_wp
    phi = 0.7_wp
    zeta = 1.0_wp
    load = fk_box_load(box, zeta, k, 0.0_wp, phi)
    call check(state, load(3), -rho_water*gravity*zeta*box%length*box%beam*cos(phi), &
               "heave force, long head wave", rel_tol=1e-5_wp)
    load = fk_transfer(fk_box_load(box, zeta, k, 0.5_wp*pi, phi), 0.0_wp, 0.0_wp)
    vol = box%length*box%beam*box%draught
    gm = box%beam**2/(12*box%draught) - box%draught/2
    call check(state, load(4), -rho_water*gravity*vol*gm*k*zeta*sin(phi), &
               "beam-sea roll moment about G = wave-slope excitation", rel_tol=1e-4_wp)
    ! Long wave along +x: the pressure is ~ rho g eta(x), eta ~ zeta (cos Phi + k x sin Phi).
    ! Bottom: M = -x F_z = rho g B integral x eta dx = rho g zeta k B l^3/12 sin Phi.
    ! Ends: M = z F_x = -rho g B d^2/2 (eta(l/2) - eta(-l/2)) = -rho g zeta k B l d^2/2 sin Phi.
    ! Bow up (positive about +y with z down) when the surface rises towards the bow. The
    ! review's A3 text prints the bottom term with a minus sign; its own closed form (and
    ! the quadrature above) give the sign derived here.
    load = fk_box_load(box, zeta, k, 0.0_wp, phi)
    call check(state, load(5), rho_water*gravity*zeta*k*box%beam*(box%length**3/12 - &
               box%length*box%draught**2/2)*sin(phi), "pitch moment, long wave along x", &
               rel_tol=1e-5_wp)
  end subroutine fk_long_wave

  !> Wind from starboard (air moving towards port, -y) must push the ship to port (Y < 0)
  !> and heel it to port (K < 0 about x forward with z down) with the G14 magnitude; a head
  !> wind pushes it astern; neither gives a yaw moment (sin 2 alpha = 0).
  subroutine wind_signs(state)
    type(case_state), intent(inout) :: state
    type(ship_wind_type) :: w
    real(wp) :: load(6), q
    q = 0.5_wp*rho_air*10.0_wp**2
    load = ship_wind_load(w, [0.0_wp, -10.0_wp, 0.0_wp])
    call check(state, load(2), -0.85_wp*q*w%area_lateral, "Y of a beam wind from starboard", &
               rel_tol=1e-12_wp)
    call check(state, load(4), -0.85_wp*q*w%area_lateral*w%height, "K: heel to port", &
               rel_tol=1e-12_wp)
    call check(state, load(1), 0.0_wp, "no surge force", abs_tol=1e-9_wp*q*w%area_front)
    call check(state, load(6), 0.0_wp, "no yaw moment", &
               abs_tol=1e-9_wp*q*w%area_lateral*w%length_overall)
    load = ship_wind_load(w, [-10.0_wp, 0.0_wp, 0.0_wp])
    call check(state, load(1), -0.7_wp*q*w%area_front, "head wind pushes astern", &
               rel_tol=1e-12_wp)
    load = ship_wind_load(w, [0.0_wp, 10.0_wp, 0.0_wp])
    call check(state, load(2), 0.85_wp*q*w%area_lateral, "wind from port pushes to starboard", &
               rel_tol=1e-12_wp)
  end subroutine wind_signs

  !> Infinite-frequency added masses of half-ellipses, whose doubled body is a full
  !> ellipse in unbounded fluid: heave rho pi b^2/2 (b the half-beam), roll about the
  !> waterline centre (pi/16) rho (b^2 - t^2)^2; a semicircle does not roll any water.
  subroutine section_exact(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: shapes(2, 3) = reshape([1.0_wp, 1.0_wp, 10.4_wp, 4.4_wp, &
                                                   2.0_wp, 5.0_wp], [2, 3])
    real(wp), allocatable :: y(:), z(:)
    real(wp) :: a(4), b, t
    type(error_type), allocatable :: error
    integer :: k
    do k = 1, size(shapes, 2)
      b = shapes(1, k); t = shapes(2, k)
      call ellipse_contour(b, t, 400, y, z)
      call section_added_mass(y, z, a, error)
      call check_true_err(error)
      call check(state, a(2), rho_water*pi*b**2/2, "half-ellipse heave", rel_tol=5e-3_wp)
      call check(state, a(3), pi/16*rho_water*(b**2 - t**2)**2, "half-ellipse roll", &
                 rel_tol=1e-2_wp, abs_tol=1e-3_wp*rho_water*b**4)
      if (k == 2) call note(state, "B 20.8, T 4.4 half-ellipse heave / exact", &
                            a(2)/(rho_water*pi*b**2/2))
    end do
    call rectangle_contour(20.8_wp, 4.4_wp, 40, 120, y, z)
    call section_added_mass(y, z, a, error)
    call note(state, "rectangle 20.8 x 4.4: a22 [t/m]", a(1)/1e3_wp)
    call note(state, "rectangle 20.8 x 4.4: a33 [t/m]", a(2)/1e3_wp)
    call note(state, "rectangle 20.8 x 4.4: a44 [t m^2/m]", a(3)/1e3_wp)
    call note(state, "rectangle a33 / (rho pi B^2/8)", a(2)/(rho_water*pi*20.8_wp**2/8))
  contains
    subroutine check_true_err(err)
      type(error_type), allocatable, intent(in) :: err
      if (allocated(err)) call check(state, 1.0_wp, 0.0_wp, err%message)
    end subroutine check_true_err
  end subroutine section_exact

  !> Table 1 defaults give the review's derived numbers (G9, G11, §1.8).
  subroutine hull_derived(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(hull_type) :: hull
    type(error_type), allocatable :: error
    real(wp) :: t(3)
    call parse_config("t.nml", "", cfg, error)
    call new_hull(hull, cfg%ship, error)
    call check(state, merge(1.0_wp, 0.0_wp, allocated(error)), 0.0_wp, "hull built")
    call check(state, hull%box%length, 107.65_wp, "box length sqrt(Cb) Lwl", abs_tol=0.01_wp)
    call check(state, hull%c33, 2.25e7_wp, "C33", rel_tol=5e-3_wp)
    call check(state, hull%c44, 4.13e8_wp, "C44", rel_tol=5e-3_wp)
    call check(state, hull%c55, 2.18e10_wp, "C55", rel_tol=5e-3_wp)
    call check(state, hull%inertia(1), 4.72e8_wp, "I_xx", rel_tol=5e-3_wp)
    call check(state, hull%inertia(2), 7.49e9_wp, "I_yy", rel_tol=5e-3_wp)
    t = hull_natural_periods(hull)
    call note(state, "A33/Delta", hull%added_mass(3)/hull%mass)
    call note(state, "A22/Delta", hull%added_mass(2)/hull%mass)
    call note(state, "A44/I_xx", hull%added_inertia(1)/hull%inertia(1))
    call note(state, "A55/I_yy", hull%added_inertia(2)/hull%inertia(2))
    call note(state, "heave period [s]", t(1))
    call note(state, "roll period [s]", t(2))
    call note(state, "pitch period [s]", t(3))
  end subroutine hull_derived

  !> Build the ship scene of a deck; integrate n RK4 steps of dt, sampling component k.
  subroutine ship_run(deck, y0_offset, dt, n, k, s, final)
    character(len=*), intent(in) :: deck
    real(wp), intent(in) :: y0_offset(12), dt
    integer, intent(in) :: n, k
    real(wp), intent(out) :: s(0:n), final(12)
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t
    integer :: i
    call parse_config("ship.nml", deck, cfg, error)
    if (allocated(error)) error stop "ship test deck"
    call build_ship_scene(cfg, ship, y, error)
    y = y + y0_offset
    call rk%init(size(y))
    t = 0.0_wp
    s(0) = y(k)
    do i = 1, n
      call rk%step(ship, t, y, dt)
      call ship%after_step(t, y)
      s(i) = y(k)
    end do
    final = y
  end subroutine ship_run

  !> Mean period of upward mean crossings.
  real(wp) function crossing_period(s, dt) result(period)
    real(wp), intent(in) :: s(0:), dt
    real(wp) :: mean, first, last
    integer :: i, nc
    mean = sum(s)/size(s)
    nc = 0; first = 0; last = 0
    do i = 1, ubound(s, 1)
      if (s(i - 1) < mean .and. s(i) >= mean) then
        last = (i - 1 + (mean - s(i - 1))/(s(i) - s(i - 1)))*dt
        if (nc == 0) first = last
        nc = nc + 1
      end if
    end do
    period = -1
    if (nc >= 2) period = (last - first)/(nc - 1)
  end function crossing_period

  !> Calm water, no wind, at rest in equilibrium (with a list): nothing moves in 600 s.
  subroutine calm_rest(state)
    type(case_state), intent(inout) :: state
    real(wp) :: s(0:30000), final(12)
    call ship_run("&ship list_deg = 5 / &wind speed = 0 /", zero12, &
                  0.02_wp, 30000, 1, s, final)
    call check(state, maxval(abs(final(4:12))), 0.0_wp, "no drift of position and speeds", &
               abs_tol=1e-12_wp)
    call check(state, final(1), 5*pi/180, "the list is held", abs_tol=1e-12_wp)
  end subroutine calm_rest

  !> Undamped free decay of heave, roll and pitch: periods of the model's own mass, added
  !> mass and restoring (2 %).
  subroutine free_decay(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: deck = "&ship zeta_heave = 0, zeta_roll = 0, "// &
                                          "zeta_pitch = 0, crossflow_cd = 0 / &wind speed = 0 /"
    real(wp), parameter :: dt = 0.01_wp
    integer, parameter :: n = 6000
    real(wp) :: s(0:n), final(12), offset(12), expected(3)
    type(config_type) :: cfg
    type(hull_type) :: hull
    type(error_type), allocatable :: error
    integer :: mode
    integer, parameter :: index_of(3) = [6, 1, 2]
    character(len=5), parameter :: names(3) = ["heave", "roll ", "pitch"]
    call parse_config("t.nml", deck, cfg, error)
    call new_hull(hull, cfg%ship, error)
    expected = hull_natural_periods(hull)
    do mode = 1, 3
      offset = 0.0_wp
      offset(index_of(mode)) = merge(0.2_wp, 0.02_wp, mode == 1)
      call ship_run(deck, offset, dt, n, index_of(mode), s, final)
      call note(state, trim(names(mode))//" period simulated [s]", crossing_period(s, dt))
      call note(state, trim(names(mode))//" period analytic [s]", expected(mode))
      call check(state, crossing_period(s, dt), expected(mode), trim(names(mode))//" period", &
                 rel_tol=0.02_wp)
    end do
  end subroutine free_decay

  !> A beam wind from starboard (blowing towards -y) drives the ship to port and heels it to
  !> port; with roll damped, the heel settles at K/C44.
  subroutine beam_wind_motion(state)
    type(case_state), intent(inout) :: state
    real(wp) :: s(0:20000), final(12), heel
    type(ship_wind_type) :: w
    type(config_type) :: cfg
    type(hull_type) :: hull
    type(error_type), allocatable :: error
    real(wp) :: load(6)
    character(len=*), parameter :: deck = "&ship zeta_roll = 0.3 / "// &
                                          "&wind speed = 20, direction_deg = -90 /"
    call ship_run(deck, zero12, 0.02_wp, 20000, 1, s, final)
    call parse_config("t.nml", deck, cfg, error)
    call new_hull(hull, cfg%ship, error)
    ! at steady drift the relative wind is smaller; use the recorded sway speed
    load = ship_wind_load(hull%wind, [0.0_wp, -20.0_wp - final(11), 0.0_wp])
    heel = load(4)/hull%c44
    call check_true_local(final(5) < -1.0_wp, "drifted to port (y < 0)")
    call check_true_local(final(1) < 0.0_wp, "heeled to port (roll < 0)")
    call note(state, "steady heel [deg]", final(1)*180/pi)
    call check(state, final(1), heel, "heel = K/C44", rel_tol=0.02_wp)
    w = hull%wind
  contains
    subroutine check_true_local(c, what)
      logical, intent(in) :: c
      character(len=*), intent(in) :: what
      call check(state, merge(1.0_wp, 0.0_wp, c), 1.0_wp, what)
    end subroutine check_true_local
  end subroutine beam_wind_motion

  !> Head seas, omega -> 0: the ship follows the surface, heave RAO -> 1 (the box's long-wave
  !> heave force -rho g zeta l B equals C33 zeta; residual 1/(1 - (w/w3)^2) = 1.5 % at
  !> 0.1 rad/s). Beam seas: roll RAO largest at the frequency closest to the roll
  !> natural frequency 2 pi/T44 (ten frequencies 0.55-1.0 rad/s).
  subroutine rao_checks(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(hull_type) :: hull
    type(error_type), allocatable :: error
    real(wp) :: amp(6), phase(6), roll(10), w(10), wn(3)
    integer :: i
    call parse_config("t.nml", "&rao settle_time = 150, measure_periods = 4 /", cfg, error)
    call rao_case(cfg, 0.1_wp, pi, amp, phase, error)
    call note(state, "head-sea heave RAO at 0.1 rad/s", amp(3))
    call check(state, amp(3), 1.0_wp, "heave RAO -> 1", rel_tol=0.03_wp)
    call new_hull(hull, cfg%ship, error)
    wn = 2*pi/hull_natural_periods(hull)
    do i = 1, 10
      w(i) = 0.55_wp + 0.05_wp*(i - 1)
      call rao_case(cfg, w(i), 0.5_wp*pi, amp, phase, error)
      roll(i) = amp(4)
    end do
    call note(state, "roll natural frequency [rad/s]", wn(2))
    call note(state, "frequency of the largest roll RAO [rad/s]", w(maxloc(roll, 1)))
    call check(state, w(maxloc(roll, 1)), wn(2), "roll RAO peak at the roll frequency", &
               abs_tol=0.025_wp + 1e-9_wp)
  end subroutine rao_checks

  !> 5 kn headway in calm water: the thrust holds the speed and the ship runs straight;
  !> after a yaw-rate kick the MMG yaw damping (N'_r < 0) slows the turn faster than the
  !> zero-speed cross-flow drag alone does.
  subroutine headway(state)
    type(case_state), intent(inout) :: state
    real(wp) :: s(0:5000), final(12), kick(12), r_moving, r_still
    call ship_run("&ship headway = 2.57 / &wind speed = 0 /", zero12, 0.02_wp, 5000, 10, &
                  s, final)
    call check(state, final(10), 2.57_wp, "speed held", rel_tol=1e-9_wp)
    call check(state, maxval(abs(final([1, 2, 3, 6, 7, 8, 9, 11, 12]))), 0.0_wp, &
               "straight and level", abs_tol=1e-12_wp)
    call check(state, final(4), 2.57_wp*100, "distance run in 100 s", rel_tol=1e-9_wp)
    kick = 0.0_wp
    kick(9) = 0.01_wp
    call ship_run("&ship headway = 2.57 / &wind speed = 0 /", kick, 0.02_wp, 1000, 9, s, final)
    r_moving = abs(final(9))
    call ship_run("&wind speed = 0 /", kick, 0.02_wp, 1000, 9, s, final)
    r_still = abs(final(9))
    call note(state, "yaw rate after 20 s, 5 kn / at rest", r_moving/r_still)
    call check(state, merge(1.0_wp, 0.0_wp, r_moving < r_still), 1.0_wp, &
               "yaw damped more when making way")
  end subroutine headway

  !> Roll is a single-DOF response to the roll moment: the 135 deg roll RAO must equal the
  !> beam-sea RAO times the ratio of the closed-form roll excitations at the same frequency
  !> (same natural frequency and damping), off and at resonance. 5 %.
  subroutine oblique_roll(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(box_type) :: box
    real(wp) :: amp90(6), amp135(6), phase(6), k, ratio, w
    integer :: i
    real(wp), parameter :: omegas(2) = [0.5_wp, 0.75_wp]
    call parse_config("t.nml", "&rao settle_time = 250, measure_periods = 10 /", cfg, error)
    box = box_type(sqrt(cfg%ship%cb)*cfg%ship%lwl, cfg%ship%beam, cfg%ship%draught)
    do i = 1, 2
      w = omegas(i)
      k = w*w/gravity
      ratio = fk_roll(0.75_wp*pi)/fk_roll(0.5_wp*pi)
      call rao_case(cfg, w, 0.5_wp*pi, amp90, phase, error)
      call rao_case(cfg, w, 0.75_wp*pi, amp135, phase, error)
      call note(state, "roll RAO 135/90 at "//trim(merge("0.50", "0.75", i == 1)), &
                amp135(4)/amp90(4))
      call note(state, "roll excitation ratio", ratio)
      call check(state, amp135(4)/amp90(4), abs(ratio), "oblique roll RAO", rel_tol=0.05_wp)
    end do
  contains
    real(wp) function fk_roll(chi)
      real(wp), intent(in) :: chi
      real(wp) :: load(6)
      load = fk_box_load(box, 1.0_wp, k, chi, 0.5_wp*pi)
      fk_roll = load(4)
    end function fk_roll
  end subroutine oblique_roll

  !> Heading keeping (the launch scene's PID yaw moment, set_mooring): (1) as a pure
  !> spring (no damping, no integral, calm, no cross-flow drag) the yaw released 0.05 rad
  !> off swings with the set period T = 2 pi sqrt((I_zz + A_66)/k) (first zero crossing at
  !> T/4 within 1 %); (2) in a steady oblique wind, whose yaw moment N holds a PD-kept ship
  !> off by N/k, the integral term takes the mean error out (< 5 % of the PD offset over the
  !> last 100 s of 600 s).
  subroutine heading_keeping(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    real(wp), allocatable :: y(:)
    real(wp) :: t_cross, offset_pd, offset_pid
    real(wp), parameter :: period = 30.0_wp
    call parse_config("t.nml", "&ship crossflow_cd = 0 / &wind speed = 0 /", cfg, error)
    call build_ship_scene(cfg, ship, y, error)
    call ship%set_mooring([0.0_wp, 0.0_wp, period], 0.0_wp, y)
    y(ship%par%body%q(1) + 2) = 0.05_wp
    t_cross = first_crossing(ship, y, ship%par%body%q(1) + 2, ship%heading_setpoint())
    call note(state, "first zero crossing / (T/4)", t_cross/(0.25_wp*period))
    call check(state, t_cross, 0.25_wp*period, "spring period", rel_tol=0.01_wp)
    call parse_config("t.nml", "&ship heading_deg = 0 / &wind speed = 15, direction_deg = 60 /"// &
                      " &sea wave_type = 'calm' /", cfg, error)
    offset_pd = kept_offset(cfg, .false.)
    offset_pid = kept_offset(cfg, .true.)
    call note(state, "PD offset in the wind [deg]", offset_pd*180.0_wp/pi)
    call note(state, "PID offset in the wind [deg]", offset_pid*180.0_wp/pi)
    call check_true(state, abs(offset_pd) > 0.1_wp*pi/180.0_wp, &
                    "the wind holds a PD ship off (> 0.1 deg)")
    call check(state, offset_pid, 0.0_wp, "the integral takes the offset out", &
               abs_tol=0.05_wp*abs(offset_pd))
  end subroutine heading_keeping

  !> Time of the first crossing of y(k) through level, from rest.
  real(wp) function first_crossing(ship, y0, k, level) result(tc)
    type(ship_system_type), intent(inout) :: ship
    real(wp), intent(in) :: y0(:), level
    integer, intent(in) :: k
    type(rk4_type) :: rk
    real(wp) :: y(size(y0)), t, prev, dt
    integer :: i
    dt = 0.01_wp
    y = y0
    call rk%init(size(y))
    t = 0.0_wp
    tc = -1.0_wp
    prev = y(k) - level
    do i = 1, 10000
      call rk%step(ship, t, y, dt)
      t = real(i, wp)*dt
      call ship%after_step(t, y)
      if (sign(1.0_wp, y(k) - level) /= sign(1.0_wp, prev)) then
        tc = t - dt*(y(k) - level)/(y(k) - level - prev)
        return
      end if
      prev = y(k) - level
    end do
  end function first_crossing

  !> Mean yaw error over the last 100 s of 600 s with heading keeping (30 s, 0.7), PD or PID.
  real(wp) function kept_offset(cfg, integral) result(mean)
    type(config_type), intent(in) :: cfg
    logical, intent(in) :: integral
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t
    integer :: i, n
    call build_ship_scene(cfg, ship, y, error)
    call ship%set_mooring([0.0_wp, 0.0_wp, 30.0_wp], 0.7_wp, y, integral=integral)
    y = ship_initial_state(ship, cfg)
    call rk%init(size(y))
    t = 0.0_wp
    mean = 0.0_wp
    n = 0
    do i = 1, 12000
      call rk%step(ship, t, y, 0.05_wp)
      t = real(i, wp)*0.05_wp
      call ship%after_step(t, y)
      if (t > 500.0_wp) then
        mean = mean + y(ship%par%body%q(1) + 2) - ship%heading_setpoint()
        n = n + 1
      end if
    end do
    mean = mean/n
  end function kept_offset

end module test_ship
