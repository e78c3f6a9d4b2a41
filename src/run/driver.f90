!> Running a scene: build the scene's system, integrate (step dt, or smaller where the
!> problem asks), record at exact multiples of the output interval and write the HDF5
!> file. One time loop serves every scene; each scene brings its recorder.
!> A non-finite state (or an unphysical speed) stops the run with a diagnostic naming the
!> time and the offending quantity; the partial record is still written, marked incomplete,
!> under the output name, or beside an existing output (OUT.partial.h5), which stays as it was.
module davit_run_driver
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type, simulation_config
  use davit_io_deck_reader, only: fmt_real
  use davit_io_hdf5_writer, only: h5_writer_type, check_output_path
  use davit_solve_integrator, only: integrator_type, ode_problem
  use davit_solve_factory, only: new_integrator
  use davit_solve_step_control, only: stretch_to
  use davit_solve_event_location, only: event_stepper_type
  use davit_run_run_summary, only: run_summary
  use davit_run_scenario, only: write_root_attributes
  use davit_run_recorders, only: recorder_type
  use davit_run_step_monitor, only: step_monitor
  use davit_run_budget, only: check_run_budget
  use davit_run_scene, only: scene_type, new_scene
  use davit_run_progress, only: progress_meter
  implicit none
  private
  public :: run_simulation, integrate_scene, integrate, first_bad, speed_limit

  !> Speeds beyond this (m/s, rad/s) are a numerical blow-up, not a lifeboat or a ship.
  real(wp), parameter :: speed_limit = 1.0e3_wp

contains

  !> Run the deck's scene and write `out_path`; `progress` (davit run at a terminal) sees
  !> the time loop of the integrated scenes.
  subroutine run_simulation(cfg, out_path, summary, error, progress)
    !> The checked configuration of the run.
    type(config_type), intent(in) :: cfg
    !> Path of the HDF5 file written.
    character(len=*), intent(in) :: out_path
    !> Steps, evaluations, wall time and completion of the run.
    type(run_summary), intent(out) :: summary
    !> Set when the run cannot be set up or its file not written (a divergence is reported in the
    !> file and the summary).
    type(error_type), allocatable, intent(out) :: error
    !> Progress line at a terminal (absent: none).
    type(progress_meter), intent(inout), optional :: progress
    class(scene_type), allocatable :: scene
    ! a run that cannot finish or cannot fit is refused before anything is built or written
    call check_run_budget(cfg, error)
    if (allocated(error)) return
    call new_scene(cfg%simulation%scene, scene, error)
    if (allocated(error)) return
    call scene%run(cfg, out_path, summary, error, progress)
  end subroutine run_simulation

  !> Integrate a scene into its recorder and write `out_path` (the scenes' `run` bindings).
  subroutine integrate_scene(cfg, problem, y, rec, out_path, summary, error, monitor, &
                             progress)
    !> The checked configuration of the run.
    type(config_type), intent(in) :: cfg
    !> The scene's system.
    class(ode_problem), intent(inout) :: problem
    !> Its state: initial, then at the run's end.
    real(wp), intent(inout) :: y(:)
    !> The scene's recorder.
    class(recorder_type), intent(inout) :: rec
    !> Path of the HDF5 file written.
    character(len=*), intent(in) :: out_path
    !> Steps, evaluations, wall time and completion of the run.
    type(run_summary), intent(out) :: summary
    !> Set when the run cannot be set up, its file not written or it diverged.
    type(error_type), allocatable, intent(out) :: error
    !> Watches the accepted steps and may end the run (the boat scenes' launch log).
    class(step_monitor), intent(inout), optional :: monitor
    !> Progress line at a terminal (absent: none).
    type(progress_meter), intent(inout), optional :: progress
    type(h5_writer_type) :: writer
    type(error_type), allocatable :: run_error, io_error
    character(len=:), allocatable :: kept
    logical :: exists

    call writer%create(out_path, error)
    if (allocated(error)) return
    call integrate(cfg%simulation, problem, y, rec, summary, run_error, error, monitor, &
                   progress)
    if (allocated(error)) then
      call writer%discard()
      return
    end if
    call rec%write(problem, writer)
    if (present(monitor)) call monitor%write(problem, writer)
    call write_root_attributes(writer, cfg, summary, cfg%simulation%integrator, run_error)
    ! A failed run never replaces an existing output: its partial record goes beside it.
    kept = out_path
    if (allocated(run_error)) then
      inquire (file=out_path, exist=exists)
      if (exists) then
        kept = partial_path(out_path)
        call check_output_path(kept, io_error)
        if (allocated(io_error)) then  ! OUT.partial.h5 is someone else's file: keep it
          call writer%discard()
          call move_alloc(run_error, error)
          error%message = error%message//"; partial record not kept: "// &
                          io_error%message//"; the earlier '"//out_path// &
                          "' is left as it was"
          return
        end if
      end if
      call writer%retarget(kept)
    end if
    call writer%close(io_error)
    if (allocated(run_error)) then
      call move_alloc(run_error, error)
      if (allocated(io_error)) then
        error%message = error%message//"; "//io_error%message
      else if (kept /= out_path) then
        error%message = error%message//"; partial output kept in '"//kept// &
                        "' (attribute complete = 0); the earlier '"//out_path// &
                        "' is left as it was"
      else
        error%message = error%message//"; partial output kept in '"//out_path// &
                        "' (attribute complete = 0)"
      end if
    else if (allocated(io_error)) then
      call move_alloc(io_error, error)
    end if
  end subroutine integrate_scene

  !> OUT.partial.h5 for OUT.h5 (OUT.partial.h5 for a name without .h5 too).
  pure function partial_path(path) result(partial)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: partial
    integer :: n
    n = len(path)
    if (n > 3) then
      if (path(n - 2:) == ".h5") then
        partial = path(1:n - 3)//".partial.h5"
        return
      end if
    end if
    partial = path//".partial.h5"
  end function partial_path

  !> The time loop shared by all integrated scenes: from t = 0 to t_end, or until the
  !> monitor ends the run, sampling `rec` (in memory) at exact multiples of the output
  !> interval. A divergence or a failed step ends the loop with its message in run_error and
  !> the record so far kept; `error` reports a set-up failure only. `progress`, if given,
  !> is told the time after every step (it redraws on its own clock). davit_capi_session
  !> steps the same loop one pass at a time: a change here goes there too (test_capi and
  !> test_library compare them).
  subroutine integrate(sim, problem, y, rec, summary, run_error, error, monitor, progress)
    !> The &simulation settings (integrator, tolerances, steps, t_end, output interval).
    type(simulation_config), intent(in) :: sim
    !> The system integrated.
    class(ode_problem), intent(inout) :: problem
    !> State vector: in the initial state, out the last one.
    real(wp), intent(inout) :: y(:)
    !> The recorder sampled at each output time.
    class(recorder_type), intent(inout) :: rec
    !> Steps, evaluations, wall times and completion.
    type(run_summary), intent(out) :: summary
    !> Why the loop ended early (divergence, failed step; the record so far kept), and a
    !> set-up failure.
    type(error_type), allocatable, intent(out) :: run_error, error
    !> Watches each accepted step and may end the run (launch log).
    class(step_monitor), intent(inout), optional :: monitor
    !> Progress line at a terminal.
    type(progress_meter), intent(inout), optional :: progress
    class(integrator_type), allocatable :: integ
    type(event_stepper_type) :: stepper
    real(wp) :: t, t_next, t_new, h
    integer(i8) :: k, nsamples, clock0, clock1, rate, tick, last_tick, sample_tick
    integer :: bad
    logical :: done, event

    call new_integrator(sim%integrator, size(y), integ, error, sim%rtol, sim%atol, &
                        fixed_step=sim%fixed_step, substeps=sim%substeps)
    if (allocated(error)) return
    ! adaptive integrators return after each accepted step: the history, the monitors
    ! and event location see every step, and dt is the largest step
    integ%single_step = .true.
    call stepper%init(size(y), problem%n_modes())
    ! Samples at exact multiples of the output interval; each step is the deck's dt or what
    ! the problem allows (problem%max_step, e.g. near a contact), shortened to land on the
    ! next sample (stretched by up to 1 % rather than leave a sliver step).
    nsamples = int(sim%t_end/sim%output_interval + 1.0e-9_wp, i8)
    call rec%init(problem, int(nsamples) + 1)
    t = 0.0_wp
    k = 1
    call rec%sample(problem, t, y)
    done = .false.
    if (present(monitor)) call monitor%watch(problem, t, y, done)
    call system_clock(clock0, rate)
    last_tick = clock0
    sample_tick = clock0
    if (present(progress)) call progress%start(sim%t_end)
    do while (t < sim%t_end .and. .not. done)
      t_next = min(real(k, wp)*sim%output_interval, sim%t_end)
      h = problem%max_step(t, y, sim%dt)
      t_new = merge(t_next, t + h, stretch_to(h, t_next - t))
      ! a step cut at an event (a contact phase switch, a link going slack or taut) ends
      ! just past it, for after_step to switch there
      call stepper%step(integ, problem, t, y, t_new, event)
      if (integ%failed) then
        call fatal_error(run_error, "run stopped: "//integ%failure)
        exit
      end if
      bad = first_bad(y, rec%speed_range(problem))
      if (bad > 0) then
        call fatal_error(run_error, "run diverged at t = "//fmt_real(t)//" s: "// &
                         rec%state_name(problem, bad)//" = "//fmt_real(y(bad))//" is not finite"// &
                         " or beyond "//fmt_real(speed_limit)//" (step size "// &
                         fmt_real(integ%stiff_step(h))//" s may exceed the stability limit)")
        exit
      end if
      call problem%after_step(t, y)
      if (present(monitor)) call monitor%watch(problem, t, y, done)
      if (present(progress)) call progress%update(t)
      if (t == t_next .and. k <= nsamples) then
        call rec%sample(problem, t, y)
        k = k + 1
      else if (done) then
        ! a run the monitor ends between samples still records its last state
        call rec%sample(problem, t, y)
      end if
      ! what a real-time user meets: the slowest step, and the slowest output interval
      ! (a frame), in wall time
      call system_clock(tick)
      call summary%worst_step%note(real(tick - last_tick, wp)/real(rate, wp), t)
      last_tick = tick
      if (t == t_next) then
        call summary%worst_interval%note(real(tick - sample_tick, wp)/real(rate, wp), t)
        sample_tick = tick
      end if
    end do
    call system_clock(clock1)
    if (present(progress)) call progress%finish(t)
    summary%steps = integ%steps
    summary%rhs_evaluations = integ%rhs_evaluations
    summary%wall_time = real(clock1 - clock0, wp)/real(rate, wp)
    summary%samples = rec%n
    summary%complete = .not. allocated(run_error)
  end subroutine integrate

  !> Index of the first non-finite state component, or of a speed (indices in
  !> speeds(1):speeds(2)) beyond any physical value, which marks a blow-up early.
  pure integer function first_bad(y, speeds)
    !> State vector.
    real(wp), intent(in) :: y(:)
    !> First and last index of the speeds checked against physical bounds.
    integer, intent(in) :: speeds(2)
    integer :: k
    first_bad = 0
    do k = 1, size(y)
      if (.not. ieee_is_finite(y(k)) .or. &
          (k >= speeds(1) .and. k <= speeds(2) .and. abs(y(k)) > speed_limit)) then
        first_bad = k
        return
      end if
    end do
  end function first_bad

end module davit_run_driver
