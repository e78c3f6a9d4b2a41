!> Quasi-static blocks (&rigging blocks = 'quasi_static', review §4.3 item 2): the force
!> balance of the two inertia-free blocks (eq. 82 without m_b a; weight eq. 78, cable pull
!> eqs. 69, 79, top sling segment eqs. 80-81, corrected 63), solved by Newton on the 6
!> block coordinates.
!>
!> The rigging's make-up that the balance needs is falls_type (davit_rigging_falls; the
!> rigging extends it); what changes with the state comes in a balance_input_type (sling
!> low ends, drum and sheaves, ship-fixed cable nodes); the balance at one set of block
!> positions and its linearisation is a balance_type. Nothing here knows the rigging's
!> state layout.
module davit_rigging_block_balance
  use davit_kinds, only: wp, gravity
  use davit_core_pose, only: pose_type
  use davit_rigging_cable, only: cable_node_kinematics
  use davit_rigging_falls, only: falls_type
  use davit_rigging_sling_chain, only: top_segment_tangent
  use davit_rigging_block_forces, only: balance_input_type, balance_type, block_balance
  implicit none
  private
  public :: balance_input_type, solve_blocks

  !> Newton on the elastic balance stops after a step of at most newton_tol [m]:
  !> convergence is quadratic there (analytic tangents, smooth while the active set
  !> holds), so what remains is below 1e-12 m, which keeps finite-difference Jacobians of
  !> the right-hand side (davit modes, RODAS3) clean; from an RK4 stage's start that takes
  !> 3 evaluations of the balance (start, step, dashpots). A step moves a block by at most
  !> newton_cap [m] (a block falling onto its cable after the drum paid out over a slack
  !> sling).
  real(wp), parameter :: newton_tol = 1.0e-9_wp, newton_cap = 2.0_wp
  !> newton_floor [N/m] on the diagonal keeps the matrix positive definite where a block
  !> has a direction that nothing holds (resting on its hook stop with both links slack:
  !> any place on the stop within the sling's slack is a balance) and ties the block's
  !> velocity in such a direction to its hook's, as the stop's friction does for a massive
  !> block. (With 1e-3 N/m and no tie, the velocity -(dF/dr)^(-1) dF/dt of such a block
  !> came out at ~100 m/s from the last few mN of a sling at its kink, its position copy
  !> ran off, and 13 of 432 water entries at 0.85 m/s stopped: input/sweep_lsa_fast.nml.)
  !> Far below every stiffness that holds a block (its pendulum on slack falls, m_b g/l ~
  !> 25 N/m; taut links 1e5 to 1e8 N/m), so it moves neither the balance (the floor is in
  !> the Newton matrix, not in the force) nor, by more than floor/k, the velocity.
  real(wp), parameter :: newton_floor = 0.1_wp
  integer, parameter :: newton_max = 60, search_max = 12, max_switches = 8
  !> A Newton step is cut back when it overshoots the balance along its line by more than
  !> search_ratio of the force component it started with (line_search); 0.1 leaves the
  !> quadratic regime alone (there the overshoot is ~|step|/l of it).
  real(wp), parameter :: search_ratio = 0.1_wp
  !> The dashpots shift a block by ~c v/k ~ 1e-4 m on taut links; dashpot_cap [m] bounds
  !> that shift where the links are so slack that a small dashpot force would move the
  !> block far across (it is then not first order in c/k any more).
  real(wp), parameter :: dashpot_cap = 1.0e-3_wp
  !> Fallback of solve_blocks: anchor stiffness m_b/anchor_time^2 (2e4 N/m for 50 kg),
  !> above a nearly slack block's pendulum stiffness (~1e2 to 1e3 N/m), far below a taut
  !> link's (1e7 N/m along it).
  real(wp), parameter :: anchor_time = 0.05_wp
  !> A sling counts as slack at the balance if its continued tension is below -k kink_tol
  !> (and as taut if its tension-only value is above k kink_tol); kink_tol [m] of stretch
  !> is far below what Newton leaves (< 1e-12 m) and far below anything physical.
  real(wp), parameter :: kink_tol = 1.0e-11_wp
  !> ... and is corrected during the iterations once it is off by more than gross_stretch
  !> [m] of stretch (6 kN on the default sling), which no converging iterate comes near.
  real(wp), parameter :: gross_stretch = 1.0e-4_wp
  !> ... or, for a held sling that pushes, once its push exceeds push_share of the block's
  !> weight (gross_correction).
  real(wp), parameter :: push_share = 0.1_wp

  !> Newton's iterate: blocks b, their velocity v, the last solve's solution x (step,
  !> velocity), the active set taut, the best iterate so far, the balance at b, the
  !> counts of active-set switches and balance evaluations, and the elastic force left on
  !> a block at the end [N].
  type :: newton_type
    real(wp) :: b(6) = 0.0_wp, v(6) = 0.0_wp, x(6, 2) = 0.0_wp
    real(wp) :: b_best(6) = 0.0_wp, best_norm = 0.0_wp, left = 0.0_wp
    logical :: taut(2) = .false., solved = .false.
    integer :: nswitch = 0, nbal = 0
    type(balance_type) :: bal
  end type newton_type

contains

  !> Quasi-static blocks: positions br (in: the start, e.g. the state's copies) where the
  !> net force on each block, cable pull + top sling segment + weight m_b g, vanishes, and
  !> their velocities bv on that balance, for the ship at `ship` and inp's low ends and
  !> drive. Both blocks together (6 coordinates): with quasi-static sheaves on reeving A
  !> one tension couples them. Where the balance fails (slack or nearly slack links in a
  !> violent phase: a hook unloaded by a wave or an impact, the falls paid out over a
  !> waterborne boat) the blocks are tied by m_b/anchor_time^2 to their start (the
  !> state's copies) and the balance solved again: the copies follow the solved blocks, so
  !> the anchor acts like the block's inertia over anchor_time, letting it drift rather
  !> than jump to where its slack links would put it. iterations: balance evaluations;
  !> residual: the elastic force left on a block at the balance [N] (links, stop and
  !> weight, without the fallback's anchor).
  pure subroutine solve_blocks(falls, inp, ship, br, bv, solved, iterations, residual)
    !> The falls (cables, top sling segments, block mass).
    type(falls_type), intent(in) :: falls
    !> The lower ends of the top segments, the hooks and the drive (balance_input_type).
    type(balance_input_type), intent(in) :: inp
    !> The ship's pose.
    type(pose_type), intent(in) :: ship
    !> Block positions (3, block), inertial [m]: in the start, out the balance.
    real(wp), intent(inout) :: br(3, 2)
    !> Block velocities (3, block) on the balance, inertial [m/s].
    real(wp), intent(out) :: bv(3, 2)
    !> Whether Newton's iteration converged.
    logical, intent(out) :: solved
    !> Balance evaluations used.
    integer, intent(out), optional :: iterations
    !> Largest net force left on a block relative to its load.
    real(wp), intent(out), optional :: residual
    type(balance_input_type) :: in
    real(wp) :: b0(3, 2), left
    integer :: c, n1, n2
    in = inp
    ! the ship-fixed nodes once (blocks at rest in vn); block_balance places the blocks
    do c = 1, falls%ncable
      call cable_node_kinematics(falls%cables(c), ship, br, 0.0_wp*br, in%pn(:, :, c), &
                                 in%vn(:, :, c))
    end do
    in%anchor(1:3) = br(:, 1)
    in%anchor(4:6) = br(:, 2)
    in%k_anchor = 0.0_wp
    b0 = br
    call newton_blocks(falls, in, br, bv, solved, n1, left)
    n2 = 0
    if (.not. solved) then
      br = b0
      in%k_anchor = falls%block_mass/anchor_time**2
      call newton_blocks(falls, in, br, bv, solved, n2, left)
    end if
    if (present(iterations)) iterations = n1 + n2
    if (present(residual)) residual = left
  end subroutine solve_blocks

  !> First the elastic balance (no dashpots): it minimises a convex potential (elastic
  !> energies - m_b g z) whose gradient and Hessian are -F and -dF/dr, so it is unique and
  !> symmetric, and it is well posed whenever the cable is taut, which the weight ensures
  !> (a tension-only sling pulls its block towards the hook; only the cable holds it up).
  !> Along the motion dF/dr dr + dF/dt = 0, so the blocks move at bv = -(dF/dr)^(-1) dF/dt,
  !> dF/dt the force rate due to everything else (hooks or lumps, ship-fixed nodes, drum,
  !> sheaves) at fixed blocks. Then the dashpots, at that velocity, shift the blocks by
  !> (-dF/dr)^(-1) F_dashpot, ~1e-4 m: the slow motion of the massive model to first
  !> order in c/k (its block lags the same way); left out are O((c v/k)^2/l) and the
  !> dashpots' response to accelerations, O(c a/k).
  !>
  !> Newton with: an active set for the slings' slack kink (D = l0, where Newton would
  !> cycle between the sides): each sling is held (its law continued smoothly through
  !> D = l0) or free (left out), guessed at the start, corrected once converged (a held
  !> sling that would push, or a free one that would pull, changes side) or at once when
  !> off by gross_stretch; steps capped at newton_cap per block and cut back where they
  !> overshoot (search_ratio); the diagonal floor newton_floor for a block with no taut
  !> link. After newton_max iterations the best iterate is taken if the force left on
  !> each block is below its weight, else solved = .false.; iterations counts the balance
  !> evaluations (3 from an RK4 stage's start: start, step, dashpots).
  pure subroutine newton_blocks(falls, inp, br, bv, solved, iterations, left)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    real(wp), intent(inout) :: br(3, 2)
    real(wp), intent(out) :: bv(3, 2)
    logical, intent(out) :: solved
    integer, intent(out) :: iterations
    real(wp), intent(out) :: left
    type(newton_type) :: nt
    integer :: it
    logical :: done
    call newton_start(falls, inp, br, nt)
    do it = 1, newton_max
      call newton_iteration(falls, inp, nt, done)
      if (done) exit
    end do
    if (.not. nt%solved) call best_iterate(falls, inp, nt)
    call dashpot_shift(falls, inp, nt)
    left = nt%left
    br(:, 1) = nt%b(1:3)
    br(:, 2) = nt%b(4:6)
    bv(:, 1) = nt%v(1:3)
    bv(:, 2) = nt%v(4:6)
    solved = nt%solved
    iterations = nt%nbal
  end subroutine newton_blocks

  !> Newton's start at br: which slings hold their blocks is guessed from their tension-only
  !> law there (then corrected: the active set), and the balance evaluated.
  pure subroutine newton_start(falls, inp, br, nt)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    real(wp), intent(in) :: br(3, 2)
    type(newton_type), intent(out) :: nt
    real(wp) :: f_top(3), k(3, 3), f_sling, f_real
    integer :: c
    nt%b(1:3) = br(:, 1)
    nt%b(4:6) = br(:, 2)
    nt%v = 0.0_wp
    nt%nswitch = 0
    nt%solved = .false.
    do c = 1, 2
      call top_segment_tangent(falls%sling, inp%low_r(:, c), inp%low_v(:, c), br(:, c), &
                               0.0_wp*br(:, c), f_top, f_sling, f_real, k)
      nt%taut(c) = f_real > 0.0_wp
    end do
    call block_balance(falls, inp, nt%b, nt%v, nt%taut, nt%bal)
    nt%nbal = 1
    nt%best_norm = huge(1.0_wp)
    nt%b_best = nt%b
  end subroutine newton_start

  !> One Newton iteration: (-dF/dr + floor) x = [F, dF/dt], x(:, 1) the step (capped at
  !> newton_cap), x(:, 2) the velocity. A step below newton_tol has converged for this
  !> active set (active_set); a larger one is cut back by the line search and taken.
  !> done: stop iterating (solved, or out of active-set switches).
  pure subroutine newton_iteration(falls, inp, nt, done)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    type(newton_type), intent(inout) :: nt
    logical, intent(out) :: done
    real(wp) :: step(6), b_try(6), longest
    type(balance_type) :: bal_t
    done = .false.
    call newton_matrix(nt%bal%jac)
    nt%x(:, 1) = nt%bal%res
    nt%x(:, 2) = velocity_rhs(inp, nt%bal)
    call dense_solve(nt%bal%jac, nt%x)
    step = nt%x(:, 1)
    longest = max(norm2(step(1:3)), norm2(step(4:6)))
    if (longest > newton_cap) step = step*(newton_cap/longest)
    if (maxval(abs(step)) <= newton_tol) then
      nt%b = nt%b + step
      call active_set(falls, inp, nt, done)
      return
    end if
    call line_search(falls, inp, nt, step, b_try, bal_t)
    nt%b = b_try
    nt%bal = bal_t
    if (max(norm2(nt%bal%res(1:3)), norm2(nt%bal%res(4:6))) < nt%best_norm) then
      nt%best_norm = max(norm2(nt%bal%res(1:3)), norm2(nt%bal%res(4:6)))
      nt%b_best = nt%b
    end if
    call gross_correction(falls, inp, nt)
  end subroutine newton_iteration

  !> Converged with these slings holding: a held sling must pull, a free one must not. If
  !> none changes side the balance is solved (done); else, up to max_switches times, the
  !> balance is taken again with the new active set.
  pure subroutine active_set(falls, inp, nt, done)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    type(newton_type), intent(inout) :: nt
    logical, intent(out) :: done
    real(wp) :: f_tol
    logical :: changed
    integer :: c
    f_tol = falls%sling%k_seg*kink_tol
    changed = .false.
    do c = 1, 2
      if (nt%taut(c) .and. nt%bal%f_sling(c) < -f_tol .or. &
          .not. nt%taut(c) .and. nt%bal%f_real(c) > f_tol) then
        nt%taut(c) = .not. nt%taut(c)
        changed = .true.
      end if
    end do
    done = .true.
    if (.not. changed) then
      nt%solved = .true.
      return
    end if
    nt%nswitch = nt%nswitch + 1
    if (nt%nswitch > max_switches) return
    call block_balance(falls, inp, nt%b, nt%v, nt%taut, nt%bal)
    nt%nbal = nt%nbal + 1
    nt%best_norm = huge(1.0_wp)
    done = .false.
  end subroutine active_set

  !> Line search: along the step the force component g(alpha) = step . F(b + alpha step)
  !> starts positive, g(0) = F . (-dF/dr)^(-1) F, and falls (the potential is convex).
  !> A whole step leaves g(1) ~ 0 (quadratic convergence) and is taken; one that
  !> overshoots, g(1) < -search_ratio g(0) (a far start, a kink where a link goes slack,
  !> the soft swing of a block on slack links), is cut back to where g is within
  !> search_ratio g(0) of zero, by regula falsi (Illinois) on [0, 1]. Returns the blocks
  !> b_try taken and the balance bal_t there.
  pure subroutine line_search(falls, inp, nt, step, b_try, bal_t)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    type(newton_type), intent(inout) :: nt
    real(wp), intent(in) :: step(6)
    real(wp), intent(out) :: b_try(6)
    type(balance_type), intent(out) :: bal_t
    real(wp) :: g, g_lo, g_hi, g_tol, a_lo, a_hi, alpha
    integer :: ls, side
    b_try = nt%b + step
    call block_balance(falls, inp, b_try, nt%v, nt%taut, bal_t)
    nt%nbal = nt%nbal + 1
    g_lo = dot_product(nt%bal%res, step)
    g_hi = dot_product(bal_t%res, step)
    if (.not. (g_lo > 0.0_wp .and. g_hi < -search_ratio*g_lo)) return
    g_tol = search_ratio*g_lo
    a_lo = 0.0_wp
    a_hi = 1.0_wp
    side = 0
    do ls = 1, search_max
      alpha = a_hi - g_hi*(a_hi - a_lo)/(g_hi - g_lo)
      b_try = nt%b + alpha*step
      call block_balance(falls, inp, b_try, nt%v, nt%taut, bal_t)
      nt%nbal = nt%nbal + 1
      g = dot_product(bal_t%res, step)
      if (abs(g) <= g_tol) return
      if (g < 0.0_wp) then
        a_hi = alpha
        g_hi = g
        if (side == -1) g_lo = 0.5_wp*g_lo
        side = -1
      else
        a_lo = alpha
        g_lo = g
        if (side == 1) g_hi = 0.5_wp*g_hi
        side = 1
      end if
    end do
    ! not bracketed to search_ratio within search_max: take the bracket's low end, up to
    ! which the force component stayed positive (the potential fell all the way there)
    if (a_lo > 0.0_wp) then
      b_try = nt%b + a_lo*step
      call block_balance(falls, inp, b_try, nt%v, nt%taut, bal_t)
      nt%nbal = nt%nbal + 1
    end if
  end subroutine line_search

  !> A guess that is plainly wrong (a free sling stretched by more than gross_stretch, or
  !> a held one pushing by more than push_share of the block's weight) is corrected at
  !> once rather than after converging to it. (A held sling that carries the block's weight
  !> as a push is an inverted pendulum: the continued law has no stable balance there for
  !> Newton to converge to, so the push must free it at once.)
  pure subroutine gross_correction(falls, inp, nt)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    type(newton_type), intent(inout) :: nt
    real(wp) :: f_gross, f_push
    logical :: wrong(2)
    f_gross = falls%sling%k_seg*gross_stretch
    f_push = push_share*falls%block_mass*gravity
    associate (taut => nt%taut, f_sling => nt%bal%f_sling, f_real => nt%bal%f_real)
      wrong = taut .and. f_sling < -f_push .or. .not. taut .and. f_real > f_gross
      if (nt%nswitch < max_switches .and. any(wrong)) then
        taut = taut .neqv. wrong
        nt%nswitch = nt%nswitch + 1
        call block_balance(falls, inp, nt%b, nt%v, taut, nt%bal)
        nt%nbal = nt%nbal + 1
        nt%best_norm = huge(1.0_wp)
        nt%b_best = nt%b
      end if
    end associate
  end subroutine gross_correction

  !> Newton stalled (links near slack: soft and kinked): take the best iterate (of this
  !> active set) if the force left on each block, and the force a sling would have on the
  !> wrong side of its kink, are below the block's weight. Neglecting the block's inertia
  !> already errs by m_b a, of that size when slack slings jerk the block about; taut
  !> links converge in 2-3 evaluations. Leaves the velocity solve in x(:, 2).
  pure subroutine best_iterate(falls, inp, nt)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    type(newton_type), intent(inout) :: nt
    real(wp) :: weight
    weight = falls%block_mass*gravity
    nt%b = nt%b_best
    call block_balance(falls, inp, nt%b, nt%v, nt%taut, nt%bal)
    nt%nbal = nt%nbal + 1
    associate (res => nt%bal%res, taut => nt%taut)
      nt%solved = max(norm2(res(1:3)), norm2(res(4:6))) <= weight .and. &
                  all(.not. taut .or. nt%bal%f_sling >= -weight) .and. &
                  all(taut .or. nt%bal%f_real <= weight)
    end associate
    call newton_matrix(nt%bal%jac)
    nt%x(:, 2) = velocity_rhs(inp, nt%bal)
    call dense_solve(nt%bal%jac, nt%x)
  end subroutine best_iterate

  !> Right-hand side of the velocity solve (-dF/dr + floor) v = dF/dt + floor v_hook: a
  !> direction that nothing holds moves with the block's hook.
  pure function velocity_rhs(inp, bal) result(r)
    type(balance_input_type), intent(in) :: inp
    type(balance_type), intent(in) :: bal
    real(wp) :: r(6)
    r(1:3) = bal%rate(1:3) + newton_floor*inp%hook_v(:, 1)
    r(4:6) = bal%rate(4:6) + newton_floor*inp%hook_v(:, 2)
  end function velocity_rhs

  !> The velocity on the balance (from the last tangent, within newton_tol of it), then
  !> the dashpots at that velocity and the shift by what is left (their force, and the
  !> balance's own ~1e-6 N), capped at dashpot_cap.
  pure subroutine dashpot_shift(falls, inp, nt)
    type(falls_type), intent(in) :: falls
    type(balance_input_type), intent(in) :: inp
    type(newton_type), intent(inout) :: nt
    real(wp) :: step(6), longest
    nt%v = nt%x(:, 2)
    call block_balance(falls, inp, nt%b, nt%v, nt%taut, nt%bal, dashpots=.true.)
    nt%nbal = nt%nbal + 1
    ! the force left by the links, stop and weight alone (without the fallback's anchor)
    step = nt%bal%res + inp%k_anchor*(nt%b - inp%anchor)
    nt%left = max(norm2(step(1:3)), norm2(step(4:6)))
    call newton_matrix(nt%bal%jac)
    nt%x(:, 1) = nt%bal%res + nt%bal%res_d
    nt%x(:, 2) = 0.0_wp
    call dense_solve(nt%bal%jac, nt%x)
    step = nt%x(:, 1)
    ! only where the sling holds: a free block would be moved by the cable's dashpot
    ! alone, along links so slack that the shift would no longer be small (and could
    ! take up its sling's slack, which the balance has not seen)
    if (.not. nt%taut(1)) step(1:3) = 0.0_wp
    if (.not. nt%taut(2)) step(4:6) = 0.0_wp
    longest = max(norm2(step(1:3)), norm2(step(4:6)))
    if (longest > dashpot_cap) step = step*(dashpot_cap/longest)
    nt%b = nt%b + step
  end subroutine dashpot_shift

  !> -jac + newton_floor I, the matrix of the Newton step.
  pure subroutine newton_matrix(jac)
    real(wp), intent(inout) :: jac(6, 6)
    integer :: j
    jac = -jac
    do j = 1, 6
      jac(j, j) = jac(j, j) + newton_floor
    end do
  end subroutine newton_matrix

  !> Solves a x = b in place (b holds x on return) by Gaussian elimination with partial
  !> pivoting; a is overwritten. For the small, regular 6 x 6 systems of the balance.
  pure subroutine dense_solve(a, b)
    real(wp), intent(inout) :: a(6, 6), b(6, 2)
    real(wp) :: row(6), rhs(2), m
    integer :: i, j, k, piv
    do j = 1, 6
      piv = j - 1 + maxloc(abs(a(j:6, j)), 1)
      if (piv /= j) then
        row = a(j, :)
        a(j, :) = a(piv, :)
        a(piv, :) = row
        rhs = b(j, :)
        b(j, :) = b(piv, :)
        b(piv, :) = rhs
      end if
      do i = j + 1, 6
        m = a(i, j)/a(j, j)
        a(i, j + 1:6) = a(i, j + 1:6) - m*a(j, j + 1:6)
        b(i, :) = b(i, :) - m*b(j, :)
      end do
    end do
    do j = 6, 1, -1
      do k = j + 1, 6
        b(j, :) = b(j, :) - a(j, k)*b(k, :)
      end do
      b(j, :) = b(j, :)/a(j, j)
    end do
  end subroutine dense_solve

end module davit_rigging_block_balance
