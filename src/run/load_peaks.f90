!> Peak tensions over every accepted step and the limits they are checked against: the
!> wire's minimum breaking load (MBL) and safe working load (MBL over the falls' factor of
!> safety), and the lateral impact speed. For each limit: the first time it is exceeded
!> (-1: never) and the time spent beyond it.
module davit_run_load_peaks
  use davit_kinds, only: wp
  implicit none
  private
  public :: load_peaks, limit_watch

  !> One limit: its value, first exceedance [s] and total time beyond it [s].
  type :: limit_watch
    !> The limit [N or m/s] (huge: none), first time beyond it [s] (-1: never), total time beyond
    !> [s].
    real(wp) :: value = huge(1.0_wp), first = -1.0_wp, duration = 0.0_wp
    !> Number of exceedances.
    integer :: count = 0
    !> Whether the last value was beyond the limit.
    logical :: beyond = .false.
  end type limit_watch

  type :: load_peaks
    !> Peak tension of each cable segment and each sling [N] and when [s].
    real(wp), allocatable :: segment(:), segment_time(:), sling(:), sling_time(:)
    !> Watches of the safe working load (MBL/safety factor) and the MBL of the wire [N], and of
    !> the impact speed limit [m/s].
    type(limit_watch) :: swl, mbl, impact
    !> Largest impact speed [m/s]; time of the last update [s].
    real(wp) :: max_impact_speed = 0.0_wp, t_prev = 0.0_wp
  contains
    procedure :: init => peaks_init
    procedure :: update => peaks_update
    procedure :: impact_at => peaks_impact
  end type load_peaks

contains

  subroutine peaks_init(self, nseg, nsling, mbl, safety_factor, impact_speed)
    !> The peaks, reset.
    class(load_peaks), intent(inout) :: self
    !> Number of cable segments and of slings.
    integer, intent(in) :: nseg, nsling
    !> Minimum breaking load of the wire [N], safety factor of the safe working load, impact speed
    !> limit [m/s].
    real(wp), intent(in) :: mbl, safety_factor, impact_speed
    allocate (self%segment(nseg), self%segment_time(nseg), source=0.0_wp)
    allocate (self%sling(nsling), self%sling_time(nsling), source=0.0_wp)
    self%mbl%value = mbl
    self%swl%value = mbl/safety_factor
    self%impact%value = impact_speed
  end subroutine peaks_init

  !> Tensions of the cable segments and of the slings (largest over each sling's
  !> segments) after the step ending at t.
  subroutine peaks_update(self, t, segment, sling)
    !> The peaks.
    class(load_peaks), intent(inout) :: self
    !> End of the step [s]; cable segment tensions [N]; each sling's tension [N].
    real(wp), intent(in) :: t, segment(:), sling(:)
    real(wp) :: largest
    where (segment > self%segment)
      self%segment = segment
      self%segment_time = t
    end where
    where (sling > self%sling)
      self%sling = sling
      self%sling_time = t
    end where
    largest = max(max(0.0_wp, maxval(segment)), max(0.0_wp, maxval(sling)))
    call check(self%swl, t, t - self%t_prev, largest)
    call check(self%mbl, t, t - self%t_prev, largest)
    self%t_prev = t
  end subroutine peaks_update

  !> An impact at t with normal speed `speed`.
  subroutine peaks_impact(self, t, speed)
    !> The peaks.
    class(load_peaks), intent(inout) :: self
    !> Time of the impact [s] and its normal speed [m/s].
    real(wp), intent(in) :: t, speed
    self%max_impact_speed = max(self%max_impact_speed, speed)
    call check(self%impact, t, 0.0_wp, speed)
    self%impact%beyond = .false.
  end subroutine peaks_impact

  !> Count an excursion beyond the limit once, from its first step.
  subroutine check(w, t, h, x)
    type(limit_watch), intent(inout) :: w
    real(wp), intent(in) :: t, h, x
    if (x > w%value) then
      if (w%first < 0.0_wp) w%first = t
      if (.not. w%beyond) w%count = w%count + 1
      w%duration = w%duration + h
      w%beyond = .true.
    else
      w%beyond = .false.
    end if
  end subroutine check

end module davit_run_load_peaks
