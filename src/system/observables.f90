!> What the recorders, the sweep metrics and the events read from a state: the boat's
!> inertial kinematics, rigging tensions and lengths, foundation-sling tensions, contact
!> clearance and forces, and the mechanical energy. Pure functions of (parameters,
!> history, state); none changes anything.
module davit_system_observables
  use davit_kinds, only: wp, gravity
  use davit_core_rotation, only: rotation_matrix, cross
  use davit_core_pose, only: pose_type
  use davit_core_layout, only: state_part_type
  use davit_core_body, only: body_inertial_position, body_kinetic_energy
  use davit_rigging_elastic_sling, only: elastic_sling_type, sling_hook_force, sling_energy
  use davit_rigging_rigging, only: rigging_type
  use davit_boat_fenders, only: side_plane_type, fender_set_type, fender_probe, fender_loads
  use davit_boat_contact_law, only: fender_state_type
  use davit_system_parameters, only: system_params_type, nslings, ship_pose, hook_kinematics, &
                                     falls_ends_type
  use davit_system_history, only: system_history_type
  implicit none
  private
  public :: boat_kinematics, rigging_state, sling_tensions, contact_state, energy

contains

  !> Inertial-frame observables of the boat at state y with rates dydt: position, velocity
  !> and acceleration of the CG (a = C (u_dot + omega x v), eq. 8), Euler angles and body
  !> angular velocity; out(:, 1:5) in that order of (position, euler, velocity,
  !> angular_velocity, acceleration).
  pure function boat_kinematics(boat_part, y, dydt) result(out)
    !> The boat's state part (system_params_type's boat_part).
    type(state_part_type), intent(in) :: boat_part
    !> State y and its rates dydt.
    real(wp), intent(in) :: y(:), dydt(:)
    real(wp) :: out(3, 5), c(3, 3)
    associate (q => y(boat_part%q(1):boat_part%q(2)), &
               u => y(boat_part%u(1):boat_part%u(2)), &
               u_dot => dydt(boat_part%u(1):boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      out(:, 1) = body_inertial_position(q)
      out(:, 2) = q(1:3)
      out(:, 3) = matmul(c, u(4:6))
      out(:, 4) = u(1:3)
      out(:, 5) = matmul(c, u_dot(4:6) + cross(u(1:3), u(4:6)))
    end associate
  end function boat_kinematics

  !> Rigging observables at state y: cable segment tensions [N], sling segment tensions
  !> (row 1 at the hook; zero once the hooks are released) [N], paid-out length [m] and lump
  !> positions (inertial) [m]. After release the caller passes the hooks, the ship's pose
  !> and the time of the release: the falls are not simulated after it (their states are
  !> frozen), so they are reported as they were when the hooks let go, not stretched by the
  !> boat and ship moving on.
  pure subroutine rigging_state(rig, t, yr, ends, released, seg, sling, paid, lumps)
    !> The davit rigging.
    type(rigging_type), intent(in) :: rig
    !> Time [s] and the rigging's part of the state vector.
    real(wp), intent(in) :: t, yr(:)
    !> The falls' ends: the hooks and the ship's pose.
    type(falls_ends_type), intent(in) :: ends
    !> Whether the hooks have been released.
    logical, intent(in) :: released
    !> Cable segment tensions [N] (rig%nseg), sling segment tensions [N] (rig%nlump + 1 per
    !> sling, row 1 at the hook), paid-out length [m] and lump positions [m] (inertial,
    !> (3, rig%nlump, sling)).
    real(wp), intent(out) :: seg(:), sling(:, :), paid, lumps(:, :, :)
    call rig%observe(t, yr, ends, seg, sling)
    ! Released hooks carry nothing: the frozen slings would otherwise report the stretch
    ! to wherever the boat has moved on the waves (MN on a 4 m sea, III.A decks).
    if (released) sling = 0.0_wp
    paid = rig%paid_out(yr)
    if (rig%nlump > 0) lumps = rig%lump_positions(yr)
  end subroutine rigging_state

  !> Tensions [N] of the foundation slings at state y (zero when detached or on the davit,
  !> where rigging_state gives the sling tensions).
  pure function sling_tensions(attached, slings, boat_part, hooks, y) result(tension)
    !> Whether the foundation slings hold the boat.
    logical, intent(in) :: attached
    !> The foundation slings, one per hook.
    type(elastic_sling_type), intent(in) :: slings(nslings)
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> Hook points in the boat frame [m], one column per sling.
    real(wp), intent(in) :: hooks(3, nslings)
    !> State vector.
    real(wp), intent(in) :: y(:)
    real(wp) :: tension(nslings), hook_pos(3, nslings), hook_vel(3, nslings), fh(3)
    integer :: i
    tension = 0.0_wp
    if (.not. attached) return
    call hook_kinematics(boat_part, hooks, y, hook_pos, hook_vel)
    do i = 1, nslings
      call sling_hook_force(slings(i), hook_pos(:, i), hook_vel(:, i), fh, tension(i))
    end do
  end function sling_tensions

  !> Smallest fender-to-side distance [m] (negative = penetration) and each fender's
  !> normal force [N] at state y.
  pure subroutine contact_state(contact, fenders, states, plane, boat_part, y, clearance, &
                                force)
    !> Whether the fenders' contact acts (the forces are zero otherwise).
    logical, intent(in) :: contact
    !> The boat's fenders and their contact law.
    type(fender_set_type), intent(in) :: fenders
    !> Each fender's contact phase (the history's), which the forces read.
    type(fender_state_type), intent(in) :: states(:)
    !> The ship's side plane at y.
    type(side_plane_type), intent(in) :: plane
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> State vector.
    real(wp), intent(in) :: y(:)
    !> Smallest fender-to-side distance [m] (negative: penetration) and each fender's
    !> normal force [N] (zero without contact; one per fender).
    real(wp), intent(out) :: clearance, force(:)
    real(wp) :: c(3, 3), r(3), delta(fenders%nf), delta_dot(fenders%nf), f(6)
    integer :: deepest(fenders%nf)
    associate (q => y(boat_part%q(1):boat_part%q(2)), &
               u => y(boat_part%u(1):boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      r = matmul(c, q(4:6))
      call fender_probe(fenders, plane, c, r, u, deepest, delta, delta_dot)
      clearance = -maxval(delta)
      force = 0.0_wp
      if (contact) call fender_loads(fenders, states, plane, c, r, u, f, force)
    end associate
  end subroutine contact_state

  !> Mechanical energy of the conservative part in air: kinetic (with the BEM water model,
  !> of M + s A(inf)) + gravity (N3 down, so -m g z) + elastic slings [J]. Once the hooks
  !> are released the falls' energy is that of
  !> their frozen states at the released hooks (the boat has left them), not the stretch
  !> to wherever the boat drifts.
  pure function energy(par, hist, y) result(e)
    !> The system's parameters (boat, its BEM water model, rigging, slings).
    type(system_params_type), intent(in) :: par
    !> The history (hook positions and ship's pose at release).
    type(system_history_type), intent(in) :: hist
    !> State vector.
    real(wp), intent(in) :: y(:)
    real(wp) :: e, c(3, 3), r(3), hook_pos(3, nslings), hook_vel(3, nslings)
    type(pose_type) :: pose
    integer :: i
    associate (q => y(par%boat_part%q(1):par%boat_part%q(2)), &
               u => y(par%boat_part%u(1):par%boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      r = matmul(c, q(4:6))
      e = body_kinetic_energy(par%boat, u) - par%boat%mass*gravity*r(3)
      call par%water_terms%add_kinetic_energy(y(par%radiation_part%q(1): &
                                                par%radiation_part%q(2)), u, e)
    end associate
    if (par%on_davit) then
      pose = ship_pose(par%with_ship, par%ship_part, par%ship_rest, y)
      hook_pos = spread(r, 2, 2) + matmul(c, par%hooks)
      if (hist%release_time >= 0.0_wp) then
        hook_pos = hist%released_hooks
        pose = hist%released_pose
      end if
      e = e + par%rig%energy(y(par%rig_slice(1):par%rig_slice(2)), &
                             hook_pos, pose)
    end if
    if (.not. par%slings_attached) return
    call hook_kinematics(par%boat_part, par%hooks, y, hook_pos, hook_vel)
    do i = 1, nslings
      e = e + sling_energy(par%slings(i), hook_pos(:, i))
    end do
  end function energy

end module davit_system_observables
