!> The BEM ship's second-order wave drift (davit_ship_wave_drift, `&ship drift`): the load
!> model against its closed forms, the database's coefficients against the physics of
!> reflection, and the ship in regular beam waves against the coefficient and Newton's law;
!> the factory (davit_system_law_factory) builds each level from its deck name.
module test_ship_drift
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_ship_bem_database, only: bem_database_type, read_bem_database, bem_drift
  use davit_ship_ship_model, only: ship_system_type, ship_loads
  use system_fixture, only: ship_bem
  use davit_ship_bem_loads, only: bem_ship_type
  use davit_ship_wave_drift, only: drift_mean, drift_newman, drift_coefficients, drift_load, &
                                   wave_drift_type, mean_drift_type, newman_drift_type
  use davit_system_law_factory, only: new_wave_drift
  use davit_sea_wave_field, only: wave_field_type, wave_irregular
  use davit_core_rotation, only: rotation_matrix
  use davit_run_ship_scene, only: build_ship_scene
  use davit_solve_rk4, only: rk4_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_ship_drift

  character(len=*), parameter :: database = "input/ship_bem.nc"
  !> The equivalent box of Table 1: l = sqrt(C_b) L_wl, B, d.
  real(wp), parameter :: box(3) = [sqrt(0.68_wp)*130.55_wp, 20.8_wp, 4.4_wp]

contains

  function collect_ship_drift() result(suite)
    type(suite_type) :: suite
    suite%name = "ship_drift"
    suite%cases = [new_case("load_mean_and_newman_closed_forms", closed_forms), &
                   new_case("database_down_wave_and_reflection_limit", database_physics), &
                   new_case("beam_sea_mean_sway_force_is_the_drift", beam_sea_force), &
                   new_case("beam_sea_sway_after_100s_newton", beam_sea_sway), &
                   new_case("yawed_ship_drift_along_the_waves", yawed_ship), &
                   new_case("factory_builds_each_drift_level", factory_levels)]
  end function collect_ship_drift

  !> Two components (0.5 and 1.0 rad/s, amplitudes 1.5 and 0.7 m, phases 0.3 and 1.1 rad)
  !> on a database of hand-set coefficients D (surge +2e4, +6e4; sway -3e4, -1e4 N/m^2: same
  !> signs; yaw +5e5, -2e5 N m/m^2: opposite signs) read at its grid points:
  !>  * 'mean' is sum_i D_i a_i^2 at any time;
  !>  * 'newman' is the double sum sum_i sum_j a_i a_j T_ij cos((w_i - w_j) t + e_i - e_j)
  !>    with T_ij = sign(D_i) sqrt(D_i D_j) for same-signed D and 0 otherwise (written out
  !>    here term by term), at 5 times over the difference period, to 1e-12;
  !>  * its average over the 4 pi difference period is the mean;
  !>  * the load grows with the square of the ramp (1/4 at half the ramp time);
  !>  * a single component (a regular wave): 'newman' is the constant D a^2.
  !> A changed sign, square root or pairing rule changes one of these.
  subroutine closed_forms(state)
    type(case_state), intent(inout) :: state
    type(bem_database_type) :: db
    type(wave_field_type) :: sea
    real(wp) :: coef(3, 2), d(3, 2), a(2), w(2), e(2), t, f(6), direct(3), mean(3), avg(3)
    integer :: k, i, j
    w = [0.5_wp, 1.0_wp]
    a = [1.5_wp, 0.7_wp]
    e = [0.3_wp, 1.1_wp]
    d(:, 1) = [2.0e4_wp, -3.0e4_wp, 5.0e5_wp]
    d(:, 2) = [6.0e4_wp, -1.0e4_wp, -2.0e5_wp]
    db%omega = w
    db%heading = [0.0_wp, 2.0_wp*pi]
    allocate (db%drift(3, 2, 2))
    db%drift(:, 1, :) = d
    db%drift(:, 2, :) = d
    db%has_drift = .true.
    call two_component_sea(sea, w, a, e)
    call drift_coefficients(db, sea, 0.0_wp, coef)
    mean = d(:, 1)*a(1)**2 + d(:, 2)*a(2)**2
    avg = 0.0_wp
    do k = 0, 4
      t = 0.8_wp*pi*k
      f = drift_load(drift_mean, sea, coef, t, 0.0_wp, 0.0_wp)
      call check(state, f(2), mean(2), "mean sway at t = "//char(48 + k), rel_tol=1.0e-12_wp)
      call check(state, f(6), mean(3), "mean yaw", rel_tol=1.0e-12_wp)
      f = drift_load(drift_newman, sea, coef, t, 0.0_wp, 0.0_wp)
      direct = 0.0_wp
      do i = 1, 2
        do j = 1, 2
          direct = direct + a(i)*a(j)*pairing(d(:, i), d(:, j))* &
                   cos((w(i) - w(j))*t + e(i) - e(j))
        end do
      end do
      call check(state, f(1), direct(1), "newman surge vs double sum", rel_tol=1.0e-12_wp)
      call check(state, f(2), direct(2), "newman sway vs double sum", rel_tol=1.0e-12_wp)
      call check(state, f(6), direct(3), "newman yaw vs double sum", rel_tol=1.0e-12_wp)
      call check_true(state, all(abs(f([3, 4, 5])) == 0.0_wp), "no heave, roll, pitch")
    end do
    do k = 0, 399
      f = drift_load(drift_newman, sea, coef, 4.0_wp*pi*(k + 0.5_wp)/400.0_wp, 0.0_wp, 0.0_wp)
      avg = avg + f([1, 2, 6])/400.0_wp
    end do
    call check(state, avg(2), mean(2), "newman averaged = mean (sway)", rel_tol=1.0e-10_wp)
    call check(state, avg(3), mean(3), "newman averaged = mean (yaw)", rel_tol=1.0e-10_wp)
    sea%ramp_time = 10.0_wp
    f = drift_load(drift_mean, sea, coef, 5.0_wp, 0.0_wp, 0.0_wp)
    call check(state, f(2), 0.25_wp*mean(2), "half-way up the ramp: 1/4", rel_tol=1.0e-12_wp)
    call two_component_sea(sea, w(1:1), a(1:1), e(1:1))
    call drift_coefficients(db, sea, 0.0_wp, coef(:, 1:1))
    f = drift_load(drift_newman, sea, coef(:, 1:1), 3.7_wp, 0.0_wp, 0.0_wp)
    call check(state, f(2), d(2, 1)*a(1)**2, "regular wave: newman = D a^2", rel_tol=1.0e-12_wp)
  end subroutine closed_forms

  !> T_ij of Newman's approximation (geometric mean of same-signed coefficients).
  pure function pairing(di, dj) result(tij)
    real(wp), intent(in) :: di(3), dj(3)
    real(wp) :: tij(3)
    where (di*dj > 0.0_wp)
      tij = sign(sqrt(di*dj), di)
    else where
      tij = 0.0_wp
    end where
  end function pairing

  !> Components of frequencies w, amplitudes a, phases e travelling along x (deep water).
  !> `&ship drift` names: 'none' builds no level (no drift load) and no error; 'mean' the
  !> mean level, which gives sum_i D_i a_i^2 on the two components of closed_forms (sway
  !> -3e4 x 1.5^2 - 1e4 x 0.7^2 = -72400 N, yaw 5e5 x 2.25 - 2e5 x 0.49 = 1027000 N m); 'newman'
  !> Newman's level, which in a regular wave (the first component alone) is D a^2 (sway
  !> -67500 N); an unknown name is an error naming the key, the value and the levels.
  subroutine factory_levels(state)
    type(case_state), intent(inout) :: state
    class(wave_drift_type), allocatable :: drift
    type(error_type), allocatable :: error
    type(bem_database_type) :: db
    type(wave_field_type) :: sea
    real(wp) :: coef(3, 2), f(6)
    logical :: ok
    db%omega = [0.5_wp, 1.0_wp]
    db%heading = [0.0_wp, 2.0_wp*pi]
    allocate (db%drift(3, 2, 2))
    db%drift(:, 1, 1) = [2.0e4_wp, -3.0e4_wp, 5.0e5_wp]
    db%drift(:, 1, 2) = [6.0e4_wp, -1.0e4_wp, -2.0e5_wp]
    db%drift(:, 2, :) = db%drift(:, 1, :)
    db%has_drift = .true.
    call new_wave_drift("none", drift, error)
    call check_true(state, .not. allocated(drift) .and. .not. allocated(error), &
                    "none -> no level, no error")
    call new_wave_drift("mean", drift, error)
    ok = .false.
    if (allocated(drift)) then
      select type (drift)
      type is (mean_drift_type)
        ok = .true.
      end select
    end if
    call check_true(state, ok .and. .not. allocated(error), "mean -> mean_drift_type")
    if (.not. ok) return
    call two_component_sea(sea, [0.5_wp, 1.0_wp], [1.5_wp, 0.7_wp], [0.3_wp, 1.1_wp])
    call drift_coefficients(db, sea, 0.0_wp, coef)
    f = drift_load(drift, sea, coef, 2.0_wp, 0.0_wp, 0.0_wp)
    call check(state, f(2), -72400.0_wp, "mean: sway sum D a^2", rel_tol=1.0e-12_wp)
    call check(state, f(6), 1027000.0_wp, "mean: yaw sum D a^2", rel_tol=1.0e-12_wp)
    call new_wave_drift("newman", drift, error)
    ok = .false.
    if (allocated(drift)) then
      select type (drift)
      type is (newman_drift_type)
        ok = .true.
      end select
    end if
    call check_true(state, ok .and. .not. allocated(error), "newman -> newman_drift_type")
    if (.not. ok) return
    call two_component_sea(sea, [0.5_wp], [1.5_wp], [0.3_wp])
    call drift_coefficients(db, sea, 0.0_wp, coef(:, 1:1))
    f = drift_load(drift, sea, coef(:, 1:1), 3.7_wp, 0.0_wp, 0.0_wp)
    call check(state, f(2), -67500.0_wp, "newman, regular wave: D a^2", rel_tol=1.0e-12_wp)
    call new_wave_drift("stokes", drift, error)
    call check_true(state, allocated(error) .and. .not. allocated(drift), "stokes -> error")
    if (.not. allocated(error)) return
    call check_true(state, index(error%message, "&ship drift") > 0 .and. &
                    index(error%message, "'stokes'") > 0, "names key and value: "// &
                    error%message)
    call check_true(state, index(error%message, "none") > 0 .and. &
                    index(error%message, "mean") > 0 .and. &
                    index(error%message, "newman") > 0, "lists the levels")
  end subroutine factory_levels

  pure subroutine two_component_sea(sea, w, a, e)
    type(wave_field_type), intent(out) :: sea
    real(wp), intent(in) :: w(:), a(:), e(:)
    sea%kind = wave_irregular
    sea%n = size(w)
    sea%omega = w
    sea%k = w**2/gravity
    sea%kx = sea%k
    sea%ky = 0.0_wp*w
    sea%amplitude = a
    sea%phase = e
    sea%direction = 0.0_wp*w
    sea%cos_dir = 1.0_wp + 0.0_wp*w
    sea%sin_dir = 0.0_wp*w
  end subroutine two_component_sea

  !> The shipped database's coefficients (far field of the freely floating box, Capytaine):
  !>  * down-wave: beam seas from port (beta = 90 deg, waves travelling to starboard) push to
  !>    starboard (D_sway > 0, from 0.3 rad/s where it is measurable) and from starboard to
  !>    port, by the same amount (the hull is symmetric: 1 %); head seas push aft, following
  !>    seas forward (from 0.6 rad/s);
  !>  * long waves pass the ship unreflected: D -> 0 (at 0.1 rad/s below 1e-3 of the limit);
  !>  * short waves are reflected whole by the vertical side: D_sway -> 1/2 rho g l, the
  !>    2-D wall's 1/2 rho g a^2 per metre of lit side (Faltinsen 1990, Sea loads on ships
  !>    and offshore structures, eq. 5.47); at 2 rad/s (a 15 m wave, k d = 1.8, the motions
  !>    small) within 10 % below it (the ends diffract); head seas on the 20.8 m bow alike.
  subroutine database_physics(state)
    type(case_state), intent(inout) :: state
    type(bem_database_type) :: db
    type(error_type), allocatable :: error
    real(wp) :: wall, d90(3), d270(3), d180(3), d0(3), w
    integer :: k
    call read_bem_database(database, db, error)
    if (allocated(error)) error stop error%message
    call check_true(state, db%has_drift, "the shipped database has davit_drift")
    wall = 0.5_wp*rho_water*gravity*box(1)
    do k = 1, size(db%omega)
      w = db%omega(k)
      d90 = bem_drift(db, w, 0.5_wp*pi)
      d270 = bem_drift(db, w, 1.5_wp*pi)
      d180 = bem_drift(db, w, pi)
      if (w >= 0.3_wp) then
        call check_true(state, d90(2) > 0.0_wp .and. d270(2) < 0.0_wp, "beam seas down-wave")
      end if
      ! end-on, the 20.8 m bow reflects nothing measurable of waves longer than ~100 m
      if (w >= 0.6_wp) then
        d0 = bem_drift(db, w, 0.0_wp)
        call check_true(state, d180(1) < 0.0_wp .and. d0(1) > 0.0_wp, &
                        "head seas push aft, following forward")
      end if
      call check(state, d270(2), -d90(2), "port-starboard symmetry", &
                 abs_tol=1.0e-2_wp*abs(d90(2)) + 1.0e-6_wp*wall)
    end do
    d90 = bem_drift(db, 0.1_wp, 0.5_wp*pi)
    call check(state, d90(2), 0.0_wp, "long waves", abs_tol=1.0e-3_wp*wall)
    d90 = bem_drift(db, 2.0_wp, 0.5_wp*pi)
    call note(state, "D_sway(2 rad/s, 90 deg) / (rho g l / 2)", d90(2)/wall)
    call check(state, d90(2), 0.95_wp*wall, "short beam waves: the wall's limit", &
               rel_tol=0.053_wp)
    d90 = bem_drift(db, 2.0_wp, pi)
    call note(state, "D_surge(2 rad/s, 180 deg) / (rho g B / 2)", &
              -d90(1)/(0.5_wp*rho_water*gravity*box(2)))
    call check(state, -d90(1), 0.95_wp*0.5_wp*rho_water*gravity*box(2), &
               "short head waves: the bow's limit", rel_tol=0.053_wp)
  end subroutine database_physics

  !> Level 5 regular beam waves (Airy, H = 4 m, T = 12.72 s, travelling to starboard; no
  !> wind; crossflow_cd = 0), the ship free: the mean over periods 3-7 (after the 2-period
  !> ramp) of the ship's external loads' inertial sway component, averaged over the wave
  !> phases 0 and 180 deg (the first-order start-up part changes sign with the wave, a
  !> second-order one does not). With drift = 'mean' it is down-wave (+y) and the
  !> coefficient's D(w, 90 deg) a^2 within 10 % (the load turned into ship axes with the
  !> roll, pitch and yaw and back); with drift = 'none' below 2 % of it. (In these long
  !> waves, 253 m on a 20.8 m beam, the box reflects little: D a^2 ~ 1.5 kN; the next case
  !> takes shorter waves.)
  subroutine beam_sea_force(state)
    type(case_state), intent(inout) :: state
    real(wp) :: f_on(2), f_off(2), y(2), expected, t, me
    integer :: k
    do k = 1, 2
      call drift_run("mean", "", 180.0_wp*(k - 1), 8, f_on(k), y(k), expected, t, me)
      call drift_run("none", "", 180.0_wp*(k - 1), 8, f_off(k), y(k), expected, t, me)
    end do
    call note(state, "D(w, 90 deg) a^2 [N]", expected)
    call note(state, "mean sway force, drift 'mean' [N]", sum(f_on)/2.0_wp)
    call note(state, "mean sway force, drift 'none' [N]", sum(f_off)/2.0_wp)
    call check_true(state, expected > 0.0_wp, "the drift coefficient is down-wave")
    call check(state, sum(f_on)/2.0_wp, expected, "mean sway force = D a^2", rel_tol=0.1_wp)
    call check(state, sum(f_off)/2.0_wp, 0.0_wp, "no drift: no mean sway force", &
               abs_tol=0.02_wp*expected)
  end subroutine beam_sea_force

  !> Shorter regular beam waves (H = 1.5 m, T = 6 s: 56 m long, D ~ 0.7 of the wall's
  !> limit), the ship free in sway (no cross-flow drag, station keeping or wind: nothing
  !> holds a steady drift; the radiation memory's K(0) = 0), run with and without drift
  !> from the same wave: the difference of the mean sway over the period ending at >= 100 s
  !> is the response to the drift load alone, F(t) = F0 r(t)^2 (r the sea's ramp), of a
  !> mass with its low-frequency added mass, m_e = M + A22(0) (a steady acceleration sees
  !> the zero-frequency added mass; A22 at 0.1 rad/s, the grid's lowest, for A22(0)):
  !>   dy(t) = (F0/m_e) int_0^t (t - tau) r(tau)^2 dtau
  !> (integrated here by the trapezoidal rule on 0.01 s), within 10 %.
  subroutine beam_sea_sway(state)
    type(case_state), intent(inout) :: state
    real(wp) :: f, y_on, y_off, d_a2, t, me, closed
    integer :: n
    n = ceiling(100.0_wp/6.0_wp)
    call drift_run("mean", "height = 1.5, period = 6, ", 0.0_wp, n, f, y_on, d_a2, t, me)
    call drift_run("none", "height = 1.5, period = 6, ", 0.0_wp, n, f, y_off, d_a2, t, me)
    closed = d_a2/me*period_mean_ramped_drift(2.0_wp*t, (n - 1)*t, t)
    call note(state, "F0 = D a^2 [N]", d_a2)
    call note(state, "m_e = M + A22(0) [kg]", me)
    call note(state, "sway by the drift over the period ending at [s]", n*t)
    call note(state, "  time domain [m]", y_on - y_off)
    call note(state, "  closed form [m]", closed)
    call check_true(state, y_on - y_off > 0.0_wp, "the ship drifts down-wave")
    call check(state, y_on - y_off, closed, "drift sway vs F0/m_e double integral", &
               rel_tol=0.1_wp)
  end subroutine beam_sea_sway

  !> The ship heading 30 deg in waves travelling towards 120 deg (relative heading 90 deg, H =
  !> 1.5 m, T = 6 s), drift 'mean': the mean inertial horizontal force over periods 3-7
  !> (phases 0 and 180 deg averaged) points along the waves, (cos 120, sin 120) D a^2,
  !> within 10 % of D a^2 in each component: the load acts in the seakeeping frame and is
  !> turned with the yaw (a lost or doubled yaw rotation points it along 90 or 150 deg).
  subroutine yawed_ship(state)
    type(case_state), intent(inout) :: state
    real(wp) :: f(2, 2), fy, y, d_a2, t, me, expected(2)
    integer :: k
    do k = 1, 2
      call drift_run("mean", "height = 1.5, period = 6, ", 180.0_wp*(k - 1), 8, fy, y, d_a2, &
                     t, me, "heading_deg = 30, ", 120.0_wp, f(:, k))
    end do
    expected = d_a2*[cos(120.0_wp*pi/180.0_wp), sin(120.0_wp*pi/180.0_wp)]
    call note(state, "D a^2 [N]", d_a2)
    call note(state, "mean force x [N]", sum(f(1, :))/2.0_wp)
    call note(state, "mean force y [N]", sum(f(2, :))/2.0_wp)
    call check(state, sum(f(1, :))/2.0_wp, expected(1), "x along the waves", &
               abs_tol=0.1_wp*d_a2)
    call check(state, sum(f(2, :))/2.0_wp, expected(2), "y along the waves", &
               abs_tol=0.1_wp*d_a2)
  end subroutine yawed_ship

  !> Mean over [t0, t0 + period] of int_0^t (t - tau) r(tau)^2 dtau, r = (1 - cos(pi tau/tr))/2
  !> up to the ramp time tr, 1 after: trapezoidal rule on 0.01 s.
  pure real(wp) function period_mean_ramped_drift(tr, t0, period) result(s)
    real(wp), intent(in) :: tr, t0, period
    real(wp), parameter :: h = 0.01_wp
    real(wp) :: tau, v, x, r2
    integer :: i, n
    ! x(t) = int_0^t (t - tau) r^2: integrate x'' = r^2 with x(0) = x'(0) = 0
    n = nint((t0 + period)/h)
    v = 0.0_wp
    x = 0.0_wp
    s = 0.0_wp
    do i = 1, n
      tau = (i - 1)*h
      r2 = ramp2(tau)
      x = x + h*v + h*h*(2.0_wp*r2 + ramp2(tau + h))/6.0_wp
      v = v + h*(r2 + ramp2(tau + h))/2.0_wp
      if (tau + h > t0 + 0.5_wp*h) s = s + x*h/period
    end do
  contains
    pure real(wp) function ramp2(tt)
      real(wp), intent(in) :: tt
      ramp2 = 1.0_wp
      if (tt < tr) ramp2 = (0.5_wp*(1.0_wp - cos(pi*tt/tr)))**2
    end function ramp2
  end function period_mean_ramped_drift

  !> Level 5 beam waves (Airy, `extra` overriding height and period) at phase phase_deg,
  !> no wind, crossflow_cd = 0, drift level `drift`, n_periods whole periods at 128 RK4 steps
  !> each: the mean inertial sway force of the external loads over periods 3-7 (fbar), the
  !> mean sway over the last period (ybar), D(w, 90 deg) a^2 of the database, the period
  !> and m_e = M + A22(0.1 rad/s).
  subroutine drift_run(drift, extra, phase_deg, n_periods, fbar, ybar, d_a2, period, me, &
                       ship_extra, direction_deg, fxy)
    character(len=*), intent(in) :: drift, extra
    real(wp), intent(in) :: phase_deg
    integer, intent(in) :: n_periods
    real(wp), intent(out) :: fbar, ybar, d_a2, period, me
    character(len=*), intent(in), optional :: ship_extra
    real(wp), intent(in), optional :: direction_deg
    real(wp), intent(out), optional :: fxy(2)
    integer, parameter :: per_period = 128
    character(len=16) :: phase
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t, dt, c(3, 3), load(6), d(3), f(2), chi
    type(bem_ship_type) :: bem
    character(len=16) :: direction
    character(len=:), allocatable :: keys
    integer :: i
    write (phase, "(f6.1)") phase_deg
    chi = 90.0_wp
    if (present(direction_deg)) chi = direction_deg
    write (direction, "(f6.1)") chi
    keys = ""
    if (present(ship_extra)) keys = ship_extra
    call parse_config("t.nml", "&ship model = 'bem', database = '"//database// &
                      "', crossflow_cd = 0, "//keys//"drift = '"//drift//"' / &sea level = 5, "// &
                      extra//"wave_type = 'airy', direction_deg = "//trim(direction)// &
                      ", ramp_periods = 2, phase_deg = "//trim(phase)//" / &wind speed = 0 /", &
                      cfg, error)
    if (allocated(error)) error stop error%message
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop error%message
    bem = ship_bem(ship)
    d = bem_drift(bem%db, ship%par%sea%omega(1), &
                  ship%par%sea%direction(1) - ship%heading_reference())
    d_a2 = d(2)*ship%par%sea%amplitude(1)**2
    me = bem%mass + bem%db%added_mass(2, 2, 1)
    period = 2.0_wp*pi/ship%par%sea%omega(1)
    dt = period/per_period
    call rk%init(size(y))
    ybar = 0.0_wp
    f = 0.0_wp
    do i = 1, n_periods*per_period
      t = real(i - 1, wp)*dt
      call rk%step(ship, t, y, dt)
      call ship%after_step(t + dt, y)
      associate (q => y(ship%par%body%q(1):ship%par%body%q(2)), &
                 u => y(ship%par%body%u(1):ship%par%body%u(2)))
        if (i > 2*per_period .and. i <= 7*per_period) then
          c = rotation_matrix(q(1:3))
          load = ship_loads(ship, t + dt, q, u, c)
          f = f + matmul(c(1:2, :), load(1:3))/(5*per_period)
        end if
        if (i > (n_periods - 1)*per_period) ybar = ybar + q(5)/per_period
      end associate
    end do
    fbar = f(2)
    if (present(fxy)) fxy = f
  end subroutine drift_run

end module test_ship_drift
