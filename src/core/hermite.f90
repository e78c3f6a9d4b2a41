!> The cubic Hermite basis of the slow clocks (the strips' water, the boat's diffraction):
!> a value and its rate sampled at both ends of a window [t1, t2] give the cubic through
!> them, f(t) = hw(1) f1 + hw(2) f1' + hw(3) f2 + hw(4) f2'.
module davit_core_hermite
  use davit_kinds, only: wp
  implicit none
  private
  public :: hermite_weights

contains

  !> Weights (h00, h10 h, h01, h11 h) at s = (t - t1)/h, h = t2 - t1.
  pure function hermite_weights(window, t) result(hw)
    !> Window [t1, t2] of the two samples and the time t [s] to weigh for.
    real(wp), intent(in) :: window(2), t
    real(wp) :: hw(4), h, s
    h = window(2) - window(1)
    s = (t - window(1))/h
    hw = [(1.0_wp + 2.0_wp*s)*(1.0_wp - s)**2, h*s*(1.0_wp - s)**2, s*s*(3.0_wp - 2.0_wp*s), &
          h*s*s*(s - 1.0_wp)]
  end function hermite_weights

end module davit_core_hermite
