!> The assembled multibody system and its Kane right-hand side (eqs. 12, 89).
!>
!> A system is its parameters (built once: bodies, force models, environment, state
!> layout), its history (contact phases, events, slow caches: written only by the
!> after-step hook), its contact step policy and, in the 'launch' scene, the 6-DOF ship
!> (which carries its own slowly varying wave coefficients, refreshed after each step).
!> The right-hand side collects each body's Kane blocks (boat, rigging, ship) over the
!> named state layout and forms u_dot = (F - W phi)/V for all of them at once (eq. 89,
!> davit_core_kane), reading parameters, history and state and writing only its output.
module davit_system_model
  use davit_kinds, only: wp
  use davit_core_rotation, only: rotation_matrix
  use davit_core_pose, only: pose_type
  use davit_core_layout, only: state_part_type
  use davit_rigging_rigging, only: rigging_type
  use davit_core_kane, only: kane_f, kane_rates, kane_at_rest
  use davit_core_body, only: body_point_force
  use davit_solve_integrator, only: ode_problem, part_fast
  use davit_ship_ship_model, only: ship_system_type
  use davit_system_parameters, only: system_params_type, nslings, ship_pose, side_plane, &
                                     fender_gaps, falls_ends_type, falls_ends_at
  use davit_system_history, only: system_history_type
  use davit_system_contact_policy, only: contact_policy_type, limits_steps, contact_max_step
  use davit_system_boat_loads, only: boat_kane_blocks, loads_all, loads_slow, loads_fast
  use davit_system_events, only: advance_history
  use davit_system_observables, only: boat_kinematics, rigging_state, sling_tensions, &
                                      contact_state, energy
  implicit none
  private
  public :: system_type

  !> The launch as an ODE problem for the integrators.
  type, extends(ode_problem) :: system_type
    !> What never changes during the run: bodies, force models, environment, state layout.
    type(system_params_type) :: par
    !> What the after-step hook updates: contact phases, events, the water's slow caches.
    type(system_history_type) :: hist
    !> The step policy of fender contact.
    type(contact_policy_type) :: policy
    !> The 6-DOF ship of the 'launch' scene (built only there, with_ship).
    type(ship_system_type) :: ship
  contains
    procedure :: rhs => system_rhs
    procedure :: rhs_part => system_rhs_part
    procedure :: after_step => system_after_step
    procedure :: max_step => system_max_step
    procedure :: stiff_states => system_stiff_states
    procedure :: coupled_states => system_coupled_states
    procedure :: n_modes => system_n_modes
    procedure :: modes => system_modes
    procedure :: observe
    procedure :: energy => system_energy
    procedure :: sling_tensions => system_sling_tensions
    procedure :: contact_state => system_contact_state
    procedure :: rigging_state => system_rigging_state
  end type system_type

contains

  !> Kane's equations: y' = (q_dot, (F - W phi)/V).
  subroutine system_rhs(self, t, y, dydt)
    !> The system.
    class(system_type), intent(in) :: self
    !> Time [s].
    real(wp), intent(in) :: t
    !> State vector (the layout's: boat, its water states, rigging, ship).
    real(wp), intent(in) :: y(:)
    !> Its time derivative y' = (q_dot, (F - W phi)/V).
    real(wp), intent(out) :: dydt(:)
    real(wp) :: kane(3, size(y))
    call kane_blocks(self, t, y, dydt, kane, loads_all)
    call kane_rates(self%par%layout, kane, dydt)
  end subroutine system_rhs

  !> One part of the multirate split (davit_solve_multirate), eq. 89 with the same V for
  !> both, so slow + fast = system_rhs. The slow part: the one-way coupled ship whole, and
  !> the boat's water and wind loads (with the BEM water states). The fast part: the boat's
  !> kinematics, gyroscopic terms, gravity, slings and fenders, and the rigging with its
  !> hook forces; the ship has no rates there.
  subroutine system_rhs_part(self, t, y, dydt, part)
    !> The system.
    class(system_type), intent(in) :: self
    !> Time [s].
    real(wp), intent(in) :: t
    !> State vector (the layout's: boat, its water states, rigging, ship).
    real(wp), intent(in) :: y(:)
    !> The part of y' asked for (the fast part's ship rows zero).
    real(wp), intent(out) :: dydt(:)
    !> part_slow or part_fast.
    integer, intent(in) :: part
    real(wp) :: kane(3, size(y))
    call kane_blocks(self, t, y, dydt, kane, part)
    if (part == part_fast .and. self%par%with_ship) then
      call kane_rates(self%par%layout, kane, dydt, self%par%ship_slice)
    else
      call kane_rates(self%par%layout, kane, dydt)
    end if
  end subroutine system_rhs_part

  !> Every body's q_dot and Kane blocks at (t, y): the ship, the boat and, on the davit,
  !> the rigging, whose hook forces act on the boat through the hooks' partial
  !> velocities (eq. 26); `part` (loads_all, loads_slow, loads_fast) selects the terms of
  !> the multirate split, the parts it leaves out at rest.
  subroutine kane_blocks(self, t, y, dydt, kane, part)
    type(system_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    integer, intent(in) :: part
    type(pose_type) :: pose
    associate (par => self%par, b => self%par%boat_part, s => self%par%ship_slice, &
               x => self%par%radiation_part%q, r => self%par%rig_slice)
      pose = ship_pose(par%with_ship, par%ship_part, par%ship_rest, y)
      if (par%with_ship) then
        if (part == loads_fast) then
          ! the ship's rows are 0 here; kane_rates leaves its speeds so
          dydt(s(1):s(2)) = 0.0_wp
        else
          call self%ship%kane_blocks(t, y(s(1):s(2)), dydt(s(1):s(2)), kane(:, s(1):s(2)))
        end if
      end if
      call boat_kane_blocks(par, self%hist, t, y(b%q(1):b%q(2)), y(b%u(1):b%u(2)), &
                            y(x(1):x(2)), side_plane(par%side_y, pose), dydt(b%q(1):b%q(2)), &
                            dydt(x(1):x(2)), kane(:, b%u(1):b%u(2)), part)
      if (par%on_davit) then
        if (part == loads_slow) then
          call kane_at_rest(dydt(r(1):r(2)), kane(:, r(1):r(2)))
        else
          call rigging_blocks(par%rig, r, b, par%hooks, self%hist%release_time >= 0.0_wp, t, &
                              y, pose, dydt, kane)
        end if
      end if
    end associate
  end subroutine kane_blocks

  !> The rigging's Kane blocks, and its hook forces added to the boat's F (eq. 26); after
  !> release the falls are frozen and act on nothing.
  subroutine rigging_blocks(rig, rig_slice, boat_part, hooks, released, t, y, pose, dydt, kane)
    !> The davit rigging.
    type(rigging_type), intent(in) :: rig
    !> First and last state index of the rigging.
    integer, intent(in) :: rig_slice(2)
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> Hook points in the boat frame [m], one column per sling.
    real(wp), intent(in) :: hooks(3, nslings)
    !> Whether the hooks have been released.
    logical, intent(in) :: released
    real(wp), intent(in) :: t, y(:)
    type(pose_type), intent(in) :: pose
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    real(wp) :: hook_force(3, nslings), c(3, 3)
    integer :: i, i0, i1
    i0 = rig_slice(1)
    i1 = rig_slice(2)
    if (released) then
      call kane_at_rest(dydt(i0:i1), kane(:, i0:i1))
      return
    end if
    call rig%kane_blocks(t, y(i0:i1), falls_ends_at(boat_part, hooks, pose, y), dydt(i0:i1), &
                         kane(:, i0:i1), hook_force)
    associate (b => boat_part)
      c = rotation_matrix(y(b%q(1):b%q(1) + 2))
      do i = 1, nslings
        kane(kane_f, b%u(1):b%u(2)) = kane(kane_f, b%u(1):b%u(2)) + &
                                      body_point_force(hooks(:, i), matmul(hook_force(:, i), c))
      end do
    end associate
  end subroutine rigging_blocks

  !> The after-step hook: the ship's slow coefficients, then the launch's history.
  subroutine system_after_step(self, t, y)
    !> The system (the ship's history and the launch's history written).
    class(system_type), intent(inout) :: self
    !> Time [s] and state vector at the end of the accepted step.
    real(wp), intent(in) :: t, y(:)
    associate (s => self%par%ship_slice)
      if (self%par%with_ship) call self%ship%after_step(t, y(s(1):s(2)))
    end associate
    call advance_history(self%par, self%hist, t, y)
  end subroutine system_after_step

  !> Largest step [s] from (t, y): the contact policy's (davit_system_contact_policy).
  pure real(wp) function system_max_step(self, t, y, dt) result(h)
    !> The system.
    class(system_type), intent(in) :: self
    !> Time [s], state vector and the deck's step dt [s].
    real(wp), intent(in) :: t, y(:), dt
    real(wp) :: delta(self%par%fenders%nf), delta_dot(self%par%fenders%nf)
    h = dt
    if (.not. limits_steps(self%policy, self%par%contact, dt)) return
    associate (par => self%par)
      call fender_gaps(par%fenders, side_plane(par%side_y, ship_pose(par%with_ship, &
                       par%ship_part, par%ship_rest, y)), par%boat_part, y, delta, delta_dot)
    end associate
    h = contact_max_step(self%policy, self%hist%fender_states, delta, delta_dot, dt)
  end function system_max_step

  !> The rigging's states (blocks, lumps, sheaves, drum): their axial springs are the
  !> system's stiff modes (the block on its sling ~1260 1/s, lumps ~3e4 1/s).
  pure function system_stiff_states(self) result(idx)
    !> The system (its rigging slice).
    class(system_type), intent(in) :: self
    integer, allocatable :: idx(:)
    integer :: i
    if (self%par%on_davit) then
      idx = [(i, i=self%par%rig_slice(1), self%par%rig_slice(2))]
    else
      allocate (idx(0))
    end if
  end function system_stiff_states

  !> The states the rigging's rows depend on through the wire's stiffness: the boat's
  !> (hooks) and the ship's body states (davit heads, lead sheave, drum): the q and u of
  !> its part "ship" (not its memory, rudder or control states).
  pure function system_coupled_states(self) result(idx)
    !> The system (its boat and ship parts).
    class(system_type), intent(in) :: self
    integer, allocatable :: idx(:)
    integer :: i
    allocate (idx(0))
    if (.not. self%par%on_davit) return
    associate (b => self%par%boat_part, s => self%par%ship_part)
      idx = [(i, i=b%q(1), b%q(2)), (i, i=b%u(1), b%u(2))]
      if (self%par%with_ship) idx = [idx, (i, i=s%q(1), s%q(2)), (i, i=s%u(1), s%u(2))]
    end associate
  end function system_coupled_states

  !> Modes located as events ('event' contact approach): each fender's contact phase as
  !> the after-step hook would set it, then, on the davit before release, whether each
  !> sling and cable segment is taut (the kinks of their tension-only laws), or whether
  !> each foundation sling is.
  pure integer function system_n_modes(self) result(n)
    !> The system (contact policy, fenders, rigging, slings).
    class(system_type), intent(in) :: self
    n = 0
    if (.not. self%policy%located) return
    if (self%par%contact) n = self%par%fenders%nf
    if (self%par%on_davit) n = n + self%par%rig%nseg + nslings*(self%par%rig%nlump + 1)
    if (self%par%slings_attached) n = n + nslings
  end function system_n_modes

  !> The mode of each of the system_n_modes switches at (t, y), in that order: each
  !> fender's next contact phase, then 1 (taut) or 0 (slack) for each cable and sling
  !> segment on the davit, or for each foundation sling.
  subroutine system_modes(self, t, y, m)
    !> The system.
    class(system_type), intent(in) :: self
    !> Time [s] and state vector.
    real(wp), intent(in) :: t, y(:)
    !> The modes, system_n_modes of them.
    integer, intent(out) :: m(:)
    real(wp) :: delta(self%par%fenders%nf), delta_dot(self%par%fenders%nf)
    type(pose_type) :: pose
    integer :: j, n
    n = 0
    associate (par => self%par)
      pose = ship_pose(par%with_ship, par%ship_part, par%ship_rest, y)
      if (par%contact) then
        call fender_gaps(par%fenders, side_plane(par%side_y, pose), par%boat_part, y, delta, &
                         delta_dot)
        do j = 1, par%fenders%nf
          m(j) = par%fenders%law%next_phase(self%hist%fender_states(j), delta(j), delta_dot(j))
        end do
        n = par%fenders%nf
      end if
      if (par%on_davit) call link_modes(par%rig, self%hist%release_time >= 0.0_wp, t, &
                                        y(par%rig_slice(1):par%rig_slice(2)), &
                                        falls_ends_at(par%boat_part, par%hooks, pose, y), m(n + 1:))
      if (par%slings_attached) m(n + 1:n + nslings) = &
        merge(1, 0, sling_tensions(par%slings_attached, par%slings, par%boat_part, par%hooks, &
                                   y) > 0.0_wp)
    end associate
  end subroutine system_modes

  !> 1 for each taut sling segment and cable segment, 0 for a slack one; all 0 after
  !> release (the falls are frozen).
  subroutine link_modes(rig, released, t, yr, ends, m)
    !> The davit rigging.
    type(rigging_type), intent(in) :: rig
    !> Whether the hooks have been released.
    logical, intent(in) :: released
    !> Time [s] and the rigging's part of the state vector.
    real(wp), intent(in) :: t, yr(:)
    !> The falls' ends: the hooks and the ship's pose.
    type(falls_ends_type), intent(in) :: ends
    !> The modes, rig%nseg + nslings*(rig%nlump + 1) of them.
    integer, intent(out) :: m(:)
    real(wp) :: seg(rig%nseg), sling(rig%nlump + 1, nslings), paid
    real(wp) :: lumps(3, rig%nlump, nslings)
    m = 0
    if (released) return
    call rigging_state(rig, t, yr, ends, .false., seg, sling, paid, lumps)
    m(1:size(seg)) = merge(1, 0, seg > 0.0_wp)
    m(size(seg) + 1:) = merge(1, 0, reshape(sling, [size(sling)]) > 0.0_wp)
  end subroutine link_modes

  !> Inertial-frame observables of the boat (davit_system_observables), with its
  !> acceleration from the right-hand side.
  subroutine observe(self, t, y, position, euler, velocity, angular_velocity, acceleration)
    !> The system.
    class(system_type), intent(in) :: self
    !> Time [s] and state vector.
    real(wp), intent(in) :: t, y(:)
    !> The boat's CG position [m] and velocity [m/s] (inertial), Euler angles [rad] and
    !> angular velocity [rad/s] (body components).
    real(wp), intent(out) :: position(3), euler(3), velocity(3), angular_velocity(3)
    !> The CG's acceleration [m/s^2] (inertial).
    real(wp), intent(out) :: acceleration(3)
    real(wp) :: dydt(size(y)), out(3, 5)
    call self%rhs(t, y, dydt)
    out = boat_kinematics(self%par%boat_part, y, dydt)
    position = out(:, 1)
    euler = out(:, 2)
    velocity = out(:, 3)
    angular_velocity = out(:, 4)
    acceleration = out(:, 5)
  end subroutine observe

  !> Mechanical energy [J] of the conservative part at y (davit_system_observables' energy).
  pure real(wp) function system_energy(self, y) result(e)
    !> The system.
    class(system_type), intent(in) :: self
    !> State vector.
    real(wp), intent(in) :: y(:)
    e = energy(self%par, self%hist, y)
  end function system_energy

  !> Tensions [N] of the foundation slings at y (zero when detached or on the davit).
  pure function system_sling_tensions(self, y) result(tension)
    !> The system.
    class(system_type), intent(in) :: self
    !> State vector.
    real(wp), intent(in) :: y(:)
    real(wp) :: tension(nslings)
    associate (par => self%par)
      tension = sling_tensions(par%slings_attached, par%slings, par%boat_part, par%hooks, y)
    end associate
  end function system_sling_tensions

  !> Smallest fender-to-side distance and each fender's normal force at y.
  pure subroutine system_contact_state(self, y, clearance, force)
    !> The system.
    class(system_type), intent(in) :: self
    !> State vector.
    real(wp), intent(in) :: y(:)
    !> Smallest fender-to-side distance [m] (negative: penetration) and each fender's
    !> normal force [N] (one per fender).
    real(wp), intent(out) :: clearance, force(:)
    associate (par => self%par)
      call contact_state(par%contact, par%fenders, self%hist%fender_states, &
                         side_plane(par%side_y, ship_pose(par%with_ship, par%ship_part, &
                                                          par%ship_rest, y)), &
                         par%boat_part, y, clearance, force)
    end associate
  end subroutine system_contact_state

  !> The rigging's tensions, paid-out length and lump positions at (t, y)
  !> (davit_system_observables' rigging_state).
  pure subroutine system_rigging_state(self, t, y, seg, sling, paid, lumps)
    !> The system (on the davit).
    class(system_type), intent(in) :: self
    !> Time [s] and state vector.
    real(wp), intent(in) :: t, y(:)
    !> Cable segment tensions [N] (one per segment), sling segment tensions [N] (nlump + 1
    !> per sling, row 1 at the hook), paid-out length [m] and lump positions [m] (inertial,
    !> (3, nlump, sling)).
    real(wp), intent(out) :: seg(:), sling(:, :), paid, lumps(:, :, :)
    type(falls_ends_type) :: ends
    real(wp) :: tr
    associate (par => self%par, hist => self%hist)
      if (hist%release_time >= 0.0_wp) then
        ! The falls are not simulated after release (their states are frozen): report them
        ! as they were when the hooks let go.
        ends = falls_ends_type(hist%released_hooks, 0.0_wp, hist%released_pose)
        tr = hist%release_time
      else
        ends = falls_ends_at(par%boat_part, par%hooks, &
                             ship_pose(par%with_ship, par%ship_part, par%ship_rest, y), y)
        tr = t
      end if
      call rigging_state(par%rig, tr, y(par%rig_slice(1):par%rig_slice(2)), ends, &
                         hist%release_time >= 0.0_wp, seg, sling, paid, lumps)
    end associate
  end subroutine system_rigging_state

end module davit_system_model
