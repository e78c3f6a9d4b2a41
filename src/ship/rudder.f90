!> The steering gear and its orders: the rudder angle is a state driven by a rate-limited
!> servo towards the ordered angle; the order comes from a PD autopilot on the heading
!> error, a fixed angle, a turning-circle order or the zig-zag logic (IMO MSC.137(76)
!> manoeuvres: the order reverses when the heading change reaches the switching angle).
module davit_ship_rudder
  use davit_kinds, only: wp
  implicit none
  private
  public :: rudder_type, rudder_order, rudder_rate, rudder_switch, rudder_servo_time, &
            autopilot_integral_rate, autopilot_order, autopilot_states, notch_period

  !> Time constant [s] of the servo inside the rate limit: delta' = (order - delta)/tau,
  !> clipped to the rudder rate. Small against every manoeuvre (the rate limit governs a
  !> 35 deg order for 2.2 s at model scale, 15 s at full scale) but keeps the rate
  !> continuous for the integrator.
  real(wp), parameter :: rudder_servo_time = 0.1_wp
  !> Damping ratio of the notch's poles: its width (-3 dB band w0 (sqrt(1 + zeta^2) +- zeta))
  !> and its phase lag below w0 (2 zeta w w0/(w0^2 - w^2)).
  real(wp), parameter :: notch_damping = 0.5_wp

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
    !> acts on pass `filter_order` equal first-order low-pass stages in cascade (filter 0:
    !> unfiltered). A cascade of two or three rolls off the encounter-frequency yaw
    !> (-40, -60 dB/decade) that one stage passes to a rate-limited rudder.
    real(wp) :: filter = 0.0_wp
    !> Low-pass stages in cascade on the heading error and on the yaw rate (1-3).
    integer :: filter_order = 1
    !> Period [s] of the autopilot's notch filter, the encounter period of the waves whose
    !> yaw the rudder is not to answer (0: off): N(s) = (s^2 + w0^2)/(s^2 + 2 zeta w0 s +
    !> w0^2) on the heading error and yaw rate ahead of the low-pass stages.
    real(wp) :: notch = 0.0_wp
    !> Place the notch at the encounter period of the sea's largest wave component at the
    !> headway (davit_system_build, with notch_period).
    logical :: notch_encounter = .false.
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
    !> The steering (mode, gains, limits, set-point).
    type(rudder_type), intent(in) :: self
    !> Time [s], heading psi [rad] and yaw rate r [rad/s] (ship's horizontal frame).
    real(wp), intent(in) :: t, psi, r
    !> Time integral of the heading error [rad s] (PID autopilot; absent: PD).
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
    !> The autopilot (gains, set-point, angle limit).
    type(rudder_type), intent(in) :: self
    !> Heading [rad] and the integral of its error so far [rad s].
    real(wp), intent(in) :: psi, z
    zdot = psi - self%heading
    if (self%ki*abs(z) >= self%max_angle .and. zdot*z > 0.0_wp) zdot = 0.0_wp
  end function autopilot_integral_rate

  !> How many states the autopilot keeps (part "ship_autopilot"): its integral z and the
  !> filter stages of the heading error and of the yaw rate (filter_order each), or none
  !> for a plain PD.
  pure integer function autopilot_states(self) result(n)
    !> The steering whose autopilot's state count is asked.
    type(rudder_type), intent(in) :: self
    n = 0
    if (self%mode == "autopilot" .and. (self%ki > 0.0_wp .or. self%filter > 0.0_wp .or. &
                                        self%notch > 0.0_wp)) n = 1 + 2*max(self%filter_order, 1)
    if (n > 0 .and. self%notch > 0.0_wp) n = n + 4
  end function autopilot_states

  !> The autopilot's order at time t for heading psi and yaw rate r with its states
  !> x = (z, e_1 .. e_m, r_1 .. r_m[, notch states]) (m = filter_order) and their rates:
  !> the notch (if on: two states for each signal) takes the encounter frequency out of
  !> the heading error and yaw rate, then the wave filter e_1' = (e - e_1)/T, e_k' =
  !> (e_(k-1) - e_k)/T, the same for r (T = filter; off: the stages unused), the PID on the
  !> last stages e_m, r_m, the integral of e_m.
  pure subroutine autopilot_order(self, t, psi, r, x, order, xdot)
    !> The autopilot (gains, filters, notch, set-point, limits).
    type(rudder_type), intent(in) :: self
    !> Time [s], heading [rad], yaw rate [rad/s] and the autopilot's states x = (z, e_1 ..
    !> e_m, r_1 .. r_m[, notch states]) [rad s, rad, rad/s].
    real(wp), intent(in) :: t, psi, r, x(:)
    !> The rudder order [rad], within the angle limit (the sign convention of
    !> rudder_order), and the states' rates.
    real(wp), intent(out) :: order, xdot(size(x))
    real(wp) :: e, rf
    integer :: m, k
    e = psi - self%heading
    rf = r
    xdot = 0.0_wp
    m = max(self%filter_order, 1)
    if (self%notch > 0.0_wp) then
      call notch_filter(self%notch, x(2*m + 2:2*m + 3), e, xdot(2*m + 2:2*m + 3))
      call notch_filter(self%notch, x(2*m + 4:2*m + 5), rf, xdot(2*m + 4:2*m + 5))
    end if
    if (self%filter > 0.0_wp) then
      xdot(2) = (e - x(2))/self%filter
      xdot(2 + m) = (rf - x(2 + m))/self%filter
      do k = 2, m
        xdot(1 + k) = (x(k) - x(1 + k))/self%filter
        xdot(1 + m + k) = (x(m + k) - x(1 + m + k))/self%filter
      end do
      e = x(1 + m)
      rf = x(1 + 2*m)
    end if
    order = rudder_order(self, t, self%heading + e, rf, x(1))
    xdot(1) = autopilot_integral_rate(self, self%heading + e, x(1))
  end subroutine autopilot_order

  !> The notch of period `period` on signal f with states w (a second-order band-pass
  !> w1' = w2, w2' = f - w0^2 w1 - 2 zeta w0 w2, its output 2 zeta w0 w2): f becomes
  !> f - 2 zeta w0 w2, i.e. f through (s^2 + w0^2)/(s^2 + 2 zeta w0 s + w0^2).
  pure subroutine notch_filter(period, w, f, wdot)
    real(wp), intent(in) :: period, w(2)
    real(wp), intent(inout) :: f
    real(wp), intent(out) :: wdot(2)
    real(wp) :: w0
    w0 = 2.0_wp*acos(-1.0_wp)/period
    wdot(1) = w(2)
    wdot(2) = f - w0**2*w(1) - 2.0_wp*notch_damping*w0*w(2)
    f = f - 2.0_wp*notch_damping*w0*w(2)
  end subroutine notch_filter

  !> The encounter period [s] of the largest of the wave components (frequencies omega,
  !> wave numbers kx, ky, amplitudes a) met by a frame moving at `velocity` (x, y):
  !> 2 pi/|omega - kx U_x - ky U_y|; 0 for no waves or a component met at zero frequency.
  pure real(wp) function notch_period(omega, kx, ky, a, velocity) result(period)
    !> The sea's components: frequencies [rad/s], wave numbers along x and y [1/m],
    !> amplitudes [m]; the frame's velocity (x, y) [m/s], inertial.
    real(wp), intent(in) :: omega(:), kx(:), ky(:), a(:), velocity(2)
    real(wp) :: we
    integer :: i
    period = 0.0_wp
    if (size(a) == 0) return
    i = maxloc(abs(a), 1)
    we = abs(omega(i) - kx(i)*velocity(1) - ky(i)*velocity(2))
    if (we > 0.0_wp) period = 2.0_wp*acos(-1.0_wp)/we
  end function notch_period

  !> The steering gear: delta' = (order - delta)/tau within +-rate.
  pure real(wp) function rudder_rate(self, delta, order) result(rate)
    !> The steering gear (its rate limit).
    type(rudder_type), intent(in) :: self
    !> Rudder angle and its order [rad].
    real(wp), intent(in) :: delta, order
    rate = max(-self%rate, min(self%rate, (order - delta)/rudder_servo_time))
  end function rudder_rate

  !> Zig-zag logic after each step: the order goes to port once the heading has changed by
  !> +switch (to starboard), and back to starboard at -switch.
  pure subroutine rudder_switch(self, t, psi)
    !> The zig-zag steering, its order switched.
    type(rudder_type), intent(inout) :: self
    !> Time [s] and heading [rad] after the step.
    real(wp), intent(in) :: t, psi
    if (self%mode /= "zigzag" .or. t < self%start) return
    if (self%side > 0.0_wp .and. psi - self%heading >= self%switch) self%side = -1.0_wp
    if (self%side < 0.0_wp .and. psi - self%heading <= -self%switch) self%side = 1.0_wp
  end subroutine rudder_switch

end module davit_ship_rudder
