!> `davit modes`: the fastest rates of a deck's system at its initial state, for the
!> stability map (analytic RK4 limit 2.83/omega_max against the largest step that runs).
module davit_run_linear_modes
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_solve_modes, only: jacobian_spectrum
  use davit_system_model, only: system_type
  use davit_system_build, only: new_system, initial_state
  use davit_run_ship_scene, only: build_ship_scene
  use davit_ship_ship_model, only: ship_system_type
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
    type(system_type) :: sys
    type(ship_system_type) :: ship
    real(wp), allocatable :: y(:)
    integer :: info
    rate_max = 0.0_wp
    omega_max = 0.0_wp
    select case (cfg%simulation%scene)
    case ("sea")
      call fatal_error(error, cfg%filename//": &simulation: scene = 'sea' has no dynamics "// &
                       "to linearise")
      return
    case ("ship")
      call build_ship_scene(cfg, ship, y, error)
      if (allocated(error)) return
      call jacobian_spectrum(ship, 0.0_wp, y, rate_max, omega_max, info)
    case default
      call new_system(sys, cfg, error)
      if (allocated(error)) return
      call initial_state(sys, cfg, y, error)
      if (allocated(error)) return
      call jacobian_spectrum(sys, 0.0_wp, y, rate_max, omega_max, info)
    end select
    if (info /= 0) call fatal_error(error, "LAPACK dgeev failed on the Jacobian")
  end subroutine linear_modes

end module davit_run_linear_modes
