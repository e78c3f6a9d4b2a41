!> Where the davit's falls end at a state: the two hooks (on the boat) and the ship that
!> carries the davit heads, lead sheave and drum. The rigging's evaluations (Kane blocks,
!> tensions, block balance) take these three together, as one argument, from the system
!> (davit_system_parameters's falls_ends_at) or from a test's fixed ends.
module davit_rigging_falls_ends
  use davit_kinds, only: wp
  use davit_core_pose, only: pose_type
  implicit none
  private
  public :: falls_ends_type

  !> The falls' two lower ends and the ship their upper ends move with.
  type :: falls_ends_type
    !> Positions [m] and velocities [m/s] of the hooks, inertial components, one column
    !> per sling (fore, aft).
    real(wp) :: hook_pos(3, 2) = 0.0_wp, hook_vel(3, 2) = 0.0_wp
    !> The ship's pose (the davit heads, sheaves and drum move with it).
    type(pose_type) :: ship
  end type falls_ends_type

end module davit_rigging_falls_ends
