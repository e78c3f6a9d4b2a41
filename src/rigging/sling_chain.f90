!> Lumped-mass sling (paper §II.D, eqs. 47-65, 80-81; review §1.6): n particles between the
!> boat hook (node 0) and the movable block (node n+1), joined by n+1 tension-only
!> spring-dashpot segments. Positions and velocities are inertial (N: z down), which the
!> design allows instead of the paper's boat-frame components; a lump's generalized active
!> force is then its segment forces plus its weight +m g N3 (corrected eq. 54) and its Kane
!> mass block m I (eq. 53). n = 0 gives a massless spring hook-block.
module davit_rigging_sling_chain
  use davit_kinds, only: wp, gravity
  use davit_core_rotation, only: length3
  use davit_rigging_cable, only: ramp_factor, ramp_slope
  implicit none
  private
  public :: sling_chain_type, max_lumps, chain_forces, chain_energy, new_sling_chain
  public :: top_segment_tangent

  integer, parameter :: max_lumps = 20

  type :: sling_chain_type
    !> Lumps per sling (0..max_lumps).
    integer :: nlump = 0
    !> Unstretched segment length l/(n+1) [m], its stiffness EA (n+1)/l [N/m] and its
    !> absolute dashpot [N s/m], c_top that of the top segment (at the block); lump mass
    !> mu l/(n+1) [kg].
    real(wp) :: l0_seg = 1.0_wp, k_seg = 0.0_wp, c_seg = 0.0_wp, c_top = 0.0_wp
    !> Mass of a lump [kg].
    real(wp) :: m_lump = 0.0_wp
    !> Stretch over which the dashpot tension grows from 0 to full [m] (0: at once), as
    !> cable_type%ramp.
    real(wp) :: ramp = 0.0_wp
  end type sling_chain_type

contains

  !> A sling of unstretched length l, axial stiffness ea, whole-sling dashpot c (segments in
  !> series, so each gets (n+1) c) and mass mu per metre, split over n lumps.
  pure function new_sling_chain(nlump, length, ea, c, mu) result(ch)
    !> Lumps per sling (0..max_lumps).
    integer, intent(in) :: nlump
    !> Unstretched length [m], axial stiffness EA [N], whole-sling dashpot [N s/m], mass per metre
    !> [kg/m].
    real(wp), intent(in) :: length, ea, c, mu
    type(sling_chain_type) :: ch
    ch%nlump = nlump
    ch%l0_seg = length/real(nlump + 1, wp)
    ch%k_seg = ea/ch%l0_seg
    ch%c_seg = c*real(nlump + 1, wp)
    ch%c_top = ch%c_seg
    ch%m_lump = mu*ch%l0_seg
  end function new_sling_chain

  !> Tension of one segment (lower node a, upper node b): spring k (D - l0) plus absolute
  !> dashpot c dD/dt (corrected eq. 63, never divided by the stretch), zero when slack and
  !> clipped at >= 0 (corrected eq. 58). e is the unit vector a -> b.
  pure subroutine segment(ch, c, ra, va, rb, vb, f, e)
    type(sling_chain_type), intent(in) :: ch
    real(wp), intent(in) :: c, ra(3), va(3), rb(3), vb(3)
    real(wp), intent(out) :: f, e(3)
    real(wp) :: d(3), dist
    d = rb - ra
    dist = length3(d)
    f = 0.0_wp
    e = 0.0_wp
    if (dist <= ch%l0_seg) return
    e = d/dist
    f = max(0.0_wp, ch%k_seg*(dist - ch%l0_seg) + c*dot_product(vb - va, e)* &
                    ramp_factor(dist - ch%l0_seg, ch%ramp))
  end subroutine segment

  !> Net segment forces on the lumps f_lump (their weight is the caller's: the Kane
  !> blocks add it, eq. 54 corrected), forces on the top (block) and on the hook, and the
  !> segment tensions (segment k joins node k-1 and node k; node 0 = hook, n+1 = top),
  !> eqs. 59-65.
  pure subroutine chain_forces(ch, r_hook, v_hook, r_lump, v_lump, r_top, v_top, f_lump, &
                               f_top, f_hook, tension)
    ! 11 arguments: the chain's two ends and its lumps as they lie in the state, and its
    ! four results; bundling them would copy the lump arrays at every evaluation.
    !> The sling.
    type(sling_chain_type), intent(in) :: ch
    !> Hook and top (block) positions and velocities, inertial [m, m/s].
    real(wp), intent(in) :: r_hook(3), v_hook(3), r_top(3), v_top(3)
    !> Lump positions and velocities (3, lump), inertial [m, m/s].
    real(wp), intent(in) :: r_lump(3, ch%nlump), v_lump(3, ch%nlump)
    !> Net segment forces on the lumps (3, lump), force on the top and on the hook, inertial [N].
    real(wp), intent(out) :: f_lump(3, ch%nlump), f_top(3), f_hook(3)
    !> Segment tensions (segment 1 at the hook) [N].
    real(wp), intent(out) :: tension(ch%nlump + 1)
    real(wp) :: r(3, 0:max_lumps + 1), v(3, 0:max_lumps + 1), fn(3, 0:max_lumps + 1), e(3)
    integer :: k, n
    n = ch%nlump
    r(:, 0) = r_hook
    v(:, 0) = v_hook
    r(:, 1:n) = r_lump
    v(:, 1:n) = v_lump
    r(:, n + 1) = r_top
    v(:, n + 1) = v_top
    fn(:, 0:n + 1) = 0.0_wp
    do k = 1, n + 1
      call segment(ch, merge(ch%c_top, ch%c_seg, k == n + 1), r(:, k - 1), v(:, k - 1), &
                   r(:, k), v(:, k), tension(k), e)
      fn(:, k - 1) = fn(:, k - 1) + tension(k)*e
      fn(:, k) = fn(:, k) - tension(k)*e
    end do
    f_hook = fn(:, 0)
    f_top = fn(:, n + 1)
    f_lump = fn(:, 1:n)
  end subroutine chain_forces

  !> Kinetic + gravity (z down: -m g z) + elastic energy of the lumps and segments [J].
  pure function chain_energy(ch, r_hook, r_lump, v_lump, r_top) result(en)
    !> The sling.
    type(sling_chain_type), intent(in) :: ch
    !> Hook and top (block) positions, inertial [m].
    real(wp), intent(in) :: r_hook(3), r_top(3)
    !> Lump positions and velocities (3, lump), inertial [m, m/s].
    real(wp), intent(in) :: r_lump(3, ch%nlump), v_lump(3, ch%nlump)
    real(wp) :: en, r(3, 0:max_lumps + 1), stretch
    integer :: k, n
    n = ch%nlump
    r(:, 0) = r_hook
    r(:, 1:n) = r_lump
    r(:, n + 1) = r_top
    en = 0.5_wp*ch%m_lump*sum(v_lump**2) - ch%m_lump*gravity*sum(r_lump(3, :))
    do k = 1, n + 1
      stretch = max(0.0_wp, length3(r(:, k) - r(:, k - 1)) - ch%l0_seg)
      en = en + 0.5_wp*ch%k_seg*stretch**2
    end do
  end function chain_energy

  !> The top segment (from r_low, the hook or lump n, to the block at r_top) for a
  !> quasi-static block (ch%ramp > 0), taken as taut: f = k (D - l0) + c e . dv phi (dv =
  !> v_top - v_low, phi the dashpot's ramp) on both sides of D = l0, so that the balance
  !> is smooth; the caller keeps the segment
  !> only where this f is positive (it is then the tension-only law of `segment`). Returns
  !> the force on the block f_top = -f e, f, the tension-only law's value f_real, and the
  !> tangent d f_top/d r_top = -(e g^T + (f/D)(I - e e^T)) with g = k e + (c/D)(I - e e^T) dv
  !> the change of f with r_top (spring, dashpot through the turning chord) and the chord
  !> turning the force. Moving r_low changes f_top by -jac times its displacement.
  pure subroutine top_segment_tangent(ch, r_low, v_low, r_top, v_top, f_top, f, f_real, jac)
    ! 9 arguments: the segment's two ends (position, velocity) and its four results.
    !> The sling.
    type(sling_chain_type), intent(in) :: ch
    !> Lower end (hook or lump n) and block positions and velocities, inertial [m, m/s].
    real(wp), intent(in) :: r_low(3), v_low(3), r_top(3), v_top(3)
    !> Force on the block, inertial [N]; the segment's tension continued through slack and its
    !> tension-only value [N]; d(force on block)/d(block position) [N/m].
    real(wp), intent(out) :: f_top(3), f, f_real, jac(3, 3)
    real(wp) :: e(3), k_geo, dist, g(3), dv(3), phi, dphi
    integer :: j
    call segment(ch, ch%c_top, r_low, v_low, r_top, v_top, f_real, e)
    dist = length3(r_top - r_low)
    e = (r_top - r_low)/dist
    dv = v_top - v_low
    ! the dashpot ramps in over ch%ramp of stretch (none in compression)
    phi = ramp_factor(dist - ch%l0_seg, ch%ramp)
    dphi = ramp_slope(dist - ch%l0_seg, ch%ramp)
    f = ch%k_seg*(dist - ch%l0_seg) + ch%c_top*dot_product(dv, e)*phi
    f_top = -f*e
    k_geo = f/dist
    g = (ch%k_seg + ch%c_top*dot_product(dv, e)*dphi)*e + &
        ch%c_top*phi/dist*(dv - dot_product(e, dv)*e)
    do j = 1, 3
      jac(:, j) = -e*g(j) + k_geo*e(j)*e
      jac(j, j) = jac(j, j) - k_geo
    end do
  end subroutine top_segment_tangent

end module davit_rigging_sling_chain
