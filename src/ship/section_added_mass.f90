!> Two-dimensional added masses of a ship section at infinite frequency, by a source-panel
!> method. At infinite frequency the free-surface condition is phi = 0 on z = 0, which the
!> Green function G = (ln r - ln r')/(2 pi) satisfies through a negative image above the
!> surface; panels cover only the wetted contour. Modes: sway (2), heave (3) and roll (4)
!> about the waterline point on the centreline. Strip theory integrates these along the ship
!> (review G10: section coefficients, not rules of thumb).
!>
!> Section coordinates (y, z): y to starboard, z down, waterline z = 0. The contour runs
!> from the starboard waterline round the keel to the port waterline; the normal (tz, -ty)
!> then points out of the body into the water.
module davit_ship_section_added_mass
  use davit_core_quadrature, only: gx => gauss8_x, gw => gauss8_w
  use davit_kinds, only: wp, pi, rho_water
  use davit_error, only: error_type, fatal_error
  implicit none
  private
  public :: section_added_mass, rectangle_contour, ellipse_contour

  interface
    subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: wp
      integer, intent(in) :: n, nrhs, lda, ldb
      real(wp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: ipiv(*)
      integer, intent(out) :: info
    end subroutine dgesv
  end interface

  !> Gauss-Legendre points on (-1, 1) (davit_core_quadrature).
  integer, parameter :: ng = 8

contains

  !> Added mass per unit length [kg/m, kg m/m for 24, kg m^2/m for 44]:
  !> a(1) = a22, a(2) = a33, a(3) = a44, a(4) = a24, from the contour vertices (y, z).
  subroutine section_added_mass(y, z, a, error)
    !> Section vertices [m], y to starboard and z down (waterline z = 0), from the starboard
    !> waterline round the keel to the port waterline (size = panels + 1).
    real(wp), intent(in) :: y(:), z(:)
    !> a22 [kg/m], a33 [kg/m], a44 [kg m^2/m] about the waterline point on the centreline and
    !> the coupling a24 [kg m/m], per unit length of ship.
    real(wp), intent(out) :: a(4)
    !> Set when the panel system is singular (a degenerate contour).
    type(error_type), allocatable, intent(out) :: error
    integer :: n, i, j, info
    real(wp), allocatable :: ym(:), zm(:), len(:), ny(:), nz(:), infl(:, :), pot(:, :), vn(:, :)
    real(wp), allocatable :: sigma(:, :), phi(:, :)
    integer, allocatable :: ipiv(:)
    n = size(y) - 1
    allocate (ym(n), zm(n), len(n), ny(n), nz(n), infl(n, n), pot(n, n), vn(n, 3), ipiv(n))
    do i = 1, n
      ym(i) = 0.5_wp*(y(i) + y(i + 1))
      zm(i) = 0.5_wp*(z(i) + z(i + 1))
      len(i) = hypot(y(i + 1) - y(i), z(i + 1) - z(i))
      ny(i) = (z(i + 1) - z(i))/len(i)
      nz(i) = -(y(i + 1) - y(i))/len(i)
    end do
    ! unit normal velocities: sway, heave, roll (omega x r with omega along x: (-z, y))
    vn(:, 1) = ny
    vn(:, 2) = nz
    vn(:, 3) = -zm*ny + ym*nz
    do i = 1, n
      do j = 1, n
        call panel_influence(i, j, infl(i, j), pot(i, j))
      end do
    end do
    sigma = vn
    call dgesv(n, 3, infl, n, ipiv, sigma, n, info)
    if (info /= 0) then
      call fatal_error(error, "section added mass: singular panel system")
      return
    end if
    phi = matmul(pot, sigma)
    a(1) = -rho_water*sum(phi(:, 1)*vn(:, 1)*len)
    a(2) = -rho_water*sum(phi(:, 2)*vn(:, 2)*len)
    a(3) = -rho_water*sum(phi(:, 3)*vn(:, 3)*len)
    a(4) = -rho_water*sum(phi(:, 1)*vn(:, 3)*len)

  contains

    !> Normal velocity at collocation point i and potential there due to a unit source
    !> density on panel j and its negative image.
    subroutine panel_influence(i, j, dphidn, phij)
      integer, intent(in) :: i, j
      real(wp), intent(out) :: dphidn, phij
      real(wp) :: qy, qz, dy, dz, r2, s
      integer :: k
      dphidn = 0.0_wp
      phij = 0.0_wp
      if (i == j) then
        dphidn = 0.5_wp
        ! integral of ln|t| over the panel itself, analytic
        phij = len(j)*(log(0.5_wp*len(j)) - 1.0_wp)/(2*pi)
      end if
      do k = 1, ng
        s = 0.5_wp*(1.0_wp + gx(k))
        qy = y(j) + s*(y(j + 1) - y(j))
        qz = z(j) + s*(z(j + 1) - z(j))
        if (i /= j) then
          dy = ym(i) - qy; dz = zm(i) - qz
          r2 = dy*dy + dz*dz
          dphidn = dphidn + 0.5_wp*gw(k)*len(j)*(dy*ny(i) + dz*nz(i))/r2/(2*pi)
          phij = phij + 0.5_wp*gw(k)*len(j)*0.5_wp*log(r2)/(2*pi)
        end if
        ! negative image at (qy, -qz)
        dy = ym(i) - qy; dz = zm(i) + qz
        r2 = dy*dy + dz*dz
        dphidn = dphidn - 0.5_wp*gw(k)*len(j)*(dy*ny(i) + dz*nz(i))/r2/(2*pi)
        phij = phij - 0.5_wp*gw(k)*len(j)*0.5_wp*log(r2)/(2*pi)
      end do
    end subroutine panel_influence

  end subroutine section_added_mass

  !> Vertices of a rectangular section of beam b and draught t, nside panels on each side
  !> and nbottom on the bottom, clustered towards the corners.
  pure subroutine rectangle_contour(b, t, nside, nbottom, y, z)
    !> Beam b [m] and draught t [m] of the rectangle.
    real(wp), intent(in) :: b, t
    !> Number of panels on each side and on the bottom.
    integer, intent(in) :: nside, nbottom
    !> The vertices [m] (y to starboard, z down), 2 nside + nbottom + 1 of them, from the
    !> starboard waterline round the keel to the port waterline.
    real(wp), allocatable, intent(out) :: y(:), z(:)
    integer :: i, k
    allocate (y(2*nside + nbottom + 1), z(2*nside + nbottom + 1))
    k = 0
    do i = 0, nside - 1
      k = k + 1
      y(k) = 0.5_wp*b
      z(k) = t*cluster(real(i, wp)/nside)
    end do
    do i = 0, nbottom - 1
      k = k + 1
      y(k) = 0.5_wp*b - b*cluster(real(i, wp)/nbottom)
      z(k) = t
    end do
    do i = 0, nside
      k = k + 1
      y(k) = -0.5_wp*b
      z(k) = t - t*cluster(real(i, wp)/nside)
    end do
  end subroutine rectangle_contour

  !> Half-ellipse (semi-axes yb across, zt down) from the starboard waterline to port.
  pure subroutine ellipse_contour(yb, zt, n, y, z)
    !> Half-beam yb [m] at the waterline and depth zt [m] at the keel (the semi-axes).
    real(wp), intent(in) :: yb, zt
    !> Number of panels.
    integer, intent(in) :: n
    !> The n + 1 vertices [m] (y to starboard, z down), from the starboard waterline to port.
    real(wp), allocatable, intent(out) :: y(:), z(:)
    integer :: i
    allocate (y(n + 1), z(n + 1))
    do i = 0, n
      y(i + 1) = yb*cos(pi*i/n)
      z(i + 1) = zt*sin(pi*i/n)
    end do
  end subroutine ellipse_contour

  !> Cosine clustering of [0, 1] towards both ends.
  pure real(wp) function cluster(s)
    real(wp), intent(in) :: s
    cluster = 0.5_wp*(1.0_wp - cos(pi*s))
  end function cluster

end module davit_ship_section_added_mass
