!> The pose of a rigid body: where its reference point is, how it is turned, how it moves.
!> One type for every body and force model (the ship carrying the davit and the side
!> plane, the boat at its hooks), so a pose travels as one argument.
module davit_core_pose
  use davit_kinds, only: wp
  use davit_core_rotation, only: cross
  implicit none
  private
  public :: pose_type, pose_point, pose_point_velocity

  !> Reference point r (inertial) [m], rotation c (body -> inertial components, eq. 2),
  !> velocity v of the reference point and angular velocity w, both inertial components.
  type :: pose_type
    !> Reference point r (inertial) [m]; rotation c (body -> inertial); velocity v [m/s]
    !> and angular velocity w [rad/s] of the body, inertial components.
    real(wp) :: r(3) = 0.0_wp, c(3, 3) = 0.0_wp, v(3) = 0.0_wp, w(3) = 0.0_wp
  end type pose_type

contains

  !> Inertial position of the body point a (body components, from the reference point).
  pure function pose_point(pose, a) result(p)
    !> The body's pose.
    type(pose_type), intent(in) :: pose
    !> Body point from the reference point, body components [m].
    real(wp), intent(in) :: a(3)
    real(wp) :: p(3)
    p = pose%r + matmul(pose%c, a)
  end function pose_point

  !> Inertial velocity of the body point a: v + w x (c a).
  pure function pose_point_velocity(pose, a) result(v)
    !> The body's pose.
    type(pose_type), intent(in) :: pose
    !> Body point from the reference point, body components [m].
    real(wp), intent(in) :: a(3)
    real(wp) :: v(3)
    v = pose%v + cross(pose%w, matmul(pose%c, a))
  end function pose_point_velocity

end module davit_core_pose
