!> Rotation matrix and Euler-angle kinematics (paper eqs. 1-2 and 5).
!>
!> Convention (review §0): N3 points down; the body frame is x forward, y starboard, z down;
!> theta = (roll, pitch, yaw), C = Rz(theta3) Ry(theta2) Rx(theta1) maps body components to
!> inertial ones, v_N = C v_b.
module davit_core_rotation
  use davit_kinds, only: wp
  use davit_core_fastmath, only: fast_sincos
  implicit none
  private
  public :: rotation_matrix, euler_rates, cross, skew, length3

contains

  !> Eq. (2): C = Rz(theta3) Ry(theta2) Rx(theta1).
  pure function rotation_matrix(theta) result(c)
    !> Euler angles (roll, pitch, yaw) [rad].
    real(wp), intent(in) :: theta(3)
    real(wp) :: c(3, 3)
    real(wp) :: s1, s2, s3, c1, c2, c3, sn(3), cs(3)
    ! the three angles' sines and cosines in one branch-free pass: every right-hand side
    ! forms several of these matrices, and libm's sincos is a call per angle
    call fast_sincos(theta, sn, cs)
    s1 = sn(1); c1 = cs(1)
    s2 = sn(2); c2 = cs(2)
    s3 = sn(3); c3 = cs(3)
    c(1, :) = [c2*c3, s1*s2*c3 - s3*c1, c1*s2*c3 + s3*s1]
    c(2, :) = [c2*s3, s1*s2*s3 + c1*c3, c1*s2*s3 - c3*s1]
    c(3, :) = [-s2, s1*c2, c1*c2]
  end function rotation_matrix

  !> Eq. (5): Euler-angle rates from the body angular velocity omega (body components).
  !> Singular at theta2 = +-90 deg, which a hanging or floating lifeboat never reaches.
  pure function euler_rates(theta, omega) result(rates)
    !> Euler angles theta (roll, pitch, yaw) [rad] and angular velocity omega, body
    !> components [rad/s].
    real(wp), intent(in) :: theta(3), omega(3)
    real(wp) :: rates(3)
    real(wp) :: s1, c1, c2, t, sn(2), cs(2)
    call fast_sincos(theta(1:2), sn, cs)
    s1 = sn(1); c1 = cs(1); c2 = cs(2)
    t = omega(2)*s1 + omega(3)*c1
    rates(1) = omega(1) + sn(2)/c2*t
    rates(2) = omega(2)*c1 - omega(3)*s1
    rates(3) = t/c2
  end function euler_rates

  pure function cross(a, b) result(c)
    !> The two vectors of the cross product a x b.
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross

  !> Euclidean length of a 3-vector, sqrt(a . a): the rigging's hot paths take it per
  !> segment and evaluation, and gfortran's NORM2 guards against overflow with a scaled
  !> sum (divisions per element) that lengths in metres never need.
  pure real(wp) function length3(a) result(l)
    !> The vector.
    real(wp), intent(in) :: a(3)
    l = sqrt(a(1)*a(1) + a(2)*a(2) + a(3)*a(3))
  end function length3

  !> Skew matrix: skew(a) b = a x b.
  pure function skew(a) result(s)
    !> Vector a of a x b.
    real(wp), intent(in) :: a(3)
    real(wp) :: s(3, 3)
    s(1, :) = [0.0_wp, -a(3), a(2)]
    s(2, :) = [a(3), 0.0_wp, -a(1)]
    s(3, :) = [-a(2), a(1), 0.0_wp]
  end function skew

end module davit_core_rotation
