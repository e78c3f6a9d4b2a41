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
  public :: dynamic_response, response_peaks

contains

  !> DR(t_k) of the model (omega [rad/s], zeta [-]) for a(t) sampled every dt from rest,
  !> a taken linear between samples; classical RK4 on half-interval input values. The
  !> model's period is ~0.12 s against dt ~1e-3 s: RK4's error (omega dt)^4/120 ~ 1e-7.
  pure function dynamic_response(a, dt, omega, zeta) result(dr)
    real(wp), intent(in) :: a(:), dt, omega, zeta
    ! on the heap: the signal is as long as the run (a 1 kHz seat trace)
    real(wp), allocatable :: dr(:)
    real(wp) :: x(2), k1(2), k2(2), k3(2), k4(2), amid
    integer :: i
    allocate (dr(size(a)))
    x = 0.0_wp
    if (size(a) == 0) return
    dr(1) = 0.0_wp
    do i = 2, size(a)
      amid = 0.5_wp*(a(i - 1) + a(i))
      k1 = rate(x, a(i - 1))
      k2 = rate(x + 0.5_wp*dt*k1, amid)
      k3 = rate(x + 0.5_wp*dt*k2, amid)
      k4 = rate(x + dt*k3, a(i))
      x = x + dt/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
      dr(i) = omega**2*x(1)/gravity
    end do
  contains
    pure function rate(s, f) result(d)
      real(wp), intent(in) :: s(2), f
      real(wp) :: d(2)
      d = [s(2), f - 2.0_wp*zeta*omega*s(2) - omega**2*s(1)]
    end function rate
  end function dynamic_response

  !> Largest positive and largest negative DR (as a positive number) of a(t).
  pure function response_peaks(a, dt, omega, zeta) result(peaks)
    real(wp), intent(in) :: a(:), dt, omega, zeta
    real(wp) :: peaks(2)
    real(wp), allocatable :: dr(:)
    peaks = 0.0_wp
    if (size(a) == 0) return
    dr = dynamic_response(a, dt, omega, zeta)
    peaks = [max(0.0_wp, maxval(dr)), max(0.0_wp, -minval(dr))]
  end function response_peaks

end module davit_assess_occupant
