!> Slow clock of the water at the boat's strips (davit_boat_strip_waves) against the exact
!> sums of the wave field: the cubic Hermite time error bound and its fourth order, the
!> first-order spatial expansion's second-order remainder, the window's far end (turned
!> from its near end) against the sums evaluated there, and the coupled boat in an
!> irregular sea with and without the clock.
module test_strip_waves
  use davit_kinds, only: wp, pi
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_core_random, only: rng_type, new_rng
  use davit_core_rotation, only: rotation_matrix
  use davit_sea_wave_field, only: wave_field_type, new_irregular_sea, wave_elevation, &
                                  wave_kinematics
  use davit_boat_hull, only: boat_hull_type, new_boat_hull, section_wet_type, section_immersion
  use davit_boat_strip_pressure, only: section_wave_load, surface_plane
  use davit_core_slow_clock, only: new_slow_clock, clock_reach
  use davit_boat_strip_waves, only: strip_wave_cache_type, new_strip_wave_cache, &
                                    strip_waves_open, strip_waves_sample, &
                                    cached_kinematics, &
                                    strip_waves_surface, cached_wave_load, cached_surface, &
                                    strip_waves_renew_loads
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, drop_cg
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_strip_waves, level5_sea, afloat

contains

  function collect_strip_waves() result(suite)
    type(suite_type) :: suite
    suite%name = "strip_waves"
    suite%cases = [new_case("hermite_time_error_bound_and_order4", time_order), &
                   new_case("spatial_expansion_remainder_orders", space_order), &
                   new_case("window_far_end_equals_sums_there", far_end), &
                   new_case("window_section_loads_follow_the_moved_hull", moved_hull), &
                   new_case("slope_cubic_in_time_and_curved_in_space", slope_orders), &
                   new_case("window_section_loads_follow_the_hull_path", hull_path), &
                   new_case("window_samples_sections_that_wet_later", catch_up), &
                   new_case("section_loads_renewed_in_their_own_windows", own_windows), &
                   new_case("coupled_boat_with_and_without_clock", coupled_boat)]
  end function collect_strip_waves

  !> Level 5 short-crested sea (H = 4 m, 100 x 13 components, no ramp).
  subroutine level5_sea(field)
    type(wave_field_type), intent(out) :: field
    type(rng_type) :: rng
    rng = new_rng(7)
    call new_irregular_sea(field, 4.0_wp, 0.5_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, &
                           .true., .true., rng, 0.0_wp)
  end subroutine level5_sea

  !> Boat of the paper (11.5 x 2.8 m, 20 strips), CG 1.5 m below the still water (in a 4 m sea).
  subroutine afloat(hull, c, r)
    type(boat_hull_type), intent(out) :: hull
    real(wp), intent(out) :: c(3, 3), r(3)
    hull = new_boat_hull(11.5_wp, 2.8_wp, 3.0_wp, 1.0_wp, 4.3_wp, 20)
    c = rotation_matrix([0.05_wp, -0.03_wp, 0.4_wp])
    r = [3.0_wp, -2.0_wp, 1.5_wp]
  end subroutine afloat

  !> Largest error of the cached elevation at the strip centres and of the velocity at
  !> the wet-centroid references displaced by dx, at time t.
  subroutine max_errors(cache, field, hull, c, r, t, dx, err_eta, err_v)
    type(strip_wave_cache_type), intent(in) :: cache
    type(wave_field_type), intent(in) :: field
    type(boat_hull_type), intent(in) :: hull
    real(wp), intent(in) :: c(3, 3), r(3), t, dx(3)
    real(wp), intent(out) :: err_eta, err_v
    real(wp) :: p(3), pt(3), eta, eta_x, v(3), v_x(3), a(3), pw, slope(2)
    integer :: k, nwet
    err_eta = 0.0_wp
    nwet = 0
    err_v = 0.0_wp
    do k = 1, hull%n
      p = r + c(:, 1)*hull%x(k) + dx
      call cached_surface(cache, field, k, t, p(1), p(2), eta, slope)
      err_eta = max(err_eta, abs(eta - wave_elevation(field, t, p(1), p(2))))
      ! a point below the surface at the reference's stretched depth, shifted by dx (not
      ! at references on the surface, where Wheeler's zero above it is a jump)
      if (cache%q(3, k) < 0.05_wp) cycle
      nwet = nwet + 1
      pt = [cache%q(1, k), cache%q(2, k), 0.0_wp] + dx
      pt(3) = cache%q(3, k) + dx(3) - wave_elevation(field, t, pt(1), pt(2))
      call cached_kinematics(cache, field, k, t, pt, eta, v)
      call wave_kinematics(field, t, pt, eta_x, v_x, a, pw)
      err_v = max(err_v, norm2(v - v_x))
    end do
    if (nwet < hull%n/2) err_v = huge(1.0_wp)
  end subroutine max_errors

  !> Strips at rest: only the time interpolation errs. Cubic Hermite on [t1, t1 + h]:
  !> |f - H| <= h^4/384 max|f''''|, and per component |eta''''| <= a w^4, |v''''| <= a w^5
  !> (v = a w e^{-kd} ...). Halving h divides the error by ~16.
  subroutine time_order(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    real(wp) :: c(3, 3), r(3), h, e_eta(2), e_v(2), bound_eta, bound_v
    integer :: i, k
    call level5_sea(field)
    call afloat(hull, c, r)
    do i = 1, 2
      h = 0.4_wp/real(2**i, wp)
      cache = new_strip_wave_cache(field, hull%n, new_slow_clock(h, clock_reach))
      call refresh(cache, hull, field, 20.0_wp, c, r)
      call max_errors(cache, field, hull, c, r, 20.0_wp + 0.37_wp*h, [0.0_wp, 0.0_wp, 0.0_wp], &
                      e_eta(i), e_v(i))
      bound_eta = h**4/384*sum(field%amplitude*field%omega**4)
      bound_v = h**4/384*sum(field%amplitude*field%omega**5)
      call check_true(state, e_eta(i) <= bound_eta, "eta error within h^4/384 sum a w^4")
      call check_true(state, e_v(i) <= bound_v, "velocity error within h^4/384 sum a w^5")
    end do
    call note(state, "eta error at h = 0.1 s (m)", e_eta(2))
    call note(state, "velocity error at h = 0.1 s (m/s)", e_v(2))
    call check(state, log(e_eta(1)/e_eta(2))/log(2.0_wp), 4.0_wp, "eta order in h", &
               abs_tol=0.5_wp)
    call check(state, log(e_v(1)/e_v(2))/log(2.0_wp), 4.0_wp, "velocity order in h", &
               abs_tol=0.5_wp)
  end subroutine time_order

  !> Strips moved by dx at the window start (no time error): the elevation at the strip
  !> centres carries its curvature, so its remainder is third order, <= sum a k^3 |dx|^3/6
  !> (|dx| horizontal; halving dx divides it by ~8); the velocity's first-order expansion
  !> leaves <= sum a w k^2 (|dx_h| + |dd|)^2/2 (e^{-kd} <= 1), divided by ~4.
  subroutine space_order(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    real(wp) :: c(3, 3), r(3), dx(3), e_eta(2), e_v(2), bound_eta, bound_v, dh
    integer :: i, k
    call level5_sea(field)
    call afloat(hull, c, r)
    cache = new_strip_wave_cache(field, hull%n, new_slow_clock(0.05_wp, clock_reach))
    call refresh(cache, hull, field, 20.0_wp, c, r)
    do i = 1, 2
      dx = [0.08_wp, -0.06_wp, 0.04_wp]/real(i, wp)
      call max_errors(cache, field, hull, c, r, 20.0_wp, dx, e_eta(i), e_v(i))
      dh = norm2(dx(1:2))
      bound_eta = dh**3/6.0_wp*sum(field%amplitude*field%k**3)
      bound_v = 0.5_wp*(dh + abs(dx(3)))**2*sum(field%amplitude*field%omega*field%k**2)
      call check_true(state, e_eta(i) <= bound_eta, "eta remainder within sum a k^3 dx^3/6")
      call check_true(state, e_v(i) <= bound_v, "velocity remainder within its bound")
    end do
    call note(state, "eta error at |dx| = 5 cm (m)", e_eta(2))
    call note(state, "velocity error at |dx| = 5 cm (m/s)", e_v(2))
    call check(state, log(e_eta(1)/e_eta(2))/log(2.0_wp), 3.0_wp, "eta order in dx", &
               abs_tol=0.4_wp)
    call check(state, log(e_v(1)/e_v(2))/log(2.0_wp), 2.0_wp, "velocity order in dx", &
               abs_tol=0.3_wp)
  end subroutine space_order

  !> One pass samples both ends of a window: the far end's phases are the near end's turned
  !> by w h (angle addition), the sums run in vector lanes. At t2 = t1 + h the Hermite
  !> interpolant returns the far end's samples, which must be the sums evaluated at t2 by
  !> the wave field (its own phases and sines, summed one by one) to rounding: elevation
  !> at every strip centre, velocity at the wet references, each wet section's pressure
  !> load (section_wave_load at t2 alone, its phases from the sine); and the elevation
  !> handed to the surface watch is the field's at t1.
  subroutine far_end(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    type(section_wet_type) :: wet
    real(wp) :: c(3, 3), r(3), t2, p(3), pt(3), eta, eta_x, v(3), v_x(3), a(3), pw
    real(wp) :: err_eta, err_v, err_load, err_watch, scale, grad(3), d0, load(3), rate(3)
    real(wp) :: xy(2, 20), eta1(20), grad1(2, 20), slope(2)
    integer :: k, nload
    call level5_sea(field)
    call afloat(hull, c, r)
    cache = new_strip_wave_cache(field, hull%n, new_slow_clock(0.05_wp, clock_reach))
    call refresh(cache, hull, field, 20.0_wp, c, r)
    t2 = cache%clock%window(2)
    err_eta = 0.0_wp
    err_v = 0.0_wp
    err_load = 0.0_wp
    scale = 0.0_wp
    nload = 0
    call strip_waves_surface(cache, field, xy, eta1, grad1)
    err_watch = 0.0_wp
    do k = 1, hull%n
      p = r + c(:, 1)*hull%x(k)
      err_watch = max(err_watch, abs(eta1(k) - wave_elevation(field, 20.0_wp, p(1), p(2))))
      call cached_surface(cache, field, k, t2, p(1), p(2), eta, slope)
      err_eta = max(err_eta, abs(eta - wave_elevation(field, t2, p(1), p(2))))
      if (cache%q(3, k) < 0.05_wp) cycle
      ! the reference's stretched depth below the window's surface and the sums'
      pt = [cache%q(1, k), cache%q(2, k), 0.0_wp]
      call cached_surface(cache, field, k, t2, pt(1), pt(2), eta, slope)
      pt(3) = cache%q(3, k) - eta
      call cached_kinematics(cache, field, k, t2, pt, eta, v)
      pt(3) = cache%q(3, k) - wave_elevation(field, t2, pt(1), pt(2))
      call wave_kinematics(field, t2, pt, eta_x, v_x, a, pw)
      err_v = max(err_v, norm2(v - v_x))
      if (.not. cache%loaded(k)) cycle
      ! the window's wet polygon (tangent plane at t1), loaded at t2 from the sines
      grad = c(3, :) + cache%ep(3, 1, k)*c(1, :) + cache%ep(4, 1, k)*c(2, :)
      d0 = p(3) + cache%ep(1, 1, k)
      wet = section_immersion(hull, k, d0, grad(2), grad(3))
      call section_wave_load(field, t2, hull, wet, c, p, d0, grad(2), grad(3), load, rate)
      nload = nload + 1
      scale = max(scale, maxval(abs(load)))
      err_load = max(err_load, maxval(abs(cache%fk(:, 1, 2, k) - load)), &
                     maxval(abs(cache%fk(:, 2, 2, k) - rate))/maxval(field%omega))
    end do
    call note(state, "far-end elevation error (m)", err_eta)
    call note(state, "far-end velocity error (m/s)", err_v)
    call note(state, "far-end section load error (N/m)", err_load)
    call check_true(state, nload >= 5, "wet sections compared")
    call check(state, err_watch, 0.0_wp, "watch's elevation at t1 (m)", abs_tol=1e-11_wp)
    call check(state, err_eta, 0.0_wp, "elevation at t2 (m)", abs_tol=1e-11_wp)
    call check(state, err_v, 0.0_wp, "velocity at t2 (m/s)", abs_tol=1e-11_wp)
    call check(state, err_load/scale, 0.0_wp, "section load at t2 (relative)", &
               abs_tol=1e-11_wp)
  end subroutine far_end

  !> The window's section loads for a hull that has moved since t1 (a 0.1 s window of the
  !> Level 5 sea, read at t1, so that only the geometry differs; the water's own move is
  !> Hermite's, tested above): the boat heaved, swayed and surged by up to 6 cm and
  !> rolled, pitched and yawed by up to 0.03 rad (scale s = 1, then 1/2). The exact
  !> load of each wet section at its new geometry (its wet polygon found again under the
  !> surface's tangent plane there, section_wave_load) against the window's: expanded to
  !> first order in the geometry, its error must fall as s^2 (ratio 4 for half the move)
  !> and stay far below the frozen geometry's (the window at the sampled geometry), which
  !> falls as s. Fails with the expansion's sign reversed or a parameter left out.
  subroutine moved_hull(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    real(wp) :: c(3, 3), r(3), t, err(2), frozen(2)
    integer :: i
    call level5_sea(field)
    call afloat(hull, c, r)
    cache = new_strip_wave_cache(field, hull%n, new_slow_clock(0.1_wp, clock_reach))
    call refresh(cache, hull, field, 20.0_wp, c, r)
    t = 20.05_wp
    do i = 1, 2
      call moved_errors(cache, field, hull, t, 0.5_wp**(i - 1), err(i), frozen(i))
    end do
    call note(state, "expanded error, s = 1 and 1/2 (of the largest load)", err(1))
    call note(state, "expanded error, s = 1/2", err(2))
    call note(state, "frozen geometry's error, s = 1", frozen(1))
    call note(state, "frozen geometry's error, s = 1/2", frozen(2))
    call check(state, err(1)/err(2), 4.0_wp, "expanded: second order", rel_tol=0.2_wp)
    call check(state, frozen(1)/frozen(2), 2.0_wp, "frozen: first order", rel_tol=0.2_wp)
    call check_true(state, err(1) < 0.05_wp*frozen(1), "expanded far below frozen")
  end subroutine moved_hull

  !> The surface's slope at the strip centres (it sets each section's tangent plane): cubic
  !> in time through its values and rates, |g - H| <= h^4/384 sum a k w^4 at rest (order
  !> 4; a slope linear in time errs by ~(w h)^2/8, order 2), and expanded with the
  !> curvature in space, remainder <= sum a k^3 |dx|^2/2 (order 2; the slope of the
  !> reference point alone errs at first order). Against the field's own sums.
  subroutine slope_orders(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    real(wp) :: c(3, 3), r(3), h, e_t(2), e_x(2), dx(2), bound
    integer :: i, k
    call level5_sea(field)
    call afloat(hull, c, r)
    do i = 1, 2
      h = 0.4_wp/real(2**i, wp)
      cache = new_strip_wave_cache(field, hull%n, new_slow_clock(h, clock_reach))
      call refresh(cache, hull, field, 20.0_wp, c, r)
      e_t(i) = slope_error(cache, field, hull, c, r, 20.0_wp + 0.37_wp*h, [0.0_wp, 0.0_wp])
      bound = h**4/384*sum(field%amplitude*field%k*field%omega**4)
      call check_true(state, e_t(i) <= bound, "slope error within h^4/384 sum a k w^4")
    end do
    cache = new_strip_wave_cache(field, hull%n, new_slow_clock(0.05_wp, clock_reach))
    call refresh(cache, hull, field, 20.0_wp, c, r)
    do i = 1, 2
      dx = [0.08_wp, -0.06_wp]/real(i, wp)
      e_x(i) = slope_error(cache, field, hull, c, r, 20.0_wp, dx)
      bound = 0.5_wp*sum(dx**2)*sum(field%amplitude*field%k**3)
      call check_true(state, e_x(i) <= bound, "slope remainder within sum a k^3 dx^2/2")
    end do
    call note(state, "slope error at h = 0.1 s", e_t(2))
    call note(state, "slope error at |dx| = 5 cm", e_x(2))
    call check(state, log(e_t(1)/e_t(2))/log(2.0_wp), 4.0_wp, "slope order in h", &
               abs_tol=0.5_wp)
    call check(state, log(e_x(1)/e_x(2))/log(2.0_wp), 2.0_wp, "slope order in dx", &
               abs_tol=0.3_wp)
  end subroutine slope_orders

  !> Largest error of the cached slope at the strip centres moved by dx at time t.
  real(wp) function slope_error(cache, field, hull, c, r, t, dx) result(err)
    type(strip_wave_cache_type), intent(in) :: cache
    type(wave_field_type), intent(in) :: field
    type(boat_hull_type), intent(in) :: hull
    real(wp), intent(in) :: c(3, 3), r(3), t, dx(2)
    real(wp) :: p(3), eta, exact(2), slope(2)
    integer :: k
    err = 0.0_wp
    do k = 1, hull%n
      p = r + c(:, 1)*hull%x(k)
      p(1:2) = p(1:2) + dx
      call surface_plane(field, t, p(1), p(2), eta, exact)
      call cached_surface(cache, field, k, t, p(1), p(2), eta, slope)
      err = max(err, norm2(slope - exact))
    end do
  end function slope_error

  !> A hull accelerating through the Level 5 sea (from 0.3, -0.4, 0.6 m/s by 1.5, 1,
  !> -2 m/s^2; roll, pitch, yaw rates 0.3, -0.2, 0.1 rad/s by 1, 0.5, -0.5 rad/s^2),
  !> windows of 0.1 s renewed at 20.0, 20.1 and 20.2 s and read at 20.25 s, each wet
  !> section against its exact load at its geometry then (section_wave_load, the wet
  !> polygon found again). A window carries each section's geometry on along its path
  !> through its last samples: through three (a parabola) its error must be well below
  !> through two (a line), and that well below a window opened at 20.2 s alone (which
  !> expands the whole move since t1). Fails with the path's rates left out of the
  !> sampled loads' time rates, the path not followed, or its curvature dropped.
  subroutine hull_path(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: caches(3)
    real(wp) :: c(3, 3), r(3), err(3), t
    integer :: i, j, k
    call level5_sea(field)
    call afloat(hull, c, r)
    caches = new_strip_wave_cache(field, hull%n, new_slow_clock(0.1_wp, clock_reach))
    ! caches(i) sees the last i windows
    do j = 1, 3
      t = 19.9_wp + 0.1_wp*j
      call moving_pose(t, c, r)
      do i = 4 - j, 3
        call refresh(caches(i), hull, field, t, c, r)
      end do
    end do
    do i = 1, 3
      err(i) = path_error(caches(i), field, hull, 20.25_wp)
    end do
    call note(state, "error of the window alone (of the largest load)", err(1))
    call note(state, "error on the line through two samples", err(2))
    call note(state, "error on the parabola through three samples", err(3))
    call check_true(state, err(2) < 0.3_wp*err(1), "the line's error well below the window's")
    call check_true(state, err(3) < 0.5_wp*err(2), "the parabola's error well below the line's")
  end subroutine hull_path

  !> A hull partly out of the water at t1 (its CG raised until 3 to 17 of its 20 sections
  !> are wet in the Level 5 sea) lowered by 0.5 m at t1 + 0.03 s: sections dry at t1 are
  !> wet then. After the step the window samples them over a quarter of the load span,
  !> [t, t + 0.025 s] (before, their stages took the exact sums): read at t1 + 0.05 s,
  !> each such section's load against its exact one at its geometry then (the wet polygon
  !> found again), within 1e-3 of the largest; renewed at t + 0.025 s, over twice that, to
  !> the window's end. Fails where the catch-up samples nothing, or on the wrong span.
  subroutine catch_up(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    real(wp) :: c(3, 3), r(3), exact(3), load(3), g(7), pc(2), err, scale
    logical :: dry_at_t1(20), found, wet_now
    integer :: i, k, n_new
    call level5_sea(field)
    call afloat(hull, c, r)
    cache = new_strip_wave_cache(field, hull%n, new_slow_clock(0.1_wp, clock_reach))
    do k = 0, 60
      r(3) = 1.5_wp - 0.1_wp*k
      call refresh(cache, hull, field, 20.0_wp, c, r)
      if (count(cache%loaded) <= hull%n - 3) exit
    end do
    dry_at_t1 = .not. cache%loaded
    call note(state, "CG height raised to (m, z down)", r(3))
    r(3) = r(3) + 0.5_wp
    call strip_waves_renew_loads(cache, hull, field, 20.03_wp, c, r)
    n_new = count(dry_at_t1 .and. cache%loaded)
    err = 0.0_wp
    scale = 0.0_wp
    do k = 1, hull%n
      if (.not. (dry_at_t1(k) .and. cache%loaded(k))) cycle
      call check(state, cache%t_end(k) - cache%t_load(k), 0.025_wp, "onset span", &
                 abs_tol=1.0e-12_wp)
      call exact_section(field, hull, k, 20.05_wp, c, r, exact, g, pc, wet_now)
      call cached_wave_load(cache, field, k, 20.05_wp, g, pc, load, found)
      scale = max(scale, maxval(abs(exact)))
      err = max(err, maxval(abs(load - exact)))
    end do
    call note(state, "sections dry at t1", real(count(dry_at_t1), wp))
    call note(state, "of them sampled after the step", real(n_new, wp))
    call note(state, "error (of the largest load)", err/max(scale, tiny(1.0_wp)))
    call check_true(state, n_new >= 3, "sections wetted since t1 sampled")
    call check(state, err/scale, 0.0_wp, "caught-up loads vs exact", abs_tol=1.0e-3_wp)
    call strip_waves_renew_loads(cache, hull, field, 20.055_wp, c, r)
    do k = 1, hull%n
      if (.not. (dry_at_t1(k) .and. cache%loaded(k))) cycle
      call check(state, cache%t_end(k), 20.1_wp, "renewed onset to the window's end", &
                 abs_tol=1.0e-12_wp)
      call check(state, cache%t_load(k), 20.055_wp, "renewed at the step", abs_tol=1.0e-12_wp)
    end do
  end subroutine catch_up

  !> The accelerating hull of hull_path on a 0.6 s window from 20.0 s (two before it, so
  !> its paths are parabolas): the section loads' windows are 0.3 s (the interval in
  !> two), renewed at the accepted steps (every 0.01 s) that reach their ends. Read at
  !> 20.4 s, each wet section against its exact load: the renewed windows' error well below
  !> that of the first load window run on past its end (the same cache without renewals)
  !> and within 2.5e-3 of the largest load; every loaded section's window at most 0.3 s long
  !> and renewed at 20.3 s. Fails where the loads are sampled over the whole interval, not
  !> renewed, or renewed off their path.
  subroutine own_windows(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: renewed, kept, before
    real(wp) :: c(3, 3), r(3), t, err(2), jump, scale, g(7), pc(2), exact(3), l1(3), l2(3)
    integer :: j, k
    logical :: found, wet_now
    call level5_sea(field)
    call afloat(hull, c, r)
    renewed = new_strip_wave_cache(field, hull%n, new_slow_clock(0.6_wp, clock_reach))
    do j = 0, 2
      t = 18.8_wp + 0.6_wp*j
      call moving_pose(t, c, r)
      call refresh(renewed, hull, field, t, c, r)
    end do
    kept = renewed
    call check(state, maxval(renewed%t_end - renewed%t_load, mask=renewed%loaded), 0.3_wp, &
               "first load windows: half the interval", abs_tol=1.0e-12_wp)
    jump = 0.0_wp
    scale = 0.0_wp
    do j = 1, 40
      t = 20.0_wp + 0.01_wp*j
      call moving_pose(t, c, r)
      before = renewed
      call strip_waves_renew_loads(renewed, hull, field, t, c, r)
      if (j /= 30) cycle
      do k = 1, hull%n
        if (.not. (before%loaded(k) .and. renewed%loaded(k))) cycle
        call exact_section(field, hull, k, t, c, r, exact, g, pc, wet_now)
        call cached_wave_load(before, field, k, t, g, pc, l1, found)
        call cached_wave_load(renewed, field, k, t, g, pc, l2, found)
        jump = max(jump, maxval(abs(l2 - l1)))
        scale = max(scale, maxval(abs(exact)))
      end do
    end do
    err(1) = path_error(renewed, field, hull, 20.4_wp)
    err(2) = path_error(kept, field, hull, 20.4_wp)
    call note(state, "error with the renewed windows (of the largest load)", err(1))
    call note(state, "error of the first window run on", err(2))
    call note(state, "the first windows' error at 20.3 s (of the largest load)", jump/scale)
    call check_true(state, count(renewed%loaded) >= 10, "sections loaded")
    call check_true(state, all(pack(renewed%t_load, renewed%loaded) >= 20.3_wp - 1.0e-9_wp), &
                    "every load window renewed at the step that reached its end")
    call check_true(state, maxval(renewed%t_end - renewed%t_load, mask=renewed%loaded) <= &
                    0.3_wp + 1.0e-9_wp, "renewed windows at most 0.3 s")
    call check_true(state, err(1) < 0.3_wp*err(2), "renewed well below run on")
    ! on the path through the last samples 1.5e-3; renewed with the path dropped 3.6e-3
    call check(state, err(1), 0.0_wp, "renewed windows' error", abs_tol=2.5e-3_wp)
  end subroutine own_windows

  !> Open the window at t and sample every strip (the hull may wet any).
  subroutine refresh(cache, hull, field, t, c, r)
    type(strip_wave_cache_type), intent(inout) :: cache
    type(boat_hull_type), intent(in) :: hull
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, c(3, 3), r(3)
    logical :: every(hull%n)
    every = .true.
    call strip_waves_open(cache, hull, field, t, c, r)
    call strip_waves_sample(cache, hull, field, c, r, every)
  end subroutine refresh

  !> The accelerating hull of hull_path at time t.
  subroutine moving_pose(t, c, r)
    real(wp), intent(in) :: t
    real(wp), intent(out) :: c(3, 3), r(3)
    real(wp) :: s
    s = t - 20.0_wp
    c = rotation_matrix([0.05_wp, -0.03_wp, 0.4_wp] + s*[0.3_wp, -0.2_wp, 0.1_wp] + &
                        0.5_wp*s**2*[1.0_wp, 0.5_wp, -0.5_wp])
    r = [3.0_wp, -2.0_wp, 1.5_wp] + s*[0.3_wp, -0.4_wp, 0.6_wp] + &
        0.5_wp*s**2*[1.5_wp, 1.0_wp, -2.0_wp]
  end subroutine moving_pose

  !> Largest error of the window's section loads at time t for the accelerating hull,
  !> relative to the largest exact load.
  real(wp) function path_error(cache, field, hull, t) result(err)
    type(strip_wave_cache_type), intent(in) :: cache
    type(wave_field_type), intent(in) :: field
    type(boat_hull_type), intent(in) :: hull
    real(wp), intent(in) :: t
    real(wp) :: c(3, 3), r(3), exact(3), load(3), g(7), pc(2), scale
    integer :: k
    logical :: found, wet_now
    call moving_pose(t, c, r)
    err = 0.0_wp
    scale = 0.0_wp
    do k = 1, hull%n
      if (.not. cache%loaded(k)) cycle
      call exact_section(field, hull, k, t, c, r, exact, g, pc, wet_now)
      if (.not. wet_now) cycle
      call cached_wave_load(cache, field, k, t, g, pc, load, found)
      scale = max(scale, maxval(abs(exact)))
      err = max(err, maxval(abs(load - exact)))
    end do
    err = err/scale
  end function path_error

  !> Strip k of the hull at (c, r) at time t: its exact section load (the wet polygon found
  !> again under the surface's tangent plane there, section_wave_load; zero and wet_now =
  !> .false. where dry) and the geometry the window reads (d0, gy, gz, c12, c22, c13, c23)
  !> with the centre's horizontal position pc.
  subroutine exact_section(field, hull, k, t, c, r, exact, g, pc, wet_now)
    type(wave_field_type), intent(in) :: field
    type(boat_hull_type), intent(in) :: hull
    integer, intent(in) :: k
    real(wp), intent(in) :: t, c(3, 3), r(3)
    real(wp), intent(out) :: exact(3), g(7), pc(2)
    logical, intent(out) :: wet_now
    type(section_wet_type) :: wet
    real(wp) :: p(3), eta, slope(2), grad(3), rate(3)
    p = r + c(:, 1)*hull%x(k)
    call surface_plane(field, t, p(1), p(2), eta, slope)
    grad = c(3, :) + slope(1)*c(1, :) + slope(2)*c(2, :)
    g = [p(3) + eta, grad(2), grad(3), c(1:2, 2), c(1:2, 3)]
    pc = p(1:2)
    wet = section_immersion(hull, k, g(1), g(2), g(3))
    wet_now = wet%area > 0.0_wp
    call section_wave_load(field, t, hull, wet, c, p, g(1), g(2), g(3), exact, rate)
  end subroutine exact_section

  !> Largest error of the window's section loads against the exact ones, relative to the
  !> largest exact load, for the hull of afloat moved by the scale s: expanded and frozen.
  subroutine moved_errors(cache, field, hull, t, s, err, frozen)
    type(strip_wave_cache_type), intent(in) :: cache
    type(wave_field_type), intent(in) :: field
    type(boat_hull_type), intent(in) :: hull
    real(wp), intent(in) :: t, s
    real(wp), intent(out) :: err, frozen
    real(wp) :: c(3, 3), r(3), exact(3), load(3), still(3), g(7), pc(2), scale
    integer :: k
    logical :: found, wet_now
    ! afloat's pose, moved
    c = rotation_matrix([0.05_wp + 0.03_wp*s, -0.03_wp + 0.02_wp*s, 0.4_wp - 0.03_wp*s])
    r = [3.0_wp, -2.0_wp, 1.5_wp] + s*[0.04_wp, -0.05_wp, 0.06_wp]
    err = 0.0_wp
    frozen = 0.0_wp
    scale = 0.0_wp
    do k = 1, hull%n
      if (.not. cache%loaded(k)) cycle
      call exact_section(field, hull, k, t, c, r, exact, g, pc, wet_now)
      if (.not. wet_now) cycle
      call cached_wave_load(cache, field, k, t, g, pc, load, found)
      call cached_wave_load(cache, field, k, t, cache%g_ref(:, k), cache%p(:, k), still, &
                            found)
      scale = max(scale, maxval(abs(exact)))
      err = max(err, maxval(abs(load - exact)))
      frozen = max(frozen, maxval(abs(still - exact)))
    end do
    err = err/scale
    frozen = frozen/scale
  end subroutine moved_errors

  !> The paper's strips (water_model = 'paper': the clock's elevation and velocity; the
  !> pressure level's sampled section loads freeze the wet geometry over a window, README).
  !> The free boat afloat in the Level 5 irregular sea for 3 s (RK4, dt = 5e-3 s), with
  !> the slow clock at 0.05 s and exact: by the bounds above the forcing differs by
  !> ~1e-5 relative, so the CG paths agree to well below a millimetre. The strips alone
  !> (water_model = 'paper'): the clock serves them; the BEM terms take exact phases.
  subroutine coupled_boat(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp), allocatable :: y(:), cg(:, :)
    integer :: j
    logical :: used
    character(len=*), parameter :: deck = "&sea level = 5 wave_type = 'irregular' "// &
                                          "ramp_periods = 0.0 / &slings attached = .false. / "// &
                                          "&contact enabled = .false. / &wind speed = 0.0 / "// &
                                          "&boat position = 0.0, 0.0, -0.5 "// &
                                          "water_model = 'paper' / "// &
                                          "&simulation wave_update = "
    allocate (cg(3, 2))
    used = .false.
    do j = 1, 2
      call parse_config("test.nml", deck//merge("0.05", "0.00", j == 1)//" /", cfg, error)
      if (allocated(error)) error stop "test deck rejected: "//error%message
      y = new_test_system(sys, cfg)
      cg(:, j) = drop_cg(sys, y, 600, 5.0e-3_wp)
      if (j == 1) used = sys%hist%waves%clock%valid
    end do
    call note(state, "CG difference after 3 s (m)", norm2(cg(:, 1) - cg(:, 2)))
    call note(state, "CG travel (m)", norm2(cg(:, 2) - [0.0_wp, 0.0_wp, -0.5_wp]))
    call check_true(state, used, "the clock was used")
    call check_true(state, norm2(cg(:, 2) - [0.0_wp, 0.0_wp, -0.5_wp]) > 0.1_wp, &
                    "the sea moves the boat")
    call check(state, norm2(cg(:, 1) - cg(:, 2)), 0.0_wp, "CG with clock vs exact", &
               abs_tol=1e-4_wp)
  end subroutine coupled_boat

end module test_strip_waves
