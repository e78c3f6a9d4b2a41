!> The cubic Hermite basis, the one copy of it in the code: a value and its rate sampled at
!> both ends of a window [t1, t2] give the cubic through them,
!> f(t) = h00(s) f1 + h h10(s) f1' + h01(s) f2 + h h11(s) f2', s = (t - t1)/h, h = t2 - t1
!> (Hairer, Norsett & Wanner I, sec. II.6; error ~ h^4 max|f''''|/384). Its users: the slow
!> clocks of the water (davit_core_slow_clock: the boat's strips and diffraction, the ship's
!> Froude-Krylov loads) and the dense output of event location (davit_solve_event_location).
module davit_core_hermite
  use davit_kinds, only: wp
  implicit none
  private
  public :: hermite_weights, hermite_interpolate, hermite_max

contains

  !> Weights (h00, h10 h, h01, h11 h) at s = (t - t1)/h, h = t2 - t1: the window length
  !> folded into the rates' weights.
  pure function hermite_weights(window, t) result(hw)
    !> Window [t1, t2] of the two samples and the time t [s] to weigh for.
    real(wp), intent(in) :: window(2), t
    real(wp) :: hw(4), h, s
    h = window(2) - window(1)
    s = (t - window(1))/h
    hw = cubic_basis(s, h*s)
  end function hermite_weights

  !> The cubic through values f1, f2 and rates d1, d2 at the ends of `window`, at time t:
  !> h00 f1 + h (h10 d1) + h01 f2 + h (h11 d2), the window length applied to the rates'
  !> terms (the ship's loads, the integrator's dense output).
  pure function hermite_interpolate(window, f1, d1, f2, d2, t) result(f)
    !> Window [t1, t2] of the two samples [s].
    real(wp), intent(in) :: window(2)
    !> Values f1, f2 and rates d1, d2 at t1 and t2.
    real(wp), intent(in) :: f1(:), d1(:), f2(:), d2(:)
    !> Time t [s] to interpolate at.
    real(wp), intent(in) :: t
    real(wp) :: f(size(f1)), h, s, b(4)
    h = window(2) - window(1)
    s = (t - window(1))/h
    b = cubic_basis(s, s)
    f = b(1)*f1 + h*b(2)*d1 + b(3)*f2 + h*b(4)*d2
  end function hermite_interpolate

  !> The largest value over the window of the cubic through values f1, f2 and rates d1, d2
  !> at its ends: the larger end, or the cubic at a root of its derivative inside (the
  !> derivative, a quadratic in s, solved in the form that does not cancel).
  pure real(wp) function hermite_max(window, f1, d1, f2, d2) result(top)
    !> Window [t1, t2] of the two samples [s].
    real(wp), intent(in) :: window(2)
    !> Values f1, f2 and rates d1, d2 at t1 and t2.
    real(wp), intent(in) :: f1, d1, f2, d2
    real(wp) :: h, qa, qb, qc, disc, root, s(2)
    integer :: i
    top = max(f1, f2)
    h = window(2) - window(1)
    ! f(s) = f1 + h d1 s + (3 df - h (2 d1 + d2)) s^2 + (h (d1 + d2) - 2 df) s^3, df = f2 - f1:
    ! f'(s) = qc + qb s + qa s^2
    qc = h*d1
    qb = 2.0_wp*(3.0_wp*(f2 - f1) - h*(2.0_wp*d1 + d2))
    qa = 3.0_wp*(h*(d1 + d2) - 2.0_wp*(f2 - f1))
    disc = qb*qb - 4.0_wp*qa*qc
    if (disc < 0.0_wp) return
    root = -0.5_wp*(qb + sign(sqrt(disc), qb))
    s = -1.0_wp
    if (root /= 0.0_wp) s(1) = qc/root
    if (qa /= 0.0_wp) s(2) = root/qa
    do i = 1, 2
      if (s(i) > 0.0_wp .and. s(i) < 1.0_wp) top = max(top, &
          f1 + s(i)*(qc + s(i)*(0.5_wp*qb + s(i)*qa/3.0_wp)))
    end do
  end function hermite_max

  !> h00, hs (1 - s)^2, h01, hs s (s - 1) at s in [0, 1]: with hs = s the four cubics of
  !> the unit interval, with hs = h s the rates' two already times the window length h.
  !> (Which product takes h first sets the last bit; the two users keep the order they
  !> were validated with, so their results are unchanged.)
  pure function cubic_basis(s, hs) result(b)
    !> Position s in the window and s or h s.
    real(wp), intent(in) :: s, hs
    real(wp) :: b(4)
    b = [(1.0_wp + 2.0_wp*s)*(1.0_wp - s)**2, hs*(1.0_wp - s)**2, s*s*(3.0_wp - 2.0_wp*s), &
         hs*s*(s - 1.0_wp)]
  end function cubic_basis

end module davit_core_hermite
