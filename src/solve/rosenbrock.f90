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
!> adaptive internal steps; the proposed step persists between calls. J is recomputed at
!> every accepted point and reused (exactly) after a rejection. Reusing it across steps
!> would need a W-method (RODAS3 loses order with an inexact J), so that is not offered.
module davit_solve_rosenbrock
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_solve_step_control, only: error_norm, initial_step, record_failure, stretch_to, &
                                      is_finite_real, substep_allowed
  implicit none
  private
  public :: rosenbrock_type

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
  !> Order of the error estimate's leading term (h_new ~ err^(-1/3)).
  real(wp), parameter :: err_order = 3.0_wp

  interface
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: wp
      integer, intent(in) :: m, n, lda
      real(wp), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*)
      integer, intent(out) :: info
    end subroutine dgetrf
    subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: wp
      character(len=1), intent(in) :: trans
      integer, intent(in) :: n, nrhs, lda, ldb
      real(wp), intent(in) :: a(lda, *)
      integer, intent(in) :: ipiv(*)
      real(wp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgetrs
  end interface

  type, extends(integrator_type) :: rosenbrock_type
    !> Mixed error tolerance: |e_i| <= atol + rtol |y_i| in the RMS sense.
    real(wp) :: rtol = 1.0e-6_wp
    real(wp) :: atol = 1.0e-9_wp
    !> Relative step floor: h < h_min max(1, |t|) is a step-size collapse (failure).
    real(wp) :: h_min = 1.0e-12_wp
    !> Most internal steps (accepted or rejected) in one macro step before failing.
    integer :: max_substeps = 100000
    !> No error control: exactly one internal step of size dt per call (order studies).
    logical :: fixed_step = .false.
    !> f does not depend on t explicitly: skip the df/dt difference (one RHS per step).
    logical :: autonomous = .false.
    !> Controller: safety factor and shrink/growth limits of h_new/h.
    real(wp) :: safety = 0.9_wp
    real(wp) :: fac_min = 0.2_wp
    real(wp) :: fac_max = 6.0_wp
    !> Proposed internal step (0: choose by the starting heuristic on the next call).
    real(wp) :: h = 0.0_wp
    !> Accepted-point Jacobians formed and LU factorisations done (statistics).
    integer :: jacobians = 0, decompositions = 0
    real(wp), allocatable :: k(:, :), f0(:), fcn(:), dfdt(:), ytmp(:), ynew(:), yerr(:)
    real(wp), allocatable :: jac(:, :), lu(:, :)
    integer, allocatable :: ipiv(:)
  contains
    procedure :: init => rosenbrock_init
    procedure :: step => rosenbrock_step
    procedure :: name => rosenbrock_name
    procedure, private :: linearise, factor, stages
  end type rosenbrock_type

contains

  subroutine rosenbrock_init(self, n)
    class(rosenbrock_type), intent(inout) :: self
    integer, intent(in) :: n
    if (allocated(self%k)) then
      deallocate (self%k, self%f0, self%fcn, self%dfdt, self%ytmp, self%ynew, self%yerr)
      deallocate (self%jac, self%lu, self%ipiv)
    end if
    allocate (self%k(n, ns), self%f0(n), self%fcn(n), self%dfdt(n), self%ytmp(n), &
              self%ynew(n), self%yerr(n), self%jac(n, n), self%lu(n, n), self%ipiv(n))
    self%steps = 0
    self%rhs_evaluations = 0
    self%jacobians = 0
    self%decompositions = 0
    self%failed = .false.
    if (allocated(self%failure)) deallocate (self%failure)
    self%h = 0.0_wp
  end subroutine rosenbrock_init

  !> f0 = f(t, y), J = df/dy by one forward difference per column, and df/dt.
  subroutine linearise(self, problem, t, y)
    class(rosenbrock_type), intent(inout) :: self
    class(ode_problem), intent(in) :: problem
    real(wp), intent(in) :: t, y(:)
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

  !> LU of I/(h gamma) - J; info /= 0 when singular.
  subroutine factor(self, h, info)
    class(rosenbrock_type), intent(inout) :: self
    real(wp), intent(in) :: h
    integer, intent(out) :: info
    integer :: i, n
    n = size(self%jac, 1)
    self%lu = -self%jac
    do i = 1, n
      self%lu(i, i) = self%lu(i, i) + 1.0_wp/(h*rgamma(1))
    end do
    call dgetrf(n, n, self%lu, n, self%ipiv, info)
    self%decompositions = self%decompositions + 1
  end subroutine factor

  !> The four stages from (t, y) with step h (LU ready): ynew and the error vector yerr.
  subroutine stages(self, problem, t, y, h)
    class(rosenbrock_type), intent(inout) :: self
    class(ode_problem), intent(in) :: problem
    real(wp), intent(in) :: t, y(:), h
    integer :: i, j, n, info
    n = size(y)
    self%fcn = self%f0
    do i = 1, ns
      if (i > 1 .and. new_f(i)) then
        self%ytmp = y
        do j = 1, i - 1
          if (ra(i, j) /= 0.0_wp) self%ytmp = self%ytmp + ra(i, j)*self%k(:, j)
        end do
        call problem%rhs(t + ralpha(i)*h, self%ytmp, self%fcn)
        self%rhs_evaluations = self%rhs_evaluations + 1
      end if
      self%k(:, i) = self%fcn
      do j = 1, i - 1
        self%k(:, i) = self%k(:, i) + (rc(i, j)/h)*self%k(:, j)
      end do
      if (rgamma(i) /= 0.0_wp) self%k(:, i) = self%k(:, i) + (h*rgamma(i))*self%dfdt
      call dgetrs("N", n, 1, self%lu, n, self%ipiv, self%k(:, i), n, info)
    end do
    self%ynew = y
    self%yerr = 0.0_wp
    do i = 1, ns
      if (rm(i) /= 0.0_wp) self%ynew = self%ynew + rm(i)*self%k(:, i)
      if (re(i) /= 0.0_wp) self%yerr = self%yerr + re(i)*self%k(:, i)
    end do
  end subroutine stages

  subroutine rosenbrock_step(self, problem, t, y, dt)
    class(rosenbrock_type), intent(inout) :: self
    class(ode_problem), intent(in) :: problem
    real(wp), intent(inout) :: t
    real(wp), intent(inout) :: y(:)
    real(wp), intent(in) :: dt
    real(wp) :: t_end, tc, h, err, h_new
    integer :: tries, info
    logical :: last, rejected

    if (self%failed) return
    t_end = t + dt
    call self%linearise(problem, t, y)
    if (self%fixed_step) then
      call self%factor(dt, info)
      if (info /= 0) then
        call record_failure(self, t, dt, "singular iteration matrix")
        return
      end if
      call self%stages(problem, t, y, dt)
      y = self%ynew
      t = t_end
      self%steps = self%steps + 1
      return
    end if
    if (self%h <= 0.0_wp) then
      self%h = initial_step(problem, t, y, self%f0, 3, self%atol, self%rtol, abs(dt), &
                            self%ytmp, self%fcn)
      self%rhs_evaluations = self%rhs_evaluations + 1
    end if

    tc = t
    rejected = .false.
    tries = 0
    do
      last = stretch_to(self%h, t_end - tc)
      h = merge(t_end - tc, self%h, last)
      tries = tries + 1
      if (.not. substep_allowed(self, tries, self%max_substeps, tc, h, self%h_min)) exit
      call self%factor(h, info)
      if (info /= 0) then
        self%h = 0.5_wp*h
        rejected = .true.
        cycle
      end if
      call self%stages(problem, tc, y, h)
      err = error_norm(self%yerr, y, self%ynew, self%atol, self%rtol)
      if (.not. is_finite_real(err)) then
        ! Overflow in a stage: reject with the strongest shrink; if it persists the step
        ! collapses and the h_min failure above reports it.
        self%h = h*self%fac_min
        rejected = .true.
        cycle
      end if
      h_new = h*min(self%fac_max, max(self%fac_min, &
                                      self%safety/max(err, 1.0e-10_wp)**(1.0_wp/err_order)))
      if (err > 1.0_wp) then
        ! Same point: J, df/dt and f0 stay valid, only the matrix is refactored.
        self%h = h_new
        rejected = .true.
        cycle
      end if
      if (rejected) h_new = min(h_new, h)
      y = self%ynew
      self%steps = self%steps + 1
      rejected = .false.
      if (last) then
        ! A clipped final step says little about growth; only let it shrink h.
        self%h = min(self%h, h_new)
        exit
      end if
      tc = tc + h
      self%h = h_new
      call self%linearise(problem, tc, y)
    end do
    t = merge(t_end, tc, .not. self%failed)
  end subroutine rosenbrock_step

  pure function rosenbrock_name(self) result(name)
    class(rosenbrock_type), intent(in) :: self
    character(len=:), allocatable :: name
    name = "rosenbrock"
  end function rosenbrock_name

end module davit_solve_rosenbrock
