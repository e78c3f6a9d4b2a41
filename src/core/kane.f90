!> Kane's equations in the form every body contributes to (paper eqs. 12, 53, 73, 87, 89).
!>
!> Each body or subsystem fills, over its own slice of the state, q_dot at its coordinates
!> (its kinematic relations: eqs. 5-6, 51, 77) and, at each of its speeds, the diagonal of
!> its mass block V, its gyroscopic and velocity terms W phi and its generalized active
!> forces F (eq. 12 for a rigid body; eqs. 53, 73 and 87 for lumps, blocks and sheaves),
!> stored as kane(kane_v, i), kane(kane_w_phi, i) and kane(kane_f, i) at state index i.
!> kane_rates then forms u_dot for every speed at once: eq. 89, the one place it is coded.
!> Where a body's mass block is full (the layout's coupled blocks: a BEM ship with A(inf)),
!> it fills V = 1 there, and the block's inverse turns F - W phi into u_dot; where it varies
!> in time (a lifeboat's M + s A(inf)), the body fills its modal masses as V and the
!> layout's modal matrix P gives u_dot = P ((P^T (F - W phi)) / V).
module davit_core_kane
  use davit_kinds, only: wp
  use davit_core_layout, only: state_layout_type
  implicit none
  private
  public :: kane_v, kane_w_phi, kane_f, kane_rates, kane_at_rest

  !> Rows of the Kane block array kane(3, n).
  integer, parameter :: kane_v = 1, kane_w_phi = 2, kane_f = 3

contains

  !> Eq. (89): u_dot = V^-1 (F - W phi) at every speed of the layout: V diagonal, but for
  !> the layout's coupled blocks. The speeds inside the state range `at_rest` (a part the
  !> caller set at rest, its u_dot = 0: the ship in the multirate method's fast part) are
  !> left as they are.
  pure subroutine kane_rates(layout, kane, dydt, at_rest)
    !> The state layout: the parts' speed ranges and the coupled blocks.
    type(state_layout_type), intent(in) :: layout
    !> Kane blocks, rows kane_v, kane_w_phi, kane_f, one column per state index.
    real(wp), intent(in) :: kane(:, :)
    !> State rates; u_dot is written at the speeds, q_dot left as the bodies filled it.
    real(wp), intent(inout) :: dydt(:)
    !> State index range [first, last] of speeds left as they are (a part at rest).
    integer, intent(in), optional :: at_rest(2)
    integer :: k, skip(2)
    skip = [1, 0]
    if (present(at_rest)) skip = at_rest
    ! part by part: each part's speeds are contiguous, so this is whole-array work on
    ! sections, with no gathered temporaries
    do k = 1, layout%nparts
      associate (u1 => layout%parts(k)%u(1), u2 => layout%parts(k)%u(2))
        if (u1 >= skip(1) .and. u2 <= skip(2)) cycle
        dydt(u1:u2) = (kane(kane_f, u1:u2) - kane(kane_w_phi, u1:u2))/kane(kane_v, u1:u2)
      end associate
    end do
    if (.not. allocated(layout%coupled)) return
    do k = 1, size(layout%coupled)
      associate (b => layout%coupled(k))
        if (b%u(1) >= skip(1) .and. b%u(2) <= skip(2)) cycle
        if (b%modal) then
          call apply_modal(b%v_inv, kane(:, b%u(1):b%u(2)), dydt(b%u(1):b%u(2)))
        else
          call apply_inverse(b%v_inv, dydt(b%u(1):b%u(2)))
        end if
      end associate
    end do
  end subroutine kane_rates

  !> x = v_inv x.
  pure subroutine apply_inverse(v_inv, x)
    !> Inverse of the block's mass matrix, V^-1.
    real(wp), intent(in) :: v_inv(:, :)
    !> Right-hand side F - W phi on entry, u_dot on return.
    real(wp), intent(inout) :: x(:)
    real(wp) :: b(size(x))
    b = x
    x = matmul(v_inv, b)
  end subroutine apply_inverse

  !> u_dot = P diag(1/V) P^T (F - W phi) of a modal block (V: the modal masses).
  pure subroutine apply_modal(p, kane, u_dot)
    !> Constant modal matrix P of the block, and its Kane blocks (V the modal masses).
    real(wp), intent(in) :: p(:, :), kane(:, :)
    !> Rates u_dot of the block's speeds.
    real(wp), intent(out) :: u_dot(:)
    real(wp) :: b(size(u_dot))
    b = matmul(kane(kane_f, :) - kane(kane_w_phi, :), p)/kane(kane_v, :)
    u_dot = matmul(p, b)
  end subroutine apply_modal

  !> A part that does not move (a frozen ship, the falls after hook release): q_dot = 0 and
  !> blocks V = 1, W phi = F = 0, so eq. 89 gives u_dot = 0 too.
  pure subroutine kane_at_rest(qdot, kane)
    !> The part's q_dot (set to 0) and its Kane blocks (V = 1, W phi = F = 0).
    real(wp), intent(out) :: qdot(:), kane(:, :)
    qdot = 0.0_wp
    kane(kane_v, :) = 1.0_wp
    kane(kane_w_phi, :) = 0.0_wp
    kane(kane_f, :) = 0.0_wp
  end subroutine kane_at_rest

end module davit_core_kane
