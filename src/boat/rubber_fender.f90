!> A rubber fender's reaction-deflection curve and its hysteresis (the default fender law,
!> in place of the paper's eqs. 27-28; review §1.7 finds the 55 GPa Hertz contact far too
!> stiff for the Section III.C model-test accelerations).
!>
!> Loading: the generic performance curve of a floating pneumatic rubber fender at 50 kPa
!> initial pressure (ISO 17357-1:2014; the curve as tabulated in steps of 5 % of the
!> diameter up to the rated deflection of 60 %): reaction R(delta) = R_r r(delta/D) with r
!> from the table, linear between points (so the force is continuous), nearly linear at
!> first and stiffening towards the rated deflection. Past 60 % (bottoming, outside the
!> table) the last segment's slope continues.
!>
!> Unloading from the turning point (delta_m, f_m): f = f_m (R(delta)/f_m)^p, p >= 1, which
!> meets the loading curve at delta_m (continuous), lies below it (rubber loses energy,
!> never gains), and returns to zero force at zero deflection (a rubber fender recovers
!> its shape: no permanent set). p is chosen per contact so that the work returned is
!> e_r^2 times the work of compression: a mass rebounds at e_r times its approach speed
!> and absorbs (1 - e_r^2) of its kinetic energy.
module davit_boat_rubber_fender
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use davit_kinds, only: wp
  implicit none
  private
  public :: rubber_loading, rubber_unloading, rubber_unloading_exponent, rubber_work
  public :: curve_deflection, curve_reaction

  !> Generic curve: deflection / diameter and reaction / rated reaction (ISO 17357-1
  !> pneumatic fender, 50 kPa; README "### Fenders" gives the sources).
  real(wp), parameter :: curve_deflection(13) = [0.0_wp, 0.05_wp, 0.10_wp, 0.15_wp, &
                                                 0.20_wp, 0.25_wp, 0.30_wp, 0.35_wp, &
                                                 0.40_wp, 0.45_wp, 0.50_wp, 0.55_wp, 0.60_wp]
  real(wp), parameter :: curve_reaction(13) = [0.0_wp, 0.03_wp, 0.06_wp, 0.10_wp, 0.14_wp, &
                                               0.19_wp, 0.25_wp, 0.32_wp, 0.40_wp, 0.51_wp, &
                                               0.66_wp, 0.82_wp, 1.0_wp]
  !> Largest deflection / diameter the last segment's slope is continued to: 10^6 diameters
  !> (a fender squeezed 60 % is bottomed out; only a diverging trial stage goes further).
  real(wp), parameter :: max_deflection = 1.0e6_wp
  !> Midpoint points of the work integrals (error ~1e-6 of the work).
  integer, parameter :: nquad = 512

contains

  !> Loading reaction [N] of a fender of diameter d [m] and rated reaction r_rated [N] at
  !> deflection delta [m] (0 for delta <= 0).
  !> Any trial state is safe (an integrator's trial stage is not the solution): NaN gives
  !> NaN, for the run's divergence check to report; the deflection is capped at
  !> max_deflection diameters, so a huge or infinite one gives a finite force, and the
  !> table index is formed from the deflection clamped to the table, never from int() of a
  !> value out of the integer range.
  pure real(wp) function rubber_loading(d, r_rated, delta) result(f)
    !> Fender diameter [m], rated reaction [N] at 60 % deflection, deflection [m].
    real(wp), intent(in) :: d, r_rated, delta
    real(wp) :: x, w
    integer :: i, n
    f = 0.0_wp
    if (ieee_is_nan(delta)) then
      f = delta
      return
    end if
    if (delta <= 0.0_wp) return
    n = size(curve_deflection)
    x = min(delta/d, max_deflection)
    i = min(int(min(x, curve_deflection(n))/curve_deflection(2)) + 1, n - 1)
    w = (x - curve_deflection(i))/(curve_deflection(i + 1) - curve_deflection(i))
    f = r_rated*(curve_reaction(i) + w*(curve_reaction(i + 1) - curve_reaction(i)))
  end function rubber_loading

  !> Unloading reaction [N] from the turning point (delta_m, f_m) with exponent p; capped
  !> at f_m (beyond delta_m the fender is loading again, which the phase machine catches).
  pure real(wp) function rubber_unloading(d, r_rated, f_m, p, delta) result(f)
    !> Fender diameter [m], rated reaction [N], force at the turning point [N], unloading exponent,
    !> deflection [m].
    real(wp), intent(in) :: d, r_rated, f_m, p, delta
    f = 0.0_wp
    if (delta <= 0.0_wp .or. f_m <= 0.0_wp) return
    f = f_m*min(rubber_loading(d, r_rated, delta)/f_m, 1.0_wp)**p
  end function rubber_unloading

  !> Work [J] of the path f_m (R/f_m)^p from 0 to delta_m (p = 1: the loading curve).
  pure real(wp) function rubber_work(d, r_rated, delta_m, p) result(w)
    !> Fender diameter [m], rated reaction [N], turning-point deflection [m], path exponent.
    real(wp), intent(in) :: d, r_rated, delta_m, p
    real(wp) :: h, f_m
    integer :: i
    w = 0.0_wp
    f_m = rubber_loading(d, r_rated, delta_m)
    if (delta_m <= 0.0_wp .or. f_m <= 0.0_wp) return
    h = delta_m/nquad
    do i = 1, nquad
      w = w + (rubber_loading(d, r_rated, (i - 0.5_wp)*h)/f_m)**p
    end do
    w = w*h*f_m
  end function rubber_work

  !> The exponent p >= 1 whose unloading path returns e^2 of the loading work up to
  !> delta_m (bisection on a bracket that doubles until it holds the root).
  pure real(wp) function rubber_unloading_exponent(d, r_rated, delta_m, e) result(p)
    !> Fender diameter [m], rated reaction [N], turning-point deflection [m], coefficient of
    !> restitution.
    real(wp), intent(in) :: d, r_rated, delta_m, e
    real(wp) :: target, lo, hi
    integer :: it
    p = 1.0_wp
    if (e >= 1.0_wp .or. delta_m <= 0.0_wp) return
    target = e**2*rubber_work(d, r_rated, delta_m, 1.0_wp)
    lo = 1.0_wp
    hi = 2.0_wp
    do it = 1, 60
      if (rubber_work(d, r_rated, delta_m, hi) <= target) exit
      lo = hi
      hi = 2.0_wp*hi
    end do
    do it = 1, 60
      p = 0.5_wp*(lo + hi)
      if (rubber_work(d, r_rated, delta_m, p) > target) then
        lo = p
      else
        hi = p
      end if
      if (hi - lo <= 1e-10_wp*hi) exit
    end do
    p = 0.5_wp*(lo + hi)
  end function rubber_unloading_exponent

end module davit_boat_rubber_fender
