!> Directional spreading, paper eq. (45): D(g) = c_s cos^(2s)(g) for |g| < pi/2, with
!> c_s = 2^(2s-1) s! (s-1)!/(pi (2s-1)!) = 4^s (s!)^2/(pi (2s)!), exactly the inverse of the
!> integral of cos^(2s) over (-pi/2, pi/2) (review §1.9). Integer s >= 1.
module davit_sea_spreading
  use davit_kinds, only: wp, pi
  implicit none
  private
  public :: spreading_density, spreading_weights

contains

  elemental real(wp) function spreading_density(gamma, s) result(d)
    real(wp), intent(in) :: gamma
    integer, intent(in) :: s
    real(wp) :: c
    if (abs(gamma) >= 0.5_wp*pi) then
      d = 0.0_wp
      return
    end if
    ! 4^s (s!)^2/(2s)! via log-gamma, safe for large s
    c = exp(s*log(4.0_wp) + 2.0_wp*log_gamma(real(s + 1, wp)) - log_gamma(real(2*s + 1, wp)))/pi
    d = c*cos(gamma)**(2*s)
  end function spreading_density

  !> n directions (relative to the mean) equally spaced over [-window, +window], endpoints
  !> included (5 deg spacing for 13 over +-30 deg, review G21), and weights D(g_j) dg
  !> renormalised to sum to one: the truncated window keeps the requested variance
  !> (review G20). n = 1 gives a long-crested sea.
  pure subroutine spreading_weights(n, window, s, gamma, weight)
    integer, intent(in) :: n, s
    real(wp), intent(in) :: window
    real(wp), intent(out) :: gamma(n), weight(n)
    integer :: j
    if (n == 1) then
      gamma = 0.0_wp
      weight = 1.0_wp
      return
    end if
    do j = 1, n
      gamma(j) = -window + 2.0_wp*window*real(j - 1, wp)/real(n - 1, wp)
    end do
    weight = spreading_density(gamma, s)
    weight = weight/sum(weight)
  end subroutine spreading_weights

end module davit_sea_spreading
