!> Deck keys of the standard MMG manoeuvring model and the steering (group "mmg", used
!> when `&ship manoeuvring = 'mmg'`). Defaults: the KVLCC2 L = 7 m model of Yasukawa &
!> Yoshimura 2015 (J. Mar. Sci. Technol. 20:37-52, Tables 2-4), at model scale.
module davit_io_mmg_keys
  use davit_kinds, only: wp, pi
  use davit_io_deck_reader, only: deck_reader_type
  use davit_ship_mmg, only: mmg_type
  use davit_ship_rudder, only: rudder_type
  implicit none
  private
  public :: read_mmg

  character(len=*), parameter :: g = "mmg"
  real(wp), parameter :: deg = pi/180.0_wp
  !> Bounds of a non-dimensional hull derivative.
  real(wp), parameter :: dmax = 10.0_wp

contains

  !> The MMG coefficients, the propeller revolutions [1/s] (0: the self-propulsion point
  !> at &ship headway) and the steering.
  subroutine read_mmg(r, p, rps, steer)
    !> The deck's reader, positioned at the &mmg group.
    type(deck_reader_type), intent(inout) :: r
    !> The MMG coefficients, defaults (KVLCC2) in, the deck's read over them.
    type(mmg_type), intent(inout) :: p
    !> Propeller revolutions [1/s] (0: the self-propulsion point at &ship headway).
    real(wp), intent(out) :: rps
    !> The rudder's steering (autopilot or orders).
    type(rudder_type), intent(out) :: steer
    call read_hull(r, p)
    call read_propeller(r, p, rps)
    call read_rudder(r, p)
    call read_steering(r, steer)
  end subroutine read_mmg

  !> One hull derivative (non-dimensional, Yasukawa & Yoshimura 2015 eqs. 8-10).
  subroutine deriv(r, key, x, default, text)
    type(deck_reader_type), intent(inout) :: r
    character(len=*), intent(in) :: key, text
    real(wp), intent(out) :: x
    real(wp), intent(in) :: default
    call r%real(g, key, x, default, -dmax, dmax, "-", text//" (Table 3, KVLCC2).")
  end subroutine deriv

  subroutine read_hull(r, p)
    type(deck_reader_type), intent(inout) :: r
    type(mmg_type), intent(inout) :: p
    call r%real(g, "r0", p%r0, 0.022_wp, 0.0_wp, 1.0_wp, "-", &
                "Straight-running resistance R'_0 on 1/2 rho L d U^2 (Table 3, KVLCC2).")
    call deriv(r, "x_vv", p%xvv, -0.040_wp, "Hull surge derivative X'_vv")
    call deriv(r, "x_vr", p%xvr, 0.002_wp, "Hull surge derivative X'_vr")
    call deriv(r, "x_rr", p%xrr, 0.011_wp, "Hull surge derivative X'_rr")
    call deriv(r, "x_vvvv", p%xvvvv, 0.771_wp, "Hull surge derivative X'_vvvv")
    call deriv(r, "y_v", p%yv, -0.315_wp, "Hull sway derivative Y'_v")
    call deriv(r, "y_r", p%yr, 0.083_wp, "Hull sway derivative Y'_R")
    call deriv(r, "y_vvv", p%yvvv, -1.607_wp, "Hull sway derivative Y'_vvv")
    call deriv(r, "y_vvr", p%yvvr, 0.379_wp, "Hull sway derivative Y'_vvr")
    call deriv(r, "y_vrr", p%yvrr, -0.391_wp, "Hull sway derivative Y'_vrr")
    call deriv(r, "y_rrr", p%yrrr, 0.008_wp, "Hull sway derivative Y'_rrr")
    call deriv(r, "n_v", p%nv, -0.137_wp, "Hull yaw derivative N'_v")
    call deriv(r, "n_r", p%nr, -0.049_wp, "Hull yaw derivative N'_R")
    call deriv(r, "n_vvv", p%nvvv, -0.030_wp, "Hull yaw derivative N'_vvv")
    call deriv(r, "n_vvr", p%nvvr, -0.294_wp, "Hull yaw derivative N'_vvr")
    call deriv(r, "n_vrr", p%nvrr, 0.055_wp, "Hull yaw derivative N'_vrr")
    call deriv(r, "n_rrr", p%nrrr, -0.013_wp, "Hull yaw derivative N'_rrr")
    call r%real(g, "m_x", p%mx, 0.022_wp, 0.0_wp, 2.0_wp, "-", &
                "Surge added mass m'_x on 1/2 rho L^2 d (Table 3, KVLCC2); replaces the "// &
                "box's surge added mass.")
    call r%real(g, "m_y", p%my, 0.223_wp, 0.0_wp, 2.0_wp, "-", &
                "Sway added mass m'_y on 1/2 rho L^2 d (Table 3, KVLCC2), at midship.")
    call r%real(g, "j_z", p%jz, 0.011_wp, 0.0_wp, 1.0_wp, "-", &
                "Added yaw inertia J'_z on 1/2 rho L^4 d (Table 3, KVLCC2), about midship.")
  end subroutine read_hull

  subroutine read_propeller(r, p, rps)
    type(deck_reader_type), intent(inout) :: r
    type(mmg_type), intent(inout) :: p
    real(wp), intent(out) :: rps
    call r%real(g, "propeller_diameter", p%dp, 0.216_wp, 0.01_wp, 20.0_wp, "m", &
                "Propeller diameter D_P (Table 2, KVLCC2 model).")
    call r%real(g, "propeller_rps", rps, 0.0_wp, 0.0_wp, 100.0_wp, "1/s", &
                "Propeller revolutions n, constant; 0 = the self-propulsion point that "// &
                "holds &ship headway in straight running.")
    call r%real(g, "k0", p%k0, 0.2931_wp, -2.0_wp, 2.0_wp, "-", &
                "Open-water thrust K_T = k0 + k1 J + k2 J^2 (Table 4, KVLCC2).")
    call r%real(g, "k1", p%k1, -0.2753_wp, -2.0_wp, 2.0_wp, "-", "K_T slope k1 (Table 4).")
    call r%real(g, "k2", p%k2, -0.1385_wp, -2.0_wp, 2.0_wp, "-", "K_T curvature k2 (Table 4).")
    call r%real(g, "t_p", p%tp, 0.220_wp, 0.0_wp, 0.9_wp, "-", &
                "Thrust deduction factor t_P (Table 4).")
    call r%real(g, "w_p0", p%wp0, 0.40_wp, 0.0_wp, 0.9_wp, "-", &
                "Wake fraction w_P0 at the propeller in straight running (Table 4).")
    call r%real(g, "x_p", p%xp, -0.48_wp, -1.0_wp, 0.0_wp, "-", &
                "Propeller position x'_P on L_pp from midship (Table 4).")
    call r%real(g, "c1", p%c1, 2.0_wp, 0.0_wp, 20.0_wp, "-", &
                "Wake change with the propeller inflow angle: C_1 (eq. 16, Table 4).")
    call r%real(g, "c2_plus", p%c2_plus, 1.6_wp, 0.0_wp, 5.0_wp, "-", &
                "C_2 for beta_P > 0 (eq. 16, Table 4).")
    call r%real(g, "c2_minus", p%c2_minus, 1.1_wp, 0.0_wp, 5.0_wp, "-", &
                "C_2 for beta_P < 0 (eq. 16, Table 4).")
  end subroutine read_propeller

  subroutine read_rudder(r, p)
    type(deck_reader_type), intent(inout) :: r
    type(mmg_type), intent(inout) :: p
    call r%real(g, "rudder_area", p%area, 0.0539_wp, 0.0_wp, 1000.0_wp, "m^2", &
                "Rudder area A_R (Table 2, KVLCC2 model).")
    call r%real(g, "rudder_span", p%span, 0.345_wp, 0.01_wp, 50.0_wp, "m", &
                "Rudder span H_R (Table 2); eta = D_P/H_R.")
    call r%real(g, "f_alpha", p%f_alpha, 2.747_wp, 0.0_wp, 10.0_wp, "-", &
                "Rudder normal-force gradient f_alpha (Table 4).")
    call r%real(g, "epsilon", p%eps, 1.09_wp, 0.1_wp, 3.0_wp, "-", &
                "Wake ratio rudder/propeller epsilon (Table 4).")
    call r%real(g, "kappa", p%kappa, 0.50_wp, 0.0_wp, 2.0_wp, "-", &
                "Propeller-race factor kappa (Table 4).")
    call r%real(g, "t_r", p%tr, 0.387_wp, 0.0_wp, 1.0_wp, "-", &
                "Steering resistance deduction t_R (Table 4).")
    call r%real(g, "a_h", p%ah, 0.312_wp, 0.0_wp, 2.0_wp, "-", &
                "Rudder force increase a_H (hull interaction, Table 4).")
    call r%real(g, "x_h", p%xh, -0.464_wp, -1.0_wp, 0.0_wp, "-", &
                "Position x'_H of the hull's share of the rudder force (Table 4).")
    call r%real(g, "x_r", p%xr, -0.5_wp, -1.0_wp, 0.0_wp, "-", &
                "Rudder position x'_R on L_pp from midship (Table 4).")
    call r%real(g, "l_r", p%lr, -0.710_wp, -2.0_wp, 0.0_wp, "-", &
                "Effective lever l'_R of the yaw rate in the rudder inflow angle (Table 4).")
    call r%real(g, "gamma_plus", p%gamma_plus, 0.640_wp, 0.0_wp, 2.0_wp, "-", &
                "Flow-straightening gamma_R for beta_R > 0 (Table 4).")
    call r%real(g, "gamma_minus", p%gamma_minus, 0.395_wp, 0.0_wp, 2.0_wp, "-", &
                "Flow-straightening gamma_R for beta_R < 0 (Table 4).")
  end subroutine read_rudder

  subroutine read_steering(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(rudder_type), intent(out) :: s
    character(len=:), allocatable :: mode
    call r%choice(g, "rudder_mode", mode, "autopilot", &
                  [character(len=9) :: "autopilot", "fixed", "turning", "zigzag"], &
                  "Rudder orders: a PD autopilot on the initial heading, a fixed angle, "// &
                  "a turning circle (rudder_deg from manoeuvre_start) or a zig-zag "// &
                  "(+-rudder_deg, first to starboard, reversed at +-zigzag_heading_deg).")
    s%mode = mode
    call r%real(g, "rudder_deg", s%angle, 0.0_wp, -45.0_wp, 45.0_wp, "deg", &
                "Ordered rudder angle (fixed, turning) or zig-zag rudder angle; "// &
                "positive turns to starboard.")
    s%angle = s%angle*deg
    call r%real(g, "zigzag_heading_deg", s%switch, 10.0_wp, 1.0_wp, 90.0_wp, "deg", &
                "Zig-zag: heading change that reverses the rudder.")
    s%switch = s%switch*deg
    call r%real(g, "manoeuvre_start", s%start, 0.0_wp, 0.0_wp, 1.0e5_wp, "s", &
                "Time of the turning or zig-zag order (rudder amidships before).")
    call r%real(g, "rudder_rate_deg", s%rate, 2.32_wp, 0.1_wp, 50.0_wp, "deg/s", &
                "Rudder rate limit (IMO full scale 2.32 deg/s; SIMMAN KVLCC2 model "// &
                "15.68 deg/s).")
    s%rate = s%rate*deg
    call r%real(g, "rudder_max_deg", s%max_angle, 35.0_wp, 1.0_wp, 45.0_wp, "deg", &
                "Rudder angle limit.")
    s%max_angle = s%max_angle*deg
    call r%real(g, "autopilot_gain", s%kp, 2.0_wp, 0.0_wp, 50.0_wp, "-", &
                "Autopilot: rudder angle per heading error.")
    call r%real(g, "autopilot_derivative", s%kd, 10.0_wp, 0.0_wp, 1000.0_wp, "s", &
                "Autopilot: rudder angle per yaw rate (the D of the PD).")
    call r%real(g, "autopilot_integral", s%ki, 0.0_wp, 0.0_wp, 10.0_wp, "1/s", &
                "Autopilot: rudder angle per time integral of the heading error (the I "// &
                "of a PID, against steady yaw moments such as the wind's); 0 = PD only.")
    call r%real(g, "autopilot_filter", s%filter, 0.0_wp, 0.0_wp, 100.0_wp, "s", &
                "Autopilot: time constant of its wave filter, first-order low-pass stages on "// &
                "the heading error and yaw rate it steers by, so that the rudder does not "// &
                "chase the wave-frequency yaw; 0 = unfiltered.")
    call r%int(g, "autopilot_filter_order", s%filter_order, 1, 1, 3, "-", &
               "Autopilot: how many such low-pass stages in cascade (1: -20 dB/decade "// &
               "above 1/autopilot_filter, 2: -40, 3: -60), for a wave frequency close "// &
               "to the steering's.")
    call r%choice(g, "autopilot_notch", mode, "off", [character(len=9) :: "off", "encounter"], &
                  "Autopilot: 'encounter' passes the heading error and yaw rate through a "// &
                  "notch filter at the encounter period of the sea's largest wave "// &
                  "component at the headway, 2 pi/(omega - k U cos(beta)), so that the "// &
                  "rudder does not answer the wave-frequency yaw; 'off': no notch.")
    s%notch_encounter = mode == "encounter"
  end subroutine read_steering

end module davit_io_mmg_keys
