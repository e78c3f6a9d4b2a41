!> Massless, tension-only elastic sling between an anchor point and a hook (review §1.6 with
!> n = 0 lumps). This is the simplest rigging force model; the lumped-mass slings and the
!> cable-pulley system of the rigging issue replace it behind the same role: given the hook's
!> position and velocity, return the force on the hook.
module davit_rigging_elastic_sling
  use davit_kinds, only: wp
  use davit_core_rotation, only: length3
  implicit none
  private
  public :: elastic_sling_type, sling_hook_force, sling_energy

  type :: elastic_sling_type
    !> Anchor point in the inertial frame [m].
    real(wp) :: anchor(3) = 0.0_wp
    !> Unstretched length [m], axial stiffness EA [N], axial dashpot [N s/m].
    real(wp) :: length = 1.0_wp
    !> Axial stiffness EA [N].
    real(wp) :: ea = 0.0_wp
    !> Axial dashpot [N s/m].
    real(wp) :: damping = 0.0_wp
  end type elastic_sling_type

contains

  !> Force on the hook (inertial components) and the sling tension.
  !> Spring k = EA/l0 on the stretch, plus an absolute axial dashpot c * dD/dt with
  !> dD/dt = (v_hook - v_anchor) . e: the corrected eq. (63) (review §1.6), never divided by
  !> the stretch. Tension-only: zero when slack, and spring + dashpot clipped at >= 0 (eq. 58).
  pure subroutine sling_hook_force(sling, r_hook, v_hook, force, tension)
    !> The sling.
    type(elastic_sling_type), intent(in) :: sling
    !> Hook position [m] and velocity [m/s], inertial.
    real(wp), intent(in) :: r_hook(3), v_hook(3)
    !> Force on the hook, inertial [N], and the sling tension [N].
    real(wp), intent(out) :: force(3), tension
    real(wp) :: d(3), dist, e(3), stretch, rate
    d = r_hook - sling%anchor
    dist = length3(d)
    stretch = dist - sling%length
    if (stretch <= 0.0_wp .or. dist <= 0.0_wp) then
      force = 0.0_wp
      tension = 0.0_wp
      return
    end if
    e = d/dist
    rate = dot_product(v_hook, e)
    tension = max(0.0_wp, sling%ea/sling%length*stretch + sling%damping*rate)
    force = -tension*e
  end subroutine sling_hook_force

  !> Elastic energy 1/2 k stretch^2 (zero when slack) [J].
  pure function sling_energy(sling, r_hook) result(e)
    !> The sling.
    type(elastic_sling_type), intent(in) :: sling
    !> Hook position, inertial [m].
    real(wp), intent(in) :: r_hook(3)
    real(wp) :: e, stretch
    stretch = max(0.0_wp, length3(r_hook - sling%anchor) - sling%length)
    e = 0.5_wp*sling%ea/sling%length*stretch**2
  end function sling_energy

end module davit_rigging_elastic_sling
