!> Tests build launch systems from decks they trust: new_system and initial_state in one
!> call, stopping the test program on an error (a broken fixture, not a failed check).
module system_fixture
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_system_model, only: system_type
  use davit_system_build, only: new_system, initial_state
  implicit none
  private
  public :: new_test_system, nstate, deck_config

  !> State length of a boat on foundation slings (the boat's part alone, eqs. 3-4).
  integer, parameter :: nstate = 12

contains

  function new_test_system(sys, cfg) result(y)
    type(system_type), intent(out) :: sys
    type(config_type), intent(in) :: cfg
    real(wp), allocatable :: y(:)
    type(error_type), allocatable :: error
    call new_system(sys, cfg, error)
    if (.not. allocated(error)) call initial_state(sys, cfg, y, error)
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

end module system_fixture
