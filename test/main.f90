!> Runs every Fortran test suite; optional first argument filters cases by name.
program main
  use, intrinsic :: iso_fortran_env, only: output_unit
  use harness, only: suite_type, run_suites
  use test_rotation, only: collect_rotation
  use test_deck, only: collect_deck
  use test_hanging, only: collect_hanging
  use test_sea, only: collect_sea
  use test_ship, only: collect_ship
  use test_boat, only: collect_boat
  use test_fenders, only: collect_fenders
  use test_contact_laws, only: collect_contact_laws
  use test_strip_levels, only: collect_strip_levels
  use test_boat_water, only: collect_boat_water
  use test_rigging, only: collect_rigging
  use test_rigging_static, only: collect_rigging_static
  use test_slack, only: collect_slack
  use test_block_balance, only: collect_block_balance
  use test_integrators, only: collect_integrators
  use test_sweep, only: collect_sweep
  use test_strip_waves, only: collect_strip_waves
  use test_bem_ship, only: collect_bem_ship
  use test_ship_drift, only: collect_ship_drift
  use test_launch_log, only: collect_launch_log
  use test_boat_bem, only: collect_boat_bem
  use test_force_levels, only: collect_force_levels
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use test_strip_pressure, only: collect_strip_pressure
  use test_events, only: collect_events
  use test_assess, only: collect_assess
  use test_adaptive, only: collect_adaptive
  use test_core, only: collect_core
  use test_wave_grid, only: collect_wave_grid
  use test_multirate, only: collect_multirate
  use test_capi, only: collect_capi
  use test_mmg, only: collect_mmg
  use test_mmg_bem, only: collect_mmg_bem
  use test_ship_speed, only: collect_ship_speed
  use test_small_laws, only: collect_small_laws
  use test_scene, only: collect_scene
  use test_system_parts, only: collect_system_parts
  use test_surface_watch, only: collect_surface_watch
  implicit none
  interface
    integer(c_int) function setenv(name, value, overwrite) bind(c, name="setenv")
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: name(*), value(*)
      integer(c_int), value :: overwrite
    end function setenv
  end interface
  type(suite_type), allocatable :: suites(:)
  character(len=256) :: filter
  integer :: npass, nfail

  ! decks given as text ("test.nml") find their data files (the boat's BEM database) in
  ! the project's input/, as test/python/conftest.py does for the Python tests
  if (setenv("DAVIT_PATH"//c_null_char, "input"//c_null_char, 0_c_int) /= 0) error stop 1
  filter = ""
  if (command_argument_count() > 0) call get_command_argument(1, filter)
  suites = [collect_rotation(), collect_deck(), collect_hanging(), collect_sea(), &
            collect_ship(), collect_boat(), collect_fenders(), collect_contact_laws(), &
            collect_boat_water(), &
            collect_rigging(), collect_rigging_static(), collect_slack(), &
            collect_integrators(), collect_sweep(), &
            collect_strip_waves(), collect_surface_watch(), collect_bem_ship(), &
            collect_ship_drift(), &
            collect_launch_log(), &
            collect_boat_bem(), collect_strip_pressure(), collect_strip_levels(), &
            collect_events(), &
            collect_assess(), collect_adaptive(), collect_core(), &
            collect_wave_grid(), collect_multirate(), collect_block_balance(), &
            collect_capi(), collect_mmg(), collect_mmg_bem(), collect_small_laws(), &
            collect_scene(), collect_ship_speed(), collect_system_parts(), &
            collect_force_levels()]
  call run_suites(suites, trim(filter), npass, nfail)
  write (output_unit, "(i0,a,i0,a)") npass, " passed, ", nfail, " failed"
  if (nfail > 0 .or. npass == 0) error stop 1, quiet=.true.
end program main
