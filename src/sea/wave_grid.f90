!> The sea's kinematics on a precomputed grid (`&sea kinematics = 'grid'`): the exact
!> component sum of eq. (43) (davit_sea_wave_field) evaluated once per node and time sample
!> and interpolated, so that a query costs the same for 100 or 1300 components.
!>
!> Nodes: an earth-fixed horizontal box of the lattice (i h, j h) around the boat's
!> footprint plus a margin. The free-floating ship drifts (in the Level 5 irregular launch
!> the boat's CG moves 15 m across the waves over 117 s), so the box is placed anew around
!> the footprint when the boat leaves it, keeping the nodes both boxes share; a query
!> outside the box, or at a node not built, gets grid_covers = .false. and the caller
!> takes the exact sum. Nodes are built lazily: only those the footprint's interpolation
!> stencils reach. Optionally, velocity at depth levels d_l = (l - 2) h below the
!> instantaneous surface (the Wheeler-stretched depth of davit_sea_wave_field), l = 1..nl,
!> covering 0 <= d <= depth; one level above the surface and one below the deepest keep
!> the interpolation stencil inside. Time samples at a uniform step dt, held in a block of
!> nt samples that is rebuilt further on when a query asks for a later time (memory
!> bounded whatever the run's length).
!>
!> Building a block: per sample the time phasors a (cos A_i, sin A_i), A_i = w_i t + eps_i,
!> are advanced by rotation (angle addition, no trigonometry in the loop; resynchronised
!> at each block's start), and with B_i = k_i . x_node
!>   eta = sum a (cos A cos B + sin A sin B),  u, v = sum a w e^{-k d} cos(A - B) (cos g, sin g),
!>   w   = sum a w e^{-k d} (sin A cos B - cos A sin B),
!> so a block is one matrix product (rows: field x sample, columns: cos B and sin B of each
!> component; DGEMM), exact at the nodes to rounding.
!>
!> Interpolation: Catmull-Rom cubics in x, y, t (and d): C1, reproduce quadratics, error
!> O(h^3) per component of wavenumber k (O(dt^3) in time, frequency w). The elevation's
!> derivatives (d/dt, d/dx, d/dy) are fields of their own, sampled exactly and
!> interpolated (O(h^3)); the velocity's (d/dt, d/dx, d/dy, d/dd: the slow clock's rates
!> and first-order expansion over centimetres) are those of the interpolant, O(h^2). The
!> test suite checks the orders on one Airy component. Values are unramped (the caller
!> multiplies by wave_ramp, as for the exact sums).
module davit_sea_wave_grid
  use davit_kinds, only: wp, i8
  use davit_core_fastmath, only: fast_sincos
  use davit_sea_wave_field, only: wave_field_type, wave_irregular, time_phasors, &
                                  rotation_phasors, advance_phasors, wave_chunk
  implicit none
  private
  public :: wave_grid_type, new_wave_grid, grid_place, grid_prepare, grid_covers
  public :: grid_elevation, grid_kinematics, catmull_rom, grid_error_bounds

  !> Elevation fields per node: eta and its derivatives (t, x, y), each sampled exactly and
  !> interpolated (O(h^3)) rather than differentiated from the interpolant (O(h^2)): the
  !> slope sets the tangent-plane buoyancy, and the steep short components dominate it.
  integer, parameter :: ne = 4
  !> Nodes built beyond the footprint's stencils on each side.
  integer, parameter :: pad = 0

  type :: wave_grid_type
    !> Grid in use (irregular seas only); nodes placed; water velocity held too.
    logical :: enabled = .false., placed = .false., velocity = .false.
    !> Node spacing [m] (also the depth levels'), time step [s], margin [m], deepest
    !> stretched depth covered [m].
    real(wp) :: h = 1.0_wp, dt = 0.1_wp, margin = 3.0_wp, depth = 3.0_wp
    !> Node (1, 1) at (x0, y0); nx x ny nodes; nl depth levels; nfld fields per node.
    real(wp) :: x0 = 0.0_wp, y0 = 0.0_wp
    !> Nodes nx along N1 and ny along N2, depth levels nl, fields per node nfld.
    integer :: nx = 0, ny = 0, nl = 0, nfld = ne
    !> Samples per block; global index of the block's first sample (time s0 dt); samples held.
    integer :: nb = 16, nt = 0
    !> Global index s0 of the block's first sample (time s0 dt).
    integer(i8) :: s0 = 0
    !> Blocks started, node time series built, placements (for the report).
    integer :: builds = 0, node_builds = 0, placements = 0
    !> Nodes whose spatial phasors are known; nodes built for the block in memory.
    logical, allocatable :: phased(:), ready(:)
    !> Fields (nfld, nt, nx*ny): eta, d eta/dt, d eta/dx, d eta/dy, then (u, v, w) per level.
    real(wp), allocatable :: f(:, :, :)
    !> Spatial phasors (2n, nx*ny): cos(k . x), sin(k . x) of each node.
    real(wp), allocatable :: sp(:, :)
    !> The block's time phasors times each field's factor, (2n, nfld*nt): a node's fields
    !> are sp(:, node) . tp(:, row) (one matrix product for the nodes built together).
    real(wp), allocatable :: tp(:, :)
    !> w_i exp(-k_i d_l), (n, nl).
    real(wp), allocatable :: decay(:, :)
  end type wave_grid_type

  interface
    subroutine dgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
      import :: wp
      !> BLAS transposition flags of a and b ('N' or 'T').
      character, intent(in) :: transa, transb
      !> BLAS sizes: c is m x n, the inner dimension k; the leading dimensions of a, b, c.
      integer, intent(in) :: m, n, k, lda, ldb, ldc
      !> BLAS factors alpha, beta and the operands a, b of c = alpha op(a) op(b) + beta c.
      real(wp), intent(in) :: alpha, beta, a(lda, *), b(ldb, *)
      !> The BLAS product c, overwritten.
      real(wp), intent(inout) :: c(ldc, *)
    end subroutine dgemm
  end interface

contains

  !> A grid of spacing h [m], time step dt [s] and margin [m] around the boat; with
  !> `velocity`, also the water velocity down to `depth` [m]. Enabled for irregular seas.
  pure function new_wave_grid(field, h, dt, margin, depth, velocity) result(g)
    !> The wave field the grid samples.
    type(wave_field_type), intent(in) :: field
    !> Node spacing h [m], time step dt [s], margin around the footprint [m] and deepest
    !> stretched depth of the velocity levels [m].
    real(wp), intent(in) :: h, dt, margin, depth
    !> True to hold the water velocity at depth levels too.
    logical, intent(in) :: velocity
    type(wave_grid_type) :: g
    integer :: l
    g%enabled = field%kind == wave_irregular .and. h > 0.0_wp .and. dt > 0.0_wp
    g%h = h
    g%dt = dt
    g%margin = margin
    g%depth = depth
    g%velocity = velocity
    if (.not. g%enabled) return
    g%nl = 0
    if (velocity) g%nl = ceiling(depth/h - 1.0e-9_wp) + 3
    g%nfld = ne + 3*g%nl
    allocate (g%decay(field%n, g%nl))
    do l = 1, g%nl
      g%decay(:, l) = field%omega*exp(-field%k*real(l - 2, wp)*h)
    end do
  end function new_wave_grid

  !> Place the nodes over the horizontal points xy(2, :) (the boat's footprint) plus the
  !> margin; the spatial phasors of every node.
  pure subroutine grid_place(g, field, xy)
    !> The grid, placed anew (the nodes both boxes share are kept).
    type(wave_grid_type), intent(inout) :: g
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Horizontal points xy(2, :) of the boat's footprint, inertial frame N [m].
    real(wp), intent(in) :: xy(:, :)
    real(wp) :: lo(2), hi(2)
    real(wp), allocatable :: sp(:, :), f(:, :, :)
    logical, allocatable :: phased(:), ready(:)
    integer :: old(4), ix, iy, jx, jy, j, k
    if (.not. g%enabled) return
    lo = minval(xy, dim=2) - g%margin
    hi = maxval(xy, dim=2) + g%margin
    ! nodes on the lattice (i h, j h), so that a box placed anew shares the nodes it
    ! overlaps with the old one (copied, not rebuilt); one ghost node before the first
    ! interval and two after the last (stencil i-1..i+2)
    old = [nint(g%x0/g%h), nint(g%y0/g%h), g%nx, g%ny]
    if (g%placed .or. g%placements > 0) then
      call move_alloc(g%sp, sp)
      call move_alloc(g%phased, phased)
      call move_alloc(g%ready, ready)
      if (allocated(g%f)) call move_alloc(g%f, f)
    end if
    g%x0 = g%h*real(floor(lo(1)/g%h) - 1, wp)
    g%y0 = g%h*real(floor(lo(2)/g%h) - 1, wp)
    g%nx = ceiling(hi(1)/g%h) + 2 - nint(g%x0/g%h)
    g%ny = ceiling(hi(2)/g%h) + 2 - nint(g%y0/g%h)
    allocate (g%sp(2*field%n, g%nx*g%ny), g%phased(g%nx*g%ny), g%ready(g%nx*g%ny))
    g%phased = .false.
    g%ready = .false.
    if (allocated(f)) allocate (g%f(g%nfld, g%nt, g%nx*g%ny))
    if (allocated(sp)) then
      do iy = 1, g%ny
        jy = iy + nint(g%y0/g%h) - old(2)
        if (jy < 1 .or. jy > old(4)) cycle
        do ix = 1, g%nx
          jx = ix + nint(g%x0/g%h) - old(1)
          if (jx < 1 .or. jx > old(3)) cycle
          j = ix + g%nx*(iy - 1)
          k = jx + old(3)*(jy - 1)
          g%phased(j) = phased(k)
          if (phased(k)) g%sp(:, j) = sp(:, k)
          if (allocated(f)) then
            g%ready(j) = ready(k)
            if (ready(k)) g%f(:, :, j) = f(:, :, k)
          end if
        end do
      end do
    end if
    g%placed = .true.
    g%placements = g%placements + 1
  end subroutine grid_place

  !> Make the grid hold the horizontal points xy(2, :) (the boat's footprint; placed anew
  !> around them when one has left the box) over times [t_lo, t_hi]: a new block from t_lo
  !> on if the one in memory does not cover them, and the time series of every node the
  !> footprint's interpolation stencils (plus one node) reach, built if not yet. Nodes
  !> are built lazily: only those near the boat cost anything.
  subroutine grid_prepare(g, field, t_lo, t_hi, xy)
    !> The grid, made to hold the points and times.
    type(wave_grid_type), intent(inout) :: g
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Times [t_lo, t_hi] [s] and horizontal points xy(2, :) of the boat's footprint,
    !> inertial frame N [m].
    real(wp), intent(in) :: t_lo, t_hi, xy(:, :)
    integer :: need, j, i0(2), i1(2), ix, iy, m
    integer, allocatable :: list(:)
    if (.not. g%enabled) return
    if (g%placed) then
      do j = 1, size(xy, 2)
        if (.not. space_inside(g, xy(1, j), xy(2, j))) g%placed = .false.
      end do
    end if
    if (.not. g%placed) call grid_place(g, field, xy)
    if (.not. (time_inside(g, t_lo) .and. time_inside(g, t_hi))) then
      need = ceiling((t_hi - t_lo)/g%dt) + 4
      g%nt = max(g%nb, need)
      g%s0 = floor(t_lo/g%dt, kind=i8) - 1
      if (allocated(g%f)) then
        if (size(g%f, 2) /= g%nt .or. size(g%f, 3) /= g%nx*g%ny) deallocate (g%f)
      end if
      if (.not. allocated(g%f)) allocate (g%f(g%nfld, g%nt, g%nx*g%ny))
      call block_phasors(g, field)
      g%ready = .false.
      g%builds = g%builds + 1
    end if
    ! stencils of the footprint's box: nodes int(s) - 1 .. int(s) + 2 (0-based), and `pad`
    ! more on each side (fewer, larger matrix products as the boat moves)
    i0(1) = max(0, int((minval(xy(1, :)) - g%x0)/g%h) - 1 - pad)
    i1(1) = min(g%nx - 1, int((maxval(xy(1, :)) - g%x0)/g%h) + 2 + pad)
    i0(2) = max(0, int((minval(xy(2, :)) - g%y0)/g%h) - 1 - pad)
    i1(2) = min(g%ny - 1, int((maxval(xy(2, :)) - g%y0)/g%h) + 2 + pad)
    allocate (list((i1(1) - i0(1) + 1)*(i1(2) - i0(2) + 1)))
    m = 0
    do iy = i0(2), i1(2)
      do ix = i0(1), i1(1)
        j = ix + 1 + g%nx*iy
        if (g%ready(j)) cycle
        m = m + 1
        list(m) = j
      end do
    end do
    if (m > 0) call build_nodes(g, field, list(1:m))
  end subroutine grid_prepare

  !> The block's time phasors, each field's factor applied: per sample a (cos A_i, sin A_i)
  !> advanced by rotation (no trigonometry in the loop, resynchronised at the block's
  !> start). a cos(A - B) = (a cos A) cos B + (a sin A) sin B and a sin(A - B) = (a sin A)
  !> cos B - (a cos A) sin B: rows 1..n multiply cos B, n+1..2n sin B.
  subroutine block_phasors(g, field)
    !> The grid, its time phasors tp filled for the block from sample s0.
    type(wave_grid_type), intent(inout) :: g
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    real(wp), allocatable :: ca(:), sa(:), cr(:), sr(:)
    integer :: n, j, l, r
    n = field%n
    if (allocated(g%tp)) then
      if (size(g%tp, 2) /= g%nfld*g%nt) deallocate (g%tp)
    end if
    if (.not. allocated(g%tp)) allocate (g%tp(2*n, g%nfld*g%nt))
    allocate (ca(n), sa(n), cr(n), sr(n))
    call time_phasors(field, real(g%s0, wp)*g%dt, ca, sa)
    call rotation_phasors(field, g%dt, cr, sr)
    do j = 1, g%nt
      r = g%nfld*(j - 1)
      g%tp(1:n, r + 1) = ca
      g%tp(n + 1:2*n, r + 1) = sa
      g%tp(1:n, r + 2) = -field%omega*sa
      g%tp(n + 1:2*n, r + 2) = field%omega*ca
      g%tp(1:n, r + 3) = field%kx*sa
      g%tp(n + 1:2*n, r + 3) = -field%kx*ca
      g%tp(1:n, r + 4) = field%ky*sa
      g%tp(n + 1:2*n, r + 4) = -field%ky*ca
      do l = 1, g%nl
        associate (e => g%decay(:, l), q => r + ne + 3*(l - 1))
          g%tp(1:n, q + 1) = ca*e*field%cos_dir
          g%tp(n + 1:2*n, q + 1) = sa*e*field%cos_dir
          g%tp(1:n, q + 2) = ca*e*field%sin_dir
          g%tp(n + 1:2*n, q + 2) = sa*e*field%sin_dir
          g%tp(1:n, q + 3) = sa*e
          g%tp(n + 1:2*n, q + 3) = -ca*e
        end associate
      end do
      call advance_phasors(ca, sa, cr, sr)
    end do
  end subroutine block_phasors

  !> The block's time series of the nodes in `list` (their spatial phasors first, if not
  !> yet): one matrix product, (fields x samples) x nodes.
  subroutine build_nodes(g, field, list)
    !> The grid, the nodes' time series filled.
    type(wave_grid_type), intent(inout) :: g
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Node indices (ix + nx (iy - 1)) to build.
    integer, intent(in) :: list(:)
    real(wp), allocatable :: spc(:, :), out(:, :)
    integer :: m, c, rows_all
    m = size(list)
    do c = 1, m
      if (.not. g%phased(list(c))) call node_phasors(g, field, list(c))
    end do
    rows_all = g%nfld*g%nt
    allocate (spc(2*field%n, m), out(rows_all, m))
    spc = g%sp(:, list)
    call dgemm("T", "N", rows_all, m, 2*field%n, 1.0_wp, g%tp, 2*field%n, spc, 2*field%n, &
               0.0_wp, out, rows_all)
    do c = 1, m
      g%f(:, :, list(c)) = reshape(out(:, c), [g%nfld, g%nt])
    end do
    g%ready(list) = .true.
    g%node_builds = g%node_builds + m
  end subroutine build_nodes

  !> cos(k . x), sin(k . x) of node j.
  pure subroutine node_phasors(g, field, j)
    !> The grid, node j's spatial phasors filled.
    type(wave_grid_type), intent(inout) :: g
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Node index (ix + nx (iy - 1)).
    integer, intent(in) :: j
    real(wp) :: x, y, b(wave_chunk), sn(wave_chunk), cs(wave_chunk)
    integer :: i0, m
    x = g%x0 + real(mod(j - 1, g%nx), wp)*g%h
    y = g%y0 + real((j - 1)/g%nx, wp)*g%h
    do i0 = 1, field%n, wave_chunk
      m = min(wave_chunk, field%n - i0 + 1)
      b(1:m) = field%kx(i0:i0 + m - 1)*x + field%ky(i0:i0 + m - 1)*y
      call fast_sincos(b(1:m), sn(1:m), cs(1:m))
      g%sp(i0:i0 + m - 1, j) = cs(1:m)
      g%sp(field%n + i0:field%n + i0 + m - 1, j) = sn(1:m)
    end do
    g%phased(j) = .true.
  end subroutine node_phasors

  !> True when time t can be interpolated from the block in memory.
  pure logical function time_inside(g, t)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> Time [s].
    real(wp), intent(in) :: t
    real(wp) :: s
    time_inside = .false.
    if (g%nt == 0) return
    s = t/g%dt - real(g%s0, wp)
    time_inside = s >= 1.0_wp .and. s <= real(g%nt - 2, wp)
  end function time_inside

  !> True when the nodes hold (x, y) (the interpolation stencil inside the box).
  pure logical function space_inside(g, x, y)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> Horizontal position x, y in the inertial frame N [m].
    real(wp), intent(in) :: x, y
    real(wp) :: sx, sy
    sx = (x - g%x0)/g%h
    sy = (y - g%y0)/g%h
    space_inside = g%nx > 0 .and. sx >= 1.0_wp .and. sx <= real(g%nx - 2, wp) .and. &
                   sy >= 1.0_wp .and. sy <= real(g%ny - 2, wp)
  end function space_inside

  !> True when the 4 x 4 nodes of the stencil at (x, y) are built.
  pure logical function stencil_ready(g, x, y)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> Horizontal position x, y in the inertial frame N [m].
    real(wp), intent(in) :: x, y
    integer :: ix, iy, b
    ix = min(int((x - g%x0)/g%h), g%nx - 3)
    iy = min(int((y - g%y0)/g%h), g%ny - 3)
    stencil_ready = .true.
    do b = 0, 3
      stencil_ready = stencil_ready .and. all(g%ready(ix + g%nx*(iy + b - 1):ix + 3 + &
                                                                   g%nx*(iy + b - 1)))
    end do
  end function stencil_ready

  !> True when the grid holds (t, x, y) (and depth d, with velocity).
  pure logical function grid_covers(g, t, x, y, d)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> Time t [s] and horizontal position x, y in the inertial frame N [m].
    real(wp), intent(in) :: t, x, y
    !> Stretched depth below the instantaneous surface [m], for a velocity query.
    real(wp), intent(in), optional :: d
    grid_covers = .false.
    if (.not. (g%enabled .and. g%placed)) return
    if (.not. time_inside(g, t)) return
    if (.not. space_inside(g, x, y)) return
    if (.not. stencil_ready(g, x, y)) return
    if (present(d)) then
      if (.not. g%velocity) return
      if (d < 0.0_wp .or. d > real(g%nl - 3, wp)*g%h) return
    end if
    grid_covers = .true.
  end function grid_covers

  !> Bounds of the interpolation error of the elevation [m] and of its slope [-], for the
  !> surface watch's proof of dryness. One dimension, a cos(k x) sampled at spacing h:
  !> error <= a E(k h), E(z) = min(0.034 z^3, 2.25) (maximum over phase and position,
  !> z <= 3; 2.25 = 1 + the weights' largest sum of magnitudes 1.25). The tensor product
  !> in x, y, t compounds them with the factor 1.25 per dimension (1.5625 for three); the
  !> slope is a field of its own (a k sin), so its bound carries a factor k.
  pure function grid_error_bounds(g, field) result(b)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> The wave field the grid samples.
    type(wave_field_type), intent(in) :: field
    real(wp) :: b(2)
    real(wp) :: ex, ey, et
    integer :: i
    b = 0.0_wp
    if (.not. g%enabled) return
    do i = 1, field%n
      ex = cubic_error(abs(field%kx(i))*g%h)
      ey = cubic_error(abs(field%ky(i))*g%h)
      et = cubic_error(field%omega(i)*g%dt)
      b(1) = b(1) + abs(field%amplitude(i))*1.5625_wp*(ex + ey + et)
      b(2) = b(2) + abs(field%amplitude(i))*field%k(i)*1.5625_wp*(ex + ey + et)
    end do
  end function grid_error_bounds

  pure real(wp) function cubic_error(z)
    !> Product k h (or w dt) of a component's wave number and the sampling step.
    real(wp), intent(in) :: z
    cubic_error = min(0.034_wp*z**3, 2.25_wp)
  end function cubic_error

  !> Catmull-Rom weights of the stencil i-1..i+2 at fraction u of interval [i, i+1], and
  !> their derivatives d/du.
  pure subroutine catmull_rom(u, w, dw)
    !> Fraction u in [0, 1] of the interval [i, i+1].
    real(wp), intent(in) :: u
    !> Weights w of nodes i-1..i+2 and their derivatives dw = d w/du.
    real(wp), intent(out) :: w(4), dw(4)
    real(wp) :: u2, u3
    u2 = u*u
    u3 = u2*u
    w = 0.5_wp*[-u3 + 2.0_wp*u2 - u, 3.0_wp*u3 - 5.0_wp*u2 + 2.0_wp, &
                -3.0_wp*u3 + 4.0_wp*u2 + u, u3 - u2]
    dw = 0.5_wp*[-3.0_wp*u2 + 4.0_wp*u - 1.0_wp, 9.0_wp*u2 - 10.0_wp*u, &
                 -9.0_wp*u2 + 8.0_wp*u + 1.0_wp, 3.0_wp*u2 - 2.0_wp*u]
  end subroutine catmull_rom

  !> Stencil start (1-based index of node i-1) and weights for coordinate s (0-based
  !> position in node units) on n nodes; s in [1, n - 2].
  pure subroutine stencil(s, n, i1, w, dw)
    !> Coordinate s, 0-based position in node units.
    real(wp), intent(in) :: s
    !> Number of nodes.
    integer, intent(in) :: n
    !> Stencil start, the 1-based index of node i-1.
    integer, intent(out) :: i1
    !> Weights w of the stencil's nodes and their derivatives dw = d w/ds.
    real(wp), intent(out) :: w(4), dw(4)
    integer :: i
    i = min(int(s), n - 3)
    call catmull_rom(s - real(i, wp), w, dw)
    i1 = i
  end subroutine stencil

  !> Unramped elevation terms at (x, y, t), as elevation_sums gives them: e = (eta,
  !> d eta/dt, d eta/dx, d eta/dy). The caller checks grid_covers first.
  pure subroutine grid_elevation(g, t, x, y, e)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> Time t [s] and horizontal position x, y in the inertial frame N [m].
    real(wp), intent(in) :: t, x, y
    !> Unramped (eta [m], d eta/dt [m/s], d eta/dx, d eta/dy [-]).
    real(wp), intent(out) :: e(4)
    real(wp) :: wx(4), dwx(4), wy(4), dwy(4), wt(4), dwt(4)
    integer :: ix, iy, it, a, b, node
    call stencil((x - g%x0)/g%h, g%nx, ix, wx, dwx)
    call stencil((y - g%y0)/g%h, g%ny, iy, wy, dwy)
    call stencil(t/g%dt - real(g%s0, wp), g%nt, it, wt, dwt)
    e = 0.0_wp
    do b = 1, 4
      do a = 1, 4
        node = ix + a - 1 + g%nx*(iy + b - 2)
        e = e + wx(a)*wy(b)*matmul(g%f(1:ne, it:it + 3, node), wt)
      end do
    end do
  end subroutine grid_elevation

  !> Unramped elevation terms e and water velocity (inertial, z down) at (x, y), stretched
  !> depth d and time t with its derivatives, as kinematic_sums gives them: v(:, 1) value,
  !> v(:, 2:5) d/dt, d/dx, d/dy, d/dd. The caller checks grid_covers(..., d) first.
  pure subroutine grid_kinematics(g, t, x, y, d, e, v)
    !> The grid.
    type(wave_grid_type), intent(in) :: g
    !> Time t [s], horizontal position x, y in the inertial frame N [m] and stretched
    !> depth d below the instantaneous surface [m].
    real(wp), intent(in) :: t, x, y, d
    !> Unramped elevation terms e (as grid_elevation) and water velocity v [m/s]
    !> (inertial, z down): v(:, 1) value, v(:, 2:5) d/dt, d/dx, d/dy, d/dd.
    real(wp), intent(out) :: e(4), v(3, 5)
    real(wp) :: wx(4), dwx(4), wy(4), dwy(4), wt(4), dwt(4), wd(4), dwd(4)
    real(wp) :: q(3, 4), qt(3, 4), val(3), dep(3), wab
    integer :: ix, iy, it, id, a, b, node, l, c, fl
    call grid_elevation(g, t, x, y, e)
    call stencil((x - g%x0)/g%h, g%nx, ix, wx, dwx)
    call stencil((y - g%y0)/g%h, g%ny, iy, wy, dwy)
    call stencil(t/g%dt - real(g%s0, wp), g%nt, it, wt, dwt)
    call stencil((d + g%h)/g%h, g%nl, id, wd, dwd)
    v = 0.0_wp
    do b = 1, 4
      do a = 1, 4
        node = ix + a - 1 + g%nx*(iy + b - 2)
        do l = 1, 4
          do c = 1, 3
            fl = ne + 3*(id + l - 2) + c
            q(c, l) = sum(wt*g%f(fl, it:it + 3, node))
            qt(c, l) = sum(dwt*g%f(fl, it:it + 3, node))
          end do
        end do
        val = matmul(q, wd)
        dep = matmul(q, dwd)
        wab = wx(a)*wy(b)
        v(:, 1) = v(:, 1) + wab*val
        v(:, 2) = v(:, 2) + wab*matmul(qt, wd)
        v(:, 3) = v(:, 3) + dwx(a)*wy(b)*val
        v(:, 4) = v(:, 4) + wx(a)*dwy(b)*val
        v(:, 5) = v(:, 5) + wab*dep
      end do
    end do
    v(:, 2) = v(:, 2)/g%dt
    v(:, 3:5) = v(:, 3:5)/g%h
  end subroutine grid_kinematics

end module davit_sea_wave_grid
