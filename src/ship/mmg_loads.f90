!> The MMG forces (davit_ship_mmg) on davit's 6-DOF ship: the manoeuvring problem lives in
!> the horizontal-body frame (level, yawed with the ship, origin at midship), the
!> seakeeping (the box's or BEM loads) acts about it; the two are summed on the one rigid
!> body (the usual two-time-scale superposition: the MMG forces see the slow horizontal
!> speeds, the seakeeping the wave-frequency motions about them).
module davit_ship_mmg_loads
  use davit_kinds, only: wp
  use davit_ship_mmg, only: mmg_type, mmg_motion, mmg_total
  implicit none
  private
  public :: mmg_body_load

contains

  !> Loads (X, Y, Z, K, M, N; ship axes about G) of the MMG model for the ship's speeds
  !> u = (omega, v) (ship axes, at G), with m = C^T R_z(psi) (level frame to ship axes),
  !> the CG x_g forward of midship, the horizontal added masses mx, my that the ship's
  !> mass matrix holds, rudder angle delta and propeller revolutions n.
  !>
  !> Yasukawa & Yoshimura's eq. 4 carries the added masses as (m + m_x) u' - (m + m_y) v_m
  !> r and (m + m_y) v_m' + (m + m_x) u r (Kirchhoff's terms; the Munk moment is in N_v),
  !> while davit's ship carries (M + A)(v' + omega x v) about G with m_y at midship
  !> (davit_ship_hull mmg_added_masses): their difference, (m_y v_m - m_x v_G) r in surge,
  !> (m_y - m_x) u r in sway at midship, is added here so that the ship obeys eq. 4.
  pure function mmg_body_load(p, x_g, mx, my, m, u, delta, n) result(load)
    !> The MMG coefficients.
    type(mmg_type), intent(in) :: p
    !> CG forward of midship x_g [m], horizontal added masses m_x, m_y [kg] held by the
    !> ship's mass matrix, rotation m = C^T R_z(psi) from the level frame to ship axes,
    !> speeds u = (omega [rad/s], v [m/s]) in ship axes at G, rudder angle delta [rad] and
    !> propeller revolutions n [1/s].
    real(wp), intent(in) :: x_g, mx, my, m(3, 3), u(6), delta, n
    real(wp) :: load(6), vl(3), r, vm, f(3)
    vl = matmul(transpose(m), u(4:6))
    r = dot_product(m(:, 3), u(1:3))
    vm = vl(2) - x_g*r
    f = mmg_total(p, mmg_motion(vl(1), vm, r, delta, n))
    f(1) = f(1) + (my*vm - mx*vl(2))*r
    f(2) = f(2) + (my - mx)*vl(1)*r
    ! moment about G of the midship forces
    f(3) = f(3) - x_g*f(2)
    load(1:3) = matmul(m, [f(1), f(2), 0.0_wp])
    load(4:6) = matmul(m, [0.0_wp, 0.0_wp, f(3)])
  end function mmg_body_load

end module davit_ship_mmg_loads
