!> Strip geometry of the lifeboat hull (paper §II.B, eqs. 18-24; review gap G25).
!>
!> n strips of equal thickness t_s = L/n along b1, centred at (x_k, 0, 0) with x_k measured
!> from the CG. Each strip is a rectangular section of breadth b(x_k) = B (1 - |2x/L|^p)
!> (p = 4.3 gives a plan-area coefficient of 0.81, i.e. the paper's A3 = 26.2 m^2) and
!> height H, its bottom (keel) at z_b = keel below the CG (b3 points down).
!>
!> The submerged part of a section is found exactly for any attitude: in the section plane
!> the depth below the local free surface is linear in (y, z), so the wet part is the
!> rectangle clipped by a straight line (a convex polygon of up to five corners). Its area
!> gives V_k = A_k t_s (eq. 23), its centroid the point where the water velocity is taken
!> (review §1.5), and its extents the drag areas A2 = t_s x wet height, A3 = t_s x wet width.
module davit_boat_hull
  use davit_kinds, only: wp
  implicit none
  private
  public :: boat_hull_type, new_boat_hull, section_immersion, section_wet_type
  public :: hull_metacentric_height, hull_waterplane_area

  type :: boat_hull_type
    !> Number of sections along the hull.
    integer :: n = 0
    !> Length, beam and height of the hull [m]; keel depth below the CG [m].
    real(wp) :: length = 0.0_wp, beam = 0.0_wp, height = 0.0_wp, keel = 0.0_wp
    !> Strip thickness t_s = L/n [m].
    real(wp) :: thickness = 0.0_wp
    !> Strip centres x_k [m] (from the CG along b1) and section breadths b(x_k) [m].
    real(wp), allocatable :: x(:), breadth(:)
  end type boat_hull_type

  !> The wet part of one section: area [m^2], centroid (y, z) in the boat frame [m],
  !> its extent along b2 (wet width) and b3 (wet height) [m], and the wet polygon itself
  !> (m corners (y, z), in the rectangle's order; cut(i): corner i lies on the surface
  !> line, so the edge i -> i+1 is the waterline where both its ends are cut).
  type :: section_wet_type
    !> Wet area [m^2].
    real(wp) :: area = 0.0_wp
    !> Centroid (y, z) of the wet area, boat frame [m].
    real(wp) :: centroid(2) = 0.0_wp
    !> Wet width along b2 and wet height along b3 [m].
    real(wp) :: width = 0.0_wp, height = 0.0_wp
    !> Corners of the wet polygon (0..5).
    integer :: m = 0
    !> The wet polygon's corners (y, z), boat frame [m].
    real(wp) :: poly(2, 5) = 0.0_wp
    !> Whether corner i lies on the surface line.
    logical :: cut(5) = .false.
  end type section_wet_type

contains

  pure function new_boat_hull(length, beam, height, keel, exponent, n) result(h)
    !> Length, beam, height [m], keel depth below the CG [m] and the breadth exponent of the
    !> sections' taper.
    real(wp), intent(in) :: length, beam, height, keel, exponent
    !> Number of sections.
    integer, intent(in) :: n
    type(boat_hull_type) :: h
    integer :: k
    h%n = n
    h%length = length
    h%beam = beam
    h%height = height
    h%keel = keel
    h%thickness = length/real(n, wp)
    allocate (h%x(n), h%breadth(n))
    do k = 1, n
      h%x(k) = -0.5_wp*length + (real(k, wp) - 0.5_wp)*h%thickness
      h%breadth(k) = beam*(1.0_wp - abs(2.0_wp*h%x(k)/length)**exponent)
    end do
  end function new_boat_hull

  !> Wet part of section k where the depth below the surface is d(y, z) = d0 + gy y + gz z
  !> (d0 includes the section's x position; wet where d > 0).
  pure function section_immersion(h, k, d0, gy, gz) result(s)
    !> The hull.
    type(boat_hull_type), intent(in) :: h
    !> Section index (1..n).
    integer, intent(in) :: k
    !> Depth below the surface at the section's centre d0 [m] (with its x position) and its slopes
    !> gy, gz along b2, b3: d(y, z) = d0 + gy y + gz z.
    real(wp), intent(in) :: d0, gy, gz
    type(section_wet_type) :: s
    real(wp) :: corner(2, 4), poly(2, 5), depth(4), a, cross_term, half
    logical :: cut(5)
    integer :: i, j, m
    half = 0.5_wp*h%breadth(k)
    corner(:, 1) = [-half, h%keel]
    corner(:, 2) = [half, h%keel]
    corner(:, 3) = [half, h%keel - h%height]
    corner(:, 4) = [-half, h%keel - h%height]
    depth = d0 + gy*corner(1, :) + gz*corner(2, :)
    if (all(depth <= 0.0_wp)) return
    ! Clip the rectangle to d > 0 (Sutherland-Hodgman against one line).
    m = 0
    do i = 1, 4
      j = merge(1, i + 1, i == 4)
      if (depth(i) > 0.0_wp) then
        m = m + 1
        poly(:, m) = corner(:, i)
        cut(m) = .false.
      end if
      if ((depth(i) > 0.0_wp) .neqv. (depth(j) > 0.0_wp)) then
        m = m + 1
        poly(:, m) = corner(:, i) + depth(i)/(depth(i) - depth(j))*(corner(:, j) - corner(:, i))
        cut(m) = .true.
      end if
    end do
    ! Shoelace area and centroid.
    a = 0.0_wp
    s%centroid = 0.0_wp
    do i = 1, m
      j = merge(1, i + 1, i == m)
      cross_term = poly(1, i)*poly(2, j) - poly(1, j)*poly(2, i)
      a = a + cross_term
      s%centroid = s%centroid + (poly(:, i) + poly(:, j))*cross_term
    end do
    s%area = 0.5_wp*abs(a)
    if (s%area <= 0.0_wp) then
      s = section_wet_type()
      return
    end if
    s%centroid = s%centroid/(3.0_wp*a)
    s%width = maxval(poly(1, 1:m)) - minval(poly(1, 1:m))
    s%height = maxval(poly(2, 1:m)) - minval(poly(2, 1:m))
    s%m = m
    s%poly(:, 1:m) = poly(:, 1:m)
    s%cut(1:m) = cut(1:m)
  end function section_immersion

  !> Waterplane area of the upright strip hull, sum b_k t_s [m^2].
  pure real(wp) function hull_waterplane_area(h) result(a)
    !> The hull.
    type(boat_hull_type), intent(in) :: h
    a = sum(h%breadth)*h%thickness
  end function hull_waterplane_area

  !> Transverse metacentric height of the upright strip hull floating with volume v [m^3]
  !> and the CG h%keel above the keel: GM_T = KB + BM - KG with the draught T = v/A_wp,
  !> KB = T/2 (wall-sided sections, flat bottom), BM = I_T/v, I_T = sum b_k^3 t_s/12 (the
  !> strips' waterplane), KG = h%keel (review G25). 0.766 m for the III.B boat.
  pure real(wp) function hull_metacentric_height(h, v) result(gm)
    !> The hull.
    type(boat_hull_type), intent(in) :: h
    !> Wet volume [m^3].
    real(wp), intent(in) :: v
    gm = 0.5_wp*v/hull_waterplane_area(h) + sum(h%breadth**3)*h%thickness/(12.0_wp*v) - h%keel
  end function hull_metacentric_height

end module davit_boat_hull
