!> The sea's component sums at one point, as the strips' slow clock samples them
!> (davit_boat_strip_waves): the elevation with its time and space derivatives (and, at
!> the strip centres, its curvature and the slope's rates), and the water velocity with
!> its derivatives in time, space and stretched depth; at one time, or at both ends of a
!> window in one pass (the far end's phases turned from the near end's by angle addition).
!> The sums run in `lanes` partial sums, added at the end: independent lanes vectorise (one
!> sum at a time is bound by the adder's latency).
module davit_boat_strip_sums
  use davit_kinds, only: wp
  use davit_sea_wave_field, only: wave_field_type, wave_chunk, component_phases, advance_phasors
  use davit_core_fastmath, only: fast_sincos
  implicit none
  private
  public :: ne, nv, nep, elevation_sums, elevation_pass, elevation_line, kinematic_sums
  public :: kinematic_pass

  !> Elevation terms: value, d/dt, d/dx, d/dy. Velocity terms: the same and d/dd.
  integer, parameter :: ne = 4, nv = 5
  !> Partial sums per accumulated term (8: one AVX-512 register of doubles), and the
  !> terms of the kinematic sums: ne elevation terms, then 3 x nv velocity terms.
  integer, parameter :: lanes = 8, nk = ne + 3*nv
  !> Elevation terms at the strip centres: ne, then the curvature d2/dx2, d2/dxdy, d2/dy2
  !> (the slope a section's tangent plane takes moves with the strip to first order) and
  !> the slope's rates d2/dxdt, d2/dydt (the slope cubic in time, as the elevation).
  integer, parameter :: nep = ne + 5

contains

  !> Unramped elevation of the linear sea at (x, y, t) and its derivatives (t, x, y).
  pure subroutine elevation_sums(field, t, x, y, e)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s] and horizontal position (inertial) [m].
    real(wp), intent(in) :: t, x, y
    !> Unramped elevation [m] and its derivatives in t, x, y.
    real(wp), intent(out) :: e(ne)
    real(wp) :: none(0), e1(ne, 1)
    call elevation_pass(field, t, x, y, 1, none, none, e1)
    e = e1(:, 1)
  end subroutine elevation_sums

  !> Elevation terms at nt times: t, and with nt = 2 also t + h, whose phases are those
  !> at t turned by w h (rotation factors cr, sr of every component). The sums run in
  !> `lanes` partial sums each, added at the end: independent lanes vectorise (one sum
  !> at a time is bound by the adder's latency).
  pure subroutine elevation_pass(field, t, x, y, nt, cr, sr, e)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s] and horizontal position (inertial) [m].
    real(wp), intent(in) :: t, x, y
    !> Number of times: 1 (t) or 2 (t and t + h).
    integer, intent(in) :: nt
    !> With nt = 2: cos(w h) and sin(w h) of every component.
    real(wp), intent(in) :: cr(:), sr(:)
    !> Unramped elevation terms (term, time): ne terms, or nep with the curvature and the
    !> slope's rates.
    real(wp), intent(out) :: e(:, :)
    real(wp) :: s(wave_chunk), cs(wave_chunk), acc(lanes, nep, nt)
    integer :: i0, m, q, j
    acc = 0.0_wp
    do i0 = 1, field%n, wave_chunk
      m = min(wave_chunk, field%n - i0 + 1)
      call component_phases(field, i0, m, t, x, y, s, cs)
      do j = 1, nt
        if (j == 2) call advance_phasors(cs(1:m), s(1:m), cr(i0:i0 + m - 1), &
                                         sr(i0:i0 + m - 1))
        if (size(e, 1) > ne) then
          call add_curvature(field, i0, m, s, cs, acc(:, :, j))
        else
          call add_elevation(field, i0, m, s, cs, acc(:, 1:ne, j))
        end if
      end do
    end do
    do j = 1, nt
      do q = 1, size(e, 1)
        e(q, j) = sum(acc(:, q, j))
      end do
    end do
  end subroutine elevation_pass

  !> Elevation terms with the curvature and the slope's rates (nep) at t and t + h at points
  !> evenly spaced on a line, (x, y) + (j - 1) (dx, dy), j = 1.. size(e, 3) (the strip
  !> centres): each point's phases are the last one's turned by -k . (dx, dy) (angle
  !> addition: one sine and cosine per component for the line, not one per point).
  pure subroutine elevation_line(field, t, x, y, dx, dy, cr, sr, e)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s], the first point and the step between points (inertial) [m].
    real(wp), intent(in) :: t, x, y, dx, dy
    !> cos(w h) and sin(w h) of every component.
    real(wp), intent(in) :: cr(:), sr(:)
    !> Unramped elevation terms (term, time, point).
    real(wp), intent(out) :: e(:, :, :)
    real(wp) :: s(wave_chunk), cs(wave_chunk), s2(wave_chunk), c2(wave_chunk)
    real(wp) :: sd(wave_chunk), cd(wave_chunk), acc(lanes, nep, 2, size(e, 3))
    integer :: i0, i1, m, q, j, k
    acc = 0.0_wp
    do i0 = 1, field%n, wave_chunk
      m = min(wave_chunk, field%n - i0 + 1)
      i1 = i0 + m - 1
      call component_phases(field, i0, m, t, x, y, s, cs)
      s2(1:m) = -(field%kx(i0:i1)*dx + field%ky(i0:i1)*dy)
      call fast_sincos(s2(1:m), sd(1:m), cd(1:m))
      do k = 1, size(e, 3)
        if (k > 1) call advance_phasors(cs(1:m), s(1:m), cd(1:m), sd(1:m))
        call add_curvature(field, i0, m, s, cs, acc(:, :, 1, k))
        c2(1:m) = cs(1:m)
        s2(1:m) = s(1:m)
        call advance_phasors(c2(1:m), s2(1:m), cr(i0:i1), sr(i0:i1))
        call add_curvature(field, i0, m, s2, c2, acc(:, :, 2, k))
      end do
    end do
    do k = 1, size(e, 3)
      do j = 1, 2
        do q = 1, nep
          e(q, j, k) = sum(acc(:, q, j, k))
        end do
      end do
    end do
  end subroutine elevation_line

  !> Add components i0.. i0 + m - 1 (phases' sines s and cosines cs) to the lanes' partial
  !> sums of the elevation terms.
  pure subroutine add_elevation(field, i0, m, s, cs, acc)
    type(wave_field_type), intent(in) :: field
    integer, intent(in) :: i0, m
    real(wp), intent(in) :: s(:), cs(:)
    real(wp), intent(inout) :: acc(lanes, ne)
    real(wp) :: as
    integer :: i, j, l, b
    do b = 0, m - 1, lanes
      do l = 1, min(lanes, m - b)
        j = b + l
        i = i0 + j - 1
        as = field%amplitude(i)*s(j)
        acc(l, 1) = acc(l, 1) + field%amplitude(i)*cs(j)
        acc(l, 2) = acc(l, 2) - as*field%omega(i)
        acc(l, 3) = acc(l, 3) + as*field%kx(i)
        acc(l, 4) = acc(l, 4) + as*field%ky(i)
      end do
    end do
  end subroutine add_elevation

  !> Add components i0.. i0 + m - 1 (phases' sines s and cosines cs) to the lanes' partial
  !> sums of the elevation terms (as add_elevation, in one loop) and of the elevation's
  !> curvature: d2/dx2 = -a kx^2 cos theta, d2/dxdy = -a kx ky cos theta,
  !> d2/dy2 = -a ky^2 cos theta, and the slope's rates d2/dxdt = a w kx cos theta,
  !> d2/dydt = a w ky cos theta.
  pure subroutine add_curvature(field, i0, m, s, cs, acc)
    type(wave_field_type), intent(in) :: field
    integer, intent(in) :: i0, m
    real(wp), intent(in) :: s(:), cs(:)
    real(wp), intent(inout) :: acc(lanes, nep)
    real(wp) :: ac, as, akx, aky
    integer :: i, j, l, b
    do b = 0, m - 1, lanes
      do l = 1, min(lanes, m - b)
        j = b + l
        i = i0 + j - 1
        ac = field%amplitude(i)*cs(j)
        as = field%amplitude(i)*s(j)
        akx = ac*field%kx(i)
        aky = ac*field%ky(i)
        acc(l, 1) = acc(l, 1) + ac
        acc(l, 2) = acc(l, 2) - as*field%omega(i)
        acc(l, 3) = acc(l, 3) + as*field%kx(i)
        acc(l, 4) = acc(l, 4) + as*field%ky(i)
        acc(l, 5) = acc(l, 5) - akx*field%kx(i)
        acc(l, 6) = acc(l, 6) - akx*field%ky(i)
        acc(l, 7) = acc(l, 7) - aky*field%ky(i)
        acc(l, 8) = acc(l, 8) + akx*field%omega(i)
        acc(l, 9) = acc(l, 9) + aky*field%omega(i)
      end do
    end do
  end subroutine add_curvature

  !> Elevation terms as elevation_sums, and the unramped water velocity (inertial, z down)
  !> at (x, y) and stretched depth d with its derivatives (t, x, y, d): per component
  !> v = a w exp(-k d) (cos theta cos g, cos theta sin g, sin theta), with
  !> theta = w t + eps - kx x - ky y: d(cos)/dt = -w sin, d(cos)/dx = kx sin,
  !> d(sin)/dx = -kx cos, d/dd = -k.
  pure subroutine kinematic_sums(field, t, x, y, d, e, v)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s], horizontal position (inertial) [m], stretched depth [m].
    real(wp), intent(in) :: t, x, y, d
    !> Unramped elevation terms (as elevation_sums) and water velocity (inertial, z down)
    !> [m/s] with its derivatives in t, x, y, d.
    real(wp), intent(out) :: e(ne), v(3, nv)
    real(wp) :: none(0)
    call kinematic_pass(field, t, x, y, d, 1, none, none, e, v, .true.)
  end subroutine kinematic_sums

  !> Elevation and velocity terms at nt times as elevation_pass (lanes' partial sums): the
  !> depth decay a w exp(-k d) is formed once for both.
  pure subroutine kinematic_pass(field, t, x, y, d, nt, cr, sr, e, v, with_eta)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s], horizontal position (inertial) [m], stretched depth [m].
    real(wp), intent(in) :: t, x, y, d
    !> Number of times: 1 (t) or 2 (t and t + h).
    integer, intent(in) :: nt
    !> With nt = 2: cos(w h) and sin(w h) of every component.
    real(wp), intent(in) :: cr(:), sr(:)
    !> Unramped elevation terms (zero without with_eta) and velocity terms, per time.
    real(wp), intent(out) :: e(ne, nt), v(3, nv, nt)
    !> Whether to sum the elevation terms too.
    logical, intent(in) :: with_eta
    real(wp) :: s(wave_chunk), cs(wave_chunk), w(wave_chunk), acc(lanes, nk, nt)
    integer :: i0, m, q, j
    acc = 0.0_wp
    do i0 = 1, field%n, wave_chunk
      m = min(wave_chunk, field%n - i0 + 1)
      call component_phases(field, i0, m, t, x, y, s, cs)
      w(1:m) = field%amplitude(i0:i0 + m - 1)*field%omega(i0:i0 + m - 1)* &
               exp(-field%k(i0:i0 + m - 1)*d)
      call add_kinematics(field, i0, m, s, cs, w, with_eta, acc(:, :, 1))
      if (nt < 2) cycle
      call advance_phasors(cs(1:m), s(1:m), cr(i0:i0 + m - 1), sr(i0:i0 + m - 1))
      call add_kinematics(field, i0, m, s, cs, w, with_eta, acc(:, :, 2))
    end do
    do j = 1, nt
      do q = 1, ne
        e(q, j) = sum(acc(:, q, j))
      end do
      do q = 1, 3*nv
        v(mod(q - 1, 3) + 1, (q - 1)/3 + 1, j) = sum(acc(:, ne + q, j))
      end do
    end do
  end subroutine kinematic_pass

  !> Add components i0.. i0 + m - 1 (phases' sines s and cosines cs, decayed amplitudes
  !> w = a w exp(-k d)) to the lanes' partial sums: the elevation terms (with_eta; the
  !> window takes the elevation from the strip centres'), then the velocity terms
  !> v(1:3, 1:nv) in column order.
  pure subroutine add_kinematics(field, i0, m, s, cs, w, with_eta, acc)
    type(wave_field_type), intent(in) :: field
    integer, intent(in) :: i0, m
    real(wp), intent(in) :: s(:), cs(:), w(:)
    logical, intent(in) :: with_eta
    real(wp), intent(inout) :: acc(lanes, nk)
    real(wp) :: wc, ws, wcg, wsg, wsc, wss
    integer :: i, j, l, b
    if (with_eta) call add_elevation(field, i0, m, s, cs, acc(:, 1:ne))
    do b = 0, m - 1, lanes
      do l = 1, min(lanes, m - b)
        j = b + l
        i = i0 + j - 1
        wc = w(j)*cs(j)
        ws = w(j)*s(j)
        wcg = wc*field%cos_dir(i)
        wsg = wc*field%sin_dir(i)
        wsc = ws*field%cos_dir(i)
        wss = ws*field%sin_dir(i)
        acc(l, 5) = acc(l, 5) + wcg
        acc(l, 6) = acc(l, 6) + wsg
        acc(l, 7) = acc(l, 7) + ws
        acc(l, 8) = acc(l, 8) - wsc*field%omega(i)
        acc(l, 9) = acc(l, 9) - wss*field%omega(i)
        acc(l, 10) = acc(l, 10) + wc*field%omega(i)
        acc(l, 11) = acc(l, 11) + wsc*field%kx(i)
        acc(l, 12) = acc(l, 12) + wss*field%kx(i)
        acc(l, 13) = acc(l, 13) - wc*field%kx(i)
        acc(l, 14) = acc(l, 14) + wsc*field%ky(i)
        acc(l, 15) = acc(l, 15) + wss*field%ky(i)
        acc(l, 16) = acc(l, 16) - wc*field%ky(i)
        acc(l, 17) = acc(l, 17) - wcg*field%k(i)
        acc(l, 18) = acc(l, 18) - wsg*field%k(i)
        acc(l, 19) = acc(l, 19) - ws*field%k(i)
      end do
    end do
  end subroutine add_kinematics

end module davit_boat_strip_sums
