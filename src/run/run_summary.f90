!> What every run reports: integrator statistics and completion, shared by all scenes
!> (written as the output file's root attributes by davit_run_scenario).
module davit_run_run_summary
  use davit_kinds, only: wp, i8
  implicit none
  private
  public :: run_summary

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

end module davit_run_run_summary
