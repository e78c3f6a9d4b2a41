!> The shared state of a running sweep (the rows, the counters and the clocks that the
!> critical section of davit_sweep_driver updates) and the progress line it prints on
!> stderr: cases done, failures, the rate and the time left.
module davit_sweep_progress
  use, intrinsic :: iso_fortran_env, only: error_unit
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type
  use davit_io_namelist, only: int_to_str
  use davit_io_text, only: fmt_fixed
  use davit_sweep_metrics, only: case_result
  implicit none
  private
  public :: sweep_state, report_progress, seconds_since, fmt_duration

  !> What the critical section shares: the rows, counters, clocks of the last progress line
  !> and checkpoint, and the first I/O failure.
  type :: sweep_state
    !> One row per case.
    type(case_result), allocatable :: results(:)
    !> Cases finished, failed, to run; threads.
    integer :: done = 0, failed = 0, todo = 0, threads = 1
    !> Clock counts at the start, per second, at the last progress line and at the last checkpoint.
    integer(i8) :: clock0 = 0, rate = 1, last_progress = 0, last_checkpoint = 0
    !> The first I/O failure inside the loop (reported at the end).
    type(error_type), allocatable :: io_error
  end type sweep_state

contains

  !> "davit sweep: 12/80 cases (1 failed), 0.41 cases/s, ETA 2 min 21 s" on stderr.
  subroutine report_progress(state)
    !> Counters and clocks.
    type(sweep_state), intent(in) :: state
    real(wp) :: elapsed, rate
    character(len=:), allocatable :: line
    elapsed = seconds_since(state, state%clock0)
    rate = real(state%done, wp)/max(elapsed, 1.0e-9_wp)
    line = "davit sweep: "//int_to_str(state%done)//"/"//int_to_str(state%todo)// &
           " cases ("//int_to_str(state%failed)//" failed), "//fmt_fixed(rate, 3)//" cases/s"
    if (state%done < state%todo) then
      line = line//", ETA "//fmt_duration(real(state%todo - state%done, wp)/rate)
    else
      line = line//", "//fmt_duration(elapsed)
    end if
    write (error_unit, "(a)") line
    flush (error_unit)
  end subroutine report_progress

  real(wp) function seconds_since(state, clock) result(dt)
    !> The clock rate.
    type(sweep_state), intent(in) :: state
    !> A clock count (system_clock).
    integer(i8), intent(in) :: clock
    integer(i8) :: now
    call system_clock(now)
    dt = real(now - clock, wp)/real(state%rate, wp)
  end function seconds_since

  !> "2 h 5 min", "3 min 21 s" or "42 s".
  function fmt_duration(seconds) result(s)
    !> Duration [s].
    real(wp), intent(in) :: seconds
    character(len=:), allocatable :: s
    integer :: t
    t = nint(max(seconds, 0.0_wp))
    if (t >= 3600) then
      s = int_to_str(t/3600)//" h "//int_to_str(mod(t, 3600)/60)//" min"
    else if (t >= 60) then
      s = int_to_str(t/60)//" min "//int_to_str(mod(t, 60))//" s"
    else
      s = int_to_str(t)//" s"
    end if
  end function fmt_duration

end module davit_sweep_progress
