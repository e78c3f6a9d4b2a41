!> Tests build launch systems from decks they trust: new_system and initial_state in one
!> call, stopping the test program on an error (a broken fixture, not a failed check).
module system_fixture
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_system_model, only: system_type
  use davit_run_scene, only: new_boat_system
  use davit_solve_rk4, only: rk4_type
  use davit_core_rotation, only: rotation_matrix
  use davit_boat_contact, only: hertz_law_type, hertz_peak
  implicit none
  private
  public :: new_test_system, nstate, deck_config, drop_cg, system_hertz_peak

  !> State length of a boat on foundation slings (the boat's part alone, eqs. 3-4).
  integer, parameter :: nstate = 12

contains

  function new_test_system(sys, cfg) result(y)
    type(system_type), intent(out) :: sys
    type(config_type), intent(in) :: cfg
    real(wp), allocatable :: y(:)
    type(error_type), allocatable :: error
    call new_boat_system(cfg, sys, y, error)
    if (allocated(error)) error stop "test system: "//error%message
  end function new_test_system

  !> The configuration of a deck given as text (file name "test.nml" in its messages).
  function deck_config(text) result(cfg)
    character(len=*), intent(in) :: text
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    call parse_config("test.nml", text, cfg, error)
    if (allocated(error)) error stop "test deck rejected: "//error%message
  end function deck_config

  !> The boat's inertial CG after n RK4 steps of dt from t = 0, the after-step hook run at
  !> the start and after every step (as the driver does).
  function drop_cg(sys, y, n, dt) result(cg)
    type(system_type), intent(inout) :: sys
    real(wp), intent(inout) :: y(:)
    integer, intent(in) :: n
    real(wp), intent(in) :: dt
    real(wp) :: cg(3), t
    type(rk4_type) :: rk4
    integer :: i
    call rk4%init(size(y))
    t = 0.0_wp
    call sys%after_step(t, y)
    do i = 1, n
      call rk4%step(sys, t, y, dt)
      call sys%after_step(t, y)
    end do
    cg = matmul(rotation_matrix(y(1:3)), y(4:6))
  end function drop_cg

  !> Hertz impact peak (hertz_peak) of the system's fender law; a law that is not a Hertz
  !> law gives huge values, so that a check against them fails.
  subroutine system_hertz_peak(sys, mass, v0, delta_m, f_m)
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: mass, v0
    real(wp), intent(out) :: delta_m, f_m
    delta_m = huge(1.0_wp)
    f_m = huge(1.0_wp)
    select type (law => sys%par%fenders%law)
    class is (hertz_law_type)
      call hertz_peak(law, mass, v0, delta_m, f_m)
    end select
  end subroutine system_hertz_peak

end module system_fixture
