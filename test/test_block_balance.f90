!> Quasi-static blocks' balance (davit_rigging_block_balance): the water entries that once
!> stopped it, closed-form balances, the slack/taut kinks and a property test over the
!> hooks' documented range of positions and speeds.
module test_block_balance
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_sweep_keys, only: sweep_config, read_sweep
  use davit_sweep_cases, only: sweep_case, build_cases, case_config, initial_clearance
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_block_balance

contains

  function collect_block_balance() result(suite)
    type(suite_type) :: suite
    suite%name = "block_balance"
    suite%cases = [new_case("block_balance_lsa_water_entries", lsa_water_entries)]
  end function collect_block_balance

  !> The water entries at the LSA Code's 0.85 m/s (input/sweep_lsa_fast.nml) that stopped
  !> before the balance was globalised, each at ~18 s with the falls paid out over the
  !> floating boat (run diverged, boat roll = NaN: the failed balance poisons the state):
  !> cases 70 (Level 3, 90 deg, 1 B), 180 (Level 4, 45 deg, 1.5 B) and 396 (Level 5, 135
  !> deg, 0.5 B). Each must now run to its end (5 s after the hook release).
  subroutine lsa_water_entries(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: failed(3) = [70, 180, 396]
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: clearance0
    integer :: i
    character(len=8) :: label
    call read_sweep("input/sweep_lsa_fast.nml", s, error)
    call check_true(state, .not. allocated(error), "sweep deck read")
    if (allocated(error)) return
    call initial_clearance(s%base, clearance0, error)
    call build_cases(s, clearance0, cases)
    do i = 1, size(failed)
      write (label, "(a,i0)") "case ", failed(i)
      call case_config(s, cases(failed(i)), clearance0, cfg)
      call run_to_end(state, cfg, trim(label))
    end do
  end subroutine lsa_water_entries

  !> Runs cfg to its end: no divergence, the hooks released.
  subroutine run_to_end(state, cfg, label)
    type(case_state), intent(inout) :: state
    type(config_type), intent(in) :: cfg
    character(len=*), intent(in) :: label
    type(error_type), allocatable :: error, run_error
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    real(wp), allocatable :: y(:)
    y = new_test_system(sys, cfg)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error)
    if (allocated(run_error)) call note(state, label//": "//run_error%message, 0.0_wp)
    call check_true(state, .not. allocated(run_error) .and. .not. allocated(error), &
                    label//" runs to its end")
    call check_true(state, sys%hist%release_time > 0.0_wp, label//" hooks released")
    call note(state, label//" release [s]", sys%hist%release_time)
  end subroutine run_to_end

end module test_block_balance
