!> Each fender impact as an event, resolved at every accepted step (not at output samples):
!> onset time, fender, normal impact speed (the approach rate delta_dot of eq. 33 at the
!> first step with a contact force), peak normal force, peak CG acceleration, duration.
!> A contact episode of a fender runs from its first step with a force to its first step
!> without; a re-contact after that is a new event.
module davit_run_impact_events
  use davit_kinds, only: wp
  implicit none
  private
  public :: impact_event, impact_tracker

  type :: impact_event
    !> The fender that struck (1..nf).
    integer :: fender = 0
    !> Onset [s], duration [s], normal impact speed [m/s], peak force [N], peak step-mean
    !> CG and seat accelerations [m/s^2]; the seat's filtered peak is filled in at the end.
    real(wp) :: time = 0.0_wp, duration = 0.0_wp, speed = 0.0_wp, peak_force = 0.0_wp
    !> Peak step-mean CG acceleration, peak raw and filtered seat acceleration [m/s^2].
    real(wp) :: peak_acceleration = 0.0_wp, peak_seat_raw = 0.0_wp, peak_seat = 0.0_wp
  end type impact_event

  type :: impact_tracker
    !> Number of events recorded.
    integer :: n = 0
    !> The events, in order of onset.
    type(impact_event), allocatable :: events(:)
    !> Per fender: its open event, 0 while it does not touch.
    integer, allocatable :: open(:)
  contains
    procedure :: init => tracker_init
    procedure :: track => tracker_track
  end type impact_tracker

contains

  subroutine tracker_init(self, nfender)
    !> The tracker, emptied.
    class(impact_tracker), intent(inout) :: self
    !> Number of fenders.
    integer, intent(in) :: nfender
    self%n = 0
    allocate (self%events(16))
    allocate (self%open(nfender), source=0)
  end subroutine tracker_init

  !> The fenders' forces and approach rates after the step ending at t, with the step's
  !> mean CG and seat accelerations. `started` counts the events opened by this step.
  subroutine tracker_track(self, t, force, delta_dot, acceleration, seat, started)
    !> The tracker.
    class(impact_tracker), intent(inout) :: self
    !> End of the step [s]; each fender's normal force [N] and approach rate [m/s]; the step's mean
    !> CG and seat accelerations [m/s^2].
    real(wp), intent(in) :: t, force(:), delta_dot(:), acceleration, seat
    !> Number of events this step opened.
    integer, intent(out) :: started
    integer :: j, k
    started = 0
    do j = 1, size(force)
      k = self%open(j)
      if (force(j) > 0.0_wp) then
        if (k == 0) then
          call open_event(self, j, t, delta_dot(j))
          k = self%n
          started = started + 1
        end if
        associate (e => self%events(k))
          e%peak_force = max(e%peak_force, force(j))
          e%peak_acceleration = max(e%peak_acceleration, acceleration)
          e%peak_seat_raw = max(e%peak_seat_raw, seat)
          e%duration = t - e%time
        end associate
      else if (k > 0) then
        self%events(k)%duration = t - self%events(k)%time
        self%open(j) = 0
      end if
    end do
  end subroutine tracker_track

  subroutine open_event(self, fender, t, speed)
    type(impact_tracker), intent(inout) :: self
    integer, intent(in) :: fender
    real(wp), intent(in) :: t, speed
    type(impact_event), allocatable :: grown(:)
    if (self%n == size(self%events)) then
      allocate (grown(2*self%n))
      grown(1:self%n) = self%events(1:self%n)
      call move_alloc(grown, self%events)
    end if
    self%n = self%n + 1
    self%events(self%n) = impact_event(fender=fender, time=t, speed=speed)
    self%open(fender) = self%n
  end subroutine open_event

end module davit_run_impact_events
