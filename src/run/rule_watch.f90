!> What the rule checks (davit_assess_rules) need from a launch beyond its peaks, followed at
!> every accepted step:
!>
!> * the lowering speed after the initial acceleration (LSA Code 6.1.2.8): the hooks' mean
!>   speed down relative to the davit heads, (d(t2) - d(t1))/(t2 - t1), d the vertical
!>   distance from the heads' midpoint to the hooks' midpoint; t1 = winch start + ramp +
!>   1 s (the ramp's transient), t2 the first of: the keel 1 m above the still water, the
!>   brake, the release, the end of the run; at least 1 s long, else not applicable;
!> * an emergency stop (&rigging stop_time while lowering): the fall load before it, the
!>   mean of the largest cable-segment tension over the last second before stop_time, and
!>   the largest one from stop_time to 2 s after the drum is at rest;
!> * the hooks' load at release: the sum of the slings' tensions at the last step before the
!>   hooks let go (release is simultaneous: both hooks at once, LSA Code 4.4.7.6.1);
!> * the davit head height H above the still water at t = 0 (the deck's loading condition
!>   stands for the lightest seagoing one).
module davit_run_rule_watch
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use davit_kinds, only: wp, gravity
  use davit_core_pose, only: pose_type, pose_point
  use davit_core_rotation, only: rotation_matrix
  use davit_io_config, only: config_type
  use davit_system_parameters, only: ship_pose, hook_kinematics
  use davit_system_model, only: system_type
  implicit none
  private
  public :: rule_watch, new_rule_watch

  !> How long the ramp's transient is left to settle, the mean before a stop and the ring-out
  !> after it [s]; the keel's height above the still water that ends the lowering [m].
  real(wp), parameter :: settle_time = 1.0_wp, ring_out = 2.0_wp, water_gap = 1.0_wp

  type :: rule_watch
    !> Whether the boat hangs from a davit (the lowering checks apply).
    logical :: on_davit = .false.
    !> Heads' midpoint in the ship frame [m]; keel below the CG [m]; boat weight [N].
    real(wp) :: head_mid(3) = 0.0_wp, keel = 0.0_wp, weight = 0.0_wp
    !> The winch: end of the initial acceleration, brake start and end of its ring-out [s].
    real(wp) :: t_accel = 0.0_wp, t_stop = huge(1.0_wp), t_ring = huge(1.0_wp)
    !> Davit head height above the still water at t = 0 [m] (< 0: not seen yet).
    real(wp) :: head_height = -1.0_wp
    !> Lowering window: 0 before it, 1 open, 2 closed; its first and last (t, d).
    integer :: window = 0
    !> Start and end of the window (t [s], distance lowered d [m]).
    real(wp) :: t1 = 0.0_wp, d1 = 0.0_wp, t2 = 0.0_wp, d2 = 0.0_wp
    !> Emergency stop: integral of the fall load over the second before it [N s], the time
    !> covered [s], the largest fall load after it [N], and whether the run saw it all.
    real(wp) :: pre_load = 0.0_wp, pre_time = 0.0_wp, stop_peak = 0.0_wp
    !> Whether the stop and its ring-out were seen.
    logical :: stop_seen = .false.
    !> The hooks: their load at the last step [N], at release [N] (< 0: no release).
    real(wp) :: hook_load = 0.0_wp, release_load = -1.0_wp, t_release = -1.0_wp
    !> Time of the last step [s].
    real(wp) :: t_prev = -1.0_wp
  contains
    procedure :: watch => rules_watch
    procedure :: loads => rules_loads
    procedure :: lowering_speed => rules_lowering_speed
    procedure :: stop_loads => rules_stop_loads
  end type rule_watch

contains

  function new_rule_watch(cfg, sys) result(w)
    !> The run's configuration (&limits, the winch).
    type(config_type), intent(in) :: cfg
    !> The system of the run.
    type(system_type), intent(in) :: sys
    type(rule_watch) :: w
    w%on_davit = sys%par%on_davit
    w%head_mid = 0.5_wp*(cfg%rigging%head_fore + cfg%rigging%head_aft)
    w%keel = cfg%boat%keel
    w%weight = sys%par%boat%mass*gravity
    w%t_accel = cfg%rigging%winch_start + cfg%rigging%ramp_time + settle_time
    if (cfg%rigging%stop_time < 1.0e5_wp) then
      w%t_stop = cfg%rigging%stop_time
      w%t_ring = cfg%rigging%stop_time + cfg%rigging%brake_time + ring_out
    end if
  end function new_rule_watch

  !> The lowering window and the release, after the step ending at t.
  subroutine rules_watch(self, sys, t, y)
    !> The watch.
    class(rule_watch), intent(inout) :: self
    !> The system of the run.
    type(system_type), intent(in) :: sys
    !> End of the step [s] and the state there.
    real(wp), intent(in) :: t, y(:)
    type(pose_type) :: ship
    real(wp) :: hooks(3, 2), hook_vel(3, 2), head(3), d, cg_height, c(3, 3)
    if (.not. self%on_davit) return
    ship = ship_pose(sys%par%with_ship, sys%par%ship_part, sys%par%ship_rest, y)
    head = pose_point(ship, self%head_mid)
    if (self%head_height < 0.0_wp) self%head_height = -head(3)
    call hook_kinematics(sys%par%boat_part, sys%par%hooks, y, hooks, hook_vel)
    d = 0.5_wp*(hooks(3, 1) + hooks(3, 2)) - head(3)
    associate (q => y(sys%par%boat_part%q(1):sys%par%boat_part%q(2)))
      c = rotation_matrix(q(1:3))
      cg_height = -dot_product(c(3, :), q(4:6))
    end associate
    if (self%window == 0 .and. t >= self%t_accel) then
      self%window = 1
      self%t1 = t
      self%d1 = d
    end if
    if (self%window == 1) then
      self%t2 = t
      self%d2 = d
      if (cg_height < self%keel + water_gap .or. t >= self%t_stop .or. &
          sys%hist%release_time >= 0.0_wp) self%window = 2
    end if
    if (sys%hist%release_time >= 0.0_wp .and. self%release_load < 0.0_wp) then
      self%release_load = self%hook_load
      self%t_release = sys%hist%release_time
    end if
  end subroutine rules_watch

  !> The falls' load (largest cable-segment tension) and the hooks' load (sum of the
  !> slings') after the step ending at t, until the hooks are released.
  subroutine rules_loads(self, t, fall, hooks)
    !> The watch.
    class(rule_watch), intent(inout) :: self
    !> End of the step [s]; the falls' load and the hooks' load [N].
    real(wp), intent(in) :: t, fall, hooks
    real(wp) :: h
    h = 0.0_wp
    if (self%t_prev >= 0.0_wp) h = t - self%t_prev
    self%t_prev = t
    self%hook_load = hooks
    if (t > self%t_stop - settle_time .and. t <= self%t_stop) then
      self%pre_load = self%pre_load + h*fall
      self%pre_time = self%pre_time + h
    else if (t > self%t_stop .and. t <= self%t_ring) then
      self%stop_peak = max(self%stop_peak, fall)
      self%stop_seen = t >= self%t_ring - 1.0e-9_wp
    end if
  end subroutine rules_loads

  !> Mean lowering speed over the window [m/s] (NaN: the window was shorter than 1 s) and
  !> the davit head height H [m].
  subroutine rules_lowering_speed(self, speed, height)
    !> The watch.
    class(rule_watch), intent(in) :: self
    !> Mean lowering speed [m/s] (NaN: window under 1 s) and the davit head height H [m].
    real(wp), intent(out) :: speed, height
    speed = ieee_value(speed, ieee_quiet_nan)
    height = self%head_height
    if (self%window == 0 .or. self%t2 - self%t1 < 1.0_wp) return
    speed = (self%d2 - self%d1)/(self%t2 - self%t1)
  end subroutine rules_lowering_speed

  !> The fall load before the emergency stop and its peak after it [N]; NaN when no stop
  !> happened while lowering (before it the window must have opened, the hooks not be
  !> released) or the run ended before the ring-out.
  subroutine rules_stop_loads(self, before, peak)
    !> The watch.
    class(rule_watch), intent(in) :: self
    !> Fall load before the stop and its peak after it [N] (NaN: no stop seen).
    real(wp), intent(out) :: before, peak
    before = ieee_value(before, ieee_quiet_nan)
    peak = before
    if (.not. self%stop_seen .or. self%pre_time < 0.5_wp*settle_time) return
    if (self%t_stop < self%t_accel) return
    ! released before the ring-out ended: the stop's snatch was not followed through
    if (self%t_release >= 0.0_wp .and. self%t_release < self%t_ring) return
    before = self%pre_load/self%pre_time
    peak = self%stop_peak
  end subroutine rules_stop_loads

end module davit_run_rule_watch
