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
!>
!> The lift form is a type: boat_wind_type holds the data and the drag, and each form is an
!> extension giving its lift (add_lift), chosen once at build from &boat lift_form.
module davit_boat_wind_loads
  use davit_kinds, only: wp, rho_air
  implicit none
  private
  public :: boat_wind_type, symmetric_lift_wind_type, literal_lift_wind_type
  public :: boat_wind_force, lift_form_names

  !> The deck's names of the lift forms (&boat lift_form).
  character(len=*), parameter :: lift_form_names(2) = [character(len=9) :: "symmetric", &
                                                       "literal"]

  type, abstract :: boat_wind_type
    !> Projected areas normal to b1, b2, b3 [m^2], drag and lift coefficients.
    real(wp) :: areas(3) = [8.5_wp, 26.2_wp, 26.2_wp]
    !> Drag and lift coefficients of the hull (eqs. 15-16).
    real(wp) :: cd = 0.5_wp, cl = 1.2_wp
    !> Lift cylinder diameter D_b and length l_b [m].
    real(wp) :: diameter = 3.29_wp, length = 11.5_wp
  contains
    procedure :: force => boat_wind_force
    procedure(add_lift_i), deferred :: add_lift
  end type boat_wind_type

  !> Upward lift from the lateral cross-flow, from either side (the default).
  type, extends(boat_wind_type) :: symmetric_lift_wind_type
  contains
    procedure :: add_lift => add_symmetric_lift
  end type symmetric_lift_wind_type

  !> Eq. 16 as printed: lift along b1 x v_n.
  type, extends(boat_wind_type) :: literal_lift_wind_type
  contains
    procedure :: add_lift => add_literal_lift
  end type literal_lift_wind_type

  abstract interface
    !> The lift (eq. 16) for the relative velocity v (b components) added to f [N].
    pure subroutine add_lift_i(self, v, f)
      import :: wp, boat_wind_type
      class(boat_wind_type), intent(in) :: self
      real(wp), intent(in) :: v(3)
      real(wp), intent(inout) :: f(3)
    end subroutine add_lift_i
  end interface

contains

  !> Force on the boat (b components) for its velocity relative to the air v (b components).
  pure function boat_wind_force(w, v, dry_fraction) result(f)
    !> The wind load model.
    class(boat_wind_type), intent(in) :: w
    !> Velocity of the boat relative to the air, b components [m/s]; fraction of the hull above the
    !> water (0..1).
    real(wp), intent(in) :: v(3), dry_fraction
    real(wp) :: f(3), speed
    f = 0.0_wp
    speed = norm2(v)
    if (speed <= 0.0_wp) return
    f = -0.5_wp*rho_air*w%cd*sum(w%areas*abs(v))*v   ! A_w |v| = sum A_i |v_i|
    call w%add_lift(v, f)
    f = f*dry_fraction
  end function boat_wind_force

  !> -1/2 rho_air D_b l_b C_L v2^2 along b3 (upward: b3 points down).
  pure subroutine add_symmetric_lift(self, v, f)
    !> The symmetric lift model.
    class(symmetric_lift_wind_type), intent(in) :: self
    !> Velocity relative to the air, b components [m/s].
    real(wp), intent(in) :: v(3)
    !> Force on the boat, b components [N], with the lift added.
    real(wp), intent(inout) :: f(3)
    f(3) = f(3) - 0.5_wp*rho_air*self%diameter*self%length*self%cl*v(2)**2
  end subroutine add_symmetric_lift

  !> -1/2 rho_air D_b l_b C_L |v_n|^2 k, k = b1 x v_n / |b1 x v_n| (eq. 16).
  pure subroutine add_literal_lift(self, v, f)
    !> The paper's lift model (eq. 16).
    class(literal_lift_wind_type), intent(in) :: self
    !> Velocity relative to the air, b components [m/s].
    real(wp), intent(in) :: v(3)
    !> Force on the boat, b components [N], with the lift added.
    real(wp), intent(inout) :: f(3)
    real(wp) :: vn(3), kdir(3)
    vn = [0.0_wp, v(2), v(3)]
    kdir = [0.0_wp, -vn(3), vn(2)]
    if (norm2(kdir) > 0.0_wp) then
      f = f - 0.5_wp*rho_air*self%diameter*self%length*self%cl*sum(vn**2)*kdir/norm2(kdir)
    end if
  end subroutine add_literal_lift

end module davit_boat_wind_loads
