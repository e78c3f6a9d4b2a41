!> The MMG ship with BEM seakeeping at headway (input/solas_headway.nml's ship, 5 kn):
!> the waves met at the encounter frequency omega_e = omega - k U cos(beta) in the
!> excitation (box and BEM ship; direct and through the Hermite wave clock), the speed
!> held in calm water at the self-propulsion revolutions (the radiation memory fed the
!> speeds about the steady forward motion; the propeller overcoming hull resistance and
!> still-air windage), and the autopilot's integral term by hand.
module test_mmg_bem
  use davit_kinds, only: wp, pi, gravity
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_core_rotation, only: rotation_matrix
  use davit_ship_ship_model, only: ship_system_type, ship_loads
  use system_fixture, only: is_bem_ship, is_mmg_ship, ship_rps
  use davit_core_slow_clock, only: slow_clock_type
  use davit_ship_rudder, only: rudder_type, rudder_order, autopilot_integral_rate, &
                               autopilot_order, autopilot_states, notch_period
  use davit_run_ship_scene, only: build_ship_scene
  use davit_solve_rk4, only: rk4_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_mmg_bem

  real(wp), parameter :: deg = pi/180.0_wp
  !> The deck's headway [m/s] and the test wave's period [s] (Level 5's peak period).
  real(wp), parameter :: headway = 2.57_wp, period = 12.72_wp
  character(len=*), parameter :: deck = "input/solas_headway.nml"

contains

  function collect_mmg_bem() result(suite)
    type(suite_type) :: suite
    suite%name = "mmg_bem"
    suite%cases = [new_case("encounter_frequency_head_and_following", encounter), &
                   new_case("encounter_frequency_kijima_ship", encounter_kijima), &
                   new_case("encounter_rate_in_the_wave_clock", wave_clock), &
                   new_case("calm_water_speed_held_at_self_propulsion", calm_speed), &
                   new_case("autopilot_integral_by_hand", integral_orders), &
                   new_case("autopilot_wave_filter_by_hand", wave_filter), &
                   new_case("autopilot_cascade_by_hand", cascade), &
                   new_case("autopilot_notch_gain_and_period", notch)]
  end function collect_mmg_bem

  !> The SOLAS headway deck as the ship alone ('ship' scene), its text with each
  !> (old, new) pair of `edits` replaced.
  subroutine headway_ship(edits, ship, y)
    character(len=*), intent(in) :: edits(:, :)
    type(ship_system_type), intent(out) :: ship
    real(wp), allocatable, intent(out) :: y(:)
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    character(len=:), allocatable :: text
    integer :: unit, length, k, j
    open (newunit=unit, file=deck, access="stream", form="unformatted", action="read")
    inquire (unit=unit, size=length)
    allocate (character(len=length) :: text)
    read (unit) text
    close (unit)
    text = edited(text, "scene = 'launch'", "scene = 'ship'")
    ! zero-speed kernels as these cases were written for (the speed terms: test_ship_speed;
    ! the box ship has none)
    text = edited(text, "speed_terms = 'heave_pitch'", "speed_terms = 'none'")
    do j = 1, size(edits, 2)
      k = index(text, trim(edits(1, j)))
      if (k == 0) error stop "test_mmg_bem: deck edit not found"
      text = edited(text, trim(edits(1, j)), trim(edits(2, j)))
    end do
    call parse_config(deck, text, cfg, error)
    if (allocated(error)) error stop "test_mmg_bem: deck"
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop "test_mmg_bem: ship"
  end subroutine headway_ship

  pure function edited(text, old, new) result(out)
    character(len=*), intent(in) :: text, old, new
    character(len=:), allocatable :: out
    integer :: k
    k = index(text, old)
    out = text
    if (k > 0) out = text(1:k - 1)//new//text(k + len(old):)
  end function edited

  !> The deck's &sea as a regular Airy wave of 2 m, `period`, travelling towards
  !> `direction_deg`, without start-up ramp; with `model` as the ship's level of detail.
  function wave_edits(direction_deg, model, extra) result(e)
    real(wp), intent(in) :: direction_deg
    character(len=*), intent(in) :: model, extra
    character(len=160) :: e(2, 3)
    character(len=16) :: a
    write (a, "(f0.1)") direction_deg
    e(:, 1) = [character(len=160) :: "wave_type = 'calm'", "wave_type = 'airy', "// &
               "height = 2.0, period = 12.72, ramp_periods = 0.0, direction_deg = "//trim(a)]
    e(:, 2) = [character(len=160) :: "model = 'bem'", "model = '"//model//"'"]
    e(:, 3) = [character(len=160) :: "t_end = 0.0", "t_end = 0.0"//extra]
  end function wave_edits

  !> Mean period [s] between the upward zero crossings of f - mean(f) sampled every dt.
  pure real(wp) function crossing_period(f, dt) result(tp)
    real(wp), intent(in) :: f(:), dt
    real(wp) :: g(size(f)), first, last, tc
    integer :: i, n
    g = f - sum(f)/size(f)
    n = 0
    first = 0.0_wp
    last = 0.0_wp
    do i = 1, size(g) - 1
      if (g(i) < 0.0_wp .and. g(i + 1) >= 0.0_wp) then
        tc = dt*(i - 1 + g(i)/(g(i) - g(i + 1)))
        if (n == 0) first = tc
        last = tc
        n = n + 1
      end if
    end do
    tp = (last - first)/max(n - 1, 1)
  end function crossing_period

  !> The ship making 5 kn (heading 0) in a regular 12.72 s Airy wave (omega = 0.494 rad/s,
  !> k = omega^2/g) from ahead (travelling towards 180 deg) and from astern (0 deg): its
  !> wave heave force at the initial pose is periodic with 2 pi/omega_e, omega_e = omega -
  !> k U cos(beta) (head 11.26 s, following 14.58 s), within 1 %, on the BEM and on the box
  !> ship; with U left out of the phase it would be 12.72 s (checked > 5 % away).
  subroutine encounter(state)
    type(case_state), intent(inout) :: state
    call encounter_periods(state, "mmg")
  end subroutine encounter

  !> The same with `&ship manoeuvring = 'kijima'` (linear derivatives, cross-flow drag and
  !> a constant thrust instead of the MMG model): a ship making way meets the waves at
  !> omega_e whatever its manoeuvring model (before, the 'kijima' ship's phases stayed at
  !> its initial position and it met them at omega: 12.72 s).
  subroutine encounter_kijima(state)
    type(case_state), intent(inout) :: state
    call encounter_periods(state, "kijima")
  end subroutine encounter_kijima

  !> The heave-force period of the encounter cases with `manoeuvring` as the ship's model.
  subroutine encounter_periods(state, manoeuvring)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: manoeuvring
    character(len=6), parameter :: models(2) = [character(len=6) :: "bem", "fk_box"]
    real(wp), parameter :: directions(2) = [180.0_wp, 0.0_wp], dt = 0.02_wp
    type(ship_system_type) :: ship
    real(wp), allocatable :: y(:)
    character(len=160) :: edits(2, 4)
    real(wp) :: f(10000), omega, k, we, tp, c(3, 3), q(6), u(6), load(6)
    integer :: i, j, m
    omega = 2.0_wp*pi/period
    k = omega**2/gravity
    do m = 1, 2
      do j = 1, 2
        edits(:, 1:3) = wave_edits(directions(j), trim(models(m)), "")
        edits(:, 4) = [character(len=160) :: "manoeuvring = 'mmg'", &
                       "manoeuvring = '"//manoeuvring//"'"]
        call headway_ship(edits, ship, y)
        call check_true(state, is_mmg_ship(ship) .eqv. manoeuvring == "mmg", "manoeuvring model")
        q = y(ship%par%body%q(1):ship%par%body%q(2))
        u = y(ship%par%body%u(1):ship%par%body%u(2))
        c = rotation_matrix(q(1:3))
        do i = 1, size(f)
          load = ship_loads(ship, dt*(i - 1), q, u, c)
          f(i) = load(3)
        end do
        we = omega - k*headway*cos(directions(j)*deg)
        tp = crossing_period(f, dt)
        call note(state, manoeuvring//" "//trim(models(m))//" heave-force period [s]", tp)
        call check(state, tp, 2.0_wp*pi/we, trim(models(m))//": period 2 pi/omega_e", &
                   rel_tol=0.01_wp)
        call check_true(state, abs(tp/period - 1.0_wp) > 0.05_wp, &
                        "encounter period apart from the wave's")
      end do
    end do
  end subroutine encounter_periods

  !> With `&simulation wave_update = 0.1` the BEM ship's wave loads come from cubic Hermite
  !> interpolation of samples and their rates; the rates are those of the encounter phase
  !> (omega_e), so the interpolated heave force in a head sea at 5 kn equals the direct one
  !> within 1e-6 of its amplitude (Hermite error (omega_e h)^4/384 = 2.5e-8; with omega
  !> in place of omega_e ~1e-3).
  subroutine wave_clock(state)
    type(case_state), intent(inout) :: state
    type(ship_system_type) :: cached, direct
    type(slow_clock_type) :: clock
    real(wp), allocatable :: y(:), y2(:)
    real(wp) :: c(3, 3), q(6), u(6), t, worst, amp, a(6), b(6), b0(6)
    integer :: i
    call headway_ship(wave_edits(180.0_wp, "bem", ", wave_update = 0.1"), cached, y)
    call headway_ship(wave_edits(180.0_wp, "bem", ""), direct, y2)
    q = y(cached%par%body%q(1):cached%par%body%q(2))
    u = y(cached%par%body%u(1):cached%par%body%u(2))
    c = rotation_matrix(q(1:3))
    worst = 0.0_wp
    amp = 0.0_wp
    b0 = ship_loads(direct, 0.0_wp, q, u, c)
    do i = 0, 400
      t = 0.1_wp*i
      call cached%after_step(t, y)
      t = t + 0.037_wp
      a = ship_loads(cached, t, q, u, c)
      b = ship_loads(direct, t, q, u, c)
      worst = max(worst, abs(a(3) - b(3)))
      amp = max(amp, abs(b(3) - b0(3)))
    end do
    call note(state, "largest interpolation error / amplitude", worst/amp)
    clock = cached%wave_clock()
    call check_true(state, clock%valid, "the wave clock is on")
    call check_true(state, worst < 1.0e-6_wp*amp, "interpolated = direct loads")
  end subroutine wave_clock

  !> input/solas_headway.nml's BEM/MMG ship alone in calm water and still air, the
  !> propeller at its self-propulsion revolutions (hull R_0 plus windage at 5 kn): 200 s
  !> of RK4 at 0.01 s keep the speed within 1 % of 2.57 m/s at every step (the memory,
  !> fed u - U, adds nothing at the steady speed; fed u, it costs 6.5 %), in fact to
  !> rounding (without the windage in the balance: 0.6 %), the ship straight, the rudder
  !> amidships.
  subroutine calm_speed(state)
    type(case_state), intent(inout) :: state
    character(len=1), parameter :: none(2, 0) = reshape([character(len=1) ::], [2, 0])
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t, worst, side
    integer :: i
    call headway_ship(none, ship, y)
    call rk%init(size(y))
    t = 0.0_wp
    worst = 0.0_wp
    side = 0.0_wp
    do i = 1, 20000
      call rk%step(ship, t, y, 0.01_wp)
      call ship%after_step(t, y)
      associate (u => y(ship%par%body%u(1):ship%par%body%u(2)), &
                 q => y(ship%par%body%q(1):ship%par%body%q(2)))
        worst = max(worst, abs(hypot(u(4), u(5))/headway - 1.0_wp))
        side = max(side, abs(q(3)) + abs(q(5)) + abs(y(ship%par%rudder%q(1))))
      end associate
    end do
    call note(state, "self-propulsion rps", ship_rps(ship))
    call note(state, "largest relative speed error", worst)
    call check_true(state, is_bem_ship(ship) .and. is_mmg_ship(ship), "the BEM/MMG ship")
    call check(state, worst, 0.0_wp, "speed held within 1 %", abs_tol=0.01_wp)
    ! the self-propulsion point balances exactly: a load left out of it (the windage:
    ! 0.6 % in 200 s) shows at once
    call check(state, worst, 0.0_wp, "speed held to rounding", abs_tol=1e-6_wp)
    call check(state, y(ship%par%body%q(1) + 3), 200.0_wp*headway, "distance in 200 s", &
               rel_tol=0.01_wp)
    call check(state, side, 0.0_wp, "straight, rudder amidships", abs_tol=1e-9_wp)
  end subroutine calm_speed

  !> The PID autopilot by hand: order -kp e - kd r - ki z (e = psi - psi_0, clipped to the
  !> angle limit); the integral's rate is e, held at zero while ki |z| alone passes the
  !> limit in the error's sense (anti-windup), free again when the error turns.
  subroutine integral_orders(state)
    type(case_state), intent(inout) :: state
    type(rudder_type) :: s
    s%mode = "autopilot"
    s%kp = 20.0_wp
    s%kd = 100.0_wp
    s%ki = 0.1_wp
    s%max_angle = 35.0_wp*deg
    s%heading = 0.1_wp
    call check(state, rudder_order(s, 5.0_wp, 0.1_wp + 0.002_wp, 1e-4_wp, 0.5_wp), &
               -20.0_wp*0.002_wp - 100.0_wp*1e-4_wp - 0.1_wp*0.5_wp, "PID order", &
               abs_tol=1e-14_wp)
    call check(state, rudder_order(s, 5.0_wp, 0.1_wp, 0.0_wp, -8.0_wp), 35.0_wp*deg, &
               "PID order clipped", abs_tol=1e-14_wp)
    call check(state, rudder_order(s, 5.0_wp, 0.1_wp + 0.002_wp, 1e-4_wp), &
               -20.0_wp*0.002_wp - 100.0_wp*1e-4_wp, "PD without z", abs_tol=1e-14_wp)
    call check(state, autopilot_integral_rate(s, 0.13_wp, 1.0_wp), 0.03_wp, &
               "integral rate = heading error", abs_tol=1e-14_wp)
    call check(state, autopilot_integral_rate(s, 0.13_wp, 7.0_wp), 0.0_wp, &
               "held past the limit", abs_tol=0.0_wp)
    call check(state, autopilot_integral_rate(s, 0.07_wp, 7.0_wp), -0.03_wp, &
               "free when the error turns", abs_tol=1e-14_wp)
  end subroutine integral_orders

  !> The autopilot of the by-hand cases: a PID (kp 10, kd 20 s, ki 0.1 1/s) on a set-point
  !> of 0.1 rad, 35 deg angle limit, one 5 s low-pass stage.
  pure function filtered_pid() result(s)
    type(rudder_type) :: s
    s%mode = "autopilot"
    s%kp = 10.0_wp
    s%kd = 20.0_wp
    s%ki = 0.1_wp
    s%max_angle = 35.0_wp*deg
    s%heading = 0.1_wp
    s%filter = 5.0_wp
  end function filtered_pid

  !> The autopilot's wave filter by hand (time constant T = 5 s): states x = (z, e_f, r_f)
  !> with rates ((e_f), (psi - psi_0 - e_f)/T, (r - r_f)/T), the order -kp e_f - kd r_f -
  !> ki z on the filtered error and rate; unfiltered (T = 0) the order takes psi and r and
  !> the filter states rest; a PD keeps no states, a PID or a filtered PD three.
  subroutine wave_filter(state)
    type(case_state), intent(inout) :: state
    type(rudder_type) :: s
    real(wp) :: order, xdot(3), x(3)
    s = filtered_pid()
    x = [0.2_wp, 0.01_wp, -0.002_wp]
    call autopilot_order(s, 3.0_wp, 0.13_wp, 0.004_wp, x, order, xdot)
    call check(state, order, -10.0_wp*0.01_wp - 20.0_wp*(-0.002_wp) - 0.1_wp*0.2_wp, &
               "order on the filtered error and rate", abs_tol=1e-14_wp)
    call check(state, xdot(1), 0.01_wp, "integral of the filtered error", abs_tol=1e-14_wp)
    call check(state, xdot(2), (0.03_wp - 0.01_wp)/5.0_wp, "error filter rate", &
               abs_tol=1e-14_wp)
    call check(state, xdot(3), (0.004_wp + 0.002_wp)/5.0_wp, "yaw-rate filter rate", &
               abs_tol=1e-14_wp)
    s%filter = 0.0_wp
    call autopilot_order(s, 3.0_wp, 0.13_wp, 0.004_wp, x, order, xdot)
    call check(state, order, -10.0_wp*0.03_wp - 20.0_wp*0.004_wp - 0.1_wp*0.2_wp, &
               "unfiltered order", abs_tol=1e-14_wp)
    call check(state, abs(xdot(2)) + abs(xdot(3)), 0.0_wp, "filter states rest", &
               abs_tol=0.0_wp)
    call check(state, real(autopilot_states(s), wp), 3.0_wp, "PID: three states", &
               abs_tol=0.0_wp)
    s%ki = 0.0_wp
    call check(state, real(autopilot_states(s), wp), 0.0_wp, "PD: none", abs_tol=0.0_wp)
    s%filter = 5.0_wp
    call check(state, real(autopilot_states(s), wp), 3.0_wp, "filtered PD: three", &
               abs_tol=0.0_wp)
  end subroutine wave_filter

  !> Two low-pass stages (filter_order = 2, T = 5 s) by hand: x = (z, e_1, e_2, r_1, r_2),
  !> rates (e_2, (e - e_1)/T, (e_1 - e_2)/T, (r - r_1)/T, (r_1 - r_2)/T), the order
  !> -kp e_2 - kd r_2 - ki z on the last stages; five states.
  subroutine cascade(state)
    type(case_state), intent(inout) :: state
    type(rudder_type) :: s
    real(wp) :: order, xdot(5), x(5)
    s = filtered_pid()
    s%filter_order = 2
    x = [0.2_wp, 0.01_wp, 0.02_wp, -0.002_wp, 0.001_wp]
    call autopilot_order(s, 3.0_wp, 0.13_wp, 0.004_wp, x, order, xdot)
    call check(state, order, -10.0_wp*0.02_wp - 20.0_wp*0.001_wp - 0.1_wp*0.2_wp, &
               "order on the last stages", abs_tol=1e-14_wp)
    call check(state, xdot(1), 0.02_wp, "integral of the filtered error", abs_tol=1e-14_wp)
    call check(state, xdot(2), (0.03_wp - 0.01_wp)/5.0_wp, "first error stage", &
               abs_tol=1e-14_wp)
    call check(state, xdot(3), (0.01_wp - 0.02_wp)/5.0_wp, "second error stage", &
               abs_tol=1e-14_wp)
    call check(state, xdot(4), (0.004_wp + 0.002_wp)/5.0_wp, "first rate stage", &
               abs_tol=1e-14_wp)
    call check(state, xdot(5), (-0.002_wp - 0.001_wp)/5.0_wp, "second rate stage", &
               abs_tol=1e-14_wp)
    call check(state, real(autopilot_states(s), wp), 5.0_wp, "five states", abs_tol=0.0_wp)
  end subroutine cascade

  !> The autopilot's notch (a P on the heading error, kp = 1, no low-pass) driven by a
  !> heading error A sin(w t), integrated by RK4: the steady order's amplitude is A |N(i w)|
  !> with N(s) = (s^2 + w0^2)/(s^2 + 2 zeta w0 s + w0^2), zeta = 0.5: zero at w = w0 (below
  !> 1 % of A), 0.9949 A at w0/10 and 0.9949 A at 10 w0 (within 0.5 %); seven states. The
  !> notch's period for a wave of 12.72 s towards 45 deg met at 2.57 m/s along x:
  !> 2 pi/(w - k U cos 45) = 14.00 s; for waves met from ahead, 2 pi/(w + k U).
  subroutine notch(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: w0 = 0.45_wp, ratio(3) = [1.0_wp, 0.1_wp, 10.0_wp]
    real(wp), parameter :: gain(3) = [0.0_wp, 0.99_wp/sqrt(0.99_wp**2 + 0.01_wp), &
                                      99.0_wp/sqrt(99.0_wp**2 + 100.0_wp)]
    type(rudder_type) :: s
    real(wp) :: w, omega, k, amp
    integer :: j
    s%mode = "autopilot"
    s%kp = 1.0_wp
    s%kd = 0.0_wp
    s%max_angle = 35.0_wp*deg
    s%notch = 2.0_wp*pi/w0
    call check(state, real(autopilot_states(s), wp), 7.0_wp, "seven states", abs_tol=0.0_wp)
    do j = 1, 3
      w = ratio(j)*w0
      amp = steady_amplitude(s, w)
      call note(state, "order amplitude / A", amp/0.01_wp)
      call check(state, amp/0.01_wp, gain(j), "|N(i w)|", abs_tol=merge(0.01_wp, 0.005_wp, j == 1))
    end do
    omega = 2.0_wp*pi/12.72_wp
    k = omega**2/gravity
    call check(state, notch_period([omega], [k*cos(45.0_wp*deg)], [k*sin(45.0_wp*deg)], &
                                   [2.0_wp], [2.57_wp, 0.0_wp]), &
               2.0_wp*pi/(omega - k*2.57_wp*cos(45.0_wp*deg)), "encounter period 45 deg", &
               rel_tol=1e-12_wp)
    call check(state, notch_period([omega, 2.0_wp*omega], [-k, -4.0_wp*k], [0.0_wp, 0.0_wp], &
                                   [2.0_wp, 0.1_wp], [2.57_wp, 0.0_wp]), &
               2.0_wp*pi/(omega + k*2.57_wp), "the largest component, head sea", &
               rel_tol=1e-12_wp)
  end subroutine notch

  !> Amplitude of the autopilot's order over the second half of 40 periods (of w or of the
  !> notch, the longer; RK4, 400 steps each) of a heading error 0.01 sin(w t).
  real(wp) function steady_amplitude(s, w) result(amp)
    type(rudder_type), intent(in) :: s
    real(wp), intent(in) :: w
    real(wp) :: x(7), k1(7), k2(7), k3(7), k4(7), order, t, h, tp
    integer :: i, n
    tp = max(2.0_wp*pi/w, s%notch)
    h = tp/400.0_wp
    n = 40*400
    x = 0.0_wp
    t = 0.0_wp
    amp = 0.0_wp
    do i = 1, n
      call autopilot_order(s, t, 0.01_wp*sin(w*t), 0.0_wp, x, order, k1)
      call autopilot_order(s, t, 0.01_wp*sin(w*(t + h/2)), 0.0_wp, x + h/2*k1, order, k2)
      call autopilot_order(s, t, 0.01_wp*sin(w*(t + h/2)), 0.0_wp, x + h/2*k2, order, k3)
      call autopilot_order(s, t, 0.01_wp*sin(w*(t + h)), 0.0_wp, x + h*k3, order, k4)
      x = x + h/6*(k1 + 2*k2 + 2*k3 + k4)
      t = t + h
      call autopilot_order(s, t, 0.01_wp*sin(w*t), 0.0_wp, x, order, k1)
      if (i > n/2) amp = max(amp, abs(order))
    end do
  end function steady_amplitude

end module test_mmg_bem
