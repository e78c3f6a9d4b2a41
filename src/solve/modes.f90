!> Spectrum of the linearised right-hand side, df/dy at one state: its largest eigenvalue
!> modulus bounds the step of an explicit method (RK4 is stable for h |lambda| <= 2.83 on
!> the imaginary axis, 2.79 on the negative real axis), which the stability map compares
!> with the largest step that runs.
module davit_solve_modes
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem
  implicit none
  private
  public :: jacobian_spectrum

  interface
    subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
      import :: wp
      character, intent(in) :: jobvl, jobvr
      integer, intent(in) :: n, lda, ldvl, ldvr, lwork
      real(wp), intent(inout) :: a(lda, *)
      real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
      integer, intent(out) :: info
    end subroutine dgeev
  end interface

contains

  !> Largest |lambda| and largest |Im lambda| (the fastest oscillation, rad/s) of df/dy at
  !> (t, y), by central differences (error O(del^2), so the stiff springs' eigenvalues come
  !> out to ~1e-8 relative) and LAPACK dgeev; info /= 0 if dgeev failed.
  subroutine jacobian_spectrum(problem, t, y, rate_max, omega_max, info)
    class(ode_problem), intent(in) :: problem
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: rate_max, omega_max
    integer, intent(out) :: info
    real(wp), parameter :: cbrt_eps = epsilon(1.0_wp)**(1.0_wp/3.0_wp)
    real(wp) :: jac(size(y), size(y)), yp(size(y)), fp(size(y)), fm(size(y)), del
    real(wp) :: wr(size(y)), wi(size(y)), vdum(1, 1), work(4*size(y))
    integer :: j, n
    n = size(y)
    yp = y
    do j = 1, n
      del = cbrt_eps*max(abs(y(j)), 1.0e-3_wp)
      yp(j) = y(j) + del
      call problem%rhs(t, yp, fp)
      yp(j) = y(j) - del
      call problem%rhs(t, yp, fm)
      jac(:, j) = (fp - fm)/(2.0_wp*del)
      yp(j) = y(j)
    end do
    call dgeev("N", "N", n, jac, n, wr, wi, vdum, 1, vdum, 1, work, size(work), info)
    rate_max = maxval(hypot(wr, wi))
    omega_max = maxval(abs(wi))
  end subroutine jacobian_spectrum

end module davit_solve_modes
