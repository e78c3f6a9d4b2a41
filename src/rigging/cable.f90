!> One continuous cable over drum, sheaves and movable blocks to a dead end (paper §II.E,
!> eqs. 66-82, Figs. 8-10; review §1.10). Nodes 1..n: node 1 is the drum, node n the dead
!> end, interior nodes are sheaves (fixed in the ship frame, or the sheave of a movable
!> block). Segment i joins node i and node i+1 along the current chord (eq. 69, lambda is a
!> unit vector of current positions).
!>
!> Passage s_i (review §1.10): cable length that has passed node i towards node n, measured
!> in unstretched cable; s_1 = drum pay-out, s_n = 0, s_i = r theta_i on a sheave. Unstretched
!> lengths L0_i = L0_i(0) + s_i - s_(i+1) (eqs. 66-67 read as in §1.10) and k_i = EA/L0_i.
module davit_rigging_cable
  use davit_kinds, only: wp
  use davit_core_rotation, only: cross, length3
  use davit_core_pose, only: pose_type
  implicit none
  private
  public :: cable_type, cable_eval_type, max_nodes, node_drum, node_fixed, node_block, node_dead
  public :: cable_node_kinematics, cable_passages, cable_tensions_rotating
  public :: cable_tension_quasi_static, cable_node_forces, cable_energy_rotating
  public :: cable_geometry, cable_block_tangent_rotating, cable_block_tangent_quasi_static
  public :: ramp_factor, ramp_slope

  integer, parameter :: max_nodes = 8
  integer, parameter :: node_drum = 1, node_fixed = 2, node_block = 3, node_dead = 4
  !> Shortest unstretched length a segment may reach before the model is meaningless [m].
  real(wp), parameter :: l0_floor = 1.0e-6_wp

  type :: cable_type
    !> Number of nodes of the cable.
    integer :: nnode = 0
    !> Kind of each node: node_drum, node_fixed, node_block or node_dead.
    integer :: kind(max_nodes) = 0
    !> Ship-frame position of drum, fixed-sheave and dead-end nodes [m].
    real(wp) :: p_ship(3, max_nodes) = 0.0_wp
    !> Block (1 or 2) of a block node; sheave index (in the rigging's list, 0 = none).
    integer :: block(max_nodes) = 0
    !> Sheave index of each node in the rigging's list (0: none).
    integer :: sheave(max_nodes) = 0
    !> Unstretched segment lengths at zero passage L0_i(0) [m].
    real(wp) :: l0_init(max_nodes - 1) = 0.0_wp
    !> Axial stiffness EA [N] and per-segment absolute dashpot [N s/m].
    real(wp) :: ea = 0.0_wp, damping = 0.0_wp
    !> Stretch over which the dashpot tension grows from 0 to full [m]; 0: at once (the
    !> paper's law, massive blocks). Quasi-static blocks need the tension continuous where
    !> a cable goes slack, or a massless block has no balance there (ramp_factor).
    real(wp) :: ramp = 0.0_wp
  end type cable_type

  !> One cable's chords (lam, l), passages (s, sdot; rotating sheaves), segment tensions f
  !> and the tensions g that drive the sheaves (cable_tensions_rotating).
  type :: cable_eval_type
    !> Chord unit vectors, inertial, and chord lengths [m]; passages [m] and their rates [m/s] at
    !> the nodes.
    real(wp) :: lam(3, max_nodes - 1), l(max_nodes - 1), s(max_nodes), sdot(max_nodes)
    !> Segment tensions [N] and the tensions that drive the sheaves [N].
    real(wp) :: f(max_nodes - 1), g(max_nodes - 1)
  end type cable_eval_type

contains

  !> Inertial node positions and velocities: ship-fixed nodes p = r_s + C_s p_ship,
  !> v = v_s + w_s x (C_s p_ship) (w_s inertial components); block nodes from the blocks.
  pure subroutine cable_node_kinematics(cab, ship, block_r, block_v, p, v)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> The ship's pose.
    type(pose_type), intent(in) :: ship
    !> Block positions and velocities (3, block), inertial [m, m/s].
    real(wp), intent(in) :: block_r(3, 2), block_v(3, 2)
    !> Node positions and velocities (3, node), inertial [m, m/s].
    real(wp), intent(out) :: p(3, max_nodes), v(3, max_nodes)
    real(wp) :: arm(3)
    integer :: i
    p = 0.0_wp
    v = 0.0_wp
    do i = 1, cab%nnode
      if (cab%kind(i) == node_block) then
        p(:, i) = block_r(:, cab%block(i))
        v(:, i) = block_v(:, cab%block(i))
      else
        arm = matmul(ship%c, cab%p_ship(:, i))
        p(:, i) = ship%r + arm
        v(:, i) = ship%v + cross(ship%w, arm)
      end if
    end do
  end subroutine cable_node_kinematics

  !> Passages s_i and rates: drum from the winch, dead end 0, sheaves r theta (no slip).
  pure subroutine cable_passages(cab, s_drum, v_drum, radius, theta, omega, s, sdot)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Drum passage [m] and pay-out speed [m/s]; sheave radius [m]; sheave angles [rad] and rates
    !> [rad/s].
    real(wp), intent(in) :: s_drum, v_drum, radius, theta(:), omega(:)
    !> Passages at the nodes [m] and their rates [m/s].
    real(wp), intent(out) :: s(max_nodes), sdot(max_nodes)
    integer :: i
    s = 0.0_wp
    sdot = 0.0_wp
    do i = 1, cab%nnode
      if (cab%kind(i) == node_drum) then
        s(i) = s_drum
        sdot(i) = v_drum
      else if (cab%sheave(i) > 0) then
        s(i) = radius*theta(cab%sheave(i))
        sdot(i) = radius*omega(cab%sheave(i))
      end if
    end do
  end subroutine cable_passages

  !> Chord unit vectors lam, chord lengths l and their rates for every segment.
  pure subroutine cable_geometry(cab, p, v, lam, l, ldot)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Node positions and velocities (3, node), inertial [m, m/s].
    real(wp), intent(in) :: p(3, max_nodes), v(3, max_nodes)
    !> Chord unit vectors (inertial), chord lengths [m] and their rates [m/s].
    real(wp), intent(out) :: lam(3, max_nodes - 1), l(max_nodes - 1), ldot(max_nodes - 1)
    real(wp) :: d(3)
    integer :: i
    lam = 0.0_wp
    l = 0.0_wp
    ldot = 0.0_wp
    do i = 1, cab%nnode - 1
      d = p(:, i + 1) - p(:, i)
      l(i) = max(length3(d), tiny(1.0_wp))
      lam(:, i) = d/l(i)
      ldot(i) = dot_product(v(:, i + 1) - v(:, i), lam(:, i))
    end do
  end subroutine cable_geometry

  !> Rotating sheaves: per-segment tension f = max(0, EA e/L0 + c de/dt) when e > 0, else 0
  !> (tension-only, §1.10), with e = l - L0. g = -dV/dL0 = f + f_el^2/(2 EA) is the tension
  !> that drives the sheaves: with k = EA/L0 updated, V = EA e^2/(2 L0) also depends on L0,
  !> and using g (not f) in the torque keeps the discrete model exactly conservative.
  !> The difference is O(strain) ~ 3e-4 of f.
  pure subroutine cable_tensions_rotating(cab, l, ldot, s, sdot, f, g)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Chord lengths [m] and their rates [m/s].
    real(wp), intent(in) :: l(max_nodes - 1), ldot(max_nodes - 1)
    !> Passages at the nodes [m] and their rates [m/s].
    real(wp), intent(in) :: s(max_nodes), sdot(max_nodes)
    !> Segment tensions [N] and the tensions that drive the sheaves [N].
    real(wp), intent(out) :: f(max_nodes - 1), g(max_nodes - 1)
    real(wp) :: l0, e, fel, edot
    integer :: i
    f = 0.0_wp
    g = 0.0_wp
    do i = 1, cab%nnode - 1
      l0 = max(cab%l0_init(i) + s(i) - s(i + 1), l0_floor)
      e = l(i) - l0
      if (e <= 0.0_wp) cycle
      fel = cab%ea*e/l0
      edot = ldot(i) - (sdot(i) - sdot(i + 1))
      f(i) = max(0.0_wp, fel + cab%damping*edot*ramp_factor(e, cab%ramp))
      g(i) = f(i) + fel**2/(2.0_wp*cab%ea)
    end do
  end subroutine cable_tensions_rotating

  !> Quasi-static (massless, frictionless-bearing) sheaves, review §4.3 item 3: one tension
  !> T = EA (L_geom - L0_tot)/L0_tot along the whole cable, L0_tot(t) = L0_tot(0) + s_drum.
  !> With a friction ratio rho, segment i carries T rho^(dir (i-1)) (dir = +1 when paying
  !> out: the load side pulls the cable over each sheave against friction). The n-1 segment
  !> dashpots act in series, so the cable dashpot is c/(n-1) on dL/dt - v_drum.
  pure subroutine cable_tension_quasi_static(cab, l, ldot, l0_total, v_drum, ratio, f)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Chord lengths [m] and their rates [m/s].
    real(wp), intent(in) :: l(max_nodes - 1), ldot(max_nodes - 1)
    !> Unstretched length of the whole cable [m], drum pay-out speed [m/s], sheave friction ratio
    !> (1: frictionless).
    real(wp), intent(in) :: l0_total, v_drum, ratio
    !> Segment tensions [N].
    real(wp), intent(out) :: f(max_nodes - 1)
    real(wp) :: w(max_nodes - 1), stretch, total, lengths, t
    integer :: nseg
    nseg = cab%nnode - 1
    f = 0.0_wp
    w = friction_weights(nseg, ratio, v_drum)
    total = sum(l(1:nseg))
    stretch = total - l0_total
    if (stretch <= 0.0_wp) return
    ! sum_i w_i T L0_i/EA = stretch, with L0_i = l_i L0_tot/L_geom
    lengths = sum(w(1:nseg)*l(1:nseg))*l0_total/total
    t = cab%ea*stretch/lengths + cab%damping*(sum(ldot(1:nseg)) - v_drum)/sum(w(1:nseg))* &
        ramp_factor(stretch, cab%ramp)
    f(1:nseg) = max(0.0_wp, t)*w(1:nseg)
  end subroutine cable_tension_quasi_static

  !> Eq. (79) corrected: node i receives f_i lam_i - f_(i-1) lam_(i-1); block nodes add it to
  !> their block. Sheave torques r (g_out - g_in) (eq. 71, corrected, c_gamma = 1).
  pure subroutine cable_node_forces(cab, lam, f, g, radius, block_f, torque)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Chord unit vectors (inertial), segment tensions and sheave-driving tensions [N].
    real(wp), intent(in) :: lam(3, max_nodes - 1), f(max_nodes - 1), g(max_nodes - 1)
    !> Sheave radius [m].
    real(wp), intent(in) :: radius
    !> Forces on the blocks (3, block), inertial [N], and torques on the sheaves [N m], the cable's
    !> added.
    real(wp), intent(inout) :: block_f(3, 2), torque(:)
    integer :: i
    do i = 2, cab%nnode - 1
      if (cab%kind(i) == node_block) then
        block_f(:, cab%block(i)) = block_f(:, cab%block(i)) + f(i)*lam(:, i) - &
                                   f(i - 1)*lam(:, i - 1)
      end if
      if (cab%sheave(i) > 0) then
        torque(cab%sheave(i)) = torque(cab%sheave(i)) + radius*(g(i) - g(i - 1))
      end if
    end do
  end subroutine cable_node_forces

  !> Elastic energy sum EA e^2/(2 L0) over taut segments [J] (rotating sheaves).
  pure function cable_energy_rotating(cab, l, s) result(en)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Chord lengths [m] and passages at the nodes [m].
    real(wp), intent(in) :: l(max_nodes - 1), s(max_nodes)
    real(wp) :: en, l0, e
    integer :: i
    en = 0.0_wp
    do i = 1, cab%nnode - 1
      l0 = max(cab%l0_init(i) + s(i) - s(i + 1), l0_floor)
      e = max(0.0_wp, l(i) - l0)
      en = en + 0.5_wp*cab%ea*e**2/l0
    end do
  end function cable_energy_rotating

  !> Quasi-static blocks: how the cable's pull on the blocks changes with them, for rotating
  !> sheaves. jac(3a-2:3a, 3b-2:3b) += d(force on block a)/d(position of block b) and
  !> rate += d(force on the blocks)/dt at fixed blocks (the ship-fixed nodes moving at
  !> v_exo, whose block nodes must be 0, and the passages at sdot). A taut segment i
  !> (f_i > 0) pulls node i with f_i lam_i; f_i = EA e/L0 + c (lam . dv - dL0/dt) changes
  !> with the far node as g = (EA/L0) lam + (c/l)(I - lam lam^T) dv (the dashpot through
  !> the turning chord, dv = v_(i+1) - v_i at the actual velocities v), so the tangent is
  !> K_i = lam g^T + (f_i/l_i)(I - lam lam^T); and df/dL0 = -EA l/L0^2. What is left out,
  !> d f/d(node velocities) times accelerations, is the O(c a/k) lag of a massive block.
  pure subroutine cable_block_tangent_rotating(cab, ce, v, v_exo, jac, rate)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> The cable evaluated at the blocks (chords, passages, tensions).
    type(cable_eval_type), intent(in) :: ce
    !> Node velocities and their part from the ship alone (3, node), inertial [m/s].
    real(wp), intent(in) :: v(3, max_nodes), v_exo(3, max_nodes)
    !> Jacobian of the force on the blocks [N/m] and its rate at fixed blocks [N/s], the cable's
    !> added.
    real(wp), intent(inout) :: jac(6, 6), rate(6)
    real(wp) :: k(3, 3), l0, dl0, g(3), e, edot, phi, dphi
    integer :: i
    associate (lam => ce%lam, l => ce%l, f => ce%f, s => ce%s, sdot => ce%sdot)
      do i = 1, cab%nnode - 1
        if (f(i) <= 0.0_wp) cycle
        l0 = max(cab%l0_init(i) + s(i) - s(i + 1), l0_floor)
        dl0 = sdot(i) - sdot(i + 1)
        e = l(i) - l0
        edot = dot_product(lam(:, i), v(:, i + 1) - v(:, i)) - dl0
        phi = ramp_factor(e, cab%ramp)
        dphi = ramp_slope(e, cab%ramp)
        g = (cab%ea/l0 + cab%damping*edot*dphi)*lam(:, i) + &
            cab%damping*phi/l(i)*across(lam(:, i), v(:, i + 1) - v(:, i))
        k = tangent(lam(:, i), g, f(i)/l(i))
        call add_segment(cab, i, k, v_exo, &
                         -(cab%ea*l(i)/l0**2 + cab%damping*edot*dphi)*dl0*lam(:, i), jac, rate)
      end do
    end associate
  end subroutine cable_block_tangent_rotating

  !> As cable_block_tangent_rotating for quasi-static sheaves: f_i = w_i T with one tension
  !> T = EA (L - L0) L/(L0 A) + c (sum ldot - v_drum)/sum w, L = sum l_i, A = sum w_i l_i
  !> (cable_tension_quasi_static). T changes with segment i's far node as
  !> t_i = (EA (2L - L0)/(L0 A) - T_el w_i/A) lam_i + c/(l_i sum w) (I - lam lam^T) dv_i,
  !> and with L0 (growing at the drum speed) as -EA L^2/(A L0^2). Each segment adds its
  !> chord's turning w_i T/l_i (I - lam lam^T); the change of T couples every block on the
  !> cable (reeving A: both): block a is pulled along u_a = sum (+-w_i lam_i).
  pure subroutine cable_block_tangent_quasi_static(cab, ce, l0_total, v_drum, ratio, v, &
                                                   v_exo, jac, rate)
    ! 9 arguments: as cable_block_tangent_rotating, with the one-tension law's inputs
    ! (unstretched length, drum speed, friction ratio) in place of the passages.
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> The cable evaluated at the blocks (chords, tensions).
    type(cable_eval_type), intent(in) :: ce
    !> Unstretched cable length [m], pay-out speed [m/s], friction ratio; node velocities and their
    !> part from the ship alone (3, node), inertial [m/s].
    real(wp), intent(in) :: l0_total, v_drum, ratio, v(3, max_nodes), v_exo(3, max_nodes)
    !> Jacobian of the force on the blocks [N/m] and its rate at fixed blocks [N/s], the cable's
    !> added.
    real(wp), intent(inout) :: jac(6, 6), rate(6)
    real(wp) :: w(max_nodes - 1), u(3, 2), q(3, 2), k(3, 3), t_i(3)
    real(wp) :: total, weighted, t_el, tdot, d_el, d_damp, phi, rate_l
    real(wp), parameter :: zero3(3) = 0.0_wp
    integer :: i, j, nseg, a, b, lo, hi
    associate (lam => ce%lam, l => ce%l, f => ce%f)
      nseg = cab%nnode - 1
      if (f(1) <= 0.0_wp) return
      w = friction_weights(nseg, ratio, v_drum)
      total = sum(l(1:nseg))
      weighted = sum(w(1:nseg)*l(1:nseg))
      t_el = cab%ea*(total - l0_total)*total/(l0_total*weighted)
      d_el = cab%ea*(2.0_wp*total - l0_total)/(l0_total*weighted)
      ! the dashpot's ramp in: d/dL of c (dL/dt - v_drum) phi(L - L0)/sum w
      rate_l = -v_drum
      do i = 1, nseg
        rate_l = rate_l + dot_product(lam(:, i), v(:, i + 1) - v(:, i))
      end do
      phi = ramp_factor(total - l0_total, cab%ramp)
      d_damp = cab%damping*rate_l*ramp_slope(total - l0_total, cab%ramp)/sum(w(1:nseg))
      d_el = d_el + d_damp
      tdot = -(cab%ea*total**2/(weighted*l0_total**2) + d_damp)*v_drum
      u = 0.0_wp
      q = 0.0_wp
      do i = 1, nseg
        k = tangent(lam(:, i), zero3, f(i)/l(i))
        call add_segment(cab, i, k, v_exo, zero3, jac, rate)
        t_i = (d_el - t_el*w(i)/weighted)*lam(:, i) + &
              cab%damping*phi/(l(i)*sum(w(1:nseg)))*across(lam(:, i), v(:, i + 1) - v(:, i))
        tdot = tdot + dot_product(t_i, v_exo(:, i + 1) - v_exo(:, i))
        if (cab%kind(i) == node_block) then
          u(:, cab%block(i)) = u(:, cab%block(i)) + w(i)*lam(:, i)
          q(:, cab%block(i)) = q(:, cab%block(i)) - t_i
        end if
        if (cab%kind(i + 1) == node_block) then
          u(:, cab%block(i + 1)) = u(:, cab%block(i + 1)) - w(i)*lam(:, i)
          q(:, cab%block(i + 1)) = q(:, cab%block(i + 1)) + t_i
        end if
      end do
      do a = 1, 2
        lo = 3*a - 2
        hi = 3*a
        rate(lo:hi) = rate(lo:hi) + u(:, a)*tdot
        do b = 1, 2
          do j = 1, 3
            jac(lo:hi, 3*b - 3 + j) = jac(lo:hi, 3*b - 3 + j) + u(:, a)*q(j, b)
          end do
        end do
      end do
    end associate
  end subroutine cable_block_tangent_quasi_static

  !> Weights w_i of the quasi-static sheaves' one tension, f_i = w_i T: the bearing friction
  !> ratio to the power of the segment's place from the drum, against the drum's motion
  !> (all 1 when the drum is held or there is no friction).
  pure function friction_weights(nseg, ratio, v_drum) result(w)
    integer, intent(in) :: nseg
    real(wp), intent(in) :: ratio, v_drum
    real(wp) :: w(max_nodes - 1)
    integer :: i
    w = 1.0_wp
    if (ratio /= 1.0_wp .and. v_drum /= 0.0_wp) then
      do i = 1, nseg
        w(i) = ratio**(sign(1.0_wp, v_drum)*real(i - 1, wp))
      end do
    end if
  end function friction_weights

  !> Share of the dashpot tension at stretch e: 0 at e <= 0, 1 from e = ramp on, and the
  !> smooth step 3x^2 - 2x^3 (x = e/ramp) between (always 1 with ramp = 0). Multiplying
  !> the dashpot by it keeps a tension-only segment's tension continuous, with a
  !> continuous slope, where it goes slack, instead of jumping from c de/dt to 0.
  elemental real(wp) function ramp_factor(e, ramp) result(phi)
    !> Stretch [m] and the ramp length [m] (0: none).
    real(wp), intent(in) :: e, ramp
    real(wp) :: x
    x = ramp_position(e, ramp)
    phi = x*x*(3.0_wp - 2.0_wp*x)
  end function ramp_factor

  !> d ramp_factor/de.
  elemental real(wp) function ramp_slope(e, ramp) result(dphi)
    !> Stretch [m] and the ramp length [m] (0: none).
    real(wp), intent(in) :: e, ramp
    real(wp) :: x
    x = ramp_position(e, ramp)
    dphi = 0.0_wp
    if (ramp > 0.0_wp) dphi = 6.0_wp*x*(1.0_wp - x)/ramp
  end function ramp_slope

  !> x = e/ramp clamped to [0, 1], the smooth step's argument; 1 (the step passed) with
  !> ramp = 0, where both the factor (1) and its slope (0) follow from it.
  elemental real(wp) function ramp_position(e, ramp) result(x)
    !> Stretch [m] and the ramp length [m] (0: none).
    real(wp), intent(in) :: e, ramp
    x = 1.0_wp
    if (ramp > 0.0_wp) x = min(1.0_wp, max(0.0_wp, e/ramp))
  end function ramp_position

  !> The part of d across lam: (I - lam lam^T) d.
  pure function across(lam, d) result(p)
    real(wp), intent(in) :: lam(3), d(3)
    real(wp) :: p(3)
    p = d - dot_product(lam, d)*lam
  end function across

  !> lam g^T + k_geo (I - lam lam^T): a force f lam whose magnitude changes by g . dr and
  !> whose direction turns by (I - lam lam^T) dr/l (k_geo = f/l).
  pure function tangent(lam, g, k_geo) result(k)
    real(wp), intent(in) :: lam(3), g(3), k_geo
    real(wp) :: k(3, 3)
    integer :: j
    do j = 1, 3
      k(:, j) = lam*g(j) - k_geo*lam(j)*lam
      k(j, j) = k(j, j) + k_geo
    end do
  end function tangent

  !> Segment i pulls node i with F = f lam and node i+1 with -F; dF = K (dp_(i+1) - dp_i) +
  !> extra dt. Adds the parts that fall on block nodes: their Jacobian blocks, and their
  !> rates with the other nodes moving at v (block nodes at rest in v).
  pure subroutine add_segment(cab, i, k, v, extra, jac, rate)
    type(cable_type), intent(in) :: cab
    integer, intent(in) :: i
    real(wp), intent(in) :: k(3, 3), v(3, max_nodes), extra(3)
    real(wp), intent(inout) :: jac(6, 6), rate(6)
    real(wp) :: df(3)
    integer :: a, b
    a = 0
    b = 0
    if (cab%kind(i) == node_block) a = cab%block(i)
    if (cab%kind(i + 1) == node_block) b = cab%block(i + 1)
    if (a == 0 .and. b == 0) return
    df = matmul(k, v(:, i + 1) - v(:, i)) + extra
    if (a > 0) then
      jac(3*a - 2:3*a, 3*a - 2:3*a) = jac(3*a - 2:3*a, 3*a - 2:3*a) - k
      rate(3*a - 2:3*a) = rate(3*a - 2:3*a) + df
      if (b > 0) jac(3*a - 2:3*a, 3*b - 2:3*b) = jac(3*a - 2:3*a, 3*b - 2:3*b) + k
    end if
    if (b > 0) then
      jac(3*b - 2:3*b, 3*b - 2:3*b) = jac(3*b - 2:3*b, 3*b - 2:3*b) - k
      rate(3*b - 2:3*b) = rate(3*b - 2:3*b) - df
      if (a > 0) jac(3*b - 2:3*b, 3*a - 2:3*a) = jac(3*b - 2:3*b, 3*a - 2:3*a) + k
    end if
  end subroutine add_segment

end module davit_rigging_cable
