!> Axial damping of the wires (review §1.6, §4.1, G26; issue 12 "slack rigging"). A stranded
!> steel rope dissipates by friction between its wires: a hysteretic loss, nearly the same
!> share of the strain energy per cycle at every frequency, stated as one damping ratio
!> zeta (loss factor 2 zeta). The model's segments are Kelvin-Voigt spring-dashpots
!> (corrected eq. 63), and a viscous dashpot gives zeta only in the mode it is sized for;
!> each wire is sized for the mode that rings when the falls go slack and snatch taut: a
!> movable block of mass m_b on that wire, k = EA/L0, so c = 2 zeta sqrt(k m_b), the
!> mass-spring's critical damping times zeta. (MoorDyn's "-zeta" input sizes the same
!> c = zeta sqrt(EA w) per segment against the segment's own mass w L0, for the
!> discretisation's highest mode; here the mass that rings is the block, 30x a sling's.)
!> The boat's bounce on the falls is damped by the G26 cable dashpot, which is larger.
module davit_rigging_wire_damping
  use davit_kinds, only: wp
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_cable, only: cable_type, node_block
  use davit_rigging_sling_chain, only: sling_chain_type
  implicit none
  private
  public :: wire_dashpot, sling_dashpot, sling_lump_dashpots, cable_floor

contains

  !> c = 2 zeta sqrt(k m) [N s/m]: damping ratio zeta of a mass m on a spring k.
  pure real(wp) function wire_dashpot(zeta, k, m) result(c)
    !> Damping ratio; spring stiffness [N/m]; mass [kg].
    real(wp), intent(in) :: zeta, k, m
    c = 2.0_wp*zeta*sqrt(max(k, 0.0_wp)*max(m, 0.0_wp))
  end function wire_dashpot

  !> Whole-sling dashpot [N s/m]: sling_damping if the deck gives it, else the wire's, for
  !> the block on the whole sling (EA/l; segments in series each get (n+1) times it, so
  !> the block mode keeps zeta whatever the lumps).
  pure real(wp) function sling_dashpot(cfg, ea) result(c)
    !> The &rigging configuration (sling_damping, wire damping ratio, block mass).
    type(rigging_config), intent(in) :: cfg
    !> Axial stiffness EA of the sling [N].
    real(wp), intent(in) :: ea
    if (cfg%sling_damping_given) then
      c = cfg%sling_damping
    else
      c = wire_dashpot(cfg%wire_damping_ratio, ea/cfg%sling_length, cfg%block_mass)
    end if
  end function sling_dashpot

  !> With lumps (n > 0) and the wire's damping (sling_damping not given): the series rule
  !> of sling_dashpot would put (n+1) 2 zeta sqrt(EA m_b/l) on every segment, over-damping
  !> the light lumps (zeta ~ 2 at n = 20: a real rate ~1e6 1/s, RK4 diverges at 1e-5 s).
  !> So each segment is sized for the mass it moves: the top one (k_seg, the block) for
  !> the block, the others for a lump, 2 zeta sqrt(k_seg m_p) (MoorDyn's per-segment
  !> rule); the block mode then rings mostly in the top segment (zeta/sqrt(n+1) or more).
  pure subroutine sling_lump_dashpots(cfg, ch)
    !> The &rigging configuration.
    type(rigging_config), intent(in) :: cfg
    !> The sling, its segments' dashpots set.
    type(sling_chain_type), intent(inout) :: ch
    if (cfg%sling_damping_given .or. ch%nlump == 0) return
    ch%c_top = wire_dashpot(cfg%wire_damping_ratio, ch%k_seg, cfg%block_mass)
    ch%c_seg = wire_dashpot(cfg%wire_damping_ratio, ch%k_seg, ch%m_lump)
  end subroutine sling_lump_dashpots

  !> The wire's floor for one cable's per-segment dashpot [N s/m]: the block on its
  !> stiffest (shortest) part, 2 zeta sqrt(EA/L0_min m_b) over the segments that end at a
  !> block (their unstretched lengths l0).
  pure real(wp) function cable_floor(cab, l0, zeta, m_b) result(c)
    !> The cable.
    type(cable_type), intent(in) :: cab
    !> Unstretched segment lengths [m]; damping ratio; block mass [kg].
    real(wp), intent(in) :: l0(:), zeta, m_b
    real(wp) :: shortest
    integer :: i
    shortest = huge(1.0_wp)
    do i = 1, cab%nnode - 1
      if (cab%kind(i) == node_block .or. cab%kind(i + 1) == node_block) then
        shortest = min(shortest, l0(i))
      end if
    end do
    c = 0.0_wp
    if (shortest < huge(1.0_wp)) c = wire_dashpot(zeta, cab%ea/shortest, m_b)
  end function cable_floor

end module davit_rigging_wire_damping
