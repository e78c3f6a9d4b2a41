!> The force balance of the two inertia-free blocks (&rigging blocks = 'quasi_static'):
!> at given block positions and velocities, the net force on each block (weight eq. 78,
!> cable pull eqs. 69, 79, top sling segment eqs. 80-81, corrected 63, hook stop), its
!> Jacobian with respect to the block positions and its rate at fixed blocks, and the
!> dashpots' share. davit_rigging_block_balance solves the balance by Newton on these.
module davit_rigging_block_forces
  use davit_kinds, only: wp, gravity
  use davit_core_rotation, only: length3
  use davit_rigging_sling_chain, only: sling_chain_type, top_segment_tangent
  use davit_rigging_cable, only: cable_type, cable_eval_type, max_nodes, node_block, &
                                 cable_node_forces, cable_block_tangent_rotating, &
                                 cable_block_tangent_quasi_static
  use davit_rigging_falls, only: falls_type, drive_type, max_sheaves, cable_tensions
  use davit_rigging_block_stop, only: stop_tangent
  implicit none
  private
  public :: balance_input_type, balance_type, block_balance

  !> What the balance takes from the rest of the system. The caller sets the lower ends of
  !> the top sling segments (hook or top lump) and their velocities, the hooks (for the
  !> blocks' stops, davit_rigging_block_stop) and theirs, and the drive;
  !> solve_blocks sets the cables' ship-fixed node positions pn and velocities vn (block
  !> nodes at rest in vn: rates are taken at fixed blocks) and, for its fallback, the
  !> anchor of the blocks and its stiffness k_anchor (0: none).
  type :: balance_input_type
    !> Lower ends of the top sling segments (3, sling), inertial [m], and their velocities [m/s].
    real(wp) :: low_r(3, 2) = 0.0_wp, low_v(3, 2) = 0.0_wp
    !> Hook positions (3, hook), inertial [m], and their velocities [m/s] (the blocks' stops).
    real(wp) :: hook_r(3, 2) = 0.0_wp, hook_v(3, 2) = 0.0_wp
    !> Drum passage and speed, sheave angles and rates.
    type(drive_type) :: drive
    !> The cables' node positions (3, node, cable), inertial [m], and velocities [m/s], set by
    !> solve_blocks.
    real(wp) :: pn(3, max_nodes, 2) = 0.0_wp, vn(3, max_nodes, 2) = 0.0_wp
    !> Anchor positions of the two blocks (3 each), inertial [m], and the anchoring spring [N/m]
    !> (0: none).
    real(wp) :: anchor(6) = 0.0_wp, k_anchor = 0.0_wp
  end type balance_input_type

  !> The elastic balance at block positions b (6): net force res on the blocks, its
  !> Jacobian jac = d res/d b, its rate at fixed blocks rate = d res/dt; f_sling: the top
  !> segments' elastic tensions continued through slack (< 0 there), f_real: their
  !> tension-only values; res_d: the dashpots' force on the moving blocks (0 unless asked).
  type :: balance_type
    !> Net force on the blocks [N], its Jacobian d res/d b [N/m] and its rate at fixed blocks
    !> [N/s].
    real(wp) :: res(6) = 0.0_wp, jac(6, 6) = 0.0_wp, rate(6) = 0.0_wp
    !> The top segments' elastic tensions continued through slack and their tension-only values
    !> [N]; the dashpots' force on the blocks [N].
    real(wp) :: f_sling(2) = 0.0_wp, f_real(2) = 0.0_wp, res_d(6) = 0.0_wp
  end type balance_type

contains

  !> The elastic balance bal on the two blocks at positions b (cable and top sling segments
  !> where held, without their dashpots, and weight; balance_type); with dashpots, also
  !> the dashpots' force on the blocks moving at v (cable, and held slings). With
  !> inp%k_anchor > 0 a spring k_anchor ties each block to inp%anchor (solve_blocks'
  !> fallback).
  pure subroutine block_balance(falls, inp, b, v, taut, bal, dashpots)
    !> The falls.
    type(falls_type), intent(in) :: falls
    !> The lower ends, hooks, drive and nodes (balance_input_type).
    type(balance_input_type), intent(in) :: inp
    !> Block positions and velocities (two blocks, 3 each), inertial [m, m/s].
    real(wp), intent(in) :: b(6), v(6)
    !> Per sling, whether its top segment is held (taut).
    logical, intent(in) :: taut(2)
    !> The balance at b.
    type(balance_type), intent(out) :: bal
    !> Also the dashpots' force (default: without).
    logical, intent(in), optional :: dashpots
    real(wp) :: br(3, 2), bv(3, 2), block_f(3, 2), damp_f(3, 2)
    integer :: i
    logical :: with_dashpots
    with_dashpots = .false.
    if (present(dashpots)) with_dashpots = dashpots
    br(:, 1) = b(1:3)
    br(:, 2) = b(4:6)
    bv(:, 1) = v(1:3)
    bv(:, 2) = v(4:6)
    bal%jac = 0.0_wp
    bal%rate = 0.0_wp
    block_f = 0.0_wp
    block_f(3, :) = falls%block_mass*gravity
    damp_f = 0.0_wp
    call sling_pulls(falls, inp, br, bv, taut, with_dashpots, block_f, damp_f, bal)
    call cable_pulls(falls, inp, br, bv, with_dashpots, block_f, damp_f, bal)
    call stop_pushes(falls, inp, br, block_f, bal)
    bal%res(1:3) = block_f(:, 1)
    bal%res(4:6) = block_f(:, 2)
    if (inp%k_anchor > 0.0_wp) then
      bal%res = bal%res - inp%k_anchor*(b - inp%anchor)
      do i = 1, 6
        bal%jac(i, i) = bal%jac(i, i) - inp%k_anchor
      end do
    end if
    bal%res_d(1:3) = damp_f(:, 1)
    bal%res_d(4:6) = damp_f(:, 2)
  end subroutine block_balance

  !> block_balance's top sling segments (eqs. 80-81): their elastic pull on the blocks at
  !> br where held (taut), its tangent and rate (the low ends moving), the continued and
  !> tension-only tensions, and with_dashpots the dashpots' share at block velocities bv.
  pure subroutine sling_pulls(falls, inp, br, bv, taut, with_dashpots, block_f, damp_f, bal)
    ! 9 arguments: the balance's accumulators (block_f, damp_f, bal) are shared with
    ! cable_pulls, which adds to them in the order block_balance has always summed.
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    real(wp), intent(in) :: br(3, 2), bv(3, 2)
    logical, intent(in) :: taut(2), with_dashpots
    real(wp), intent(inout) :: block_f(3, 2), damp_f(3, 2)
    type(balance_type), intent(inout) :: bal
    type(sling_chain_type) :: sling_el
    real(wp) :: f_top(3), k(3, 3), f_damped(3), fs_damped, fr_damped, k_damped(3, 3)
    integer :: a
    sling_el = falls%sling
    sling_el%c_seg = 0.0_wp
    sling_el%c_top = 0.0_wp
    do a = 1, 2
      call top_segment_tangent(sling_el, inp%low_r(:, a), inp%low_v(:, a), br(:, a), &
                               bv(:, a), f_top, bal%f_sling(a), bal%f_real(a), k)
      if (.not. taut(a)) cycle
      if (with_dashpots) then
        call top_segment_tangent(falls%sling, inp%low_r(:, a), inp%low_v(:, a), br(:, a), &
                                 bv(:, a), f_damped, fs_damped, fr_damped, k_damped)
        damp_f(:, a) = f_damped - f_top
      end if
      block_f(:, a) = block_f(:, a) + f_top
      ! a held sling pushing (continued through slack, f < 0) would turn its push with the
      ! chord, a negative stiffness across it (the continued energy is not convex there):
      ! Newton's tangent keeps only what a pull would give, so its matrix stays positive
      ! definite and the step descends; the active set then frees the sling
      if (bal%f_sling(a) < 0.0_wp) call clip_across(inp%low_r(:, a), br(:, a), bal%f_sling(a), k)
      bal%jac(3*a - 2:3*a, 3*a - 2:3*a) = k
      bal%rate(3*a - 2:3*a) = -matmul(k, inp%low_v(:, a))
    end do
  end subroutine sling_pulls

  !> The tangent k of a segment from r_low to r_top pushing with f < 0, without its
  !> negative stiffness across the chord, f/D (I - e e^T).
  pure subroutine clip_across(r_low, r_top, f, k)
    real(wp), intent(in) :: r_low(3), r_top(3), f
    real(wp), intent(inout) :: k(3, 3)
    real(wp) :: e(3), dist
    integer :: j
    dist = length3(r_top - r_low)
    e = (r_top - r_low)/dist
    do j = 1, 3
      k(:, j) = k(:, j) - f/dist*e(j)*e
      k(j, j) = k(j, j) + f/dist
    end do
  end subroutine clip_across

  !> block_balance's hook stops (davit_rigging_block_stop): a block resting on its hook
  !> (slack falls) is held there under its weight, where without the stop it would have no
  !> balance. Elastic only (a C1 law: the tangent stays continuous); vertical tangent.
  pure subroutine stop_pushes(falls, inp, br, block_f, bal)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    real(wp), intent(in) :: br(3, 2)
    real(wp), intent(inout) :: block_f(3, 2)
    type(balance_type), intent(inout) :: bal
    real(wp) :: f(3), dfdz, rate
    integer :: a
    do a = 1, 2
      call stop_tangent(falls%stop, inp%hook_r(:, a), inp%hook_v(:, a), br(:, a), f, dfdz, rate)
      block_f(:, a) = block_f(:, a) + f
      bal%jac(3*a, 3*a) = bal%jac(3*a, 3*a) + dfdz
      bal%rate(3*a) = bal%rate(3*a) + rate
    end do
  end subroutine stop_pushes

  !> block_balance's cables (eqs. 69, 79): their elastic pull on the blocks at br, its
  !> tangent and rate at fixed blocks, and with_dashpots the dashpots' share (the same
  !> cable with and without them) at block velocities bv.
  pure subroutine cable_pulls(falls, inp, br, bv, with_dashpots, block_f, damp_f, bal)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    real(wp), intent(in) :: br(3, 2), bv(3, 2)
    logical, intent(in) :: with_dashpots
    real(wp), intent(inout) :: block_f(3, 2), damp_f(3, 2)
    type(balance_type), intent(inout) :: bal
    type(cable_type) :: cab_el
    type(cable_eval_type) :: ce
    real(wp) :: p(3, max_nodes), vv(3, max_nodes), torque(max_sheaves)
    integer :: c, i
    torque = 0.0_wp
    do c = 1, falls%ncable
      associate (cab => falls%cables(c))
        p = inp%pn(:, :, c)
        vv = inp%vn(:, :, c)
        do i = 1, cab%nnode
          if (cab%kind(i) /= node_block) cycle
          p(:, i) = br(:, cab%block(i))
          vv(:, i) = bv(:, cab%block(i))
        end do
        ! without the dashpots (the same cable with c = 0); asked for, also with them:
        ! the difference is the dashpots' share
        if (with_dashpots) then
          call cable_tensions(falls, cab, c, inp%drive, p, vv, ce)
          call cable_node_forces(cab, ce%lam, ce%f, ce%g, falls%sheave_radius, damp_f, torque)
        end if
        cab_el = cab
        cab_el%damping = 0.0_wp
        call cable_tensions(falls, cab_el, c, inp%drive, p, vv, ce)
        call cable_node_forces(cab_el, ce%lam, ce%f, ce%g, falls%sheave_radius, block_f, &
                               torque)
        if (with_dashpots) call cable_node_forces(cab_el, ce%lam, -ce%f, -ce%g, &
                                                  falls%sheave_radius, damp_f, torque)
        if (falls%rotating) then
          call cable_block_tangent_rotating(cab_el, ce, vv, inp%vn(:, :, c), bal%jac, bal%rate)
        else
          call cable_block_tangent_quasi_static(cab_el, ce, &
                                                falls%l0_total(c) + inp%drive%s_drum, &
                                                inp%drive%v_drum, falls%friction_ratio, &
                                                vv, inp%vn(:, :, c), bal%jac, bal%rate)
        end if
      end associate
    end do
  end subroutine cable_pulls

end module davit_rigging_block_forces
