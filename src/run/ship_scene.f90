!> Build the ship alone in its sea and wind (the 'ship' scene, free decay and RAO runs).
module davit_run_ship_scene
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_system_sea_builder, only: build_wave_field, build_wind
  use davit_ship_ship_model, only: ship_system_type
  use davit_system_build, only: ship_initial_state, new_ship
  implicit none
  private
  public :: build_ship_scene

contains

  subroutine build_ship_scene(cfg, ship, y, error)
    !> The 'ship' deck's configuration.
    type(config_type), intent(in) :: cfg
    !> The ship system built.
    type(ship_system_type), intent(out) :: ship
    !> Its initial state.
    real(wp), allocatable, intent(out) :: y(:)
    !> Set when the ship cannot be built.
    type(error_type), allocatable, intent(out) :: error
    type(wave_field_type) :: sea
    call build_wave_field(cfg%sea, cfg%simulation%seed, 0, sea)
    call new_ship(ship, cfg, sea, build_wind(cfg%wind), error)
    if (allocated(error)) return
    y = ship_initial_state(ship, cfg)
  end subroutine build_ship_scene

end module davit_run_ship_scene
