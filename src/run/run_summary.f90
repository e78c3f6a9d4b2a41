!> What every run reports: integrator statistics, completion, and the root attributes of
!> the output file, shared by all scenes.
module davit_run_run_summary
  use davit_kinds, only: wp, i8, davit_version
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_run_scenario, only: write_scenario
  implicit none
  private
  public :: run_summary, write_root_attributes

  type :: run_summary
    !> Accepted steps and right-hand-side evaluations.
    integer(i8) :: steps = 0, rhs_evaluations = 0
    !> Wall time of the run [s].
    real(wp) :: wall_time = 0.0_wp
    !> The longest wall time of one step (step, events, history, monitors, sample) [s] and
    !> the simulated time it ended at [s]; the longest wall time of one output interval (a
    !> frame of a live display) [s] and the time it ended at [s]: what a real-time user
    !> needs beside the totals.
    real(wp) :: worst_step = 0.0_wp, worst_step_time = 0.0_wp
    !> Longest wall time of one output interval [s] and the simulated time it ended at [s].
    real(wp) :: worst_interval = 0.0_wp, worst_interval_time = 0.0_wp
    !> Samples recorded.
    integer :: samples = 0
    !> Whether the run reached its end time (or the launch's end).
    logical :: complete = .false.
    !> The launch's outcome, peaks and rule checks in words (boat scenes; else empty).
    character(len=:), allocatable :: report
  contains
    procedure :: note_step
    procedure :: note_interval
  end type run_summary

contains

  !> A step that took `wall` seconds and ended at simulated time t.
  pure subroutine note_step(self, wall, t)
    !> The summary.
    class(run_summary), intent(inout) :: self
    !> Wall time of the step [s] and the simulated time it ended at [s].
    real(wp), intent(in) :: wall, t
    call keep_worst(self%worst_step, self%worst_step_time, wall, t)
  end subroutine note_step

  !> An output interval that took `wall` seconds and ended at simulated time t.
  pure subroutine note_interval(self, wall, t)
    !> The summary.
    class(run_summary), intent(inout) :: self
    !> Wall time of the interval [s] and the simulated time it ended at [s].
    real(wp), intent(in) :: wall, t
    call keep_worst(self%worst_interval, self%worst_interval_time, wall, t)
  end subroutine note_interval

  !> (worst, at) = (wall, t) where wall exceeds worst.
  pure subroutine keep_worst(worst, at, wall, t)
    real(wp), intent(inout) :: worst, at
    real(wp), intent(in) :: wall, t
    if (wall <= worst) return
    worst = wall
    at = t
  end subroutine keep_worst

  !> davit_version, input file and deck text, seed, integrator statistics, completion;
  !> and /scenario (what the run simulated, davit_run_scenario) unless `scenario` is false
  !> (the RAO runs, which sweep their own waves).
  subroutine write_root_attributes(w, cfg, summary, integrator, run_error, scenario)
    !> The open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> The run's statistics.
    type(run_summary), intent(in) :: summary
    !> Name of the integrator used.
    character(len=*), intent(in) :: integrator
    !> Why the run ended early (unallocated: it did not).
    type(error_type), allocatable, intent(in) :: run_error
    !> Write /scenario (default: yes).
    logical, intent(in), optional :: scenario
    call w%attr_str("/", "davit_version", davit_version)
    call w%attr_str("/", "input_file", cfg%filename)
    call w%attr_str("/", "input_namelist", cfg%deck_text)
    call w%attr_str("/", "scene", cfg%simulation%scene)
    call w%attr_int("/", "seed", int(cfg%simulation%seed, i8))
    call w%attr_str("/", "integrator", integrator)
    call w%attr_real("/", "dt", cfg%simulation%dt)
    call w%attr_int("/", "steps", summary%steps)
    call w%attr_int("/", "rhs_evaluations", summary%rhs_evaluations)
    call w%attr_real("/", "wall_time", summary%wall_time)
    call w%attr_real("/", "worst_step_wall", summary%worst_step)
    call w%attr_real("/", "worst_step_at", summary%worst_step_time)
    call w%attr_real("/", "worst_interval_wall", summary%worst_interval)
    call w%attr_real("/", "worst_interval_at", summary%worst_interval_time)
    call w%attr_int("/", "complete", merge(1_i8, 0_i8, summary%complete))
    if (allocated(run_error)) then
      call w%attr_str("/", "status", run_error%message)
    else
      call w%attr_str("/", "status", "ok")
    end if
    if (.not. present(scenario)) then
      call write_scenario(w, cfg)
    else if (scenario) then
      call write_scenario(w, cfg)
    end if
  end subroutine write_root_attributes

end module davit_run_run_summary
