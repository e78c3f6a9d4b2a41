!> Speed-controlled winch drum (paper §III.B: "only needs to control the speed of the drum";
!> review §1.10, G8). The drum is not a dynamic DOF: its pay-out speed is prescribed, ramped
!> up linearly from winch_start over ramp_time and down to rest over brake_time from
!> stop_time; the passage s_drum = int v dt is carried as a state by the rigging.
module davit_rigging_winch
  use davit_kinds, only: wp
  implicit none
  private
  public :: winch_type, winch_speed, winch_passage, winch_command

  type :: winch_type
    !> Full rope pay-out speed at the drum [m/s] (positive = lowering).
    real(wp) :: speed = 0.0_wp
    !> Start, ramp length, brake start and brake length [s].
    real(wp) :: t_start = 0.0_wp, t_ramp = 1.0_wp, t_stop = huge(1.0_wp), t_brake = 0.5_wp
    !> An operator's set-point (the library's winch lever and brake, davit_capi_session):
    !> after t_cmd the speed goes linearly from v_from to v_to over t_cmd_ramp [s] and the
    !> deck's ramp and stop no longer apply. No command: t_cmd = huge, the deck's profile.
    real(wp) :: t_cmd = huge(1.0_wp), v_from = 0.0_wp, v_to = 0.0_wp, t_cmd_ramp = 0.0_wp
  end type winch_type

contains

  !> Pay-out speed v(t) = speed * ramp(t) * brake(t) [m/s].
  pure function winch_speed(w, t) result(v)
    !> The winch.
    type(winch_type), intent(in) :: w
    !> Time [s].
    real(wp), intent(in) :: t
    real(wp) :: v, ramp, brake
    if (t > w%t_cmd) then
      ramp = 1.0_wp
      if (w%t_cmd_ramp > 0.0_wp) ramp = min(1.0_wp, (t - w%t_cmd)/w%t_cmd_ramp)
      v = w%v_from + (w%v_to - w%v_from)*ramp
      return
    end if
    if (t <= w%t_start) then
      v = 0.0_wp
      return
    end if
    ramp = 1.0_wp
    if (w%t_ramp > 0.0_wp) ramp = min(1.0_wp, (t - w%t_start)/w%t_ramp)
    brake = 1.0_wp
    if (t >= w%t_stop) then
      brake = 0.0_wp
      if (w%t_brake > 0.0_wp) brake = max(0.0_wp, 1.0_wp - (t - w%t_stop)/w%t_brake)
    end if
    v = w%speed*ramp*brake
  end function winch_speed

  !> Command the drum's speed to `v_to` [m/s], reached linearly over `ramp` [s] from the
  !> speed it has at t (so the speed stays continuous); stepping continues from t on.
  pure subroutine winch_command(w, t, v_to, ramp)
    !> The winch, its command set.
    type(winch_type), intent(inout) :: w
    !> Time of the command [s], target speed [m/s], time to reach it [s].
    real(wp), intent(in) :: t, v_to, ramp
    w%v_from = winch_speed(w, t)
    w%t_cmd = t
    w%v_to = v_to
    w%t_cmd_ramp = ramp
  end subroutine winch_command

  !> Paid-out length int_0^t v dt [m], closed form. Exact when the brake starts after the
  !> ramp has finished (t_stop >= t_start + t_ramp), which is the case it is used for.
  pure function winch_passage(w, t) result(s)
    !> The winch.
    type(winch_type), intent(in) :: w
    !> Time [s].
    real(wp), intent(in) :: t
    real(wp) :: s, tau, dt
    s = 0.0_wp
    if (t <= w%t_start) return
    tau = min(t, w%t_stop) - w%t_start
    if (tau <= w%t_ramp) then
      s = w%speed*tau**2/(2.0_wp*max(w%t_ramp, tiny(1.0_wp)))
    else
      s = w%speed*(tau - 0.5_wp*w%t_ramp)
    end if
    if (t > w%t_stop .and. w%t_brake > 0.0_wp) then
      dt = min(t - w%t_stop, w%t_brake)
      s = s + w%speed*(dt - dt**2/(2.0_wp*w%t_brake))
    end if
  end function winch_passage

end module davit_rigging_winch
