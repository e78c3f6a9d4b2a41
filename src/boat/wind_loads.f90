!> Wind on the lifeboat: drag (eq. 15) and lift (eq. 16), review §1.4, G27-G29.
!>
!> Drag F = -1/2 rho_air A_w C_w |v| v on the boat's velocity relative to the wind, with the
!> projected area of a box along the flow direction e: A_w = sum_i A_i |e_i| (exact for a
!> box). Lift on the cylinder of diameter D_b and length l_b from the cross-flow
!> v_n = (0, v2, v3):
!>   'literal'   F = -1/2 rho_air D_b l_b C_L |v_n|^2 k, k = b1 x v_n / |b1 x v_n| (eq. 16);
!>               its vertical part flips sign with the side the wind comes from, which a
!>               port/starboard-symmetric hull cannot do;
!>   'symmetric' F = -1/2 rho_air D_b l_b C_L v2^2 b3 (upward lift from the lateral
!>               cross-flow whatever its side; the default).
!> Both act at the CG. Once the boat is in the water only its dry part is loaded: the
!> forces are scaled by the dry fraction 1 - V/V_hull.
module davit_boat_wind_loads
  use davit_kinds, only: wp, rho_air
  implicit none
  private
  public :: boat_wind_type, boat_wind_force, lift_symmetric, lift_literal

  integer, parameter :: lift_symmetric = 1, lift_literal = 2

  type :: boat_wind_type
    !> Projected areas normal to b1, b2, b3 [m^2], drag and lift coefficients.
    real(wp) :: areas(3) = [8.5_wp, 26.2_wp, 26.2_wp]
    real(wp) :: cd = 0.5_wp, cl = 1.2_wp
    !> Lift cylinder diameter D_b and length l_b [m].
    real(wp) :: diameter = 3.29_wp, length = 11.5_wp
    integer :: lift_form = lift_symmetric
  end type boat_wind_type

contains

  !> Force on the boat (b components) for its velocity relative to the air v (b components).
  pure function boat_wind_force(w, v, dry_fraction) result(f)
    type(boat_wind_type), intent(in) :: w
    real(wp), intent(in) :: v(3), dry_fraction
    real(wp) :: f(3), speed, vn(3), kdir(3)
    f = 0.0_wp
    speed = norm2(v)
    if (speed <= 0.0_wp) return
    f = -0.5_wp*rho_air*w%cd*sum(w%areas*abs(v))*v   ! A_w |v| = sum A_i |v_i|
    select case (w%lift_form)
    case (lift_literal)
      vn = [0.0_wp, v(2), v(3)]
      kdir = [0.0_wp, -vn(3), vn(2)]
      if (norm2(kdir) > 0.0_wp) then
        f = f - 0.5_wp*rho_air*w%diameter*w%length*w%cl*sum(vn**2)*kdir/norm2(kdir)
      end if
    case default
      f(3) = f(3) - 0.5_wp*rho_air*w%diameter*w%length*w%cl*v(2)**2
    end select
    f = f*dry_fraction
  end function boat_wind_force

end module davit_boat_wind_loads
