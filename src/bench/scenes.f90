!> `davit bench`, whole scenes: a boat deck run in memory through the run driver's time
!> loop (recorded as by `davit run`, but no file written), timed on the calling thread.
!> Optionally at the RK4 stability limit of the deck's linearised system, for the
!> paper-literal level of detail whose step the stiff lumps set.
module davit_bench_scenes
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type, read_config
  use davit_io_deck_reader, only: fmt_real
  use davit_system_model, only: system_type
  use davit_run_scene, only: scene_type, new_scene
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use davit_run_linear_modes, only: linear_modes
  use davit_run_launch_log, only: launch_log, new_launch_log
  use davit_bench_timing, only: timed_run, wall_seconds
  use davit_bench_accuracy, only: scene_accuracy
  implicit none
  private
  public :: step_limit, time_deck, rk4_bound, safety_factor

  !> RK4 is stable for h |lambda| <= 2.83 on the imaginary axis (README, Integrators).
  real(wp), parameter :: rk4_bound = 2.83_wp
  !> Margin below the limit at t = 0: the fastest rates move as the falls pay out.
  real(wp), parameter :: safety_factor = 0.9_wp

contains

  !> Run deck `path` for `t_end` seconds (its own t_end when t_end <= 0), at its own step
  !> or, with `at_limit`, at the step of step_limit. `rate_max` is the deck's largest
  !> |eigenvalue| at t = 0 when at_limit (else 0). The run's errors are measured against
  !> group `group` of the reference file `reference` (where it has one). A nonblank
  !> `integrator` replaces the deck's, with its tolerances and largest step dt, and its
  !> fast substeps when `substeps` > 0.
  subroutine time_deck(name, path, t_end, at_limit, reference, group, integrator, rtol, &
                       atol, dt, run, rate_max, error, substeps)
    !> Scene name, deck path, reference file, its group for the scene, and the integrator
    !> replacing the deck's (blank = the deck's).
    character(len=*), intent(in) :: name, path, reference, group, integrator
    !> Relative and absolute tolerances and largest step dt [s] of that integrator.
    real(wp), intent(in) :: rtol, atol, dt
    !> Simulated time [s] (<= 0: the deck's t_end).
    real(wp), intent(in) :: t_end
    !> Whether to run at the step of step_limit.
    logical, intent(in) :: at_limit
    !> The run's timings and counts.
    type(timed_run), intent(out) :: run
    !> Largest |eigenvalue| of the system at t = 0 [1/s] (0 unless at_limit).
    real(wp), intent(out) :: rate_max
    !> Set when the deck cannot be read or the run fails.
    type(error_type), allocatable, intent(out) :: error
    !> Fast substeps of the integrator (used when > 0).
    integer, intent(in), optional :: substeps
    type(config_type) :: cfg
    rate_max = 0.0_wp
    call read_config(path, cfg, error)
    if (allocated(error)) return
    if (len(integrator) > 0) then
      cfg%simulation%integrator = integrator
      cfg%simulation%rtol = rtol
      cfg%simulation%atol = atol
      cfg%simulation%dt = dt
      if (present(substeps)) then
        if (substeps > 0) cfg%simulation%substeps = substeps
      end if
    end if
    if (t_end > 0.0_wp) cfg%simulation%t_end = max(t_end, cfg%simulation%dt)
    if (at_limit) then
      call step_limit(cfg, rate_max, error)
      if (allocated(error)) return
    end if
    run%name = name
    run%deck = path
    call time_config(cfg, reference, group, run, error)
  end subroutine time_deck

  !> Set the deck's step to safety_factor x the RK4 limit rk4_bound/|lambda|max of its
  !> system at t = 0, rounded down to a whole fraction of the output interval (so that
  !> landing on every sample costs no extra short step).
  subroutine step_limit(cfg, rate_max, error)
    !> The deck's configuration, whose step is set.
    type(config_type), intent(inout) :: cfg
    !> Largest |eigenvalue| of the linearised system at t = 0 [1/s].
    real(wp), intent(out) :: rate_max
    !> Set when the system cannot be built or linearised.
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: omega_max, h
    call linear_modes(cfg, rate_max, omega_max, error)
    if (allocated(error)) return
    if (cfg%simulation%integrator /= "rk4" .or. .not. rate_max > 0.0_wp) then
      call fatal_error(error, cfg%filename//": the stability-limited bench scene needs "// &
                       "integrator = 'rk4' and a system with a nonzero fastest rate")
      return
    end if
    h = safety_factor*rk4_bound/rate_max
    cfg%simulation%dt = cfg%simulation%output_interval/ &
                        real(ceiling(cfg%simulation%output_interval/h), wp)
  end subroutine step_limit

  !> Build the boat scene of `cfg` and time its time loop (the driver's own clock and
  !> counters) with the launch log watching it, as `davit run` does: a launch ends where
  !> the run would (after_release past the hook release). A run that diverges is an
  !> error: its rates would mean nothing.
  subroutine time_config(cfg, reference, group, run, error)
    !> The configuration run.
    type(config_type), intent(in) :: cfg
    !> Reference file and its group for the scene.
    character(len=*), intent(in) :: reference, group
    !> The run's timings and counts (its name set by the caller).
    type(timed_run), intent(inout) :: run
    !> Set when the system cannot be built or the run diverges.
    type(error_type), allocatable, intent(out) :: error
    type(system_type) :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(launch_log) :: log
    type(error_type), allocatable :: run_error
    real(wp), allocatable :: y(:)
    real(wp) :: start
    class(scene_type), allocatable :: scene
    call new_scene(cfg%simulation%scene, scene, error)
    if (allocated(error)) return
    if (.not. scene%has_boat()) then
      call fatal_error(error, cfg%filename//": bench scenes run the boat scenes, not '"// &
                       cfg%simulation%scene//"'")
      return
    end if
    start = wall_seconds()
    call scene%build_boat(cfg, sys, y, error)
    if (allocated(error)) return
    log = new_launch_log(cfg, sys)
    run%setup = wall_seconds() - start
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, log)
    if (allocated(error)) return
    if (allocated(run_error)) then
      call fatal_error(error, cfg%filename//" (dt = "//fmt_real(cfg%simulation%dt)// &
                       " s): "//run_error%message)
      return
    end if
    run%threads = 1
    run%dt = cfg%simulation%dt
    ! the last sample is the last state: t_end, or where the launch log ended the run
    run%simulated = rec%time(rec%n)
    run%wall = summary%wall_time
    run%worst_step = summary%worst_step%wall
    run%worst_interval = summary%worst_interval%wall
    run%steps = summary%steps
    run%rhs_evaluations = summary%rhs_evaluations
    run%accuracy = scene_accuracy(reference, group, rec%time(1:rec%n), &
                                  rec%position(:, 1:rec%n), log%loads%sling, &
                                  log%loads%segment)
  end subroutine time_config

end module davit_bench_scenes
