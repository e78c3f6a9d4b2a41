!> Dormand-Prince 5(4) embedded Runge-Kutta pair (Dormand & Prince 1980; coefficients and
!> PI step control as in Hairer, Norsett & Wanner, Solving ODEs I, sec. II.4-5 and their
!> DOPRI5 code). The fifth-order solution is propagated (local extrapolation), the
!> difference to the fourth-order one estimates the error.
!>
!> Contract: step(problem, t, y, dt) advances exactly from t to t + dt (the driver's macro
!> step, after which after_step may change the problem, e.g. a contact phase), using as
!> many adaptive internal steps as the error control needs. FSAL is used only inside one
!> macro step: after_step may change the RHS, so the first stage is recomputed on entry.
!> The proposed internal step size persists between calls.
module davit_solve_dopri5
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_solve_step_control, only: error_norm, initial_step, stretch_to, &
                                      is_finite_real, substep_allowed
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

  type, extends(integrator_type) :: dopri5_type
    !> Mixed error tolerance: |e_i| <= atol + rtol |y_i| in the RMS sense.
    real(wp) :: rtol = 1.0e-6_wp
    real(wp) :: atol = 1.0e-9_wp
    !> Relative step floor: h < h_min max(1, |t|) is a step-size collapse (failure).
    real(wp) :: h_min = 1.0e-12_wp
    !> Most internal steps (accepted or rejected) in one macro step before failing.
    integer :: max_substeps = 100000
    !> No error control: exactly one internal step of size dt per call (order studies).
    logical :: fixed_step = .false.
    !> Controller: safety factor, shrink/growth limits of h_new/h, PI exponent beta.
    real(wp) :: safety = 0.9_wp
    real(wp) :: fac_min = 0.2_wp
    real(wp) :: fac_max = 10.0_wp
    real(wp) :: beta = 0.04_wp
    !> Proposed internal step (0: choose by the starting heuristic on the next call).
    real(wp) :: h = 0.0_wp
    real(wp) :: err_old = 1.0e-4_wp
    real(wp), allocatable :: k1(:), k2(:), k3(:), k4(:), k5(:), k6(:), k7(:)
    real(wp), allocatable :: ytmp(:), ynew(:), yerr(:)
  contains
    procedure :: init => dopri5_init
    procedure :: step => dopri5_step
    procedure :: name => dopri5_name
    procedure, private :: attempt
  end type dopri5_type

contains

  subroutine dopri5_init(self, n)
    class(dopri5_type), intent(inout) :: self
    integer, intent(in) :: n
    if (allocated(self%k1)) then
      deallocate (self%k1, self%k2, self%k3, self%k4, self%k5, self%k6, self%k7)
      deallocate (self%ytmp, self%ynew, self%yerr)
    end if
    allocate (self%k1(n), self%k2(n), self%k3(n), self%k4(n), self%k5(n), self%k6(n), &
              self%k7(n), self%ytmp(n), self%ynew(n), self%yerr(n))
    self%steps = 0
    self%rhs_evaluations = 0
    self%failed = .false.
    if (allocated(self%failure)) deallocate (self%failure)
    self%h = 0.0_wp
    self%err_old = 1.0e-4_wp
  end subroutine dopri5_init

  !> One trial step of size h from (t, y) with k1 = f(t, y) given: ynew, and (when
  !> `with_error`) k7 = f(t + h, ynew) and the error vector yerr.
  subroutine attempt(self, problem, t, y, h, with_error)
    class(dopri5_type), intent(inout) :: self
    class(ode_problem), intent(in) :: problem
    real(wp), intent(in) :: t, y(:), h
    logical, intent(in) :: with_error
    self%ytmp = y + h*a21*self%k1
    call problem%rhs(t + c2*h, self%ytmp, self%k2)
    self%ytmp = y + h*(a31*self%k1 + a32*self%k2)
    call problem%rhs(t + c3*h, self%ytmp, self%k3)
    self%ytmp = y + h*(a41*self%k1 + a42*self%k2 + a43*self%k3)
    call problem%rhs(t + c4*h, self%ytmp, self%k4)
    self%ytmp = y + h*(a51*self%k1 + a52*self%k2 + a53*self%k3 + a54*self%k4)
    call problem%rhs(t + c5*h, self%ytmp, self%k5)
    self%ytmp = y + h*(a61*self%k1 + a62*self%k2 + a63*self%k3 + a64*self%k4 + a65*self%k5)
    call problem%rhs(t + h, self%ytmp, self%k6)
    self%ynew = y + h*(b1*self%k1 + b3*self%k3 + b4*self%k4 + b5*self%k5 + b6*self%k6)
    self%rhs_evaluations = self%rhs_evaluations + 5
    if (.not. with_error) return
    call problem%rhs(t + h, self%ynew, self%k7)
    self%rhs_evaluations = self%rhs_evaluations + 1
    self%yerr = h*(e1*self%k1 + e3*self%k3 + e4*self%k4 + e5*self%k5 + e6*self%k6 + &
                   e7*self%k7)
  end subroutine attempt

  subroutine dopri5_step(self, problem, t, y, dt)
    class(dopri5_type), intent(inout) :: self
    class(ode_problem), intent(in) :: problem
    real(wp), intent(inout) :: t
    real(wp), intent(inout) :: y(:)
    real(wp), intent(in) :: dt
    real(wp) :: t_end, tc, h, err, fac, h_new
    integer :: tries
    logical :: last, rejected

    if (self%failed) return
    t_end = t + dt
    call problem%rhs(t, y, self%k1)
    self%rhs_evaluations = self%rhs_evaluations + 1
    if (self%fixed_step) then
      call self%attempt(problem, t, y, dt, .false.)
      y = self%ynew
      t = t_end
      self%steps = self%steps + 1
      return
    end if
    if (self%h <= 0.0_wp) then
      self%h = initial_step(problem, t, y, self%k1, 5, self%atol, self%rtol, abs(dt), &
                            self%ytmp, self%k2)
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
      call self%attempt(problem, tc, y, h, .true.)
      err = error_norm(self%yerr, y, self%ynew, self%atol, self%rtol)
      if (.not. is_finite_real(err)) then
        ! A non-finite trial (overflow in a stage) is a rejection with the strongest
        ! shrink; a persistent one ends in the h_min failure above.
        self%h = h*self%fac_min
        rejected = .true.
        cycle
      end if
      fac = err**(0.2_wp - 0.75_wp*self%beta)
      if (err <= 1.0_wp) then
        ! PI controller (HNW I, eq. 4.13' of sec. IV.2 as in DOPRI5).
        fac = fac/self%err_old**self%beta
        fac = max(1.0_wp/self%fac_max, min(1.0_wp/self%fac_min, fac/self%safety))
        h_new = h/fac
        if (rejected) h_new = min(h_new, h)
        self%err_old = max(err, 1.0e-4_wp)
        y = self%ynew
        self%k1 = self%k7
        self%steps = self%steps + 1
        rejected = .false.
        if (last) then
          ! A clipped final step says little about growth; only let it shrink h.
          self%h = min(self%h, h_new)
          exit
        end if
        tc = tc + h
        self%h = h_new
        if (self%single_step) then
          t = tc
          return
        end if
      else
        self%h = h/min(1.0_wp/self%fac_min, fac/self%safety)
        rejected = .true.
      end if
    end do
    t = merge(t_end, tc, .not. self%failed)
  end subroutine dopri5_step

  pure function dopri5_name(self) result(name)
    class(dopri5_type), intent(in) :: self
    character(len=:), allocatable :: name
    name = "dopri5"
  end function dopri5_name

end module davit_solve_dopri5
