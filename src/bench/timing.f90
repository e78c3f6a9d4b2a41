!> What one timed piece of `davit bench` reports, and the clock it is timed with. The rates
!> are derived from the stored counts and times, never measured on their own, so the
!> printed table and the HDF5 file agree with each other by construction.
module davit_bench_timing
  use davit_kinds, only: wp, i8
  use davit_bench_accuracy, only: accuracy_type
  implicit none
  private
  public :: timed_run, wall_seconds, per_wall

  !> One timed run of a deck, or the cases of a sweep deck on a number of threads.
  type :: timed_run
    !> Label of the benchmark and the deck it ran (as opened).
    character(len=:), allocatable :: name, deck
    !> Runs timed together (1, or the sweep's cases) and the OpenMP threads they ran on.
    integer :: cases = 1, threads = 1
    !> Time step [s]: the deck's, or the one set from the stability limit.
    real(wp) :: dt = 0.0_wp
    !> Simulated time, summed over a sweep's cases [s], and wall time of the timed section
    !> (a scene's time loop; a sweep's whole parallel loop) [s].
    real(wp) :: simulated = 0.0_wp, wall = 0.0_wp
    !> A scene's set-up wall time (deck read, system built: BEM databases, sea, rigging)
    !> [s], the longest single step and the longest output interval in wall time [s]
    !> (what a real-time user meets; 0 for sweeps).
    real(wp) :: setup = 0.0_wp, worst_step = 0.0_wp, worst_interval = 0.0_wp
    !> The run driver's counters (summed over a sweep's cases).
    integer(i8) :: steps = 0, rhs_evaluations = 0
    !> A scene's errors against its converged reference (unknown for sweeps).
    type(accuracy_type) :: accuracy
  end type timed_run

contains

  !> Monotonic wall-clock reading [s]; system_clock with a 64-bit count ticks in ns.
  real(wp) function wall_seconds() result(t)
    integer(i8) :: count, rate
    call system_clock(count, rate)
    t = real(count, wp)/real(rate, wp)
  end function wall_seconds

  !> A count or simulated time of a run per wall second of it (RHS/s, steps/s, real-time
  !> factor).
  elemental real(wp) function per_wall(run, amount)
    !> A timed run.
    type(timed_run), intent(in) :: run
    !> The amount done in the run's wall time (evaluations, steps, simulated seconds).
    real(wp), intent(in) :: amount
    per_wall = amount/positive(run%wall)
  end function per_wall

  !> A wall time below the clock's tick still divides (a rate, not a division by zero).
  elemental real(wp) function positive(seconds)
    !> Wall time [s].
    real(wp), intent(in) :: seconds
    positive = max(seconds, 1.0e-9_wp)
  end function positive

end module davit_bench_timing
