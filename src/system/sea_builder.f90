!> Build the wave field and wind of a run from the validated &sea / &wind configuration
!> (here, in the build layer, so that src/sea never depends on src/io).
module davit_system_sea_builder
  use davit_kinds, only: wp
  use davit_core_random, only: rng_type, new_rng
  use davit_io_config, only: sea_config, wind_config
  use davit_sea_wave_field, only: wave_field_type, new_calm_sea, new_regular_wave, &
                                  new_irregular_sea, new_single_sum_sea, wave_airy, &
                                  wave_stokes2, single_random, single_equal_energy
  use davit_sea_wind, only: wind_type, new_wind
  implicit none
  private
  public :: build_wave_field, build_wind

contains

  !> The wave field of the &sea group (calm, regular or irregular); the random phases (and
  !> frequency jitter) come from `seed` and `stream` only.
  subroutine build_wave_field(sea, seed, stream, field)
    !> The &sea group as read from the deck.
    type(sea_config), intent(in) :: sea
    !> Seed of the random generator (&simulation seed) and its stream index (0: the
    !> seed's own; davit_core_random).
    integer, intent(in) :: seed, stream
    !> The wave field built.
    type(wave_field_type), intent(out) :: field
    type(rng_type) :: rng
    select case (sea%wave_type)
    case ("airy")
      call new_regular_wave(field, wave_airy, sea%height, sea%period, sea%direction, &
                            sea%phase, sea%ramp_time)
    case ("stokes2")
      call new_regular_wave(field, wave_stokes2, sea%height, sea%period, sea%direction, &
                            sea%phase, sea%ramp_time)
    case ("irregular")
      rng = new_rng(seed, stream)
      if (sea%summation /= "double") then
        call new_single_sum_sea(field, sea%height, sea%direction, sea%spreading_s, &
                                sea%spread_window, sea%n_frequencies, sea%n_directions, &
                                sea%omega_min, sea%omega_max, sea%jitter, &
                                merge(single_random, single_equal_energy, &
                                      sea%summation == "single_random"), rng, sea%ramp_time)
        return
      end if
      call new_irregular_sea(field, sea%height, sea%direction, sea%spreading_s, &
                             sea%spread_window, sea%n_frequencies, sea%n_directions, &
                             sea%omega_min, sea%omega_max, sea%jitter, &
                             sea%independent_frequencies, rng, sea%ramp_time)
    case default
      call new_calm_sea(field)
    end select
  end subroutine build_wave_field

  !> The mean wind of the &wind group.
  pure function build_wind(wind) result(w)
    !> The &wind group as read from the deck (speed [m/s], direction it blows towards
    !> [rad], converted from direction_deg).
    type(wind_config), intent(in) :: wind
    type(wind_type) :: w
    w = new_wind(wind%speed, wind%direction)
  end function build_wind

end module davit_system_sea_builder
