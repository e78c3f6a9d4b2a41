!> Pieces shared by the adaptive integrators: the mixed absolute/relative RMS error norm of
!> Hairer, Norsett & Wanner (Solving ODEs I, sec. II.4, eq. 4.11), the starting-step
!> heuristic of the same section, and the failure record on the integrator's base type.
module davit_solve_step_control
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem, integrator_type
  implicit none
  private
  public :: error_norm, initial_step, record_failure, is_finite_real, substep_allowed
  public :: stretch_to

contains

  !> sqrt(1/n sum (e_i / (atol + rtol max(|y0_i|, |y1_i|)))^2); a step is accepted when
  !> this is <= 1. Non-finite components give a non-finite norm (a rejection).
  pure function error_norm(e, y0, y1, atol, rtol) result(err)
    !> Error estimate e, the step's start y0 and end y1 (state vectors).
    real(wp), intent(in) :: e(:), y0(:), y1(:)
    !> Absolute and relative tolerances.
    real(wp), intent(in) :: atol, rtol
    real(wp) :: err
    integer :: i
    err = 0.0_wp
    do i = 1, size(e)
      err = err + (e(i)/(atol + rtol*max(abs(y0(i)), abs(y1(i)))))**2
    end do
    err = sqrt(err/real(max(1, size(e)), wp))
  end function error_norm

  !> The step rule of every time loop: a step h that falls short of a target (a sample
  !> time, the end of a macro step) by less than 1 % of h is stretched to land on it,
  !> rather than leave a sliver step after it.
  pure logical function stretch_to(h, remaining)
    !> Step h [s] and the time remaining to the target [s].
    real(wp), intent(in) :: h, remaining
    stretch_to = 1.01_wp*h >= remaining
  end function stretch_to

  pure logical function is_finite_real(x)
    !> Value checked.
    real(wp), intent(in) :: x
    is_finite_real = ieee_is_finite(x)
  end function is_finite_real

  !> Starting step for a method of order `order` (HNW I, sec. II.4): an explicit Euler
  !> probe of size h0 estimates the second derivative; one extra RHS evaluation, f1 is work.
  function initial_step(problem, t, y, f0, order, atol, rtol, h_cap, ywork, f1) result(h)
    !> The problem.
    class(ode_problem), intent(in) :: problem
    !> Time t [s], state y and its derivative f0 = f(t, y).
    real(wp), intent(in) :: t, y(:), f0(:)
    !> Order of the method.
    integer, intent(in) :: order
    !> Absolute and relative tolerances, and the largest step allowed h_cap [s].
    real(wp), intent(in) :: atol, rtol, h_cap
    !> Work arrays of the state's size (overwritten).
    real(wp), intent(inout) :: ywork(:), f1(:)
    real(wp) :: h, d0, d1, d2, h0, h1
    d0 = error_norm(y, y, y, atol, rtol)
    d1 = error_norm(f0, y, y, atol, rtol)
    if (d0 < 1.0e-5_wp .or. d1 < 1.0e-5_wp) then
      h0 = 1.0e-6_wp
    else
      h0 = 0.01_wp*d0/d1
    end if
    h0 = min(h0, h_cap)
    ywork = y + h0*f0
    call problem%rhs(t + h0, ywork, f1)
    ywork = f1 - f0
    d2 = error_norm(ywork, y, y, atol, rtol)/h0
    if (max(d1, d2) <= 1.0e-15_wp) then
      h1 = max(1.0e-6_wp, h0*1.0e-3_wp)
    else
      h1 = (0.01_wp/max(d1, d2))**(1.0_wp/real(order + 1, wp))
    end if
    h = min(100.0_wp*h0, h1, h_cap)
    if (.not. ieee_is_finite(h) .or. h <= 0.0_wp) h = h0
  end function initial_step

  !> Mark the integrator failed with a message naming the method, time, step and reason.
  subroutine record_failure(self, t, h, reason)
    !> The integrator, marked failed.
    class(integrator_type), intent(inout) :: self
    !> Time t [s] and step h [s] where it failed.
    real(wp), intent(in) :: t, h
    !> Why it failed.
    character(len=*), intent(in) :: reason
    character(len=64) :: buf
    self%failed = .true.
    write (buf, "(a,es23.15,a,es10.3)") " at t = ", t, " s, h = ", h
    self%failure = self%name()//": "//reason//trim(buf)//" s; y kept at the last "// &
                   "accepted state"
  end subroutine record_failure

  !> The guard of every adaptive substep: false, with the failure recorded, after more
  !> than max_substeps tries in one macro step or when h has collapsed below
  !> h_min max(1, |t|).
  logical function substep_allowed(self, tries, max_substeps, t, h, h_min) result(ok)
    !> The integrator, marked failed when the step is not allowed.
    class(integrator_type), intent(inout) :: self
    !> Tries so far in this macro step and the most allowed.
    integer, intent(in) :: tries, max_substeps
    !> Time t [s], step h [s], and the relative smallest step h_min.
    real(wp), intent(in) :: t, h, h_min
    ok = .false.
    if (tries > max_substeps) then
      call record_failure(self, t, h, "more than max_substeps internal steps in one "// &
                          "macro step")
    else if (h < h_min*max(1.0_wp, abs(t))) then
      call record_failure(self, t, h, "step size collapsed below h_min")
    else
      ok = .true.
    end if
  end function substep_allowed

end module davit_solve_step_control
