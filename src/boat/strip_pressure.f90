!> Wave pressure on the strips' sections (issue 18: pressure-averaged Froude-Krylov loads).
!>
!> The pressure of the linear sea with Wheeler stretching (davit_sea_wave_field) is, z down,
!>   p = rho g (z + sum_i a_i exp(-k_i d) cos theta_i),   d = z + eta   (depth below the surface).
!> Across one section (a few metres) the surface is replaced by its tangent plane at the
!> strip centre, eta_pl = eta_c + grad(eta) . dx, and p is split into
!>   p = rho g d_pl + p',   d_pl = z + eta_pl,
!>   p' = rho g sum_i a_i [exp(-k_i d_pl) cos theta_i - cos theta_ic - sin theta_ic k_i . dx],
!> (the bracket's last two terms are component i's share of eta_pl). The first part is
!> linear over the section and vanishes on the wet polygon's waterline, so its load is
!> exactly -rho g V_k grad(d_pl) at the wet centroid (the buoyancy of the part below the
!> tangent plane, which is what makes the restoring follow the local surface; in calm water
!> it is the exact gradient of rho g int z dV, hence conservative). p' is what the tangent
!> plane misses: the decay with depth (Smith effect) and the phase varying across the
!> breadth. It is zero in calm water and integrated here exactly, per component, along each
!> wet hull edge of the section (bottom and sides), where d_pl and theta are linear in the
!> edge parameter s in [0, 1]:
!>   int_0^1 exp(z s) ds = (e^z - 1)/z,   int_0^1 s exp(z s) ds = e^z/z - (e^z - 1)/z^2,
!> z = -k (d_B - d_A) - i (phi_B - phi_A), phi the phase lag k . dx of the edge's ends. The
!> result is the section-plane force (b2, b3) and the moment about b1 through G, per unit
!> ramp, with its time derivative at fixed geometry (for the slow clock's Hermite cubic).
module davit_boat_strip_pressure
  use davit_kinds, only: wp, gravity, rho_water
  use davit_core_fastmath, only: fast_sincos
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_stokes2, wave_ramp, &
                                  wave_chunk
  use davit_boat_hull, only: boat_hull_type, section_wet_type
  implicit none
  private
  public :: surface_plane, section_wave_load, section_wave_loads

  !> Below this |z| the edge integrals use their power series (cancellation above ~eps/|z|^2).
  real(wp), parameter :: series_limit = 0.5_wp
  integer, parameter :: series_terms = 14
  integer :: n_
  !> 1/n, 1/(n + 1), 1/(n + 2), 1/(n + 3) for n = 1 .. series_terms: the series multiplies by
  !> them (a division per term would dominate the vectorised block).
  real(wp), parameter :: inv_n(series_terms) = [(1.0_wp/real(n_, wp), n_ = 1, series_terms)]
  real(wp), parameter :: inv_n1(series_terms) = [(1.0_wp/real(n_ + 1, wp), n_ = 1, series_terms)]
  real(wp), parameter :: inv_n2(series_terms) = [(1.0_wp/real(n_ + 2, wp), n_ = 1, series_terms)]
  !> Vector lanes of the sensitivities' partial sums (8 doubles: one AVX-512 register).
  integer, parameter :: sens_lanes = 8
  real(wp), parameter :: inv_n3(series_terms) = [(1.0_wp/real(n_ + 3, wp), n_ = 1, series_terms)]

contains

  !> Elevation eta [m] (up, ramped) at (x, y) and its horizontal gradient (d/dx, d/dy):
  !> grad of a cos(theta) is a sin(theta) (kx, ky); the Stokes-2 term (k a^2/2) cos(2 theta)
  !> adds k a^2 sin(2 theta) (kx, ky) (r^2 with the ramp r).
  pure subroutine surface_plane(field, t, x, y, eta, grad)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s] and horizontal position (inertial) [m].
    real(wp), intent(in) :: t, x, y
    !> Surface elevation [m] (up) and its horizontal gradient.
    real(wp), intent(out) :: eta, grad(2)
    real(wp) :: th(wave_chunk), sn(wave_chunk), cs(wave_chunk), r, s2, th1
    integer :: i0, i1, m
    eta = 0.0_wp
    grad = 0.0_wp
    if (field%kind == wave_none) return
    r = wave_ramp(field, t)
    do i0 = 1, field%n, wave_chunk
      i1 = min(field%n, i0 + wave_chunk - 1)
      m = i1 - i0 + 1
      associate (a => field%amplitude(i0:i1))
        th(1:m) = field%omega(i0:i1)*t + field%phase(i0:i1) - field%kx(i0:i1)*x - &
                  field%ky(i0:i1)*y
        ! one vectorised sine and cosine per component (the watch samples every strip)
        call fast_sincos(th(1:m), sn(1:m), cs(1:m))
        sn(1:m) = a*sn(1:m)
        eta = eta + sum(a*cs(1:m))
        grad(1) = grad(1) + sum(sn(1:m)*field%kx(i0:i1))
        grad(2) = grad(2) + sum(sn(1:m)*field%ky(i0:i1))
      end associate
    end do
    eta = r*eta
    grad = r*grad
    if (field%kind == wave_stokes2) then
      th1 = field%omega(1)*t + field%phase(1) - field%kx(1)*x - field%ky(1)*y
      s2 = field%k(1)*(r*field%amplitude(1))**2
      eta = eta + 0.5_wp*s2*cos(2.0_wp*th1)
      grad = grad + s2*sin(2.0_wp*th1)*[field%kx(1), field%ky(1)]
    end if
  end subroutine surface_plane

  !> Load of p' on the wet hull edges of section k (polygon `wet`, boat rotation c, strip
  !> centre pk inertial, tangent-plane depth d_pl = d0 + gy y + gz z over the section):
  !> load = (F2, F3, M1) in b per unit ramp [N, N, N m] (force on the strip of thickness
  !> t_s; M1 about b1 through G) and rate = d(load)/dt at fixed geometry.
  pure subroutine section_wave_load(field, t, hull, wet, c, pk, d0, gy, gz, load, rate)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> The hull.
    type(boat_hull_type), intent(in) :: hull
    !> The section's wet polygon.
    type(section_wet_type), intent(in) :: wet
    !> Time [s], rotation b -> inertial, section centre (inertial) [m], and the depth d0 [m] with
    !> its slopes gy, gz across the section (d = d0 + gy y + gz z).
    real(wp), intent(in) :: t, c(3, 3), pk(3), d0, gy, gz
    !> Froude-Krylov load on the section per unit length, boat frame [N/m], and its time rate.
    real(wp), intent(out) :: load(3), rate(3)
    real(wp) :: loads(3, 1), rates(3, 1)
    call section_wave_loads(field, [t], hull, wet, c, pk, d0, gy, gz, loads, rates)
    load = loads(:, 1)
    rate = rates(:, 1)
  end subroutine section_wave_load

  !> section_wave_load at several times for one wet geometry: load(:, j) and rate(:, j) at
  !> times(j). Per component only the time phasor q = a exp(i theta) depends on t; the edge
  !> integrals (the exponentials, the trigonometry of the lags, the divisions) are shared
  !> by all times, so the slow clock's two window ends cost little more than one.
  !> Components are processed in blocks of wave_chunk with real arithmetic in loops over
  !> the block (vectorised: exp and fast_sincos have SIMD forms, complex exp and libm
  !> sincos do not), summed per lane and reduced once at the end.
  pure subroutine section_wave_loads(field, times, hull, wet, c, pk, d0, gy, gz, load, rate, &
                                     cr, sr, sens)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Sample times [s].
    real(wp), intent(in) :: times(:)
    !> The hull.
    type(boat_hull_type), intent(in) :: hull
    !> The section's wet polygon.
    type(section_wet_type), intent(in) :: wet
    !> Rotation b -> inertial, section centre (inertial) [m], and the depth d0 [m] with its slopes
    !> gy, gz across the section (d = d0 + gy y + gz z).
    real(wp), intent(in) :: c(3, 3), pk(3), d0, gy, gz
    !> Load per unit length (3, time) [N/m] and its time rate at each sample.
    real(wp), intent(out) :: load(:, :), rate(:, :)
    !> With two times t2 = t1 + h: cos(w h) and sin(w h) of every component, which turn
    !> the phasors of t1 into those of t2 (no second sine and cosine).
    real(wp), intent(in), optional :: cr(:), sr(:)
    !> The load's first derivatives at the first size(sens, 3) samples, (load, parameter,
    !> time), the parameters (d0, x, y, gy, gz, c12, c22, c13, c23): the section's immersion
    !> below the tangent plane (all depths by one step), its horizontal travel (every phase
    !> by -k . dx), the plane's slopes across it (depths by gy y + gz z, and the waterline
    !> moving along the hull's sides) and the horizontal parts of the rotation's columns b2,
    !> b3 (the lags) [N/m per m, or per unit slope or unit entry].
    real(wp), intent(out), optional :: sens(:, :, :)
    real(wp) :: depth(5), dxy(2, 5), geo(5, 5), j(4)
    ! per block: lags and vertex factors f_v = exp(-k d_v) (cos lag_v, -sin lag_v), time
    ! phasors (qr, qi) per time, edge integrals, and the per-lane partial sums
    ! acc(lane, (Re q w0, Re q w1, w Im q w0, w Im q w1), edge, time)
    real(wp) :: lag(wave_chunk, 5), fr(wave_chunk, 5), fi(wave_chunk, 5)
    real(wp) :: sn(wave_chunk), cs(wave_chunk), th(wave_chunk)
    real(wp) :: qr(wave_chunk, size(times)), qi(wave_chunk, size(times))
    real(wp) :: w0r(wave_chunk), w0i(wave_chunk), w1r(wave_chunk), w1i(wave_chunk)
    real(wp) :: acc(wave_chunk, 4, 5, size(times)), accs(sens_lanes, 16, 5, size(times))
    real(wp) :: w2r(wave_chunk), w2i(wave_chunk), accw(sens_lanes, 5, size(times))
    integer :: i0, i1, nc, nt, ns, v, e, m, it, l, l0, ll, lanes
    nt = size(times)
    ns = 0
    if (present(sens)) ns = size(sens, 3)
    load = 0.0_wp
    rate = 0.0_wp
    if (present(sens)) sens = 0.0_wp
    if (field%kind == wave_none .or. wet%m < 3) return
    m = wet%m
    call edge_geometry(hull, wet, geo)
    do v = 1, m
      depth(v) = max(0.0_wp, d0 + gy*wet%poly(1, v) + gz*wet%poly(2, v))
      dxy(:, v) = c(1:2, 2)*wet%poly(1, v) + c(1:2, 3)*wet%poly(2, v)
    end do
    ! only the lanes a block fills are used (a regular sea has one component)
    lanes = min(wave_chunk, field%n)
    acc(1:lanes, :, :, :) = 0.0_wp
    if (present(sens)) accs = 0.0_wp
    if (present(sens)) accw = 0.0_wp
    do i0 = 1, field%n, wave_chunk
      nc = min(wave_chunk, field%n - i0 + 1)
      i1 = i0 + nc - 1
      associate (k => field%k(i0:i1), kx => field%kx(i0:i1), ky => field%ky(i0:i1), &
                 a => field%amplitude(i0:i1), w => field%omega(i0:i1))
        do v = 1, m
          lag(1:nc, v) = kx*dxy(1, v) + ky*dxy(2, v)
          call fast_sincos(lag(1:nc, v), sn(1:nc), cs(1:nc))
          th(1:nc) = exp(-k*depth(v))
          fr(1:nc, v) = th(1:nc)*cs(1:nc)
          fi(1:nc, v) = -th(1:nc)*sn(1:nc)
        end do
        do it = 1, nt
          if (it == 2 .and. present(cr)) then
            ! a (cos, sin)(theta + w h) by angle addition
            qr(1:nc, 2) = qr(1:nc, 1)*cr(i0:i1) - qi(1:nc, 1)*sr(i0:i1)
            qi(1:nc, 2) = qi(1:nc, 1)*cr(i0:i1) + qr(1:nc, 1)*sr(i0:i1)
            cycle
          end if
          th(1:nc) = w*times(it) + field%phase(i0:i1) - kx*pk(1) - ky*pk(2)
          call fast_sincos(th(1:nc), sn(1:nc), cs(1:nc))
          qr(1:nc, it) = a*cs(1:nc)
          qi(1:nc, it) = a*sn(1:nc)
        end do
        do v = 1, m
          if (geo(1, v) == 0.0_wp) cycle
          e = merge(1, v + 1, v == m)
          call edge_integrals(nc, k, depth(e) - depth(v), lag(:, v), lag(:, e), fr(:, v), &
                              fi(:, v), fr(:, e), fi(:, e), w0r, w0i, w1r, w1i, &
                              merge(2, 1, present(sens)), w2r, w2i)
          ! J = Re(q w) and dJ/dt = Re(i omega q w) = -omega Im(q w) (sign at the end)
          do it = 1, nt
            do l = 1, nc
              acc(l, 1, v, it) = acc(l, 1, v, it) + (qr(l, it)*w0r(l) - qi(l, it)*w0i(l))
              acc(l, 2, v, it) = acc(l, 2, v, it) + (qr(l, it)*w1r(l) - qi(l, it)*w1i(l))
              acc(l, 3, v, it) = acc(l, 3, v, it) + w(l)*(qr(l, it)*w0i(l) + qi(l, it)*w0r(l))
              acc(l, 4, v, it) = acc(l, 4, v, it) + w(l)*(qr(l, it)*w1i(l) + qi(l, it)*w1r(l))
            end do
          end do
          if (present(sens)) call add_sensitivities(nc, k, kx, ky, lag(:, v), lag(:, e), &
                                                    wet%poly(:, v), wet%poly(:, e), qr, qi, &
                                                    w0r, w0i, w1r, w1i, w2r, w2i, &
                                                    accs(:, :, v, 1:ns))
        end do
        if (present(sens)) then
          ! p' at the waterline's corners (depth 0): what a moving waterline adds or takes
          do v = 1, m
            if (.not. wet%cut(v)) cycle
            do it = 1, ns
              do l0 = 0, nc - 1, sens_lanes
                do ll = 1, min(sens_lanes, nc - l0)
                  l = l0 + ll
                  accw(ll, v, it) = accw(ll, v, it) + (qr(l, it)*(fr(l, v) - 1.0_wp) - &
                                                       qi(l, it)*(fi(l, v) + lag(l, v)))
                end do
              end do
            end do
          end do
        end if
      end associate
    end do
    do it = 1, nt
      do v = 1, m
        if (geo(1, v) == 0.0_wp) cycle
        j = sum(acc(1:lanes, :, v, it), dim=1)
        j(3:4) = -j(3:4)
        ! (F2, F3, M1) += -rho g t_s L (n2 J0, n3 J0, c0 J0 + L J1)
        load(:, it) = load(:, it) + geo(1, v)*[geo(2, v)*j(1), geo(3, v)*j(1), &
                                               geo(4, v)*j(1) + geo(5, v)*j(2)]
        rate(:, it) = rate(:, it) + geo(1, v)*[geo(2, v)*j(3), geo(3, v)*j(3), &
                                               geo(4, v)*j(3) + geo(5, v)*j(4)]
        if (.not. present(sens)) cycle
        if (it > ns) cycle
        do l = 1, 5
          j(1:2) = sum(accs(:, 2*l - 1:2*l, v, it), dim=1)
          sens(:, l, it) = sens(:, l, it) + geo(1, v)*[geo(2, v)*j(1), geo(3, v)*j(1), &
                                                       geo(4, v)*j(1) + geo(5, v)*j(2)]
        end do
        call add_rotation_terms(v, merge(1, v + 1, v == m), wet, geo(:, v), &
                                sum(accs(:, 11:16, v, it), dim=1), sens(:, :, it))
      end do
      if (present(sens) .and. it <= ns) call add_waterline_terms(wet, geo, depth, &
                                                  sum(accw(:, :, it), dim=1), sens(:, :, it))
    end do
  end subroutine section_wave_loads

  !> The turning section's share: a change of the rotation's columns b2, b3 (their
  !> horizontal parts c12, c22, c13, c23) moves the horizontal offset of the section point
  !> (y, z) by (dc12 y + dc13 z, dc22 y + dc23 z), its lag by k . that, and d Re(q w)/d eps
  !> = Im(q int phi_eps (E - 1) ds), phi_eps = k_x y(s) for c12 and so on, from the sums
  !> x(n) = sum k_x Im(q A_n), y(n) = sum k_y Im(q A_n), A_n = int s^n (E - 1) ds.
  pure subroutine add_rotation_terms(v, e, wet, geo, x, sens)
    integer, intent(in) :: v, e
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: geo(5), x(6)
    real(wp), intent(inout) :: sens(:, :)
    real(wp) :: u0, du, j(2)
    integer :: i, kk, uu
    do i = 1, 4
      ! 6: c12 (k_x, y), 7: c22 (k_y, y), 8: c13 (k_x, z), 9: c23 (k_y, z)
      kk = merge(0, 3, mod(i, 2) == 1)
      uu = merge(1, 2, i <= 2)
      u0 = wet%poly(uu, v)
      du = wet%poly(uu, e) - u0
      j = [u0*x(kk + 1) + du*x(kk + 2), u0*x(kk + 2) + du*x(kk + 3)]
      sens(:, 5 + i) = sens(:, 5 + i) + geo(1)*[geo(2)*j(1), geo(3)*j(1), &
                                                geo(4)*j(1) + geo(5)*j(2)]
    end do
  end subroutine add_rotation_terms

  !> The moving waterline's share of the load's derivatives: where the surface line cuts a
  !> hull edge V -> W (V on the line, W at depth d_W), a depth change dd at V wets (or
  !> dries) a further dd L/d_W of that edge, carrying p' of the waterline corner: the load
  !> changes by geo1 p'_V dd/d_W (n2, n3, y_V n3 - z_V n2) (geo1 = -rho g t_s L, p'_V per
  !> unit rho g), with dd = 1, y_V, z_V for the immersion and the slopes gy, gz.
  pure subroutine add_waterline_terms(wet, geo, depth, pv, sens)
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: geo(5, 5), depth(5), pv(5)
    real(wp), intent(inout) :: sens(:, :)
    real(wp) :: f(3)
    integer :: v, ie, iw, m
    m = wet%m
    do v = 1, m
      if (.not. wet%cut(v)) cycle
      ! its hull edge: v -> v + 1, unless that is the waterline, else v - 1 -> v
      ie = v
      iw = merge(1, v + 1, v == m)
      if (geo(1, ie) == 0.0_wp) then
        ie = merge(m, v - 1, v == 1)
        iw = ie
      end if
      if (geo(1, ie) == 0.0_wp .or. depth(iw) <= 0.0_wp) cycle
      f = geo(1, ie)*pv(v)/depth(iw)*[geo(2, ie), geo(3, ie), &
                                      wet%poly(1, v)*geo(3, ie) - wet%poly(2, v)*geo(2, ie)]
      sens(:, 1) = sens(:, 1) + f
      sens(:, 4) = sens(:, 4) + f*wet%poly(1, v)
      sens(:, 5) = sens(:, 5) + f*wet%poly(2, v)
    end do
  end subroutine add_waterline_terms

  !> The load's derivatives per component of a block along one edge A -> B (weights 1 and
  !> s): a depth change dd(s) at fixed polygon changes p' by -k rho g a exp(-k d) cos theta dd
  !> (the tangent plane's terms do not depend on depth), so the immersion (dd = 1) gives
  !> -k Re(q W0), -k Re(q W1) and the slopes (dd = y(s), z(s), linear from A to B)
  !> -k Re(q (y_A W0 + (y_B - y_A) W1)) and with s -k Re(q (y_A W1 + (y_B - y_A) W2)), W_n
  !> the edge integrals with weight s^n before the plane's share 1 - i phi is taken off;
  !> travel dx turns every phase (the plane's with them) by -k . dx: d Re(q w)/dx =
  !> k_x Im(q w). Accumulated per lane in acc(lane, (d0, x, y, gy, gz) x (w0, w1), time).
  pure subroutine add_sensitivities(nc, k, kx, ky, phi_a, phi_b, pa, pb, qr, qi, w0r, w0i, &
                                    w1r, w1i, w2r, w2i, acc)
    ! 17 arguments: a block's wavenumbers, the edge's lags and ends, the time phasors, the
    ! edge integrals and the accumulator (the hot loop's operands, passed as they lie).
    integer, intent(in) :: nc
    real(wp), intent(in) :: k(nc), kx(nc), ky(nc), phi_a(:), phi_b(:), pa(2), pb(2)
    real(wp), intent(in) :: qr(:, :), qi(:, :), w0r(:), w0i(:), w1r(:), w1i(:), w2r(:), w2i(:)
    real(wp), intent(inout) :: acc(:, :, :)
    real(wp) :: im0, im1, re0, re1, re2, a0, a1, a2, dy, dz
    integer :: it, l, l0, ll
    dy = pb(1) - pa(1)
    dz = pb(2) - pa(2)
    do it = 1, size(acc, 3)
      do l0 = 0, nc - 1, sens_lanes
      do ll = 1, min(sens_lanes, nc - l0)
        l = l0 + ll
        im0 = qr(l, it)*w0i(l) + qi(l, it)*w0r(l)
        im1 = qr(l, it)*w1i(l) + qi(l, it)*w1r(l)
        re0 = -k(l)*(qr(l, it)*(w0r(l) + 1.0_wp) - &
                     qi(l, it)*(w0i(l) - 0.5_wp*(phi_a(l) + phi_b(l))))
        re1 = -k(l)*(qr(l, it)*(w1r(l) + 0.5_wp) - &
                     qi(l, it)*(w1i(l) - (phi_a(l)/6.0_wp + phi_b(l)/3.0_wp)))
        re2 = -k(l)*(qr(l, it)*w2r(l) - qi(l, it)*w2i(l))
        acc(ll, 1, it) = acc(ll, 1, it) + re0
        acc(ll, 2, it) = acc(ll, 2, it) + re1
        acc(ll, 3, it) = acc(ll, 3, it) + kx(l)*im0
        acc(ll, 4, it) = acc(ll, 4, it) + kx(l)*im1
        acc(ll, 5, it) = acc(ll, 5, it) + ky(l)*im0
        acc(ll, 6, it) = acc(ll, 6, it) + ky(l)*im1
        acc(ll, 7, it) = acc(ll, 7, it) + (pa(1)*re0 + dy*re1)
        acc(ll, 8, it) = acc(ll, 8, it) + (pa(1)*re1 + dy*re2)
        acc(ll, 9, it) = acc(ll, 9, it) + (pa(2)*re0 + dz*re1)
        acc(ll, 10, it) = acc(ll, 10, it) + (pa(2)*re1 + dz*re2)
        ! turning the section (lags k . dx of its points): Im(q A_n), A_n = W_n - 1/(n+1)
        a0 = qr(l, it)*(w0i(l) - 0.5_wp*(phi_a(l) + phi_b(l))) + qi(l, it)*w0r(l)
        a1 = qr(l, it)*(w1i(l) - (phi_a(l)/6.0_wp + phi_b(l)/3.0_wp)) + qi(l, it)*w1r(l)
        a2 = qr(l, it)*w2i(l) + qi(l, it)*(w2r(l) - 1.0_wp/3.0_wp)
        acc(ll, 11, it) = acc(ll, 11, it) + kx(l)*a0
        acc(ll, 12, it) = acc(ll, 12, it) + kx(l)*a1
        acc(ll, 13, it) = acc(ll, 13, it) + kx(l)*a2
        acc(ll, 14, it) = acc(ll, 14, it) + ky(l)*a0
        acc(ll, 15, it) = acc(ll, 15, it) + ky(l)*a1
        acc(ll, 16, it) = acc(ll, 16, it) + ky(l)*a2
      end do
      end do
    end do
  end subroutine add_sensitivities

  !> For the nc components of a block, int_0^1 (exp(-k d(s) - i phi(s)) - (1 - i phi(s))) ds
  !> (w0) and the same with the weight s (w1), d and phi linear from the edge's start A to
  !> its end B (depth step dd = d_B - d_A, lags phi_a, phi_b, vertex factors fa, fb as real
  !> and imaginary parts, exponent z = ln(fb/fa) = -k dd + i (phi_a - phi_b)): the exact
  !> pressure minus the tangent plane's. The closed form runs over the whole block with a
  !> safe divisor (one loop, vectorised); the few components with |z| below series_limit
  !> are then overwritten by the series.
  pure subroutine edge_integrals(nc, k, dd, phi_a, phi_b, far, fai, fbr, fbi, &
                                 w0r, w0i, w1r, w1i, order, w2r, w2i)
    ! 15 arguments: the block's wavenumbers, the edge's depth step, lags and vertex factors,
    ! and the integrals it returns (the hot loop's operands, passed as they lie).
    integer, intent(in) :: nc
    real(wp), intent(in) :: k(nc), dd, phi_a(nc), phi_b(nc), far(nc), fai(nc), fbr(nc), fbi(nc)
    real(wp), intent(out) :: w0r(nc), w0i(nc), w1r(nc), w1i(nc)
    !> With order 2 also w2 = int s^2 exp(-k d(s) - i phi(s)) ds (the whole integrand, no
    !> plane's share taken off), by w2 = (fb - 2 w1)/z, or the series E3 = sum z^n/(n! (n + 3)).
    integer, intent(in) :: order
    real(wp), intent(out) :: w2r(:), w2i(:)
    real(wp) :: zr, zi, z2, rz, ir, ii, dr, di, t0
    real(wp) :: zr_(nc), zi_(nc), tr(nc), ti(nc), e1r(nc), e1i(nc), e2r(nc), e2i(nc)
    real(wp) :: e3r(nc), e3i(nc)
    logical :: small(nc)
    integer :: l, n
    do l = 1, nc
      zr = -k(l)*dd
      zi = phi_a(l) - phi_b(l)
      ! squared modulus: no hypot; a series lane divides by 1 (result overwritten below)
      z2 = zr*zr + zi*zi
      small(l) = z2 < series_limit**2
      rz = 1.0_wp/merge(1.0_wp, z2, small(l))
      ir = zr*rz
      ii = -zi*rz
      ! w0 = (fb - fa)/z, w1 = (fb - w0)/z
      dr = fbr(l) - far(l)
      di = fbi(l) - fai(l)
      w0r(l) = dr*ir - di*ii
      w0i(l) = dr*ii + di*ir
      dr = fbr(l) - w0r(l)
      di = fbi(l) - w0i(l)
      w1r(l) = dr*ir - di*ii
      w1i(l) = dr*ii + di*ir
      if (order < 2) cycle
      ! w2 = (fb - 2 w1)/z
      dr = fbr(l) - 2.0_wp*w1r(l)
      di = fbi(l) - 2.0_wp*w1i(l)
      w2r(l) = dr*ir - di*ii
      w2i(l) = dr*ii + di*ir
    end do
    if (any(small)) then
      ! E1 = sum z^n/(n+1)!, E2 = sum z^n/(n! (n+2)); w0 = fa E1, w1 = fa E2: the terms
      ! in lockstep over every lane (independent lanes vectorise), kept where the lane
      ! is small. Real arithmetic: a link-time-optimised build applies C's complex rules
      ! (NaN checks in every product) where Fortran's need none
      zr_(1:nc) = -k*dd
      zi_(1:nc) = phi_a - phi_b
      tr(1:nc) = 1.0_wp
      ti(1:nc) = 0.0_wp
      e1r(1:nc) = 1.0_wp
      e1i(1:nc) = 0.0_wp
      e2r(1:nc) = 0.5_wp
      e2i(1:nc) = 0.0_wp
      e3r(1:nc) = 1.0_wp/3.0_wp
      e3i(1:nc) = 0.0_wp
      do n = 1, series_terms
        do l = 1, nc
          t0 = (tr(l)*zr_(l) - ti(l)*zi_(l))*inv_n(n)
          ti(l) = (tr(l)*zi_(l) + ti(l)*zr_(l))*inv_n(n)
          tr(l) = t0
          e1r(l) = e1r(l) + tr(l)*inv_n1(n)
          e1i(l) = e1i(l) + ti(l)*inv_n1(n)
          e2r(l) = e2r(l) + tr(l)*inv_n2(n)
          e2i(l) = e2i(l) + ti(l)*inv_n2(n)
          if (order < 2) cycle
          e3r(l) = e3r(l) + tr(l)*inv_n3(n)
          e3i(l) = e3i(l) + ti(l)*inv_n3(n)
        end do
      end do
      do l = 1, nc
        if (.not. small(l)) cycle
        w0r(l) = far(l)*e1r(l) - fai(l)*e1i(l)
        w0i(l) = far(l)*e1i(l) + fai(l)*e1r(l)
        w1r(l) = far(l)*e2r(l) - fai(l)*e2i(l)
        w1i(l) = far(l)*e2i(l) + fai(l)*e2r(l)
        if (order < 2) cycle
        w2r(l) = far(l)*e3r(l) - fai(l)*e3i(l)
        w2i(l) = far(l)*e3i(l) + fai(l)*e3r(l)
      end do
    end if
    ! less the tangent plane's share 1 - i phi (weights 1 and s)
    do l = 1, nc
      w0r(l) = w0r(l) - 1.0_wp
      w0i(l) = w0i(l) + 0.5_wp*(phi_a(l) + phi_b(l))
      w1r(l) = w1r(l) - 0.5_wp
      w1i(l) = w1i(l) + (phi_a(l)/6.0_wp + phi_b(l)/3.0_wp)
    end do
  end subroutine edge_integrals

  !> Per polygon edge v -> v+1 of the wet section: (-rho g t_s L, n2, n3, c0, L) with L the
  !> length, n = (-t3, t2) the outward normal (the rectangle is listed bottom first,
  !> counter-clockwise in (y, z) with z down), c0 = A2 n3 - A3 n2 the moment arm term of its
  !> start A (M1 = y F3 - z F2 along the edge is -t_s int p (c0 + L s) L ds);
  !> geo(1) = 0 marks the waterline edge (both ends on the surface line).
  pure subroutine edge_geometry(hull, wet, geo)
    type(boat_hull_type), intent(in) :: hull
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(out) :: geo(5, 5)
    real(wp) :: tang(2), len
    integer :: v, e
    geo = 0.0_wp
    do v = 1, wet%m
      e = merge(1, v + 1, v == wet%m)
      if (wet%cut(v) .and. wet%cut(e)) cycle
      tang = wet%poly(:, e) - wet%poly(:, v)
      len = norm2(tang)
      if (len <= 0.0_wp) cycle
      tang = tang/len
      geo(1, v) = -rho_water*gravity*hull%thickness*len
      geo(2, v) = -tang(2)
      geo(3, v) = tang(1)
      geo(4, v) = wet%poly(1, v)*geo(3, v) - wet%poly(2, v)*geo(2, v)
      geo(5, v) = len
    end do
  end subroutine edge_geometry

end module davit_boat_strip_pressure
