!> The assembled multibody system and its Kane right-hand side (eqs. 12, 89).
!>
!> State vector y = [q; u]: q = (theta1..3, q4..6) and u = (omega_b, v_b) of the lifeboat
!> (eqs. 3-4). The assembler only sums each force model's generalized force and forms
!> u_dot = (F - W phi)/V (eq. 89) and q_dot from eqs. (5)-(6). Force models (gravity, the
!> rigging) are pure functions of the state; the rigging here is the foundation's two massless
!> slings, which the full cable-pulley rigging replaces behind the same hook-force role.
module davit_system_model
  use davit_kinds, only: wp, gravity
  use davit_core_rotation, only: rotation_matrix, cross
  use davit_core_body, only: rigid_body_type, body_mass_diagonal, body_w_phi, body_qdot, &
                             body_gravity_force, body_point_force, body_point_velocity, &
                             body_inertial_position, body_kinetic_energy
  use davit_rigging_elastic_sling, only: elastic_sling_type, sling_hook_force, sling_energy
  use davit_solve_integrator, only: ode_problem
  use davit_io_config, only: config_type
  implicit none
  private
  public :: system_type, new_system, nstate, boat_q, boat_u

  integer, parameter :: nstate = 12
  !> Index ranges of the boat's coordinates and speeds in y.
  integer, parameter :: boat_q(2) = [1, 6], boat_u(2) = [7, 12]
  integer, parameter :: nslings = 2

  type, extends(ode_problem) :: system_type
    type(rigid_body_type) :: boat
    !> Hook points in the boat frame, one column per sling.
    real(wp) :: hooks(3, nslings) = 0.0_wp
    type(elastic_sling_type) :: slings(nslings)
  contains
    procedure :: rhs => system_rhs
    procedure :: initial_state
    procedure :: energy
    procedure :: sling_tensions
    procedure :: observe
  end type system_type

contains

  !> Build the system from a validated configuration.
  subroutine new_system(self, cfg)
    type(system_type), intent(out) :: self
    type(config_type), intent(in) :: cfg
    real(wp) :: ea
    self%boat%mass = cfg%boat%mass
    self%boat%inertia = cfg%boat%inertia
    self%hooks(:, 1) = cfg%slings%hook_fore
    self%hooks(:, 2) = cfg%slings%hook_aft
    ea = cfg%slings%youngs_modulus*acos(-1.0_wp)*cfg%slings%diameter**2/4.0_wp
    self%slings(1) = elastic_sling_type(cfg%slings%anchor_fore, cfg%slings%length, ea, &
                                        cfg%slings%damping)
    self%slings(2) = elastic_sling_type(cfg%slings%anchor_aft, cfg%slings%length, ea, &
                                        cfg%slings%damping)
  end subroutine new_system

  !> Initial y from inertial position/velocity and Euler angles / body rates.
  function initial_state(self, cfg) result(y)
    class(system_type), intent(in) :: self
    type(config_type), intent(in) :: cfg
    real(wp) :: y(nstate), c(3, 3)
    c = rotation_matrix(cfg%boat%euler)
    y(1:3) = cfg%boat%euler
    y(4:6) = matmul(transpose(c), cfg%boat%position)
    y(7:9) = cfg%boat%angular_velocity
    y(10:12) = matmul(transpose(c), cfg%boat%velocity)
  end function initial_state

  !> Kane's equations: y' = (q_dot, (F - W phi)/V).
  subroutine system_rhs(self, t, y, dydt)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: f(6)
    associate (q => y(boat_q(1):boat_q(2)), u => y(boat_u(1):boat_u(2)))
      f = boat_forces(self, q, u)
      dydt(boat_q(1):boat_q(2)) = body_qdot(q, u)
      dydt(boat_u(1):boat_u(2)) = (f - body_w_phi(self%boat, u))/body_mass_diagonal(self%boat)
    end associate
  end subroutine system_rhs

  !> Generalized active forces on the boat: gravity (eq. 13) and slings (eq. 26).
  pure function boat_forces(self, q, u) result(f)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: q(6), u(6)
    real(wp) :: f(6), c(3, 3), r(3), fh(3), tension
    integer :: i
    c = rotation_matrix(q(1:3))
    r = matmul(c, q(4:6))
    f = body_gravity_force(self%boat, c)
    do i = 1, nslings
      call sling_hook_force(self%slings(i), r + matmul(c, self%hooks(:, i)), &
                            matmul(c, body_point_velocity(u, self%hooks(:, i))), fh, tension)
      f = f + body_point_force(self%hooks(:, i), matmul(transpose(c), fh))
    end do
  end function boat_forces

  !> Total mechanical energy: kinetic + gravity (N3 down, so -m g z) + elastic [J].
  pure function energy(self, y) result(e)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: e, c(3, 3), r(3)
    integer :: i
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    e = body_kinetic_energy(self%boat, y(boat_u(1):boat_u(2))) - self%boat%mass*gravity*r(3)
    do i = 1, nslings
      e = e + sling_energy(self%slings(i), r + matmul(c, self%hooks(:, i)))
    end do
  end function energy

  !> Sling tensions [N] at state y.
  pure function sling_tensions(self, y) result(tension)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: tension(nslings), c(3, 3), r(3), fh(3)
    integer :: i
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    do i = 1, nslings
      call sling_hook_force(self%slings(i), r + matmul(c, self%hooks(:, i)), &
                            matmul(c, body_point_velocity(y(boat_u(1):boat_u(2)), &
                                                          self%hooks(:, i))), fh, tension(i))
    end do
  end function sling_tensions

  !> Inertial-frame observables of the boat: position, velocity and acceleration of the CG
  !> (a = C (u_dot + omega x v), eq. 8), Euler angles and body angular velocity.
  subroutine observe(self, t, y, position, euler, velocity, angular_velocity, acceleration)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: position(3), euler(3), velocity(3), angular_velocity(3)
    real(wp), intent(out) :: acceleration(3)
    real(wp) :: c(3, 3), dydt(nstate)
    associate (u => y(boat_u(1):boat_u(2)))
      call self%rhs(t, y, dydt)
      c = rotation_matrix(y(1:3))
      position = body_inertial_position(y(boat_q(1):boat_q(2)))
      euler = y(1:3)
      velocity = matmul(c, u(4:6))
      angular_velocity = u(1:3)
      acceleration = matmul(c, dydt(boat_u(1) + 3:boat_u(2)) + cross(u(1:3), u(4:6)))
    end associate
  end subroutine observe

end module davit_system_model
