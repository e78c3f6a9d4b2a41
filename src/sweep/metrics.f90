!> What a sweep measures in each launch, from the state after every accepted step (so no
!> contact or snatch load falls between output samples), over the lowering: from t = 0 until
!> the hooks are released (or, with release off, until the boat is waterborne), else to
!> the end of the run.
!>
!> * clearance: smallest fender-to-ship-side distance; negative = fender indentation, which
!>   is a collision.
!> * impacts: separate contact episodes: the boat goes from no fender touching to some
!>   fender in its compression or restitution phase (a re-contact after separating counts
!>   again).
!> * accelerations: of the boat's CG in the inertial frame, as the velocity change over each
!>   step over dt (the step's mean acceleration: within O((omega dt)^2) of the
!>   instantaneous peak for a mode omega, 1e-3 for a 6 ms fender contact at dt = 2e-4 s,
!>   and free of an extra RHS evaluation); horizontal = |(a_x, a_y)|, vertical = |a_z|.
!> * tension: largest tension of any cable segment or sling segment (or foundation sling).
!> * the launch log's (davit_run_launch_log) peaks, limits and outcome over the run: the peak
!>   sling and fall (cable segment) tensions, the fastest impact, the seat's filtered peak
!>   acceleration, when the safe working load, the breaking load and the impact speed
!>   limit were first exceeded, and how the launch ended.
module davit_sweep_metrics
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use davit_kinds, only: wp, i8
  use davit_core_rotation, only: rotation_matrix
  use davit_boat_contact, only: phase_compression, phase_restitution
  use davit_solve_integrator, only: ode_problem
  use davit_system_model, only: system_type
  use davit_run_step_monitor, only: step_monitor
  use davit_run_launch_log, only: launch_log
  use davit_run_impact_events, only: impact_tracker
  use davit_assess_rules, only: n_checks, rule_check
  implicit none
  private
  public :: launch_metrics, case_result, status_not_run, status_ok, status_failed
  public :: not_run_result, status_not_needed

  integer, parameter :: status_not_run = 0, status_ok = 1, status_failed = 2
  !> Adaptive realisations: the case's cell converged before reaching it (counts as done).
  integer, parameter :: status_not_needed = 3

  !> One row of the summary. Results are defined for status ok; otherwise the reals are NaN
  !> and the integers -1, except wall time, steps and RHS evaluations of a failed case.
  !> Event times are -1 when the event did not happen.
  type :: case_result
    !> Case status (not run, ok, failed, not needed).
    integer :: status = status_not_run
    !> Why the case failed or was not needed.
    character(len=:), allocatable :: message
    !> Smallest fender-to-side clearance [m] (negative = indentation) and peak horizontal CG
    !> acceleration [m/s^2] (inertial frame).
    real(wp) :: min_clearance = 0.0_wp, peak_horizontal_acceleration = 0.0_wp
    !> Peak vertical CG acceleration [m/s^2] (inertial frame) and largest segment tension [N].
    real(wp) :: peak_vertical_acceleration = 0.0_wp, peak_segment_tension = 0.0_wp
    !> Times of the first fender contact and of the boat becoming waterborne [s] (-1 = never).
    real(wp) :: first_contact_time = -1.0_wp, waterborne_time = -1.0_wp
    !> Simulated time at the lowering's end [s] and the case's wall-clock time [s].
    real(wp) :: end_time = 0.0_wp, wall_time = 0.0_wp
    !> From the launch log: peak sling and fall tensions [N], fastest impact [m/s], filtered
    !> seat peak [m/s^2], first times beyond the safe working load, the breaking load and
    !> the impact speed limit [s] (-1 = never), and the outcome in words.
    real(wp) :: peak_sling_tension = 0.0_wp, peak_fall_tension = 0.0_wp
    !> Fastest impact [m/s] and the seat's filtered peak acceleration [m/s^2].
    real(wp) :: max_impact_speed = 0.0_wp, peak_seat_acceleration = 0.0_wp
    !> First times beyond the safe working load and the breaking load [s] (-1 = never).
    real(wp) :: swl_exceeded_time = -1.0_wp, mbl_exceeded_time = -1.0_wp
    !> First time beyond the impact speed limit [s] (-1 = never).
    real(wp) :: impact_speed_exceeded_time = -1.0_wp
    !> How the launch ended, in words.
    character(len=:), allocatable :: outcome
    !> The rule checks (davit_assess_rules): value, limit and relative margin (>= 0 passes,
    !> NaN: does not apply).
    real(wp) :: check_value(n_checks) = 0.0_wp, check_limit(n_checks) = 0.0_wp
    !> Relative margins of the rule checks (>= 0 passes, NaN when a check does not apply).
    real(wp) :: check_margin(n_checks) = 0.0_wp
    !> Whether the boat collided (1 if the clearance went negative, else 0) and the number of
    !> contact episodes.
    integer :: collided = -1, impacts = -1
    !> Accepted steps and right-hand-side evaluations of the run.
    integer(i8) :: steps = 0, rhs_evaluations = 0
  end type case_result

  type, extends(step_monitor) :: launch_metrics
    !> Whether the lowering ends at hook release (else when the boat is waterborne).
    logical :: stop_at_release = .true.
    !> False once the lowering is over: later steps change nothing.
    logical :: open = .true.
    !> Smallest fender-to-side clearance [m] and peak horizontal CG acceleration [m/s^2].
    real(wp) :: min_clearance = huge(1.0_wp), peak_horizontal = 0.0_wp
    !> Peak vertical CG acceleration [m/s^2] and largest segment tension [N].
    real(wp) :: peak_vertical = 0.0_wp, peak_tension = 0.0_wp
    !> First contact time, lowering's end time and waterborne time [s] (-1 = not yet).
    real(wp) :: first_contact_time = -1.0_wp, end_time = 0.0_wp, waterborne_time = -1.0_wp
    !> Contact episodes so far.
    integer :: impacts = 0
    !> Whether a fender touched (compression or restitution) after the previous step.
    logical :: touching = .false.
    !> Inertial CG velocity and time of the previous step.
    real(wp) :: v_prev(3) = 0.0_wp, t_prev = -1.0_wp
    !> Peaks, limits and outcome over the run (set up by the caller: new_launch_log).
    type(launch_log) :: log
  contains
    procedure :: watch => metrics_watch
    procedure :: result => metrics_result
  end type launch_metrics

contains

  !> A row for a case that has not run (or whose results are undefined).
  function not_run_result() result(r)
    type(case_result) :: r
    real(wp) :: nan
    nan = ieee_value(nan, ieee_quiet_nan)
    r%status = status_not_run
    r%message = ""
    r%min_clearance = nan
    r%peak_horizontal_acceleration = nan
    r%peak_vertical_acceleration = nan
    r%peak_segment_tension = nan
    r%first_contact_time = nan
    r%waterborne_time = nan
    r%end_time = nan
    r%wall_time = nan
    r%peak_sling_tension = nan
    r%peak_fall_tension = nan
    r%max_impact_speed = nan
    r%peak_seat_acceleration = nan
    r%swl_exceeded_time = nan
    r%mbl_exceeded_time = nan
    r%impact_speed_exceeded_time = nan
    r%outcome = ""
    r%check_value = nan
    r%check_limit = nan
    r%check_margin = nan
    r%collided = -1
    r%impacts = -1
  end function not_run_result

  !> The integrated launch system's state after a step (its fender phases and events are
  !> read, never changed).
  subroutine metrics_watch(self, problem, t, y, done)
    !> The monitor, updated with the step.
    class(launch_metrics), intent(inout) :: self
    !> The integrated problem (the launch system).
    class(ode_problem), intent(in) :: problem
    !> Time [s] and state vector after the step.
    real(wp), intent(in) :: t, y(:)
    !> Whether the integration should stop (lowering over and stop_at_release).
    logical, intent(out) :: done
    logical :: log_done
    call self%log%watch(problem, t, y, log_done)
    done = .false.
    if (.not. self%open) then
      done = log_done
      return
    end if
    select type (sys => problem)
    type is (system_type)
      self%end_time = t
      call watch_contact(self, sys, t, y)
      call watch_acceleration(self, sys, t, y)
      ! the log has just formed the step's largest tension (0 once released)
      self%peak_tension = max(self%peak_tension, self%log%step_tension)
      self%waterborne_time = sys%hist%waterborne_time
      if (lowering_over(sys)) then
        self%open = .false.
        done = self%stop_at_release
      end if
    end select
  end subroutine metrics_watch

  !> Clearance and contact episodes (fender phases are advanced before the monitor).
  subroutine watch_contact(self, sys, t, y)
    !> The monitor, updated with the clearance and contact episodes.
    type(launch_metrics), intent(inout) :: self
    !> The launch system.
    type(system_type), intent(in) :: sys
    !> Time [s] and state vector after the step.
    real(wp), intent(in) :: t, y(:)
    real(wp) :: clearance, force(sys%par%fenders%nf)
    logical :: touching
    call sys%contact_state(y, clearance, force)
    self%min_clearance = min(self%min_clearance, clearance)
    touching = any(sys%hist%fender_states%phase == phase_compression .or. &
                   sys%hist%fender_states%phase == phase_restitution)
    if (touching .and. .not. self%touching) then
      self%impacts = self%impacts + 1
      if (self%first_contact_time < 0.0_wp) self%first_contact_time = t
    end if
    self%touching = touching
  end subroutine watch_contact

  !> Mean CG acceleration over the last step, Delta v/Delta t (inertial frame).
  subroutine watch_acceleration(self, sys, t, y)
    !> The monitor, updated with the peak accelerations.
    type(launch_metrics), intent(inout) :: self
    !> The launch system.
    type(system_type), intent(in) :: sys
    !> Time [s] and state vector after the step.
    real(wp), intent(in) :: t, y(:)
    real(wp) :: v(3), a(3)
    associate (q => y(sys%par%boat_part%q(1):sys%par%boat_part%q(2)), &
               u => y(sys%par%boat_part%u(1):sys%par%boat_part%u(2)))
      v = matmul(rotation_matrix(q(1:3)), u(4:6))
    end associate
    if (self%t_prev >= 0.0_wp .and. t > self%t_prev) then
      a = (v - self%v_prev)/(t - self%t_prev)
      self%peak_horizontal = max(self%peak_horizontal, norm2(a(1:2)))
      self%peak_vertical = max(self%peak_vertical, abs(a(3)))
    end if
    self%v_prev = v
    self%t_prev = t
  end subroutine watch_acceleration

  !> The lowering is over once the hooks are released (or, with release off, once the
  !> boat is waterborne).
  pure logical function lowering_over(sys)
    !> The launch system.
    type(system_type), intent(in) :: sys
    lowering_over = sys%par%on_davit .and. (sys%hist%release_time >= 0.0_wp .or. &
                                            (.not. sys%par%release .and. &
                                             sys%hist%waterborne_time >= 0.0_wp))
  end function lowering_over

  !> The measured quantities as a summary row of status ok (`sys`: the system integrated).
  function metrics_result(self, sys) result(r)
    !> The monitor after the run.
    class(launch_metrics), intent(in) :: self
    !> The system integrated.
    type(system_type), intent(in) :: sys
    type(case_result) :: r
    type(impact_tracker) :: impacts
    real(wp), allocatable :: a(:, :)
    real(wp) :: seat(2)
    r%status = status_ok
    r%message = "ok"
    r%min_clearance = self%min_clearance
    r%collided = merge(1, 0, self%min_clearance < 0.0_wp)
    r%impacts = self%impacts
    r%peak_horizontal_acceleration = self%peak_horizontal
    r%peak_vertical_acceleration = self%peak_vertical
    r%peak_segment_tension = self%peak_tension
    r%first_contact_time = self%first_contact_time
    r%waterborne_time = self%waterborne_time
    r%end_time = self%end_time
    r%outcome = ""
    if (.not. allocated(self%log%impacts%open)) return
    impacts = self%log%impacts
    call self%log%seat_peaks(a, impacts, seat)
    r%peak_seat_acceleration = seat(1)
    r%peak_sling_tension = max(0.0_wp, maxval(self%log%loads%sling))
    r%peak_fall_tension = max(0.0_wp, maxval(self%log%loads%segment))
    r%max_impact_speed = self%log%loads%max_impact_speed
    r%swl_exceeded_time = self%log%loads%swl%first
    r%mbl_exceeded_time = self%log%loads%mbl%first
    r%impact_speed_exceeded_time = self%log%loads%impact%first
    r%outcome = self%log%outcome(sys)
    block
      type(rule_check) :: c(n_checks)
      c = self%log%checks()
      r%check_value = c%value
      r%check_limit = c%limit
      r%check_margin = c%margin
    end block
  end function metrics_result

end module davit_sweep_metrics
