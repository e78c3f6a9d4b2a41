!> The strips' window read from the precomputed surface grid (`&sea kinematics = 'grid'`,
!> davit_sea_wave_grid): the elevation terms at both ends of a window with the curvature
!> the strip centres carry (davit_boat_strip_sums' nep terms), where the grid holds them.
module davit_boat_strip_grid
  use davit_kinds, only: wp
  use davit_boat_strip_sums, only: ne, nep
  use davit_sea_wave_grid, only: wave_grid_type, grid_covers, grid_elevation
  implicit none
  private
  public :: grid_holds, grid_ends

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

end module davit_boat_strip_grid
