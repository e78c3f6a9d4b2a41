!> Slow clock of the water the boat's strips see (`&simulation wave_update`, irregular seas).
!>
!> In a 1300-component short-crested sea every strip load (eqs. 18-25) needs the elevation
!> at the strip centre and the water velocity at the wet centroid: 2 x 1300 sines per strip
!> and stage, 97 % of a launch once the boat is in the water. The water moves on the wave
!> time scale (periods of seconds), the strips by centimetres over a few hundredths of a
!> second, so the field is sampled on a slow window [t1, t2 = t1 + h] at reference points
!> (each strip's centre p_k and its wet centroid q_k at t1) and expanded:
!>   f(x, t) ~ H(t) + grad f(t) . (x - x_ref),
!> H the cubic Hermite interpolant of the reference value from its exact values and time
!> derivatives at t1 and t2, grad f (d/dx, d/dy, and for the velocity d/dd with d the
!> Wheeler-stretched depth) linear in time. The elevation at the strip centres also
!> carries its curvature (linear in time), and its slope is cubic in time: the slope sets
!> each section's tangent plane, so a slope held at x_ref, or linear in time, put its
!> error into the hydrostatic loads at first order (the Level 5 beam-sea launch of seed 2
!> was 0.57 % off in its peak sling tension at h = 0.1 s; with exact slopes 0.01 %). Per
!> component of amplitude a, frequency w and wavenumber k the error is at most
!> a [ (w h)^4/384 + (k |dx|)^2/2 + ... ] (velocity: times w; the elevation at the
!> centres (k |dx|)^3/6), |dx| the strip's travel since t1: ~1e-6 a at h = 0.05 s and
!> ~1e-3 a for the shortest components when the strip moves 5 cm. The ramp multiplies
!> exactly. Other stages, and regular and Stokes-2 seas, take the exact sums.
!> The pressure level's dynamic section load (davit_boat_strip_pressure: the pressure's
!> decay with depth and phase across the breadth) is sampled in the window as well, with its
!> time derivative and its first derivatives in the section's geometry (its immersion, its
!> travel, the tangent plane's slopes across it with the waterline's move along the hull's
!> sides, and its turn), Hermite-interpolated and expanded in the geometry's departure from
!> a path: the geometry of t1 carried on to t2 along the parabola through the section's
!> last two samples and t1's (a line with one; each end sampled for its own wet polygon;
!> with no earlier sample, t1's polygon at both ends). Held fixed, the geometry cost the
!> single-summation launch 0.6 % of its peak sling tension at h = 0.05 s and 1.5 % at
!> 0.1 s (a beam sea rolls the boat by degrees per window, and the surface's departure
!> from its tangent plane at the sides, a few cm, rides on the moving waterline);
!> expanded about t1's geometry 0.01 % and 0.3 % (doc/benchmarks/multirate.md).
!> The section loads keep windows of their own inside the clock's: at most max_load_span
!> long (the clock's interval split in equal parts), each renewed at the first accepted
!> step that reaches its end, along the path through its last samples
!> (strip_waves_renew_loads). A section dry at its last sample that wets takes the exact
!> sums until the next accepted step, which samples it over a quarter of that span, then
!> half, then the whole: at its onset a section's wet breadth grows like the square root
!> of its immersion (a round bilge), so the expansion in the immersion about a sliver
!> is poorest there. With the onsets sampled over the whole window the Level 5 beam-sea
!> launch of seed 2 lost 2.3 % of its peak sling tension at h = 0.3 s; on their own spans
!> 0.28 % (exact section loads: 0.24 %); split in two 0.42 % (renewed along a path
!> extrapolated from the window's start), so only windows over 0.3 s are split.
module davit_boat_strip_waves
  use davit_kinds, only: wp
  use davit_sea_wave_field, only: wave_field_type, wave_irregular, wave_ramp, rotation_phasors
  use davit_boat_hull, only: boat_hull_type, section_immersion, section_wet_type
  use davit_boat_strip_pressure, only: section_wave_loads
  use davit_core_slow_clock, only: slow_clock_type, clock_renewed
  use davit_core_hermite, only: hermite_weights
  use davit_boat_strip_sums, only: ne, nv, nep
  use davit_sea_wave_grid, only: wave_grid_type
  use davit_boat_strip_grid, only: window_elevations, window_kinematics, window_bounds
  implicit none
  private
  public :: strip_wave_cache_type, new_strip_wave_cache, strip_waves_open, strip_waves_sample
  public :: strip_waves_bounds
  public :: strip_waves_due, strip_waves_cover, strip_waves_renew_loads
  public :: cached_kinematics, cached_wave_load, cached_surface, strip_waves_surface

  type :: strip_wave_cache_type
    !> Whether the slow clock is on.
    logical :: enabled = .false.
    !> The slow clock (davit_core_slow_clock, rule clock_reach): window length h, the
    !> window [t1, t2] and whether it holds samples.
    type(slow_clock_type) :: clock
    !> Strips whose velocity is sampled in this window (those the hull may wet in it).
    logical, allocatable :: sampled(:)
    !> Reference points: strip centres (x, y) and wet centroids (x, y, stretched depth d0).
    real(wp), allocatable :: p(:, :), q(:, :)
    !> Unramped elevation terms at p, (nep, end, strip) (the surface near q is read from
    !> them too); velocity terms at q, (component, nv, end, strip).
    real(wp), allocatable :: ep(:, :, :), vq(:, :, :, :)
    !> Unramped dynamic section loads (F2, F3, M1) and their rates, (3, 2, end, strip), for
    !> the strips wet at t1 (`loaded`).
    real(wp), allocatable :: fk(:, :, :, :)
    !> Their first derivatives (load, parameter, end, strip) with respect to the section's
    !> geometry (davit_boat_strip_pressure's sens: immersion below its tangent plane, the
    !> centre's horizontal travel, the plane's slopes gy, gz across it, the horizontal
    !> parts of the rotation's columns b2, b3), and that geometry of each sampled strip at
    !> t1 (d0, gy, gz, c12, c22, c13, c23; the travel from p): the sections move in the
    !> window (heave, roll, the passing wave), so the load is expanded about the sampled
    !> geometry as the kinematics are about their reference points.
    real(wp), allocatable :: fd(:, :, :, :), g_ref(:, :)
    !> The geometry's path from t1k, G(t) = G1 + gv s + ga s^2/2 (s = t - t1k, G the nine
    !> parameters of sens: d0, x, y, gy, gz, c12, c22, c13, c23): velocity and acceleration
    !> through the section's last two samples and t1k's (zero where there are none), so the
    !> expansion covers the departure from that path, not the whole move.
    real(wp), allocatable :: gv(:, :), ga(:, :)
    !> The sample before t1k's, (nine parameters, strip), and its time [s] (-huge: none).
    real(wp), allocatable :: g_prev(:, :), t_prev(:)
    !> The loads' reference centre at their window's start (x, y) [m] and that start t1k
    !> [s]: the window's t1, the step that renewed the load window, or the step at which a
    !> section dry at its last sample got wet.
    real(wp), allocatable :: p_load(:, :), t_load(:)
    !> The end of each strip's load window [s]: at most load_span after t_load.
    real(wp), allocatable :: t_end(:)
    !> Length of the section loads' windows [s]: the clock's interval in equal parts of at
    !> most max_load_span.
    real(wp) :: load_span = 0.0_wp
    !> sum |a| w^4 and sum |a| k w^4 over the components: the fourth time derivatives'
    !> bounds of the elevation and of a slope component (strip_waves_bounds).
    real(wp) :: quartic(2) = 0.0_wp
    !> Whether the window just opened follows one (the path history of its samples holds).
    logical :: continued = .false.
    !> Per component, cos(w s) and sin(w s) of the load span s.
    real(wp), allocatable :: crl(:), srl(:)
    !> Per strip, whether its samples were taken (it was possibly wet).
    logical, allocatable :: loaded(:)
    !> Per component, cos(w h) and sin(w h): the window's far end from its near end by
    !> angle addition, one sine and cosine per component for both ends.
    real(wp), allocatable :: cr(:), sr(:)
  end type strip_wave_cache_type

  !> The longest window of the section loads [s]: the 12 double-summation launches of
  !> doc/benchmarks/multirate.md keep their peak sling tensions within 0.28 % on one 0.3 s
  !> load window (0.42 % split in two); on one 0.4 s window 0.88 % (0.81 % in two).
  real(wp), parameter :: max_load_span = 0.3_wp
  !> A section that wets starts on this part of the load span, doubled at each renewal.
  real(wp), parameter :: onset_part = 0.25_wp

contains

  !> A cache for n strips on the slow clock `clock` (rule clock_reach); enabled only for
  !> irregular seas and a running clock.
  pure function new_strip_wave_cache(field, n, clock) result(cache)
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Number of strips.
    integer, intent(in) :: n
    !> The strips' slow clock (its window length h; not running: off).
    type(slow_clock_type), intent(in) :: clock
    type(strip_wave_cache_type) :: cache
    cache%clock = clock
    cache%enabled = clock%enabled() .and. field%kind == wave_irregular
    if (.not. cache%enabled) return
    allocate (cache%p(2, n), cache%q(3, n), cache%ep(nep, 2, n), &
              cache%vq(3, nv, 2, n), cache%sampled(n), cache%fk(3, 2, 2, n), cache%loaded(n), &
              cache%fd(3, 9, 2, n), cache%g_ref(7, n), cache%gv(9, n), cache%ga(9, n), &
              cache%g_prev(9, n), cache%t_prev(n), cache%p_load(2, n), cache%t_load(n), &
              cache%t_end(n))
    allocate (cache%cr(field%n), cache%sr(field%n), cache%crl(field%n), cache%srl(field%n))
    call rotation_phasors(field, clock%interval, cache%cr, cache%sr)
    cache%load_span = clock%interval/real(ceiling(clock%interval/max_load_span - 1.0e-9_wp), wp)
    call rotation_phasors(field, cache%load_span, cache%crl, cache%srl)
    cache%quartic = [sum(abs(field%amplitude)*field%omega**4), &
                     sum(abs(field%amplitude)*field%k*field%omega**4)]
    cache%sampled = .false.
    cache%loaded = .false.
    cache%t_prev = -huge(1.0_wp)
  end function new_strip_wave_cache

  !> After a step ending at t: true when the window should be renewed (the next step may
  !> leave it); records t.
  pure subroutine strip_waves_due(cache, t, due)
    !> The strips' window.
    type(strip_wave_cache_type), intent(inout) :: cache
    !> Time [s].
    real(wp), intent(in) :: t
    !> Whether t has left the window and it must be refreshed.
    logical, intent(out) :: due
    integer :: action
    call cache%clock%tick(t, action)
    due = action == clock_renewed .and. cache%enabled
  end subroutine strip_waves_due

  !> True when a stage at time t may use the cache.
  pure logical function strip_waves_cover(cache, t)
    !> The strips' window.
    type(strip_wave_cache_type), intent(in) :: cache
    !> Time [s].
    real(wp), intent(in) :: t
    strip_waves_cover = cache%clock%covers(t)
  end function strip_waves_cover

  !> New window [t, t + h] for the boat at (c, r): the elevation terms at both ends at
  !> every strip centre (every stage needs them to find the wet sections; the surface
  !> watch takes its bounds from them, strip_waves_bounds). strip_waves_sample then
  !> samples the strips the hull may wet. With the grids (`&sea kinematics = 'grid'`),
  !> the elevation terms come from `surface` wherever it holds the point.
  pure subroutine strip_waves_open(cache, hull, field, t, c, r, surface)
    !> The strips' window, opened.
    type(strip_wave_cache_type), intent(inout) :: cache
    !> The hull.
    type(boat_hull_type), intent(in) :: hull
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Window start [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> Precomputed grid of the surface (absent: the sea itself).
    type(wave_grid_type), intent(in), optional :: surface
    integer :: k
    if (.not. cache%enabled) return
    ! the sections' geometry is carried on along its path through its last samples (those
    ! of the windows just ending, each at most two windows before the next)
    cache%continued = cache%clock%valid
    call cache%clock%open(t)
    do k = 1, hull%n
      cache%p(:, k) = r(1:2) + c(1:2, 1)*hull%x(k)
    end do
    call window_elevations(field, cache%clock%window, cache%cr, cache%sr, cache%p, &
                           hull%thickness*c(1:2, 1), cache%ep, surface)
    cache%sampled = .false.
  end subroutine strip_waves_open

  !> Sample the window just opened at the strips in `maybe_wet` (a strip the surface watch
  !> proves dry over the window needs none; should it get wet after all, its stages take
  !> the exact sums): the section loads, and the velocity at the wet centroids of the
  !> sections at t (the keel line of a dry section, where it would first get wet); from
  !> the grid `volume` wherever it holds the point.
  pure subroutine strip_waves_sample(cache, hull, field, c, r, maybe_wet, volume)
    !> The strips' window, opened at the boat's pose (c, r).
    type(strip_wave_cache_type), intent(inout) :: cache
    !> The hull.
    type(boat_hull_type), intent(in) :: hull
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Rotation b -> inertial, CG position (inertial) [m] at the window's start.
    real(wp), intent(in) :: c(3, 3), r(3)
    !> Per strip, whether it may be wet in the window (only those are sampled).
    logical, intent(in) :: maybe_wet(:)
    !> Precomputed grid of the water below the surface (absent: the sea itself).
    type(wave_grid_type), intent(in), optional :: volume
    type(section_wet_type) :: wet
    real(wp) :: p(3), q(3), eta, ramp, t
    logical :: history(2, hull%n)
    integer :: k
    if (.not. cache%enabled) return
    t = cache%clock%window(1)
    history = .false.
    if (cache%continued) then
      do k = 1, hull%n
        history(:, k) = path_history(cache, k, t)
      end do
    end if
    ramp = wave_ramp(field, t)
    cache%sampled = maybe_wet
    cache%loaded = .false.
    do k = 1, hull%n
      if (.not. maybe_wet(k)) cycle
      p = r + c(:, 1)*hull%x(k)
      eta = ramp*cache%ep(1, 1, k)
      call sample_section_load(cache, hull, field, k, c, p, ramp, history(:, k))
      wet = section_immersion(hull, k, p(3) + eta, c(3, 2), c(3, 3))
      if (wet%area > 0.0_wp) then
        q = r + matmul(c, [hull%x(k), wet%centroid])
      else
        q = r + matmul(c, [hull%x(k), 0.0_wp, hull%keel])
      end if
      eta = ramp*(cache%ep(1, 1, k) + sum(cache%ep(3:4, 1, k)*(q(1:2) - p(1:2))))
      cache%q(:, k) = [q(1), q(2), max(0.0_wp, q(3) + eta)]
      call window_kinematics(field, cache%clock%window, cache%cr, cache%sr, q(1), q(2), &
                             cache%q(3, k), cache%vq(:, :, :, k), volume)
    end do
  end subroutine strip_waves_sample

  !> Upper bounds over the window just opened of the ramped elevation and of the slope's
  !> size at each strip centre (davit_boat_strip_grid's window_bounds).
  pure subroutine strip_waves_bounds(cache, field, eta_up, slope_up)
    !> The strips' window.
    type(strip_wave_cache_type), intent(in) :: cache
    !> The sea (its start-up ramp).
    type(wave_field_type), intent(in) :: field
    !> Per strip: the bounds of the elevation [m] and of |grad eta| over the window.
    real(wp), intent(out) :: eta_up(:), slope_up(:)
    call window_bounds(field, cache%clock%window, cache%ep, cache%quartic, eta_up, slope_up)
  end subroutine strip_waves_bounds

  !> After an accepted step at t inside the window: renew the load window of each strip
  !> that reached its end (the next as long again, at most load_span), and sample each
  !> strip whose velocity the window holds, dry at its last sample and wet now, over
  !> onset_part of load_span (its stages took the exact sums until now). The geometry
  !> comes from the window's surface at the strip's centre.
  pure subroutine strip_waves_renew_loads(cache, hull, field, t, c, r)
    !> The strips' window.
    type(strip_wave_cache_type), intent(inout) :: cache
    !> The hull.
    type(boat_hull_type), intent(in) :: hull
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Time of the accepted step [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    real(wp) :: p(3), slope(2), grad(3), eta, span
    logical :: history(2)
    integer :: k
    if (.not. (cache%enabled .and. cache%clock%covers(t))) return
    do k = 1, hull%n
      if (.not. cache%sampled(k)) cycle
      span = onset_part*cache%load_span
      if (cache%loaded(k)) then
        if (t < cache%t_end(k) - 1.0e-9_wp) cycle
        span = min(2.0_wp*(cache%t_end(k) - cache%t_load(k)), cache%load_span)
      end if
      history = path_history(cache, k, t)
      ! too close to the window's end: the few stages left run on or take the exact sums
      if (cache%clock%window(2) - t < 0.25_wp*span) cycle
      p = r + c(:, 1)*hull%x(k)
      call cached_surface(cache, field, k, t, p(1), p(2), eta, slope)
      grad = c(3, :) + slope(1)*c(1, :) + slope(2)*c(2, :)
      call sample_path(cache, hull, field, k, [t, load_end(cache, t, span)], .false., p, &
                       [p(3) + eta, grad(2), grad(3), c(1:2, 2), c(1:2, 3)], history)
    end do
  end subroutine strip_waves_renew_loads

  !> Whether strip k's geometry at t has a path through its samples: its last one (loaded,
  !> before t) and the one before that, each at most two intervals before the next.
  pure function path_history(cache, k, t) result(history)
    type(strip_wave_cache_type), intent(in) :: cache
    integer, intent(in) :: k
    real(wp), intent(in) :: t
    logical :: history(2)
    associate (reach => 2.0_wp*cache%clock%interval, t1 => cache%t_load(k))
      history(1) = cache%loaded(k) .and. t > t1 .and. t - t1 <= reach
      history(2) = history(1) .and. cache%t_prev(k) < t1 .and. t1 - cache%t_prev(k) <= reach
    end associate
  end function path_history

  !> End of a load window of at most span from t: the clock's window's end where it is
  !> that close, half way to it where less than half a span would be left after a span.
  pure real(wp) function load_end(cache, t, span) result(t_end)
    type(strip_wave_cache_type), intent(in) :: cache
    real(wp), intent(in) :: t, span
    real(wp) :: rest
    rest = cache%clock%window(2) - t
    if (rest <= span + 1.0e-9_wp) then
      t_end = cache%clock%window(2)
    else if (rest < 1.5_wp*span) then
      t_end = t + 0.5_wp*rest
    else
      t_end = t + span
    end if
  end function load_end

  !> The ramped elevation and its gradient at the strip centres at the window's start, as
  !> sampled by the last refresh (exact sums: the surface watch takes them).
  pure subroutine strip_waves_surface(cache, field, xy, eta, grad)
    !> The strips' window.
    type(strip_wave_cache_type), intent(in) :: cache
    !> The sea (its start-up ramp).
    type(wave_field_type), intent(in) :: field
    !> Per strip: centre (x, y) (inertial) [m], elevation [m] and its gradient.
    real(wp), intent(out) :: xy(:, :), eta(:), grad(:, :)
    real(wp) :: ramp
    ramp = wave_ramp(field, cache%clock%window(1))
    xy = cache%p
    eta = ramp*cache%ep(1, 1, :)
    grad = ramp*cache%ep(3:4, 1, :)
  end subroutine strip_waves_surface

  !> Dynamic section load of strip k (centre p) at both ends of the window: for its wet
  !> polygon under the tangent plane at t1 and, where the section was sampled in the last
  !> window (rate > 0), for the geometry carried on to t2 at the rate it changed since
  !> then (each end with its own polygon); else for t1's polygon at both ends.
  pure subroutine sample_section_load(cache, hull, field, k, c, p, ramp, history)
    type(strip_wave_cache_type), intent(inout) :: cache
    type(boat_hull_type), intent(in) :: hull
    type(wave_field_type), intent(in) :: field
    integer, intent(in) :: k
    real(wp), intent(in) :: c(3, 3), p(3), ramp
    logical, intent(in) :: history(2)
    real(wp) :: grad(3), g1(7)
    grad = c(3, :) + ramp*(cache%ep(3, 1, k)*c(1, :) + cache%ep(4, 1, k)*c(2, :))
    g1 = [p(3) + ramp*cache%ep(1, 1, k), grad(2), grad(3), c(1:2, 2), c(1:2, 3)]
    call sample_path(cache, hull, field, k, cache%clock%window(1) + [0.0_wp, cache%load_span], &
                     .true., p, g1, history)
  end subroutine sample_section_load

  !> Strip k's section load on `window` (its start t1k and end; `whole`: a window of
  !> load_span, whose far end's phases are the near end's turned) for the
  !> geometry g1 with centre p at t1k, and at the far end for that geometry carried on
  !> along its path: through its last sample (history(1): linear) and the one before
  !> (history(2): quadratic), each end with its own wet polygon; with no history, or the
  !> carried polygon dry, t1k's polygon at both ends.
  pure subroutine sample_path(cache, hull, field, k, window, whole, p, g1, history)
    type(strip_wave_cache_type), intent(inout) :: cache
    type(boat_hull_type), intent(in) :: hull
    type(wave_field_type), intent(in) :: field
    integer, intent(in) :: k
    real(wp), intent(in) :: window(2), p(3), g1(7)
    logical, intent(in) :: whole, history(2)
    type(section_wet_type) :: wet, wet2
    real(wp) :: load(3, 2), rate_t(3, 2), g(9), g2(9), g_old(9), v(9), a(9), c(3, 3), h
    integer :: j
    h = window(2) - window(1)
    g = [g1(1), p(1:2), g1(2:7)]
    g_old = [cache%g_ref(1, k), cache%p_load(:, k), cache%g_ref(2:7, k)]
    call path_rates(g, window(1), g_old, cache%t_load(k), cache%g_prev(:, k), cache%t_prev(k), &
                    history, v, a)
    g2 = g + v*h + 0.5_wp*a*h**2
    ! the samples' history moves on (the sample of t1k's window becomes the one before)
    cache%t_prev(k) = merge(cache%t_load(k), -huge(1.0_wp), history(1))
    cache%g_prev(:, k) = g_old
    cache%loaded(k) = .false.
    wet = section_immersion(hull, k, g(1), g(4), g(5))
    if (wet%area <= 0.0_wp) return
    wet2 = wet
    if (history(1)) wet2 = section_immersion(hull, k, g2(1), g2(4), g2(5))
    ! the lags read only the horizontal parts of b2 and b3
    c = 0.0_wp
    c(1:2, 2) = g(6:7)
    c(1:2, 3) = g(8:9)
    if (.not. history(1) .or. wet2%area <= 0.0_wp) then
      v = 0.0_wp
      a = 0.0_wp
      if (whole) then
        ! both ends in one pass: they share the edge integrals, only the phase differs
        call section_wave_loads(field, window, hull, wet, c, p, g(1), g(4), g(5), load, &
                                rate_t, cache%crl, cache%srl, cache%fd(:, :, :, k))
      else
        call section_wave_loads(field, window, hull, wet, c, p, g(1), g(4), g(5), load, &
                                rate_t, sens=cache%fd(:, :, :, k))
      end if
    else
      call section_wave_loads(field, window(1:1), hull, wet, c, p, g(1), g(4), g(5), &
                              load(:, 1:1), rate_t(:, 1:1), sens=cache%fd(:, :, 1:1, k))
      c(1:2, 2) = g2(6:7)
      c(1:2, 3) = g2(8:9)
      call section_wave_loads(field, window(2:2), hull, wet2, c, [g2(2:3), p(3)], g2(1), &
                              g2(4), g2(5), load(:, 2:2), rate_t(:, 2:2), &
                              sens=cache%fd(:, :, 2:2, k))
    end if
    ! the rates along the path: d/dt at fixed geometry plus the geometry's own change
    do j = 1, 2
      cache%fk(:, 1, j, k) = load(:, j)
      cache%fk(:, 2, j, k) = rate_t(:, j) + matmul(cache%fd(:, :, j, k), v + (j - 1)*h*a)
    end do
    cache%g_ref(:, k) = g1
    cache%p_load(:, k) = p(1:2)
    cache%gv(:, k) = v
    cache%ga(:, k) = a
    cache%t_load(k) = window(1)
    cache%t_end(k) = window(2)
    cache%loaded(k) = .true.
  end subroutine sample_path

  !> The geometry's path at t through its samples g_old at t_old (history(1)) and g_pp at
  !> t_pp (history(2)): velocity v and acceleration a of the line or the parabola through
  !> them and g (zero without history).
  pure subroutine path_rates(g, t, g_old, t_old, g_pp, t_pp, history, v, a)
    real(wp), intent(in) :: g(9), t, g_old(9), t_old, g_pp(9), t_pp
    logical, intent(in) :: history(2)
    real(wp), intent(out) :: v(9), a(9)
    real(wp) :: d1(9), d2(9)
    v = 0.0_wp
    a = 0.0_wp
    if (.not. history(1)) return
    d1 = (g_old - g)/(t_old - t)
    v = d1
    if (.not. history(2)) return
    ! q(s) = g + v s + a s^2/2 through (t_old - t, g_old) and (t_pp - t, g_pp)
    d2 = (g_pp - g)/(t_pp - t)
    a = 2.0_wp*(d1 - d2)/(t_old - t_pp)
    v = d1 - 0.5_wp*a*(t_old - t)
  end subroutine path_rates

  !> Elevation [m] and slope (d eta/dx, d eta/dy) at the horizontal point (x, y) near strip
  !> k's centre at time t (surface_terms, ramped).
  pure subroutine cached_surface(cache, field, k, t, x, y, eta, slope)
    !> The strips' window.
    type(strip_wave_cache_type), intent(in) :: cache
    !> The sea (its start-up ramp).
    type(wave_field_type), intent(in) :: field
    !> Strip index.
    integer, intent(in) :: k
    !> Time [s] and horizontal position (inertial) [m].
    real(wp), intent(in) :: t, x, y
    !> Elevation [m] and slope [-].
    real(wp), intent(out) :: eta, slope(2)
    real(wp) :: ramp
    call surface_terms(cache, k, cache%clock%weights(t), window_fraction(cache, t), x, y, &
                       eta, slope)
    ramp = wave_ramp(field, t)
    eta = ramp*eta
    slope = ramp*slope
  end subroutine cached_surface

  !> Unramped elevation and slope at (x, y) near strip k's centre, at the time of the
  !> Hermite weights hw and window fraction lam: value, slope and their rates cubic in
  !> time, the curvature linear in time, expanded to second order in the offset.
  pure subroutine surface_terms(cache, k, hw, lam, x, y, eta, slope)
    type(strip_wave_cache_type), intent(in) :: cache
    integer, intent(in) :: k
    real(wp), intent(in) :: hw(4), lam, x, y
    real(wp), intent(out) :: eta, slope(2)
    real(wp) :: dx(2), g(2), hv(3), hdx(2)
    dx = [x, y] - cache%p(:, k)
    associate (e => cache%ep(:, :, k))
      g = hw(1)*e(3:4, 1) + hw(2)*e(8:9, 1) + hw(3)*e(3:4, 2) + hw(4)*e(8:9, 2)
      hv = (1.0_wp - lam)*e(5:7, 1) + lam*e(5:7, 2)
      hdx = [hv(1)*dx(1) + hv(2)*dx(2), hv(2)*dx(1) + hv(3)*dx(2)]
      eta = hw(1)*e(1, 1) + hw(2)*e(2, 1) + hw(3)*e(1, 2) + hw(4)*e(2, 2) + &
            dot_product(g, dx) + 0.5_wp*dot_product(dx, hdx)
    end associate
    slope = g + hdx
  end subroutine surface_terms

  !> Elevation and water velocity (inertial, z down; zero above the surface) at the point
  !> pt near strip k's wet centroid at time t, as wave_kinematics gives them.
  pure subroutine cached_kinematics(cache, field, k, t, pt, eta, velocity)
    !> The strips' window.
    type(strip_wave_cache_type), intent(in) :: cache
    !> The sea (when the window does not hold strip k).
    type(wave_field_type), intent(in) :: field
    !> Strip index.
    integer, intent(in) :: k
    !> Time [s] and the point (inertial) [m].
    real(wp), intent(in) :: t, pt(3)
    !> Surface elevation [m] and the water velocity at the point, inertial [m/s].
    real(wp), intent(out) :: eta, velocity(3)
    real(wp) :: hw(4), lam, ramp, dx(3), slope(2)
    integer :: i
    hw = cache%clock%weights(t)
    lam = window_fraction(cache, t)
    ramp = wave_ramp(field, t)
    dx(1:2) = pt(1:2) - cache%q(1:2, k)
    ! the surface from the strip centre's terms (second order in the offset)
    call surface_terms(cache, k, hw, lam, pt(1), pt(2), eta, slope)
    eta = ramp*eta
    velocity = 0.0_wp
    if (pt(3) + eta < 0.0_wp) return
    dx(3) = pt(3) + eta - cache%q(3, k)
    associate (v => cache%vq(:, :, :, k))
      do i = 1, 3
        velocity(i) = ramp*(hw(1)*v(i, 1, 1) + hw(2)*v(i, 2, 1) + hw(3)*v(i, 1, 2) + &
                            hw(4)*v(i, 2, 2) + &
                            sum(((1.0_wp - lam)*v(i, 3:5, 1) + lam*v(i, 3:5, 2))*dx))
      end do
    end associate
  end subroutine cached_kinematics

  !> Dynamic section load (F2, F3, M1) of strip k at time t from the window (found), or
  !> found = .false. where the strip was dry at t1.
  pure subroutine cached_wave_load(cache, field, k, t, g, pc, load, found)
    !> The strips' window.
    type(strip_wave_cache_type), intent(in) :: cache
    !> The sea.
    type(wave_field_type), intent(in) :: field
    !> Strip index.
    integer, intent(in) :: k
    !> Time [s]; the section's geometry now: the strip centre's depth below its tangent
    !> plane [m], the plane's slopes across the section and the horizontal parts of the
    !> rotation's columns b2, b3 (d0, gy, gz, c12, c22, c13, c23); the centre's horizontal
    !> position now (inertial) [m].
    real(wp), intent(in) :: t, g(7), pc(2)
    !> The section's pressure load per unit length, boat frame [N/m].
    real(wp), intent(out) :: load(3)
    !> Whether the window holds the load of strip k.
    logical, intent(out) :: found
    real(wp) :: hw(4), dg(9), lam, gr(9), span(2), sk
    load = 0.0_wp
    found = cache%loaded(k)
    if (.not. found) return
    ! the strip's own window; a stage past its end (the step that reaches it) runs on by at
    ! most half its length, further ones take the exact sums
    span = [cache%t_load(k), cache%t_end(k)]
    found = t <= span(2) + 0.5_wp*(span(2) - span(1))
    if (.not. found) return
    hw = hermite_weights(span, t)
    lam = (t - span(1))/(span(2) - span(1))
    ! the section's displacement from the sampled geometry (deeper, moved, tilted, turned);
    ! the derivatives, like the gradients of the kinematics, linear in time (those of t1
    ! alone leave the water's own move times the window's time in the error: first order)
    sk = t - span(1)
    gr = [cache%g_ref(1, k), cache%p_load(:, k), cache%g_ref(2:7, k)] + cache%gv(:, k)*sk + &
         0.5_wp*cache%ga(:, k)*sk**2
    dg = [g(1), pc, g(2:7)] - gr
    associate (f => cache%fk(:, :, :, k), s => cache%fd(:, :, :, k))
      load = wave_ramp(field, t)*(hw(1)*f(:, 1, 1) + hw(2)*f(:, 2, 1) + hw(3)*f(:, 1, 2) + &
                                  hw(4)*f(:, 2, 2) + &
                                  matmul((1.0_wp - lam)*s(:, :, 1) + lam*s(:, :, 2), dg))
    end associate
  end subroutine cached_wave_load

  !> Where t lies in the window, (t - t1)/(t2 - t1): the weight of the far end in the
  !> gradient terms, which are linear in time.
  pure real(wp) function window_fraction(cache, t) result(lam)
    type(strip_wave_cache_type), intent(in) :: cache
    real(wp), intent(in) :: t
    associate (w => cache%clock%window)
      lam = (t - w(1))/(w(2) - w(1))
    end associate
  end function window_fraction

end module davit_boat_strip_waves
