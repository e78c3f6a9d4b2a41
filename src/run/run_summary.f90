!> What every run reports: integrator statistics and completion, shared by all scenes
!> (written as the output file's root attributes by davit_run_scenario).
module davit_run_run_summary
  use davit_kinds, only: wp, i8
  implicit none
  private
  public :: run_summary, worst_wall

  !> The longest wall time of one piece of a run (a step, an output interval) and the
  !> simulated time that piece ended at.
  type :: worst_wall
    !> The longest wall time [s].
    real(wp) :: wall = 0.0_wp
    !> The simulated time the longest piece ended at [s].
    real(wp) :: at = 0.0_wp
  contains
    procedure :: note
  end type worst_wall

  type :: run_summary
    !> Accepted steps and right-hand-side evaluations.
    integer(i8) :: steps = 0, rhs_evaluations = 0
    !> Wall time of the run [s].
    real(wp) :: wall_time = 0.0_wp
    !> The longest wall time of one step (step, events, history, monitors, sample) and of
    !> one output interval (a frame of a live display), each with the simulated time it
    !> ended at: what a real-time user needs beside the totals.
    type(worst_wall) :: worst_step, worst_interval
    !> Samples recorded.
    integer :: samples = 0
    !> Whether the run reached its end time (or the launch's end).
    logical :: complete = .false.
    !> The launch's outcome, peaks and rule checks in words (boat scenes; else empty).
    character(len=:), allocatable :: report
  end type run_summary

contains

  !> A piece of the run that took `wall` seconds and ended at simulated time t: kept where
  !> it is the longest so far.
  pure subroutine note(self, wall, t)
    !> The longest piece so far.
    class(worst_wall), intent(inout) :: self
    !> Wall time of the piece [s] and the simulated time it ended at [s].
    real(wp), intent(in) :: wall, t
    if (wall <= self%wall) return
    self%wall = wall
    self%at = t
  end subroutine note

end module davit_run_run_summary
