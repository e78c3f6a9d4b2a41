!> The ship's hydrodynamic database from a boundary-element solution (Capytaine, written by
!> `python -m postproc.bem build`; netCDF4 = HDF5, read here with the HDF5 Fortran API).
!>
!> All in davit's frame: ship body axes x forward, y starboard, z down, about the CG; DOFs
!> surge, sway, heave, roll, pitch, yaw (index i the force or moment, j the motion). What a
!> time-domain ship needs from it (Cummins' equation): the infinite-frequency added mass
!> A(inf), the hydrostatic stiffness C, the first-order wave load per unit amplitude
!> X(omega, beta) (Froude-Krylov + diffraction, phase at the CG) and the radiation memory
!> mu_i = sum_j int K_ij(t - tau) u_j(tau) dtau as fitted state-space models
!> x' = A_s x + B_s u_j, mu_ij = C_s x per DOF pair (Perez & Fossen 2008: a few states per
!> pair instead of a convolution over the whole history in every right-hand side). A(omega)
!> and B(omega) are kept for checks and for the viscous roll damping's reference. The
!> Froude-Krylov part of X is kept apart too: a body whose Froude-Krylov load comes from
!> elsewhere (the lifeboat's strips, on the instantaneous wetted hull) takes the
!> diffraction part X - X_FK alone (bem_excitation with diffraction_only).
module davit_ship_bem_database
  use davit_kinds, only: wp, pi
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_reader, only: h5_reader_type
  implicit none
  private
  public :: bem_database_type, radiation_pair_type, read_bem_database, bem_excitation, bracket, &
            bem_drift

  !> One fitted memory kernel: force DOF i, motion DOF j, order n, its first state in the
  !> ship's radiation states, and its matrices (n x n, n, n).
  type :: radiation_pair_type
    !> Force DOF i and motion DOF j (1..6: surge, sway, heave, roll, pitch, yaw), the order n
    !> (number of states) and the index of the first state in the ship's radiation states.
    integer :: i = 0, j = 0, n = 0, first = 0
    !> State matrix A_s (n x n, [1/s]), input vector B_s (n) and output vector C_s (n) of
    !> x' = A_s x + B_s u_j, mu_ij = C_s x (units such that mu_ij is in N or N m).
    real(wp), allocatable :: a(:, :), b(:), c(:)
  end type radiation_pair_type

  !> A ship's BEM database as davit uses it (body axes, about the CG).
  type :: bem_database_type
    !> The file the database was read from (named in the error messages).
    character(len=:), allocatable :: path
    !> Frequencies [rad/s] (ascending) and relative headings [rad] (0 .. 2 pi).
    real(wp), allocatable :: omega(:), heading(:)
    !> A_ij(omega), B_ij(omega) as (i, j, omega).
    real(wp), allocatable :: added_mass(:, :, :), damping(:, :, :)
    !> Re and Im of X_i(omega, beta) as (i, beta, omega) [N/m, N m/m].
    real(wp), allocatable :: exc_re(:, :, :), exc_im(:, :, :)
    !> Its Froude-Krylov part, as (i, beta, omega).
    real(wp), allocatable :: fk_re(:, :, :), fk_im(:, :, :)
    !> Infinite-frequency added mass A(inf) of the memory model (davit_ss_added_mass_inf,
    !> else davit_added_mass_inf) [kg, kg m, kg m^2] and hydrostatic stiffness C
    !> [N/m, N, N m/rad], 6 x 6 about the CG in body axes.
    real(wp) :: added_mass_inf(6, 6) = 0.0_wp, stiffness(6, 6) = 0.0_wp
    !> Rigid-body mass matrix [kg, kg m, kg m^2] (6 x 6 about the CG) and displaced volume
    !> [m^3] of the hull the database was computed for.
    real(wp) :: mass(6, 6) = 0.0_wp, volume = 0.0_wp
    !> Whether the file holds the mean wave drift load per unit amplitude squared (optional:
    !> databases written before it lack it).
    logical :: has_drift = .false.
    !> Mean wave drift load per unit amplitude squared D_i(omega, beta) (surge, sway [N/m^2],
    !> yaw [N m/m^2]) as (i, beta, omega); allocated only when has_drift.
    real(wp), allocatable :: drift(:, :, :)
    !> Radiation states in all (sum of the orders).
    integer :: nrad = 0
    !> The fitted memory kernels, one per DOF pair of non-zero order.
    type(radiation_pair_type), allocatable :: pairs(:)
  end type bem_database_type

contains

  !> Read the davit variables of database `path`.
  subroutine read_bem_database(path, db, error)
    !> Path of the netCDF4/HDF5 file written by `python -m postproc.bem build`.
    character(len=*), intent(in) :: path
    !> The database read.
    type(bem_database_type), intent(out) :: db
    !> Set when the file is missing, unreadable or a dataset has the wrong shape or values.
    type(error_type), allocatable, intent(out) :: error
    type(h5_reader_type) :: h5
    db%path = path
    call h5%open(path, error)
    if (allocated(error)) return
    call read_grid(h5, db, error)
    if (.not. allocated(error)) call read_matrices(h5, db, error)
    if (.not. allocated(error)) call read_radiation(h5, db, error)
    if (.not. allocated(error)) call read_drift(h5, db, error)
    call h5%close()
    if (allocated(error)) error%message = "BEM database: "//error%message
  end subroutine read_bem_database

  !> Frequencies, headings, A(omega), B(omega) and the excitation.
  subroutine read_grid(h5, db, error)
    type(h5_reader_type), intent(inout) :: h5
    type(bem_database_type), intent(inout) :: db
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:)
    integer, allocatable :: dims(:)
    integer :: nw, nb
    call h5%read_1d("davit_omega", db%omega, error)
    if (allocated(error)) return
    call h5%read_1d("davit_heading", db%heading, error)
    if (allocated(error)) return
    nw = size(db%omega)
    nb = size(db%heading)
    if (nb == 1) then
      ! the excitation is interpolated between headings as the ship yaws: one heading says
      ! nothing about the others (`davit-post bem rao` answers at that one heading only)
      call fatal_error(error, "'"//db%path//"': holds one heading only; davit's ship "// &
                       "needs at least 2 around the headings it meets (rebuild with "// &
                       "davit-post bem build --headings-deg ...)")
      return
    end if
    ! written as "all ascending" so that a NaN fails the check too
    if (nw < 2 .or. nb < 2 .or. .not. all(db%omega(2:) > db%omega(:nw - 1)) .or. &
        .not. all(db%heading(2:) > db%heading(:nb - 1))) then
      call fatal_error(error, "'"//db%path//"': davit_omega and davit_heading must hold "// &
                       "at least 2 ascending values each")
      return
    end if
    ! numpy (omega, i, j) is Fortran (j, i, omega): transpose each matrix
    call read_shaped(h5, "davit_added_mass", [6, 6, nw], x, dims, error)
    if (allocated(error)) return
    db%added_mass = transposed(reshape(x, [6, 6, nw]))
    call read_shaped(h5, "davit_radiation_damping", [6, 6, nw], x, dims, error)
    if (allocated(error)) return
    db%damping = transposed(reshape(x, [6, 6, nw]))
    ! numpy (omega, beta, i) is Fortran (i, beta, omega)
    call read_shaped(h5, "davit_excitation_re", [6, nb, nw], x, dims, error)
    if (allocated(error)) return
    db%exc_re = reshape(x, [6, nb, nw])
    call read_shaped(h5, "davit_excitation_im", [6, nb, nw], x, dims, error)
    if (allocated(error)) return
    db%exc_im = reshape(x, [6, nb, nw])
    call read_shaped(h5, "davit_froude_krylov_re", [6, nb, nw], x, dims, error)
    if (allocated(error)) return
    db%fk_re = reshape(x, [6, nb, nw])
    call read_shaped(h5, "davit_froude_krylov_im", [6, nb, nw], x, dims, error)
    if (allocated(error)) return
    db%fk_im = reshape(x, [6, nb, nw])
  end subroutine read_grid

  !> A(inf), hydrostatic stiffness, rigid-body mass matrix and displaced volume.
  subroutine read_matrices(h5, db, error)
    type(h5_reader_type), intent(inout) :: h5
    type(bem_database_type), intent(inout) :: db
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:)
    integer, allocatable :: dims(:)
    call read_shaped(h5, "davit_added_mass_inf", [6, 6], x, dims, error)
    if (allocated(error)) return
    db%added_mass_inf = transpose(reshape(x, [6, 6]))
    ! the memory fits' A_inf where the build wrote it: an impedance fit may shift the BEM's
    ! A_inf (postproc.bem_fit.fit_impedance), and Cummins' mass must be the fitted model's
    if (h5%has_dataset("davit_ss_added_mass_inf")) then
      call read_shaped(h5, "davit_ss_added_mass_inf", [6, 6], x, dims, error)
      if (allocated(error)) return
      db%added_mass_inf = transpose(reshape(x, [6, 6]))
    end if
    call read_shaped(h5, "davit_hydrostatic_stiffness", [6, 6], x, dims, error)
    if (allocated(error)) return
    db%stiffness = transpose(reshape(x, [6, 6]))
    call read_shaped(h5, "davit_mass_matrix", [6, 6], x, dims, error)
    if (allocated(error)) return
    db%mass = transpose(reshape(x, [6, 6]))
    call h5%read_array("davit_displaced_volume", x, dims, error)
    if (allocated(error)) return
    if (size(x) /= 1) then
      call fatal_error(error, "'"//h5%path//"': davit_displaced_volume must hold one value")
      return
    end if
    db%volume = x(1)
  end subroutine read_matrices

  !> The fitted state-space kernels: every pair of non-zero order, its states numbered
  !> consecutively.
  subroutine read_radiation(h5, db, error)
    type(h5_reader_type), intent(inout) :: h5
    type(bem_database_type), intent(inout) :: db
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: order(:), a(:), b(:), c(:)
    integer, allocatable :: dims(:)
    integer :: i, j, n, nmax, k
    call read_shaped(h5, "davit_ss_order", [6, 6], order, dims, error)
    if (allocated(error)) return
    call h5%read_array("davit_ss_a", a, dims, error)
    if (allocated(error)) return
    nmax = 0
    if (size(dims) == 4) nmax = dims(1)
    ! orders are whole numbers 0 .. n (written so that a NaN fails too)
    if (size(dims) /= 4 .or. any(dims /= [nmax, nmax, 6, 6]) .or. &
        .not. all(order >= 0.0_wp .and. order <= real(nmax, wp) .and. &
                  order == aint(order))) then
      call fatal_error(error, "'"//db%path//"': davit_ss_a must be (6, 6, n, n) with "// &
                       "n >= every davit_ss_order (whole numbers >= 0)")
      return
    end if
    call read_shaped(h5, "davit_ss_b", [nmax, 6, 6], b, dims, error)
    if (allocated(error)) return
    call read_shaped(h5, "davit_ss_c", [nmax, 6, 6], c, dims, error)
    if (allocated(error)) return
    allocate (db%pairs(count(order > 0.0_wp)))
    k = 0
    db%nrad = 0
    ! numpy (i, j, r, c) is Fortran (c, r, j, i); order (i, j) is Fortran (j, i)
    do i = 1, 6
      do j = 1, 6
        n = nint(order(j + 6*(i - 1)))
        if (n == 0) cycle
        k = k + 1
        db%pairs(k) = new_pair(i, j, n, db%nrad + 1, &
                               reshape(a(1 + nmax*nmax*(j - 1 + 6*(i - 1)):), [nmax, nmax]), &
                               b(1 + nmax*(j - 1 + 6*(i - 1)):), c(1 + nmax*(j - 1 + 6*(i - 1)):))
        db%nrad = db%nrad + n
      end do
    end do
  end subroutine read_radiation

  !> The mean drift coefficients davit_drift, numpy (omega, beta, 3), if the file has them.
  subroutine read_drift(h5, db, error)
    type(h5_reader_type), intent(inout) :: h5
    type(bem_database_type), intent(inout) :: db
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:)
    integer, allocatable :: dims(:)
    if (.not. h5%has_dataset("davit_drift")) return
    call read_shaped(h5, "davit_drift", [3, size(db%heading), size(db%omega)], x, dims, error)
    if (allocated(error)) return
    if (.not. all(abs(x) < huge(1.0_wp))) then
      call fatal_error(error, "'"//h5%path//"': davit_drift holds a NaN or infinite value")
      return
    end if
    db%drift = reshape(x, [3, size(db%heading), size(db%omega)])
    db%has_drift = .true.
  end subroutine read_drift

  !> Pair (i, j) of order n from its zero-padded blocks (a_t: the transposed n x n block).
  pure function new_pair(i, j, n, first, a_t, b, c) result(p)
    integer, intent(in) :: i, j, n, first
    real(wp), intent(in) :: a_t(:, :), b(:), c(:)
    type(radiation_pair_type) :: p
    p%i = i
    p%j = j
    p%n = n
    p%first = first
    p%a = transpose(a_t(1:n, 1:n))
    p%b = b(1:n)
    p%c = c(1:n)
  end function new_pair

  !> Read `name` and check its extents (Fortran order).
  subroutine read_shaped(h5, name, expected, x, dims, error)
    type(h5_reader_type), intent(inout) :: h5
    character(len=*), intent(in) :: name
    integer, intent(in) :: expected(:)
    real(wp), allocatable, intent(out) :: x(:)
    integer, allocatable, intent(out) :: dims(:)
    type(error_type), allocatable, intent(out) :: error
    call h5%read_array(name, x, dims, error)
    if (allocated(error)) return
    if (size(dims) /= size(expected)) then
      call fatal_error(error, "'"//h5%path//"': "//name//" has the wrong rank")
    else if (any(dims /= expected)) then
      call fatal_error(error, "'"//h5%path//"': "//name//" has the wrong shape")
    end if
  end subroutine read_shaped

  !> Each omega's 6 x 6 matrix transposed.
  pure function transposed(m) result(t)
    real(wp), intent(in) :: m(:, :, :)
    real(wp) :: t(size(m, 2), size(m, 1), size(m, 3))
    integer :: k
    do k = 1, size(m, 3)
      t(:, :, k) = transpose(m(:, :, k))
    end do
  end function transposed

  !> The wave load per unit amplitude X(omega, beta) [complex, N/m, N m/m], linear in
  !> omega and in beta (headings wrap at 2 pi). Below the lowest frequency the lowest
  !> one's (the long-wave limit is reached there); above the highest, none: waves that
  !> short do not move a ship this size, and the database says nothing about them. With
  !> diffraction_only, X minus its Froude-Krylov part.
  pure function bem_excitation(db, omega, beta, diffraction_only) result(x)
    !> The database.
    type(bem_database_type), intent(in) :: db
    !> Wave frequency omega [rad/s] and relative heading beta [rad] (wave direction minus
    !> the ship's heading; any value, wrapped to the database's range).
    real(wp), intent(in) :: omega, beta
    !> Take X - X_FK, the diffraction part alone (default: the whole X).
    logical, intent(in), optional :: diffraction_only
    complex(wp) :: x(6)
    logical :: diffraction
    real(wp) :: b, sw, sb
    integer :: iw, ib
    x = (0.0_wp, 0.0_wp)
    if (omega > db%omega(size(db%omega))) return
    diffraction = .false.
    if (present(diffraction_only)) diffraction = diffraction_only
    b = modulo(beta - db%heading(1), 2.0_wp*pi) + db%heading(1)
    call bracket(db%omega, omega, iw, sw)
    call bracket(db%heading, b, ib, sb)
    x = (1.0_wp - sw)*((1.0_wp - sb)*load(iw, ib) + sb*load(iw, ib + 1)) + &
        sw*((1.0_wp - sb)*load(iw + 1, ib) + sb*load(iw + 1, ib + 1))
  contains
    pure function load(kw, kb) result(z)
      integer, intent(in) :: kw, kb
      complex(wp) :: z(6)
      z = cmplx(db%exc_re(:, kb, kw), db%exc_im(:, kb, kw), wp)
      if (diffraction) z = z - cmplx(db%fk_re(:, kb, kw), db%fk_im(:, kb, kw), wp)
    end function load
  end function bem_excitation

  !> The mean drift load per unit amplitude squared D(omega, beta) (surge, sway, yaw; heading
  !> frame), linear in omega and beta, clamped at both ends of the frequency grid: in long
  !> waves it vanishes (the lowest frequency's is ~0), in short ones it tends to the
  !> reflection limit 1/2 rho g times the lit waterline's projection, not to zero.
  pure function bem_drift(db, omega, beta) result(d)
    !> The database (with has_drift set).
    type(bem_database_type), intent(in) :: db
    !> Wave frequency omega [rad/s] and relative heading beta [rad] (wave direction minus
    !> the ship's heading, wrapped to the database's range).
    real(wp), intent(in) :: omega, beta
    real(wp) :: d(3)
    real(wp) :: b, sw, sb
    integer :: iw, ib
    b = modulo(beta - db%heading(1), 2.0_wp*pi) + db%heading(1)
    call bracket(db%omega, omega, iw, sw)
    call bracket(db%heading, b, ib, sb)
    d = (1.0_wp - sw)*((1.0_wp - sb)*db%drift(:, ib, iw) + sb*db%drift(:, ib + 1, iw)) + &
        sw*((1.0_wp - sb)*db%drift(:, ib, iw + 1) + sb*db%drift(:, ib + 1, iw + 1))
  end function bem_drift

  !> Interval [x(i), x(i+1)] holding v (clamped at the ends) and the weight of x(i+1).
  pure subroutine bracket(x, v, i, s)
    !> Ascending grid x (at least 2 points) and the value v to place in it.
    real(wp), intent(in) :: x(:), v
    !> Index of the interval's left end (1 .. size(x) - 1).
    integer, intent(out) :: i
    !> Weight of x(i+1) in the linear interpolation, clamped to 0..1.
    real(wp), intent(out) :: s
    integer :: j, m
    ! bisection for the last i <= n - 1 with x(i) < v (1 where there is none): a sea of
    ! 1300 components places each of them on the grids at every heading refresh
    i = 1
    j = size(x) - 1
    do while (i < j)
      m = (i + j + 1)/2
      if (v > x(m)) then
        i = m
      else
        j = m - 1
      end if
    end do
    s = min(1.0_wp, max(0.0_wp, (v - x(i))/(x(i + 1) - x(i))))
  end subroutine bracket

end module davit_ship_bem_database
