!> Confidence intervals for a binomial proportion (how often a launch collides, from k of n
!> realisations). The Wilson score interval without continuity correction (Wilson 1927;
!> Newcombe 1998, Stat Med 17:857, method 3) is used because, unlike the Wald interval
!> p +- z sqrt(p(1-p)/n), it stays inside [0, 1] and does not collapse to zero width when
!> no (or every) realisation collides, which is the common case for a safe (or hopeless)
!> launch condition.
module davit_assess_statistics
  use davit_kinds, only: wp
  implicit none
  private
  public :: wilson_interval, wilson_halfwidth, z95

  !> Two-sided 95 % standard normal quantile.
  real(wp), parameter :: z95 = 1.959963984540054_wp

contains

  !> [lower, upper] of the Wilson score interval of k successes in n trials at normal
  !> quantile z (default z95): (2k + z^2 -+ z sqrt(z^2 + 4k(n-k)/n)) / (2(n + z^2)).
  !> n = 0 carries no information: [0, 1].
  pure function wilson_interval(k, n, z) result(bounds)
    !> Successes k and trials n (0 <= k <= n).
    integer, intent(in) :: k, n
    !> Normal quantile of the confidence level (default: 95 %).
    real(wp), intent(in), optional :: z
    real(wp) :: bounds(2)
    real(wp) :: q, centre, spread
    if (n <= 0) then
      bounds = [0.0_wp, 1.0_wp]
      return
    end if
    q = z95
    if (present(z)) q = z
    centre = 2.0_wp*real(k, wp) + q*q
    spread = q*sqrt(q*q + 4.0_wp*real(k, wp)*real(n - k, wp)/real(n, wp))
    bounds = [centre - spread, centre + spread]/(2.0_wp*(real(n, wp) + q*q))
    ! rounding may leave k = 0 (or k = n) a hair outside [0, 1]
    bounds = min(max(bounds, 0.0_wp), 1.0_wp)
  end function wilson_interval

  !> Half the width of the Wilson interval of k in n (0.5 for n = 0).
  pure real(wp) function wilson_halfwidth(k, n, z) result(half)
    !> Successes k and trials n (0 <= k <= n).
    integer, intent(in) :: k, n
    !> Normal quantile of the confidence level (default: 95 %).
    real(wp), intent(in), optional :: z
    real(wp) :: bounds(2)
    bounds = wilson_interval(k, n, z)
    half = 0.5_wp*(bounds(2) - bounds(1))
  end function wilson_halfwidth

end module davit_assess_statistics
