!> The C ABI's getters (include/davit.h): what a session holds now, computed as
!> davit_run_recorders samples it, so that the values equal `davit run`'s output datasets.
!> Arrays are written into the caller's buffers of the length given; a short buffer is an
!> error (DAVIT_E_ARG), never a partial write.
module davit_capi_getters
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_size_t
  use davit_kinds, only: wp
  use davit_system_parameters, only: nslings, hook_kinematics, ship_pose
  use davit_core_pose, only: pose_type
  use davit_assess_rules, only: n_checks, rule_check, check_ids
  use davit_capi_handle, only: capi_handle, ready_handle, fail, copy_c_string, e_arg, e_ok
  implicit none
  private
  public :: davit_time, davit_finished, davit_sizes, davit_state, davit_boat_pose
  public :: davit_ship_pose, davit_blocks, davit_hooks, davit_sling_tensions
  public :: davit_fall_tensions, davit_fender_forces, davit_events, davit_impacts
  public :: davit_rule_checks, davit_check_name

contains

  real(c_double) function davit_time(h) bind(c) result(t)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    type(capi_handle), pointer :: p
    integer(c_int) :: rc
    t = -1.0_c_double
    p => ready_handle(h, rc)
    if (associated(p)) t = p%s%t
  end function davit_time

  !> 1 once the run has ended (t_end, or the deck's time after release), else 0.
  integer(c_int) function davit_finished(h) bind(c) result(f)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    type(capi_handle), pointer :: p
    integer(c_int) :: rc
    f = 0
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    if (p%s%done .or. .not. p%s%t < p%s%cfg%simulation%t_end) f = 1
  end function davit_finished

  !> n(1:4) = state components, fall (cable) segments, fenders, rule checks.
  integer(c_int) function davit_sizes(h, n) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Sizes of the state, fall segments, fenders and rule checks.
    integer(c_int), intent(out) :: n(4)
    type(capi_handle), pointer :: p
    n = 0
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    n(1) = size(p%s%y)
    if (p%s%sys%par%on_davit) n(2) = p%s%sys%par%rig%nseg
    n(3) = p%s%sys%par%fenders%nf
    n(4) = n_checks
  end function davit_sizes

  !> `len` values into `out`, or the error for a short buffer.
  integer(c_int) function put(p, what, v, out, len) result(rc)
    !> The handle (its error set for a short buffer).
    type(capi_handle), intent(inout) :: p
    !> What is copied (for the message).
    character(len=*), intent(in) :: what
    !> The values.
    real(wp), intent(in) :: v(:)
    !> The caller's buffer.
    real(c_double), intent(out) :: out(*)
    !> Length of the buffer.
    integer(c_int), intent(in) :: len
    if (len < size(v)) then
      rc = fail(p, e_arg, what//": the buffer is shorter than davit_sizes says")
      return
    end if
    out(1:size(v)) = v
    rc = e_ok
  end function put

  integer(c_int) function davit_state(h, y, len) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Buffer receiving the state vector.
    real(c_double), intent(out) :: y(*)
    !> Length of the buffer.
    integer(c_int), value, intent(in) :: len
    type(capi_handle), pointer :: p
    p => ready_handle(h, rc)
    if (associated(p)) rc = put(p, "state", p%s%y, y, len)
  end function davit_state

  !> CG position, Euler angles, CG velocity (inertial), angular velocity (boat axes):
  !> /boat/position, euler, velocity and angular_velocity of `davit run`.
  integer(c_int) function davit_boat_pose(h, out) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> CG position [m], Euler angles [rad], CG velocity [m/s] (inertial) and angular velocity
    !> [rad/s] (boat axes).
    real(c_double), intent(out) :: out(12)
    type(capi_handle), pointer :: p
    real(wp) :: acc(3)
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    call p%s%sys%observe(p%s%t, p%s%y, out(1:3), out(4:6), out(7:9), out(10:12), acc)
  end function davit_boat_pose

  !> The ship's CG position and Euler angles (/ship/position, /ship/euler); a ship that
  !> does not move: its fixed pose (position, Euler angles zero but the heading's).
  integer(c_int) function davit_ship_pose(h, out) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Ship's CG position [m] and Euler angles [rad] (inertial).
    real(c_double), intent(out) :: out(6)
    type(capi_handle), pointer :: p
    type(pose_type) :: pose
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    associate (sys => p%s%sys, y => p%s%y)
      if (sys%par%with_ship) then
        out(1:3) = y(sys%par%ship_part%q(1) + 3:sys%par%ship_part%q(1) + 5)
        out(4:6) = y(sys%par%ship_part%q(1):sys%par%ship_part%q(1) + 2)
      else
        pose = ship_pose(sys%par%with_ship, sys%par%ship_part, sys%par%ship_rest, y)
        out(1:3) = pose%r
        out(4:5) = 0.0_wp
        out(6) = atan2(pose%c(2, 1), pose%c(1, 1))
      end if
    end associate
  end function davit_ship_pose

  !> The movable blocks' positions (3 x 2, inertial; zero without the full rigging).
  integer(c_int) function davit_blocks(h, out) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> The movable blocks' positions [m] (inertial).
    real(c_double), intent(out) :: out(3, 2)
    type(capi_handle), pointer :: p
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    out = 0.0_wp
    associate (sys => p%s%sys)
      if (sys%par%on_davit) out = sys%par%rig%block_positions(p%s%y(sys%par%rig_slice(1): &
                                                                    sys%par%rig_slice(2)))
    end associate
  end function davit_blocks

  !> The hooks' positions (3 x 2, inertial).
  integer(c_int) function davit_hooks(h, out) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> The hooks' positions [m] (inertial).
    real(c_double), intent(out) :: out(3, nslings)
    type(capi_handle), pointer :: p
    real(wp) :: vel(3, nslings)
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    associate (par => p%s%sys%par)
      call hook_kinematics(par%boat_part, par%hooks, p%s%y, out, vel)
    end associate
  end function davit_hooks

  !> Fall segment tensions (seg; none with the boat not on the davit) and the slings'
  !> hook-end tensions, as the recorder.
  subroutine tensions(p, seg, sling)
    !> The handle (its session).
    type(capi_handle), intent(in) :: p
    !> Fall segment tensions [N].
    real(wp), allocatable, intent(out) :: seg(:)
    !> Each sling's tension at its hook [N].
    real(wp), intent(out) :: sling(nslings)
    real(wp) :: sl(p%s%sys%par%rig%nlump + 1, nslings), lumps(3, p%s%sys%par%rig%nlump, nslings)
    real(wp) :: paid
    associate (sys => p%s%sys)
      allocate (seg(merge(sys%par%rig%nseg, 0, sys%par%on_davit)))
      sling = sys%sling_tensions(p%s%y)
      if (sys%par%on_davit) then
        call sys%rigging_state(p%s%t, p%s%y, seg, sl, paid, lumps)
        sling = sl(1, :)
      end if
    end associate
  end subroutine tensions

  !> /slings/tension: each sling's tension at its hook [N].
  integer(c_int) function davit_sling_tensions(h, out) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Each sling's tension at its hook [N].
    real(c_double), intent(out) :: out(nslings)
    type(capi_handle), pointer :: p
    real(wp), allocatable :: seg(:)
    p => ready_handle(h, rc)
    if (associated(p)) call tensions(p, seg, out)
  end function davit_sling_tensions

  !> The falls' cable segment tensions [N] (/rigging/segment_tension).
  integer(c_int) function davit_fall_tensions(h, out, len) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Buffer receiving the segment tensions [N].
    real(c_double), intent(out) :: out(*)
    !> Length of the buffer.
    integer(c_int), value, intent(in) :: len
    type(capi_handle), pointer :: p
    real(wp) :: sling(nslings)
    real(wp), allocatable :: seg(:)
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    call tensions(p, seg, sling)
    rc = put(p, "fall tensions", seg, out, len)
  end function davit_fall_tensions

  !> Each fender's contact force [N] (/contact/force).
  integer(c_int) function davit_fender_forces(h, out, len) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Buffer receiving the fender forces [N].
    real(c_double), intent(out) :: out(*)
    !> Length of the buffer.
    integer(c_int), value, intent(in) :: len
    type(capi_handle), pointer :: p
    real(wp) :: clearance
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    block
      real(wp) :: force(p%s%sys%par%fenders%nf)
      call p%s%sys%contact_state(p%s%y, clearance, force)
      rc = put(p, "fender forces", force, out, len)
    end block
  end function davit_fender_forces

  !> Times [s] of the first fender contact, waterborne and hook release (-1: not yet),
  !> and the number of fender impacts so far.
  integer(c_int) function davit_events(h, out) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> First contact, waterborne and hook release times [s] (-1: not yet), impact count.
    real(c_double), intent(out) :: out(4)
    type(capi_handle), pointer :: p
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    associate (hist => p%s%sys%hist)
      out(1:3) = [hist%first_contact_time, hist%waterborne_time, hist%release_time]
    end associate
    out(4) = p%s%log%impacts%n
  end function davit_events

  !> The impacts so far, 4 values each: onset [s], fender (1-based), normal impact speed
  !> [m/s], peak force [N]; `len` values at most (4 x davit_events' count).
  integer(c_int) function davit_impacts(h, out, len) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Buffer receiving 4 values per impact.
    real(c_double), intent(out) :: out(*)
    !> Length of the buffer.
    integer(c_int), value, intent(in) :: len
    type(capi_handle), pointer :: p
    integer :: i
    p => ready_handle(h, rc)
    if (.not. associated(p)) return
    associate (im => p%s%log%impacts)
      if (len < 4*im%n) then
        rc = fail(p, e_arg, "impacts: the buffer is shorter than 4 x the impacts")
        return
      end if
      do i = 1, im%n
        out(4*i - 3:4*i) = [im%events(i)%time, real(im%events(i)%fender, wp), &
                            im%events(i)%speed, im%events(i)%peak_force]
      end do
    end associate
  end function davit_impacts

  !> The rule checks so far (davit_assess_rules' order): value, limit and margin of each
  !> (NaN where a check does not apply yet).
  integer(c_int) function davit_rule_checks(h, value, limit, margin, len) bind(c) result(rc)
    !> The handle.
    type(c_ptr), value, intent(in) :: h
    !> Buffers receiving each check's value, limit and relative margin.
    real(c_double), intent(out) :: value(*), limit(*), margin(*)
    !> Length of each buffer.
    integer(c_int), value, intent(in) :: len
    type(capi_handle), pointer :: p
    type(rule_check) :: c(n_checks)
    p => ready_handle(h, rc, len >= n_checks, &
                      "rule checks: the buffers are shorter than davit_sizes says")
    if (.not. associated(p)) return
    c = p%s%log%checks()
    value(1:n_checks) = c%value
    limit(1:n_checks) = c%limit
    margin(1:n_checks) = c%margin
  end function davit_rule_checks

  !> The identifier of rule check i (1-based) into buf (NUL-terminated); its length, or
  !> -1 for no such check.
  integer(c_int) function davit_check_name(i, buf, len) bind(c) result(n)
    !> Index of the rule check (1-based).
    integer(c_int), value, intent(in) :: i
    !> The C buffer receiving the name.
    type(c_ptr), value, intent(in) :: buf
    !> Size of the buffer [bytes].
    integer(c_size_t), value, intent(in) :: len
    n = -1
    if (i < 1 .or. i > n_checks) return
    n = len_trim(check_ids(i))
    call copy_c_string(check_ids(i), buf, len)
  end function davit_check_name

end module davit_capi_getters
