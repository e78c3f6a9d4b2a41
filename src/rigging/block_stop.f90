!> The hook stop of a movable block (issue 12, slack rigging). With its falls slack a block
!> comes down onto its hook: the sling (wire, links, shackle) folds, and the block's
!> becket and cheek plates land on the hook and the boat's lifting gear around it. The
!> tension-only sling alone (eqs. 58, 63 corrected) cannot push, so the block would fall
!> through the hook until the sling catches it a sling length below and snatches it.
!>
!> Geometry: a compression-only stop under the block at `height` above the hook point
!> (the sheave radius, 0.16 m, plus becket and hook eye, ~0.14 m: 0.3 m), horizontal in
!> N (the hook gear's top, level with the boat; a heel of 10 deg tilts it by that angle,
!> which the model ignores). A plane, not a sphere round the hook: a block resting on a
!> sphere's top would roll off it (rate sqrt(g/h) ~ 6 1/s) and drop past the hook after
!> all; on a plane it stays, and its potential stays convex in the block's position (the
!> quasi-static balance minimises a convex potential, davit_rigging_block_balance).
!> Law, penetration d = height - (z_hook - z_block) (z down): normal force on the block
!> f_n = k s(d) + c d' phi(d), clipped >= 0, along -N3; s(d) = d^2/(2 e) for d < e, then
!> d - e/2 (a C1 onset over e = 1e-4 m, so Newton's tangent is continuous), phi the
!> dashpot's ramp over the same e. k = EA/l of the sling: the steel that meets at the
!> stop (cheek plates, hook) is at least as stiff as the 1 m wire, and a stiffer stop
!> would add a faster mode than the block's ~200 Hz on its sling, which sets RK4's limit.
!> c = 2 zeta_s sqrt(k m_b) with zeta_s = 0.3: a low-speed steel-on-steel landing with
!> restitution exp(-pi zeta/sqrt(1 - zeta^2)) ~ 0.37. Massive blocks also feel Coulomb
!> friction mu f_n (mu = 0.3, steel on painted steel) against their slip on the stop,
!> regularised below 0.05 m/s: a frictionless block would stay put while the boat sways
!> under it until its sling snatched it sideways.
module davit_rigging_block_stop
  use davit_kinds, only: wp
  use davit_rigging_cable, only: ramp_factor
  use davit_rigging_wire_damping, only: wire_dashpot
  implicit none
  private
  public :: block_stop_type, new_block_stop, stop_force, stop_energy, stop_tangent
  public :: add_stop_forces, stop_zeta

  !> Damping ratio of the block landing on its stop, and the onset length [m].
  real(wp), parameter :: stop_zeta = 0.3_wp, stop_onset = 1.0e-4_wp
  !> Friction coefficient and the slip speed below which it is regularised [m/s].
  real(wp), parameter :: stop_mu = 0.3_wp, slip_speed = 0.05_wp

  type :: block_stop_type
    !> Height of the block's centre above the hook at contact [m] (0: no stop), stiffness
    !> [N/m], dashpot [N s/m], onset [m], friction coefficient, slip speed [m/s].
    real(wp) :: height = 0.0_wp, k = 0.0_wp, c = 0.0_wp, onset = stop_onset
    !> Friction coefficient and the slip speed below which friction is regularised [m/s].
    real(wp) :: mu = stop_mu, v_slip = slip_speed
  end type block_stop_type

contains

  !> A stop at `height` above the hook with stiffness k for a block of mass m_b.
  pure function new_block_stop(height, k, m_b) result(st)
    !> Height of the block's centre above the hook at contact [m], stiffness [N/m], block mass
    !> [kg].
    real(wp), intent(in) :: height, k, m_b
    type(block_stop_type) :: st
    st%height = height
    st%k = k
    st%c = wire_dashpot(stop_zeta, k, m_b)
  end function new_block_stop

  !> Penetration d [m] of a block at r_b into the stop of the hook at r_hook.
  pure real(wp) function penetration(st, r_hook, r_b) result(d)
    type(block_stop_type), intent(in) :: st
    real(wp), intent(in) :: r_hook(3), r_b(3)
    d = st%height - (r_hook(3) - r_b(3))
  end function penetration

  !> Elastic normal force k s(d) [N] and its slope k s'(d) [N/m].
  pure subroutine elastic(st, d, f, df)
    type(block_stop_type), intent(in) :: st
    real(wp), intent(in) :: d
    real(wp), intent(out) :: f, df
    f = 0.0_wp
    df = 0.0_wp
    if (st%height <= 0.0_wp .or. d <= 0.0_wp) return
    if (d < st%onset) then
      f = st%k*d*d/(2.0_wp*st%onset)
      df = st%k*d/st%onset
    else
      f = st%k*(d - 0.5_wp*st%onset)
      df = st%k
    end if
  end subroutine elastic

  !> Force of the stop on the block (the hook gets its negative): normal f_n up (-N3);
  !> with `dynamic` also its dashpot and the friction against the slip, else the elastic
  !> part alone (quasi-static blocks, whose balance has no inertia for them to act on).
  pure function stop_force(st, r_hook, v_hook, r_b, v_b, dynamic) result(f)
    !> The stop.
    type(block_stop_type), intent(in) :: st
    !> Hook position and velocity, block position and velocity, inertial [m, m/s].
    real(wp), intent(in) :: r_hook(3), v_hook(3), r_b(3), v_b(3)
    !> With the dashpot and friction (massive blocks), else the elastic part alone.
    logical, intent(in) :: dynamic
    real(wp) :: f(3), d, fn, df, slip(3)
    f = 0.0_wp
    d = penetration(st, r_hook, r_b)
    call elastic(st, d, fn, df)
    if (fn <= 0.0_wp) return
    if (dynamic) fn = max(0.0_wp, fn + st%c*(v_b(3) - v_hook(3))*ramp_factor(d, st%onset))
    f(3) = -fn
    if (.not. dynamic) return
    slip = [v_b(1) - v_hook(1), v_b(2) - v_hook(2), 0.0_wp]
    f = f - st%mu*fn*slip/max(norm2(slip), st%v_slip)
  end function stop_force

  !> Adds the stops' forces to both blocks (br, bv) and their reactions to the hooks.
  pure subroutine add_stop_forces(st, hook_pos, hook_vel, br, bv, dynamic, block_f, &
                                  hook_force)
    !> The stop.
    type(block_stop_type), intent(in) :: st
    !> Hook positions and velocities, block positions and velocities (3, 2 each), inertial [m,
    !> m/s].
    real(wp), intent(in) :: hook_pos(3, 2), hook_vel(3, 2), br(3, 2), bv(3, 2)
    !> With the dashpot and friction (massive blocks), else the elastic part alone.
    logical, intent(in) :: dynamic
    !> Forces on the blocks and on the hooks (3, 2 each), inertial [N], the stops' added.
    real(wp), intent(inout) :: block_f(3, 2), hook_force(3, 2)
    real(wp) :: f(3)
    integer :: a
    do a = 1, 2
      f = stop_force(st, hook_pos(:, a), hook_vel(:, a), br(:, a), bv(:, a), dynamic)
      block_f(:, a) = block_f(:, a) + f
      hook_force(:, a) = hook_force(:, a) - f
    end do
  end subroutine add_stop_forces

  !> Elastic energy of both stops [J]: k d^3/(6 e) below the onset e, then
  !> k e^2/6 + k (d^2 - e d)/2 (the integral of the elastic law).
  pure function stop_energy(st, hook_pos, br) result(en)
    !> The stop.
    type(block_stop_type), intent(in) :: st
    !> Hook positions and block positions (3, 2 each), inertial [m].
    real(wp), intent(in) :: hook_pos(3, 2), br(3, 2)
    real(wp) :: en, d, e
    integer :: a
    en = 0.0_wp
    if (st%height <= 0.0_wp) return
    e = st%onset
    do a = 1, 2
      d = penetration(st, hook_pos(:, a), br(:, a))
      if (d <= 0.0_wp) cycle
      if (d < e) then
        en = en + st%k*d**3/(6.0_wp*e)
      else
        en = en + st%k*(e*e/6.0_wp + 0.5_wp*(d*d - e*d))
      end if
    end do
  end function stop_energy

  !> The elastic stop for the quasi-static balance: its force on the block f (3), the
  !> tangent df/dz_block (-k s'(d), on the vertical only) and the force's rate at a fixed
  !> block with the hook moving at v_hook (k s'(d) v_hook,3).
  pure subroutine stop_tangent(st, r_hook, v_hook, r_b, f, dfdz, rate)
    !> The stop.
    type(block_stop_type), intent(in) :: st
    !> Hook position and velocity, block position, inertial [m, m/s].
    real(wp), intent(in) :: r_hook(3), v_hook(3), r_b(3)
    !> Force on the block, inertial [N]; its tangent along N3 [N/m]; its rate at a fixed block
    !> [N/s].
    real(wp), intent(out) :: f(3), dfdz, rate
    real(wp) :: fn, df
    call elastic(st, penetration(st, r_hook, r_b), fn, df)
    f = [0.0_wp, 0.0_wp, -fn]
    dfdz = -df
    rate = df*v_hook(3)
  end subroutine stop_tangent

end module davit_rigging_block_stop
