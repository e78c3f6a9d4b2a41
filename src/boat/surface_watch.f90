!> Proof that the hull is out of the water, so the strip loads (eqs. 18-25) can be skipped
!> while the boat hangs high above the waves: an exact shortcut, not an approximation.
!>
!> Every few hundredths of a second (after a step) the surface elevation is sampled at the
!> strips' reference points. In between, the elevation anywhere is bounded by the Lipschitz
!> constants of the wave field,
!>   |eta(p, t) - eta(p_c, t_c)| <= B_t |t - t_c| + B_x |p - p_c|,
!>   B_t = sum a (omega + r'_max) (+ Stokes term),  B_x = sum a k (+ Stokes term),
!> so a strip whose section stays dry under the raised surface eta_c + bound is surely dry.
!> The pressure level clips each section by the surface's tangent plane at its centre, which
!> rises across the section (corners within R of the centre) by at most |grad eta| R; the
!> slope is sampled too and bounded the same way, |grad eta| <= |grad eta_c| + S_t |dt| +
!> S_x |dp|, S_t = sum a k (omega + r'_max), S_x = sum a k^2 (+ Stokes terms).
!> When every strip is surely dry the strip loads are exactly zero and need not be formed.
!> In an irregular sea these Lipschitz constants are sums over every component (~30 m/s
!> in the Level 5 sea), so inside a window of the strips' slow clock the watch takes the
!> window's own bounds instead (watch_set_window: the cubics through its exact samples).
!> An irregular sea of 1300 components costs 1300 sines per strip and stage: this keeps
!> that cost out of the hanging phase.
module davit_boat_surface_watch
  use davit_kinds, only: wp, pi
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_stokes2
  use davit_boat_strip_pressure, only: surface_plane
  use davit_boat_hull, only: section_immersion, section_wet_type
  use davit_boat_strip_loads, only: strip_model_type
  use davit_sea_wave_grid, only: wave_grid_type, grid_covers, grid_elevation
  use davit_sea_wave_field, only: wave_ramp
  implicit none
  private
  public :: surface_watch_type, new_surface_watch, watch_refresh, watch_set, watch_due, &
            surely_dry, strip_surely_dry, watch_set_window, hull_surely_dry

  type :: surface_watch_type
    !> Whether the samples below have been taken.
    logical :: valid = .false.
    !> Sample time [s] and refresh interval [s].
    real(wp) :: t = 0.0_wp, interval = 0.05_wp
    !> Elevation [m] (up positive) at each strip's reference point, and that point (x, y).
    real(wp), allocatable :: eta(:), xy(:, :)
    !> Slope |grad eta| at each strip's reference point [-].
    real(wp), allocatable :: slope(:)
    !> Lipschitz constants of eta in time [m/s] and in horizontal space [-], and of its
    !> slope in time [1/s] and space [1/m].
    real(wp) :: rate_bound = 0.0_wp, slope_bound = 0.0_wp
    !> Lipschitz constants of the slope in time [1/s] and in space [1/m].
    real(wp) :: slope_rate_bound = 0.0_wp, curvature_bound = 0.0_wp
    !> Interpolation error bounds of the elevation [m] and slope [-] of a sample taken
    !> from the grid (`&sea kinematics = 'grid'`), added so the proof stays a proof.
    real(wp) :: grid_error(2) = 0.0_wp
    !> Per strip, whether its surface came from the precomputed grid.
    logical, allocatable :: from_grid(:)
    !> Until this time [s] the watch, though older than its interval, still proves the hull
    !> dry (checked an interval ahead): no refresh needed before (see watch_due).
    real(wp) :: kept_until = -huge(1.0_wp)
    !> A window [t1, t2] of the strips' slow clock, over which eta_up and slope_up bound
    !> the surface at the strips' points (empty: none; watch_set_window) [s].
    real(wp) :: window(2) = [1.0_wp, 0.0_wp]
    !> Per strip, the bounds over the window of the elevation [m] and of |grad eta| [-].
    real(wp), allocatable :: eta_up(:), slope_up(:)
  end type surface_watch_type

contains

  !> Bounds of the field's rate and slope; the watch starts invalid (no shortcut).
  pure function new_surface_watch(field, nstrips, interval) result(w)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Number of strips.
    integer, intent(in) :: nstrips
    !> Length of a window [s].
    real(wp), intent(in) :: interval
    type(surface_watch_type) :: w
    real(wp) :: amp, ramp_rate, stokes
    allocate (w%eta(nstrips), w%xy(2, nstrips), w%slope(nstrips), w%from_grid(nstrips), &
              w%eta_up(nstrips), w%slope_up(nstrips))
    w%from_grid = .false.
    w%eta_up = 0.0_wp
    w%slope_up = 0.0_wp
    w%interval = interval
    if (field%kind == wave_none) return
    amp = sum(abs(field%amplitude))
    ! (1 - cos(pi t/T))/2 rises at most at pi/(2 T).
    ramp_rate = 0.0_wp
    if (field%ramp_time > 0.0_wp) ramp_rate = 0.5_wp*pi/field%ramp_time
    stokes = 0.0_wp
    if (field%kind == wave_stokes2) stokes = 0.5_wp*field%k(1)*field%amplitude(1)**2
    ! d/dt [r a cos] and d/dt [r^2 k a^2/2 cos 2 theta]
    w%rate_bound = sum(abs(field%amplitude)*field%omega) + amp*ramp_rate + &
                   stokes*(2.0_wp*ramp_rate + 2.0_wp*maxval(field%omega))
    w%slope_bound = sum(abs(field%amplitude)*field%k) + 2.0_wp*stokes*maxval(field%k)
    w%slope_rate_bound = sum(abs(field%amplitude)*field%k*field%omega) + &
                         w%slope_bound*ramp_rate + &
                         2.0_wp*stokes*maxval(field%k)* &
                         (2.0_wp*ramp_rate + 2.0_wp*maxval(field%omega))
    w%curvature_bound = sum(abs(field%amplitude)*field%k**2) + 4.0_wp*stokes*maxval(field%k)**2
  end function new_surface_watch

  !> Sample the elevation at the strips' reference points of the boat at (c, r): from the
  !> grid where given and it holds the point (its error bound added in the proof), else
  !> the exact sum.
  pure subroutine watch_refresh(w, s, field, t, c, r, grid)
    !> The watch, refreshed.
    type(surface_watch_type), intent(inout) :: w
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> Precomputed surface grid (absent: the sea itself).
    type(wave_grid_type), intent(in), optional :: grid
    real(wp) :: p(3), grad(2), e(4)
    integer :: k
    do k = 1, s%hull%n
      p = r + c(:, 1)*s%hull%x(k)
      w%xy(:, k) = p(1:2)
      w%from_grid(k) = .false.
      if (present(grid)) w%from_grid(k) = grid_covers(grid, t, p(1), p(2))
      if (w%from_grid(k)) then
        call grid_elevation(grid, t, p(1), p(2), e)
        w%eta(k) = wave_ramp(field, t)*e(1)
        grad = wave_ramp(field, t)*e(3:4)
      else
        call surface_plane(field, t, p(1), p(2), w%eta(k), grad)
      end if
      w%slope(k) = norm2(grad)
    end do
    w%t = t
    w%valid = .true.
    w%kept_until = -huge(1.0_wp)
    w%window = [1.0_wp, 0.0_wp]
  end subroutine watch_refresh

  !> Whether the watch must be refreshed after a step ending at t (boat at (c, r)): it is
  !> older than its interval and no longer proves every strip dry two intervals ahead at
  !> today's pose. A hull high above the waves keeps an old watch (its bound grows with
  !> its age, eq. in strip_surely_dry), checked once per interval, instead of summing the
  !> sea at every strip each interval; the bound is rigorous at any age, so what the
  !> stages find dry is dry either way.
  pure subroutine watch_due(w, s, t, c, r, due)
    !> The watch (kept_until advanced when it is kept).
    type(surface_watch_type), intent(inout) :: w
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> Whether to refresh now.
    logical, intent(out) :: due
    due = .not. w%valid
    if (due .or. t - w%t < w%interval .or. t < w%kept_until) return
    due = .not. surely_dry(w, s, t + 2.0_wp*w%interval, c, r)
    if (.not. due) w%kept_until = t + w%interval
  end subroutine watch_due

  !> The watch refreshed from elevations sampled elsewhere (the strips' slow clock samples
  !> the exact sums at the same strip centres when it opens a window): no second sum.
  pure subroutine watch_set(w, t, xy, eta, grad)
    !> The watch, refreshed.
    type(surface_watch_type), intent(inout) :: w
    !> Time of the samples [s].
    real(wp), intent(in) :: t
    !> Per strip: its centre (x, y) (inertial) [m], the ramped elevation [m] and its
    !> gradient there.
    real(wp), intent(in) :: xy(:, :), eta(:), grad(:, :)
    integer :: k
    w%xy = xy
    w%eta = eta
    do k = 1, size(eta)
      w%slope(k) = norm2(grad(:, k))
    end do
    w%from_grid = .false.
    w%t = t
    w%valid = .true.
    w%kept_until = -huge(1.0_wp)
    w%window = [1.0_wp, 0.0_wp]
  end subroutine watch_set

  !> Bounds over a window [t1, t2] of the elevation and of the slope at the strips' points
  !> (those the last watch_set took; from the strips' slow clock, whose cubics with their
  !> remainder bound them: davit_boat_strip_grid's window_bounds). Inside the window they
  !> replace the Lipschitz growth from the sample, which in an irregular sea of 1300
  !> components (sum |a| w ~ 30 m/s) proved nothing dry within metres of the crests.
  pure subroutine watch_set_window(w, window, eta_up, slope_up)
    !> The watch.
    type(surface_watch_type), intent(inout) :: w
    !> The window [t1, t2] [s].
    real(wp), intent(in) :: window(2)
    !> Per strip: the bounds of the elevation [m] and of |grad eta| over the window.
    real(wp), intent(in) :: eta_up(:), slope_up(:)
    w%window = window
    w%eta_up = eta_up
    w%slope_up = slope_up
  end subroutine watch_set_window

  !> True only if no strip can touch the water at time t with the boat at (c, r).
  pure logical function surely_dry(w, s, t, c, r)
    !> The watch.
    type(surface_watch_type), intent(in) :: w
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    integer :: k
    surely_dry = .false.
    if (.not. w%valid) return
    surely_dry = hull_surely_dry(w, s, t, c, r)
    if (surely_dry) return
    do k = 1, s%hull%n
      if (.not. strip_surely_dry(w, s, k, t, c, r)) return
    end do
    surely_dry = .true.
  end function surely_dry

  !> True only if every strip is surely dry by strip_surely_dry's test with each strip's
  !> terms replaced by their largest over the strips (the surface's bound, the distance
  !> from the sampled point, the section's radius) and every section's corners by the
  !> lowest point of the hull's box: one test instead of one per strip, which implies
  !> theirs, for a hull hanging clear of the waves.
  pure logical function hull_surely_dry(w, s, t, c, r)
    !> The watch (valid).
    type(surface_watch_type), intent(in) :: w
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    real(wp) :: dist, radius, eta_up, lowest
    associate (h => s%hull)
      dist = sqrt(maxval((r(1) + c(1, 1)*h%x - w%xy(1, :))**2 + &
                         (r(2) + c(2, 1)*h%x - w%xy(2, :))**2))
      radius = hypot(0.5_wp*maxval(h%breadth), max(abs(h%keel), abs(h%keel - h%height)))
      eta_up = raised_surface(w, t, maxval(w%eta_up), maxval(w%slope_up), maxval(w%eta), &
                              maxval(w%slope), any(w%from_grid), dist, radius)
      ! the deepest point of the sections' box (z down): x at the ends, y at the widest
      lowest = r(3) + abs(c(3, 1))*maxval(abs(h%x)) + abs(c(3, 2))*0.5_wp*maxval(h%breadth) + &
               max(c(3, 3)*h%keel, c(3, 3)*(h%keel - h%height))
    end associate
    hull_surely_dry = lowest + eta_up <= 0.0_wp
  end function hull_surely_dry

  !> True only if strip k cannot touch the water at time t with the boat at (c, r).
  pure logical function strip_surely_dry(w, s, k, t, c, r)
    !> The watch.
    type(surface_watch_type), intent(in) :: w
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> Strip index.
    integer, intent(in) :: k
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    real(wp) :: p(3), eta_up, dist, radius
    type(section_wet_type) :: wet
    strip_surely_dry = .false.
    if (.not. w%valid) return
    p = r + c(:, 1)*s%hull%x(k)
    ! the tangent plane across the section: corners within R of the centre
    dist = norm2(p(1:2) - w%xy(:, k))
    radius = hypot(0.5_wp*s%hull%breadth(k), max(abs(s%hull%keel), &
                                                 abs(s%hull%keel - s%hull%height)))
    eta_up = raised_surface(w, t, w%eta_up(k), w%slope_up(k), w%eta(k), w%slope(k), &
                            w%from_grid(k), dist, radius)
    wet = section_immersion(s%hull, k, p(3) + eta_up, c(3, 2), c(3, 3))
    strip_surely_dry = wet%area <= 0.0_wp
  end function strip_surely_dry

  !> The highest the surface can stand at time t over a section whose centre is dist from
  !> the sampled point and whose corners are within radius of its centre (the tangent
  !> plane rises across it by at most |grad eta| radius): inside the window from the
  !> window's bounds (eta_w, slope_w), else from the sample (eta_s, slope_s, with the grid's
  !> error where it came from the grid) grown by the field's Lipschitz constants.
  pure real(wp) function raised_surface(w, t, eta_w, slope_w, eta_s, slope_s, on_grid, dist, &
                                        radius) result(eta_up)
    !> The watch.
    type(surface_watch_type), intent(in) :: w
    !> Time [s].
    real(wp), intent(in) :: t
    !> The window's bounds of the elevation [m] and of |grad eta| there, and the sample's.
    real(wp), intent(in) :: eta_w, slope_w, eta_s, slope_s
    !> Whether the sample came from the grid.
    logical, intent(in) :: on_grid
    !> Distance from the sampled point [m] and the section's radius [m].
    real(wp), intent(in) :: dist, radius
    real(wp) :: eta, slope, grid_error(2)
    if (t >= w%window(1) .and. t <= w%window(2)) then
      eta = eta_w
      slope = slope_w
    else
      grid_error = 0.0_wp
      if (on_grid) grid_error = w%grid_error
      eta = eta_s + grid_error(1) + w%rate_bound*abs(t - w%t)
      slope = slope_s + grid_error(2) + w%slope_rate_bound*abs(t - w%t)
    end if
    eta_up = eta + w%slope_bound*dist + radius*min(w%slope_bound, slope + w%curvature_bound*dist)
  end function raised_surface

end module davit_boat_surface_watch
