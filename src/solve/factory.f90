!> Integrator selection by name (the `&simulation integrator` key).
module davit_solve_factory
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_solve_integrator, only: integrator_type
  use davit_solve_rk4, only: rk4_type
  use davit_solve_adaptive, only: adaptive_integrator
  use davit_solve_dopri5, only: dopri5_type
  use davit_solve_rosenbrock, only: rosenbrock_type
  use davit_solve_rosenbrock_w, only: rosenbrock_w_type
  use davit_solve_multirate, only: multirate_type
  implicit none
  private
  public :: new_integrator, integrator_names

  !> The integrators `new_integrator` builds, by the name the decks give them (the
  !> `&simulation integrator` and `&sweep integrator` choices read this list).
  character(len=*), parameter :: integrator_names(8) = [character(len=10) :: "rk4", &
    "dopri5", "rosenbrock", "rosw", "multirate", "multirate2", "mri2", "mri2b"]

contains

  !> Allocate and initialise the integrator `name` ("rk4", "dopri5", "rosenbrock", "rosw") for a
  !> state of size n. rtol/atol set the adaptive methods' tolerances (defaults 1e-6, 1e-9);
  !> rk4 has no error control and ignores them. fixed_step (default .false.) makes the
  !> adaptive methods take exactly one step of the macro step dt, without error control
  !> (observed-order studies); rk4 is always fixed-step and ignores it. "multirate" (the
  !> Wicker-Skamarock tableau) and "multirate2" (the midpoint tableau) are the MIS methods of
  !> davit_solve_multirate, with `substeps` RK4 substeps of the fast part per macro step dt
  !> (default 10); "mri2" its chained MRI-GARK-ERK22a variant (one fast sweep per step),
  !> "mri2b" the chained MRI-GARK-ERK22b (one fast sweep of exactly `substeps`).
  subroutine new_integrator(name, n, integrator, error, rtol, atol, fixed_step, substeps)
    !> Integrator name: rk4, dopri5, rosenbrock, rosw, multirate, multirate2, mri2 or mri2b.
    character(len=*), intent(in) :: name
    !> Size of the state vector.
    integer, intent(in) :: n
    !> The integrator made, initialised for n states.
    class(integrator_type), allocatable, intent(out) :: integrator
    !> Allocated on bad input (an unknown name, a tolerance or substeps out of range).
    type(error_type), allocatable, intent(out) :: error
    !> Relative (> 0) and absolute (>= 0) tolerances of the adaptive methods.
    real(wp), intent(in), optional :: rtol, atol
    !> True for one step per macro step, without error control (adaptive methods).
    logical, intent(in), optional :: fixed_step
    !> RK4 substeps of the fast part per macro step (multirate methods, >= 1).
    integer, intent(in), optional :: substeps
    if (present(substeps)) then
      if (substeps < 1) then
        call fatal_error(error, "multirate substeps must be >= 1")
        return
      end if
    end if
    if (present(rtol)) then
      if (.not. rtol > 0.0_wp) then
        call fatal_error(error, "integrator rtol must be > 0")
        return
      end if
    end if
    if (present(atol)) then
      if (.not. atol >= 0.0_wp) then
        call fatal_error(error, "integrator atol must be >= 0")
        return
      end if
    end if
    select case (name)
    case ("rk4")
      allocate (rk4_type :: integrator)
    case ("dopri5")
      allocate (dopri5_type :: integrator)
    case ("rosenbrock")
      allocate (rosenbrock_type :: integrator)
    case ("rosw")
      allocate (rosenbrock_w_type :: integrator)
    case ("multirate")
      allocate (multirate_type :: integrator)
    case ("multirate2")
      allocate (integrator, source=multirate_type(c=[0.5_wp, 1.0_wp]))
    case ("mri2")
      ! MRI-GARK-ERK22a: stage ends 1/2, 1; gamma rows [1/2, 0], [-1/2, 1]
      allocate (integrator, source=chained([0.5_wp, 1.0_wp], [0.5_wp, -0.5_wp, 0.0_wp, 1.0_wp]))
    case ("mri2b")
      ! MRI-GARK-ERK22b: stage ends 1, 1 (the second of zero length); rows [1, 0], [-1/2, 1/2]
      allocate (integrator, source=chained([1.0_wp, 1.0_wp], [1.0_wp, -0.5_wp, 0.0_wp, 0.5_wp]))
    case default
      call fatal_error(error, "unknown integrator '"//name//"' (rk4, dopri5, rosenbrock, "// &
                       "rosw, multirate, multirate2, mri2, mri2b)")
      return
    end select
    call integrator%init(n)
    select type (integrator)
    class is (adaptive_integrator)
      if (present(rtol)) integrator%rtol = rtol
      if (present(atol)) integrator%atol = atol
      if (present(fixed_step)) integrator%fixed_step = fixed_step
    type is (multirate_type)
      if (present(substeps)) integrator%substeps = substeps
    end select
  end subroutine new_integrator

  !> A chained MRI-GARK integrator (davit_solve_multirate) with stage ends c and the
  !> coupling coefficients gamma (2 x 2, column-major).
  pure function chained(c, gamma) result(m)
    !> Stage ends (fractions of the macro step) and gamma's entries, column by column.
    real(wp), intent(in) :: c(2), gamma(4)
    type(multirate_type) :: m
    m%c = c
    m%chained = .true.
    m%gamma = reshape(gamma, [2, 2])
  end function chained

end module davit_solve_factory
