!> Dormand-Prince 5(4) embedded Runge-Kutta pair (Dormand & Prince 1980; coefficients and
!> PI step control as in Hairer, Norsett & Wanner, Solving ODEs I, sec. II.4-5 and their
!> DOPRI5 code). The fifth-order solution is propagated (local extrapolation), the
!> difference to the fourth-order one estimates the error.
!>
!> Contract: step(problem, t, y, dt) advances exactly from t to t + dt (the driver's macro
!> step, after which after_step may change the problem, e.g. a contact phase), using as
!> many adaptive internal steps as the error control needs (the shared driver,
!> davit_solve_adaptive). FSAL is used only inside one macro step: after_step may change
!> the RHS, so the first stage is recomputed on entry. The proposed internal step size
!> persists between calls.
module davit_solve_dopri5
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem
  use davit_solve_adaptive, only: adaptive_integrator
  implicit none
  private
  public :: dopri5_type

  real(wp), parameter :: c2 = 1.0_wp/5, c3 = 3.0_wp/10, c4 = 4.0_wp/5, c5 = 8.0_wp/9
  real(wp), parameter :: a21 = 1.0_wp/5
  real(wp), parameter :: a31 = 3.0_wp/40, a32 = 9.0_wp/40
  real(wp), parameter :: a41 = 44.0_wp/45, a42 = -56.0_wp/15, a43 = 32.0_wp/9
  real(wp), parameter :: a51 = 19372.0_wp/6561, a52 = -25360.0_wp/2187, &
                         a53 = 64448.0_wp/6561, a54 = -212.0_wp/729
  real(wp), parameter :: a61 = 9017.0_wp/3168, a62 = -355.0_wp/33, a63 = 46732.0_wp/5247, &
                         a64 = 49.0_wp/176, a65 = -5103.0_wp/18656
  !> Fifth-order weights (= the last row of A, hence FSAL).
  real(wp), parameter :: b1 = 35.0_wp/384, b3 = 500.0_wp/1113, b4 = 125.0_wp/192, &
                         b5 = -2187.0_wp/6784, b6 = 11.0_wp/84
  !> b - b_hat (fifth minus fourth-order weights).
  real(wp), parameter :: e1 = 71.0_wp/57600, e3 = -71.0_wp/16695, e4 = 71.0_wp/1920, &
                         e5 = -17253.0_wp/339200, e6 = 22.0_wp/525, e7 = -1.0_wp/40

  type, extends(adaptive_integrator) :: dopri5_type
    !> PI controller's exponent beta on the previous error (HNW II, sec. IV.2; DOPRI5).
    real(wp) :: beta = 0.04_wp
    !> Previous accepted error (the PI controller's memory).
    real(wp) :: err_old = 1.0e-4_wp
    !> Stage derivatives k2..k7 (k1 is f0), of the state's size.
    real(wp), allocatable :: k2(:), k3(:), k4(:), k5(:), k6(:), k7(:)
  contains
    procedure :: init => dopri5_init
    procedure :: start => dopri5_start
    procedure :: attempt => dopri5_attempt
    procedure :: next_step => pi_controller
    procedure :: on_acceptance => dopri5_accepted
  end type dopri5_type

contains

  subroutine dopri5_init(self, n)
    !> The integrator whose work arrays are allocated.
    class(dopri5_type), intent(inout) :: self
    !> Size of the state vector.
    integer, intent(in) :: n
    call self%init_work(n, 5)  ! DOPRI5 propagates the 5th-order solution
    if (allocated(self%k2)) deallocate (self%k2, self%k3, self%k4, self%k5, self%k6, self%k7)
    allocate (self%k2(n), self%k3(n), self%k4(n), self%k5(n), self%k6(n), self%k7(n))
    ! DOPRI5's growth limit (HNW's fac2 = 10): an explicit step may grow faster than a
    ! Rosenbrock one
    self%fac_max = 10.0_wp
    self%err_old = 1.0e-4_wp
    self%method = "dopri5"
  end subroutine dopri5_init

  !> k1 = f0 = f(t, y); inside a macro step the last stage of the accepted step (FSAL,
  !> copied by dopri5_accepted) already is.
  subroutine dopri5_start(self, problem, t, y, first)
    !> The integrator; f0 written.
    class(dopri5_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y of the new point.
    real(wp), intent(in) :: t, y(:)
    !> True at the call's first point (FSAL's k7 not valid then).
    logical, intent(in) :: first
    if (.not. first) return
    call problem%rhs(t, y, self%f0)
    self%rhs_evaluations = self%rhs_evaluations + 1
  end subroutine dopri5_start

  !> One trial step of size h from (t, y) with k1 = f0 = f(t, y): ynew, and (when
  !> `with_error`) k7 = f(t + h, ynew) and the error vector yerr.
  subroutine dopri5_attempt(self, problem, t, y, h, with_error)
    !> The integrator; ynew, the stages (and k7, yerr) written.
    class(dopri5_type), intent(inout) :: self
    !> The problem y' = f(t, y).
    class(ode_problem), intent(in) :: problem
    !> Time t [s] and state y at the trial's start, and the trial step h [s].
    real(wp), intent(in) :: t, y(:), h
    !> True to form k7 and the error vector yerr too.
    logical, intent(in) :: with_error
    self%ytmp = y + h*a21*self%f0
    call problem%rhs(t + c2*h, self%ytmp, self%k2)
    self%ytmp = y + h*(a31*self%f0 + a32*self%k2)
    call problem%rhs(t + c3*h, self%ytmp, self%k3)
    self%ytmp = y + h*(a41*self%f0 + a42*self%k2 + a43*self%k3)
    call problem%rhs(t + c4*h, self%ytmp, self%k4)
    self%ytmp = y + h*(a51*self%f0 + a52*self%k2 + a53*self%k3 + a54*self%k4)
    call problem%rhs(t + c5*h, self%ytmp, self%k5)
    self%ytmp = y + h*(a61*self%f0 + a62*self%k2 + a63*self%k3 + a64*self%k4 + a65*self%k5)
    call problem%rhs(t + h, self%ytmp, self%k6)
    self%ynew = y + h*(b1*self%f0 + b3*self%k3 + b4*self%k4 + b5*self%k5 + b6*self%k6)
    self%rhs_evaluations = self%rhs_evaluations + 5
    if (.not. with_error) return
    call problem%rhs(t + h, self%ynew, self%k7)
    self%rhs_evaluations = self%rhs_evaluations + 1
    self%yerr = h*(e1*self%f0 + e3*self%k3 + e4*self%k4 + e5*self%k5 + e6*self%k6 + &
                   e7*self%k7)
  end subroutine dopri5_attempt

  !> PI step control (Gustafsson's, HNW II, sec. IV.2, as in HNW's DOPRI5): on acceptance
  !> err^(1/5 - 0.75 beta) / err_old^beta; a rejection uses err alone and only shrinks.
  pure function pi_controller(self, h, err, accepted) result(h_new)
    !> The integrator (its controller factors and err_old).
    class(dopri5_type), intent(in) :: self
    !> Trial step h [s] and its error norm err.
    real(wp), intent(in) :: h, err
    !> True when the trial was accepted.
    logical, intent(in) :: accepted
    real(wp) :: h_new, fac
    fac = err**(0.2_wp - 0.75_wp*self%beta)
    if (accepted) then
      fac = fac/self%err_old**self%beta
      fac = max(1.0_wp/self%fac_max, min(1.0_wp/self%fac_min, fac/self%safety))
      h_new = h/fac
    else
      h_new = h/min(1.0_wp/self%fac_min, fac/self%safety)
    end if
  end function pi_controller

  !> The PI controller's memory, and FSAL: the accepted step's k7 = f(t + h, ynew) is the
  !> next step's k1.
  subroutine dopri5_accepted(self, err)
    !> The integrator; err_old and f0 updated.
    class(dopri5_type), intent(inout) :: self
    !> Error norm of the accepted step.
    real(wp), intent(in) :: err
    self%err_old = max(err, 1.0e-4_wp)
    self%f0 = self%k7
  end subroutine dopri5_accepted

end module davit_solve_dopri5
