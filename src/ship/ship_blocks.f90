!> The ship's Kane blocks (V, W phi, F) for its rigid body and added masses in the
!> seakeeping frame: the box's constant strip-theory added masses and the BEM ship's
!> A(inf) (eq. 89 with the review's §1.2 corrections), and the restrained DOFs of a tank
!> test. Split from davit_ship_ship_model, which calls them.
module davit_ship_ship_blocks
  use davit_kinds, only: wp
  use davit_core_rotation, only: cross
  use davit_core_kane, only: kane_v, kane_w_phi, kane_f
  use davit_ship_bem_loads, only: bem_ship_type, seakeeping_mass, solve_small
  use davit_ship_hull, only: hull_type
  implicit none
  private
  public :: box_blocks, bem_blocks

contains

  !> V, W phi, F of the box ship at speeds u (omega, v) under the loads `load`, with its
  !> constant strip-theory added masses in the seakeeping frame as the BEM ship's (see
  !> bem_blocks): M_h (u' + (0, omega x v)) = F - omega x (I_g omega), M_h = M_rb + m6 A m6^T,
  !> A = diag(added inertias, added masses); V = M + A (diagonal) and M_h - V in W phi. In
  !> ship axes the heave added mass leaned with the roll: a mean sway force
  !> -<phi (a33 - a22) z''> up-wave (a 14 m drift in 100 s of Level 5 beam seas without
  !> drag).
  pure subroutine box_blocks(hull, u, m, load, kane)
    !> The box hull (masses, added masses, inertias, restrained DOFs).
    type(hull_type), intent(in) :: hull
    !> Speeds u = (omega [rad/s], v [m/s]) in ship axes at G (Kane order), the rotation m =
    !> C^T R_z(psi) from the seakeeping frame to ship axes, and the external loads (X, Y, Z [N],
    !> K, M, N [N m]) in ship axes about G.
    real(wp), intent(in) :: u(6), m(3, 3), load(6)
    !> The rows V, W phi and F (kane_v, kane_w_phi, kane_f) of the ship's six speeds, Kane
    !> order (moments [N m] and inertias first, then forces [N] and masses).
    real(wp), intent(out) :: kane(3, 6)
    real(wp) :: mt(3), it(3), ig(3), a(6, 6), mh(6, 6), transport(6), gyro(6), ud(6), rhs(6)
    integer :: k
    mt = hull%mass + hull%added_mass
    it = hull%inertia + hull%added_inertia
    ! Gyroscopic term with the rigid-body inertia plus only the manoeuvring yaw added
    ! inertia: the strip-theory roll and pitch added inertias are frequency-domain
    ! quantities, not rigid-body ones, and in omega x (I omega) their product p q (A55 - A44)
    ! made a spurious mean yaw moment of MN m that turned the ship 19 deg in 135 deg seas.
    ig = hull%inertia + [0.0_wp, 0.0_wp, hull%added_inertia(3)]
    a = 0.0_wp
    do k = 1, 3
      a(k, k) = hull%added_inertia(k)
      a(k + 3, k + 3) = hull%added_mass(k)
    end do
    a(3, 5) = hull%added_sway_yaw
    a(5, 3) = hull%added_sway_yaw
    mh = seakeeping_mass(a, hull%inertia, hull%mass, m)
    transport = [0.0_wp, 0.0_wp, 0.0_wp, cross(u(1:3), u(4:6))]
    gyro = [cross(u(1:3), ig*u(1:3)), 0.0_wp, 0.0_wp, 0.0_wp]
    ud = [load(4:6), load(1:3)] - gyro - matmul(mh, transport)
    rhs = ud
    call solve_restrained(hull%restrained, mh, ud)
    kane(kane_v, :) = [it, mt]
    ! + the restraint's reaction rhs - mh ud (zero in the free rows)
    kane(kane_w_phi, :) = gyro + matmul(mh, transport + ud) - kane(kane_v, :)*ud + &
                          rhs - matmul(mh, ud)
    kane(kane_f, 1:3) = load(4:6)
    kane(kane_f, 4:6) = load(1:3)
  end subroutine box_blocks

  !> The BEM ship's blocks (V = 1: M + A(inf) is the layout's coupled block, which takes
  !> V u' = F - W phi). Rigid body in ship axes (eq. 35: omega x (I omega), m omega x v);
  !> Cummins' added-mass force in the seakeeping frame, -m6 A m6^T (u' + (0, omega x v))
  !> (bem_loads' seakeeping_mass), so the ship's speeds obey M_h (u' + (0, omega x v)) =
  !> F - (omega x (I omega), 0) with M_h = M_rb + m6 A m6^T. Solved here for u', the
  !> difference M_h - (M + A(inf)) goes into W phi with that u'. Applied in ship axes as
  !> (M + A) u' alone, the added mass lost its transport A (omega x v) and did not turn
  !> with the roll: a second-order mean sway force of -A(inf) with the rolled heave
  !> acceleration, ~3.6e4 N up-wave in Level 5 beam seas.
  pure subroutine bem_blocks(hydro, restrained, u, m, load, kane)
    !> The BEM ship (A(inf) and M + A(inf) in Kane order, rigid-body mass and inertia).
    type(bem_ship_type), intent(in) :: hydro
    !> DOFs held at zero acceleration (surge, sway, heave, roll, pitch, yaw), as in a tank test.
    logical, intent(in) :: restrained(6)
    !> Speeds u = (omega [rad/s], v [m/s]) in ship axes at G (Kane order), the rotation m =
    !> C^T R_z(psi) from the seakeeping frame to ship axes, and the external loads (X, Y, Z [N],
    !> K, M, N [N m]; the radiation memory included) in ship axes about G.
    real(wp), intent(in) :: u(6), m(3, 3), load(6)
    !> The rows V (all 1: the layout's coupled block holds M + A(inf)), W phi [N m, N] and
    !> F [N m, N] of the ship's six speeds, Kane order.
    real(wp), intent(out) :: kane(3, 6)
    real(wp) :: mh(6, 6), transport(6), gyro(6), ud(6), rhs(6)
    mh = seakeeping_mass(hydro%a_kane, hydro%inertia, hydro%mass, m)
    transport = [0.0_wp, 0.0_wp, 0.0_wp, cross(u(1:3), u(4:6))]
    gyro = [cross(u(1:3), hydro%inertia*u(1:3)), 0.0_wp, 0.0_wp, 0.0_wp]
    ud = [load(4:6), load(1:3)] - gyro - matmul(mh, transport)
    rhs = ud
    call solve_restrained(restrained, mh, ud)
    kane(kane_v, :) = 1.0_wp
    ! + the restraint's reaction rhs - mh ud (zero in the free rows)
    kane(kane_w_phi, :) = gyro + matmul(mh, transport + ud) - matmul(hydro%m_kane, ud) + &
                          rhs - matmul(mh, ud)
    kane(kane_f, 1:3) = load(4:6)
    kane(kane_f, 4:6) = load(1:3)
  end subroutine bem_blocks

  !> Solve mh ud = rhs (ud holds rhs on entry; order roll, pitch, yaw, surge, sway, heave)
  !> with the restrained DOFs (fixed: surge .. yaw) held at zero acceleration: their rows
  !> and columns replaced by the identity, so the free ones obey their own block of mh.
  pure subroutine solve_restrained(fixed, mh, ud)
    logical, intent(in) :: fixed(6)
    real(wp), intent(in) :: mh(6, 6)
    real(wp), intent(inout) :: ud(6)
    integer, parameter :: slot(6) = [4, 5, 6, 1, 2, 3]
    real(wp) :: a(6, 6)
    integer :: k
    a = mh
    do k = 1, 6
      if (.not. fixed(k)) cycle
      a(slot(k), :) = 0.0_wp
      a(:, slot(k)) = 0.0_wp
      a(slot(k), slot(k)) = 1.0_wp
      ud(slot(k)) = 0.0_wp
    end do
    call solve_small(a, ud)
  end subroutine solve_restrained

end module davit_ship_ship_blocks
