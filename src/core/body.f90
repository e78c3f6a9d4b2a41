!> Kane blocks of one rigid body (paper eqs. 3-13 and 26).
!>
!> Generalized coordinates q = (theta1..3, q4..6) and speeds u = (omega_b, v_b), all in body
!> components. q4..6 are the CG position in body components, as in the paper (eq. 3), so the
!> kinematic relation is eq. (6), q_dot = v - omega x q (review §1.2); the inertial position
!> is r_N = C q. The body axes must be principal axes (review §1.1, eq. 11/12).
module davit_core_body
  use davit_kinds, only: wp, gravity
  use davit_core_rotation, only: rotation_matrix, euler_rates, cross
  implicit none
  private
  public :: rigid_body_type, body_mass_diagonal, body_w_phi, body_qdot, body_inertial_position
  public :: body_gravity_force, body_point_force, body_kinetic_energy, body_point_velocity

  !> Inertial parameters; I(1:3) are principal moments about the CG [kg m^2].
  type :: rigid_body_type
    !> Mass of the body [kg].
    real(wp) :: mass = 0.0_wp
    !> Principal moments of inertia about the CG, body axes 1-3 [kg m^2].
    real(wp) :: inertia(3) = 0.0_wp
  end type rigid_body_type

contains

  !> Diagonal of [V] in eq. (12): (I1, I2, I3, m, m, m).
  pure function body_mass_diagonal(body) result(v)
    !> The body's mass and principal inertia.
    type(rigid_body_type), intent(in) :: body
    real(wp) :: v(6)
    v = [body%inertia, body%mass, body%mass, body%mass]
  end function body_mass_diagonal

  !> [W]{phi} of eq. (12), i.e. omega x (I omega) and m omega x v (eq. 11).
  pure function body_w_phi(body, u) result(wphi)
    !> The body's mass and principal inertia.
    type(rigid_body_type), intent(in) :: body
    !> Generalized speeds (omega_b [rad/s], v_b [m/s]), body components.
    real(wp), intent(in) :: u(6)
    real(wp) :: wphi(6)
    associate (i => body%inertia)
      wphi(1) = (i(3) - i(2))*u(2)*u(3)
      wphi(2) = (i(1) - i(3))*u(3)*u(1)
      wphi(3) = (i(2) - i(1))*u(1)*u(2)
    end associate
    wphi(4:6) = body%mass*cross(u(1:3), u(4:6))
  end function body_w_phi

  !> Kinematic relations, eqs. (5) and (6).
  pure function body_qdot(q, u) result(qdot)
    !> Coordinates q = (theta1..3 [rad], CG position in body components [m]) and speeds
    !> u = (omega_b [rad/s], v_b [m/s]), body components.
    real(wp), intent(in) :: q(6), u(6)
    real(wp) :: qdot(6)
    qdot(1:3) = euler_rates(q(1:3), u(1:3))
    qdot(4:6) = u(4:6) - cross(u(1:3), q(4:6))
  end function body_qdot

  !> CG position in the inertial frame, r_N = C q(4:6).
  pure function body_inertial_position(q) result(r)
    !> Coordinates (theta1..3 [rad], CG position in body components [m]).
    real(wp), intent(in) :: q(6)
    real(wp) :: r(3)
    r = matmul(rotation_matrix(q(1:3)), q(4:6))
  end function body_inertial_position

  !> Velocity (body components) of the body point a_b: v + omega x a.
  pure function body_point_velocity(u, a_b) result(v)
    !> Speeds u = (omega_b [rad/s], v_b [m/s]) and the body point a_b from the CG [m], all
    !> in body components.
    real(wp), intent(in) :: u(6), a_b(3)
    real(wp) :: v(3)
    v = u(4:6) + cross(u(1:3), a_b)
  end function body_point_velocity

  !> Eq. (13): generalized gravity force, m g N3 . v_r. N3 in body components is the third
  !> row of C (review §1.3): m g (-s2, s1 c2, c1 c2).
  pure function body_gravity_force(body, c) result(f)
    !> The body's mass and principal inertia.
    type(rigid_body_type), intent(in) :: body
    !> Rotation matrix C (body -> inertial components, eq. 2).
    real(wp), intent(in) :: c(3, 3)
    real(wp) :: f(6)
    f(1:3) = 0.0_wp
    f(4:6) = body%mass*gravity*c(3, :)
  end function body_gravity_force

  !> Eq. (26) in general form: generalized force of a force f_b (body components) acting at
  !> the body point a_b; the partial angular velocities give the moment a x f.
  pure function body_point_force(a_b, f_b) result(f)
    !> Point of application a_b from the CG [m] and force f_b [N], body components.
    real(wp), intent(in) :: a_b(3), f_b(3)
    real(wp) :: f(6)
    f(1:3) = cross(a_b, f_b)
    f(4:6) = f_b
  end function body_point_force

  pure function body_kinetic_energy(body, u) result(e)
    !> The body's mass and principal inertia.
    type(rigid_body_type), intent(in) :: body
    !> Speeds (omega_b [rad/s], v_b [m/s]), body components.
    real(wp), intent(in) :: u(6)
    real(wp) :: e
    e = 0.5_wp*(sum(body%inertia*u(1:3)**2) + body%mass*sum(u(4:6)**2))
  end function body_kinetic_energy

end module davit_core_body
