!> Chinese coastal wave spectrum, paper eq. (44), with the review's analysis (§1.9):
!> S(w) = 0.74 w^-5 exp(-a/w^2), a = g^2/U^2, U = 6.28 sqrt(H). The 0.74 is dimensional
!> (m^2 s^-4). Moments: m0 = 0.37/a^2, so Hs = 4 sqrt(m0) = 0.9971 H; peak w_p = sqrt(2a/5).
module davit_sea_spectrum
  use davit_kinds, only: wp, gravity
  implicit none
  private
  public :: spectrum_u, spectrum_density, spectrum_m0, spectrum_peak_omega
  public :: spectrum_band_fraction

contains

  !> The spectrum's velocity scale U = 6.28 sqrt(H) [m/s] (not the force wind speed).
  elemental real(wp) function spectrum_u(height)
    !> Sea-state height H of the spectrum [m].
    real(wp), intent(in) :: height
    spectrum_u = 6.28_wp*sqrt(height)
  end function spectrum_u

  !> S(omega) [m^2 s] for the height H.
  elemental real(wp) function spectrum_density(omega, height) result(s)
    !> Wave frequency omega [rad/s] and sea-state height H [m].
    real(wp), intent(in) :: omega, height
    real(wp) :: a
    a = (gravity/spectrum_u(height))**2
    if (omega <= 0.0_wp) then
      s = 0.0_wp
    else
      s = 0.74_wp/omega**5*exp(-a/omega**2)
    end if
  end function spectrum_density

  !> Analytic zeroth moment m0 = 0.37 U^4/g^4 [m^2].
  elemental real(wp) function spectrum_m0(height)
    !> Sea-state height H of the spectrum [m].
    real(wp), intent(in) :: height
    spectrum_m0 = 0.37_wp*(spectrum_u(height)/gravity)**4
  end function spectrum_m0

  !> Peak frequency sqrt(2a/5) = 0.6325 g/U [rad/s].
  elemental real(wp) function spectrum_peak_omega(height)
    !> Sea-state height H of the spectrum [m].
    real(wp), intent(in) :: height
    spectrum_peak_omega = sqrt(0.4_wp)*gravity/spectrum_u(height)
  end function spectrum_peak_omega

  !> Fraction of m0 between w1 and w2: with t = a/w^2 the integral is
  !> (1 + t2) e^-t2 - (1 + t1) e^-t1.
  elemental real(wp) function spectrum_band_fraction(w1, w2, height) result(f)
    !> Band limits w1 < w2 [rad/s] and sea-state height H [m].
    real(wp), intent(in) :: w1, w2, height
    real(wp) :: a, t1, t2
    a = (gravity/spectrum_u(height))**2
    t1 = a/w1**2
    t2 = a/w2**2
    f = (1.0_wp + t2)*exp(-t2) - (1.0_wp + t1)*exp(-t1)
  end function spectrum_band_fraction

end module davit_sea_spectrum
