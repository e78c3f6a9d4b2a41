!> A watcher the time loop calls at t = 0 and after every accepted step, for results that
!> need step resolution (peaks, minima, contact onsets) without recording every step. It
!> may end the run early (e.g. once the quantity of interest can no longer change).
module davit_run_step_monitor
  use davit_kinds, only: wp
  use davit_solve_integrator, only: ode_problem
  use davit_io_hdf5_writer, only: h5_writer_type
  implicit none
  private
  public :: step_monitor

  type, abstract :: step_monitor
  contains
    procedure(watch_interface), deferred :: watch
    !> What it found, into the run's output file (by default nothing).
    procedure :: write => write_nothing
  end type step_monitor

  abstract interface
    !> See the accepted state y at time t of the problem (after its after_step; read,
    !> never changed); set `done` to end the run after this step (the run still counts as
    !> complete).
    subroutine watch_interface(self, problem, t, y, done)
      import :: step_monitor, ode_problem, wp
      class(step_monitor), intent(inout) :: self
      class(ode_problem), intent(in) :: problem
      real(wp), intent(in) :: t, y(:)
      logical, intent(out) :: done
    end subroutine watch_interface
  end interface

contains

  subroutine write_nothing(self, problem, w)
    !> The monitor.
    class(step_monitor), intent(in) :: self
    !> The system of the run.
    class(ode_problem), intent(in) :: problem
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
  end subroutine write_nothing

end module davit_run_step_monitor
