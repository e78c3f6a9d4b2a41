!> Directional spreading, paper eq. (45): D(g) = c_s cos^(2s)(g) for |g| < pi/2, with
!> c_s = 2^(2s-1) s! (s-1)!/(pi (2s-1)!) = 4^s (s!)^2/(pi (2s)!), exactly the inverse of the
!> integral of cos^(2s) over (-pi/2, pi/2) (review §1.9). Integer s >= 1.
module davit_sea_spreading
  use davit_kinds, only: wp, pi
  implicit none
  private
  public :: spreading_density, spreading_weights, spreading_quantiles

contains

  elemental real(wp) function spreading_density(gamma, s) result(d)
    !> Direction relative to the mean direction [rad].
    real(wp), intent(in) :: gamma
    !> Spreading exponent s (integer, >= 1).
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
    !> Number of directions n and spreading exponent s (integer, >= 1).
    integer, intent(in) :: n, s
    !> Half-width of the direction window about the mean [rad].
    real(wp), intent(in) :: window
    !> Directions relative to the mean [rad] and their weights (summing to one).
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

  !> Directions gamma(p) with a fraction p of the spread's energy below them, for the
  !> probabilities p(:) in [0, 1], of D(g) truncated to [-window, +window] and renormalised
  !> (as spreading_weights truncates it): the single-summation sea draws its directions
  !> from this inverse distribution. The CDF is integrated by the trapezoid rule on a
  !> fine grid (nq intervals: error ~ 1e-7 rad for s <= 30) and inverted linearly.
  pure subroutine spreading_quantiles(p, window, s, gamma)
    !> Probabilities p in [0, 1] and half-width of the direction window [rad].
    real(wp), intent(in) :: p(:), window
    !> Spreading exponent s (integer, >= 1).
    integer, intent(in) :: s
    !> Directions relative to the mean [rad], one per probability.
    real(wp), intent(out) :: gamma(:)
    integer, parameter :: nq = 4000
    real(wp) :: g(0:nq), cdf(0:nq), d(0:nq), f
    integer :: i, j
    do i = 0, nq
      g(i) = -window + 2.0_wp*window*real(i, wp)/real(nq, wp)
    end do
    d = spreading_density(g, s)
    cdf(0) = 0.0_wp
    do i = 1, nq
      cdf(i) = cdf(i - 1) + 0.5_wp*(d(i) + d(i - 1))*(g(i) - g(i - 1))
    end do
    cdf = cdf/cdf(nq)
    do j = 1, size(p)
      i = bracket(cdf, min(max(p(j), 0.0_wp), 1.0_wp))
      f = (min(max(p(j), 0.0_wp), 1.0_wp) - cdf(i - 1))/max(cdf(i) - cdf(i - 1), tiny(1.0_wp))
      gamma(j) = g(i - 1) + f*(g(i) - g(i - 1))
    end do
  end subroutine spreading_quantiles

  !> The index i in 1..n with cdf(i - 1) <= x <= cdf(i) of a non-decreasing table cdf(0:n).
  pure integer function bracket(cdf, x) result(i)
    !> Non-decreasing table cdf(0:n) and the value x looked up in it.
    real(wp), intent(in) :: cdf(0:), x
    integer :: lo, hi, mid
    lo = 0
    hi = ubound(cdf, 1)
    do while (hi - lo > 1)
      mid = (lo + hi)/2
      if (cdf(mid) <= x) then
        lo = mid
      else
        hi = mid
      end if
    end do
    i = hi
  end function bracket

end module davit_sea_spreading
