!> Kane's equations in the form every body contributes to (paper eqs. 12, 53, 73, 87, 89).
!>
!> Each body or subsystem fills, over its own slice of the state, q_dot at its coordinates
!> (its kinematic relations: eqs. 5-6, 51, 77) and, at each of its speeds, the diagonal of
!> its mass block V, its gyroscopic and velocity terms W phi and its generalized active
!> forces F (eq. 12 for a rigid body; eqs. 53, 73 and 87 for lumps, blocks and sheaves),
!> stored as kane(kane_v, i), kane(kane_w_phi, i) and kane(kane_f, i) at state index i.
!> kane_rates then forms u_dot for every speed at once: eq. 89, the one place it is coded.
module davit_core_kane
  use davit_kinds, only: wp
  implicit none
  private
  public :: kane_v, kane_w_phi, kane_f, kane_rates, kane_at_rest

  !> Rows of the Kane block array kane(3, n).
  integer, parameter :: kane_v = 1, kane_w_phi = 2, kane_f = 3

contains

  !> Eq. (89): u_dot = (F - W phi)/V at the state positions `speeds`, V diagonal.
  pure subroutine kane_rates(speeds, kane, dydt)
    integer, intent(in) :: speeds(:)
    real(wp), intent(in) :: kane(:, :)
    real(wp), intent(inout) :: dydt(:)
    dydt(speeds) = (kane(kane_f, speeds) - kane(kane_w_phi, speeds))/kane(kane_v, speeds)
  end subroutine kane_rates

  !> A part that does not move (a frozen ship, the falls after hook release): q_dot = 0 and
  !> blocks V = 1, W phi = F = 0, so eq. 89 gives u_dot = 0 too.
  pure subroutine kane_at_rest(qdot, kane)
    real(wp), intent(out) :: qdot(:), kane(:, :)
    qdot = 0.0_wp
    kane(kane_v, :) = 1.0_wp
    kane(kane_w_phi, :) = 0.0_wp
    kane(kane_f, :) = 0.0_wp
  end subroutine kane_at_rest

end module davit_core_kane
