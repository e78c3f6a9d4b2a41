!> Lifeboat in water and air, and its fenders inside the assembled system (issue "4.
!> Lifeboat"): strip kinematics (eq. 20), buoyancy (eq. 23), floating equilibrium and roll
!> period (eq. 24), free fall with quadratic air drag (eq. 15), and a fender impact.
module test_boat_water
  use davit_kinds, only: wp, pi, gravity, rho_water, rho_air
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_core_rotation, only: rotation_matrix
  use davit_core_body, only: body_qdot
  use davit_boat_strip_loads, only: strip_velocity, strip_partial_velocities, strip_loads
  use davit_boat_contact, only: hertz_elastoplastic_law_type, hertz_stiffness
  use davit_boat_fenders, only: side_plane_type, fender_set_type, new_fender_set, fender_probe
  use davit_core_rotation, only: cross
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, nstate, deck_config, system_hertz_peak
  use davit_solve_rk4, only: rk4_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_boat_water, strip_config

  !> A free boat (no slings) in still air, off the ship: the base of these tests.
  character(len=*), parameter :: free_deck = "&slings attached = .false. / "// &
                                             "&wind speed = 0.0 / &contact enabled = .false. /"

contains

  !> A deck's configuration with the paper's strips alone (&boat water_model = 'paper'):
  !> these tests check the strip physics (eqs. 18-25) and the 12-state free boat.
  function strip_config(text) result(cfg)
    character(len=*), intent(in) :: text
    type(config_type) :: cfg
    cfg = deck_config(text)
    cfg%boat%water_model = "paper"
  end function strip_config

  function collect_boat_water() result(suite)
    type(suite_type) :: suite
    suite%name = "boat_water"
    suite%cases = [new_case("strip_velocity_and_partials_eq20_vs_fd", strip_kinematics), &
                   new_case("buoyancy_equals_rho_g_v", buoyancy_volume), &
                   new_case("floating_equilibrium_60s", floating_equilibrium), &
                   new_case("floating_roll_period_h_m", roll_period), &
                   new_case("free_fall_and_terminal_velocity", free_fall), &
                   new_case("fender_impact_in_system", fender_impact), &
                   new_case("approach_rate_eq33_moving_side_vs_fd", moving_side_rate), &
                   new_case("fender_probe_deepest_point_vs_every_point", probe_deepest), &
                   new_case("contact_approach_graded_vs_window", contact_approach), &
                   new_case("strip_sway_drag_half_rho_cd_a_v2", sway_drag)]
  end function collect_boat_water


  !> Sum of the strip breadths B (1 - |2x/L|^4.3) at the strip centres times t_s: the
  !> waterplane area of the 20-strip hull [m^2] (review G25).
  pure real(wp) function waterplane_area()
    integer :: k
    real(wp) :: x
    waterplane_area = 0.0_wp
    do k = 1, 20
      x = -5.75_wp + (k - 0.5_wp)*11.5_wp/20.0_wp
      waterplane_area = waterplane_area + 2.8_wp*(1.0_wp - abs(2.0_wp*x/11.5_wp)**4.3_wp)
    end do
    waterplane_area = waterplane_area*11.5_wp/20.0_wp
  end function waterplane_area

  subroutine run(sys, y, dt, n)
    type(system_type), intent(inout) :: sys
    real(wp), intent(inout) :: y(:)
    real(wp), intent(in) :: dt
    integer, intent(in) :: n
    type(rk4_type) :: rk
    real(wp) :: t
    integer :: i
    call rk%init(size(y))
    t = 0.0_wp
    do i = 1, n
      call rk%step(sys, t, y, dt)
      call sys%after_step(t, y)
    end do
  end subroutine run

  !> Inertial position of the strip centre (x, 0, 0): C (q4..6 + x b1).
  pure function strip_position(q, x) result(p)
    real(wp), intent(in) :: q(6), x
    real(wp) :: p(3)
    p = matmul(rotation_matrix(q(1:3)), q(4:6) + [x, 0.0_wp, 0.0_wp])
  end function strip_position

  !> Strip velocity in b from central differences of its inertial position along the
  !> motion q' = q_dot(q, u): C^T (P(q + h q') - P(q - h q'))/(2h).
  pure function fd_velocity(q, u, x) result(v)
    real(wp), intent(in) :: q(6), u(6), x
    real(wp) :: v(3), qd(6)
    real(wp), parameter :: h = 1.0e-5_wp
    qd = body_qdot(q, u)
    v = matmul(strip_position(q + h*qd, x) - strip_position(q - h*qd, x), &
               rotation_matrix(q(1:3)))/(2.0_wp*h)
  end function fd_velocity

  !> v_k = (u4, u5 + x u3, u6 - x u2) (review §1.5) and the partial velocities of eq. (20)
  !> against finite differences of strip positions (and of those velocities in u).
  subroutine strip_kinematics(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: q(6) = [0.2_wp, -0.15_wp, 0.7_wp, 1.0_wp, -2.0_wp, 0.5_wp]
    real(wp), parameter :: u(6) = [0.3_wp, -0.4_wp, 0.25_wp, 1.5_wp, -0.7_wp, 0.9_wp]
    real(wp), parameter :: x = 3.7_wp, eps = 1.0e-3_wp
    real(wp) :: vr(3, 6), du(6), err_v, err_p
    integer :: r
    err_v = maxval(abs(strip_velocity(u, x) - fd_velocity(q, u, x)))
    vr = strip_partial_velocities(x)
    err_p = 0.0_wp
    do r = 1, 6
      du = 0.0_wp
      du(r) = eps
      err_p = max(err_p, maxval(abs(vr(:, r) - (fd_velocity(q, u + du, x) - &
                                                fd_velocity(q, u - du, x))/(2.0_wp*eps))))
    end do
    call note(state, "max |v - fd| (m/s)", err_v)
    call note(state, "max |v_r - fd| (-)", err_p)
    call check(state, err_v, 0.0_wp, "strip velocity vs FD of position", abs_tol=1e-7_wp)
    call check(state, err_p, 0.0_wp, "partial velocities vs FD", abs_tol=1e-6_wp)
  end subroutine strip_kinematics

  !> Wet volume of the 20-strip hull (piecewise-constant breadth, rectangular sections of
  !> height 3.1 m, keel 1.1 m below G) under the calm surface z = 0, counted on a 3-D
  !> midpoint grid: an independent V for the buoyancy check.
  real(wp) function grid_volume(euler, cg) result(v)
    real(wp), intent(in) :: euler(3), cg(3)
    integer, parameter :: nx = 8, ny = 280, nz = 620
    real(wp) :: c(3, 3), x, y, z, b, dx, dy, dz
    integer :: k, i, j, m
    c = rotation_matrix(euler)
    v = 0.0_wp
    do k = 1, 20
      dx = 11.5_wp/20.0_wp/nx
      x = -5.75_wp + (k - 0.5_wp)*11.5_wp/20.0_wp
      b = 2.8_wp*(1.0_wp - abs(2.0_wp*x/11.5_wp)**4.3_wp)
      dy = b/ny
      dz = 3.1_wp/nz
      do i = 1, nx
        x = -5.75_wp + (k - 1)*11.5_wp/20.0_wp + (i - 0.5_wp)*dx
        do j = 1, ny
          y = -0.5_wp*b + (j - 0.5_wp)*dy
          do m = 1, nz
            z = 1.1_wp - (m - 0.5_wp)*dz
            if (cg(3) + c(3, 1)*x + c(3, 2)*y + c(3, 3)*z > 0.0_wp) v = v + dx*dy*dz
          end do
        end do
      end do
    end do
  end function grid_volume

  !> Boat held at rest at a fixed draught, heel and trim in calm water: the non-gravity
  !> force is -rho g V N3 with V from the grid count (review §1.3).
  subroutine buoyancy_volume(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate), dydt(nstate), c(3, 3), fb(3), v
    real(wp), parameter :: euler(3) = [0.1_wp, 0.04_wp, 0.3_wp], cg(3) = [2.0_wp, -1.0_wp, -0.5_wp]
    cfg = strip_config(free_deck)
    cfg%boat%position = cg
    cfg%boat%euler = euler
    y = new_test_system(sys, cfg)
    call sys%rhs(0.0_wp, y, dydt)
    c = rotation_matrix(euler)
    fb = cfg%boat%mass*(matmul(c, dydt(10:12)) - [0.0_wp, 0.0_wp, gravity])
    v = grid_volume(euler, cg)
    call note(state, "grid V (m^3)", v)
    call note(state, "|F_B|/(rho g) (m^3)", norm2(fb)/(rho_water*gravity))
    call check(state, -fb(3), rho_water*gravity*v, "buoyancy = rho g V", rel_tol=1e-3_wp)
    call check(state, norm2(fb(1:2)), 0.0_wp, "buoyancy is vertical", &
               abs_tol=1e-9_wp*norm2(fb))
  end subroutine buoyancy_volume

  !> Boat released at its Archimedes draught T = m/(rho A_wp): zero net force and moment
  !> (accelerations < 1e-9 g), and no drift over 60 s of RK4.
  subroutine floating_equilibrium(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate), y0(nstate), dydt(nstate), draught
    cfg = strip_config(free_deck)
    draught = cfg%boat%mass/(rho_water*waterplane_area())
    cfg%boat%position = [0.0_wp, 0.0_wp, draught - 1.1_wp]
    y = new_test_system(sys, cfg)
    y0 = y
    call sys%rhs(0.0_wp, y, dydt)
    call note(state, "Archimedes draught (m)", draught)
    call check(state, maxval(abs(dydt(7:12))), 0.0_wp, "net force and moment", &
               abs_tol=1e-9_wp*gravity)
    call run(sys, y, 0.01_wp, 6000)
    call note(state, "max |y - y0| after 60 s", maxval(abs(y - y0)))
    call check(state, maxval(abs(y - y0)), 0.0_wp, "no drift over 60 s", abs_tol=1e-9_wp)
  end subroutine floating_equilibrium

  !> The paper's strips (water_model, roll_restoring = 'paper', set here explicitly).
  !> Small roll on calm water: T = 2 pi sqrt(I1/(m g h_m)) = 2.433 s (eq. 24, no added
  !> inertia in the paper's boat), measured from 10 upward zero crossings.
  subroutine roll_period(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(rk4_type) :: rk
    real(wp) :: y(nstate), t, dt, prev, first, last, expected
    integer :: i, ncross
    cfg = deck_config(free_deck//" &boat water_model = 'paper' roll_restoring = 'paper' /")
    cfg%boat%position = [0.0_wp, 0.0_wp, cfg%boat%mass/(rho_water*waterplane_area()) - 1.1_wp]
    cfg%boat%euler = [0.03_wp, 0.0_wp, 0.0_wp]
    y = new_test_system(sys, cfg)
    call rk%init(nstate)
    dt = 2.0e-3_wp
    t = 0.0_wp
    ncross = 0
    first = 0.0_wp
    last = 0.0_wp
    do i = 1, 15000
      prev = y(1)
      call rk%step(sys, t, y, dt)
      if (prev < 0.0_wp .and. y(1) >= 0.0_wp) then
        last = t - dt*y(1)/(y(1) - prev)
        if (ncross == 0) first = last
        ncross = ncross + 1
      end if
    end do
    expected = 2.0_wp*pi*sqrt(cfg%boat%inertia(1)/(cfg%boat%mass*gravity*2.0_wp))
    call note(state, "roll period (s)", (last - first)/(ncross - 1))
    call check(state, (last - first)/(ncross - 1), expected, "roll period vs h_m", &
               rel_tol=5e-3_wp)
  end subroutine roll_period

  !> In still air far above the water: with no drag z = z0 + g t^2/2 exactly (RK4 is exact
  !> on a quadratic); with the drag of eq. (15) on A3 the analytic fall
  !> v = v_t tanh(g t/v_t), z - z0 = v_t^2/g ln cosh(g t/v_t), v_t = sqrt(2 m g/(rho A3 C)).
  subroutine free_fall(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate), vt, t
    cfg = strip_config(free_deck//" &boat position = 0.0, 0.0, -5000.0 /")
    cfg%boat%wind_drag_coefficient = 0.0_wp
    y = new_test_system(sys, cfg)
    call run(sys, y, 0.01_wp, 500)
    call check(state, y(6) + 5000.0_wp, 0.5_wp*gravity*25.0_wp, "drop in 5 s, no drag", &
               rel_tol=1e-12_wp)
    call check(state, y(12), gravity*5.0_wp, "speed after 5 s, no drag", rel_tol=1e-12_wp)
    cfg%boat%wind_drag_coefficient = 0.5_wp
    y = new_test_system(sys, cfg)
    call run(sys, y, 0.01_wp, 2000)
    t = 20.0_wp
    vt = sqrt(2.0_wp*cfg%boat%mass*gravity/(rho_air*26.2_wp*0.5_wp))
    call note(state, "terminal velocity (m/s)", vt)
    call note(state, "speed after 20 s (m/s)", y(12))
    call check(state, y(12), vt*tanh(gravity*t/vt), "speed after 20 s with drag", &
               rel_tol=1e-8_wp)
    call check(state, y(6) + 5000.0_wp, vt**2/gravity*log(cosh(gravity*t/vt)), &
               "drop in 20 s with drag", rel_tol=1e-8_wp)
  end subroutine free_fall

  !> A free boat in still air moving sideways at 1 m/s onto the ship's side: two fenders at
  !> CG height (no moment) share the impact, each an effective mass m/2. The rebound
  !> speed is e_r v0 (1e-3), each fender's peak force the Hertz value for m/2 (A4), and the
  !> first contact comes at clearance/v0.
  subroutine fender_impact(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(rk4_type) :: rk
    real(wp) :: y(nstate), t, dt, clearance, force(2), fpeak, dm, fm
    integer :: i
    cfg = strip_config("&slings attached = .false. / &wind speed = 0.0 / "// &
                      "&contact law = 'hertz_elastoplastic', fender_z = 0.0, 0.0 / "// &
                      "&boat position = 0.0, 11.91, -100.0, velocity = 0.0, -1.0, 0.0, "// &
                      "wind_drag_coefficient = 0.0, lift_coefficient = 0.0 /")
    y = new_test_system(sys, cfg)
    call rk%init(nstate)
    dt = 2.0e-6_wp
    t = 0.0_wp
    fpeak = 0.0_wp
    do i = 1, 15000
      call rk%step(sys, t, y, dt)
      call sys%after_step(t, y)
      call sys%contact_state(y, clearance, force)
      fpeak = max(fpeak, maxval(force))
    end do
    call system_hertz_peak(sys, 0.5_wp*cfg%boat%mass, 1.0_wp, dm, fm)
    call note(state, "rebound speed (m/s)", y(11))
    call note(state, "peak force per fender (N)", fpeak)
    call note(state, "first contact (s)", sys%hist%first_contact_time)
    call check(state, y(11), 0.8_wp, "rebound = e_r v0", rel_tol=1e-3_wp)
    call check(state, fpeak, fm, "peak force = Hertz(m/2)", rel_tol=1e-3_wp)
    call check(state, sys%hist%first_contact_time, 0.01_wp, "first contact", abs_tol=2.0_wp*dt)
    call check(state, maxval(abs(y(7:9))), 0.0_wp, "no rotation", abs_tol=1e-9_wp)
    call check_true(state, clearance > 0.0_wp, "separated at the end")
  end subroutine fender_impact

  !> The fender impact of fender_impact driven by the system's step policy (dt = 1e-3 s,
  !> dt_contact = 2e-6 s): both approach rules find the onset (0.01 s) to within
  !> dt_contact and give the same rebound and Hertz peak; before contact the two-step
  !> window takes 9 steps of dt plus between dt/dt_contact = 500 and 2 dt/dt_contact small
  !> ones (by where the window opens), the graded rule 9 plus ~log2(dt/dt_contact) = 9.
  subroutine contact_approach(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    type(rk4_type) :: rk
    real(wp) :: y(nstate), t, h, clearance, force(2), fpeak, dm, fm
    integer :: i, j, before
    character(len=6), parameter :: rule(2) = ["window", "graded"]
    do j = 1, 2
      cfg = strip_config("&slings attached = .false. / &wind speed = 0.0 / "// &
                        "&contact law = 'hertz_elastoplastic', fender_z = 0.0, 0.0 / "// &
                        "&boat position = 0.0, 11.91, -100.0, velocity = 0.0, -1.0, 0.0, "// &
                        "wind_drag_coefficient = 0.0, lift_coefficient = 0.0 / "// &
                        "&simulation dt = 1e-3, dt_contact = 2e-6, contact_approach = '"// &
                        trim(rule(j))//"' /")
      y = new_test_system(sys, cfg)
      call rk%init(nstate)
      t = 0.0_wp
      fpeak = 0.0_wp
      before = 0
      do i = 1, 200000
        h = sys%max_step(t, y, 1.0e-3_wp)
        call rk%step(sys, t, y, h)
        call sys%after_step(t, y)
        if (sys%hist%first_contact_time < 0.0_wp) before = before + 1
        call sys%contact_state(y, clearance, force)
        fpeak = max(fpeak, maxval(force))
        if (t > 0.03_wp) exit
      end do
      call system_hertz_peak(sys, 0.5_wp*cfg%boat%mass, 1.0_wp, dm, fm)
      call note(state, rule(j)//": steps before contact", real(before, wp))
      call check(state, sys%hist%first_contact_time, 0.01_wp, rule(j)//": first contact", &
                 abs_tol=2.0_wp*2.0e-6_wp)
      call check(state, y(11), 0.8_wp, rule(j)//": rebound = e_r v0", rel_tol=1e-3_wp)
      call check(state, fpeak, fm, rule(j)//": peak force = Hertz(m/2)", rel_tol=2e-3_wp)
      if (j == 1) call check_true(state, before >= 500, "window: >= dt/dt_contact small steps")
      if (j == 2) call check_true(state, before <= 9 + 9 + 3, "graded: ~log2(dt/dt_contact)")
    end do
  end subroutine contact_approach

  !> Eq. (33) on a ship side that translates and rotates, with a moving, rotating boat: the
  !> approach rate of the deepest point equals the central difference of its indentation
  !> (the plane carried rigidly by the ship, the point by the boat).
  subroutine moving_side_rate(state)
    type(case_state), intent(inout) :: state
    type(fender_set_type) :: fs
    type(side_plane_type) :: plane
    real(wp), parameter :: q(6) = [0.05_wp, -0.03_wp, 0.2_wp, 0.3_wp, 12.0_wp, -14.0_wp]
    real(wp), parameter :: u(6) = [0.1_wp, -0.05_wp, 0.08_wp, 0.4_wp, -0.9_wp, 0.2_wp]
    real(wp), parameter :: h = 1.0e-5_wp
    real(wp) :: dm(2), dp(2), d(2), rate(2), unused(2)
    integer :: deepest(2)
    fs = new_fender_set([3.0_wp, -3.0_wp], -1.4_wp, [-0.8_wp, 0.2_wp], 1, &
                        hertz_elastoplastic_law_type(restitution=0.8_wp, &
                                                     k=hertz_stiffness(55.0e9_wp, 0.45_wp, &
                                                     200.0e9_wp, 0.3_wp, 0.15_wp, 0.0_wp)))
    plane%origin = [1.0_wp, 0.5_wp, 2.0_wp]
    plane%velocity = [0.3_wp, 0.7_wp, -0.2_wp]
    plane%angular_velocity = [0.02_wp, -0.04_wp, 0.05_wp]
    plane%point = plane%origin + [0.0_wp, 10.4_wp, 0.0_wp]
    plane%normal = [0.0_wp, 1.0_wp, 0.0_wp]
    call probe_at(0.0_wp, d, rate)
    call probe_at(-h, dm, unused)
    call probe_at(h, dp, unused)
    call note(state, "approach rates (m/s)", rate(1))
    call check(state, maxval(abs(rate - (dp - dm)/(2.0_wp*h))), 0.0_wp, &
               "eq. 33 rate vs FD of the indentation", abs_tol=1e-8_wp)
  contains
    !> Indentations (and rates) with boat and plane advanced rigidly by time s.
    subroutine probe_at(s, delta, delta_dot)
      real(wp), intent(in) :: s
      real(wp), intent(out) :: delta(2), delta_dot(2)
      type(side_plane_type) :: moved
      real(wp) :: qs(6), c(3, 3), rot(3, 3)
      qs = q + s*body_qdot(q, u)
      rot = rotation_about(plane%angular_velocity, s)
      moved = plane
      moved%origin = plane%origin + s*plane%velocity
      moved%point = moved%origin + matmul(rot, plane%point - plane%origin)
      moved%normal = matmul(rot, plane%normal)
      c = rotation_matrix(qs(1:3))
      call fender_probe(fs, moved, c, matmul(c, qs(4:6)), u, deepest, delta, delta_dot)
    end subroutine probe_at
  end subroutine moving_side_rate

  !> The probe takes a fender's deepest point from its segment's two ends (the penetration is
  !> linear along it): over 2000 random boat poses against a tilted side plane, its deepest
  !> point and penetration equal those of a search over all 7 points of each fender.
  subroutine probe_deepest(state)
    type(case_state), intent(inout) :: state
    type(fender_set_type) :: fs
    type(side_plane_type) :: plane
    real(wp) :: c(3, 3), r(3), u(6), x(7), delta(2), rate(2), d, best, err
    integer :: deepest(2), i, j, k, kbest, wrong
    fs = new_fender_set([3.0_wp, -3.0_wp], -1.4_wp, [-0.8_wp, 0.2_wp], 7, &
                        hertz_elastoplastic_law_type(restitution=0.8_wp, k=1.0e6_wp))
    plane%normal = [0.05_wp, 0.99_wp, 0.1_wp]/norm2([0.05_wp, 0.99_wp, 0.1_wp])
    plane%point = [0.0_wp, 2.0_wp, 0.0_wp]
    u = 0.0_wp
    wrong = 0
    err = 0.0_wp
    do i = 1, 2000
      call random_number(x)
      c = rotation_matrix(0.6_wp*(x(1:3) - 0.5_wp))
      r = [4.0_wp*(x(4) - 0.5_wp), 1.0_wp*x(5), 2.0_wp*(x(6) - 0.5_wp)]
      call fender_probe(fs, plane, c, r, u, deepest, delta, rate)
      do j = 1, 2
        best = -huge(1.0_wp)
        kbest = 0
        do k = 1, fs%nd
          d = -dot_product(plane%normal, r + matmul(c, fs%points(:, k, j)) - plane%point)
          if (d > best + 1e-12_wp) then
            best = d
            kbest = k
          end if
        end do
        if (deepest(j) /= kbest) wrong = wrong + 1
        err = max(err, abs(delta(j) - best))
      end do
    end do
    call check(state, real(wrong, wp), 0.0_wp, "deepest point differs", abs_tol=0.0_wp)
    call check(state, err, 0.0_wp, "penetration vs every point (m)", abs_tol=1e-12_wp)
  end subroutine probe_deepest

  !> Rotation by the angle |w| s about w (Rodrigues).
  pure function rotation_about(w, s) result(r)
    real(wp), intent(in) :: w(3), s
    real(wp) :: r(3, 3), k(3, 3), a
    integer :: i
    a = norm2(w)*s
    k = 0.0_wp
    r = 0.0_wp
    do i = 1, 3
      r(i, i) = 1.0_wp
    end do
    if (a == 0.0_wp) return
    k(1, 2) = -w(3); k(1, 3) = w(2); k(2, 1) = w(3); k(2, 3) = -w(1)
    k(3, 1) = -w(2); k(3, 2) = w(1)
    k = k/norm2(w)
    r = r + sin(a)*k + (1.0_wp - cos(a))*matmul(k, k)
  end function rotation_about

  !> The strips' quadratic drag (eq. 20's drag term, 0.5 rho C_D A |v| v) in sway: the
  !> boat upright in calm water with its keel 0.6 m deep, moving sideways at +-V: the odd
  !> part of the sway force is -0.5 rho C_D,y (L T) |V| V, L T the wetted lateral area of
  !> the wall-sided sections (L the hull length, T = 0.6 m), at V = 0.5 and 2 m/s. Buoyancy
  !> and the other loads do not depend on the sign of a pure sway speed.
  subroutine sway_drag(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp), allocatable :: y0(:)
    real(wp), parameter :: depth = 0.6_wp
    real(wp) :: c(3, 3), r(3), u(6), fp(6), fm(6), volume, v, expected
    integer :: i
    cfg = strip_config("&slings attached = .false. / &contact enabled = .false. /")
    y0 = new_test_system(sys, cfg)
    c = rotation_matrix([0.0_wp, 0.0_wp, 0.0_wp])
    r = [0.0_wp, 0.0_wp, depth - sys%par%water%hull%keel]
    do i = 1, 2
      v = merge(0.5_wp, 2.0_wp, i == 1)
      u = 0.0_wp
      u(5) = v
      call strip_loads(sys%par%water, sys%par%sea, 0.0_wp, c, r, u, fp, volume)
      u(5) = -v
      call strip_loads(sys%par%water, sys%par%sea, 0.0_wp, c, r, u, fm, volume)
      expected = -0.5_wp*rho_water*sys%par%water%cd(2)*sys%par%water%hull%length*depth*v*v
      call check(state, 0.5_wp*(fp(5) - fm(5)), expected, "odd sway force vs drag law", &
                 rel_tol=1.0e-9_wp)
    end do
  end subroutine sway_drag

end module test_boat_water
