!> The occupant's dynamic response model (MSC/Circ.616 5.6, the seated-occupant spine model
!> of ejection-seat practice): a single-degree-of-freedom system per seat axis, driven by
!> the seat's acceleration a(t),
!>
!>     delta'' + 2 zeta omega delta' + omega^2 delta = a(t),   DR(t) = omega^2 delta(t)/g,
!>
!> delta the body's deflection relative to the seat (positive compresses the body in the
!> direction of a). Its peak |DR| is the dynamic response index of that axis and direction.
!> The input is the kinematic acceleration in the boat's axes: a boat hanging at rest has
!> DR = 0 (the steady 1 g the occupant already carries is not part of the index).
module davit_assess_occupant
  use davit_kinds, only: wp, gravity
  implicit none
  private
  public :: response_peaks

contains

  !> Largest positive and largest negative DR (as a positive number) of the model (omega
  !> [rad/s], zeta [-]) driven from rest by a(t) sampled every dt, a taken linear between
  !> samples; classical RK4 on half-interval input values. The model's period is ~0.12 s
  !> against dt ~1e-3 s: RK4's error (omega dt)^4/120 ~ 1e-7.
  pure function response_peaks(a, dt, omega, zeta) result(peaks)
    !> Acceleration samples [m/s^2] and their spacing [s]; the model's natural frequency [rad/s]
    !> and damping ratio.
    real(wp), intent(in) :: a(:), dt, omega, zeta
    real(wp) :: peaks(2)
    real(wp) :: x(2), k1(2), k2(2), k3(2), k4(2), amid, dr
    integer :: i
    peaks = 0.0_wp
    x = 0.0_wp
    do i = 2, size(a)
      amid = 0.5_wp*(a(i - 1) + a(i))
      k1 = rate(x, a(i - 1))
      k2 = rate(x + 0.5_wp*dt*k1, amid)
      k3 = rate(x + 0.5_wp*dt*k2, amid)
      k4 = rate(x + dt*k3, a(i))
      x = x + dt/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
      dr = omega**2*x(1)/gravity
      peaks = [max(peaks(1), dr), max(peaks(2), -dr)]
    end do
  contains
    pure function rate(s, f) result(d)
      real(wp), intent(in) :: s(2), f
      real(wp) :: d(2)
      d = [s(2), f - 2.0_wp*zeta*omega*s(2) - omega**2*s(1)]
    end function rate
  end function response_peaks

end module davit_assess_occupant
