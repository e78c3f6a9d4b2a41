!> The standard MMG model (Yasukawa & Yoshimura 2015) and the rudder: every force term
!> against a hand computation from the published KVLCC2 coefficients (Tables 2-4) at two
!> stated states, one on each side of the sign switches of C_2 and gamma_R; the
!> self-propulsion point; straight running holds the speed; the autopilot holds a
!> course-unstable ship's heading; the steering gear's rate limit.
!>
!> The expected numbers were computed outside davit from the paper's formulas written
!> with J_P = u (1 - w_P)/(n D_P), K_T(J_P) and sqrt(1 + 8 K_T/(pi J_P^2)) as printed
!> (davit writes them as polynomials in n and u_P), rho = 1025 kg/m^3, L = 7 m,
!> d = 0.46 m.
module test_mmg
  use davit_kinds, only: wp, pi
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config, read_config
  use davit_ship_mmg, only: mmg_type, mmg_motion, mmg_hull, mmg_propeller, mmg_rudder, mmg_wake, &
                            mmg_rudder_inflow, mmg_total, mmg_self_propulsion
  use davit_ship_mmg_loads, only: mmg_body_load
  use davit_ship_rudder, only: rudder_type, rudder_order, rudder_rate, rudder_switch, &
                               rudder_servo_time
  use davit_core_rotation, only: rotation_matrix
  use davit_ship_ship_model, only: ship_system_type
  use system_fixture, only: is_bem_ship, is_mmg_ship
  use davit_run_ship_scene, only: build_ship_scene
  use davit_solve_rk4, only: rk4_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_mmg

  real(wp), parameter :: deg = pi/180.0_wp
  !> State A: u, v_m, r, delta, n with beta_P, beta_R > 0; state B: both < 0.
  real(wp), parameter :: state_a(5) = [1.0_wp, -0.12_wp, 0.04_wp, 0.2_wp, 11.0_wp]
  real(wp), parameter :: state_b(5) = [1.1_wp, 0.15_wp, -0.06_wp, -0.3_wp, 9.0_wp]
  real(wp), parameter :: hull_a(3) = [-3.620647667066246e+01_wp, 1.148226887434051e+02_wp, &
                                      9.436892306185715e+00_wp]
  real(wp), parameter :: hull_b(3) = [-4.271492472023328e+01_wp, -1.800774418248466e+02_wp, &
                                      5.340484419563671e+01_wp]
  real(wp), parameter :: prop_a = 4.074371241251968e+01_wp, wake_a = 7.428993903076728e-01_wp
  real(wp), parameter :: prop_b = 2.505628482948067e+01_wp, wake_b = 6.281796876209440e-01_wp
  real(wp), parameter :: rudder_a(3) = [-4.651245569086680e-01_wp, -4.910971119213664e+00_wp, &
                                        1.689409998944519e+01_wp]
  real(wp), parameter :: rudder_b(3) = [-2.020653691156948e+00_wp, 1.398087758848951e+01_wp, &
                                        -4.809524189544697e+01_wp]
  real(wp), parameter :: inflow_a(2) = [1.213326427476908e+00_wp, 2.042148740976753e-01_wp]
  real(wp), parameter :: inflow_b(2) = [1.043050300401256e+00_wp, -1.772207710803365e-01_wp]

contains

  function collect_mmg() result(suite)
    type(suite_type) :: suite
    suite%name = "mmg"
    suite%cases = [new_case("kvlcc2_terms_by_hand", terms_by_hand), &
                   new_case("self_propulsion_point", self_propulsion), &
                   new_case("straight_running_holds_speed", straight_running), &
                   new_case("autopilot_holds_unstable_heading", autopilot), &
                   new_case("steering_gear_rate_limit", steering_gear), &
                   new_case("mmg_on_bem_ship_frame", bem_frame), &
                   new_case("forces_in_the_horizontal_body_frame", horizontal_frame), &
                   new_case("autopilot_and_steering_orders", steering_orders)]
  end function collect_mmg

  !> The MMG coefficients of a deck, with its L_pp and draught.
  function coefficients(cfg) result(p)
    type(config_type), intent(in) :: cfg
    type(mmg_type) :: p
    p = cfg%ship%mmg
    p%lpp = cfg%ship%lpp
    p%draught = cfg%ship%draught
  end function coefficients

  !> Hull X_H, Y_H, N_H (eqs. 8-10), propeller X_P with the wake's sideslip correction
  !> (eqs. 14-16), rudder inflow u_R, v_R and X_R, Y_R, N_R (eqs. 18-27), each to 1e-10
  !> of the hand value, for the KVLCC2 deck input/kvlcc2.nml and for the &mmg keys'
  !> defaults (both the published set). Every coefficient moves some term by more than
  !> 1e-4 of it at these states, so a changed coefficient or sign fails.
  subroutine terms_by_hand(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg(2)
    type(error_type), allocatable :: error
    type(mmg_type) :: p
    integer :: i
    call read_config("input/kvlcc2.nml", cfg(1), error)
    call check_true(state, .not. allocated(error), "input/kvlcc2.nml reads")
    if (allocated(error)) return
    call parse_config("t.nml", "&ship length_pp = 7.0, draught = 0.46, "// &
                      "manoeuvring = 'mmg' /", cfg(2), error)
    call check_true(state, .not. allocated(error), "defaults read")
    if (allocated(error)) return
    do i = 1, 2
      p = coefficients(cfg(i))
      call compare(p, state_a, hull_a, prop_a, wake_a, inflow_a, rudder_a, &
                   trim(merge("deck A   ", "default A", i == 1)))
      call compare(p, state_b, hull_b, prop_b, wake_b, inflow_b, rudder_b, &
                   trim(merge("deck B   ", "default B", i == 1)))
    end do
  contains
    subroutine compare(p, s, hull, prop, wake, inflow, rudder, what)
      type(mmg_type), intent(in) :: p
      real(wp), intent(in) :: s(5), hull(3), prop, wake, inflow(2), rudder(3)
      character(len=*), intent(in) :: what
      real(wp) :: f(3), uv(2)
      integer :: k
      character(len=*), parameter :: names(3) = ["X", "Y", "N"]
      f = mmg_hull(p, mmg_motion(s(1), s(2), s(3)))
      do k = 1, 3
        call check(state, f(k), hull(k), what//": hull "//names(k), rel_tol=1e-10_wp)
      end do
      call check(state, mmg_wake(p, mmg_motion(s(1), s(2), s(3))), wake, what//": 1 - w_P", &
                 rel_tol=1e-12_wp)
      f = mmg_propeller(p, mmg_motion(s(1), s(2), s(3), n=s(5)))
      call check(state, f(1), prop, what//": X_P", rel_tol=1e-10_wp)
      call check(state, maxval(abs(f(2:3))), 0.0_wp, what//": Y_P, N_P", abs_tol=0.0_wp)
      uv = mmg_rudder_inflow(p, mmg_motion(s(1), s(2), s(3), n=s(5)))
      call check(state, uv(1), inflow(1), what//": u_R", rel_tol=1e-10_wp)
      call check(state, uv(2), inflow(2), what//": v_R", rel_tol=1e-10_wp)
      f = mmg_rudder(p, mmg_motion(s(1), s(2), s(3), s(4), s(5)))
      do k = 1, 3
        call check(state, f(k), rudder(k), what//": rudder "//names(k), rel_tol=1e-10_wp)
      end do
      f = mmg_total(p, mmg_motion(s(1), s(2), s(3), s(4), s(5)))
      call check(state, f(1), hull(1) + prop + rudder(1), what//": total X", rel_tol=1e-10_wp)
    end subroutine compare
  end subroutine terms_by_hand

  !> The rps that holds 1.176 m/s: (1 - t_P) rho n^2 D^4 K_T(J) = 1/2 rho L d U^2 R'_0,
  !> solved by hand: 11.821433597518 1/s (SIMMAN's model ran 10.4 rps with its own
  !> propeller and friction correction; this is the MMG set's own balance). At that rps
  !> the straight-running surge force vanishes.
  subroutine self_propulsion(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(mmg_type) :: p
    real(wp) :: n, f(3)
    call read_config("input/kvlcc2.nml", cfg, error)
    if (allocated(error)) error stop "input/kvlcc2.nml"
    p = coefficients(cfg)
    n = mmg_self_propulsion(p, 1.176_wp)
    call note(state, "self-propulsion rps", n)
    call check(state, n, 11.821433597518_wp, "n at 1.176 m/s", rel_tol=1e-10_wp)
    f = mmg_total(p, mmg_motion(1.176_wp, 0.0_wp, 0.0_wp, 0.0_wp, n))
    call check(state, f(1), 0.0_wp, "X at the self-propulsion point", abs_tol=1e-10_wp)
  end subroutine self_propulsion

  !> Integrate a ship deck (its text with `old` replaced by `new`) with RK4 (dt 0.02 s)
  !> from its initial state plus `kick` for n steps; returns the final state and the
  !> largest |rudder angle|.
  subroutine run_deck(deck, old, new, kick, n, y, rudder_max)
    character(len=*), intent(in) :: deck, old, new
    real(wp), intent(in) :: kick(:)
    integer, intent(in) :: n
    real(wp), allocatable, intent(out) :: y(:)
    real(wp), intent(out) :: rudder_max
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp) :: t
    integer :: i, unit, length, k
    character(len=:), allocatable :: text
    open (newunit=unit, file=deck, access="stream", form="unformatted", action="read")
    inquire (unit=unit, size=length)
    allocate (character(len=length) :: text)
    read (unit) text
    close (unit)
    k = index(text, old)
    if (len(old) > 0 .and. k > 0) text = text(1:k - 1)//new//text(k + len(old):)
    call parse_config(deck, text, cfg, error)
    if (allocated(error)) error stop "mmg test deck"
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) error stop "mmg test ship"
    y(1:size(kick)) = y(1:size(kick)) + kick
    call rk%init(size(y))
    t = 0.0_wp
    rudder_max = 0.0_wp
    do i = 1, n
      call rk%step(ship, t, y, 0.02_wp)
      call ship%after_step(t, y)
      rudder_max = max(rudder_max, abs(y(ship%par%rudder%q(1))))
    end do
  end subroutine run_deck

  !> input/kvlcc2.nml (self-propulsion rps, autopilot) runs 60 s straight: speed within
  !> 1 % of 1.176 m/s (it holds it to rounding), distance 60 U, no yaw, rudder amidships.
  subroutine straight_running(state)
    type(case_state), intent(inout) :: state
    real(wp), allocatable :: y(:)
    real(wp) :: rmax, zero(1)
    zero = 0.0_wp
    call run_deck("input/kvlcc2.nml", "", "", zero, 3000, y, rmax)
    call note(state, "speed after 60 s [m/s]", hypot(y(10), y(11)))
    call check(state, hypot(y(10), y(11)), 1.176_wp, "speed held", rel_tol=0.01_wp)
    call check(state, y(4), 60.0_wp*1.176_wp, "distance in 60 s", rel_tol=1e-6_wp)
    call check(state, abs(y(3)) + abs(y(5)) + rmax, 0.0_wp, "straight, rudder amidships", &
               abs_tol=1e-12_wp)
  end subroutine straight_running

  !> The KVLCC2 is course-unstable (Y'_v N'_r - N'_v (Y'_r - m' - m'_x) < 0): kicked to
  !> 0.02 rad/s of yaw rate with the rudder held amidships it turns away (16.8 deg after
  !> 90 s; checked > 10 deg);
  !> the autopilot (PD, gain 2, derivative 3 s) brings the heading back within 0.5 deg
  !> with less than 35 deg of rudder.
  subroutine autopilot(state)
    type(case_state), intent(inout) :: state
    real(wp), allocatable :: y(:)
    real(wp) :: rmax, kick(9)
    kick = 0.0_wp
    kick(9) = 0.02_wp
    call run_deck("input/kvlcc2.nml", "rudder_mode = 'autopilot'", "rudder_mode = 'fixed'", &
                  kick, 4500, y, rmax)
    call note(state, "heading after 90 s, rudder fixed [deg]", y(3)/deg)
    call check_true(state, abs(y(3)) > 10.0_wp*deg, "unsteered ship turns away")
    call run_deck("input/kvlcc2.nml", "", "", kick, 4500, y, rmax)
    call note(state, "heading after 90 s, autopilot [deg]", y(3)/deg)
    call note(state, "largest rudder [deg]", rmax/deg)
    call check(state, y(3), 0.0_wp, "autopilot heading", abs_tol=0.5_wp*deg)
    call check_true(state, rmax < 35.0_wp*deg .and. rmax > 1.0_wp*deg, "rudder used, in range")
  end subroutine autopilot

  !> The turning deck's 35 deg order at t = 1 s: the rudder moves at the rate limit
  !> 15.68 deg/s (7.84 deg between t = 1.5 s and 2 s), then holds 35 deg (the servo's tail
  !> exp(-t/0.1 s) is gone 1 s after the limit ends) and never passes it.
  subroutine steering_gear(state)
    type(case_state), intent(inout) :: state
    real(wp), allocatable :: y(:)
    real(wp) :: rmax, zero(1), d15
    zero = 0.0_wp
    call run_deck("input/kvlcc2_turning_35.nml", "", "", zero, 75, y, rmax)
    d15 = y(13)
    call run_deck("input/kvlcc2_turning_35.nml", "", "", zero, 100, y, rmax)
    call check(state, y(13) - d15, 0.5_wp*15.68_wp*deg, "rudder travel in 0.5 s", &
               rel_tol=1e-9_wp)
    call run_deck("input/kvlcc2_turning_35.nml", "", "", zero, 225, y, rmax)
    call check(state, y(13), 35.0_wp*deg, "rudder 3.5 s after the order", rel_tol=1e-6_wp)
    call check_true(state, rmax <= 35.0_wp*deg*(1.0_wp + 1e-12_wp), "never past the order")
  end subroutine steering_gear

  !> The MMG forces live in the horizontal-body frame: on a ship heeled 10 deg, trimmed
  !> 3 deg and yawed 40 deg, with speeds u (ship axes), the load turned back into the level
  !> yawed frame (m^T load, m = C^T R_z(psi)) equals the load of the upright ship moving
  !> with the level-frame speeds m^T u: horizontal forces and a vertical yaw moment only.
  subroutine horizontal_frame(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(mmg_type) :: p
    real(wp) :: c(3, 3), m(3, 3), u(6), heeled(6), upright(6), eye(3, 3), level(6)
    integer :: k
    call read_config("input/kvlcc2.nml", cfg, error)
    if (allocated(error)) error stop "input/kvlcc2.nml"
    p = coefficients(cfg)
    c = rotation_matrix([10.0_wp*deg, 3.0_wp*deg, 40.0_wp*deg])
    m = matmul(transpose(c), rotation_matrix([0.0_wp, 0.0_wp, 40.0_wp*deg]))
    u = [0.01_wp, -0.02_wp, 0.05_wp, 1.0_wp, -0.1_wp, 0.03_wp]
    heeled = mmg_body_load(p, 0.25_wp, 20.0_wp, 250.0_wp, m, u, 0.2_wp, 11.0_wp)
    eye = 0.0_wp
    do k = 1, 3
      eye(k, k) = 1.0_wp
    end do
    upright = mmg_body_load(p, 0.25_wp, 20.0_wp, 250.0_wp, eye, &
                            [matmul(transpose(m), u(1:3)), matmul(transpose(m), u(4:6))], &
                            0.2_wp, 11.0_wp)
    level = [matmul(transpose(m), heeled(1:3)), matmul(transpose(m), heeled(4:6))]
    call check(state, maxval(abs(upright([3, 4, 5]))), 0.0_wp, "upright: no Z, K, M", &
               abs_tol=0.0_wp)
    do k = 1, 6
      call check(state, level(k), upright(k), "level-frame component", &
                 abs_tol=1e-12_wp*maxval(abs(upright)))
    end do
  end subroutine horizontal_frame

  !> The orders by hand: autopilot -K_p (psi - psi_0) - K_d r (a heading error to starboard
  !> asks for port rudder) clipped to the angle limit; the turning order only from its
  !> start; the servo rate (order - delta)/tau inside +-rate; the zig-zag side reverses at
  !> +switch, stays until -switch, then reverses back.
  subroutine steering_orders(state)
    type(case_state), intent(inout) :: state
    type(rudder_type) :: s
    s%mode = "autopilot"
    s%kp = 2.0_wp
    s%kd = 3.0_wp
    s%max_angle = 35.0_wp*deg
    s%rate = 15.68_wp*deg
    s%heading = 0.1_wp
    call check(state, rudder_order(s, 5.0_wp, 0.15_wp, 0.004_wp), &
               -2.0_wp*0.05_wp - 3.0_wp*0.004_wp, "autopilot order", abs_tol=1e-14_wp)
    call check(state, rudder_order(s, 5.0_wp, -0.5_wp, 0.0_wp), 35.0_wp*deg, &
               "autopilot order clipped", abs_tol=1e-14_wp)
    s%mode = "turning"
    s%angle = -20.0_wp*deg
    s%start = 1.0_wp
    call check(state, rudder_order(s, 0.99_wp, 0.0_wp, 0.0_wp), 0.0_wp, "before the start", &
               abs_tol=0.0_wp)
    call check(state, rudder_order(s, 1.0_wp, 0.0_wp, 0.0_wp), -20.0_wp*deg, "from the start", &
               abs_tol=1e-14_wp)
    call check(state, rudder_rate(s, 0.0_wp, 0.01_wp), 0.01_wp/rudder_servo_time, &
               "servo inside the limit", abs_tol=1e-14_wp)
    call check(state, rudder_rate(s, 0.0_wp, -0.5_wp), -15.68_wp*deg, "rate limit", &
               abs_tol=1e-14_wp)
    s%mode = "zigzag"
    s%angle = 10.0_wp*deg
    s%switch = 10.0_wp*deg
    s%heading = 0.0_wp
    s%side = 1.0_wp
    call rudder_switch(s, 2.0_wp, 9.9_wp*deg)
    call check(state, s%side, 1.0_wp, "no reversal below the switch", abs_tol=0.0_wp)
    call rudder_switch(s, 2.0_wp, 10.1_wp*deg)
    call check(state, s%side, -1.0_wp, "reversed at +switch", abs_tol=0.0_wp)
    call check(state, rudder_order(s, 2.0_wp, 0.0_wp, 0.0_wp), -10.0_wp*deg, "port order", &
               abs_tol=1e-14_wp)
    call rudder_switch(s, 3.0_wp, 0.0_wp)
    call check(state, s%side, -1.0_wp, "held between the switches", abs_tol=0.0_wp)
    call rudder_switch(s, 4.0_wp, -10.1_wp*deg)
    call check(state, s%side, 1.0_wp, "back at -switch", abs_tol=0.0_wp)
  end subroutine steering_orders

  !> &ship manoeuvring = 'mmg' on the BEM ship (model = 'bem'): the ship builds with the
  !> MMG model and its seakeeping frame moves at the headway along the initial heading:
  !> U (cos psi_0, sin psi_0) = 2 (cos 30, sin 30) m/s for heading_deg = 30, headway = 2.
  subroutine bem_frame(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(ship_system_type) :: ship
    real(wp), allocatable :: y(:)
    call parse_config("t.nml", "&simulation scene = 'ship' / &ship model = 'bem', "// &
                      "manoeuvring = 'mmg', heading_deg = 30.0, headway = 2.0 /", cfg, error)
    call check_true(state, .not. allocated(error), "deck reads")
    if (allocated(error)) return
    call build_ship_scene(cfg, ship, y, error)
    call check_true(state, .not. allocated(error), "accepted")
    if (allocated(error)) return
    call check_true(state, is_bem_ship(ship) .and. is_mmg_ship(ship), "BEM ship with MMG")
    call check(state, ship%par%frame_speed, 2.0_wp, "frame speed", abs_tol=0.0_wp)
    call check(state, ship%par%frame_velocity(1), 2.0_wp*cos(30.0_wp*deg), "frame velocity x", &
               abs_tol=1e-14_wp)
    call check(state, ship%par%frame_velocity(2), 2.0_wp*sin(30.0_wp*deg), "frame velocity y", &
               abs_tol=1e-14_wp)
  end subroutine bem_frame

end module test_mmg
