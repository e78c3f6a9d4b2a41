!> `davit modes`: the fastest rates of a deck's system at its initial state, for the
!> stability map (analytic RK4 limit 2.83/omega_max against the largest step that runs).
module davit_run_linear_modes
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_solve_integrator, only: ode_problem
  use davit_solve_modes, only: jacobian_spectrum
  use davit_run_scene, only: scene_type, new_scene
  implicit none
  private
  public :: linear_modes

contains

  !> Largest eigenvalue modulus [1/s] and largest imaginary part [rad/s] of df/dy at t = 0.
  subroutine linear_modes(cfg, rate_max, omega_max, error)
    !> The deck's configuration (its system at t = 0).
    type(config_type), intent(in) :: cfg
    !> Largest eigenvalue modulus [1/s] and largest imaginary part [rad/s].
    real(wp), intent(out) :: rate_max, omega_max
    !> Set when the system cannot be built or the eigenvalues not found.
    type(error_type), allocatable, intent(out) :: error
    class(scene_type), allocatable :: scene
    class(ode_problem), allocatable :: problem
    real(wp), allocatable :: y(:)
    integer :: info
    rate_max = 0.0_wp
    omega_max = 0.0_wp
    call new_scene(cfg%simulation%scene, scene, error)
    if (allocated(error)) return
    call scene%start_problem(cfg, problem, y, error)
    if (allocated(error)) return
    call jacobian_spectrum(problem, 0.0_wp, y, rate_max, omega_max, info)
    if (info /= 0) call fatal_error(error, "LAPACK dgeev failed on the Jacobian")
  end subroutine linear_modes

end module davit_run_linear_modes
