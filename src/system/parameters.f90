!> What never changes during a run: the bodies, force models and environment of the
!> launch, and the layout of its state. Built once (davit_system_build), read by the
!> right-hand side and the observables, never written after.
!>
!> The geometry helpers here turn a state into what the force models need: the ship's pose
!> (at rest, or from its state part), the side plane it carries and the hooks' motion.
module davit_system_parameters
  use davit_kinds, only: wp
  use davit_core_rotation, only: rotation_matrix
  use davit_core_pose, only: pose_type
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_core_body, only: rigid_body_type, body_point_velocity
  use davit_rigging_elastic_sling, only: elastic_sling_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_sea_wind, only: wind_type
  use davit_boat_strip_loads, only: strip_model_type
  use davit_boat_water_terms, only: water_terms_type
  use davit_boat_wind_loads, only: boat_wind_type
  use davit_boat_fenders, only: side_plane_type, fender_set_type, fender_probe
  use davit_rigging_rigging, only: rigging_type
  use davit_rigging_falls_ends, only: falls_ends_type
  implicit none
  private
  public :: system_params_type, nslings, ship_pose, side_plane, hook_kinematics, fender_gaps
  public :: falls_ends_type, falls_ends_at

  !> Number of slings (and hooks): fore and aft.
  integer, parameter :: nslings = 2

  !> The launch's bodies, force models, environment and state layout.
  type :: system_params_type
    !> The state: part "boat" (eqs. 3-4), the rigging's parts on the davit, the ship's
    !> parts in the 'launch' scene.
    type(state_layout_type) :: layout
    !> The boat's and the moving ship's rigid-body parts (ranges of q and u) in the state.
    type(state_part_type) :: boat_part, ship_part
    !> The boat's BEM water states (&boat water_model = 'bem'): immersion and radiation
    !> memory, part "boat_radiation" (q only); empty with the strips alone.
    type(state_part_type) :: radiation_part
    !> First and last state index of the rigging, y(rig_slice(1) : rig_slice(2)), and of
    !> the ship, y(ship_slice(1) : ship_slice(2)); [1, 0] (empty) without them.
    integer :: rig_slice(2) = [1, 0], ship_slice(2) = [1, 0]
    !> The boat's mass [kg] and principal inertia about its CG [kg m^2].
    type(rigid_body_type) :: boat
    !> Hook points in the boat frame, one column per sling.
    real(wp) :: hooks(3, nslings) = 0.0_wp
    !> Foundation slings (the 'hanging' scenes), fore and aft.
    type(elastic_sling_type) :: slings(nslings)
    !> Whether the foundation slings hold the boat (never on the davit, where the rigging
    !> does).
    logical :: slings_attached = .true.
    !> The strip model of the boat in the water (sections, level of detail, drag and
    !> damping coefficients).
    type(strip_model_type) :: water
    !> The water's terms on top of the strips (davit_boat_water_terms): none, or added
    !> mass, radiation, diffraction and roll damping from the hull's BEM database
    !> (&boat water_model = 'bem'), chosen at build.
    class(water_terms_type), allocatable :: water_terms
    !> Wind drag and lift on the boat, the lift form chosen at build.
    class(boat_wind_type), allocatable :: air
    !> The sea: wave components (amplitudes, frequencies, directions, phases) and ramp.
    type(wave_field_type) :: sea
    !> The mean wind: speed and the direction it blows towards.
    type(wind_type) :: wind
    !> Hull volume (dry fraction of the wind loads) [m^3].
    real(wp) :: hull_volume = 0.0_wp
    !> Whether the fenders' contact with the ship's side acts (&contact enabled).
    logical :: contact = .false.
    !> The boat's fenders: their points in the boat frame and the contact law.
    type(fender_set_type) :: fenders
    !> Ship-frame y of the side plane [m].
    real(wp) :: side_y = 0.0_wp
    !> The full davit rigging ('lowering' and 'launch' scenes) in place of the foundation
    !> slings.
    logical :: on_davit = .false.
    !> The davit rigging (falls, winch, its state layout), built when on_davit.
    type(rigging_type) :: rig
    !> The ship at rest in its deck pose, unless a 6-DOF ship moves ('launch'), one-way
    !> coupled as in the paper (the davit loads do not act on it).
    type(pose_type) :: ship_rest
    !> Whether a 6-DOF ship moves ('launch'; its state is y(ship_slice(1) : ship_slice(2)))
    !> instead of ship_rest.
    logical :: with_ship = .false.
    !> Hook release once waterborne (review G24).
    logical :: release = .true.
    !> Delay of the release after the boat is waterborne (its condition held for 1 s) [s].
    real(wp) :: release_delay = 0.0_wp
  end type system_params_type

contains

  !> The ship's pose at state y: CG, rotation (ship -> N), velocity and angular velocity
  !> (inertial components).
  pure function ship_pose(with_ship, ship_part, ship_rest, y) result(pose)
    !> Whether a 6-DOF ship moves (system_params_type's with_ship).
    logical, intent(in) :: with_ship
    !> The ship's rigid-body part of the state (used when with_ship).
    type(state_part_type), intent(in) :: ship_part
    !> The ship at rest in its deck pose (used when not with_ship).
    type(pose_type), intent(in) :: ship_rest
    !> The system's state.
    real(wp), intent(in) :: y(:)
    type(pose_type) :: pose
    if (.not. with_ship) then
      pose = ship_rest
      return
    end if
    associate (q => y(ship_part%q(1):ship_part%q(2)), &
               u => y(ship_part%u(1):ship_part%u(2)))
      pose%c = rotation_matrix(q(1:3))
      pose%r = q(4:6)
      pose%v = matmul(pose%c, u(4:6))
      pose%w = matmul(pose%c, u(1:3))
    end associate
  end function ship_pose

  !> The falls' ends at state y: the hooks from the boat's part, the ship's pose as given.
  pure function falls_ends_at(boat_part, hooks, ship, y) result(ends)
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> Hook points in the boat frame [m], one column per sling.
    real(wp), intent(in) :: hooks(3, nslings)
    !> The ship's pose at y (ship_pose).
    type(pose_type), intent(in) :: ship
    !> The system's state.
    real(wp), intent(in) :: y(:)
    type(falls_ends_type) :: ends
    call hook_kinematics(boat_part, hooks, y, ends%hook_pos, ends%hook_vel)
    ends%ship = ship
  end function falls_ends_at

  !> The ship's side plane (ship-frame y = side_y, normal +s2) carried by the ship.
  pure function side_plane(side_y, pose) result(plane)
    !> Ship-frame y of the side plane [m] (system_params_type's side_y).
    real(wp), intent(in) :: side_y
    !> The ship's pose.
    type(pose_type), intent(in) :: pose
    type(side_plane_type) :: plane
    plane%origin = pose%r
    plane%point = pose%r + pose%c(:, 2)*side_y
    plane%normal = pose%c(:, 2)
    plane%velocity = pose%v
    plane%angular_velocity = pose%w
  end function side_plane

  !> Inertial positions and velocities of the two hooks at state y.
  pure subroutine hook_kinematics(boat_part, hooks, y, hook_pos, hook_vel)
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> Hook points in the boat frame [m], one column per sling.
    real(wp), intent(in) :: hooks(3, nslings)
    !> The system's state.
    real(wp), intent(in) :: y(:)
    !> Positions [m] and velocities [m/s] of the hooks, inertial components, one column
    !> per sling.
    real(wp), intent(out) :: hook_pos(3, nslings), hook_vel(3, nslings)
    real(wp) :: c(3, 3), r(3)
    integer :: i
    associate (q => y(boat_part%q(1):boat_part%q(2)), &
               u => y(boat_part%u(1):boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      r = matmul(c, q(4:6))
      do i = 1, nslings
        hook_pos(:, i) = r + matmul(c, hooks(:, i))
        hook_vel(:, i) = matmul(c, body_point_velocity(u, hooks(:, i)))
      end do
    end associate
  end subroutine hook_kinematics

  !> Each fender's signed distance into the ship's side delta (> 0: indentation) and its
  !> rate delta_dot at state y (eqs. 29-33).
  pure subroutine fender_gaps(fenders, side, boat_part, y, delta, delta_dot)
    !> The boat's fenders (points in the boat frame).
    type(fender_set_type), intent(in) :: fenders
    !> The ship's side plane at y (side_plane of the ship's pose).
    type(side_plane_type), intent(in) :: side
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> The system's state.
    real(wp), intent(in) :: y(:)
    !> Each fender's indentation delta [m] (> 0 into the ship's side; its deepest point's)
    !> and its rate delta_dot [m/s] (> 0 approaching).
    real(wp), intent(out) :: delta(fenders%nf), delta_dot(fenders%nf)
    real(wp) :: c(3, 3)
    integer :: deepest(fenders%nf)
    associate (q => y(boat_part%q(1):boat_part%q(2)), &
               u => y(boat_part%u(1):boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      call fender_probe(fenders, side, c, matmul(c, q(4:6)), u, deepest, delta, delta_dot)
    end associate
  end subroutine fender_gaps

end module davit_system_parameters
