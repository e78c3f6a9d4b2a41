!> Wind force and moments on the ship, paper eq. (46), with the coefficient curves and sign
!> conventions of review G14 (ship axes x forward, y starboard, z down):
!>   X = 1/2 rho_air A_F |v_R|^2 C_X,  C_X = -0.7 cos(alpha_R)
!>   Y = 1/2 rho_air A_L |v_R|^2 C_Y,  C_Y = -0.85 sin(alpha_R)
!>   K = Y h_z                          (h_z: height of the lateral centre of effort above G)
!>   N = 1/2 rho_air A_L L_oa |v_R|^2 C_N, C_N = -0.10 sin(2 alpha_R)
!> alpha_R is the relative bearing the wind comes from: 0 ahead, +90 deg from starboard.
!> Heave and pitch are ignored, as in the paper.
module davit_ship_wind_load
  use davit_kinds, only: wp, rho_air
  implicit none
  private
  public :: ship_wind_type, ship_wind_load

  !> The ship's windage, the geometry of the wind load.
  type :: ship_wind_type
    !> Frontal and lateral windage areas A_F, A_L [m^2].
    real(wp) :: area_front = 400.0_wp, area_lateral = 1600.0_wp
    !> Length overall L_oa [m] (lever of the yaw moment) and height h_z [m] of the lateral
    !> centre of effort above G (lever of the roll moment).
    real(wp) :: length_overall = 139.8_wp, height = 7.0_wp
  end type ship_wind_type

contains

  !> (X, Y, Z, K, M, N) for the relative air velocity v_rel = v_wind - v_ship, in ship axes.
  pure function ship_wind_load(w, v_rel) result(load)
    !> The ship's windage.
    type(ship_wind_type), intent(in) :: w
    !> Air velocity relative to the ship, v_wind - v_ship [m/s], in ship axes (the
    !> horizontal components are used).
    real(wp), intent(in) :: v_rel(3)
    real(wp) :: load(6), q, alpha
    load = 0.0_wp
    q = 0.5_wp*rho_air*(v_rel(1)**2 + v_rel(2)**2)
    if (q <= 0.0_wp) return
    ! the wind comes from -v_rel
    alpha = atan2(-v_rel(2), -v_rel(1))
    load(1) = q*w%area_front*(-0.7_wp*cos(alpha))
    load(2) = q*w%area_lateral*(-0.85_wp*sin(alpha))
    load(4) = load(2)*w%height
    load(6) = q*w%area_lateral*w%length_overall*(-0.10_wp*sin(2.0_wp*alpha))
  end function ship_wind_load

end module davit_ship_wind_load
