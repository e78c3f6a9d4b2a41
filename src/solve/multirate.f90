!> Multirate infinitesimal step (MIS) integration of y' = f_slow(t, y) + f_fast(t, y)
!> (Wensch, Knoth & Galant, BIT Numer. Math. 49, 2009; the split-explicit scheme of
!> Wicker & Skamarock, Mon. Wea. Rev. 130, 2002). A macro step H from y_n takes s stages;
!> stage i integrates the fast ODE
!>     v' = f_fast(t_n + tau, v) + f_slow(t_n + c_(i-1) H, Y_(i-1)),   v(0) = y_n,
!> over tau in [0, c_i H] with the slow tendency of the previous stage held constant
!> (Y_0 = y_n, c_0 = 0), by RK4 in round(c_i m) substeps (m: the substeps of a whole
!> macro step); Y_s is y_(n+1). The slow part is evaluated s times per macro step, the
!> fast part 4 (c_1 + ... + c_s) m times.
!>
!> Why this scheme: it needs nothing of the problem but the split of its right-hand side
!> (no second-order structure, which the water's velocity-dependent loads and the BEM
!> water states lack), the slow tendency enters every substep smoothly (the davit's ship
!> states move continuously under it, so the stiff falls see no jump as they would under
!> impulse splitting), and with f_slow = 0 it is RK4 at the substep, with f_fast = 0 the
!> outer Runge-Kutta method at H. Order: with the Wicker-Skamarock tableau (c = 1/3, 1/2, 1)
!> and with the midpoint tableau (c = 1/2, 1) both the outer method's order-2 conditions
!> and MIS's coupling condition hold, so the scheme is of order 2 in H (Wensch et al.
!> 2009; for a linear split y' = (A + B) y the Taylor expansion of the step
!> matches e^((A+B)H) to H^2), plus the inner RK4's O(h^4) in the substep h.
!>
!> 'mri2' chains the stages instead (MRI-GARK-ERK22a, Sandu, SIAM J. Numer. Anal. 57,
!> 2019, with c = 0, 1/2, 1): stage i starts from Y_i, not y_n, and integrates
!>     v' = f_fast(t_n + c_i H + tau, v) + (1/dc_i) sum_j gamma_ij f_slow(Y_j)
!> over tau in [0, dc_i H] (dc_i = c_(i+1) - c_i; gamma = [[1/2, 0], [-1/2, 1]]), so the
!> fast part sweeps the macro step once: 4 m fast evaluations per step where MIS needs
!> 4 (c_1 + ... + c_s) m (7.3 m for 'multirate'). The second half's forcing
!> 2 f_slow(Y_2) - f_slow(Y_1) makes the slow part's integral over the step H f_slow(Y_2),
!> the explicit midpoint rule's; order 2 (Sandu 2019, Table 2; measured in the tests).
!> Each half step takes nint(substeps/2) substeps, so an odd `substeps` runs one more
!> (5: 3 + 3 substeps of H/6).
!>
!> 'mri2b' is MRI-GARK-ERK22b (Sandu 2019; c = 1, 1, on Heun's trapezoidal rule): one
!> stage over the whole step, v' = f_fast(v) + f_slow(y_n), in exactly `substeps`
!> substeps, then a stage of zero length, the slow correction
!>     y_(n+1) = Y_2 + (H/2) (f_slow(Y_2) - f_slow(y_n)),
!> so that the slow integral is (H/2) (f_slow(y_n) + f_slow(Y_2)). The same two slow
!> evaluations and one fast sweep as 'mri2', but its substeps need not split into two
!> halves: at H = 0.01 s, 5 substeps are 5 of 2e-3 s (20 fast evaluations) where 'mri2'
!> takes 3 + 3 of 1.67e-3 s (24).
module davit_solve_multirate
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem, integrator_type, part_slow, part_fast
  implicit none
  private
  public :: multirate_type

  type, extends(integrator_type) :: multirate_type
    !> Stage ends c_i (fractions of the macro step), the last one 1.
    real(wp), allocatable :: c(:)
    !> Chained stages (MRI-GARK, 'mri2'): stage i starts from Y_i and is forced by the
    !> combination gamma(i, :) of the slow tendencies of Y_1 .. Y_i.
    logical :: chained = .false.
    !> Coupling coefficients gamma(i, j) of the chained stages (lower triangular).
    real(wp), allocatable :: gamma(:, :)
    !> Slow tendencies f_slow(Y_j) of the chained stages, one column per stage.
    real(wp), allocatable :: fs(:, :)
    !> RK4 substeps of the fast part over a whole macro step.
    integer :: substeps = 10
    !> Evaluations of each part (rhs_evaluations counts both).
    integer :: slow_evaluations = 0, fast_evaluations = 0
    !> Macro step's start y_n, the stage's slow forcing, the RK4 substep's stage
    !> derivatives k1..k4 and stage state, all of the state's size.
    real(wp), allocatable :: y0(:), slow(:), k1(:), k2(:), k3(:), k4(:), ytmp(:)
  contains
    procedure :: init => multirate_init
    procedure :: step => multirate_step
    procedure :: stiff_step => substep
  end type multirate_type

contains

  subroutine multirate_init(self, n)
    !> The integrator whose work arrays are allocated.
    class(multirate_type), intent(inout) :: self
    !> Size of the state vector.
    integer, intent(in) :: n
    if (allocated(self%y0)) deallocate (self%y0, self%slow, self%k1, self%k2, self%k3, &
                                         self%k4, self%ytmp)
    allocate (self%y0(n), self%slow(n), self%k1(n), self%k2(n), self%k3(n), self%k4(n), &
              self%ytmp(n))
    if (.not. allocated(self%c)) self%c = [1.0_wp/3.0_wp, 0.5_wp, 1.0_wp]
    if (allocated(self%fs)) deallocate (self%fs)
    if (self%chained) allocate (self%fs(n, size(self%c)))
    self%steps = 0
    self%rhs_evaluations = 0
    self%slow_evaluations = 0
    self%fast_evaluations = 0
    if (self%chained .and. self%c(1) == 1.0_wp) then
      self%method = "mri2b"
    else if (self%chained) then
      self%method = "mri2"
    else if (size(self%c) == 2) then
      self%method = "multirate2"
    else
      self%method = "multirate"
    end if
  end subroutine multirate_init

  !> One macro step of size dt (always the whole of it: there is no error control). Stage i
  !> evaluates the slow part at its start, Y_(i-1) at t + c_(i-1) dt, then integrates the
  !> fast part with that forcing: MIS restarts each stage from y_n over c_i dt; the chained
  !> MRI-GARK stages continue from Y_(i-1) over dc_i dt, their forcing the gamma
  !> combination of the slow evaluations so far (chained_forcing).
  subroutine multirate_step(self, problem, t, y, dt)
    !> The integrator (work arrays, counters).
    class(multirate_type), intent(inout) :: self
    !> The problem, split into f_slow and f_fast.
    class(ode_problem), intent(in) :: problem
    !> Time [s], advanced by dt.
    real(wp), intent(inout) :: t
    !> State vector, advanced by one macro step.
    real(wp), intent(inout) :: y(:)
    !> Macro step H [s].
    real(wp), intent(in) :: dt
    real(wp) :: c_prev, dc, t0
    integer :: i, nsub
    logical :: fast
    if (.not. self%chained) self%y0 = y
    c_prev = 0.0_wp
    do i = 1, size(self%c)
      if (self%chained) then
        call problem%rhs_part(t + c_prev*dt, y, self%fs(:, i), part_slow)
        dc = self%c(i) - c_prev
        t0 = t + c_prev*dt
        call chained_forcing(self, i, dc, dt, y, fast)
        if (.not. fast) cycle
      else
        ! y holds Y_(i-1): its slow tendency drives stage i, which restarts from y_n
        call problem%rhs_part(t + c_prev*dt, y, self%slow, part_slow)
        y = self%y0
        dc = self%c(i)
        t0 = t
      end if
      nsub = max(1, nint(dc*real(self%substeps, wp)))
      call fast_stage(self, problem, t0, y, dc*dt, nsub)
      c_prev = self%c(i)
    end do
    call finish_step(self, t, dt)
  end subroutine multirate_step

  !> The forcing of chained stage i of length dc (of dt), (1/dc) sum_j gamma_ij f_slow(Y_j),
  !> in self%slow; for a stage of zero length (ERK22b's last) the slow part's correction
  !> sum_j gamma_ij dt f_slow(Y_j) is added to y instead, and there is no fast stage.
  subroutine chained_forcing(self, i, dc, dt, y, fast)
    !> The integrator (chained, with its gamma and fs; slow written).
    type(multirate_type), intent(inout) :: self
    !> The stage.
    integer, intent(in) :: i
    !> The stage's length as a fraction of the macro step, and the macro step H [s].
    real(wp), intent(in) :: dc, dt
    !> State vector: Y_(i-1), advanced by the correction of a zero-length stage.
    real(wp), intent(inout) :: y(:)
    !> Whether the stage has a fast part (dc > 0).
    logical, intent(out) :: fast
    integer :: j
    fast = dc /= 0.0_wp
    if (.not. fast) then
      do j = 1, i
        if (self%gamma(i, j) /= 0.0_wp) y = y + (self%gamma(i, j)*dt)*self%fs(:, j)
      end do
      self%slow_evaluations = self%slow_evaluations + 1
      return
    end if
    self%slow = 0.0_wp
    do j = 1, i
      if (self%gamma(i, j) /= 0.0_wp) then
        self%slow = self%slow + (self%gamma(i, j)/dc)*self%fs(:, j)
      end if
    end do
  end subroutine chained_forcing

  !> The end of a macro step: the clock and the counters (slow plus fast evaluations).
  subroutine finish_step(self, t, dt)
    !> The integrator, its counters updated.
    type(multirate_type), intent(inout) :: self
    !> Time [s], advanced by dt.
    real(wp), intent(inout) :: t
    !> Macro step H [s].
    real(wp), intent(in) :: dt
    t = t + dt
    self%steps = self%steps + 1
    self%rhs_evaluations = int(self%slow_evaluations + self%fast_evaluations, &
                               kind(self%rhs_evaluations))
  end subroutine finish_step

  !> v' = f_fast(t0 + tau, v) + slow over tau in [0, span], RK4 in nsub equal substeps: a
  !> stage, counted as one slow evaluation (its forcing's) and 4 nsub fast ones.
  subroutine fast_stage(self, problem, t0, v, span, nsub)
    !> The integrator (its slow forcing, stage work arrays and counters).
    type(multirate_type), intent(inout) :: self
    !> The problem, split into f_slow and f_fast.
    class(ode_problem), intent(in) :: problem
    !> Time t0 at the stage's start [s] and the span integrated over [s].
    real(wp), intent(in) :: t0, span
    !> State v, advanced over the span.
    real(wp), intent(inout) :: v(:)
    !> Number of RK4 substeps.
    integer, intent(in) :: nsub
    real(wp) :: h, half, ts
    integer :: k
    self%slow_evaluations = self%slow_evaluations + 1
    self%fast_evaluations = self%fast_evaluations + 4*nsub
    h = span/real(nsub, wp)
    half = 0.5_wp*h
    do k = 0, nsub - 1
      ts = t0 + real(k, wp)*h
      call problem%rhs_part(ts, v, self%k1, part_fast)
      self%k1 = self%k1 + self%slow
      self%ytmp = v + half*self%k1
      call problem%rhs_part(ts + half, self%ytmp, self%k2, part_fast)
      self%k2 = self%k2 + self%slow
      self%ytmp = v + half*self%k2
      call problem%rhs_part(ts + half, self%ytmp, self%k3, part_fast)
      self%k3 = self%k3 + self%slow
      self%ytmp = v + h*self%k3
      call problem%rhs_part(ts + h, self%ytmp, self%k4, part_fast)
      self%k4 = self%k4 + self%slow
      v = v + (h/6.0_wp)*(self%k1 + 2.0_wp*(self%k2 + self%k3) + self%k4)
    end do
  end subroutine fast_stage

  !> The fast part's RK4 substep of a macro step h (the stability limit applies to it).
  pure real(wp) function substep(self, h) result(hs)
    !> The multirate integrator.
    class(multirate_type), intent(in) :: self
    !> Macro step [s].
    real(wp), intent(in) :: h
    hs = h/real(self%substeps, wp)
  end function substep

end module davit_solve_multirate
