!> A one-line progress meter on stderr for a long `davit run` at a terminal: simulated time
!> against t_end, the real-time factor and the time left, redrawn in place (carriage return)
!> at most every half second of wall time, closed by a newline. Off when stderr is not a
!> terminal, so logs, pipes and the sweeps' workers stay free of it; a run shorter than the
!> first interval draws nothing.
module davit_run_progress
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: error_unit
  use davit_kinds, only: wp, i8
  use davit_io_text, only: fmt_fixed
  implicit none
  private
  public :: progress_meter, new_progress_meter, stderr_is_terminal

  !> Wall-clock seconds between redraws (also before the first one).
  real(wp), parameter :: redraw_interval = 0.5_wp

  type :: progress_meter
    private
    logical :: enabled = .false.
    logical :: shown = .false.
    real(wp) :: t_end = 0.0_wp
    integer(i8) :: clock0 = 0, last = 0, rate = 1
    !> Length of the line drawn last, blanked when a shorter one replaces it.
    integer :: width = 0
  contains
    procedure :: start
    procedure :: update
    procedure :: finish
  end type progress_meter

  interface
    function c_isatty(fd) bind(c, name="isatty") result(yes)
      import :: c_int
      integer(c_int), value :: fd
      integer(c_int) :: yes
    end function c_isatty
  end interface

contains

  !> Whether file descriptor 2 (stderr) is a terminal.
  logical function stderr_is_terminal()
    stderr_is_terminal = c_isatty(2_c_int) == 1_c_int
  end function stderr_is_terminal

  !> A meter that draws when `enabled` (e.g. stderr_is_terminal()), else does nothing.
  function new_progress_meter(enabled) result(meter)
    !> Whether the meter draws.
    logical, intent(in) :: enabled
    type(progress_meter) :: meter
    meter%enabled = enabled
  end function new_progress_meter

  !> The run begins: it will go to simulated time t_end (s).
  subroutine start(self, t_end)
    !> The meter.
    class(progress_meter), intent(inout) :: self
    !> Simulated end time [s].
    real(wp), intent(in) :: t_end
    if (.not. self%enabled) return
    self%t_end = t_end
    self%shown = .false.
    self%width = 0
    call system_clock(self%clock0, self%rate)
    self%last = self%clock0
  end subroutine start

  !> The run has reached simulated time t; redraws if the interval has passed.
  subroutine update(self, t)
    !> The meter.
    class(progress_meter), intent(inout) :: self
    !> Simulated time reached [s].
    real(wp), intent(in) :: t
    integer(i8) :: now
    if (.not. self%enabled) return
    call system_clock(now)
    if (real(now - self%last, wp) < redraw_interval*real(self%rate, wp)) return
    self%last = now
    call draw(self, t, now)
  end subroutine update

  !> The run ended at simulated time t: the last line (if any was drawn) and a newline.
  subroutine finish(self, t)
    !> The meter.
    class(progress_meter), intent(inout) :: self
    !> Simulated end time reached [s].
    real(wp), intent(in) :: t
    integer(i8) :: now
    if (.not. (self%enabled .and. self%shown)) return
    call system_clock(now)
    call draw(self, t, now)
    write (error_unit, "(a)") ""
    flush (error_unit)
    self%shown = .false.
  end subroutine finish

  subroutine draw(self, t, now)
    type(progress_meter), intent(inout) :: self
    real(wp), intent(in) :: t
    integer(i8), intent(in) :: now
    character(len=:), allocatable :: line
    real(wp) :: wall, factor
    integer :: n
    wall = max(real(now - self%clock0, wp)/real(self%rate, wp), tiny(1.0_wp))
    factor = t/wall
    line = "davit: t = "//fmt_fixed(t, 2)//" / "//fmt_fixed(self%t_end, 2)//" s ("// &
           fmt_fixed(100.0_wp*t/max(self%t_end, tiny(1.0_wp)), 1)//" %), "// &
           fmt_fixed(factor, 1)//"x real time, ETA "//eta_text(self%t_end - t, factor)
    n = len_trim(line)
    ! blank what is left of a longer earlier line
    write (error_unit, "(a)", advance="no") achar(13)//line// &
      repeat(" ", max(self%width - n, 0))
    flush (error_unit)
    self%width = n
    self%shown = .true.
  end subroutine draw

  !> Wall time left at `factor` x real time for `left` simulated seconds: "M:SS" or
  !> "H:MM:SS"; "--" before anything has been simulated.
  function eta_text(left, factor) result(text)
    real(wp), intent(in) :: left, factor
    character(len=:), allocatable :: text
    character(len=32) :: buf
    integer(i8) :: s
    if (factor <= 0.0_wp) then
      text = "--"
      return
    end if
    s = nint(max(left, 0.0_wp)/factor, i8)
    if (s >= 3600_i8) then
      write (buf, "(i0,a,i2.2,a,i2.2)") s/3600_i8, ":", mod(s, 3600_i8)/60_i8, ":", &
        mod(s, 60_i8)
    else
      write (buf, "(i0,a,i2.2)") s/60_i8, ":", mod(s, 60_i8)
    end if
    text = trim(buf)
  end function eta_text

end module davit_run_progress
