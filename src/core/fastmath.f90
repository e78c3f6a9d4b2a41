!> Branch-free sine and cosine that the compiler can vectorise (the libm calls cannot be
!> vectorised without -ffast-math, which would also break the NaN checks). Cody-Waite
!> reduction by pi/2 in three parts, then the fdlibm kernel polynomials on [-pi/4, pi/4].
!> Accurate to a few ulp for |x| < 1e6 rad, far beyond any wave phase in a run.
module davit_core_fastmath
  use davit_kinds, only: wp
  implicit none
  private
  public :: fast_sincos

  real(wp), parameter :: two_over_pi = 6.36619772367581382433e-01_wp
  real(wp), parameter :: pio2_1 = 1.57079632673412561417e+00_wp
  real(wp), parameter :: pio2_2 = 6.07710050630396597660e-11_wp
  real(wp), parameter :: pio2_3 = 2.02226624871116645580e-21_wp
  real(wp), parameter :: s1 = -1.66666666666666324348e-01_wp, s2 = 8.33333333332248946124e-03_wp
  real(wp), parameter :: s3 = -1.98412698298579493134e-04_wp, s4 = 2.75573137070700676789e-06_wp
  real(wp), parameter :: s5 = -2.50507602534068634195e-08_wp, s6 = 1.58969099521155010221e-10_wp
  real(wp), parameter :: c1 = 4.16666666666666019037e-02_wp, c2 = -1.38888888888741095749e-03_wp
  real(wp), parameter :: c3 = 2.48015872894767294178e-05_wp, c4 = -2.75573143513906633035e-07_wp
  real(wp), parameter :: c5 = 2.08757232129817482790e-09_wp, c6 = -1.13596475577881948265e-11_wp

contains

  !> s = sin(x), c = cos(x).
  elemental subroutine fast_sincos(x, s, c)
    real(wp), intent(in) :: x
    real(wp), intent(out) :: s, c
    real(wp) :: fn, r, z, ps, pc
    integer :: q
    fn = anint(x*two_over_pi)
    r = ((x - fn*pio2_1) - fn*pio2_2) - fn*pio2_3
    q = iand(int(fn), 3)
    z = r*r
    ps = r + r*z*(s1 + z*(s2 + z*(s3 + z*(s4 + z*(s5 + z*s6)))))
    pc = 1.0_wp - 0.5_wp*z + z*z*(c1 + z*(c2 + z*(c3 + z*(c4 + z*(c5 + z*c6)))))
    s = merge(merge(ps, pc, q == 0), merge(-ps, -pc, q == 2), iand(q, 2) == 0)
    c = merge(merge(pc, -ps, q == 0), merge(-pc, ps, q == 2), iand(q, 2) == 0)
  end subroutine fast_sincos

end module davit_core_fastmath
