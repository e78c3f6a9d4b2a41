!> The rigging's start (davit_rigging_rigging's initial_state): each sling laid out from its
!> hook along the force it carries (lump statics, exact for a boat hanging at rest), the
!> start velocities of its lumps and block as points of a rigid pendulum from the davit
!> head to the hook, and the check that the falls can hold the blocks so placed. Nothing
!> here knows the rigging's state layout: the caller maps the positions into its state.
module davit_rigging_sling_start
  use davit_kinds, only: wp, gravity
  use davit_error, only: error_type, fatal_error
  use davit_rigging_sling_chain, only: sling_chain_type
  implicit none
  private
  public :: lay_out_sling, pendulum_velocity, check_start_residual

  !> Largest accepted residual of the initial equilibrium (initial_state): r = |Q - T s|/|Q|,
  !> the share of a block's needed cable force Q that the fitted tension T along the falls'
  !> direction s cannot supply; r = sin(angle between Q and s). The decks with &rigging sit
  !> at 2e-16 (round-off: a head midway above each hook); a boat started heeled by 0.1 rad
  !> (the order studies in test/python/test_boat_decks.py) at 5.1e-2, a start transient
  !> those tests want. Beyond 0.2 (Q more than 11.5 deg off the falls) the geometry is
  !> wrong (heads not above the hooks, drum or lead sheave misplaced), not the start.
  real(wp), parameter :: residual_max = 0.2_wp

contains

  !> Lay out a sling from its hook: segment k carries F_k = F_hook - (k-1) m_p g N3 (lump
  !> statics), along F_k, stretched by |F_k|/k_seg (unstretched: natural length along the
  !> hook force); returns the lump positions, the block's and the cable force Q the block
  !> needs (F_(n+1) less the block's weight).
  pure subroutine lay_out_sling(sling, block_mass, hook, f_hook, unstretched, lumps, block, q)
    !> The sling's lumped-mass chain (segment length, stiffness, lump mass).
    type(sling_chain_type), intent(in) :: sling
    !> The block's mass m_b [kg].
    real(wp), intent(in) :: block_mass
    !> The hook's position and the force the rigging must apply there [m, N], inertial.
    real(wp), intent(in) :: hook(3), f_hook(3)
    !> Segments at their natural length l0_seg instead of stretched by their tension.
    logical, intent(in) :: unstretched
    !> Lump positions (3, lump), lump 1 next to the hook [m].
    real(wp), intent(out) :: lumps(:, :)
    !> The block's position [m] and the cable force Q it needs [N].
    real(wp), intent(out) :: block(3), q(3)
    real(wp) :: node(3), fk(3), up(3), ez(3)
    integer :: k, n
    n = size(lumps, 2)
    ez = [0.0_wp, 0.0_wp, 1.0_wp]
    up = -ez
    if (norm2(f_hook) > 0.0_wp) up = f_hook/norm2(f_hook)
    node = hook
    do k = 1, n + 1
      fk = f_hook - real(k - 1, wp)*sling%m_lump*gravity*ez
      if (unstretched .or. norm2(fk) <= 0.0_wp) then
        node = node + sling%l0_seg*up
      else
        node = node + (sling%l0_seg + norm2(fk)/sling%k_seg)*fk/norm2(fk)
      end if
      if (k <= n) lumps(:, k) = node
    end do
    block = node
    q = fk - block_mass*gravity*ez
  end subroutine lay_out_sling

  !> Velocity of point p of a rigid pendulum from the head to the hook: v = v_head +
  !> s (v_hook - v_head), s the point's distance from the head over the hook's (at most 1).
  !> Uniform (the ship's) when the boat moves with the ship.
  pure function pendulum_velocity(p, head, hook, head_vel, hook_vel) result(v)
    !> The point, the davit head and the hook [m], inertial.
    real(wp), intent(in) :: p(3), head(3), hook(3)
    !> The head's and the hook's velocities [m/s].
    real(wp), intent(in) :: head_vel(3), hook_vel(3)
    real(wp) :: v(3), s
    s = min(1.0_wp, norm2(p - head)/max(norm2(hook - head), tiny(1.0_wp)))
    v = head_vel + s*(hook_vel - head_vel)
  end function pendulum_velocity

  !> An error if the start's equilibrium residual (see residual_max) says the falls miss a
  !> block's load: the davit heads are not above the hooks.
  subroutine check_start_residual(residual, error)
    !> max |Q - T (lam_out - lam_in)|/|Q| over the blocks (davit_rigging_falls).
    real(wp), intent(in) :: residual
    !> Set when the residual exceeds residual_max.
    type(error_type), allocatable, intent(out) :: error
    character(len=16) :: text
    if (residual > residual_max) then
      write (text, "(es10.3)") residual
      call fatal_error(error, "rigging: no initial equilibrium: the falls miss a block's "// &
                       "load by "//trim(adjustl(text))//" of it (at most 0.2): place the "// &
                       "davit heads above the hooks")
    end if
  end subroutine check_start_residual

end module davit_rigging_sling_start
