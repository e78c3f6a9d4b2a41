!> Fenders of the lifeboat against the ship's side (paper eqs. 29-34, review §1.7, G16).
!>
!> The ship's side is the plane through `point` with outer normal `normal` (towards the
!> boat), moving rigidly with the ship (origin, velocity, angular velocity; inertial). Each
!> fender is a line of n_d points on the boat; its signed distance to the plane is the
!> smallest over its points, and it makes one Hertz contact at its deepest point (the review's
!> fix for the paper's sum over points, which would scale the stiffness with n_d). The
!> approach rate is eq. (33): the plane's velocity minus the point's, along the normal.
module davit_boat_fenders
  use davit_kinds, only: wp
  use davit_core_rotation, only: cross
  use davit_core_body, only: body_point_velocity, body_point_force
  use davit_boat_contact_law, only: contact_law_type, fender_state_type
  implicit none
  private
  public :: side_plane_type, fender_set_type, new_fender_set, fender_probe, fender_loads

  type :: side_plane_type
    !> A point of the ship's side plane and its unit normal towards the boat, inertial [m].
    real(wp) :: point(3) = 0.0_wp, normal(3) = [0.0_wp, 1.0_wp, 0.0_wp]
    !> Rigid motion of the ship: a reference point, its velocity, angular velocity [SI].
    real(wp) :: origin(3) = 0.0_wp, velocity(3) = 0.0_wp, angular_velocity(3) = 0.0_wp
  end type side_plane_type

  type :: fender_set_type
    !> Number of fenders and of contact points per fender.
    integer :: nf = 0, nd = 0
    !> Fender points in the boat frame, (3, nd, nf) [m]: each fender's evenly on one
    !> segment (fender_probe relies on it).
    real(wp), allocatable :: points(:, :, :)
    !> The contact law, chosen once at build (davit_system_law_factory).
    class(contact_law_type), allocatable :: law
  end type fender_set_type

contains

  !> Fenders at boat-frame x positions xs, all at y = y0, each with nd points evenly over
  !> z in [z_range(1), z_range(2)].
  pure function new_fender_set(xs, y0, z_range, nd, law) result(fs)
    !> Fender positions along b1 [m]; their common b2 offset [m]; the b3 extent of their points
    !> [m].
    real(wp), intent(in) :: xs(:), y0, z_range(2)
    !> Contact points per fender (>= 1).
    integer, intent(in) :: nd
    !> The contact law of every fender.
    class(contact_law_type), intent(in) :: law
    type(fender_set_type) :: fs
    integer :: i, j
    real(wp) :: z
    fs%nf = size(xs)
    fs%nd = nd
    allocate (fs%law, source=law)
    allocate (fs%points(3, nd, fs%nf))
    do j = 1, fs%nf
      do i = 1, nd
        z = z_range(1)
        if (nd > 1) z = z + (z_range(2) - z_range(1))*real(i - 1, wp)/real(nd - 1, wp)
        fs%points(:, i, j) = [xs(j), y0, z]
      end do
    end do
  end function new_fender_set

  !> For each fender: the deepest point (index), its penetration delta (= -distance) and
  !> approach rate delta_dot (eq. 33), for a boat with rotation c, CG r and speeds u.
  pure subroutine fender_probe(fs, plane, c, r, u, deepest, delta, delta_dot)
    !> The boat's fenders.
    type(fender_set_type), intent(in) :: fs
    !> The ship's side plane (inertial).
    type(side_plane_type), intent(in) :: plane
    !> Boat rotation b -> inertial, CG position (inertial) [m], speeds (Kane order).
    real(wp), intent(in) :: c(3, 3), r(3), u(6)
    !> Per fender, the index of its deepest point.
    integer, intent(out) :: deepest(fs%nf)
    !> Per fender, the penetration of its deepest point [m] and its rate [m/s].
    real(wp), intent(out) :: delta(fs%nf), delta_dot(fs%nf)
    real(wp) :: p(3), d, v_point(3), v_plane(3)
    integer :: i, j
    do j = 1, fs%nf
      ! a fender's points lie evenly on one segment (new_fender_set), where the
      ! penetration is linear: its deepest point is an end (the first on a tie)
      deepest(j) = 1
      p = r + matmul(c, fs%points(:, 1, j))
      delta(j) = -dot_product(plane%normal, p - plane%point)
      i = fs%nd
      p = r + matmul(c, fs%points(:, i, j))
      d = -dot_product(plane%normal, p - plane%point)
      if (d > delta(j)) then
        delta(j) = d
        deepest(j) = i
      end if
      p = r + matmul(c, fs%points(:, deepest(j), j))
      v_point = matmul(c, body_point_velocity(u, fs%points(:, deepest(j), j)))
      v_plane = plane%velocity + cross(plane%angular_velocity, p - plane%origin)
      delta_dot(j) = dot_product(v_plane - v_point, plane%normal)
    end do
  end subroutine fender_probe

  !> Generalized contact force on the boat (eq. 34, one contact per fender) and the normal
  !> force of each fender [N].
  pure subroutine fender_loads(fs, states, plane, c, r, u, f, force)
    !> The boat's fenders.
    type(fender_set_type), intent(in) :: fs
    !> Each fender's contact state.
    type(fender_state_type), intent(in) :: states(:)
    !> The ship's side plane (inertial).
    type(side_plane_type), intent(in) :: plane
    !> Boat rotation b -> inertial, CG position (inertial) [m], speeds (Kane order).
    real(wp), intent(in) :: c(3, 3), r(3), u(6)
    !> Generalized forces (Kane order) [N m, N]; each fender's normal force [N].
    real(wp), intent(out) :: f(6), force(fs%nf)
    integer :: deepest(fs%nf), j
    real(wp) :: delta(fs%nf), delta_dot(fs%nf)
    call fender_probe(fs, plane, c, r, u, deepest, delta, delta_dot)
    f = 0.0_wp
    do j = 1, fs%nf
      force(j) = fs%law%force(states(j), delta(j), delta_dot(j))
      if (force(j) > 0.0_wp) then
        f = f + body_point_force(fs%points(:, deepest(j), j), &
                                 matmul(force(j)*plane%normal, c))
      end if
    end do
  end subroutine fender_loads

end module davit_boat_fenders
