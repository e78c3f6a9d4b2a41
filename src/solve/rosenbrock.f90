!> Linearly implicit Rosenbrock method RODAS3: 4 stages (3 RHS evaluations), order 3 with an
!> embedded order-2 solution for error control, L-stable and stiffly accurate, so stiff
!> sling/cable modes are damped rather than limiting the step (review sec. 4). Coefficients
!> from Sandu, Verwer, Blom, Spee, Carmichael & Potra, "Benchmarking stiff ODE solvers for
!> atmospheric chemistry problems II: Rosenbrock solvers", Atmos. Environ. 31 (1997)
!> 3459-3472, in the form of the KPP Rosenbrock integrator (subroutine Rodas3):
!>   (I/(h gamma) - J) K_i = f(t + alpha_i h, y + sum_j a_ij K_j) + sum_j (c_ij/h) K_j
!>                           + h gamma_i df/dt,
!>   y_new = y + sum_i m_i K_i,   error = sum_i e_i K_i.
!> J and df/dt are forward differences of the RHS (n + 1 evaluations), LU by LAPACK.
!> Stability function (evaluated from these coefficients): |R(iw)| <= 1 for all w,
!> R(z) ~ 8/(3z) -> 0 as z -> -inf (|R(-1e8)| = 2.7e-8), local error ~ z^4 (order 3).
!>
!> Contract as for dopri5: step(problem, t, y, dt) advances exactly from t to t + dt with
!> adaptive internal steps (the shared driver, davit_solve_adaptive); the proposed step
!> persists between calls. J is recomputed at every accepted point and reused (exactly)
!> after a rejection. Reusing it across steps would need a W-method (RODAS3 loses order
!> with an inexact J), so that is not offered. Unlike dopri5 and rosw, RODAS3 runs every
!> call to t + dt even with single_step (it always has: its results are kept).
module davit_solve_rosenbrock
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem
  use davit_solve_adaptive, only: adaptive_integrator, adaptive_step
  implicit none
  private
  public :: rosenbrock_type, stage_function, stage_right_side, stage_combination

  integer, parameter :: ns = 4
  !> Stage coefficients a_ij, c_ij (strictly lower triangular, row i = stage i).
  real(wp), parameter :: ra(ns, ns) = reshape([ &
                         0.0_wp, 0.0_wp, 2.0_wp, 2.0_wp, &
                         0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                         0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                         0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [ns, ns])
  real(wp), parameter :: rc(ns, ns) = reshape([ &
                         0.0_wp, 4.0_wp, 1.0_wp, 1.0_wp, &
                         0.0_wp, 0.0_wp, -1.0_wp, -1.0_wp, &
                         0.0_wp, 0.0_wp, 0.0_wp, -8.0_wp/3.0_wp, &
                         0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [ns, ns])
  real(wp), parameter :: rm(ns) = [2.0_wp, 0.0_wp, 1.0_wp, 1.0_wp]
  real(wp), parameter :: re(ns) = [0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp]
  real(wp), parameter :: ralpha(ns) = [0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp]
  real(wp), parameter :: rgamma(ns) = [0.5_wp, 1.5_wp, 0.0_wp, 0.0_wp]
  !> Stage 2 reuses f of stage 1 (alpha_2 = 0, a_21 = 0).
  logical, parameter :: new_f(ns) = [.true., .false., .true., .true.]

  interface
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: wp
      !> LAPACK dgetrf: rows m, columns n and leading dimension lda of a.
      integer, intent(in) :: m, n, lda
      !> LAPACK dgetrf: the matrix, overwritten by its LU factors.
      real(wp), intent(inout) :: a(lda, *)
      !> LAPACK dgetrf: the row pivots.
      integer, intent(out) :: ipiv(*)
      !> LAPACK dgetrf: 0 on success, > 0 for a singular factor.
      integer, intent(out) :: info
    end subroutine dgetrf
    subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: wp
      !> LAPACK dgetrs: 'N' to solve A x = b.
      character(len=1), intent(in) :: trans
      !> LAPACK dgetrs: order n, right-hand sides nrhs, leading dimensions of a and b.
      integer, intent(in) :: n, nrhs, lda, ldb
      !> LAPACK dgetrs: the LU factors from dgetrf.
      real(wp), intent(in) :: a(lda, *)
      !> LAPACK dgetrs: the row pivots from dgetrf.
      integer, intent(in) :: ipiv(*)
      !> LAPACK dgetrs: right-hand sides, overwritten by the solutions.
      real(wp), intent(inout) :: b(ldb, *)
      !> LAPACK dgetrs: 0 on success.
      integer, intent(out) :: info
    end subroutine dgetrs
  end interface

  type, extends(adaptive_integrator) :: rosenbrock_type
    !> f does not depend on t explicitly: skip the df/dt difference (one RHS per step).
    logical :: autonomous = .false.
    !> Accepted-point Jacobians formed and LU factorisations done (statistics).
    integer :: jacobians = 0, decompositions = 0
    !> Stage vectors K_i (n, ns) and the time derivative df/dt at the point.
    real(wp), allocatable :: k(:, :), dfdt(:)
    !> Jacobian J = df/dy at the point and the LU factors of I/(h gamma) - J.
    real(wp), allocatable :: jac(:, :), lu(:, :)
    !> Row pivots of the LU factors.
    integer, allocatable :: ipiv(:)
  contains
    procedure :: init => rosenbrock_init
    procedure :: step => rosenbrock_step
    procedure :: start => linearise
    procedure :: prepare => factor
    procedure :: attempt => stages
  end type rosenbrock_type

contains

  subroutine rosenbrock_init(self, n)
    !> The integrator whose work arrays are allocated.
    class(rosenbrock_type), intent(inout) :: self
    !> Size of the state vector.
    integer, intent(in) :: n
    call self%init_work(n, 3)  ! a 3rd-order method with a 2nd-order embedded one
    if (allocated(self%k)) deallocate (self%k, self%dfdt, self%jac, self%lu, self%ipiv)
    allocate (self%k(n, ns), self%dfdt(n), self%jac(n, n), self%lu(n, n), self%ipiv(n))
    self%jacobians = 0
    self%decompositions = 0
    self%method = "rosenbrock"
  end subroutine rosenbrock_init

  !> The shared driver, but each call runs to t + dt: single_step is not honoured.
  subroutine rosenbrock_step(self, problem, t, y, dt)
    !> The integrator (work arrays, statistics, proposed step, failure record).
    class(rosenbrock_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time [s], advanced by dt.
    real(wp), intent(inout) :: t
    !> State vector, advanced.
    real(wp), intent(inout) :: y(:)
    !> Macro step [s].
    real(wp), intent(in) :: dt
    logical :: single
    single = self%single_step
    self%single_step = .false.
    call adaptive_step(self, problem, t, y, dt)
    self%single_step = single
  end subroutine rosenbrock_step

  !> f0 = f(t, y), J = df/dy by one forward difference per column, and df/dt: at every
  !> accepted point (`first` or not).
  subroutine linearise(self, problem, t, y, first)
    !> The integrator; f0, jac and dfdt written.
    class(rosenbrock_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y of the accepted point.
    real(wp), intent(in) :: t, y(:)
    !> True at the call's first point (unused: J is formed at every point).
    logical, intent(in) :: first
    real(wp), parameter :: sqrt_eps = sqrt(epsilon(1.0_wp))
    real(wp) :: del
    integer :: j
    call problem%rhs(t, y, self%f0)
    self%ytmp = y
    do j = 1, size(y)
      ! Scaled perturbation; re-derive it from the rounded sum so the quotient is exact.
      del = sqrt_eps*max(abs(y(j)), 1.0e-5_wp)
      self%ytmp(j) = y(j) + del
      del = self%ytmp(j) - y(j)
      call problem%rhs(t, self%ytmp, self%fcn)
      self%jac(:, j) = (self%fcn - self%f0)/del
      self%ytmp(j) = y(j)
    end do
    self%rhs_evaluations = self%rhs_evaluations + 1 + size(y)
    self%jacobians = self%jacobians + 1
    if (self%autonomous) then
      self%dfdt = 0.0_wp
      return
    end if
    del = sqrt_eps*max(1.0_wp, abs(t))
    del = (t + del) - t
    call problem%rhs(t + del, y, self%fcn)
    self%dfdt = (self%fcn - self%f0)/del
    self%rhs_evaluations = self%rhs_evaluations + 1
  end subroutine linearise

  !> LU of I/(h gamma) - J before every trial step (J, df/dt and f0 stay valid after a
  !> rejection at the same point); ok = .false. when singular, with half the step to
  !> retry.
  subroutine factor(self, problem, t, y, h, ok)
    !> The integrator; lu and ipiv written (self%h on a singular matrix).
    class(rosenbrock_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> False when I/(h gamma) - J is singular.
    logical, intent(out) :: ok
    integer :: i, n, info
    n = size(self%jac, 1)
    self%lu = -self%jac
    do i = 1, n
      self%lu(i, i) = self%lu(i, i) + 1.0_wp/(h*rgamma(1))
    end do
    call dgetrf(n, n, self%lu, n, self%ipiv, info)
    self%decompositions = self%decompositions + 1
    ok = info == 0
    if (.not. ok) self%h = 0.5_wp*h
  end subroutine factor

  !> The four stages from (t, y) with step h (LU ready): ynew and the error vector yerr
  !> (formed with_error or not: it costs no RHS).
  subroutine stages(self, problem, t, y, h, with_error)
    !> The integrator; the stages, ynew and yerr written.
    class(rosenbrock_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> Whether the error vector is wanted (it is formed either way).
    logical, intent(in) :: with_error
    integer :: i, n, info
    n = size(y)
    self%fcn = self%f0
    do i = 1, ns
      if (i > 1 .and. new_f(i)) then
        call stage_function(self, problem, t, y, h, ra(i, :), ralpha(i), self%k, i)
      end if
      call stage_right_side(self%fcn, rc(i, :), h, self%k, i)
      if (rgamma(i) /= 0.0_wp) self%k(:, i) = self%k(:, i) + (h*rgamma(i))*self%dfdt
      call dgetrs("N", n, 1, self%lu, n, self%ipiv, self%k(:, i), n, info)
    end do
    call stage_combination(y, rm, re, self%k, self%ynew, self%yerr)
  end subroutine stages

  !> fcn = f(t + alpha_i h, y + sum_{j < i} a_ij K_j), stage i's right-hand side (one more
  !> evaluation), shared by the Rosenbrock methods (RODAS3 here, ROS34PW2 in
  !> davit_solve_rosenbrock_w).
  subroutine stage_function(self, problem, t, y, h, a, alpha, k, i)
    ! 8 arguments: the trial's start (t, y, h), stage i's coefficients and the stages
    !> The integrator; ytmp (the argument) and fcn written, the evaluation counted.
    class(adaptive_integrator), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> Row i of the stage coefficients a_ij, and the stage's time fraction alpha_i.
    real(wp), intent(in) :: a(:), alpha
    !> The stages K_j (n, stages); those before i are used.
    real(wp), intent(in) :: k(:, :)
    !> The stage.
    integer, intent(in) :: i
    call stage_argument(y, a, k, i, self%ytmp)
    call problem%rhs(t + alpha*h, self%ytmp, self%fcn)
    self%rhs_evaluations = self%rhs_evaluations + 1
  end subroutine stage_function

  !> Stage i's argument y + sum_{j < i} a_ij K_j (zero coefficients skipped), shared by the
  !> Rosenbrock methods (RODAS3 here, ROS34PW2 in davit_solve_rosenbrock_w).
  pure subroutine stage_argument(y, a, k, i, x)
    !> State at the trial's start.
    real(wp), intent(in) :: y(:)
    !> Row i of the stage coefficients a_ij.
    real(wp), intent(in) :: a(:)
    !> The stages K_j (n, stages); those before i are used.
    real(wp), intent(in) :: k(:, :)
    !> The stage.
    integer, intent(in) :: i
    !> The argument.
    real(wp), intent(out) :: x(:)
    integer :: j
    x = y
    do j = 1, i - 1
      if (a(j) /= 0.0_wp) x = x + a(j)*k(:, j)
    end do
  end subroutine stage_argument

  !> Stage i's right-hand side before its solve, f + sum_{j < i} (c_ij/h) K_j, into K_i.
  pure subroutine stage_right_side(f, c, h, k, i)
    !> f at stage i's argument.
    real(wp), intent(in) :: f(:)
    !> Row i of the coefficients c_ij, and the step h [s].
    real(wp), intent(in) :: c(:), h
    !> The stages (n, stages); column i written.
    real(wp), intent(inout) :: k(:, :)
    !> The stage.
    integer, intent(in) :: i
    integer :: j
    k(:, i) = f
    do j = 1, i - 1
      k(:, i) = k(:, i) + (c(j)/h)*k(:, j)
    end do
  end subroutine stage_right_side

  !> The new state y + sum_i m_i K_i and the error vector sum_i e_i K_i (zero weights
  !> skipped).
  pure subroutine stage_combination(y, m, e, k, ynew, yerr)
    !> State at the trial's start.
    real(wp), intent(in) :: y(:)
    !> Solution weights m_i and error weights e_i.
    real(wp), intent(in) :: m(:), e(:)
    !> The stages (n, stages).
    real(wp), intent(in) :: k(:, :)
    !> The new state and the error vector.
    real(wp), intent(out) :: ynew(:), yerr(:)
    integer :: i
    ynew = y
    yerr = 0.0_wp
    do i = 1, size(m)
      if (m(i) /= 0.0_wp) ynew = ynew + m(i)*k(:, i)
      if (e(i) /= 0.0_wp) yerr = yerr + e(i)*k(:, i)
    end do
  end subroutine stage_combination

end module davit_solve_rosenbrock
