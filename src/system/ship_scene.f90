!> Build the ship alone in its sea and wind (the 'ship' scene, free decay and RAO runs).
module davit_system_ship_scene
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_sea_builder, only: build_wave_field, build_wind
  use davit_ship_hull, only: hull_type, new_hull
  use davit_ship_ship_model, only: ship_system_type, new_ship_system, ship_nstate
  implicit none
  private
  public :: build_ship_scene, ship_initial_state

contains

  subroutine build_ship_scene(cfg, ship, y, error)
    type(config_type), intent(in) :: cfg
    type(ship_system_type), intent(out) :: ship
    real(wp), allocatable, intent(out) :: y(:)
    type(error_type), allocatable, intent(out) :: error
    type(hull_type) :: hull
    type(wave_field_type) :: sea
    call new_hull(hull, cfg%ship, error)
    if (allocated(error)) return
    call build_wave_field(cfg%sea, cfg%simulation%seed, 0, sea)
    call new_ship_system(ship, hull, sea, build_wind(cfg%wind), cfg%ship%frozen, &
                         cfg%ship%position, cfg%ship%heading, &
                         cfg%ship%wave_phase == "initial", cfg%ship%headway)
    ship%wave_dt = cfg%simulation%wave_update
    y = ship_initial_state(cfg)
  end subroutine build_ship_scene

  !> At rest in its equilibrium attitude: list, trim, heading; CG at the deck's position.
  pure function ship_initial_state(cfg) result(y)
    type(config_type), intent(in) :: cfg
    real(wp) :: y(ship_nstate)
    y = 0.0_wp
    y(1:3) = [cfg%ship%list, cfg%ship%trim, cfg%ship%heading]
    y(4:6) = cfg%ship%position
    y(10) = cfg%ship%headway
  end function ship_initial_state

end module davit_system_ship_scene
