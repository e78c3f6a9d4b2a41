!> The samples of the strips' window (davit_boat_strip_waves) at both ends: the elevation
!> terms with the curvature the strip centres carry (davit_boat_strip_sums' nep terms) and
!> the velocity terms, read from the precomputed grids (`&sea kinematics = 'grid'`,
!> davit_sea_wave_grid) where they hold them, else summed exactly; and the bounds over the
!> window the surface watch takes from the centres' samples.
module davit_boat_strip_grid
  use davit_kinds, only: wp
  use davit_boat_strip_sums, only: ne, nv, nep, elevation_pass, elevation_line, kinematic_pass
  use davit_sea_wave_field, only: wave_field_type, wave_ramp
  use davit_sea_wave_grid, only: wave_grid_type, grid_covers, grid_elevation, grid_kinematics
  use davit_core_hermite, only: hermite_max
  implicit none
  private
  public :: grid_holds, grid_ends, window_elevations, window_kinematics, window_bounds

contains

  !> Whether the grid holds (x, y) and the four points half a spacing from it at both ends
  !> of the window (the curvature's differences).
  pure logical function grid_holds(grid, window, x, y)
    !> The surface grid.
    type(wave_grid_type), intent(in) :: grid
    !> The window [t1, t2] [s] and the point (x, y) (inertial) [m].
    real(wp), intent(in) :: window(2), x, y
    real(wp) :: dl
    integer :: j
    dl = 0.5_wp*grid%h
    grid_holds = .false.
    do j = 1, 2
      if (.not. (grid_covers(grid, window(j), x, y) .and. &
                 grid_covers(grid, window(j), x - dl, y) .and. &
                 grid_covers(grid, window(j), x + dl, y) .and. &
                 grid_covers(grid, window(j), x, y - dl) .and. &
                 grid_covers(grid, window(j), x, y + dl))) return
    end do
    grid_holds = .true.
  end function grid_holds

  !> Elevation terms at both window ends from the grid: the curvature by central
  !> differences of its slope field half a spacing around (x, y), the slope's rates those
  !> of its chord over the window (the slope linear in time).
  pure subroutine grid_ends(grid, window, x, y, e)
    !> The surface grid.
    type(wave_grid_type), intent(in) :: grid
    !> The window [t1, t2] [s] and the point (x, y) (inertial) [m].
    real(wp), intent(in) :: window(2), x, y
    !> Unramped elevation terms (davit_boat_strip_sums' nep) at both ends.
    real(wp), intent(out) :: e(nep, 2)
    real(wp) :: dl, xp(ne), xm(ne), yp(ne), ym(ne)
    integer :: j
    dl = 0.5_wp*grid%h
    do j = 1, 2
      call grid_elevation(grid, window(j), x, y, e(1:ne, j))
      call grid_elevation(grid, window(j), x + dl, y, xp)
      call grid_elevation(grid, window(j), x - dl, y, xm)
      call grid_elevation(grid, window(j), x, y + dl, yp)
      call grid_elevation(grid, window(j), x, y - dl, ym)
      e(ne + 1, j) = (xp(3) - xm(3))/(2.0_wp*dl)
      e(ne + 2, j) = 0.5_wp*((xp(4) - xm(4)) + (yp(3) - ym(3)))/(2.0_wp*dl)
      e(ne + 3, j) = (yp(4) - ym(4))/(2.0_wp*dl)
    end do
    do j = 1, 2
      e(ne + 4:nep, j) = (e(3:4, 2) - e(3:4, 1))/(window(2) - window(1))
    end do
  end subroutine grid_ends

  !> Elevation terms at both ends of `window` at the strip centres p (evenly spaced, `step`
  !> apart): from the grid where it holds both, else the exact sums, along the line of
  !> centres in one pass (angle addition from one centre to the next).
  pure subroutine window_elevations(field, window, cr, sr, p, step, e, grid)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> The window [t1, t2] [s], and cos(w h), sin(w h) of every component.
    real(wp), intent(in) :: window(2), cr(:), sr(:)
    !> The strip centres (x, y) (inertial) [m] and the step from one to the next [m].
    real(wp), intent(in) :: p(:, :), step(2)
    !> Unramped elevation terms (term, end, centre).
    real(wp), intent(out) :: e(:, :, :)
    !> Precomputed grid of the surface (absent: the sea itself).
    type(wave_grid_type), intent(in), optional :: grid
    integer :: k
    if (.not. present(grid) .and. size(p, 2) > 1) then
      call elevation_line(field, window(1), p(1, 1), p(2, 1), step(1), step(2), cr, sr, e)
      return
    end if
    do k = 1, size(p, 2)
      if (present(grid)) then
        if (grid_holds(grid, window, p(1, k), p(2, k))) then
          call grid_ends(grid, window, p(1, k), p(2, k), e(:, :, k))
          cycle
        end if
      end if
      call elevation_pass(field, window(1), p(1, k), p(2, k), 2, cr, sr, e(:, :, k))
    end do
  end subroutine window_elevations

  !> Velocity terms at both ends of `window` at (x, y, d): from the grid where it holds
  !> both, else the exact sums in one pass.
  pure subroutine window_kinematics(field, window, cr, sr, x, y, d, v, grid)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> The window [t1, t2] [s], and cos(w h), sin(w h) of every component.
    real(wp), intent(in) :: window(2), cr(:), sr(:)
    !> Horizontal position (inertial) [m] and stretched depth [m].
    real(wp), intent(in) :: x, y, d
    !> Unramped velocity terms (component, term, end).
    real(wp), intent(out) :: v(3, nv, 2)
    !> Precomputed grid of the water (absent: the sea itself).
    type(wave_grid_type), intent(in), optional :: grid
    real(wp) :: e(ne, 2)
    integer :: j
    if (present(grid)) then
      if (grid_covers(grid, window(1), x, y, d) .and. grid_covers(grid, window(2), x, y, d)) then
        do j = 1, 2
          call grid_kinematics(grid, window(j), x, y, d, e(:, j), v(:, :, j))
        end do
        return
      end if
    end if
    call kinematic_pass(field, window(1), x, y, d, 2, cr, sr, e, v, .false.)
  end subroutine window_kinematics

  !> Upper bounds over `window` of the ramped elevation and of the slope's size at each
  !> strip centre from its samples e (exact sums) at both ends: the extremes of the cubics
  !> through the value and its rate (the slope's two components each) plus the cubic's
  !> remainder h^4/384 max|d4f/dt4| (the fourth time derivative of a component of the
  !> linear sea is a w^4 times a cosine: at most quartic(1) = sum |a| w^4, and quartic(2)
  !> = sum |a| k w^4 for a slope component).
  pure subroutine window_bounds(field, window, e, quartic, eta_up, slope_up)
    !> The sea (its start-up ramp).
    type(wave_field_type), intent(in) :: field
    !> The window [t1, t2] [s].
    real(wp), intent(in) :: window(2)
    !> Unramped elevation terms (term, end, centre).
    real(wp), intent(in) :: e(:, :, :)
    !> The fourth derivatives' bounds, sum |a| w^4 and sum |a| k w^4.
    real(wp), intent(in) :: quartic(2)
    !> Per centre: the bounds of the elevation [m] and of |grad eta| over the window.
    real(wp), intent(out) :: eta_up(:), slope_up(:)
    real(wp) :: rem(2), ramp(2), top, g(2)
    integer :: k, i
    rem = (window(2) - window(1))**4/384.0_wp*quartic
    ramp = [wave_ramp(field, window(1)), wave_ramp(field, window(2))]
    do k = 1, size(eta_up)
      top = hermite_max(window, e(1, 1, k), e(2, 1, k), e(1, 2, k), e(2, 2, k)) + rem(1)
      ! the ramp rises over the window: the unramped bound times its end that is larger
      eta_up(k) = top*merge(ramp(2), ramp(1), top >= 0.0_wp)
      do i = 1, 2
        g(i) = max(hermite_max(window, e(2 + i, 1, k), e(7 + i, 1, k), e(2 + i, 2, k), &
                               e(7 + i, 2, k)), &
                   hermite_max(window, -e(2 + i, 1, k), -e(7 + i, 1, k), -e(2 + i, 2, k), &
                               -e(7 + i, 2, k))) + rem(2)
      end do
      slope_up(k) = ramp(2)*norm2(g)
    end do
  end subroutine window_bounds

end module davit_boat_strip_grid
