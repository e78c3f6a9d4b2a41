!> The ship from the BEM database (input/ship_bem.nc, the paper's equivalent box): what
!> davit reads is consistent with itself and with hydrostatics, and its time-domain
!> Cummins ship reproduces the frequency domain's natural periods and long-wave limits.
module test_bem_ship
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_ship_bem_database, only: bem_database_type, read_bem_database, bem_excitation, &
                                     bracket
  use davit_ship_ship_model, only: ship_system_type
  use system_fixture, only: ship_bem, is_bem_ship
  use davit_core_rotation, only: rotation_matrix, cross
  use davit_ship_bem_loads, only: bem_memory, bem_ship_type
  use davit_run_ship_scene, only: build_ship_scene
  use davit_run_rao, only: rao_case
  use davit_solve_rk4, only: rk4_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_bem_ship


  character(len=*), parameter :: database = "input/ship_bem.nc"
  !> The equivalent box of Table 1: l = sqrt(C_b) L_wl, B, d.
  real(wp), parameter :: box(3) = [sqrt(0.68_wp)*130.55_wp, 20.8_wp, 4.4_wp]

contains

  function collect_bem_ship() result(suite)
    type(suite_type) :: suite
    suite%name = "bem_ship"
    suite%cases = [new_case("database_hydrostatics_and_mass", hydrostatics), &
                   new_case("database_memory_kernels_stable_at_zero", kernels), &
                   new_case("free_decay_roll_period_vs_frequency_domain", free_decay), &
                   new_case("rao_vs_frequency_domain_solution", rao_vs_fd), &
                   new_case("long_wave_limits", long_wave), &
                   new_case("beam_sea_no_mean_sway", beam_sea_mean_sway), &
                   new_case("fk_box_beam_sea_no_mean_sway", box_beam_sea_mean_sway), &
                   new_case("cummins_in_the_seakeeping_frame", seakeeping_frame), &
                   new_case("bracket_places_values_on_a_grid", grid_bracket)]
  end function collect_bem_ship

  !> The database's interpolation places a value in the interval that holds it (the left
  !> one at a node), clamped at both ends: on the uneven grid 0, 1, 3, 6, 10 by hand.
  subroutine grid_bracket(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: x(5) = [0.0_wp, 1.0_wp, 3.0_wp, 6.0_wp, 10.0_wp]
    real(wp), parameter :: v(9) = [-1.0_wp, 0.0_wp, 0.5_wp, 1.0_wp, 2.0_wp, 5.25_wp, 9.0_wp, &
                                   10.0_wp, 12.0_wp]
    integer, parameter :: i_expected(9) = [1, 1, 1, 1, 2, 3, 4, 4, 4]
    real(wp), parameter :: s_expected(9) = [0.0_wp, 0.0_wp, 0.5_wp, 1.0_wp, 0.5_wp, 0.75_wp, &
                                            0.75_wp, 1.0_wp, 1.0_wp]
    real(wp) :: s
    integer :: i, j
    do j = 1, size(v)
      call bracket(x, v(j), i, s)
      call check_true(state, i == i_expected(j), "interval of the value")
      call check(state, s, s_expected(j), "weight of the interval's right end", abs_tol=1e-14_wp)
    end do
  end subroutine grid_bracket

  subroutine load(db)
    type(bem_database_type), intent(out) :: db
    type(error_type), allocatable :: error
    call read_bem_database(database, db, error)
    if (allocated(error)) error stop error%message
  end subroutine load

  !> Closed-form box hydrostatics (CG on the waterline, as the database is built): V = l B d,
  !> C33 = rho g l B, C44 = rho g V GM_T with GM_T = KB + B^2/(12 d) - KG, C55 alike with
  !> l^2/(12 d); mass = rho V (free floating); A(inf) symmetric.
  subroutine hydrostatics(state)
    type(case_state), intent(inout) :: state
    type(bem_database_type) :: db
    real(wp) :: v, gm_t, gm_l
    call load(db)
    v = product(box)
    gm_t = box(3)/2.0_wp + box(2)**2/(12.0_wp*box(3)) - box(3)
    gm_l = box(3)/2.0_wp + box(1)**2/(12.0_wp*box(3)) - box(3)
    call check(state, db%volume, v, "displaced volume l B d", rel_tol=0.01_wp)
    call check(state, db%mass(1, 1), rho_water*db%volume, "mass = rho V", rel_tol=1e-9_wp)
    call check(state, db%stiffness(3, 3), rho_water*gravity*box(1)*box(2), "C33 = rho g A_wp", &
               rel_tol=0.01_wp)
    call check(state, db%stiffness(4, 4), rho_water*gravity*v*gm_t, "C44 = rho g V GM_T", &
               rel_tol=0.01_wp)
    call check(state, db%stiffness(5, 5), rho_water*gravity*v*gm_l, "C55 = rho g V GM_L", &
               rel_tol=0.01_wp)
    call check(state, maxval(abs(db%added_mass_inf - transpose(db%added_mass_inf))), 0.0_wp, &
               "A(inf) symmetric", abs_tol=1e-3_wp*maxval(abs(db%added_mass_inf)))
    call check_true(state, size(db%pairs) > 0 .and. db%nrad > 0, "memory kernels fitted")
  end subroutine hydrostatics

  !> Each fitted kernel is stable (exp(A t) has died out by t = 1024 s, by repeated
  !> squaring); it reproduces the BEM's B_ij(w) and A_ij(w) = A_ij(inf) + Im K(i w)/w,
  !> K(i w) = C_s (i w - A_s)^-1 B_s, within 5 % of their largest values at every database
  !> frequency up to 1.5 rad/s (the band of the seas); and the memory of a constant
  !> velocity dies out: K(0) = -C_s A_s^-1 B_s ~ 0 (a ship moving steadily makes no waves
  !> in this linear model).
  subroutine kernels(state)
    type(case_state), intent(inout) :: state
    type(bem_database_type) :: db
    real(wp), allocatable :: x(:)
    real(wp) :: peak_b, peak_a, err_b, err_a
    complex(wp) :: kw
    integer :: k, m
    call load(db)
    do k = 1, size(db%pairs)
      associate (p => db%pairs(k))
        call check_true(state, maxval(abs(flow(p%a, 1024.0_wp))) < 1.0e-3_wp, &
                        "stable: exp(A t) -> 0")
        peak_b = maxval(abs(db%damping(p%i, p%j, :)))
        peak_a = maxval(abs(db%added_mass(p%i, p%j, :) - db%added_mass_inf(p%i, p%j)))
        err_b = 0.0_wp
        err_a = 0.0_wp
        do m = 1, size(db%omega)
          if (db%omega(m) > 1.5_wp) exit
          kw = kernel_response(p%a, p%b, p%c, db%omega(m))
          err_b = max(err_b, abs(real(kw, wp) - db%damping(p%i, p%j, m)))
          err_a = max(err_a, abs(db%added_mass_inf(p%i, p%j) + aimag(kw)/db%omega(m) - &
                                 db%added_mass(p%i, p%j, m)))
        end do
        call check(state, err_b/peak_b, 0.0_wp, "fit reproduces B(w)", abs_tol=0.05_wp)
        call check(state, err_a/peak_a, 0.0_wp, "fit reproduces A(w)", abs_tol=0.05_wp)
        x = static_response(p%a, p%b)
        call check(state, dot_product(p%c, x), 0.0_wp, "K(0) ~ 0 against B peak", &
                   abs_tol=0.05_wp*peak_b)
      end associate
    end do
  end subroutine kernels

  !> C (i w - A)^-1 B.
  pure complex(wp) function kernel_response(a, b, c, w) result(kw)
    real(wp), intent(in) :: a(:, :), b(:), c(:), w
    complex(wp) :: m(size(b), size(b)), x(size(b))
    integer :: i
    m = -cmplx(a, 0.0_wp, wp)
    do i = 1, size(b)
      m(i, i) = m(i, i) + cmplx(0.0_wp, w, wp)
    end do
    x = cmplx(b, 0.0_wp, wp)
    call complex_solve(m, x)
    kw = sum(c*x)
  end function kernel_response

  !> exp(A t) as (I + A h + (A h)^2/2)^(2^m), h = t/2^20.
  pure function flow(a, t) result(e)
    real(wp), intent(in) :: a(:, :), t
    real(wp) :: e(size(a, 1), size(a, 1)), h
    integer :: m
    h = t/2.0_wp**20
    e = identity(size(a, 1)) + a*h + 0.5_wp*matmul(a, a)*h**2
    do m = 1, 20
      e = matmul(e, e)
    end do
  end function flow

  pure function identity(n) result(e)
    integer, intent(in) :: n
    real(wp) :: e(n, n)
    integer :: i
    e = 0.0_wp
    do i = 1, n
      e(i, i) = 1.0_wp
    end do
  end function identity

  !> x = -int_0^inf exp(A t) b dt by midpoint-rule steps of 0.01 s over 2000 s (A stable).
  pure function static_response(a, b) result(x)
    real(wp), intent(in) :: a(:, :), b(:)
    real(wp) :: x(size(b)), z(size(b)), h
    integer :: i
    h = 0.01_wp
    z = b
    x = 0.5_wp*h*z
    do i = 1, 200000
      z = z + h*matmul(a, z + 0.5_wp*h*matmul(a, z))
      x = x + h*z
    end do
    x = -x
  end function static_response

  !> Damped frequency w sqrt(1 - zeta^2) of DOF i alone, zeta = B_ii(w)/(2 (M + A(w)) w).
  pure real(wp) function damped_omega(db, i) result(wd)
    type(bem_database_type), intent(in) :: db
    integer, intent(in) :: i
    real(wp) :: w, zeta
    w = natural_omega(db, i)
    zeta = at(db, db%damping(i, i, :), w)/(2.0_wp*(db%mass(i, i) + &
                                                    at(db, db%added_mass(i, i, :), w))*w)
    wd = w*sqrt(1.0_wp - zeta**2)
  end function damped_omega

  !> y(omega) of the database's grid at w, linearly.
  pure real(wp) function at(db, y, w)
    type(bem_database_type), intent(in) :: db
    real(wp), intent(in) :: y(:), w
    real(wp) :: s
    integer :: k
    k = 1
    do while (k < size(db%omega) - 1 .and. w > db%omega(k + 1))
      k = k + 1
    end do
    s = min(1.0_wp, max(0.0_wp, (w - db%omega(k))/(db%omega(k + 1) - db%omega(k))))
    at = (1.0_wp - s)*y(k) + s*y(k + 1)
  end function at

  !> Undamped natural frequency w = sqrt(C_ii/(M_ii + A_ii(w))) iterated on the database.
  pure real(wp) function natural_omega(db, i) result(w)
    type(bem_database_type), intent(in) :: db
    integer, intent(in) :: i
    integer :: it
    w = sqrt(db%stiffness(i, i)/(db%mass(i, i) + db%added_mass_inf(i, i)))
    do it = 1, 100
      w = sqrt(db%stiffness(i, i)/(db%mass(i, i) + at(db, db%added_mass(i, i, :), w)))
    end do
  end function natural_omega

  !> Free decay of roll in calm water: its period (between the 1st and 3rd zero crossings)
  !> within 2 % of the frequency domain's damped period 2 pi/w_d from the database:
  !> w_d = w sqrt(1 - zeta^2), w = sqrt(C/(M + A(w))) iterated, zeta = B(w)/(2 (M + A(w)) w).
  !> Heave and pitch are damped 13-16 % of critical by the waves they make, with A and B
  !> changing fast near resonance: their decay is not one damped sinusoid (successive
  !> zero-crossing periods 6.91, 6.25 s in heave and 7.25, 6.96 s in pitch around the
  !> frequency domain's 6.92 and 6.88 s), so their resonances are checked where they are
  !> defined, as the peaks of the forced response (rao_vs_frequency_domain_solution).
  subroutine free_decay(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: deck = "&ship model = 'bem', database = '"//database// &
      "', zeta_roll = 0, crossflow_cd = 0 / &wind speed = 0 /"
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(bem_database_type) :: db
    real(wp), allocatable :: y(:)
    real(wp) :: period, expected
    call load(db)
    call parse_config("t.nml", deck, cfg, error)
    if (allocated(error)) error stop error%message
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop error%message
    y(ship%par%body%q(1)) = 0.02_wp
    period = decay_period(ship, y, ship%par%body%q(1))
    expected = 2.0_wp*pi/damped_omega(db, 4)
    call note(state, "roll period, time domain [s]", period)
    call note(state, "roll 2 pi/w_d, frequency domain [s]", expected)
    call check(state, period, expected, "roll period", rel_tol=0.02_wp)
  end subroutine free_decay

  !> davit's time-domain RAOs (davit rao's fit over whole periods, 5 cm waves, soft
  !> mooring) against the 6 x 6 frequency-domain solution from the same database, all
  !> couplings: [-w^2 (M + A(w)) + i w (B(w) + B_visc) + C] xi = X(w, beta), with the
  !> same viscous roll damping (5 % of critical at the roll resonance). Heave, roll and
  !> pitch amplitudes within 3 % of the frequency domain's, or 1 % of its peak where the
  !> response is small, at 9 frequencies across the peaks and 3 headings.
  subroutine rao_vs_fd(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: omegas(9) = [0.4_wp, 0.6_wp, 0.7_wp, 0.75_wp, 0.8_wp, 0.85_wp, &
                                        0.9_wp, 1.0_wp, 1.2_wp]
    real(wp), parameter :: headings(3) = [0.5_wp*pi, 0.75_wp*pi, pi]
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(bem_database_type) :: db
    real(wp) :: td(6, 9, 3), fd(6, 9, 3), phase(6), peak, b44
    integer :: iw, ib, d
    integer, parameter :: dofs(3) = [3, 4, 5]
    character(len=5), parameter :: names(3) = ["heave", "roll ", "pitch"]
    call load(db)
    call parse_config("t.nml", "&ship model = 'bem', database = '"//database//"', "// &
                      "zeta_roll = 0.05, crossflow_cd = 0 / &rao amplitude = 0.05, "// &
                      "settle_time = 120, measure_periods = 8, dt = 0.05 / &wind speed = 0 /", &
                      cfg, error)
    if (allocated(error)) error stop error%message
    b44 = 0.05_wp*2.0_wp*sqrt(db%stiffness(4, 4)*db%stiffness(4, 4)/natural_omega(db, 4)**2)
    do ib = 1, 3
      do iw = 1, 9
        call rao_case(cfg, omegas(iw), headings(ib), td(:, iw, ib), phase, error)
        fd(:, iw, ib) = abs(fd_response(db, b44, omegas(iw), headings(ib)))
      end do
    end do
    do d = 1, 3
      do ib = 1, 3
        peak = maxval(fd(dofs(d), :, ib))
        do iw = 1, 9
          call check(state, td(dofs(d), iw, ib), fd(dofs(d), iw, ib), trim(names(d))// &
                     " RAO", abs_tol=max(0.03_wp*fd(dofs(d), iw, ib), 0.01_wp*peak))
        end do
        if (peak > 1.0e-6_wp) call note(state, trim(names(d))//" largest |td/fd - 1|", &
                  maxval(abs(td(dofs(d), :, ib)/max(fd(dofs(d), :, ib), 1e-12_wp) - 1.0_wp), &
                         mask=fd(dofs(d), :, ib) > 0.01_wp*peak))
      end do
    end do
  end subroutine rao_vs_fd

  !> The frequency-domain response xi (DOF order; heave positive down) per unit amplitude.
  function fd_response(db, b44, w, beta) result(xi)
    type(bem_database_type), intent(in) :: db
    real(wp), intent(in) :: b44, w, beta
    complex(wp) :: xi(6), m(6, 6)
    real(wp) :: a(6, 6), b(6, 6)
    integer :: i, j
    do i = 1, 6
      do j = 1, 6
        a(i, j) = at(db, db%added_mass(i, j, :), w)
        b(i, j) = at(db, db%damping(i, j, :), w)
      end do
    end do
    b(4, 4) = b(4, 4) + b44
    m = cmplx(-w**2*(db%mass + a) + db%stiffness, w*b, wp)
    xi = bem_excitation(db, w, beta)
    call complex_solve(m, xi)
  end function fd_response

  !> Solve m x = x in place by Gaussian elimination with partial pivoting.
  pure subroutine complex_solve(m, x)
    complex(wp), intent(inout) :: m(:, :), x(:)
    complex(wp) :: f, row(size(x)), xi
    integer :: i, j, n, piv
    n = size(x)
    do j = 1, n
      piv = j - 1 + maxloc(abs(m(j:, j)), 1)
      row = m(j, :)
      m(j, :) = m(piv, :)
      m(piv, :) = row
      xi = x(j)
      x(j) = x(piv)
      x(piv) = xi
      do i = j + 1, n
        f = m(i, j)/m(j, j)
        m(i, :) = m(i, :) - f*m(j, :)
        x(i) = x(i) - f*x(j)
      end do
    end do
    do i = n, 1, -1
      x(i) = (x(i) - sum(m(i, i + 1:)*x(i + 1:)))/m(i, i)
    end do
  end subroutine complex_solve

  !> Time from the 1st to the 3rd zero crossing of the offset.
  real(wp) function decay_period(ship, y0, k) result(period)
    type(ship_system_type), intent(inout) :: ship
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: k
    real(wp), parameter :: dt = 0.01_wp
    type(rk4_type) :: rk
    real(wp) :: y(size(y0)), t, prev, mean, crossings(3)
    integer :: i, nc
    y = y0
    mean = 0.0_wp
    call rk%init(size(y))
    t = 0.0_wp
    nc = 0
    prev = y(k) - mean
    do i = 1, 6000
      call rk%step(ship, t, y, dt)
      t = real(i, wp)*dt
      call ship%after_step(t, y)
      if (sign(1.0_wp, y(k) - mean) /= sign(1.0_wp, prev)) then
        nc = nc + 1
        crossings(nc) = t - dt*(y(k) - mean)/(y(k) - mean - prev)
        if (nc == 3) exit
      end if
      prev = y(k) - mean
    end do
    period = crossings(3) - crossings(1)
  end function decay_period

  !> Long waves: heave follows the surface (RAO 1) in head seas, roll the wave slope k a in
  !> beam seas, pitch the slope in head seas (w = 0.15 rad/s, k = w^2/g).
  subroutine long_wave(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: amp(6), phase(6), k
    real(wp), parameter :: w = 0.15_wp
    call parse_config("t.nml", "&ship model = 'bem', database = '"//database//"' / "// &
                      "&rao omegas = 0.15, headings_deg = 180, amplitude = 0.05, "// &
                      "settle_time = 100, measure_periods = 3, dt = 0.1 / &wind speed = 0 /", &
                      cfg, error)
    if (allocated(error)) error stop error%message
    k = w**2/gravity
    call rao_case(cfg, w, pi, amp, phase, error)
    call check(state, amp(3), 1.0_wp, "head seas: heave RAO -> 1", rel_tol=0.03_wp)
    call check(state, amp(5), k, "head seas: pitch RAO -> k", rel_tol=0.05_wp)
    call rao_case(cfg, w, 0.5_wp*pi, amp, phase, error)
    call check(state, amp(3), 1.0_wp, "beam seas: heave RAO -> 1", rel_tol=0.03_wp)
    call check(state, amp(4), k, "beam seas: roll RAO -> k", rel_tol=0.05_wp)
  end subroutine long_wave


  !> Regular beam waves (Level 5: H = 4 m, T = 12.72 s, towards +y, Airy), no wind, the
  !> potential-flow ship (crossflow_cd = 0: no drag to hide a drift, no station keeping):
  !> davit has no mean wave drift force model, and Cummins' equation is linear in the
  !> seakeeping frame, so the ship's mean sway force over whole periods is zero at second
  !> order in the wave amplitude. The force is the ship's momentum change over the 5 whole
  !> periods after the 2-period ramp, m (ydot(7 T) - ydot(2 T))/(5 T) (all loads; the CG's
  !> inertial sway velocity). Its linear part (the start-up transient: a free sway keeps
  !> the impulse of the ramp, and the fitted memory's K(0) ~ 0 acts on it) changes sign
  !> with the wave, a second-order mean does not: the mean over phases 0 and 180 deg is the
  !> second-order force. Bound: 1e-4 of the first-order sway force amplitude a |X_2|
  !> (740 N against 7.4 MN): a hundredth of a real mean drift force here (1/2 rho g a^2 l R^2
  !> = 2.2 MN R^2 with a reflection R ~ 0.1-0.2 at this wave length: 20-90 kN), 200 times
  !> below the spurious up-wave mean before the fix (-1.5e5 N: the ship-axis radiation
  !> memory and added mass turned with the roll), and what is left once Cummins' loads are
  !> linear in the seakeeping frame is rounding and step error (~10 N). The ship's mean sway
  !> over the 8th period (ending at 101.8 s), its second-order part alike, is then within
  !> the drift F t^2/(2 m) of the mean acceleration F/m that this force gives in free sway
  !> (nothing damps a steady drift: K(0) ~ 0) over t = 8 T: 0.38 m (it was -50 m).
  subroutine beam_sea_mean_sway(state)
    type(case_state), intent(inout) :: state
    call mean_sway_of(state, "bem")
  end subroutine beam_sea_mean_sway

  !> The same for the paper's box ship (Froude-Krylov box loads, strip-theory added masses),
  !> whose heave added mass leaned with the roll alike (-14 m in 100 s before the fix).
  subroutine box_beam_sea_mean_sway(state)
    type(case_state), intent(inout) :: state
    call mean_sway_of(state, "fk_box")
  end subroutine box_beam_sea_mean_sway

  subroutine mean_sway_of(state, model)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: model
    real(wp) :: fbar(2), ybar(2), amp, mass, bound, t
    integer :: k
    do k = 1, 2
      call beam_run(model, 180.0_wp*(k - 1), fbar(k), ybar(k), amp, mass, t)
      call note(state, "phase "//merge("  0", "180", k == 1)//" deg: mean sway force [N]", &
                fbar(k))
      call note(state, "phase "//merge("  0", "180", k == 1)//" deg: mean sway [m]", ybar(k))
    end do
    bound = 1.0e-4_wp*amp
    call note(state, "first-order sway force amplitude [N]", amp)
    call check(state, sum(fbar)/2.0_wp, 0.0_wp, "second-order mean sway force ~ 0", &
               abs_tol=bound)
    call check(state, sum(ybar)/2.0_wp, 0.0_wp, "second-order mean sway after 8 T", &
               abs_tol=bound*(8.0_wp*t)**2/(2.0_wp*mass))
  end subroutine mean_sway_of

  !> One beam-sea run of beam_sea_mean_sway of the ship model at wave phase phase_deg: the
  !> mean sway force fbar over periods 3-7, the mean sway ybar over period 8, the amplitude
  !> of the first-order sway force (heading frame), the ship's mass and the wave period.
  subroutine beam_run(model, phase_deg, fbar, ybar, amplitude, mass, period)
    character(len=*), intent(in) :: model
    real(wp), intent(in) :: phase_deg
    real(wp), intent(out) :: fbar, ybar, amplitude, mass, period
    integer, parameter :: per_period = 128
    character(len=16) :: phase
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t, dt, ydot0, coef(2)
    type(bem_ship_type) :: bem
    integer :: i
    write (phase, "(f6.1)") phase_deg
    call parse_config("t.nml", "&ship model = '"//model//"', database = '"//database// &
                      "', crossflow_cd = 0 / &sea level = 5, wave_type = 'airy', "// &
                      "direction_deg = 90, ramp_periods = 2, phase_deg = "//trim(phase)// &
                      " / &wind speed = 0 /", cfg, error)
    if (allocated(error)) error stop error%message
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop error%message
    coef = ship%wave_coefficients(2, 1)
    amplitude = hypot(coef(1), coef(2))
    mass = ship%par%hull%mass
    bem = ship_bem(ship)
    if (is_bem_ship(ship)) mass = bem%mass
    period = 2.0_wp*pi/ship%par%sea%omega(1)
    dt = period/per_period
    call rk%init(size(y))
    ybar = 0.0_wp
    ydot0 = 0.0_wp
    do i = 1, 8*per_period
      t = real(i - 1, wp)*dt
      call rk%step(ship, t, y, dt)
      call ship%after_step(t + dt, y)
      if (i == 2*per_period) ydot0 = sway_velocity(ship, y)
      if (i == 7*per_period) fbar = mass*(sway_velocity(ship, y) - ydot0)/(5.0_wp*period)
      if (i > 7*per_period) ybar = ybar + y(ship%par%body%q(1) + 4)/per_period
    end do
  end subroutine beam_run

  !> The CG's inertial sway velocity (C v)_y.
  pure real(wp) function sway_velocity(ship, y) result(vy)
    type(ship_system_type), intent(in) :: ship
    real(wp), intent(in) :: y(:)
    real(wp) :: c(3, 3)
    c = rotation_matrix(y(ship%par%body%q(1):ship%par%body%q(1) + 2))
    vy = dot_product(c(2, :), y(ship%par%body%u(1) + 3:ship%par%body%u(2)))
  end function sway_velocity


  !> Cummins' equation holds in the seakeeping frame h (level, yawed with the ship) and the
  !> rigid body's in ship axes: at a rolled, pitched and yawed state with speeds and memory
  !> states (calm water, no cross-flow drag or windage), the rates satisfy, with
  !> m = C^T Rz(psi), m6 = diag(m, m), a = (v' + omega x v, omega'),
  !>   (m (v' + omega x v), I omega' + omega x (I omega)) =
  !>     m6 (-A(inf) m6^T a - mu(m6^T u) - C delta),
  !> to rounding (1e-9 of the largest term): a changed sign or coefficient of the transport
  !> omega x v, of a turning (m for m^T) or of the memory's input breaks it. And a ship
  !> heeled 6 deg (its static list) heaving straight up with a pure-heave memory makes no
  !> sway or roll acceleration: by port-starboard symmetry heave radiates no sway, so the
  !> heave radiation force stays vertical (in ship axes it leaned with the heel: 10 % of
  !> it sideways).
  subroutine seakeeping_frame(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: deck = "&ship model = 'bem', database = '"//database// &
      "', zeta_roll = 0, crossflow_cd = 0, list_deg = 6, area_front = 0, "// &
      "area_lateral = 0 / &wind speed = 0 /"
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    real(wp), allocatable :: y(:), dydt(:), xdot(:)
    real(wp) :: m(3, 3), c(3, 3), om(3), v(3), acc(6), mu(6), lhs(6), rhs(6), a(6, 6)
    real(wp) :: delta(6), scale, list
    type(bem_ship_type) :: bem
    integer :: k, i0
    call parse_config("t.nml", deck, cfg, error)
    if (allocated(error)) error stop error%message
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop error%message
    list = 6.0_wp*pi/180.0_wp
    bem = ship_bem(ship)
    a = bem%db%added_mass_inf
    allocate (dydt(size(y)), xdot(bem%db%nrad))
    ! a general state: attitude, heave, speeds, memory
    om = [0.05_wp, -0.02_wp, 0.01_wp]
    v = [0.0_wp, -0.5_wp, 0.8_wp]    ! no surge: the manoeuvring and resistance terms vanish
    y(ship%par%body%q(1):ship%par%body%q(1) + 2) = [list + 0.1_wp, 0.05_wp, 0.3_wp]
    y(ship%par%body%q(1) + 5) = y(ship%par%body%q(1) + 5) + 0.4_wp
    y(ship%par%body%u(1):ship%par%body%u(2)) = [om, v]
    do k = 1, bem%db%nrad
      y(ship%par%radiation%q(1) + k - 1) = 0.1_wp*sin(real(k, wp))
    end do
    call residual()
    call note(state, "largest term [N, N m]", scale)
    call check(state, maxval(abs(lhs - rhs)), 0.0_wp, "rigid body = Cummins' loads turned "// &
               "from the seakeeping frame", abs_tol=1.0e-9_wp*scale)
    ! heeled at its list, heaving at 1 m/s (inertial), memory of pure heave: no sway
    y(ship%par%body%q(1):ship%par%body%q(1) + 2) = [list, 0.0_wp, 0.0_wp]
    c = rotation_matrix([list, 0.0_wp, 0.0_wp])
    y(ship%par%body%u(1):ship%par%body%u(2)) = [0.0_wp, 0.0_wp, 0.0_wp, c(3, :)]
    y(ship%par%radiation%q(1):ship%par%radiation%q(2)) = 0.0_wp
    do k = 1, size(bem%db%pairs)
      associate (p => bem%db%pairs(k))
        i0 = ship%par%radiation%q(1) + p%first - 1
        if (p%j == 3) y(i0:i0 + p%n - 1) = p%b     ! the states after a 1 m/s, 1 s heave
      end associate
    end do
    call residual()
    acc(4:6) = matmul(c, dydt(ship%par%body%u(1) + 3:ship%par%body%u(2)))
    call note(state, "heeled ship heaving: vertical acceleration [m/s^2]", acc(6))
    call check(state, acc(5), 0.0_wp, "heeled ship heaving: no sway acceleration", &
               abs_tol=1.0e-9_wp*abs(acc(6)))
    call check(state, dydt(ship%par%body%u(1)), 0.0_wp, "heeled ship heaving: no roll "// &
               "acceleration", abs_tol=1.0e-9_wp*abs(acc(6))/box(2))
  contains

    !> lhs, rhs of the equations above (DOF order) at the state y; dydt its rates.
    subroutine residual()
      real(wp) :: f(6)
      associate (q => y(ship%par%body%q(1):ship%par%body%q(2)), &
                 u => y(ship%par%body%u(1):ship%par%body%u(2)))
        call ship%rhs(0.0_wp, y, dydt)
        c = rotation_matrix(q(1:3))
        m = matmul(transpose(c), rotation_matrix([0.0_wp, 0.0_wp, q(3)]))
        om = u(1:3)
        v = u(4:6)
        acc = [dydt(ship%par%body%u(1) + 3:ship%par%body%u(2)) + cross(om, v), &
               dydt(ship%par%body%u(1):ship%par%body%u(1) + 2)]
        lhs(1:3) = bem%mass*acc(1:3)
        lhs(4:6) = bem%inertia*acc(4:6) + cross(om, bem%inertia*om)
        call bem_memory(bem%db, y(ship%par%radiation%q(1):ship%par%radiation%q(2)), &
                        [matmul(transpose(m), v), matmul(transpose(m), om)], xdot, mu)
        delta = [0.0_wp, 0.0_wp, q(6) - ship%par%z_eq, q(1) - list, q(2), 0.0_wp]
        f = -matmul(a, [matmul(transpose(m), acc(1:3)), matmul(transpose(m), acc(4:6))]) - mu &
            - matmul(bem%db%stiffness, delta)
        rhs = [matmul(m, f(1:3)), matmul(m, f(4:6))]
        scale = max(maxval(abs(lhs)), maxval(abs(mu)), maxval(abs(rhs)))
      end associate
    end subroutine residual
  end subroutine seakeeping_frame

end module test_bem_ship
