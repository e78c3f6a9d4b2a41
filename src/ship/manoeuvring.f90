!> The ship's horizontal-plane manoeuvring model (&ship manoeuvring), chosen once at
!> build: 'kijima' (linear Kijima hull derivatives, the zero-speed cross-flow drag, surge
!> resistance and a constant thrust that holds the headway) or 'mmg' (the standard MMG
!> model of davit_ship_mmg: hull, propeller at `rps` and a rudder whose angle and
!> autopilot are states). The ship's right-hand side and after-step hook call these
!> bindings and never ask which model it is. The cross-flow drag also sets the
!> thrust at build (davit_ship_ship_model).
module davit_ship_manoeuvring
  use davit_kinds, only: wp, rho_water
  use davit_core_layout, only: state_part_type
  use davit_core_quadrature, only: gx => gauss8_x, gw => gauss8_w
  use davit_ship_hull, only: hull_type
  use davit_ship_ship_hydro, only: ship_hydro_type, level_to_body
  use davit_ship_mmg, only: mmg_type
  use davit_ship_mmg_loads, only: mmg_body_load
  use davit_ship_rudder, only: rudder_type, rudder_order, rudder_rate, rudder_switch, &
                               autopilot_order
  implicit none
  private
  public :: manoeuvring_type, kijima_type, mmg_manoeuvring_type, crossflow

  !> Surge resistance coefficient on the wetted surface (review G12; Mumford's surface).
  real(wp), parameter :: surge_ct = 0.003_wp
  !> Gauss points along the hull for the cross-flow drag integral.
  integer, parameter :: ngauss = 8

  !> A manoeuvring model.
  type, abstract :: manoeuvring_type
  contains
    procedure(hull_loads_i), deferred :: add_hull_loads
    procedure(steering_i), deferred :: add_steering
    procedure(switch_i), deferred :: switch
  end type manoeuvring_type

  !> Kijima's linear derivatives, cross-flow drag and a constant thrust.
  type, extends(manoeuvring_type) :: kijima_type
  contains
    procedure :: add_hull_loads => kijima_hull_loads
    procedure :: add_steering => kijima_steering
    procedure :: switch => kijima_switch
  end type kijima_type

  !> The MMG model: hull, propeller and rudder.
  type, extends(manoeuvring_type) :: mmg_manoeuvring_type
    !> The MMG coefficients (davit_ship_mmg).
    type(mmg_type) :: mmg
    !> Propeller revolutions [1/s].
    real(wp) :: rps = 0.0_wp
  contains
    procedure :: add_hull_loads => mmg_hull_loads
    procedure :: add_steering => mmg_steering
    procedure :: switch => mmg_switch
  end type mmg_manoeuvring_type

  abstract interface
    !> The model's hull loads with the deck's empirical loads (ship axes about G), added to
    !> `load`.
    pure subroutine hull_loads_i(self, hull, wetted, thrust, u, load)
      import :: manoeuvring_type, hull_type, wp
      !> The model.
      class(manoeuvring_type), intent(in) :: self
      !> The hull (dimensions, derivatives, drag coefficient).
      type(hull_type), intent(in) :: hull
      !> Wetted surface [m^2] and the constant thrust [N].
      real(wp), intent(in) :: wetted, thrust
      !> Speeds (omega [rad/s], v [m/s]) in ship axes, Kane order.
      real(wp), intent(in) :: u(6)
      !> Loads X, Y, Z [N], K, M, N [N m], the model's added.
      real(wp), intent(inout) :: load(6)
    end subroutine hull_loads_i

    !> The steered model's loads at the rudder angle of state y, added to `load`, and the
    !> rates of its steering gear and autopilot (into dydt).
    pure subroutine steering_i(self, hull, hydro, steer, rudder, autopilot, t, q, u, c, y, &
                               load, dydt)
      import :: manoeuvring_type, hull_type, ship_hydro_type, rudder_type, state_part_type, wp
      !> The model.
      class(manoeuvring_type), intent(in) :: self
      !> The hull (G's position).
      type(hull_type), intent(in) :: hull
      !> The ship's hydrodynamics (the horizontal added masses its mass matrix holds).
      class(ship_hydro_type), intent(in) :: hydro
      !> The steering (manoeuvre or autopilot, its switches).
      type(rudder_type), intent(in) :: steer
      !> The rudder angle's and the autopilot's state parts.
      type(state_part_type), intent(in) :: rudder, autopilot
      !> Time [s], Euler angles and CG position [rad, m], speeds (Kane order), rotation
      !> ship -> inertial.
      real(wp), intent(in) :: t, q(6), u(6), c(3, 3)
      !> The ship's state.
      real(wp), intent(in) :: y(:)
      !> Loads in ship axes about G, the model's added.
      real(wp), intent(inout) :: load(6)
      !> The ship's rates, the steering's written.
      real(wp), intent(inout) :: dydt(:)
    end subroutine steering_i

    !> After a step: the steering's switches (a zig-zag's rudder reversals) at yaw `yaw`.
    pure subroutine switch_i(self, steer, t, yaw)
      import :: manoeuvring_type, rudder_type, wp
      !> The model.
      class(manoeuvring_type), intent(in) :: self
      !> The steering, its switches advanced.
      type(rudder_type), intent(inout) :: steer
      !> Time [s] and yaw [rad] at the step's end.
      real(wp), intent(in) :: t, yaw
    end subroutine switch_i
  end interface

contains

  !> Zero-speed cross-flow drag for sway and yaw, -1/2 rho d C_D |v + x r| (v + x r) along
  !> the hull, and surge resistance -1/2 rho S C_T |u| u (review G12).
  pure function crossflow(h, wetted, v, r) result(load)
    !> The hull (length, draught, drag coefficient).
    type(hull_type), intent(in) :: h
    !> Wetted surface [m^2], CG velocity in ship axes [m/s], yaw rate [rad/s].
    real(wp), intent(in) :: wetted, v(3), r
    real(wp) :: load(6), x, vl, half
    integer :: k
    load = 0.0_wp
    half = 0.5_wp*h%lpp
    do k = 1, ngauss
      x = half*gx(k)
      vl = v(2) + x*r
      load(2) = load(2) - gw(k)*half*abs(vl)*vl
      load(6) = load(6) - gw(k)*half*abs(vl)*vl*x
    end do
    load([2, 6]) = 0.5_wp*rho_water*h%draught*h%cd*load([2, 6])
    load(1) = -0.5_wp*rho_water*wetted*surge_ct*abs(v(1))*v(1)
  end function crossflow

  !> Linear MMG hull forces (Kijima), written dimensionally so they vanish smoothly as the
  !> forward speed u -> 0 (no division by U): Y = 1/2 rho L d |u| (Y'_v v + Y'_r L r), and
  !> N alike with one more L. The lifting-hull derivatives hold for small drift angles when
  !> making way, so they scale with the forward speed |u|, not |V|: a ship drifting
  !> sideways at zero headway (drift angle 90 deg) feels only the cross-flow drag.
  pure function kijima_load(h, v, r) result(load)
    !> The hull (length, draught, the derivatives Y'_v, Y'_r, N'_v, N'_r).
    type(hull_type), intent(in) :: h
    !> CG velocity in ship axes [m/s], yaw rate [rad/s].
    real(wp), intent(in) :: v(3), r
    real(wp) :: load(6), q
    load = 0.0_wp
    q = 0.5_wp*rho_water*h%lpp*h%draught*abs(v(1))
    load(2) = q*(h%yv*v(2) + h%yr*h%lpp*r)
    load(6) = q*h%lpp*(h%nv*v(2) + h%nr*h%lpp*r)
  end function kijima_load

  !> Cross-flow drag, surge resistance, Kijima's derivatives and the constant thrust.
  pure subroutine kijima_hull_loads(self, hull, wetted, thrust, u, load)
    !> The model.
    class(kijima_type), intent(in) :: self
    !> The hull (dimensions, derivatives, drag coefficient).
    type(hull_type), intent(in) :: hull
    !> Wetted surface [m^2] and the constant thrust [N].
    real(wp), intent(in) :: wetted, thrust
    !> Speeds (omega [rad/s], v [m/s]) in ship axes, Kane order.
    real(wp), intent(in) :: u(6)
    !> Loads X, Y, Z [N], K, M, N [N m], the model's added.
    real(wp), intent(inout) :: load(6)
    load = load + crossflow(hull, wetted, u(4:6), u(3)) + kijima_load(hull, u(4:6), u(3))
    load(1) = load(1) + thrust
  end subroutine kijima_hull_loads

  !> Kijima's model is not steered.
  pure subroutine kijima_steering(self, hull, hydro, steer, rudder, autopilot, t, q, u, c, y, &
                                  load, dydt)
    !> The model.
    class(kijima_type), intent(in) :: self
    !> The hull (dimensions, derivatives, drag coefficient).
    type(hull_type), intent(in) :: hull
    !> The ship's hydrodynamics (the horizontal added masses its mass matrix holds).
    class(ship_hydro_type), intent(in) :: hydro
    !> The steering (manoeuvre or autopilot, its switches).
    type(rudder_type), intent(in) :: steer
    !> The rudder angle's and the autopilot's state parts.
    type(state_part_type), intent(in) :: rudder, autopilot
    !> Time [s], Euler angles and CG position [rad, m], speeds (Kane order), rotation
    !> ship -> inertial.
    real(wp), intent(in) :: t, q(6), u(6), c(3, 3)
    !> The ship's state.
    real(wp), intent(in) :: y(:)
    !> Loads X, Y, Z [N], K, M, N [N m], the model's added.
    real(wp), intent(inout) :: load(6)
    !> The ship's rates, the steering's written.
    real(wp), intent(inout) :: dydt(:)
  end subroutine kijima_steering

  pure subroutine kijima_switch(self, steer, t, yaw)
    !> The model.
    class(kijima_type), intent(in) :: self
    !> The steering, its switches advanced.
    type(rudder_type), intent(inout) :: steer
    !> Time [s] and yaw [rad] at the step's end.
    real(wp), intent(in) :: t, yaw
  end subroutine kijima_switch

  !> The MMG hull forces are part of its steered loads (mmg_steering).
  pure subroutine mmg_hull_loads(self, hull, wetted, thrust, u, load)
    !> The model.
    class(mmg_manoeuvring_type), intent(in) :: self
    !> The hull (dimensions, derivatives, drag coefficient).
    type(hull_type), intent(in) :: hull
    !> Wetted surface [m^2] and the constant thrust [N].
    real(wp), intent(in) :: wetted, thrust
    !> Speeds (omega [rad/s], v [m/s]) in ship axes, Kane order.
    real(wp), intent(in) :: u(6)
    !> Loads X, Y, Z [N], K, M, N [N m], the model's added.
    real(wp), intent(inout) :: load(6)
  end subroutine mmg_hull_loads

  !> The MMG loads (hull, propeller, rudder) at the rudder angle delta of state y; the
  !> steering gear's rate towards the order of the manoeuvre or the autopilot (whose
  !> integral states, where it has them, advance too).
  pure subroutine mmg_steering(self, hull, hydro, steer, rudder, autopilot, t, q, u, c, y, &
                               load, dydt)
    !> The model.
    class(mmg_manoeuvring_type), intent(in) :: self
    !> The hull (dimensions, derivatives, drag coefficient).
    type(hull_type), intent(in) :: hull
    !> The ship's hydrodynamics (the horizontal added masses its mass matrix holds).
    class(ship_hydro_type), intent(in) :: hydro
    !> The steering (manoeuvre or autopilot, its switches).
    type(rudder_type), intent(in) :: steer
    !> The rudder angle's and the autopilot's state parts.
    type(state_part_type), intent(in) :: rudder, autopilot
    !> Time [s], Euler angles and CG position [rad, m], speeds (Kane order), rotation
    !> ship -> inertial.
    real(wp), intent(in) :: t, q(6), u(6), c(3, 3)
    !> The ship's state.
    real(wp), intent(in) :: y(:)
    !> Loads X, Y, Z [N], K, M, N [N m], the model's added.
    real(wp), intent(inout) :: load(6)
    !> The ship's rates, the steering's written.
    real(wp), intent(inout) :: dydt(:)
    real(wp) :: order, a(3)
    integer :: k, j
    ! the horizontal added masses that the ship's mass matrix holds: the MMG set's on the
    ! box (davit_ship_hull), the BEM ship's A(inf) (its memory adds the rest at low frequency)
    a = hydro%horizontal_added_mass(hull)
    associate (delta => y(rudder%q(1)))
      load = load + mmg_body_load(self%mmg, hull%cg_x, a(1), a(2), level_to_body(q(3), c), u, &
                                  delta, self%rps)
      if (autopilot%q(2) >= autopilot%q(1)) then
        k = autopilot%q(1)
        j = autopilot%q(2)
        call autopilot_order(steer, t, q(3), u(3), y(k:j), order, dydt(k:j))
      else
        order = rudder_order(steer, t, q(3), u(3))
      end if
      dydt(rudder%q(1)) = rudder_rate(steer, delta, order)
    end associate
  end subroutine mmg_steering

  !> The zig-zag's rudder reversals.
  pure subroutine mmg_switch(self, steer, t, yaw)
    !> The model.
    class(mmg_manoeuvring_type), intent(in) :: self
    !> The steering, its switches advanced.
    type(rudder_type), intent(inout) :: steer
    !> Time [s] and yaw [rad] at the step's end.
    real(wp), intent(in) :: t, yaw
    call rudder_switch(steer, t, yaw)
  end subroutine mmg_switch

end module davit_ship_manoeuvring
