!> The velocity of a boat point (an occupant's seat) resampled on a uniform grid from the
!> accepted steps (linear between steps: the steps are far shorter than the filter's period
!> near an impact), so that its acceleration can be low-pass filtered as crash-test practice
!> does; and the raw peak, the largest step-mean acceleration |Delta v/Delta t| over any
!> step.
module davit_run_seat_trace
  use davit_kinds, only: wp
  use davit_core_filters, only: lowpass_in_place
  implicit none
  private
  public :: seat_trace

  type :: seat_trace
    !> Grid interval [s] and the filter's -3 dB frequency [Hz].
    real(wp) :: dt = 1.0e-3_wp, cutoff = 20.0_wp
    !> Points on the grid so far.
    integer :: n = 0
    !> Velocity at t = (k - 1) dt, inertial [m/s], and the boat's rotation matrix (boat ->
    !> inertial, by columns) at the step that reached it.
    real(wp), allocatable :: v(:, :), axes(:, :)
    !> Time of the last step [s] and the seat's inertial velocity then [m/s].
    real(wp) :: t_last = -1.0_wp, v_last(3) = 0.0_wp
    !> Largest raw (unfiltered) step-mean acceleration [m/s^2], its time [s], and the last one
    !> [m/s^2].
    real(wp) :: raw_peak = 0.0_wp, raw_time = -1.0_wp, last_raw = 0.0_wp
  contains
    procedure :: add => trace_add
    procedure :: filtered => trace_filtered
    procedure :: body_filtered => trace_body_filtered
  end type seat_trace

contains

  !> The seat velocity v after the step ending at t (the first call is at t = 0), with the
  !> boat's rotation matrix c then.
  subroutine trace_add(self, t, v, c)
    !> The trace.
    class(seat_trace), intent(inout) :: self
    !> End of the step [s]; the seat's inertial velocity [m/s]; the boat's rotation (boat ->
    !> inertial).
    real(wp), intent(in) :: t, v(3), c(3, 3)
    real(wp) :: tk
    if (self%t_last < 0.0_wp) then
      allocate (self%v(3, 1024), self%axes(9, 1024))
      self%n = 1
      self%v(:, 1) = v
      self%axes(:, 1) = reshape(c, [9])
    else if (t > self%t_last) then
      self%last_raw = norm2(v - self%v_last)/(t - self%t_last)
      if (self%last_raw > self%raw_peak) then
        self%raw_peak = self%last_raw
        self%raw_time = t
      end if
      do
        tk = real(self%n, wp)*self%dt
        if (tk > t*(1.0_wp + epsilon(1.0_wp))) exit
        call grow(self)
        self%n = self%n + 1
        self%v(:, self%n) = self%v_last + (v - self%v_last)*(tk - self%t_last)/ &
                            (t - self%t_last)
        self%axes(:, self%n) = reshape(c, [9])
      end do
    end if
    self%t_last = t
    self%v_last = v
  end subroutine trace_add

  subroutine grow(self)
    type(seat_trace), intent(inout) :: self
    real(wp), allocatable :: bigger(:, :), axes(:, :)
    if (self%n < size(self%v, 2)) return
    allocate (bigger(3, 2*size(self%v, 2)), axes(9, 2*size(self%v, 2)))
    bigger(:, 1:self%n) = self%v(:, 1:self%n)
    axes(:, 1:self%n) = self%axes(:, 1:self%n)
    call move_alloc(bigger, self%v)
    call move_alloc(axes, self%axes)
  end subroutine grow

  !> Filtered acceleration at the grid's midpoints t = (k - 1/2) dt, k = 1..n-1, (3, n-1).
  pure function trace_filtered(self) result(a)
    !> The trace.
    class(seat_trace), intent(in) :: self
    real(wp), allocatable :: a(:, :)
    allocate (a(3, max(self%n - 1, 0)))
    if (self%n < 2) return
    a = (self%v(:, 2:self%n) - self%v(:, 1:self%n - 1))/self%dt
    call lowpass_components(self, a)
  end function trace_filtered

  !> The filtered acceleration in the boat's axes (x forward, y starboard, z down) at the
  !> grid's midpoints, (3, n-1): each step-mean acceleration turned into the axes of the
  !> step's end, then filtered as `filtered` does.
  pure function trace_body_filtered(self) result(a)
    !> The trace.
    class(seat_trace), intent(in) :: self
    real(wp), allocatable :: a(:, :)
    integer :: i
    allocate (a(3, max(self%n - 1, 0)))
    if (self%n < 2) return
    do i = 1, self%n - 1
      a(:, i) = matmul((self%v(:, i + 1) - self%v(:, i))/self%dt, &
                       reshape(self%axes(:, i + 1), [3, 3]))
    end do
    call lowpass_components(self, a)
  end function trace_body_filtered

  !> Each component of a (3, n) acceleration through the occupant filter.
  pure subroutine lowpass_components(self, a)
    class(seat_trace), intent(in) :: self
    real(wp), intent(inout) :: a(:, :)
    integer :: i
    do i = 1, size(a, 1)
      call lowpass_in_place(a(i, :), self%dt, self%cutoff)
    end do
  end subroutine lowpass_components

end module davit_run_seat_trace
