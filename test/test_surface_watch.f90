!> The surface watch (davit_boat_surface_watch), which lets the strips' loads be skipped
!> only where they are exactly zero: its Lipschitz bounds from a sample, kept while they
!> prove the hull dry, and inside a window of the strips' slow clock the window's own
!> bounds (the cubics through its exact samples plus their remainder), each against the
!> exact strip loads or the exact sums at random poses and times in the Level 5 sea.
module test_surface_watch
  use davit_kinds, only: wp, pi
  use davit_core_rotation, only: rotation_matrix
  use davit_sea_wave_field, only: wave_field_type
  use davit_boat_hull, only: boat_hull_type
  use davit_boat_strip_loads, only: strip_loads
  use davit_boat_surface_watch, only: watch_refresh, watch_due, surely_dry, watch_set, &
                                      watch_set_window, surface_watch_type, hull_surely_dry, &
                                      strip_surely_dry
  use davit_boat_strip_waves, only: strip_wave_cache_type, new_strip_wave_cache, &
                                    strip_waves_open, strip_waves_surface, strip_waves_bounds
  use davit_boat_strip_sums, only: elevation_sums, ne
  use davit_core_slow_clock, only: new_slow_clock, clock_reach
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system
  use test_boat_water, only: strip_config
  use test_strip_waves, only: level5_sea, afloat
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_surface_watch

contains

  function collect_surface_watch() result(suite)
    type(suite_type) :: suite
    suite%name = "surface_watch"
    suite%cases = [new_case("never_skips_a_wet_hull", surface_watch), &
                   new_case("kept_high_refreshed_low", watch_kept), &
                   new_case("window_bounds_hold_the_surface_over_the_window", window_bounds), &
                   new_case("window_never_skips_a_wet_hull", watch_window), &
                   new_case("hull_test_implies_every_strip_test", hull_test)]
  end function collect_surface_watch

  !> The boat alone (no slings, no contact) in the Level 5 irregular sea with no ramp,
  !> and the groups in `extra` (namelist text).
  subroutine level5_system(sys, extra)
    type(system_type), intent(out) :: sys
    character(len=*), intent(in) :: extra
    real(wp), allocatable :: y0(:)
    y0 = new_test_system(sys, strip_config("&sea level = 5 wave_type = 'irregular' "// &
                                           "ramp_periods = 0.0 / "//extra// &
                                           "&slings attached = .false. / "// &
                                           "&contact enabled = .false. /"))
  end subroutine level5_system

  !> A boat pose from uniform randoms x(1:6): heel and trim within +-roll/2 and +-pitch/2
  !> [rad], any heading, the CG anywhere in a 50 m square, z_low + z_span x(1) [m] (z down).
  subroutine random_pose(x, roll, pitch, z_low, z_span, c, r)
    real(wp), intent(in) :: x(:), roll, pitch, z_low, z_span
    real(wp), intent(out) :: c(3, 3), r(3)
    c = rotation_matrix([roll*(x(2) - 0.5_wp), pitch*(x(3) - 0.5_wp), 6.0_wp*x(4)])
    r = [50.0_wp*x(5), 50.0_wp*x(6), z_low + z_span*x(1)]
  end subroutine random_pose

  !> The surface watch may skip the strip loads only when they are exactly zero: in an
  !> irregular Level 5 sea (1300 components), 4000 random boat poses at heights from 12 m
  !> above the water to 1 m into it, 0-0.05 s after the sample and up to 0.3 m and 0.1 rad
  !> away from the sampled pose: every pose it calls dry has zero strip force and volume;
  !> and it does call the boat dry high up (it is useful: > 25 % of the poses).
  subroutine surface_watch(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    real(wp) :: c0(3, 3), r0(3), c(3, 3), r(3), t, x(9)
    integer :: i, dry, missed
    call level5_system(sys, "")
    dry = 0
    missed = 0
    do i = 1, 4000
      call random_number(x)
      call random_pose(x, 0.2_wp, 0.1_wp, -12.0_wp, 13.0_wp, c0, r0)
      call watch_refresh(sys%hist%watch, sys%par%water, sys%par%sea, 10.0_wp*x(7), c0, r0)
      t = sys%hist%watch%t + 0.05_wp*x(8)
      c = matmul(rotation_matrix(0.1_wp*[x(9), 1.0_wp - x(9), x(3)]), c0)
      r = r0 + 0.3_wp*[x(9) - 0.5_wp, x(2) - 0.5_wp, x(4) - 0.5_wp]
      call tally_dry(sys, t, c, r, dry, missed)
    end do
    call note(state, "poses called dry", real(dry, wp))
    call note(state, "rate bound (m/s)", sys%hist%watch%rate_bound)
    call note(state, "slope bound (-)", sys%hist%watch%slope_bound)
    call check(state, real(missed, wp), 0.0_wp, "dry poses with water loads", abs_tol=0.0_wp)
    call check_true(state, dry > 1000, "the watch skips the high poses")
  end subroutine surface_watch

  !> A pose (t, c, r) the watch calls dry counts in `dry`, and in `missed` as well when the
  !> strips' water loads there are not exactly zero (the watch must never skip those).
  subroutine tally_dry(sys, t, c, r, dry, missed)
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: t, c(3, 3), r(3)
    integer, intent(inout) :: dry, missed
    real(wp) :: f(6), volume, u(6)
    if (.not. surely_dry(sys%hist%watch, sys%par%water, t, c, r)) return
    dry = dry + 1
    u = 0.0_wp
    call strip_loads(sys%par%water, sys%par%sea, t, c, r, u, f, volume)
    if (volume /= 0.0_wp .or. any(f /= 0.0_wp)) missed = missed + 1
  end subroutine tally_dry

  !> An old watch is kept while it proves the hull dry two intervals ahead (watch_due): a
  !> boat 12 m above the Level 5 sea (1300 components) keeps a watch sampled 0.06 s
  !> before; 0.5 m above the water it is refreshed. A kept watch stays rigorous at any
  !> age: 2000 poses around the high one, 0-1 s after the sample, called dry by it, all
  !> have zero strip force and volume.
  subroutine watch_kept(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    real(wp) :: c0(3, 3), r0(3), c(3, 3), r(3), t, x(5)
    integer :: i, dry, missed
    logical :: due_high, due_low
    call level5_system(sys, "")
    c0 = rotation_matrix([0.05_wp, -0.02_wp, 0.3_wp])
    r0 = [5.0_wp, -3.0_wp, -12.0_wp]
    call watch_refresh(sys%hist%watch, sys%par%water, sys%par%sea, 30.0_wp, c0, r0)
    call watch_due(sys%hist%watch, sys%par%water, 30.06_wp, c0, &
                   [r0(1), r0(2), -0.5_wp], due_low)
    call watch_due(sys%hist%watch, sys%par%water, 30.06_wp, c0, r0, due_high)
    call check_true(state, .not. due_high, "kept 12 m above the water")
    call check_true(state, due_low, "refreshed 0.5 m above the water")
    dry = 0
    missed = 0
    do i = 1, 2000
      call random_number(x)
      t = 30.0_wp + 0.3_wp*x(1)
      c = matmul(rotation_matrix(0.1_wp*[x(2), 1.0_wp - x(2), x(3)]), c0)
      r = r0 + [0.5_wp*(x(4) - 0.5_wp), 0.5_wp*(x(3) - 0.5_wp), 6.0_wp*x(5)]
      call tally_dry(sys, t, c, r, dry, missed)
    end do
    call note(state, "poses called dry by the old watch", real(dry, wp))
    call check(state, real(missed, wp), 0.0_wp, "dry poses with water loads", abs_tol=0.0_wp)
    call check_true(state, dry > 200, "the old watch still skips high poses")
  end subroutine watch_kept

  !> The watch's window (its bounds from the strips' window at the strip centres, as each
  !> window of the strips' slow clock sets it): in the Level 5 sea (1300 components, 0.3 s
  !> windows), 300 windows opened at random times and boat positions from 4 m above the
  !> still water to 1 m into it, 10 poses in each (any time in the window, moved up to
  !> 0.1 m and 0.03 rad): every pose it calls dry has zero strip force and volume (exact
  !> sums); and it calls > 25 % of them dry, where the Lipschitz bound from the same
  !> samples (sum |a| w ~ 30 m/s) proves almost none dry this close to the water.
  subroutine watch_window(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    type(surface_watch_type) :: lipschitz
    real(wp) :: c0(3, 3), r0(3), c(3, 3), r(3), t, x(7), xy(2, 20), eta(20), grad(2, 20)
    real(wp) :: eta_up(20), slope_up(20)
    integer :: i, j, dry, missed, dry_old
    call level5_system(sys, "&simulation wave_update = 0.3 / ")
    dry = 0
    missed = 0
    dry_old = 0
    do i = 1, 300
      call random_number(x)
      call random_pose(x, 0.1_wp, 0.05_wp, -4.0_wp, 5.0_wp, c0, r0)
      associate (w => sys%hist%waves, hull => sys%par%water%hull)
        call strip_waves_open(w, hull, sys%par%sea, 10.0_wp*x(7), c0, r0)
        call strip_waves_surface(w, sys%par%sea, xy, eta, grad)
        call watch_set(sys%hist%watch, w%clock%window(1), xy, eta, grad)
        lipschitz = sys%hist%watch
        call strip_waves_bounds(w, sys%par%sea, eta_up, slope_up)
        call watch_set_window(sys%hist%watch, w%clock%window, eta_up, slope_up)
        do j = 1, 10
          call random_number(x)
          t = w%clock%window(1) + 0.3_wp*x(1)
          c = matmul(rotation_matrix(0.03_wp*[x(2) - 0.5_wp, x(3) - 0.5_wp, x(4) - 0.5_wp]), c0)
          r = r0 + 0.1_wp*[x(5) - 0.5_wp, x(6) - 0.5_wp, x(7) - 0.5_wp]
          call tally_dry(sys, t, c, r, dry, missed)
          if (surely_dry(lipschitz, sys%par%water, t, c, r)) dry_old = dry_old + 1
        end do
      end associate
    end do
    call note(state, "poses called dry (of 3000)", real(dry, wp))
    call note(state, "of them by the Lipschitz bound", real(dry_old, wp))
    call check(state, real(missed, wp), 0.0_wp, "dry poses with water loads", abs_tol=0.0_wp)
    call check_true(state, dry > 750, "the window's watch skips the poses clear of the crests")
  end subroutine watch_window

  !> The window's bounds of the elevation and of |grad eta| at the strip centres (the
  !> cubics' extremes plus their h^4/384 remainder) against the exact sums sampled every
  !> 5 ms over 200 windows of 0.3 s at random times and boat positions in the Level 5 sea:
  !> no sample above its bound; and the bounds tight (the elevation's largest excess over
  !> the sampled maximum under 2 cm: the boat hangs this close to the crests before it
  !> samples the water, against ~10 m of the Lipschitz bound sum |a| w h). Fails on a
  !> wrong extreme (a root of the cubic's derivative missed or misplaced, a sign of the
  !> slope's lower cubic), a wrong rate term, or a bound taken at one end only.
  subroutine window_bounds(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(boat_hull_type) :: hull
    type(strip_wave_cache_type) :: cache
    real(wp) :: c(3, 3), r(3), x(4), e(ne), eta_up(20), slope_up(20), top(20), steep(20)
    real(wp) :: excess, over, t0, t
    integer :: i, j, k
    call level5_sea(field)
    call afloat(hull, c, r)
    cache = new_strip_wave_cache(field, hull%n, new_slow_clock(0.3_wp, clock_reach))
    excess = 0.0_wp
    over = -huge(1.0_wp)
    do i = 1, 200
      call random_number(x)
      t0 = 10.0_wp + 200.0_wp*x(1)
      c = rotation_matrix([0.0_wp, 0.0_wp, 2.0_wp*pi*x(2)])
      r = [60.0_wp*x(3), 60.0_wp*x(4), -5.0_wp]
      call strip_waves_open(cache, hull, field, t0, c, r)
      call strip_waves_bounds(cache, field, eta_up, slope_up)
      top = -huge(1.0_wp)
      steep = 0.0_wp
      do j = 0, 60
        t = t0 + 0.005_wp*j
        do k = 1, hull%n
          call elevation_sums(field, t, cache%p(1, k), cache%p(2, k), e)
          top(k) = max(top(k), e(1))
          steep(k) = max(steep(k), norm2(e(3:4)))
        end do
      end do
      over = max(over, maxval(top - eta_up), maxval(steep - slope_up))
      excess = max(excess, maxval(eta_up - top))
    end do
    call note(state, "largest sample over its bound (m or -; <= 0)", over)
    call note(state, "largest excess of the elevation's bound (m)", excess)
    call check_true(state, over <= 0.0_wp, "no sample above its bound")
    call check(state, excess, 0.0_wp, "the elevation's bound tight", abs_tol=0.02_wp)
  end subroutine window_bounds

  !> The whole hull's test (one bound for every strip: the largest surface bound, distance
  !> and radius, the lowest corner of the sections' box) against the per-strip tests it
  !> stands in for: over 4000 random poses of the Level 5 sea (12 m above the water to 1 m
  !> into it, heeled up to 0.3 rad, 0-0.6 s after the sample), every pose it calls dry has
  !> every strip dry by strip_surely_dry; and it decides most of the poses the strips call
  !> dry (> 50 %: the boat hanging clear). Fails on a wrong sign of a corner's term or a
  !> bound taken at one strip.
  subroutine hull_test(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    real(wp) :: c(3, 3), r(3), t, x(8)
    integer :: i, k, hull_dry, strips_dry, wrong
    logical :: all_strips
    call level5_system(sys, "")
    hull_dry = 0
    strips_dry = 0
    wrong = 0
    do i = 1, 4000
      call random_number(x)
      call random_pose(x, 0.6_wp, 0.3_wp, -12.0_wp, 13.0_wp, c, r)
      call watch_refresh(sys%hist%watch, sys%par%water, sys%par%sea, 10.0_wp*x(7), c, r)
      t = sys%hist%watch%t + 0.6_wp*x(8)
      all_strips = .true.
      do k = 1, sys%par%water%hull%n
        all_strips = all_strips .and. strip_surely_dry(sys%hist%watch, sys%par%water, k, t, c, r)
      end do
      if (all_strips) strips_dry = strips_dry + 1
      if (.not. hull_surely_dry(sys%hist%watch, sys%par%water, t, c, r)) cycle
      hull_dry = hull_dry + 1
      if (.not. all_strips) wrong = wrong + 1
    end do
    call note(state, "poses every strip calls dry", real(strips_dry, wp))
    call note(state, "of them decided by the hull's test", real(hull_dry, wp))
    call check(state, real(wrong, wp), 0.0_wp, "hull dry, a strip not", abs_tol=0.0_wp)
    call check_true(state, 2*hull_dry > strips_dry, "the hull's test decides most")
  end subroutine hull_test

end module test_surface_watch
