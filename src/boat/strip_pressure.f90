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
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_stokes2, wave_ramp, &
                                  wave_chunk
  use davit_boat_hull, only: boat_hull_type, section_wet_type
  implicit none
  private
  public :: surface_plane, section_wave_load

  !> Below this |z| the edge integrals use their power series (cancellation above ~eps/|z|^2).
  real(wp), parameter :: series_limit = 0.5_wp
  integer, parameter :: series_terms = 14

contains

  !> Elevation eta [m] (up, ramped) at (x, y) and its horizontal gradient (d/dx, d/dy):
  !> grad of a cos(theta) is a sin(theta) (kx, ky); the Stokes-2 term (k a^2/2) cos(2 theta)
  !> adds k a^2 sin(2 theta) (kx, ky) (r^2 with the ramp r).
  pure subroutine surface_plane(field, t, x, y, eta, grad)
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, x, y
    real(wp), intent(out) :: eta, grad(2)
    real(wp) :: th(wave_chunk), r, s2, th1
    integer :: i0, i1
    eta = 0.0_wp
    grad = 0.0_wp
    if (field%kind == wave_none) return
    r = wave_ramp(field, t)
    do i0 = 1, field%n, wave_chunk
      i1 = min(field%n, i0 + wave_chunk - 1)
      associate (a => field%amplitude(i0:i1), th => th(1:i1 - i0 + 1))
        th = field%omega(i0:i1)*t + field%phase(i0:i1) - field%kx(i0:i1)*x - field%ky(i0:i1)*y
        eta = eta + sum(a*cos(th))
        grad(1) = grad(1) + sum(a*sin(th)*field%kx(i0:i1))
        grad(2) = grad(2) + sum(a*sin(th)*field%ky(i0:i1))
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
    type(wave_field_type), intent(in) :: field
    type(boat_hull_type), intent(in) :: hull
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: t, c(3, 3), pk(3), d0, gy, gz
    real(wp), intent(out) :: load(3), rate(3)
    real(wp) :: depth(5), dxy(2, 5), geo(5, 5), lag(5), th, j(4)
    complex(wp) :: q, fv(5), w0, w1
    integer :: i, v, e, m
    load = 0.0_wp
    rate = 0.0_wp
    if (field%kind == wave_none .or. wet%m < 3) return
    m = wet%m
    call edge_geometry(hull, wet, geo)
    do v = 1, m
      depth(v) = max(0.0_wp, d0 + gy*wet%poly(1, v) + gz*wet%poly(2, v))
      dxy(:, v) = c(1:2, 2)*wet%poly(1, v) + c(1:2, 3)*wet%poly(2, v)
    end do
    do i = 1, field%n
      th = field%omega(i)*t + field%phase(i) - field%kx(i)*pk(1) - field%ky(i)*pk(2)
      q = field%amplitude(i)*cmplx(cos(th), sin(th), wp)
      do v = 1, m
        lag(v) = field%kx(i)*dxy(1, v) + field%ky(i)*dxy(2, v)
        fv(v) = exp(cmplx(-field%k(i)*depth(v), -lag(v), wp))
      end do
      do v = 1, m
        if (geo(1, v) == 0.0_wp) cycle
        e = merge(1, v + 1, v == m)
        call edge_integrals(fv(v), fv(e), lag(v), lag(e), &
                            cmplx(-field%k(i)*(depth(e) - depth(v)), lag(v) - lag(e), wp), &
                            w0, w1)
        ! J = Re(q w) and dJ/dt = Re(i omega q w) = -omega Im(q w)
        w0 = q*w0
        w1 = q*w1
        j = [real(w0, wp), real(w1, wp), -field%omega(i)*aimag(w0), -field%omega(i)*aimag(w1)]
        ! (F2, F3, M1) += -rho g t_s L (n2 J0, n3 J0, c0 J0 + L J1)
        load = load + geo(1, v)*[geo(2, v)*j(1), geo(3, v)*j(1), geo(4, v)*j(1) + geo(5, v)*j(2)]
        rate = rate + geo(1, v)*[geo(2, v)*j(3), geo(3, v)*j(3), geo(4, v)*j(3) + geo(5, v)*j(4)]
      end do
    end do
  end subroutine section_wave_load

  !> int_0^1 (exp(-k d(s) - i phi(s)) - (1 - i phi(s))) ds and the same with the weight s,
  !> d and phi linear from the edge's start A to its end B (vertex factors fa, fb, lags
  !> phi_a, phi_b, exponent z = ln(fb/fa)): the exact pressure minus the tangent plane's.
  pure subroutine edge_integrals(fa, fb, phi_a, phi_b, z, w0, w1)
    complex(wp), intent(in) :: fa, fb, z
    real(wp), intent(in) :: phi_a, phi_b
    complex(wp), intent(out) :: w0, w1
    complex(wp) :: term, e1, e2
    integer :: n
    if (abs(z) < series_limit) then
      ! E1 = sum z^n/(n+1)!, E2 = sum z^n/(n! (n+2))
      term = (1.0_wp, 0.0_wp)
      e1 = term
      e2 = 0.5_wp*term
      do n = 1, series_terms
        term = term*z/real(n, wp)
        e1 = e1 + term/real(n + 1, wp)
        e2 = e2 + term/real(n + 2, wp)
      end do
      w0 = fa*e1
      w1 = fa*e2
    else
      w0 = (fb - fa)/z
      w1 = fb/z - w0/z
    end if
    w0 = w0 - cmplx(1.0_wp, -0.5_wp*(phi_a + phi_b), wp)
    w1 = w1 - cmplx(0.5_wp, -(phi_a/6.0_wp + phi_b/3.0_wp), wp)
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
