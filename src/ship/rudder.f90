!> The steering gear and its orders: the rudder angle is a state driven by a rate-limited
!> servo towards the ordered angle; the order comes from a PD autopilot on the heading
!> error, a fixed angle, a turning-circle order or the zig-zag logic (IMO MSC.137(76)
!> manoeuvres: the order reverses when the heading change reaches the switching angle).
module davit_ship_rudder
  use davit_kinds, only: wp
  implicit none
  private
  public :: rudder_type, rudder_order, rudder_rate, rudder_switch, rudder_servo_time, &
            autopilot_integral_rate, autopilot_order, autopilot_states

  !> Time constant [s] of the servo inside the rate limit: delta' = (order - delta)/tau,
  !> clipped to the rudder rate. Small against every manoeuvre (the rate limit governs a
  !> 35 deg order for 2.2 s at model scale, 15 s at full scale) but keeps the rate
  !> continuous for the integrator.
  real(wp), parameter :: rudder_servo_time = 0.1_wp

  type :: rudder_type
    !> 'autopilot', 'fixed', 'turning' or 'zigzag'.
    character(len=16) :: mode = "autopilot"
    !> Ordered angle (fixed, turning) or zig-zag rudder angle [rad]; zig-zag switching
    !> heading change [rad]; time of the manoeuvre's first order [s].
    real(wp) :: angle = 0.0_wp, switch = 0.0_wp, start = 0.0_wp
    !> Rate [rad/s] and angle [rad] limits.
    real(wp) :: rate = 0.0_wp, max_angle = 0.0_wp
    !> Autopilot gains: rudder per heading error [-], per yaw rate [s] and per time
    !> integral of the heading error [1/s] (0: a PD autopilot, no integral state).
    real(wp) :: kp = 0.0_wp, kd = 0.0_wp, ki = 0.0_wp
    !> Time constant [s] of the autopilot's wave filter: the heading error and yaw rate it
    !> acts on pass a first-order low-pass filter (0: unfiltered).
    real(wp) :: filter = 0.0_wp
    !> Heading held by the autopilot and from which zig-zags are counted [rad].
    real(wp) :: heading = 0.0_wp
    !> Zig-zag side, +1 while the order is to starboard, -1 to port (rudder_switch).
    real(wp) :: side = 1.0_wp
  end type rudder_type

contains

  !> The ordered rudder angle at time t for heading psi and yaw rate r, within the angle
  !> limit. The autopilot orders -kp (psi - psi_0) - kd r - ki z (a starboard heading
  !> error asks for port rudder; z the time integral of the heading error, which takes
  !> out a steady yaw moment such as the wind's); before `start` the manoeuvres hold the
  !> rudder amidships.
  pure real(wp) function rudder_order(self, t, psi, r, z) result(order)
    type(rudder_type), intent(in) :: self
    real(wp), intent(in) :: t, psi, r
    real(wp), intent(in), optional :: z
    select case (self%mode)
    case ("autopilot")
      order = -self%kp*(psi - self%heading) - self%kd*r
      if (present(z)) order = order - self%ki*z
    case ("fixed")
      order = self%angle
    case ("turning")
      order = merge(self%angle, 0.0_wp, t >= self%start)
    case default
      order = merge(self%side*self%angle, 0.0_wp, t >= self%start)
    end select
    order = max(-self%max_angle, min(self%max_angle, order))
  end function rudder_order

  !> The rate of the autopilot's integral z of the heading error psi - psi_0, held while
  !> its share of the order alone passes the angle limit in the same sense (anti-windup).
  pure real(wp) function autopilot_integral_rate(self, psi, z) result(zdot)
    type(rudder_type), intent(in) :: self
    real(wp), intent(in) :: psi, z
    zdot = psi - self%heading
    if (self%ki*abs(z) >= self%max_angle .and. zdot*z > 0.0_wp) zdot = 0.0_wp
  end function autopilot_integral_rate

  !> How many states the autopilot keeps (part "ship_autopilot"): its integral z and the
  !> filtered heading error and yaw rate, or none for a plain PD.
  pure integer function autopilot_states(self) result(n)
    type(rudder_type), intent(in) :: self
    n = 0
    if (self%mode == "autopilot" .and. (self%ki > 0.0_wp .or. self%filter > 0.0_wp)) n = 3
  end function autopilot_states

  !> The autopilot's order at time t for heading psi and yaw rate r with its states
  !> x = (z, e_f, r_f) and their rates: the wave filter e_f' = (psi - psi_0 - e_f)/T,
  !> r_f' = (r - r_f)/T (T = filter; off: e_f, r_f unused), the PID on the filtered
  !> error and rate, the integral of the filtered error.
  pure subroutine autopilot_order(self, t, psi, r, x, order, xdot)
    type(rudder_type), intent(in) :: self
    real(wp), intent(in) :: t, psi, r, x(3)
    real(wp), intent(out) :: order, xdot(3)
    real(wp) :: pf, rf
    pf = psi
    rf = r
    xdot(2:3) = 0.0_wp
    if (self%filter > 0.0_wp) then
      pf = self%heading + x(2)
      rf = x(3)
      xdot(2) = (psi - self%heading - x(2))/self%filter
      xdot(3) = (r - x(3))/self%filter
    end if
    order = rudder_order(self, t, pf, rf, x(1))
    xdot(1) = autopilot_integral_rate(self, pf, x(1))
  end subroutine autopilot_order

  !> The steering gear: delta' = (order - delta)/tau within +-rate.
  pure real(wp) function rudder_rate(self, delta, order) result(rate)
    type(rudder_type), intent(in) :: self
    real(wp), intent(in) :: delta, order
    rate = max(-self%rate, min(self%rate, (order - delta)/rudder_servo_time))
  end function rudder_rate

  !> Zig-zag logic after each step: the order goes to port once the heading has changed by
  !> +switch (to starboard), and back to starboard at -switch.
  pure subroutine rudder_switch(self, t, psi)
    type(rudder_type), intent(inout) :: self
    real(wp), intent(in) :: t, psi
    if (self%mode /= "zigzag" .or. t < self%start) return
    if (self%side > 0.0_wp .and. psi - self%heading >= self%switch) self%side = -1.0_wp
    if (self%side < 0.0_wp .and. psi - self%heading <= -self%switch) self%side = 1.0_wp
  end subroutine rudder_switch

end module davit_ship_rudder
