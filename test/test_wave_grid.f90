!> The interpolated sea (davit_sea_wave_grid, `&sea kinematics = 'grid'`) against the exact
!> component sum: the Catmull-Rom interpolation's third order on one Airy component (and
!> the error bound the surface watch adds), the field's Hs against the spectrum's m0 over
!> an hour of blocks built on demand, and the coupled boat afloat with the grid and with
!> the exact sum.
module test_wave_grid
  use davit_kinds, only: wp, pi
  use davit_core_random, only: rng_type, new_rng, rng_uniform
  use davit_sea_wave_field, only: wave_field_type, new_regular_wave, new_single_sum_sea, &
                                  new_irregular_sea, single_equal_energy, wave_airy, &
                                  wave_irregular, wave_elevation, wave_kinematics
  use davit_boat_strip_sums, only: elevation_sums, kinematic_sums, elevation_pass, nep
  use davit_boat_strip_grid, only: grid_holds, grid_ends
  use davit_sea_spectrum, only: spectrum_m0, spectrum_band_fraction
  use davit_sea_wave_grid, only: wave_grid_type, new_wave_grid, grid_prepare, grid_covers, &
                                 grid_elevation, grid_kinematics, grid_error_bounds
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, deck_config, drop_cg
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_wave_grid

contains

  function collect_wave_grid() result(suite)
    type(suite_type) :: suite
    suite%name = "wave_grid"
    suite%cases = [new_case("grid_airy_order3_and_error_bound", airy_order), &
                   new_case("grid_hs_from_spectrum_blocks_on_demand", grid_hs), &
                   new_case("grid_coupled_boat_agrees_with_sum", coupled_boat), &
                   new_case("grid_level5_errors_within_bound", level5_errors), &
                   new_case("grid_window_ends_curvature_vs_sums", window_ends)]
  end function collect_wave_grid

  !> Largest errors of the grid's elevation, slope and velocity (at stretched depths 0 to
  !> 2.5 m) against the exact sum at 400 pseudo-random points of a 10 x 6 m box over 10 s.
  subroutine grid_errors(field, h, dt, e_eta, e_slope, e_v, bound)
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: h, dt
    real(wp), intent(out) :: e_eta, e_slope, e_v, bound
    type(wave_grid_type) :: g
    type(rng_type) :: rng
    real(wp) :: u(4), t, x, y, d, e(4), v(3, 5), eta, vx(3), a(3), p, b(2), grad(2)
    integer :: i
    g = new_wave_grid(field, h, dt, 0.0_wp, 3.0_wp, .true.)
    call grid_prepare(g, field, 10.0_wp, 20.0_wp, reshape([0.0_wp, 0.0_wp, 10.0_wp, 6.0_wp], &
                                                          [2, 2]))
    b = grid_error_bounds(g, field)
    bound = b(1)
    rng = new_rng(11)
    e_eta = 0.0_wp
    e_slope = 0.0_wp
    e_v = 0.0_wp
    do i = 1, 400
      call rng_uniform(rng, u(1))
      call rng_uniform(rng, u(2))
      call rng_uniform(rng, u(3))
      call rng_uniform(rng, u(4))
      t = 10.0_wp + 10.0_wp*u(1)
      x = 10.0_wp*u(2)
      y = 6.0_wp*u(3)
      d = 2.5_wp*u(4)
      if (.not. grid_covers(g, t, x, y, d)) error stop "grid_errors: point outside the grid"
      call grid_kinematics(g, t, x, y, d, e, v)
      ! exact: the point at stretched depth d below the exact surface
      eta = wave_elevation(field, t, x, y)
      call wave_kinematics(field, t, [x, y, d - eta], eta, vx, a, p)
      grad = field%amplitude(1)*sin(field%omega(1)*t + field%phase(1) - field%kx(1)*x - &
                                    field%ky(1)*y)*[field%kx(1), field%ky(1)]
      e_eta = max(e_eta, abs(e(1) - eta))
      e_slope = max(e_slope, norm2(e(3:4) - grad))
      e_v = max(e_v, norm2(v(:, 1) - vx))
    end do
  end subroutine grid_errors

  !> One Airy component (H = 2 m, T = 4 s, travelling at 30 deg: k = 0.252 1/m, both kx
  !> and ky non-zero) as a linear sea: Catmull-Rom in x, y, t and depth errs by O(h^3) in
  !> the elevation, its slope (a sampled field) and the velocity; halving h (1 -> 0.5 ->
  !> 0.25 m) with dt (0.2 -> 0.1 -> 0.05 s) divides the errors by ~8. The largest error
  !> stays within the bound the surface watch adds to its proof (grid_error_bounds).
  subroutine airy_order(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    real(wp) :: e_eta(3), e_slope(3), e_v(3), bound(3), h
    integer :: i
    call new_regular_wave(field, wave_airy, 2.0_wp, 4.0_wp, pi/6, 0.3_wp, 0.0_wp)
    field%kind = wave_irregular
    do i = 1, 3
      h = 1.0_wp/real(2**(i - 1), wp)
      call grid_errors(field, h, 0.2_wp*h, e_eta(i), e_slope(i), e_v(i), bound(i))
      call check_true(state, e_eta(i) <= bound(i), "eta error within grid_error_bounds")
      call check_true(state, e_slope(i) <= bound(i)*field%k(1), &
                      "slope error within grid_error_bounds")
    end do
    call note(state, "eta error at h = 1 m, dt = 0.2 s (m)", e_eta(1))
    call note(state, "eta error at h = 0.25 m (m)", e_eta(3))
    call note(state, "velocity error at h = 1 m (m/s)", e_v(1))
    call check(state, log(e_eta(2)/e_eta(3))/log(2.0_wp), 3.0_wp, "eta order", abs_tol=0.4_wp)
    call check(state, log(e_v(2)/e_v(3))/log(2.0_wp), 3.0_wp, "velocity order", &
               abs_tol=0.4_wp)
    call check(state, log(e_slope(2)/e_slope(3))/log(2.0_wp), 3.0_wp, "slope order", &
               abs_tol=0.4_wp)
    ! a unit amplitude's relative error at k h = 0.25 is ~0.034 (k h)^3 = 5e-4
    call check_true(state, e_eta(1) < 2.0e-3_wp, "eta error at h = 1 m below 2 mm")
  end subroutine airy_order

  !> The single-summation Level 5 sea (H = 4 m, 100 components in 0.3-3 rad/s): an hour of
  !> the grid's elevation at a fixed point, the grid's blocks (1.6 s each) built on demand.
  !> Its variance equals the exact sum's over the same record (to the interpolation's
  !> error), and Hs = 4 sqrt(m0) that of the spectrum's band (eq. 44 integrated in closed
  !> form over 0.3-3 rad/s) within 3 standard deviations of a one-hour record (the
  !> record's variance scatters by about 4.5 %, so Hs by about 2.3 %).
  subroutine grid_hs(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(wave_grid_type) :: g
    type(rng_type) :: rng
    real(wp) :: t, e(4), var_grid, var_sum, m0, xy(2, 1), eta
    integer :: i, n
    rng = new_rng(5)
    call new_single_sum_sea(field, 4.0_wp, 0.5_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, .true., &
                            single_equal_energy, rng, 0.0_wp)
    g = new_wave_grid(field, 1.0_wp, 0.1_wp, 0.0_wp, 3.0_wp, .false.)
    xy(:, 1) = [3.3_wp, -1.7_wp]
    n = 36000
    var_grid = 0.0_wp
    var_sum = 0.0_wp
    do i = 1, n
      t = 0.1_wp*real(i, wp) + 0.037_wp
      call grid_prepare(g, field, t, t, xy)
      if (.not. grid_covers(g, t, xy(1, 1), xy(2, 1))) error stop "grid_hs: not covered"
      call grid_elevation(g, t, xy(1, 1), xy(2, 1), e)
      eta = wave_elevation(field, t, xy(1, 1), xy(2, 1))
      var_grid = var_grid + e(1)**2
      var_sum = var_sum + eta**2
    end do
    var_grid = var_grid/real(n, wp)
    var_sum = var_sum/real(n, wp)
    m0 = spectrum_m0(4.0_wp)*spectrum_band_fraction(0.3_wp, 3.0_wp, 4.0_wp)
    call note(state, "Hs of the grid (m)", 4.0_wp*sqrt(var_grid))
    call note(state, "Hs of the spectrum's band (m)", 4.0_wp*sqrt(m0))
    call note(state, "blocks built", real(g%builds, wp))
    call check_true(state, g%builds >= n/16, "blocks built on demand")
    call check(state, var_grid, var_sum, "grid variance vs exact sum's", rel_tol=1.0e-3_wp)
    call check(state, 4.0_wp*sqrt(var_grid), 4.0_wp*sqrt(m0), "Hs vs spectrum", &
               rel_tol=0.07_wp)
  end subroutine grid_hs

  !> The free boat afloat (BEM water model) in the Level 5 irregular sea (1300 components)
  !> for 3 s (RK4, dt = 5e-3 s, slow clock 0.05 s), with the grid (h = 1 m, dt = 0.1 s)
  !> and with the exact sum: the CG paths agree within 5 mm (measured 3.5 mm: the sums'
  !> window carries the slope's curvature and rates, the grid's its curvature by differences
  !> and a slope linear in time; 1.8 mm when neither had them) while the
  !> boat, dropped from 0.5 m, travels 2.6 m. With the slope taken as the derivative of
  !> the interpolated elevation (O(h^2), the steep short components' slopes off by up to
  !> 14 %) instead of a sampled field, they differed by 5.5 cm.
  subroutine coupled_boat(state)
    type(case_state), intent(inout) :: state
    type(system_type) :: sys
    real(wp), allocatable :: y(:), cg(:, :)
    integer :: j, builds
    character(len=*), parameter :: deck = "&sea level = 5 wave_type = 'irregular' "// &
                                          "ramp_periods = 0.0 kinematics = '"
    character(len=*), parameter :: rest = "' / &slings attached = .false. / "// &
                                          "&contact enabled = .false. / &wind speed = 0.0 / "// &
                                          "&boat position = 0.0, 0.0, -0.5 / "// &
                                          "&simulation wave_update = 0.05 /"
    allocate (cg(3, 2))
    builds = 0
    do j = 1, 2
      y = new_test_system(sys, deck_config(deck//trim(merge("grid", "sum ", j == 1))//rest))
      cg(:, j) = drop_cg(sys, y, 600, 5.0e-3_wp)
      if (j == 1) builds = sys%hist%volume_grid%node_builds
    end do
    call note(state, "CG difference after 3 s (m)", norm2(cg(:, 1) - cg(:, 2)))
    call note(state, "CG travel (m)", norm2(cg(:, 2) - [0.0_wp, 0.0_wp, -0.5_wp]))
    call check_true(state, builds > 0, "the velocity grid was used")
    call check_true(state, norm2(cg(:, 2) - [0.0_wp, 0.0_wp, -0.5_wp]) > 0.1_wp, &
                    "the sea moves the boat")
    call check(state, norm2(cg(:, 1) - cg(:, 2)), 0.0_wp, "CG with grid vs exact sum", &
               abs_tol=5.0e-3_wp)
  end subroutine coupled_boat

  !> The Level 5 seas of the shipped decks (H = 4 m, 0.3-3 rad/s; double summation 100 x 13
  !> and single summation 100 components) at the defaults (h = 1 m, dt = 0.1 s, velocity
  !> to 3 m): over 2000 pseudo-random points of a 14 x 6 m box, 20 s and stretched depths
  !> 0-2.5 m, the grid's elevation terms and velocity against the exact sums of the slow
  !> clock. The largest elevation error stays within grid_error_bounds; the RMS errors
  !> are what doc/theory/sea.md quotes (notes). The elevation's RMS error below 1 mm
  !> (Hs = 4 m) and the velocity's below 5 mm/s: the spectrum's energy sits at k h < 0.25,
  !> where Catmull-Rom errs by 0.034 (k h)^3 < 5e-4 of an amplitude.
  subroutine level5_errors(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(wave_grid_type) :: g
    type(rng_type) :: rng
    real(wp) :: u(4), t, x, y, d, e(4), v(3, 5), ex(4), vx(3, 5), b(2), err(4), mx(3)
    integer :: i, sea
    character(len=6) :: label
    do sea = 1, 2
      rng = new_rng(3)
      if (sea == 1) then
        call new_irregular_sea(field, 4.0_wp, pi/2, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, .true., &
                               .true., rng, 0.0_wp)
        label = "double"
      else
        call new_single_sum_sea(field, 4.0_wp, pi/2, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, &
                                .true., single_equal_energy, rng, 0.0_wp)
        label = "single"
      end if
      g = level5_grid(field, 50.0_wp)
      b = grid_error_bounds(g, field)
      err = 0.0_wp
      mx = 0.0_wp
      do i = 1, 2000
        call rng_uniform(rng, u(1))
        call rng_uniform(rng, u(2))
        call rng_uniform(rng, u(3))
        call rng_uniform(rng, u(4))
        t = 30.0_wp + 20.0_wp*u(1)
        x = -7.0_wp + 14.0_wp*u(2)
        y = 10.0_wp + 6.0_wp*u(3)
        d = 2.5_wp*u(4)
        call grid_kinematics(g, t, x, y, d, e, v)
        call kinematic_sums(field, t, x, y, d, ex, vx)
        err(1) = err(1) + (e(1) - ex(1))**2
        err(2) = err(2) + sum((e(3:4) - ex(3:4))**2)
        err(3) = err(3) + sum((v(:, 1) - vx(:, 1))**2)
        err(4) = err(4) + ex(1)**2
        mx = max(mx, [abs(e(1) - ex(1)), norm2(e(3:4) - ex(3:4)), norm2(v(:, 1) - vx(:, 1))])
      end do
      err = sqrt(err/2000.0_wp)
      call note(state, label//": eta RMS error (m)", err(1))
      call note(state, label//": eta max error (m)", mx(1))
      call note(state, label//": eta RMS (m)", err(4))
      call note(state, label//": slope RMS error (-)", err(2))
      call note(state, label//": velocity RMS error (m/s)", err(3))
      call note(state, label//": velocity max error (m/s)", mx(3))
      call note(state, label//": eta error bound (m)", b(1))
      call check_true(state, mx(1) <= b(1), label//": eta error within grid_error_bounds")
      call check_true(state, err(1) < 1.0e-3_wp, label//": eta RMS error below 1 mm")
      call check_true(state, err(3) < 5.0e-3_wp, label//": velocity RMS error below 5 mm/s")
    end do
  end subroutine level5_errors

  !> The strips' window read from the grid (davit_boat_strip_grid) in the Level 5 sea
  !> (1 m spacing, 0.1 s blocks): at 500 random points and 0.1 s windows inside the
  !> prepared area, the elevation, its slope and its curvature (central differences of the
  !> interpolated slope half a spacing either side, second order in the spacing: for the
  !> shortest waves, k = 0.92 1/m, (k dl)^2/6 = 3.5 %) at both window ends against the
  !> exact sums (elevation_pass); RMS errors below 1 mm, 0.01 and 10 % of the curvature's
  !> own RMS. grid_holds is false for a point whose differences leave the area. Fails with
  !> a wrong difference (spacing, sign, the mixed term's half) or window end.
  subroutine window_ends(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(wave_grid_type) :: g
    type(rng_type) :: rng
    real(wp) :: u(3), t, x, y, e(nep, 2), ex(nep, 2), err(3), rms_curv, none(0)
    integer :: i, j
    rng = new_rng(5)
    call new_irregular_sea(field, 4.0_wp, pi/2, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, .true., &
                           .true., rng, 0.0_wp)
    g = level5_grid(field, 40.0_wp)
    err = 0.0_wp
    rms_curv = 0.0_wp
    do i = 1, 500
      call rng_uniform(rng, u(1))
      call rng_uniform(rng, u(2))
      call rng_uniform(rng, u(3))
      t = 30.0_wp + 9.8_wp*u(1)
      x = -6.0_wp + 12.0_wp*u(2)
      y = 11.0_wp + 4.0_wp*u(3)
      call check_true(state, grid_holds(g, [t, t + 0.1_wp], x, y), "grid holds the point")
      call grid_ends(g, [t, t + 0.1_wp], x, y, e)
      do j = 1, 2
        call elevation_pass(field, t + 0.1_wp*(j - 1), x, y, 1, none, none, ex(:, j:j))
      end do
      err(1) = err(1) + sum((e(1, :) - ex(1, :))**2)
      err(2) = err(2) + sum((e(3:4, :) - ex(3:4, :))**2)
      err(3) = err(3) + sum((e(5:7, :) - ex(5:7, :))**2)
      rms_curv = rms_curv + sum(ex(5:7, :)**2)
    end do
    err = sqrt(err/1000.0_wp)
    rms_curv = sqrt(rms_curv/1000.0_wp)
    call note(state, "eta RMS error (m)", err(1))
    call note(state, "slope RMS error (-)", err(2))
    call note(state, "curvature RMS error (1/m)", err(3))
    call note(state, "curvature RMS (1/m)", rms_curv)
    call check(state, err(1), 0.0_wp, "eta RMS error", abs_tol=1.0e-3_wp)
    call check(state, err(2), 0.0_wp, "slope RMS error", abs_tol=1.0e-2_wp)
    call check(state, err(3)/rms_curv, 0.0_wp, "curvature RMS error (of its RMS)", &
               abs_tol=0.1_wp)
    call check_true(state, .not. grid_holds(g, [30.0_wp, 30.1_wp], 6.8_wp, 12.0_wp), &
                    "a point half a spacing from the edge is not held")
  end subroutine window_ends

  !> The default grid (1 m, 0.1 s, 3 m deep) of a Level 5 sea, prepared over x -7..7 m,
  !> y 10..16 m from 30 s to t_end.
  function level5_grid(field, t_end) result(g)
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t_end
    type(wave_grid_type) :: g
    g = new_wave_grid(field, 1.0_wp, 0.1_wp, 0.0_wp, 3.0_wp, .true.)
    call grid_prepare(g, field, 30.0_wp, t_end, &
                      reshape([-7.0_wp, 10.0_wp, 7.0_wp, 16.0_wp], [2, 2]))
  end function level5_grid

end module test_wave_grid
