!> The slow clock of the wave loads (`&simulation wave_update`, its interval h > 0; 0: off).
!>
!> Loads that vary on the wave time scale (seconds) but cost a sum over every wave
!> component per evaluation are sampled with their time rates at both ends of a window
!> [t1, t2] and interpolated in between by the cubic Hermite basis (davit_core_hermite;
!> error ~ (omega h)^4/384 of each component). Stages outside the window are evaluated
!> directly by the caller. The clock holds the window and the rule that moves it; the
!> samples stay with the loads that own them. Its users: the boat's strips and diffraction
!> (davit_boat_strip_waves, davit_boat_bem_water) and the ship's Froude-Krylov loads
!> (davit_ship_ship_model).
!>
!> Two window rules, kept because they sample at different times and so give different
!> (equally accurate) results:
!> - clock_reach: the window [t, t + h] opens at an accepted step t whenever the next step,
!>   if up to `reach` times the last one, could end past it (the strips: their samples
!>   also depend on where the boat is at t1, so the window follows the steps);
!> - clock_grid: the window is the grid interval [k h, (k + 1) h] that holds t, and moves by
!>   one interval with one new sample (the ship: its loads depend on time alone).
module davit_core_slow_clock
  use davit_kinds, only: wp
  use davit_core_hermite, only: hermite_weights, hermite_interpolate
  implicit none
  private
  public :: slow_clock_type, new_slow_clock
  public :: clock_reach, clock_grid, clock_kept, clock_shifted, clock_renewed

  !> Window rules (see the module's text).
  integer, parameter :: clock_reach = 1, clock_grid = 2
  !> What `advance` (clock_grid) did to the window: nothing; moved by one interval (the old
  !> far end is the new near end, whose samples the caller keeps); a new window (both ends
  !> to sample).
  integer, parameter :: clock_kept = 0, clock_shifted = 1, clock_renewed = 2
  !> Under clock_reach a window is renewed once the next step, if up to this many times
  !> the last one, could end past it, so all stages of steady steps stay inside.
  real(wp), parameter :: reach = 2.0_wp

  !> A slow clock: its interval, rule and current window.
  type :: slow_clock_type
    !> Window length h [s] (`&simulation wave_update`); 0: the clock is off.
    real(wp) :: interval = 0.0_wp
    !> Window rule: clock_reach or clock_grid.
    integer :: rule = clock_reach
    !> True while `window` holds sampled loads.
    logical :: valid = .false.
    !> The window [t1, t2] [s].
    real(wp) :: window(2) = 0.0_wp
    !> Time of the last accepted step seen [s] (clock_reach: the next step's reach).
    real(wp) :: t_last = 0.0_wp
  contains
    procedure :: enabled
    procedure :: covers
    procedure :: tick
    procedure :: open
    procedure :: invalidate
    procedure :: weights
    procedure :: interpolate
  end type slow_clock_type

contains

  !> A clock of window length `interval` [s] (0: off) moved by `rule`.
  pure function new_slow_clock(interval, rule) result(clock)
    !> Window length h [s] (`&simulation wave_update`), >= 0.
    real(wp), intent(in) :: interval
    !> Window rule: clock_reach or clock_grid.
    integer, intent(in) :: rule
    type(slow_clock_type) :: clock
    clock%interval = interval
    clock%rule = rule
  end function new_slow_clock

  !> True when the clock runs (interval > 0).
  pure logical function enabled(self)
    !> The clock.
    class(slow_clock_type), intent(in) :: self
    enabled = self%interval > 0.0_wp
  end function enabled

  !> True when a stage at time t [s] may interpolate in the window.
  pure logical function covers(self, t)
    !> The clock.
    class(slow_clock_type), intent(in) :: self
    !> Time of the stage [s].
    real(wp), intent(in) :: t
    covers = self%valid .and. t >= self%window(1) .and. t <= self%window(2)
  end function covers

  !> After an accepted step ending at t, by the clock's rule: what the owner of the window
  !> must sample. clock_grid moves the window onto the grid interval that holds t and
  !> answers clock_kept (nothing to sample), clock_shifted (the far end; the near end's
  !> samples are the old far end's) or clock_renewed (both ends). clock_reach records t and
  !> answers clock_renewed when the next step may leave the window, else clock_kept; the
  !> owner then samples [t, t + h] and opens it (`open`), or keeps the old window when it
  !> needs none (the strips, with no strip that may get wet).
  pure subroutine tick(self, t, action)
    !> The clock.
    class(slow_clock_type), intent(inout) :: self
    !> End of the accepted step [s].
    real(wp), intent(in) :: t
    !> clock_kept, clock_shifted or clock_renewed.
    integer, intent(out) :: action
    if (self%rule == clock_grid) then
      call grid_advance(self, t, action)
    else
      action = merge(clock_renewed, clock_kept, reach_due(self, t))
      self%t_last = t
    end if
  end subroutine tick

  !> Whether, under clock_reach, the next step, if up to `reach` times the last one, may
  !> end past the window (or there is none, or t lies before it).
  pure logical function reach_due(self, t)
    type(slow_clock_type), intent(in) :: self
    real(wp), intent(in) :: t
    reach_due = .not. self%valid .or. t < self%window(1) .or. &
                t + reach*max(t - self%t_last, 0.0_wp) > self%window(2)
  end function reach_due

  !> Open the window [t, t + h] (clock_reach), valid from now on (the caller samples its
  !> ends).
  pure subroutine open(self, t)
    !> The clock.
    class(slow_clock_type), intent(inout) :: self
    !> Start of the window [s].
    real(wp), intent(in) :: t
    self%window = [t, t + self%interval]
    self%valid = .true.
  end subroutine open

  !> Move the window onto the grid interval [k h, (k + 1) h] that holds t (clock_grid).
  pure subroutine grid_advance(self, t, action)
    type(slow_clock_type), intent(inout) :: self
    real(wp), intent(in) :: t
    integer, intent(out) :: action
    real(wp) :: t0
    t0 = self%interval*floor(t/self%interval)
    if (self%valid .and. t0 == self%window(1)) then
      action = clock_kept
      return
    end if
    if (self%valid .and. t0 == self%window(2)) then
      action = clock_shifted
      self%window(1) = self%window(2)
    else
      action = clock_renewed
      self%window(1) = t0
    end if
    self%window(2) = t0 + self%interval
    self%valid = .true.
  end subroutine grid_advance

  !> The window's samples no longer hold (the loads they sample changed).
  pure subroutine invalidate(self)
    !> The clock.
    class(slow_clock_type), intent(inout) :: self
    self%valid = .false.
  end subroutine invalidate

  !> Hermite weights (h00, h h10, h01, h h11) at time t [s] in the window.
  pure function weights(self, t) result(hw)
    !> The clock.
    class(slow_clock_type), intent(in) :: self
    !> Time [s].
    real(wp), intent(in) :: t
    real(wp) :: hw(4)
    hw = hermite_weights(self%window, t)
  end function weights

  !> The cubic through values f1, f2 and rates d1, d2 sampled at the window's ends, at t.
  pure function interpolate(self, f1, d1, f2, d2, t) result(f)
    !> The clock.
    class(slow_clock_type), intent(in) :: self
    !> Values f1, f2 and rates d1, d2 at the window's ends.
    real(wp), intent(in) :: f1(:), d1(:), f2(:), d2(:)
    !> Time [s].
    real(wp), intent(in) :: t
    real(wp) :: f(size(f1))
    f = hermite_interpolate(self%window, f1, d1, f2, d2, t)
  end function interpolate

end module davit_core_slow_clock
