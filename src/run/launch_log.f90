!> What a designer reads from a launch, resolved at every accepted step: each impact as an
!> event, the peak sling and cable-segment tensions, the occupant's seat acceleration
!> (raw and filtered), the wire's and the impact's limits, and how the launch ended. It is
!> the step monitor of every run of the boat scenes and of every sweep case.
!>
!> The launch ends `after_release` after the hooks let go (review G24). One that does not get
!> waterborne is reported with its cause, judged over about the last 10 s (exponential
!> averages): still lowering, pinned against the ship's side, or riding the waves in slack
!> and snatching falls.
module davit_run_launch_log
  use davit_kinds, only: wp, gravity, pi
  use davit_core_rotation, only: rotation_matrix
  use davit_core_body, only: body_point_velocity
  use davit_io_config, only: config_type
  use davit_io_deck_reader, only: fmt_real
  use davit_io_text, only: fmt_fixed
  use davit_io_limits_keys, only: minimum_breaking_load
  use davit_io_namelist, only: int_to_str
  use davit_solve_integrator, only: ode_problem
  use davit_system_parameters, only: fender_gaps, side_plane, ship_pose, nslings
  use davit_system_model, only: system_type
  use davit_run_step_monitor, only: step_monitor
  use davit_run_impact_events, only: impact_tracker
  use davit_run_load_peaks, only: load_peaks
  use davit_run_seat_trace, only: seat_trace
  use davit_run_launch_report, only: write_impacts, write_loads, write_seat, &
                                     write_assessment, launch_text
  use davit_run_rule_watch, only: rule_watch, new_rule_watch
  use davit_assess_rules, only: n_checks, rule_check, new_check, not_applicable, &
                                check_lowering_speed, check_impact_speed, check_fall_swl, &
                                check_fall_mbl, check_sling_swl, check_sling_mbl, &
                                check_brake_load, check_release_load, check_seat_srss, &
                                check_seat_dri
  use davit_assess_occupant, only: response_peaks
  use davit_io_limits_keys, only: limits_config
  use davit_io_hdf5_writer, only: h5_writer_type
  implicit none
  private
  public :: launch_log, new_launch_log

  !> Time constant of the averages the outcome is judged on [s].
  real(wp), parameter :: judge_time = 10.0_wp

  type, extends(step_monitor) :: launch_log
    !> Time the log runs on after the release [s]; the boat's weight [N]; the seat's point in the
    !> boat frame [m].
    real(wp) :: after_release = 5.0_wp, weight = 0.0_wp, seat_point(3) = 0.0_wp
    !> The fender impacts.
    type(impact_tracker) :: impacts
    !> Peak loads and limit exceedances.
    type(load_peaks) :: loads
    !> The seat's velocity on its grid, for its filtered acceleration.
    type(seat_trace) :: seat
    !> What the rule checks need beyond the peaks, and the deck's limits.
    type(rule_watch) :: rules
    !> The deck's &limits.
    type(limits_config) :: limits
    !> Whether a fender touched at the last step.
    logical :: contact = .false.
    !> The CG: inertial velocity of the last step, its peak step-mean acceleration and when.
    real(wp) :: v_prev(3) = 0.0_wp, t_prev = -1.0_wp, peak_cg = 0.0_wp, peak_cg_time = -1.0_wp
    !> The outcome: shares of time in contact and with slack falls (averages over ~judge_time),
    !> snatches (slack to taut), lowest CG height above the still water [m], last time [s].
    real(wp) :: contact_share = 0.0_wp, slack_share = 0.0_wp, lowest = huge(1.0_wp)
    !> Largest tilt of the boat (its b3 axis from the vertical) [rad] and when [s].
    real(wp) :: tilt = 0.0_wp, tilt_time = -1.0_wp
    !> Time of the last step [s].
    real(wp) :: t_last = 0.0_wp
    !> Number of snatches (slack to taut) so far.
    integer :: snatches = 0
    !> Whether the falls were slack at the last step.
    logical :: slack = .false.
    !> The largest cable segment or sling tension at the last step [N] (the foundation
    !> slings' off the davit; 0 once the hooks are released or with the slings detached):
    !> the sweep's metrics read it rather than evaluate the tensions a second time.
    real(wp) :: step_tension = 0.0_wp
  contains
    procedure :: watch => log_watch
    procedure :: outcome => log_outcome
    procedure :: write => log_write
    procedure :: seat_peaks => log_seat_peaks
    procedure :: checks => log_checks
    procedure :: report => log_report
  end type launch_log

contains

  !> The log of a run of `sys` built from `cfg`: limits from the deck's wire (the full
  !> rigging's, or the foundation slings').
  function new_launch_log(cfg, sys) result(log)
    !> The run's configuration (&limits, the wire).
    type(config_type), intent(in) :: cfg
    !> The system of the run.
    type(system_type), intent(in) :: sys
    type(launch_log) :: log
    real(wp) :: d
    integer :: nseg
    d = merge(cfg%rigging%wire_diameter, cfg%slings%diameter, sys%par%on_davit)
    nseg = merge(sys%par%rig%nseg, 0, sys%par%on_davit)
    call log%loads%init(nseg, 2, minimum_breaking_load(cfg%limits, d), &
                        cfg%limits%safety_factor, cfg%limits%impact_speed)
    call log%impacts%init(merge(sys%par%fenders%nf, 0, sys%par%contact))
    log%seat%dt = cfg%limits%seat_interval
    log%seat%cutoff = cfg%limits%seat_filter
    log%seat_point = cfg%limits%seat
    log%after_release = cfg%simulation%after_release
    log%weight = sys%par%boat%mass*gravity
    log%rules = new_rule_watch(cfg, sys)
    log%limits = cfg%limits
    log%contact = sys%par%contact
  end function new_launch_log

  subroutine log_watch(self, problem, t, y, done)
    !> The log.
    class(launch_log), intent(inout) :: self
    !> The system (a davit_system_model system_type).
    class(ode_problem), intent(in) :: problem
    !> End of the accepted step [s] and the state there.
    real(wp), intent(in) :: t, y(:)
    !> Whether the launch has ended (released and settled).
    logical, intent(out) :: done
    done = .false.
    if (.not. allocated(self%impacts%open)) return
    select type (sys => problem)
    type is (system_type)
      call watch_motion(self, sys, t, y)
      call watch_loads(self, sys, t, y)
      call self%rules%watch(sys, t, y)
      self%t_prev = t
      self%t_last = t
      done = sys%hist%release_time >= 0.0_wp .and. &
             t >= sys%hist%release_time + self%after_release
    end select
  end subroutine log_watch

  !> CG and seat accelerations (step means), the seat's trace, and the impacts.
  subroutine watch_motion(self, sys, t, y)
    type(launch_log), intent(inout) :: self
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: t, y(:)
    real(wp) :: c(3, 3), v(3), a_cg, tilt
    integer :: started
    associate (q => y(sys%par%boat_part%q(1):sys%par%boat_part%q(2)), &
               u => y(sys%par%boat_part%u(1):sys%par%boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      v = matmul(c, u(4:6))
      self%lowest = min(self%lowest, -dot_product(c(3, :), q(4:6)))
      tilt = acos(max(-1.0_wp, min(1.0_wp, c(3, 3))))
      if (tilt > self%tilt) then
        self%tilt = tilt
        self%tilt_time = t
      end if
      call self%seat%add(t, matmul(c, body_point_velocity(u, self%seat_point)), c)
    end associate
    a_cg = 0.0_wp
    if (self%t_prev >= 0.0_wp .and. t > self%t_prev) a_cg = norm2(v - self%v_prev)/(t - self%t_prev)
    if (a_cg > self%peak_cg) then
      self%peak_cg = a_cg
      self%peak_cg_time = t
    end if
    self%v_prev = v
    if (size(self%impacts%open) == 0) return
    block
      real(wp) :: clearance, force(size(self%impacts%open)), delta(size(force))
      real(wp) :: delta_dot(size(force))
      integer :: k
      call sys%contact_state(y, clearance, force)
      associate (par => sys%par)
        call fender_gaps(par%fenders, side_plane(par%side_y, ship_pose(par%with_ship, &
                         par%ship_part, par%ship_rest, y)), par%boat_part, y, delta, delta_dot)
      end associate
      call self%impacts%track(t, force, delta_dot, a_cg, self%seat%last_raw, started)
      do k = self%impacts%n - started + 1, self%impacts%n
        call self%loads%impact_at(t, self%impacts%events(k)%speed)
      end do
      if (self%t_prev >= 0.0_wp) call average(self%contact_share, &
                                              merge(1.0_wp, 0.0_wp, any(force > 0.0_wp)), &
                                              t - self%t_prev)
    end block
  end subroutine watch_motion

  !> Sling and cable-segment tensions until the hooks are released; slack and snatches.
  subroutine watch_loads(self, sys, t, y)
    type(launch_log), intent(inout) :: self
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: t, y(:)
    real(wp) :: seg(sys%par%rig%nseg), sling(sys%par%rig%nlump + 1, 2), paid
    real(wp) :: lumps(3, sys%par%rig%nlump, 2), fall, foundation(nslings)
    self%step_tension = 0.0_wp
    if (sys%hist%release_time >= 0.0_wp) return
    if (.not. sys%par%on_davit) then
      if (sys%par%slings_attached) then
        foundation = sys%sling_tensions(y)
        self%step_tension = maxval(foundation)
        call self%loads%update(t, [real(wp) ::], foundation)
      end if
      return
    end if
    call sys%rigging_state(t, y, seg, sling, paid, lumps)
    call self%loads%update(t, seg, maxval(sling, dim=1))
    call self%rules%loads(t, max(0.0_wp, maxval(seg)), sum(max(0.0_wp, maxval(sling, dim=1))))
    fall = max(max(0.0_wp, maxval(seg)), maxval(sling))
    self%step_tension = fall
    if (self%slack .and. fall > 0.1_wp*self%weight) self%snatches = self%snatches + 1
    if (fall < 0.01_wp*self%weight) then
      self%slack = .true.
    else if (fall > 0.1_wp*self%weight) then
      self%slack = .false.
    end if
    if (self%t_prev >= 0.0_wp) call average(self%slack_share, &
                                            merge(1.0_wp, 0.0_wp, fall < 0.01_wp*self%weight), &
                                            t - self%t_prev)
  end subroutine watch_loads

  !> Exponential average over judge_time of an indicator x held over a step h.
  pure subroutine average(share, x, h)
    real(wp), intent(inout) :: share
    real(wp), intent(in) :: x, h
    share = share + (x - share)*(1.0_wp - exp(-max(h, 0.0_wp)/judge_time))
  end subroutine average

  !> Events, peaks, limits, the seat's filtered acceleration and the outcome (root
  !> attribute `outcome`), after the recorder has written its groups.
  subroutine log_write(self, problem, w)
    !> The log.
    class(launch_log), intent(in) :: self
    !> The system of the run.
    class(ode_problem), intent(in) :: problem
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    type(impact_tracker) :: impacts
    real(wp), allocatable :: a(:, :)
    real(wp) :: peak(2)
    if (.not. allocated(self%impacts%open)) return
    select type (sys => problem)
    type is (system_type)
      impacts = self%impacts
      call self%seat_peaks(a, impacts, peak)
      call write_impacts(w, impacts)
      call write_loads(w, self%loads)
      call write_seat(w, self%seat, a, self%seat_point)
      call w%write_1d("peaks/cg_acceleration", [self%peak_cg, self%peak_cg_time], &
                      "m/s^2, s", "Largest step-mean CG acceleration |Delta v/Delta t| "// &
                      "over every step, and when (the sampled /boat/acceleration misses it)", &
                      dims="value_time")
      call w%write_1d("peaks/seat_acceleration", peak, "m/s^2, s", "Largest filtered "// &
                      "seat acceleration (/seat) and when", dims="value_time")
      call w%write_1d("peaks/tilt", [self%tilt, self%tilt_time], "rad, s", "Largest tilt "// &
                      "of the boat (its b3 axis from the vertical) and when; beyond pi/2 "// &
                      "the boat overturned on its falls (outcome)", dims="value_time")
      call w%attr_str("/", "outcome", self%outcome(sys))
      block
        type(rule_check) :: c(n_checks)
        real(wp) :: dr(2)
        c = self%checks(dr)
        call write_assessment(w, c, self%rules%head_height, dr)
      end block
    end select
  end subroutine log_write

  !> The rule checks of the launch so far (davit_assess_rules).
  function log_checks(self, dr) result(c)
    !> The log.
    class(launch_log), intent(in) :: self
    !> The spine's dynamic response index: peak up and down, 0 without a seat trace.
    real(wp), intent(out), optional :: dr(2)
    type(rule_check) :: c(n_checks)
    real(wp) :: drs(2)
    real(wp) :: speed, height, before, peak, sling, fall
    call self%rules%lowering_speed(speed, height)
    c = not_applicable()
    if (speed == speed) c(check_lowering_speed) = new_check(check_lowering_speed, speed, &
                                                            0.4_wp + 0.02_wp*height)
    if (self%contact) c(check_impact_speed) = new_check(check_impact_speed, &
                                                        self%loads%max_impact_speed, &
                                                        self%loads%impact%value)
    sling = max(0.0_wp, maxval(self%loads%sling))
    c(check_sling_swl) = new_check(check_sling_swl, sling, self%loads%swl%value)
    c(check_sling_mbl) = new_check(check_sling_mbl, sling, self%loads%mbl%value)
    if (size(self%loads%segment) > 0) then
      fall = max(0.0_wp, maxval(self%loads%segment))
      c(check_fall_swl) = new_check(check_fall_swl, fall, self%loads%swl%value)
      c(check_fall_mbl) = new_check(check_fall_mbl, fall, self%loads%mbl%value)
    end if
    call self%rules%stop_loads(before, peak)
    if (before == before) c(check_brake_load) = new_check(check_brake_load, peak, &
                                                          1.1_wp*before)
    if (self%rules%release_load >= 0.0_wp) then
      c(check_release_load) = new_check(check_release_load, self%rules%release_load, &
                                        1.1_wp*self%weight)
    end if
    call occupant_checks(self, c, drs)
    if (present(dr)) dr = drs
  end function log_checks

  !> The peak SRSS of the filtered seat acceleration over the boat's axes (against the
  !> deck's limit; reported only without one) and the dynamic response index up the spine
  !> (the seat pushed up: -z in the boat's z-down axes), with its downward peak.
  subroutine occupant_checks(self, c, drs)
    type(launch_log), intent(in) :: self
    type(rule_check), intent(inout) :: c(n_checks)
    real(wp), intent(out) :: drs(2)
    ! the trace is as long as the run (1 kHz): every array of it is allocatable (heap), as
    ! an expression's temporary would go on the stack under -fstack-arrays (issue 35)
    real(wp), allocatable :: a(:, :), mag(:), up(:)
    drs = 0.0_wp
    a = self%seat%body_filtered()
    if (size(a, 2) == 0) return
    mag = norm2(a, dim=1)
    if (self%limits%srss_limit > 0.0_wp) then
      c(check_seat_srss) = new_check(check_seat_srss, maxval(mag), self%limits%srss_limit)
    else
      c(check_seat_srss)%value = maxval(mag)
    end if
    up = -a(3, :)
    drs = response_peaks(up, self%seat%dt, self%limits%dr_frequency, self%limits%dr_damping)
    c(check_seat_dri) = new_check(check_seat_dri, drs(1), self%limits%dri_limit)
  end subroutine occupant_checks

  !> The launch's outcome, events, peaks and rule checks in words (end of davit run).
  function log_report(self, sys) result(text)
    !> The log.
    class(launch_log), intent(in) :: self
    !> The system of the run.
    type(system_type), intent(in) :: sys
    character(len=:), allocatable :: text
    type(impact_tracker) :: impacts
    real(wp), allocatable :: a(:, :)
    real(wp) :: peak(2)
    text = ""
    if (.not. allocated(self%impacts%open)) return
    impacts = self%impacts
    call self%seat_peaks(a, impacts, peak)
    text = launch_text(self%outcome(sys), impacts, self%loads, peak(1), self%checks())
  end function log_report

  !> The seat's filtered acceleration a (3, n), each impact's filtered peak from its onset
  !> to 0.2 s after its end, and the largest filtered value with its time.
  subroutine log_seat_peaks(self, a, impacts, peak)
    !> The log.
    class(launch_log), intent(in) :: self
    !> The seat's filtered acceleration (3, n) [m/s^2].
    real(wp), allocatable, intent(out) :: a(:, :)
    !> The impacts, their filtered seat peaks filled in.
    type(impact_tracker), intent(inout) :: impacts
    !> The largest filtered value [m/s^2] and its time [s].
    real(wp), intent(out) :: peak(2)
    real(wp), allocatable :: mag(:)
    integer :: k, i1, i2
    a = self%seat%filtered()
    ! onto the allocatable mag (heap), never into an expression's temporary (stack)
    mag = norm2(a, dim=1)
    peak = [0.0_wp, -1.0_wp]
    if (size(mag) > 0) peak = [maxval(mag), (real(maxloc(mag, 1), wp) - 0.5_wp)*self%seat%dt]
    do k = 1, impacts%n
      associate (e => impacts%events(k))
        i1 = max(1, int(e%time/self%seat%dt))
        i2 = min(size(mag), int((e%time + e%duration + 0.2_wp)/self%seat%dt) + 1)
        if (i2 >= i1) e%peak_seat = maxval(mag(i1:i2))
      end associate
    end do
  end subroutine log_seat_peaks

  !> How the launch ended, in words (empty for a boat that is not on the davit).
  function log_outcome(self, sys) result(text)
    !> The log.
    class(launch_log), intent(in) :: self
    !> The system of the run.
    type(system_type), intent(in) :: sys
    character(len=:), allocatable :: text
    text = ""
    if (.not. sys%par%on_davit) return
    if (self%tilt > 0.5_wp*pi) then
      ! flung over on its falls: past the model's validity (falls wrapping the hull, no
      ! capsize hydrostatics), a failed launch whatever else it reports
      text = "overturned on its falls (tilted "//int_to_str(nint(self%tilt*180.0_wp/pi))// &
             " deg at t = "//event_time(self%tilt_time)//" s); "
    end if
    if (sys%hist%release_time >= 0.0_wp) then
      text = text//"released at t = "//event_time(sys%hist%release_time)//" s (waterborne at "// &
             event_time(sys%hist%waterborne_time)//" s)"
    else if (sys%hist%waterborne_time >= 0.0_wp) then
      text = text//"waterborne at t = "//event_time(sys%hist%waterborne_time)//" s; hooks not "// &
             "released (&rigging release = .false. or its delay not over)"
    else
      text = text//"not waterborne by t = "//event_time(self%t_last)//" s: "//stuck_cause(self)
    end if
  end function log_outcome

  !> An event time in the outcome text, to the millisecond: what the located events mean
  !> (the event stepper's tolerance is far finer, but digits beyond 1 ms change with the CPU's
  !> rounding, e.g. FMA or not, and would make the same launch read differently).
  pure function event_time(t) result(text)
    real(wp), intent(in) :: t
    character(len=:), allocatable :: text
    text = fmt_fixed(t, 3)
  end function event_time

  !> Why a launch is not waterborne at its end.
  function stuck_cause(self) result(text)
    type(launch_log), intent(in) :: self
    character(len=:), allocatable :: text
    if (self%lowest > 3.0_wp) then
      text = "still lowering (CG never lower than "//fmt_real(self%lowest)//" m above "// &
             "the still water; t_end is shorter than the lowering)"
    else if (self%contact_share > 0.3_wp) then
      text = "pinned against the ship's side (a fender in contact "// &
             percent(self%contact_share)//" of the last ~10 s; "// &
             int_to_str(self%impacts%n)//" impacts)"
    else if (self%slack_share > 0.2_wp) then
      text = "riding the waves in slack, snatching falls (slack "// &
             percent(self%slack_share)//" of the last ~10 s; "//int_to_str(self%snatches)// &
             " snatches): never afloat for 1 s"
    else
      text = "hanging at the water in taut falls (neither buoyancy >= weight nor hooks < "// &
             "1 % of it held for 1 s)"
    end if
  end function stuck_cause

  pure function percent(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    text = int_to_str(nint(100.0_wp*x))//" %"
  end function percent

end module davit_run_launch_log
