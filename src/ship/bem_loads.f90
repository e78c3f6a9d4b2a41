!> The ship from a BEM database in the time domain: Cummins' equation (Cummins 1962)
!>   (M + A(inf)) u' + mu(t) + C eta = F_exc + F_visc + F_other,
!>   mu_i(t) = sum_j int_0^t K_ij(t - tau) u_j(tau) dtau,
!> with the memory mu from the database's fitted state-space models (x' = A_s x + B_s u_j,
!> mu_ij = C_s x; Perez & Fossen 2008), the first-order wave load per component from the
!> database's X(omega, beta) (Froude-Krylov + diffraction), the hydrostatic stiffness C
!> of the mesh, and a viscous roll damping as a fraction of critical (potential flow has
!> almost none in roll). M and A(inf) couple surge-pitch and sway-roll-yaw: the mass block
!> is full, registered with the state layout as a coupled block (eq. 89 with V^-1).
!>
!> Speeds here in DOF order (surge, sway, heave, roll, pitch, yaw) = (v, omega); the Kane
!> speeds of a rigid body are (omega, v) (eq. 4), hence the permutations.
!>
!> Cummins' equation is linear in the seakeeping frame h (level, yawed with the ship), not
!> in the rolling and pitching ship axes: its loads are computed there from the speeds and
!> absolute accelerations resolved in h, and turned into ship axes with m = C^T Rz(psi)
!> (a rotation, so ship axes <- h is m and h <- ship axes is m^T). Written in ship axes
!> instead, a first-order load turned with the first-order roll has a second-order mean:
!> the heave memory force B33 w along the rolled z axis gave a mean sway force
!> -<phi B33 w> ~ 2.7e5 N up-wave in Level 5 beam seas (issue 20, item 1).
module davit_ship_bem_loads
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_ship_bem_database, only: bem_database_type, bem_excitation
  use davit_sea_wave_field, only: wave_field_type
  implicit none
  private
  public :: bem_ship_type, new_bem_ship, bem_wave_coefficients, bem_restoring, &
            bem_memory, to_kane_order, bem_roll_damping, invert, seakeeping_mass, &
            turn_to_body, solve_small, bem_speed_load

  !> The BEM ship's hydrodynamics: database, masses and their Kane-order blocks.
  type :: bem_ship_type
    !> The database (a copy of the one read at build).
    type(bem_database_type) :: db
    !> Rigid-body mass [kg] and principal inertia about the CG [kg m^2] (the database's).
    real(wp) :: mass = 0.0_wp, inertia(3) = 0.0_wp
    !> (M + A(inf))^-1 in Kane order (omega, v).
    real(wp) :: v_inv(6, 6) = 0.0_wp
    !> A(inf) and M + A(inf) in Kane order.
    real(wp) :: a_kane(6, 6) = 0.0_wp, m_kane(6, 6) = 0.0_wp
    !> Linear viscous roll damping [N m s].
    real(wp) :: b44 = 0.0_wp
    !> Row C A_s^-1 of each pair's memory realisation (A_s, B_s, C), laid out as the
    !> states: C A_s^-1 x is (K(s) - K(0))/s of the pair's input, its memory of the
    !> input's time integral (bem_speed_load; the fits have K(0) = 0).
    real(wp), allocatable :: c_int(:)
  end type bem_ship_type

  !> Kane order (omega, v) of the DOF indices: position k of the Kane speeds is DOF perm(k).
  integer, parameter :: perm(6) = [4, 5, 6, 1, 2, 3]

  interface
    subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: wp
      integer, intent(in) :: n, nrhs, lda, ldb
      real(wp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgesv
  end interface

contains

  !> The BEM ship of database db with viscous roll damping zeta_roll of critical:
  !> B44 = zeta 2 sqrt(C44 (I44 + A44(w_roll))), w_roll = sqrt(C44/(I44 + A44(w_roll))).
  subroutine new_bem_ship(db, zeta_roll, ship, error)
    !> The ship's BEM database.
    type(bem_database_type), intent(in) :: db
    !> Viscous roll damping as a fraction of critical (0 = none).
    real(wp), intent(in) :: zeta_roll
    !> The BEM ship built.
    type(bem_ship_type), intent(out) :: ship
    !> Set when M + A(inf) is not positive definite or the mass or an inertia is not > 0.
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: m(6, 6)
    integer :: info
    ship%db = db
    ship%mass = db%mass(1, 1)
    ship%inertia = [db%mass(4, 4), db%mass(5, 5), db%mass(6, 6)]
    m = to_kane_order(db%mass + db%added_mass_inf)
    ship%m_kane = m
    ship%a_kane = to_kane_order(db%added_mass_inf)
    call invert(m, ship%v_inv, info)
    if (info /= 0 .or. ship%mass <= 0.0_wp .or. any(ship%inertia <= 0.0_wp)) then
      call fatal_error(error, "BEM database '"//db%path//"': the mass matrix plus A(inf) "// &
                       "is not positive definite")
      return
    end if
    ship%b44 = bem_roll_damping(db, zeta_roll)
    call integral_readout(db, ship%c_int)
  end subroutine new_bem_ship

  !> C A_s^-1 of every pair's realisation (the states' layout): A_s^T y = C^T.
  pure subroutine integral_readout(db, c_int)
    type(bem_database_type), intent(in) :: db
    real(wp), allocatable, intent(out) :: c_int(:)
    real(wp), allocatable :: y(:)
    integer :: k, i0, n
    allocate (c_int(db%nrad))
    do k = 1, size(db%pairs)
      i0 = db%pairs(k)%first - 1
      n = db%pairs(k)%n
      y = db%pairs(k)%c(1:n)
      call solve_small(transpose(db%pairs(k)%a(1:n, 1:n)), y)
      c_int(i0 + 1:i0 + n) = y
    end do
  end subroutine integral_readout

  !> The forward-speed terms of the radiation load (DOF order, seakeeping frame) of the
  !> ship making way at U, beyond Cummins' zero-speed -A(inf) xi'' - mu[u] (Salvesen, Tuck
  !> & Faltinsen 1970, Table 1 without end terms, written in the time domain). Their
  !> coefficients, T(U) = T + (U/(i w)) (T E - E^T T) + (U/w)^2 E^T T E with the zero-speed
  !> T = -w^2 A + i w B and E(3,5) = 1, E(2,6) = -1 (postproc/bem_speed.py), are, with
  !> K(i w) = B + i w A = i w A(inf) + K_mem(i w) the impedance on the speeds,
  !>   F = -K u + U E^T K (int u),   u = xi' + U E xi,
  !> u the body-frame speeds about the steady motion (heave w + U theta, sway v - U psi:
  !> the body condition of a body making way). The memory is fed u by the caller; here:
  !> (1) -A(inf) u' in place of -A(inf) xi'': +U (A(:,2) r - A(:,3) q), taking out the
  !> steady speed's part of the transport acceleration that the mass block adds
  !> (davit_ship_ship_blocks: A (omega x v), v = (U, 0, 0)); (2) U E^T (A(inf) u +
  !> mu[int u]): the pitch moment U times the heave force's, the yaw moment -U times the
  !> sway force's, of the convected flow, mu[int u] = C A_s^-1 x from the memory's states.
  pure function bem_speed_load(ship, x, u_dof, speed, sway_yaw) result(load)
    !> The BEM ship (A(inf), its memory's realisations and their integral readout).
    type(bem_ship_type), intent(in) :: ship
    !> The radiation states x (the memory fed u_dof) and the body-frame speeds u (DOF
    !> order: u - U, v, w [m/s], p, q, r [rad/s]) in the seakeeping frame.
    real(wp), intent(in) :: x(:), u_dof(6)
    !> The forward speed U [m/s].
    real(wp), intent(in) :: speed
    !> With the sway-yaw terms (E(2,6)); without them, the heave-pitch ones (E(3,5)) alone.
    logical, intent(in) :: sway_yaw
    real(wp) :: load(6), f(6)
    integer :: k, i0, n
    associate (a => ship%db%added_mass_inf)
      load = -speed*a(:, 3)*u_dof(5)
      if (sway_yaw) load = load + speed*a(:, 2)*u_dof(6)
      f = matmul(a, u_dof)
    end associate
    do k = 1, size(ship%db%pairs)
      i0 = ship%db%pairs(k)%first - 1
      n = ship%db%pairs(k)%n
      associate (i => ship%db%pairs(k)%i)
        f(i) = f(i) + sum(ship%c_int(i0 + 1:i0 + n)*x(i0 + 1:i0 + n))
      end associate
    end do
    load(5) = load(5) + speed*f(3)
    if (sway_yaw) load(6) = load(6) - speed*f(2)
  end function bem_speed_load

  !> Viscous roll damping zeta of critical at the undamped roll resonance of the database,
  !> with its roll stiffness and inertia or the given ones (c44 [N m], i44 [kg m^2]: a body
  !> whose restoring comes from elsewhere, the lifeboat's strips):
  !> B44 = zeta 2 sqrt(C44 (I44 + A44(w))), w = sqrt(C44/(I44 + A44(w))) iterated.
  pure real(wp) function bem_roll_damping(db, zeta, c44, i44) result(b44)
    !> The database (A44(omega); C44 and I44 unless given).
    type(bem_database_type), intent(in) :: db
    !> Damping as a fraction of critical (0 = none).
    real(wp), intent(in) :: zeta
    !> Roll stiffness C44 [N m/rad] and roll inertia I44 [kg m^2] in place of the database's
    !> (a body whose restoring comes from elsewhere).
    real(wp), intent(in), optional :: c44, i44
    real(wp) :: w, a44, c, m
    integer :: k
    b44 = 0.0_wp
    c = db%stiffness(4, 4)
    m = db%mass(4, 4)
    if (present(c44)) c = c44
    if (present(i44)) m = i44
    if (c <= 0.0_wp) return
    w = sqrt(c/(m + db%added_mass_inf(4, 4)))
    do k = 1, 50
      a44 = interpolate(db%omega, db%added_mass(4, 4, :), w)
      w = sqrt(c/(m + a44))
    end do
    b44 = zeta*2.0_wp*sqrt(c*(m + a44))
  end function bem_roll_damping

  !> A 6 x 6 DOF-order matrix in Kane order (omega, v).
  pure function to_kane_order(m) result(k)
    !> A 6 x 6 matrix in DOF order (surge, sway, heave, roll, pitch, yaw).
    real(wp), intent(in) :: m(6, 6)
    real(wp) :: k(6, 6)
    k = m(perm, perm)
  end function to_kane_order

  !> Wave-load coefficients of every sea component for the ship at heading psi, in the
  !> heading frame (level ship axes), so that the load is
  !> sum_i fk_sin(:, i) sin(Phi_i) + fk_cos(:, i) cos(Phi_i), Phi_i the component's phase at
  !> the CG's initial position: a Re(X e^(i Phi)) = a Re X cos Phi - a Im X sin Phi.
  pure subroutine bem_wave_coefficients(ship, sea, psi, fk_sin, fk_cos)
    !> The BEM ship (its database's X(omega, beta)).
    type(bem_ship_type), intent(in) :: ship
    !> The sea: components' amplitudes [m], frequencies [rad/s] and directions [rad].
    type(wave_field_type), intent(in) :: sea
    !> The ship's heading psi [rad].
    real(wp), intent(in) :: psi
    !> Coefficients [N, N m] of sin(Phi_i) and cos(Phi_i), shape (6, number of components),
    !> load order X, Y, Z, K, M, N in the heading frame.
    real(wp), intent(out) :: fk_sin(:, :), fk_cos(:, :)
    complex(wp) :: x(6)
    integer :: i
    do i = 1, sea%n
      x = bem_excitation(ship%db, sea%omega(i), sea%direction(i) - psi)
      fk_cos(:, i) = sea%amplitude(i)*real(x, wp)
      fk_sin(:, i) = -sea%amplitude(i)*aimag(x)
    end do
  end subroutine bem_wave_coefficients

  !> Hydrostatic restoring -C delta (load order X, Y, Z, K, M, N) for the heave z - z_eq and
  !> the roll and pitch from the static list and trim, in the seakeeping frame and turned
  !> into ship axes by m: the vertical force acts along the inertial vertical (m e_z = row 3
  !> of C), as the weight and buoyancy do, the moments about the level axes.
  pure function bem_restoring(ship, dz, droll, dpitch, m) result(load)
    !> The BEM ship (its hydrostatic stiffness C).
    type(bem_ship_type), intent(in) :: ship
    !> Heave from equilibrium z - z_eq [m] (z down), roll and pitch from the static list and
    !> trim [rad], and the rotation m = C^T Rz(psi) from the seakeeping frame to ship axes.
    real(wp), intent(in) :: dz, droll, dpitch, m(3, 3)
    real(wp) :: load(6)
    load = turn_to_body(m, -matmul(ship%db%stiffness, [0.0_wp, 0.0_wp, dz, droll, dpitch, &
                                                        0.0_wp]))
  end function bem_restoring

  !> A DOF-order load (forces, moments) of the seakeeping frame in ship axes: m f.
  pure function turn_to_body(m, f) result(load)
    !> The rotation m from the seakeeping frame to ship axes and the load f (X, Y, Z [N],
    !> K, M, N [N m]) in the seakeeping frame.
    real(wp), intent(in) :: m(3, 3), f(6)
    real(wp) :: load(6)
    load(1:3) = matmul(m, f(1:3))
    load(4:6) = matmul(m, f(4:6))
  end function turn_to_body

  !> The mass matrix of a ship's speeds (Kane order) with Cummins' added-mass force
  !> -A xi'' in the seakeeping frame: M_rb + m6 A m6^T, m6 = diag(m, m), for the added mass
  !> a_kane (Kane order) and the rigid body's principal inertia and mass. The absolute
  !> accelerations in h are m^T (v' + omega x v) and m^T omega', so in ship axes the force
  !> is -m6 A m6^T (u' + (0, omega x v)): a full block that turns with the roll and pitch.
  !> At m = 1 it is M + A, the layout's block.
  pure function seakeeping_mass(a_kane, inertia, mass, m) result(mh)
    !> Added mass in Kane order (omega, v) [kg, kg m, kg m^2], the rigid body's principal
    !> inertia about the CG [kg m^2] and mass [kg], and the rotation m from the seakeeping
    !> frame to ship axes.
    real(wp), intent(in) :: a_kane(6, 6), inertia(3), mass, m(3, 3)
    real(wp) :: mh(6, 6)
    integer :: i, j, k
    do j = 0, 3, 3
      do i = 0, 3, 3
        mh(i + 1:i + 3, j + 1:j + 3) = matmul(m, matmul(a_kane(i + 1:i + 3, j + 1:j + 3), &
                                                        transpose(m)))
      end do
    end do
    do k = 1, 3
      mh(k, k) = mh(k, k) + inertia(k)
      mh(k + 3, k + 3) = mh(k + 3, k + 3) + mass
    end do
  end function seakeeping_mass

  !> Solve a x = b for a small matrix a (Gaussian elimination with partial pivoting; the
  !> database's A(inf) need not be exactly symmetric), x in place of b.
  pure subroutine solve_small(a, b)
    !> The square matrix (not changed).
    real(wp), intent(in) :: a(:, :)
    !> Right-hand side on entry, solution x on return.
    real(wp), intent(inout) :: b(:)
    real(wp) :: lu(size(b), size(b)), row(size(b)), s
    integer :: i, j, p, n
    n = size(b)
    lu = a
    do j = 1, n
      p = j - 1 + maxloc(abs(lu(j:, j)), 1)
      row = lu(j, :)
      lu(j, :) = lu(p, :)
      lu(p, :) = row
      s = b(j)
      b(j) = b(p)
      b(p) = s
      do i = j + 1, n
        s = lu(i, j)/lu(j, j)
        lu(i, j:) = lu(i, j:) - s*lu(j, j:)
        b(i) = b(i) - s*b(j)
      end do
    end do
    do i = n, 1, -1
      b(i) = (b(i) - sum(lu(i, i + 1:)*b(i + 1:)))/lu(i, i)
    end do
  end subroutine solve_small

  !> The radiation memory of database db: rates of the states x and the memory load mu
  !> (DOF order) for the speeds u_dof (DOF order).
  pure subroutine bem_memory(db, x, u_dof, xdot, mu)
    !> The database (its fitted kernels).
    type(bem_database_type), intent(in) :: db
    !> The radiation states x (db%nrad) and the speeds in DOF order (u, v, w [m/s], p, q, r
    !> [rad/s]) in the frame the memory is taken in.
    real(wp), intent(in) :: x(:), u_dof(6)
    !> Rates of the radiation states (db%nrad) and the memory load mu [N, N m] in DOF order,
    !> same frame as the speeds.
    real(wp), intent(out) :: xdot(:), mu(6)
    real(wp) :: s, m
    integer :: k, r, q, i0, n
    mu = 0.0_wp
    ! written out: the pairs' realisations are a few states each, where matmul's and
    ! dot_product's set-up on allocatable components costs more than the arithmetic
    do k = 1, size(db%pairs)
      i0 = db%pairs(k)%first - 1
      n = db%pairs(k)%n
      m = 0.0_wp
      do r = 1, n
        s = db%pairs(k)%b(r)*u_dof(db%pairs(k)%j)
        do q = 1, n
          s = s + db%pairs(k)%a(r, q)*x(i0 + q)
        end do
        xdot(i0 + r) = s
        m = m + db%pairs(k)%c(r)*x(i0 + r)
      end do
      mu(db%pairs(k)%i) = mu(db%pairs(k)%i) + m
    end do
  end subroutine bem_memory

  !> Linear interpolation of y(x) at v (clamped).
  pure real(wp) function interpolate(x, y, v) result(r)
    real(wp), intent(in) :: x(:), y(:), v
    integer :: i
    if (v <= x(1)) then
      r = y(1)
    else if (v >= x(size(x))) then
      r = y(size(y))
    else
      i = 1
      do while (v > x(i + 1))
        i = i + 1
      end do
      r = y(i) + (y(i + 1) - y(i))*(v - x(i))/(x(i + 1) - x(i))
    end if
  end function interpolate

  !> Inverse of a small matrix by LAPACK (dgesv on the identity).
  subroutine invert(a, a_inv, info)
    !> The square matrix (not changed).
    real(wp), intent(in) :: a(:, :)
    !> Its inverse, same shape.
    real(wp), intent(out) :: a_inv(:, :)
    !> LAPACK dgesv's status: 0 on success, > 0 when the matrix is singular.
    integer, intent(out) :: info
    real(wp) :: lu(size(a, 1), size(a, 1))
    integer :: ipiv(size(a, 1)), k
    lu = a
    a_inv = 0.0_wp
    do k = 1, size(a, 1)
      a_inv(k, k) = 1.0_wp
    end do
    call dgesv(size(a, 1), size(a, 1), lu, size(a, 1), ipiv, a_inv, size(a, 1), info)
  end subroutine invert

end module davit_ship_bem_loads
