!> A launch run one step at a time, for the library (davit_capi_bindings, include/davit.h):
!> the time loop of davit_run_driver's `integrate`, one pass per call, with the same step
!> sequence (the deck's dt or what the contact asks, cut at the output samples), so that a
!> launch stepped in any pieces reproduces `davit run` bit for bit. Between passes an
!> operator may move the winch lever, brake, open the hooks or turn the ship. Every control
!> is logged with the pass it came before: the snapshot (davit_capi_snapshot) is the deck,
!> that log and the pass count, and a restore replays it.
module davit_capi_session
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_io_deck_reader, only: fmt_real
  use davit_io_namelist, only: int_to_str
  use davit_solve_integrator, only: integrator_type
  use davit_solve_factory, only: new_integrator
  use davit_solve_step_control, only: stretch_to
  use davit_solve_event_location, only: event_stepper_type
  use davit_system_model, only: system_type
  use davit_run_scene, only: scene_type, new_scene
  use davit_system_events, only: release_hooks
  use davit_rigging_winch, only: winch_command
  use davit_run_driver, only: first_bad, speed_limit
  use davit_run_launch_log, only: launch_log, new_launch_log
  use davit_run_budget, only: check_run_budget
  use davit_core_blas_threads, only: single_threaded_blas
  implicit none
  private
  public :: session_type, session_open, session_advance_to, session_control, session_replay
  public :: ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading

  !> Controls (the log's kinds): winch speed set-point (value 1: drum speed [m/s], value 2:
  !> ramp [s]), brake (value 1: time to rest [s]), hook release, heading set-point [rad].
  integer, parameter :: ctrl_winch = 1, ctrl_brake = 2, ctrl_release = 3, ctrl_heading = 4

  type :: session_type
    !> The deck as read (its name only for messages) and its configuration.
    character(len=:), allocatable :: deck_name, deck_text
    !> The deck's run configuration.
    type(config_type) :: cfg
    !> The launch system integrated.
    type(system_type) :: sys
    !> The deck's time integrator.
    class(integrator_type), allocatable :: integ
    !> Event-locating stepper around the integrator (fender contacts).
    type(event_stepper_type) :: stepper
    !> The launch log (peaks, limits, outcome), watching every step.
    type(launch_log) :: log
    !> State vector at time t.
    real(wp), allocatable :: y(:)
    !> Time reached [s].
    real(wp) :: t = 0.0_wp
    !> Next output sample k (its time k output_interval cuts the steps) and their number.
    integer(i8) :: k = 1, nsamples = 0
    !> Passes of the loop so far; the end of the run (t_end, or the log's end after release).
    integer(i8) :: passes = 0
    !> Whether the run has ended.
    logical :: done = .false.
    !> The control log: before pass ctrl_pass(i), control ctrl_kind(i) with ctrl_value(:, i).
    integer :: n_ctrl = 0
    !> Pass before which each control came.
    integer(i8), allocatable :: ctrl_pass(:)
    !> Kind of each control (ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading).
    integer, allocatable :: ctrl_kind(:)
    !> Values of each control (2, n): see the control kinds.
    real(wp), allocatable :: ctrl_value(:, :)
  end type session_type

contains

  !> A session of deck `text` (named `name` in messages) at t = 0, as `davit run` starts it.
  subroutine session_open(s, cfg, name, text, error)
    !> The new session.
    type(session_type), intent(out) :: s
    !> The deck's run configuration.
    type(config_type), intent(in) :: cfg
    !> The deck's name (for messages) and its text.
    character(len=*), intent(in) :: name, text
    !> Set when the deck is not a boat scene, exceeds the run budget or its system fails.
    type(error_type), allocatable, intent(out) :: error
    class(scene_type), allocatable :: scene
    ! as davit does at its start: OpenBLAS's threads would split its sums differently from
    ! davit run's (and only compete for the cores on the small matrices davit solves)
    call single_threaded_blas()
    s%cfg = cfg
    s%deck_name = name
    s%deck_text = text
    allocate (s%ctrl_pass(8), s%ctrl_kind(8), s%ctrl_value(2, 8))
    call new_scene(cfg%simulation%scene, scene, error)
    if (allocated(error)) return
    if (.not. scene%has_boat()) then
      call fatal_error(error, "deck '"//name//"': &simulation scene = '"// &
                       trim(cfg%simulation%scene)//"' has no boat; the library runs the "// &
                       "scenes with one (hanging_boat, lowering, launch)")
      return
    end if
    call check_run_budget(cfg, error)
    if (allocated(error)) return
    call scene%build_boat(cfg, s%sys, s%y, error)
    if (allocated(error)) return
    s%log = new_launch_log(cfg, s%sys)
    associate (sim => cfg%simulation)
      call new_integrator(sim%integrator, size(s%y), s%integ, error, sim%rtol, sim%atol, &
                          fixed_step=sim%fixed_step)
      if (allocated(error)) return
      s%integ%single_step = .true.
      call s%stepper%init(size(s%y), s%sys%n_modes())
      s%nsamples = int(sim%t_end/sim%output_interval + 1.0e-9_wp, i8)
    end associate
    call s%log%watch(s%sys, s%t, s%y, s%done)
  end subroutine session_open

  !> Step until t >= t_stop - 1 ns (the step that crosses t_stop is not cut: the steps stay
  !> those of `davit run`; the nanosecond keeps t + dt's rounding from adding a step after
  !> a sample), the end of the run, or a failure (then `error`, the state kept at the last
  !> good step).
  subroutine session_advance_to(s, t_stop, error)
    !> The session, advanced.
    type(session_type), intent(inout) :: s
    !> Time to step to [s].
    real(wp), intent(in) :: t_stop
    !> Set when a step fails (the state kept at the last good step).
    type(error_type), allocatable, intent(out) :: error
    real(wp), parameter :: slack = 1.0e-9_wp
    do while (s%t < t_stop - slack .and. .not. finished(s))
      call one_pass(s, error)
      if (allocated(error)) return
    end do
  end subroutine session_advance_to

  !> Replay `passes` passes with the logged controls (a snapshot's) applied
  !> before the passes they came before: the state those passes and controls led to.
  subroutine session_replay(s, passes, ctrl_pass, ctrl_kind, ctrl_value, error)
    !> The session, replayed from its start.
    type(session_type), intent(inout) :: s
    !> Passes to replay, and the pass before which each logged control came.
    integer(i8), intent(in) :: passes, ctrl_pass(:)
    !> Kind of each logged control.
    integer, intent(in) :: ctrl_kind(:)
    !> Values of each logged control (2, n).
    real(wp), intent(in) :: ctrl_value(:, :)
    !> Set when a pass or a control fails.
    type(error_type), allocatable, intent(out) :: error
    integer :: i
    do i = 1, size(ctrl_kind)
      do while (s%passes < ctrl_pass(i))
        call one_pass(s, error)
        if (allocated(error)) return
      end do
      call session_control(s, ctrl_kind(i), ctrl_value(:, i), error)
      if (allocated(error)) return
    end do
    do while (s%passes < passes)
      call one_pass(s, error)
      if (allocated(error)) return
    end do
  end subroutine session_replay

  !> The run has reached t_end, or the launch log has ended it after the release.
  pure logical function finished(s)
    !> The session.
    type(session_type), intent(in) :: s
    finished = s%done .or. .not. s%t < s%cfg%simulation%t_end
  end function finished

  !> One pass of davit_run_driver's time loop, without recording.
  subroutine one_pass(s, error)
    !> The session, advanced by one pass.
    type(session_type), intent(inout) :: s
    !> Set when the step fails.
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: t_next, t_new, h, y_keep(size(s%y)), t_keep
    integer :: bad
    logical :: event
    associate (sim => s%cfg%simulation)
      t_next = min(real(s%k, wp)*sim%output_interval, sim%t_end)
      h = s%sys%max_step(s%t, s%y, sim%dt)
      t_new = merge(t_next, s%t + h, stretch_to(h, t_next - s%t))
      y_keep = s%y
      t_keep = s%t
      call s%stepper%step(s%integ, s%sys, s%t, s%y, t_new, event)
      if (s%integ%failed) then
        call fatal_error(error, "run stopped: "//s%integ%failure)
        return
      end if
      bad = first_bad(s%y, s%sys%par%boat_part%u)
      if (bad > 0) then
        call fatal_error(error, "run diverged at t = "//fmt_real(s%t)//" s: state "// &
                         "component "//int_to_str(bad)//" = "//fmt_real(s%y(bad))// &
                         " is not finite or beyond "//fmt_real(speed_limit)// &
                         "; the state is kept at t = "//fmt_real(t_keep)//" s")
        s%y = y_keep
        s%t = t_keep
        s%done = .true.
        return
      end if
      call s%sys%after_step(s%t, s%y)
      call s%log%watch(s%sys, s%t, s%y, s%done)
      if (s%t == t_next .and. s%k <= s%nsamples) s%k = s%k + 1
    end associate
    s%passes = s%passes + 1
  end subroutine one_pass

  !> Apply control `kind` with `value` now (before the next pass) and log it.
  subroutine session_control(s, kind, value, error)
    !> The session, whose control log grows by one.
    type(session_type), intent(inout) :: s
    !> Control kind (ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading).
    integer, intent(in) :: kind
    !> Control values (see the control kinds).
    real(wp), intent(in) :: value(2)
    !> Set when a value is out of range or the deck has nothing the control can act on.
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: why
    why = control_refusal(s, kind, value)
    if (len(why) > 0) then
      call fatal_error(error, why)
      return
    end if
    call apply_control(s, kind, value)
    if (s%n_ctrl == size(s%ctrl_kind)) call grow_log(s)
    s%n_ctrl = s%n_ctrl + 1
    s%ctrl_pass(s%n_ctrl) = s%passes
    s%ctrl_kind(s%n_ctrl) = kind
    s%ctrl_value(:, s%n_ctrl) = value
  end subroutine session_control

  !> Why the control cannot be applied (a value out of range, nothing it can act on), or
  !> empty where it can.
  pure function control_refusal(s, kind, value) result(why)
    !> The session the control would act on.
    type(session_type), intent(in) :: s
    !> Control kind (ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading).
    integer, intent(in) :: kind
    !> Control values (see the control kinds).
    real(wp), intent(in) :: value(2)
    character(len=:), allocatable :: why
    why = ""
    if (kind /= ctrl_heading .and. .not. s%sys%par%on_davit) then
      why = "deck '"//s%deck_name//"': the boat hangs on no davit "// &
            "(no &rigging): no winch or hooks to control"
    else if (.not. (abs(value(1)) < huge(1.0_wp) .and. abs(value(2)) < huge(1.0_wp))) then
      why = "control value is not a finite number"
    else if (kind == ctrl_winch .and. (abs(value(1)) > 10.0_wp .or. value(2) < 0.0_wp .or. &
                                       value(2) > 60.0_wp)) then
      why = "winch set-point: drum speed "//fmt_real(value(1))// &
            " m/s must lie in [-10, 10] and its ramp "//fmt_real(value(2))//" s in [0, 60]"
    else if (kind == ctrl_brake .and. (value(1) < 0.0_wp .or. value(1) > 60.0_wp)) then
      why = "brake: time to rest "//fmt_real(value(1))//" s must lie in [0, 60]"
    else if (kind == ctrl_heading .and. .not. ship_keeps_heading(s)) then
      why = "deck '"//s%deck_name//"': the ship keeps no heading "// &
            "(a moving ship with heading keeping, &ship): no heading set-point"
    else if (all(kind /= [ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading])) then
      why = "unknown control "//int_to_str(kind)
    end if
  end function control_refusal

  pure logical function ship_keeps_heading(s)
    !> The session.
    type(session_type), intent(in) :: s
    ship_keeps_heading = s%sys%par%with_ship
    if (ship_keeps_heading) ship_keeps_heading = s%sys%ship%par%moor_k(3) > 0.0_wp
  end function ship_keeps_heading

  !> Apply a control that control_refusal let through.
  subroutine apply_control(s, kind, value)
    !> The session the control acts on.
    type(session_type), intent(inout) :: s
    !> Control kind (ctrl_winch, ctrl_brake, ctrl_release, ctrl_heading).
    integer, intent(in) :: kind
    !> Control values (see the control kinds).
    real(wp), intent(in) :: value(2)
    select case (kind)
    case (ctrl_winch)
      call winch_command(s%sys%par%rig%winch, s%t, value(1), value(2))
    case (ctrl_brake)
      call winch_command(s%sys%par%rig%winch, s%t, 0.0_wp, value(1))
    case (ctrl_release)
      if (s%sys%hist%release_time < 0.0_wp) call release_hooks(s%sys%par, s%sys%hist, s%t, s%y)
    case (ctrl_heading)
      call s%sys%ship%set_heading(value(1))
    case default
      ! control_refusal has refused every other kind
    end select
  end subroutine apply_control

  subroutine grow_log(s)
    !> The session whose control log is enlarged.
    type(session_type), intent(inout) :: s
    integer(i8), allocatable :: p(:)
    integer, allocatable :: kd(:)
    real(wp), allocatable :: v(:, :)
    integer :: n
    n = s%n_ctrl
    allocate (p(2*n), kd(2*n), v(2, 2*n))
    p(1:n) = s%ctrl_pass(1:n)
    kd(1:n) = s%ctrl_kind(1:n)
    v(:, 1:n) = s%ctrl_value(:, 1:n)
    call move_alloc(p, s%ctrl_pass)
    call move_alloc(kd, s%ctrl_kind)
    call move_alloc(v, s%ctrl_value)
  end subroutine grow_log

end module davit_capi_session
