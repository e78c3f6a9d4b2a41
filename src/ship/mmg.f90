!> The standard MMG force law (Yasukawa & Yoshimura 2015, J. Mar. Sci. Technol. 20:37-52;
!> the paper's eqs. 40-41 name its hull forces X_H, Y_H, N_H): hull, propeller and rudder
!> forces on a ship in the horizontal plane, in the horizontal-body frame with its origin
!> at midship (x forward, y to starboard, z down; r > 0 turns to starboard, a rudder angle
!> delta > 0 turns the ship to starboard).
!>
!> Inputs are the surge speed u, the sway speed at midship v_m, the yaw rate r, the rudder
!> angle delta and the propeller revolutions n [1/s]; outputs (X, Y, N) about midship [N,
!> N, N m]. Written for forward speed (u > 0), as the model is.
module davit_ship_mmg
  use davit_kinds, only: wp, pi, rho_water
  implicit none
  private
  public :: mmg_type, mmg_motion, mmg_hull, mmg_propeller, mmg_rudder, mmg_total, &
            mmg_self_propulsion, mmg_wake, mmg_rudder_inflow

  !> The coefficients (primed: non-dimensional on 1/2 rho L d U^2 for forces and
  !> 1/2 rho L^2 d U^2 for moments; v' = v_m/U, r' = r L/U; lengths x' on L).
  type :: mmg_type
    !> Length between perpendiculars L [m] and draught d [m] the coefficients are made
    !> non-dimensional with.
    real(wp) :: lpp = 1.0_wp, draught = 1.0_wp
    !> Hull (Yasukawa & Yoshimura 2015 eqs. 8-10): resistance R'_0 in straight running and
    !> the surge derivatives X'_vv, X'_vr, X'_rr, X'_vvvv.
    real(wp) :: r0 = 0.0_wp, xvv = 0.0_wp, xvr = 0.0_wp, xrr = 0.0_wp, xvvvv = 0.0_wp
    !> Sway force derivatives Y'_v, Y'_r, Y'_vvv, Y'_vvr, Y'_vrr, Y'_rrr of the cubic
    !> polynomial Y'_H(v', r').
    real(wp) :: yv = 0.0_wp, yr = 0.0_wp, yvvv = 0.0_wp, yvvr = 0.0_wp, yvrr = 0.0_wp, &
                yrrr = 0.0_wp
    !> Yaw moment derivatives N'_v, N'_r, N'_vvv, N'_vvr, N'_vrr, N'_rrr of the cubic
    !> polynomial N'_H(v', r') (about midship).
    real(wp) :: nv = 0.0_wp, nr = 0.0_wp, nvvv = 0.0_wp, nvvr = 0.0_wp, nvrr = 0.0_wp, &
                nrrr = 0.0_wp
    !> Added masses m'_x, m'_y (on 1/2 rho L^2 d) and added yaw inertia J'_z (on
    !> 1/2 rho L^4 d).
    real(wp) :: mx = 0.0_wp, my = 0.0_wp, jz = 0.0_wp
    !> Propeller (eqs. 14-17): diameter [m], K_T = k0 + k1 J + k2 J^2, thrust deduction
    !> t_P, wake w_P0 in straight running, position x'_P, wake change with the
    !> propeller's inflow angle beta_P (C_1, C_2 for beta_P > 0 and < 0).
    real(wp) :: dp = 0.0_wp, k0 = 0.0_wp, k1 = 0.0_wp, k2 = 0.0_wp, tp = 0.0_wp, &
                wp0 = 0.0_wp, xp = 0.0_wp, c1 = 0.0_wp, c2_plus = 1.0_wp, c2_minus = 1.0_wp
    !> Rudder (eqs. 18-27): area A_R [m^2], span H_R [m], normal-force slope f_alpha,
    !> wake ratio epsilon, propeller-race factor kappa, steering resistance deduction t_R,
    !> hull-interaction a_H and x'_H, position x'_R, flow-straightening gamma_R (beta_R > 0
    !> and < 0) with its lever l'_R.
    real(wp) :: area = 0.0_wp, span = 1.0_wp, f_alpha = 0.0_wp, eps = 1.0_wp, &
                kappa = 0.0_wp, tr = 0.0_wp, ah = 0.0_wp, xh = 0.0_wp, xr = -0.5_wp, &
                lr = 0.0_wp, gamma_plus = 0.0_wp, gamma_minus = 0.0_wp
  end type mmg_type

  !> Below this speed [m/s] the hull's non-dimensional angles are undefined: zero force.
  !> The ship's motion and controls the MMG force laws read, the same for all of them.
  type :: mmg_motion
    !> Surge speed u [m/s], sway speed at midship v_m [m/s] and yaw rate r [rad/s].
    real(wp) :: u = 0.0_wp, vm = 0.0_wp, r = 0.0_wp
    !> Rudder angle delta [rad] (> 0 turns the ship to starboard) and propeller
    !> revolutions n [1/s].
    real(wp) :: delta = 0.0_wp, n = 0.0_wp
  end type mmg_motion

  real(wp), parameter :: u_small = 1.0e-9_wp

contains

  !> Hull forces (eq. 8-10): X_H = 1/2 rho L d U^2 (-R'_0 + X'_vv v'^2 + X'_vr v' r' +
  !> X'_rr r'^2 + X'_vvvv v'^4); Y_H, N_H the cubic polynomials in v', r'.
  pure function mmg_hull(p, s) result(f)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The motion (u, v_m, r).
    type(mmg_motion), intent(in) :: s
    real(wp) :: f(3), uu, v, w, q
    f = 0.0_wp
    uu = hypot(s%u, s%vm)
    if (uu < u_small) return
    v = s%vm/uu
    w = s%r*p%lpp/uu
    q = 0.5_wp*rho_water*p%lpp*p%draught*uu**2
    f(1) = q*(-p%r0 + p%xvv*v**2 + p%xvr*v*w + p%xrr*w**2 + p%xvvvv*v**4)
    f(2) = q*(p%yv*v + p%yr*w + p%yvvv*v**3 + p%yvvr*v**2*w + p%yvrr*v*w**2 + p%yrrr*w**3)
    f(3) = q*p%lpp*(p%nv*v + p%nr*w + p%nvvv*v**3 + p%nvvr*v**2*w + p%nvrr*v*w**2 + &
                    p%nrrr*w**3)
  end function mmg_hull

  !> 1 - w_P (eq. 16): (1 - w_P0) [1 + (1 - exp(-C_1 |beta_P|)) (C_2 - 1)],
  !> beta_P = beta - x'_P r', beta = atan(-v_m/u); C_2 by the sign of beta_P.
  pure real(wp) function mmg_wake(p, s) result(one_minus_w)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The motion (u, v_m, r).
    type(mmg_motion), intent(in) :: s
    real(wp) :: uu, beta_p, c2
    one_minus_w = 1.0_wp - p%wp0
    uu = hypot(s%u, s%vm)
    if (uu < u_small) return
    beta_p = atan2(-s%vm, s%u) - p%xp*s%r*p%lpp/uu
    c2 = merge(p%c2_plus, p%c2_minus, beta_p > 0.0_wp)
    one_minus_w = one_minus_w*(1.0_wp + (1.0_wp - exp(-p%c1*abs(beta_p)))*(c2 - 1.0_wp))
  end function mmg_wake

  !> rho n^2 D^4 K_T(J_P)/rho with J_P = u_P/(n D), written as a polynomial in n and u_P
  !> so that it stays finite at n -> 0 [N per unit density].
  pure real(wp) function thrust_per_rho(p, up, n) result(t)
    type(mmg_type), intent(in) :: p
    real(wp), intent(in) :: up, n
    t = p%dp**2*(p%k0*(n*p%dp)**2 + p%k1*n*p%dp*up + p%k2*up**2)
  end function thrust_per_rho

  !> Propeller (eq. 14): X_P = (1 - t_P) rho n^2 D_P^4 K_T(J_P), J_P = u (1 - w_P)/(n D_P).
  pure function mmg_propeller(p, s) result(f)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The motion (u, v_m, r) and the propeller revolutions n.
    type(mmg_motion), intent(in) :: s
    real(wp) :: f(3)
    f = 0.0_wp
    f(1) = (1.0_wp - p%tp)*rho_water*thrust_per_rho(p, s%u*mmg_wake(p, s), s%n)
  end function mmg_propeller

  !> Rudder inflow (eqs. 23-26): u_R = epsilon u_P sqrt(eta {1 + kappa (sqrt(1 +
  !> 8 K_T/(pi J^2)) - 1)}^2 + 1 - eta), eta = D_P/H_R; v_R = U gamma_R beta_R,
  !> beta_R = beta - l'_R r'. u_P sqrt(1 + 8 K_T/(pi J^2)) = sqrt(u_P^2 + 8 T/(pi rho D^2))
  !> keeps it finite at u_P -> 0.
  pure function mmg_rudder_inflow(p, s) result(uv)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The motion (u, v_m, r) and the propeller revolutions n.
    type(mmg_motion), intent(in) :: s
    real(wp) :: uv(2), up, race, eta, uu, beta_r
    up = s%u*mmg_wake(p, s)
    race = sqrt(max(up**2 + 8.0_wp*thrust_per_rho(p, up, s%n)/(pi*p%dp**2), 0.0_wp))
    race = (1.0_wp - p%kappa)*up + p%kappa*race
    eta = p%dp/p%span
    uv(1) = p%eps*sqrt(eta*race**2 + (1.0_wp - eta)*up**2)
    uv(2) = 0.0_wp
    uu = hypot(s%u, s%vm)
    if (uu < u_small) return
    beta_r = atan2(-s%vm, s%u) - p%lr*s%r*p%lpp/uu
    uv(2) = uu*merge(p%gamma_plus, p%gamma_minus, beta_r > 0.0_wp)*beta_r
  end function mmg_rudder_inflow

  !> Rudder (eqs. 18-22): F_N = 1/2 rho A_R U_R^2 f_alpha sin(alpha_R), alpha_R = delta -
  !> atan(v_R/u_R); X_R = -(1 - t_R) F_N sin(delta), Y_R = -(1 + a_H) F_N cos(delta),
  !> N_R = -(x_R + a_H x_H) F_N cos(delta).
  pure function mmg_rudder(p, s) result(f)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The motion (u, v_m, r), the rudder angle delta and the propeller revolutions n.
    type(mmg_motion), intent(in) :: s
    real(wp) :: f(3), uv(2), fn
    uv = mmg_rudder_inflow(p, s)
    fn = 0.5_wp*rho_water*p%area*(uv(1)**2 + uv(2)**2)*p%f_alpha* &
         sin(s%delta - atan2(uv(2), uv(1)))
    f(1) = -(1.0_wp - p%tr)*fn*sin(s%delta)
    f(2) = -(1.0_wp + p%ah)*fn*cos(s%delta)
    f(3) = -(p%xr + p%ah*p%xh)*p%lpp*fn*cos(s%delta)
  end function mmg_rudder

  !> X, Y, N about midship: hull + propeller + rudder (eq. 5).
  pure function mmg_total(p, s) result(f)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The motion (u, v_m, r), the rudder angle delta and the propeller revolutions n.
    type(mmg_motion), intent(in) :: s
    real(wp) :: f(3)
    f = mmg_hull(p, s) + mmg_propeller(p, s) + mmg_rudder(p, s)
  end function mmg_total

  !> The propeller revolutions [1/s] that hold the speed u in straight running with the
  !> rudder amidships: (1 - t_P) T(n) = R_0 (+ `extra` [N], a further resistance such as
  !> the windage in still air), a quadratic in n (the rudder's normal force vanishes
  !> there, alpha_R = 0).
  pure real(wp) function mmg_self_propulsion(p, u, extra) result(n)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> The straight-running surge speed to hold [m/s] (> 0).
    real(wp), intent(in) :: u
    !> A further resistance [N] the thrust also overcomes (default 0).
    real(wp), intent(in), optional :: extra
    real(wp) :: up, a, b, c, r
    up = u*(1.0_wp - p%wp0)
    a = p%k0*p%dp**4
    b = p%k1*p%dp**3*up
    r = 0.5_wp*p%lpp*p%draught*u**2*p%r0
    if (present(extra)) r = r + extra/rho_water
    c = p%k2*p%dp**2*up**2 - r/(1.0_wp - p%tp)
    n = (-b + sqrt(max(b*b - 4.0_wp*a*c, 0.0_wp)))/(2.0_wp*a)
  end function mmg_self_propulsion

end module davit_ship_mmg
