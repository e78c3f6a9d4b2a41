!> Steady, uniform wind (review G29: no profile, no shielding). Its speed is the force wind
!> of the paper's sea levels (8 and 10 m/s), not the spectrum's U = 6.28 sqrt(H).
module davit_sea_wind
  use davit_kinds, only: wp
  implicit none
  private
  public :: wind_type, new_wind, wind_velocity

  type :: wind_type
    !> Speed [m/s] and the direction the wind blows towards, from N1 to N2 [rad].
    real(wp) :: speed = 0.0_wp
    !> Direction the wind blows towards, from N1 to N2 [rad].
    real(wp) :: direction = 0.0_wp
  end type wind_type

contains

  pure function new_wind(speed, direction) result(wind)
    !> Wind speed [m/s] and the direction it blows towards, from N1 to N2 [rad].
    real(wp), intent(in) :: speed, direction
    type(wind_type) :: wind
    wind%speed = speed
    wind%direction = direction
  end function new_wind

  !> Wind velocity in the inertial frame [m/s] (horizontal).
  pure function wind_velocity(wind) result(v)
    !> The wind.
    type(wind_type), intent(in) :: wind
    real(wp) :: v(3)
    v = wind%speed*[cos(wind%direction), sin(wind%direction), 0.0_wp]
  end function wind_velocity

end module davit_sea_wind
