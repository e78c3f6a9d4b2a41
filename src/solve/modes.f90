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
      !> LAPACK dgeev: 'N' for no left and no right eigenvectors.
      character, intent(in) :: jobvl, jobvr
      !> LAPACK dgeev: order n, leading dimensions, length of work.
      integer, intent(in) :: n, lda, ldvl, ldvr, lwork
      !> LAPACK dgeev: the matrix (overwritten).
      real(wp), intent(inout) :: a(lda, *)
      !> LAPACK dgeev: real and imaginary parts of the eigenvalues, eigenvectors, work.
      real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
      !> LAPACK dgeev: 0 on success.
      integer, intent(out) :: info
    end subroutine dgeev
  end interface

contains

  !> Largest |lambda| and largest |Im lambda| (the fastest oscillation, rad/s) of df/dy at
  !> (t, y), by central differences (error O(del^2), so the stiff springs' eigenvalues come
  !> out to ~1e-8 relative) and LAPACK dgeev; info /= 0 if dgeev failed.
  subroutine jacobian_spectrum(problem, t, y, rate_max, omega_max, info)
    !> The problem whose right-hand side is linearised.
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y of the linearisation.
    real(wp), intent(in) :: t, y(:)
    !> Largest eigenvalue modulus [1/s] and largest imaginary part [rad/s] of df/dy.
    real(wp), intent(out) :: rate_max, omega_max
    !> 0 on success, dgeev's code otherwise.
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
