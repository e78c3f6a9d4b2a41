!> Rosenbrock-W method ROS34PW2 (Rang & Angermann, BIT 45 (2005) 761-787): 4 stages, order
!> 3 with an embedded order-2 solution, L-stable and stiffly accurate, and of order 3 for
!> ANY matrix W in place of the Jacobian (a W-method). That is what lets davit treat only
!> the stiff part implicitly (issue 14): W is the Jacobian's rows of the problem's stiff
!> states (the rigging: blocks, lumps, sheaves; `ode_problem%stiff_states`), in the
!> columns of those states and of the states they are stiffly coupled to
!> (`coupled_states`: the boat and ship, whose hooks and heads pull on the blocks with
!> the wire's stiffness), formed by forward differences (one RHS per column) and kept for
!> many steps; every other row is explicit, so I/(h gamma) - W is block lower triangular:
!> the explicit rows first, then one small solve for the stiff ones. The stiff springs
!> (the 50 kg block on its 1 m sling,
!> |lambda| ~ 1260 1/s) are then damped where they are not excited instead of capping the
!> step, while the error control still resolves them where they are (a snatch).
!>
!> In the transformed form (Hairer & Wanner II, sec. IV.7) with u_i = sum_j gamma_ij k_j:
!>   (I/(h gamma) - W) u_i = f(t + alpha_i h, y + sum_j a_ij u_j) + sum_j (c_ij/h) u_j,
!>   y_new = y + sum_i m_i u_i,   error = sum_i (m_i - mhat_i) u_i,
!> a = alpha Gamma^-1, c = diag(1/gamma) - Gamma^-1, m = b Gamma^-1 (computed once here
!> from the published alpha, Gamma, b, bhat). W is zero outside the stiff rows, so the
!> other rows are u_i = h gamma (...), and the stiff rows solve
!> (I/(h gamma) - W_SS) u_S = r_S + W_SC u_C with only W_SS factored. The explicit
!> time dependence (df/dt) is left out of W as W-methods allow (t is a state whose column
!> of W is zero).
!>
!> Contract as for dopri5: step(problem, t, y, dt) advances exactly from t to t + dt with
!> adaptive internal steps (the shared driver, davit_solve_adaptive); the proposed step and
!> W persist between calls. W is formed
!> afresh after a rejection once more than 10 steps old, and after `max_age` accepted steps
!> (measured: 50 and every rejection, 200 and 10, 400 and 20 gave 0.58, 0.56, 0.60 s on the
!> regular launch and 4.8, 4.2, 5.0 s on the irregular one at rtol 1e-4 and 1e-5).
module davit_solve_rosenbrock_w
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem
  use davit_solve_adaptive, only: adaptive_integrator
  use davit_solve_rosenbrock, only: stage_function, stage_right_side, stage_combination
  implicit none
  private
  public :: rosenbrock_w_type

  integer, parameter :: ns = 4
  real(wp), parameter :: gam = 4.3586652150845900e-1_wp
  !> alpha_ij and gamma_ij (i > j) of ROS34PW2, Rang & Angermann (2005), Table 3.
  real(wp), parameter :: alpha_rw(ns, ns) = reshape([ &
    0.0_wp, 8.7173304301691801e-1_wp, 8.4457060015369423e-1_wp, 0.0_wp, &
    0.0_wp, 0.0_wp, -1.1299064236484185e-1_wp, 0.0_wp, &
    0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
    0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [ns, ns])
  real(wp), parameter :: gamma_rw(ns, ns) = reshape([ &
    gam, -8.7173304301691801e-1_wp, -9.0338057013044082e-1_wp, 2.4212380706095346e-1_wp, &
    0.0_wp, gam, 5.4180672388095326e-2_wp, -1.2232505839045147_wp, &
    0.0_wp, 0.0_wp, gam, 5.4526025533510214e-1_wp, &
    0.0_wp, 0.0_wp, 0.0_wp, gam], [ns, ns])
  real(wp), parameter :: b_rw(ns) = [2.4212380706095346e-1_wp, -1.2232505839045147_wp, &
                                     1.5452602553351020_wp, gam]
  real(wp), parameter :: bhat_rw(ns) = [3.7810903145819369e-1_wp, &
                                        -9.6042292212423178e-2_wp, 0.5_wp, &
                                        2.1793326075422950e-1_wp]

  type, extends(adaptive_integrator) :: rosenbrock_w_type
    !> Accepted steps a W is kept for.
    integer :: max_age = 200
    !> Ws formed and factorisations (statistics).
    integer :: jacobians = 0, decompositions = 0
    !> Transformed coefficients a = alpha Gamma^-1, c = diag(1/gamma) - Gamma^-1 (diagonal
    !> zeroed), m = b Gamma^-1 and the error weights e = m - bhat Gamma^-1.
    real(wp) :: a(ns, ns) = 0.0_wp, c(ns, ns) = 0.0_wp, m(ns) = 0.0_wp, e(ns) = 0.0_wp
    !> Stage times alpha_i (fractions of the step).
    real(wp) :: alpha(ns) = 0.0_wp
    !> The problem's stiff states, the states they are coupled to, and the LU's row pivots.
    integer, allocatable :: stiff(:), coupled(:), piv(:)
    !> W_SS and W_SC, the LU factors of I/(h gamma) - W_SS, and the stages u (n, ns).
    real(wp), allocatable :: w(:, :), wc(:, :), lu(:, :), u(:, :)
    !> Accepted steps since W was formed (-1: form one before the next trial step), and
    !> the step its LU is for (-1: none).
    integer :: age = -1
    !> Step h the LU is for [s] (-1: none).
    real(wp) :: h_lu = -1.0_wp
  contains
    procedure :: init => rosw_init
    procedure :: start => rosw_start
    procedure :: prepare => rosw_prepare
    procedure :: attempt => stages
    procedure :: next_step => rosw_controller
    procedure :: on_acceptance => rosw_accepted
    procedure :: on_rejection => rosw_rejected
    procedure, private :: form_w, factor
  end type rosenbrock_w_type

contains

  subroutine rosw_init(self, n)
    !> The integrator whose work arrays and coefficients are set.
    class(rosenbrock_w_type), intent(inout) :: self
    !> Size of the state vector.
    integer, intent(in) :: n
    real(wp) :: ginv(ns, ns)
    integer :: i
    call self%init_work(n, 3)  ! a 3rd-order method with a 2nd-order embedded one
    if (allocated(self%u)) deallocate (self%u)
    ! the stiff set and W are the problem's: taken on the first step
    if (allocated(self%stiff)) deallocate (self%stiff, self%coupled, self%w, self%wc, &
                                           self%lu, self%piv)
    allocate (self%u(n, ns))
    ginv = lower_inverse(gamma_rw)
    self%a = matmul(alpha_rw, ginv)
    self%c = -ginv
    do i = 1, ns
      self%c(i, i) = 0.0_wp
    end do
    self%m = matmul(b_rw, ginv)
    self%e = self%m - matmul(bhat_rw, ginv)
    self%alpha = sum(alpha_rw, dim=2)
    self%jacobians = 0
    self%decompositions = 0
    self%age = -1
    self%h_lu = -1.0_wp
    self%method = "rosw"
  end subroutine rosw_init

  !> f0 = f(t, y) at every new point; on the first call, the problem's stiff and coupled
  !> states (W's rows and columns) are taken.
  subroutine rosw_start(self, problem, t, y, first)
    !> The integrator; f0 written (and the stiff sets taken on the first call).
    class(rosenbrock_w_type), intent(inout) :: self
    !> The problem y' = f(t, y), with its stiff and coupled states.
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y of the new point.
    real(wp), intent(in) :: t, y(:)
    !> True at the call's first point.
    logical, intent(in) :: first
    if (.not. allocated(self%stiff)) then
      self%stiff = problem%stiff_states()
      self%coupled = problem%coupled_states()
      allocate (self%w(size(self%stiff), size(self%stiff)), &
                self%wc(size(self%stiff), size(self%coupled)), &
                self%lu(size(self%stiff), size(self%stiff)), self%piv(size(self%stiff)))
    end if
    call problem%rhs(t, y, self%f0)
    self%rhs_evaluations = self%rhs_evaluations + 1
  end subroutine rosw_start

  !> W formed afresh when none is valid, after max_age accepted steps, and for every fixed
  !> step; refactored only when h changes. A singular I/(h gamma) - W: retry with a fresh
  !> W at a fac_min times smaller step.
  subroutine rosw_prepare(self, problem, t, y, h, ok)
    !> The integrator; W and its LU formed as needed (self%h on a singular matrix).
    class(rosenbrock_w_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> False when I/(h gamma) - W is singular.
    logical, intent(out) :: ok
    ok = .true.
    if (self%fixed_step .or. self%age < 0 .or. self%age >= self%max_age) then
      call self%form_w(problem, t, y)
    end if
    if (h /= self%h_lu) call self%factor(h, ok)
    if (ok) return
    self%h = h*self%fac_min
    self%age = -1
    self%h_lu = -1.0_wp
  end subroutine rosw_prepare

  !> HNW I, eq. 4.13 as written for rosw (safety err^(-1/3), the same value as the
  !> default's safety / err^(1/3) but for rounding: kept so that results do not change).
  !> A rejection (err > 1) gives a factor below safety, so fac_max does not bind there.
  pure function rosw_controller(self, h, err, accepted) result(h_new)
    !> The integrator (its controller factors).
    class(rosenbrock_w_type), intent(in) :: self
    !> Trial step h [s] and its error norm err.
    real(wp), intent(in) :: h, err
    !> True when the trial was accepted.
    logical, intent(in) :: accepted
    real(wp) :: h_new
    h_new = h*min(self%fac_max, max(self%fac_min, &
                                    self%safety*max(err, 1.0e-10_wp)** &
                                    (-1.0_wp/real(self%order, wp))))
  end function rosw_controller

  subroutine rosw_accepted(self, err)
    !> The integrator; W's age advanced.
    class(rosenbrock_w_type), intent(inout) :: self
    !> Error norm of the accepted step.
    real(wp), intent(in) :: err
    self%age = self%age + 1
  end subroutine rosw_accepted

  !> After a rejection a fresh W, unless this one is young (<= 10 accepted steps).
  subroutine rosw_rejected(self)
    !> The integrator; W marked stale when old.
    class(rosenbrock_w_type), intent(inout) :: self
    if (self%age > 10) self%age = -1
  end subroutine rosw_rejected

  !> Inverse of a lower-triangular matrix with nonzero diagonal (forward substitution).
  pure function lower_inverse(l) result(x)
    !> Lower-triangular matrix with a nonzero diagonal.
    real(wp), intent(in) :: l(:, :)
    real(wp) :: x(size(l, 1), size(l, 1))
    integer :: i, j, n
    n = size(l, 1)
    x = 0.0_wp
    do j = 1, n
      x(j, j) = 1.0_wp/l(j, j)
      do i = j + 1, n
        x(i, j) = -dot_product(l(i, j:i - 1), x(j:i - 1, j))/l(i, i)
      end do
    end do
  end function lower_inverse

  !> W_SS = df_S/dy_S and W_SC = df_S/dy_C by one forward difference per column, at
  !> (t, y) with f0 = f(t, y).
  subroutine form_w(self, problem, t, y)
    !> The integrator; w and wc formed, its age reset.
    class(rosenbrock_w_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y of the point (f0 = f(t, y) there).
    real(wp), intent(in) :: t, y(:)
    integer :: j
    do j = 1, size(self%stiff)
      call difference(self, problem, t, y, self%stiff(j), self%w(:, j))
    end do
    do j = 1, size(self%coupled)
      call difference(self, problem, t, y, self%coupled(j), self%wc(:, j))
    end do
    self%rhs_evaluations = self%rhs_evaluations + size(self%stiff) + size(self%coupled)
    self%jacobians = self%jacobians + 1
    self%age = 0
    self%h_lu = -1.0_wp
  end subroutine form_w

  !> Column js of the stiff rows' Jacobian by a forward difference (ytmp = y on return).
  subroutine difference(self, problem, t, y, js, col)
    !> The integrator (f0, the stiff set; ytmp and fcn used as work).
    class(rosenbrock_w_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y of the point.
    real(wp), intent(in) :: t, y(:)
    !> Index of the state the column is for.
    integer, intent(in) :: js
    !> The column: d f_S/d y_js at the stiff rows.
    real(wp), intent(out) :: col(:)
    real(wp), parameter :: sqrt_eps = sqrt(epsilon(1.0_wp))
    real(wp) :: del
    self%ytmp = y
    del = sqrt_eps*max(abs(y(js)), 1.0e-5_wp)
    self%ytmp(js) = y(js) + del
    del = self%ytmp(js) - y(js)
    call problem%rhs(t, self%ytmp, self%fcn)
    col = (self%fcn(self%stiff) - self%f0(self%stiff))/del
    self%ytmp(js) = y(js)
  end subroutine difference

  !> LU (partial pivoting) of I/(h gamma) - W on the stiff block; ok = .false. if singular.
  subroutine factor(self, h, ok)
    !> The integrator; lu and piv written.
    class(rosenbrock_w_type), intent(inout) :: self
    !> Step h [s].
    real(wp), intent(in) :: h
    !> False when a pivot is zero (singular matrix).
    logical, intent(out) :: ok
    integer :: i, k, p, n
    real(wp) :: row(size(self%stiff))
    n = size(self%stiff)
    ok = .true.
    self%decompositions = self%decompositions + 1
    self%h_lu = h
    self%lu = -self%w
    do i = 1, n
      self%lu(i, i) = self%lu(i, i) + 1.0_wp/(h*gam)
      self%piv(i) = i
    end do
    do k = 1, n
      p = k - 1 + maxloc(abs(self%lu(k:n, k)), dim=1)
      if (self%lu(p, k) == 0.0_wp) then
        ok = .false.
        return
      end if
      if (p /= k) then
        row = self%lu(k, :)
        self%lu(k, :) = self%lu(p, :)
        self%lu(p, :) = row
        i = self%piv(k)
        self%piv(k) = self%piv(p)
        self%piv(p) = i
      end if
      self%lu(k + 1:n, k) = self%lu(k + 1:n, k)/self%lu(k, k)
      do i = k + 1, n
        self%lu(i, k + 1:n) = self%lu(i, k + 1:n) - self%lu(i, k)*self%lu(k, k + 1:n)
      end do
    end do
  end subroutine factor

  !> Solve (I/(h gamma) - W) x = r in place: the explicit rows by the diagonal h gamma,
  !> then the stiff rows by the LU with the coupled rows' part W_SC x_C moved right.
  pure subroutine solve_stage(stiff, coupled, wc, lu, piv, h, r)
    !> Stiff states, coupled states and the LU's row pivots.
    integer, intent(in) :: stiff(:), coupled(:), piv(:)
    !> W_SC, the LU factors of I/(h gamma) - W_SS, and the step h [s].
    real(wp), intent(in) :: wc(:, :), lu(:, :), h
    !> Right-hand side r on entry, the solution x on return.
    real(wp), intent(inout) :: r(:)
    real(wp) :: x(size(stiff)), rs(size(stiff))
    integer :: i, n
    n = size(stiff)
    rs = r(stiff)
    r = (h*gam)*r
    if (size(coupled) > 0) rs = rs + matmul(wc, r(coupled))
    x = rs(piv)
    do i = 2, n
      x(i) = x(i) - dot_product(lu(i, 1:i - 1), x(1:i - 1))
    end do
    do i = n, 1, -1
      x(i) = (x(i) - dot_product(lu(i, i + 1:n), x(i + 1:n)))/lu(i, i)
    end do
    r(stiff) = x
  end subroutine solve_stage

  !> The four stages from (t, y) with step h (f0 = f(t, y), LU ready): ynew and yerr
  !> (formed with_error or not: it costs no RHS).
  subroutine stages(self, problem, t, y, h, with_error)
    !> The integrator; the stages, ynew and yerr written.
    class(rosenbrock_w_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> Whether the error vector is wanted (it is formed either way).
    logical, intent(in) :: with_error
    integer :: i
    do i = 1, ns
      if (i == 1) then
        self%fcn = self%f0
      else
        call stage_function(self, problem, t, y, h, self%a(i, :), self%alpha(i), self%u, i)
      end if
      call stage_right_side(self%fcn, self%c(i, :), h, self%u, i)
      call solve_stage(self%stiff, self%coupled, self%wc, self%lu, self%piv, h, &
                       self%u(:, i))
    end do
    call stage_combination(y, self%m, self%e, self%u, self%ynew, self%yerr)
  end subroutine stages

end module davit_solve_rosenbrock_w
