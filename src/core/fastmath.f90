!> Branch-free sine and cosine that the compiler can vectorise (the libm calls cannot be
!> vectorised without -ffast-math, which would also break the NaN checks). Cody-Waite
!> reduction by pi/2 in three parts, then the fdlibm kernel polynomials on [-pi/4, pi/4].
!> Accurate to a few ulp for |x| < 1e6 rad, far beyond any wave phase in a run.
!> The array form keeps the loop inside this module, where it is inlined and vectorised.
module davit_core_fastmath
  use davit_kinds, only: wp
  implicit none
  private
  public :: fast_sincos

  interface fast_sincos
    module procedure sincos_scalar, sincos_array
  end interface fast_sincos

  !> 1.5 * 2^52: adding and subtracting it rounds a double (|x| < 2^51) to the nearest
  !> integer with plain arithmetic; ANINT would be a libm call on baseline x86-64.
  real(wp), parameter :: round_magic = 6755399441055744.0_wp
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
  pure subroutine sincos_scalar(x, s, c)
    !> Angle [rad].
    real(wp), intent(in) :: x
    !> Its sine s and cosine c.
    real(wp), intent(out) :: s, c
    real(wp) :: xs(1), ss(1), cs(1)
    xs(1) = x
    call sincos_array(xs, ss, cs)
    s = ss(1)
    c = cs(1)
  end subroutine sincos_scalar

  pure subroutine sincos_array(x, s, c)
    !> Angles [rad].
    real(wp), intent(in) :: x(:)
    !> Their sines s and cosines c, of the size of x.
    real(wp), intent(out) :: s(:), c(:)
    real(wp) :: fn, r, z, ps, pc, sw, cw, odd, high
    integer :: i
    do i = 1, size(x)
      fn = (x(i)*two_over_pi + round_magic) - round_magic
      r = ((x(i) - fn*pio2_1) - fn*pio2_2) - fn*pio2_3
      z = r*r
      ps = r + r*z*(s1 + z*(s2 + z*(s3 + z*(s4 + z*(s5 + z*s6)))))
      pc = 1.0_wp - 0.5_wp*z + z*z*(c1 + z*(c2 + z*(c3 + z*(c4 + z*(c5 + z*c6)))))
      ! quadrant q = fn mod 4 = 2 high + odd: odd q swaps sin and cos; sin is negated for
      ! q = 2, 3 (high), cos for q = 1, 2 (odd xor high). Arithmetic only, no branches.
      fn = fn - 4.0_wp*((0.25_wp*fn - 0.375_wp + round_magic) - round_magic)
      high = (0.5_wp*fn - 0.25_wp + round_magic) - round_magic
      odd = fn - 2.0_wp*high
      sw = merge(pc, ps, odd > 0.5_wp)
      cw = merge(ps, pc, odd > 0.5_wp)
      s(i) = sw*(1.0_wp - 2.0_wp*high)
      c(i) = cw*(1.0_wp - 2.0_wp*(odd + high - 2.0_wp*odd*high))
    end do
  end subroutine sincos_array

end module davit_core_fastmath
