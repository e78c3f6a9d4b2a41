!> Sea: spectrum (eq. 44) and spreading (eq. 45) against closed forms and the review's
!> numbers (A1, A2, §1.9); the wave field against linear potential-flow identities,
!> dispersion and the Stokes-2 profile; statistics of generated records against their
!> exact expectation and variance over random phases; determinism.
module test_sea
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_core_fastmath, only: fast_sincos
  use davit_core_random, only: rng_type, new_rng, rng_uniform
  use davit_sea_spectrum, only: spectrum_density, spectrum_m0, spectrum_peak_omega, &
                                spectrum_band_fraction, spectrum_u
  use davit_sea_spreading, only: spreading_density, spreading_weights, spreading_quantiles
  use davit_sea_wave_field, only: wave_field_type, new_regular_wave, new_irregular_sea, &
                                  new_single_sum_sea, single_random, single_equal_energy, &
                                  wave_elevation, wave_kinematics, wave_airy, wave_stokes2, &
                                  point_phasors, time_phasors, rotation_phasors, &
                                  advance_phasors, elevation_from_phasors, wave_ramp
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_sea

contains

  function collect_sea() result(suite)
    type(suite_type) :: suite
    suite%name = "sea"
    suite%cases = [new_case("fast_sincos_vs_libm", sincos_accuracy), &
                   new_case("rng_uniform_and_streams_independent", rng_quality), &
                   new_case("spectrum_moments_A1", spectrum_moments), &
                   new_case("discrete_m0", discrete_m0), &
                   new_case("spreading_normalisation_A2", spreading_normalisation), &
                   new_case("single_summation_spectrum", single_sum_spectrum), &
                   new_case("single_summation_equal_energy_sectors", single_sum_sectors), &
                   new_case("single_summation_random_directions", single_sum_random), &
                   new_case("level_presets_and_periods_G18", level_presets), &
                   new_case("dispersion_phase_speed", dispersion), &
                   new_case("stokes2_profile", stokes_profile), &
                   new_case("potential_flow_identities", potential_flow), &
                   new_case("ramp_smooth_start", ramp), &
                   new_case("phasor_path_equals_direct", phasor_path), &
                   new_case("record_statistics", record_statistics), &
                   new_case("seed_determinism_threads", determinism)]
  end function collect_sea

  !> Composite Simpson rule of S over (a, b) with n (even) panels.
  real(wp) function simpson_spectrum(a, b, n, height) result(total)
    real(wp), intent(in) :: a, b, height
    integer, intent(in) :: n
    real(wp) :: h
    integer :: i
    h = (b - a)/n
    total = spectrum_density(a, height) + spectrum_density(b, height)
    do i = 1, n - 1
      total = total + merge(4.0_wp, 2.0_wp, mod(i, 2) == 1)*spectrum_density(a + i*h, height)
    end do
    total = total*h/3.0_wp
  end function simpson_spectrum

  subroutine sincos_accuracy(state)
    type(case_state), intent(inout) :: state
    real(wp) :: x, s, c, err
    integer :: i
    type(rng_type) :: rng
    rng = new_rng(7)
    err = 0.0_wp
    do i = 1, 200000
      call rng_uniform(rng, x)
      x = (x - 0.5_wp)*2.0e4_wp
      call fast_sincos(x, s, c)
      err = max(err, abs(s - sin(x)), abs(c - cos(x)))
    end do
    call note(state, "max |error| for |x| < 1e4", err)
    call check(state, err, 0.0_wp, "fast_sincos error", abs_tol=1e-15_wp)
  end subroutine sincos_accuracy

  !> Uniform moments (mean 1/2, variance 1/12) and independence of neighbouring seeds and
  !> streams: the correlation of n-sample vectors has standard deviation 1/sqrt(n), so over
  !> 40 seeds x 40 streams' pairs its RMS must be within 15 % of that and its maximum below
  !> 5/sqrt(n).
  subroutine rng_quality(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: n = 2000, m = 40
    real(wp) :: u(n, m), v(n, m), c, rms, cmax, mean, var
    type(rng_type) :: rng
    integer :: i, j, k, pairs
    do j = 1, m
      rng = new_rng(j)
      do i = 1, n
        call rng_uniform(rng, u(i, j))
      end do
      rng = new_rng(7, stream=j)
      do i = 1, n
        call rng_uniform(rng, v(i, j))
      end do
    end do
    mean = sum(u)/size(u)
    var = sum((u - mean)**2)/size(u)
    call check(state, mean, 0.5_wp, "mean", abs_tol=4/sqrt(12.0_wp*size(u)))
    call check(state, var, 1/12.0_wp, "variance", rel_tol=0.02_wp)
    do k = 1, 2
      rms = 0.0_wp; cmax = 0.0_wp; pairs = 0
      do j = 1, m
        do i = j + 1, m
          if (k == 1) then
            c = corr(u(:, i), u(:, j))
          else
            c = corr(v(:, i), v(:, j))
          end if
          rms = rms + c*c; cmax = max(cmax, abs(c)); pairs = pairs + 1
        end do
      end do
      rms = sqrt(rms/pairs)
      call note(state, trim(merge("seeds  ", "streams", k == 1))//": rms corr * sqrt(n)", &
                rms*sqrt(real(n, wp)))
      call check(state, rms*sqrt(real(n, wp)), 1.0_wp, "rms correlation", rel_tol=0.15_wp)
      call check_true(state, cmax < 5/sqrt(real(n, wp)), "max correlation below 5 sigma")
    end do
  contains
    pure real(wp) function corr(a, b)
      real(wp), intent(in) :: a(:), b(:)
      real(wp) :: da(size(a)), db(size(b))
      da = a - sum(a)/size(a)
      db = b - sum(b)/size(b)
      corr = sum(da*db)/sqrt(sum(da*da)*sum(db*db))
    end function corr
  end subroutine rng_quality

  !> m0 = 0.37 U^4/g^4 against quadrature; Hs = 0.9971 H; w_p = 0.9877/sqrt(H) and the
  !> numerical maximum of S; band fractions in (0.3, 3): 0.9943 (2.5 m) and 0.9890 (4 m).
  subroutine spectrum_moments(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: heights(2) = [2.5_wp, 4.0_wp], fractions(2) = [0.9943_wp, 0.9890_wp]
    real(wp) :: h, m0q, wlo, whi, w1, w2
    integer :: i, it
    do i = 1, 2
      h = heights(i)
      m0q = simpson_spectrum(0.05_wp, 60.0_wp, 200000, h)
      call check(state, spectrum_m0(h), m0q, "analytic m0 vs quadrature", rel_tol=1e-6_wp)
      call check(state, 4*sqrt(spectrum_m0(h))/h, 0.9971_wp, "Hs/H", abs_tol=1e-4_wp)
      ! the review's 0.9877 is sqrt(0.4) 9.81/6.28 = 0.98796 rounded to 4 digits
      call check(state, spectrum_peak_omega(h), 0.9877_wp/sqrt(h), "w_p", rel_tol=5e-4_wp)
      ! golden-section search for the maximum of S
      wlo = 0.2_wp; whi = 2.0_wp
      do it = 1, 200
        w1 = whi - 0.618033988749895_wp*(whi - wlo)
        w2 = wlo + 0.618033988749895_wp*(whi - wlo)
        if (spectrum_density(w1, h) > spectrum_density(w2, h)) then
          whi = w2
        else
          wlo = w1
        end if
      end do
      call check(state, spectrum_peak_omega(h), 0.5_wp*(wlo + whi), "w_p = argmax S", &
                 rel_tol=1e-6_wp)
      call check(state, spectrum_band_fraction(0.3_wp, 3.0_wp, h), fractions(i), &
                 "band fraction (0.3, 3)", abs_tol=1e-4_wp)
      call check(state, spectrum_band_fraction(0.3_wp, 3.0_wp, h)*spectrum_m0(h), &
                 simpson_spectrum(0.3_wp, 3.0_wp, 20000, h), "band fraction vs quadrature", &
                 rel_tol=1e-8_wp)
    end do
    call check(state, spectrum_u(4.0_wp), 12.56_wp, "U = 6.28 sqrt(H)", rel_tol=1e-12_wp)
  end subroutine spectrum_moments

  !> Sum of a^2/2 over the generated components vs the band's analytic m0 (0.5 %), and
  !> m0 of the whole spectrum times the band fraction of the review (A1).
  subroutine discrete_m0(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp) :: expected
    integer :: seed, jit
    do jit = 0, 1
      do seed = 1, 3
        rng = new_rng(seed)
        call new_irregular_sea(field, 4.0_wp, 0.5_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, &
                               jit == 1, .true., rng, 0.0_wp)
        expected = spectrum_m0(4.0_wp)*spectrum_band_fraction(0.3_wp, 3.0_wp, 4.0_wp)
        call check(state, sum(field%amplitude**2)/2, expected, "discrete m0", rel_tol=5e-3_wp)
        call check(state, sum(field%amplitude**2)/2/spectrum_m0(4.0_wp), 0.9890_wp, &
                   "discrete m0 / m0", abs_tol=1e-3_wp)
        if (seed == 1) call note(state, "discrete m0/band m0 - 1 (jitter "// &
                                 achar(48 + jit)//")", sum(field%amplitude**2)/2/expected - 1)
      end do
    end do
  end subroutine discrete_m0

  subroutine spreading_normalisation(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: window_fraction_s1 = 0.609_wp
    real(wp) :: total, part, h, g, gam(13), weight(13)
    integer :: s, i, n
    n = 20000
    do s = 1, 10
      h = pi/n
      total = 0.0_wp
      part = 0.0_wp
      do i = 0, n
        g = -0.5_wp*pi + i*h
        total = total + merge(1.0_wp, merge(4.0_wp, 2.0_wp, mod(i, 2) == 1), &
                              i == 0 .or. i == n)*spreading_density(g, s)
      end do
      call check(state, total*h/3, 1.0_wp, "integral of D over (-pi/2, pi/2)", abs_tol=1e-10_wp)
      call spreading_weights(13, pi/6, s, gam, weight)
      call check(state, sum(weight), 1.0_wp, "discrete weights sum", abs_tol=1e-14_wp)
      call check(state, gam(2) - gam(1), 5.0_wp*pi/180, "5 deg spacing", abs_tol=1e-14_wp)
    end do
    ! fraction of the variance inside +-30 deg for s = 1 (review §1.9)
    h = (pi/3)/n
    part = 0.0_wp
    do i = 0, n
      g = -pi/6 + i*h
      part = part + merge(1.0_wp, merge(4.0_wp, 2.0_wp, mod(i, 2) == 1), &
                          i == 0 .or. i == n)*spreading_density(g, 1)
    end do
    call check(state, part*h/3, window_fraction_s1, "+-30 deg fraction, s = 1", abs_tol=1e-3_wp)
  end subroutine spreading_normalisation

  !> The single-summation sea carries each bin's whole energy in one component: a_i^2/2 is
  !> the integral of S over bin i (Simpson, 200 panels), so m0 = Hs^2/16 over the band.
  subroutine single_sum_spectrum(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp) :: dw, worst, bin
    integer :: i, mode
    do mode = single_random, single_equal_energy
      rng = new_rng(7)
      call new_single_sum_sea(field, 4.0_wp, 0.5_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, &
                              .true., mode, rng, 0.0_wp)
      call check_true(state, field%n == 100, "one component per frequency")
      dw = 2.7_wp/100
      worst = 0.0_wp
      do i = 1, 100
        bin = simpson_spectrum(0.3_wp + (i - 1)*dw, 0.3_wp + i*dw, 200, 4.0_wp)
        worst = max(worst, abs(field%amplitude(i)**2/2/bin - 1.0_wp))
        call check_true(state, field%omega(i) >= 0.3_wp + (i - 1)*dw .and. &
                        field%omega(i) <= 0.3_wp + i*dw, "jittered frequency inside its bin")
      end do
      call check(state, worst, 0.0_wp, "bin energy vs Simpson integral of S", abs_tol=1e-8_wp)
      call check(state, 4*sqrt(sum(field%amplitude**2)/2), &
                 4*sqrt(simpson_spectrum(0.3_wp, 3.0_wp, 2000, 4.0_wp)), "Hs of the band", &
                 rel_tol=1e-9_wp)
    end do
  end subroutine single_sum_spectrum

  !> Closed-form CDF of the s = 1 spreading truncated to +-w: with c(g) = g + sin(2g)/2,
  !> F(g) = (c(g) + c(w))/(2 c(w)).
  pure real(wp) function cdf_s1(g, w) result(f)
    real(wp), intent(in) :: g, w
    f = (g + sin(2*g)/2 + w + sin(2*w)/2)/(2*(w + sin(2*w)/2))
  end function cdf_s1

  !> Equal energy: sector j's median direction has F = (j - 1/2)/nd (closed form for
  !> s = 1), and every run of nd frequencies uses each sector exactly once.
  subroutine single_sum_sectors(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp) :: gam(13), rel(130)
    integer :: j, run, hits
    call spreading_quantiles([((j - 0.5_wp)/13, j = 1, 13)], pi/6, 1, gam)
    do j = 1, 13
      call check(state, cdf_s1(gam(j), pi/6), (j - 0.5_wp)/13, "sector median CDF", &
                 abs_tol=1e-7_wp)
    end do
    rng = new_rng(3)
    call new_single_sum_sea(field, 4.0_wp, 0.5_wp, 1, pi/6, 130, 13, 0.3_wp, 3.0_wp, &
                            .true., single_equal_energy, rng, 0.0_wp)
    rel = field%direction - 0.5_wp
    do run = 0, 9
      do j = 1, 13
        hits = count(abs(rel(run*13 + 1:run*13 + 13) - gam(j)) < 1e-12_wp)
        call check_true(state, hits == 1, "each sector once per run of 13 frequencies")
      end do
    end do
    ! not in sector order: the directions of consecutive frequencies are shuffled
    call check_true(state, any(rel(2:13) < rel(1:12)) .and. any(rel(2:13) > rel(1:12)), &
                    "sectors shuffled")
  end subroutine single_sum_sectors

  !> Random directions: over 20000 frequencies the share inside +-15 deg and the mean
  !> direction match the truncated s = 1 and s = 4 spreadings within 4 binomial sigmas.
  subroutine single_sum_random(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    integer, parameter :: n = 20000
    real(wp) :: p, share, h, g
    integer :: s, i
    do s = 1, 4, 3
      rng = new_rng(11)
      call new_single_sum_sea(field, 4.0_wp, 0.0_wp, s, pi/6, n, 13, 0.3_wp, 3.0_wp, &
                              .true., single_random, rng, 0.0_wp)
      if (s == 1) then
        p = cdf_s1(pi/12, pi/6) - cdf_s1(-pi/12, pi/6)
      else
        ! Simpson over +-15 deg and +-30 deg of D (s = 4)
        p = 0.0_wp
        h = (pi/6)/1000
        do i = 0, 1000
          g = -pi/12 + i*h
          p = p + merge(1.0_wp, merge(4.0_wp, 2.0_wp, mod(i, 2) == 1), i == 0 .or. i == 1000)* &
              spreading_density(g, s)
        end do
        p = p*h/3/window_integral(s)
      end if
      share = count(abs(field%direction) < pi/12)/real(n, wp)
      call check(state, share, p, "share inside +-15 deg", abs_tol=4*sqrt(p*(1 - p)/n))
      call check(state, sum(field%direction)/n, 0.0_wp, "mean direction", &
                 abs_tol=4*(pi/6)/sqrt(3.0_wp*n))
      call check_true(state, maxval(abs(field%direction)) <= pi/6 + 1e-12_wp, "inside window")
    end do
  contains
    real(wp) function window_integral(s) result(total)
      integer, intent(in) :: s
      integer :: k
      real(wp) :: hh
      hh = (pi/3)/1000
      total = 0.0_wp
      do k = 0, 1000
        total = total + merge(1.0_wp, merge(4.0_wp, 2.0_wp, mod(k, 2) == 1), &
                              k == 0 .or. k == 1000)*spreading_density(-pi/6 + k*hh, s)
      end do
      total = total*hh/3
    end function window_integral
  end subroutine single_sum_random

  subroutine level_presets(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    call parse_config("t.nml", "&sea level = 4 /", cfg, error)
    call check_true(state, .not. allocated(error), "level 4 deck")
    call check(state, cfg%sea%height, 2.5_wp, "level 4 H", abs_tol=0.0_wp)
    call check(state, cfg%wind%speed, 8.0_wp, "level 4 wind", abs_tol=0.0_wp)
    call check(state, cfg%sea%period, 10.06_wp, "level 4 peak period", abs_tol=0.01_wp)
    call parse_config("t.nml", "&sea level = 5, direction_deg = 45 / &wind speed = 3 /", &
                      cfg, error)
    call check(state, cfg%sea%height, 4.0_wp, "level 5 H", abs_tol=0.0_wp)
    call check(state, cfg%sea%period, 12.72_wp, "level 5 peak period", abs_tol=0.01_wp)
    call check(state, cfg%wind%speed, 3.0_wp, "wind override", abs_tol=0.0_wp)
    call check(state, cfg%wind%direction, pi/4, "wind follows the waves", abs_tol=1e-15_wp)
  end subroutine level_presets

  !> A crest travels at the deep-water phase speed c = g/w along its direction:
  !> eta(x + c tau e, t + tau) = eta(x, t).
  subroutine dispersion(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    real(wp) :: dir, c, tau, x, y, t
    integer :: i
    do i = 0, 3
      dir = 0.4_wp + i*pi/2.3_wp
      call new_regular_wave(field, wave_airy, 2.0_wp, 7.0_wp + i, dir, 0.3_wp, 0.0_wp)
      c = gravity/field%omega(1)
      call check(state, field%k(1), field%omega(1)**2/gravity, "k = w^2/g", rel_tol=1e-15_wp)
      x = 3.0_wp; y = -7.0_wp; t = 12.3_wp; tau = 4.1_wp
      call check(state, wave_elevation(field, t + tau, x + c*tau*cos(dir), y + c*tau*sin(dir)), &
                 wave_elevation(field, t, x, y), "crest moves at g/w", abs_tol=1e-12_wp)
    end do
  end subroutine dispersion

  !> Stokes second order: crest a + k a^2/2, trough -a + k a^2/2; H = 2a exactly.
  subroutine stokes_profile(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    real(wp) :: a, k, e, emax, emin, t
    integer :: i
    call new_regular_wave(field, wave_stokes2, 4.0_wp, 12.72_wp, 0.0_wp, 0.0_wp, 0.0_wp)
    a = 2.0_wp
    k = field%k(1)
    emax = -huge(1.0_wp); emin = huge(1.0_wp)
    do i = 0, 12720
      t = i*1.0e-3_wp
      e = wave_elevation(field, t, 0.0_wp, 0.0_wp)
      emax = max(emax, e); emin = min(emin, e)
    end do
    call note(state, "crest + trough (k a^2)", emax + emin)
    call check(state, emax, a + 0.5_wp*k*a*a, "crest", abs_tol=1e-9_wp)
    call check(state, emin, -a + 0.5_wp*k*a*a, "trough", abs_tol=1e-9_wp)
    call check(state, emax - emin, 2*a, "H = 2a", abs_tol=1e-9_wp)
  end subroutine stokes_profile

  !> Small-amplitude irregular sea (stretching negligible): continuity div u = 0,
  !> irrotationality, linear Euler a = -grad(p)/rho, and the kinematic surface condition
  !> d(eta)/dt = upward velocity at the surface, by central differences.
  subroutine potential_flow(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp), parameter :: h = 1.0e-3_wp, p0(3) = [3.0_wp, -2.0_wp, 1.5_wp], t = 40.0_wp
    real(wp) :: eta, v(3), acc(3), pr, vp(3), vm(3), ep, em, pp, pm, grad(3, 3), gp(3)
    real(wp) :: scale, dpdt, w_up
    integer :: i
    real(wp) :: e3(3, 3)
    e3 = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])*1.0_wp
    rng = new_rng(3)
    call new_irregular_sea(field, 1.0e-3_wp, 0.3_wp, 2, pi/6, 40, 7, 0.3_wp, 2.0_wp, &
                           .true., .true., rng, 0.0_wp)
    call wave_kinematics(field, t, p0, eta, v, acc, pr)
    scale = maxval(abs(v))
    do i = 1, 3
      call wave_kinematics(field, t, p0 + h*e3(:, i), ep, vp, acc, pp)
      call wave_kinematics(field, t, p0 - h*e3(:, i), em, vm, acc, pm)
      grad(:, i) = (vp - vm)/(2*h)
      gp(i) = (pp - pm)/(2*h)
    end do
    call wave_kinematics(field, t, p0, eta, v, acc, pr)
    call check(state, grad(1, 1) + grad(2, 2) + grad(3, 3), 0.0_wp, "div u", &
               abs_tol=1e-5_wp*scale)
    call check(state, grad(3, 2) - grad(2, 3), 0.0_wp, "curl_x", abs_tol=1e-5_wp*scale)
    call check(state, grad(1, 3) - grad(3, 1), 0.0_wp, "curl_y", abs_tol=1e-5_wp*scale)
    call check(state, grad(2, 1) - grad(1, 2), 0.0_wp, "curl_z", abs_tol=1e-5_wp*scale)
    do i = 1, 3
      call check(state, acc(i), -gp(i)/rho_water, "a = -grad p/rho", &
                 abs_tol=1e-5_wp*maxval(abs(acc)))
    end do
    ! kinematic condition at the mean surface (z = 0): d eta/dt = -w (z down)
    dpdt = (wave_elevation(field, t + h, 0.0_wp, 0.0_wp) - &
            wave_elevation(field, t - h, 0.0_wp, 0.0_wp))/(2*h)
    call wave_kinematics(field, t, [0.0_wp, 0.0_wp, 0.0_wp], eta, v, acc, pr)
    w_up = -v(3)
    call check(state, dpdt, w_up, "d eta/dt = w_up at the surface", &
               abs_tol=1e-4_wp*abs(w_up) + 1e-12_wp)
  end subroutine potential_flow

  subroutine ramp(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    call new_regular_wave(field, wave_airy, 2.0_wp, 10.0_wp, 0.0_wp, 0.0_wp, 20.0_wp)
    call check(state, wave_elevation(field, 0.0_wp, 0.0_wp, 0.0_wp), 0.0_wp, "eta(0) = 0", &
               abs_tol=0.0_wp)
    call check(state, wave_ramp(field, 10.0_wp), 0.5_wp, "half ramp", abs_tol=1e-15_wp)
    call check(state, (wave_ramp(field, 1e-3_wp) - wave_ramp(field, 0.0_wp))/1e-3_wp, 0.0_wp, &
               "zero slope at the start", abs_tol=1e-4_wp)
    call check(state, wave_elevation(field, 25.0_wp, 1.0_wp, 0.0_wp), &
               cos(field%omega(1)*25.0_wp - field%k(1)), "full amplitude after the ramp", &
               abs_tol=1e-12_wp)
  end subroutine ramp

  !> Probe phasors advanced by rotation (resynchronised as in the 'sea' scene) reproduce
  !> the direct evaluation over 1800 s.
  subroutine phasor_path(state)
    type(case_state), intent(inout) :: state
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp), allocatable :: cb(:, :), sb(:, :), ca(:), sa(:), cr(:), sr(:)
    real(wp) :: eta(2), x(2), y(2), err, t
    integer :: k
    rng = new_rng(11)
    call new_irregular_sea(field, 4.0_wp, 1.0_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, .true., &
                           .true., rng, 25.0_wp)
    x = [0.0_wp, 150.0_wp]; y = [0.0_wp, -75.0_wp]
    allocate (cb(field%n, 2), sb(field%n, 2), ca(field%n), sa(field%n), cr(field%n), &
              sr(field%n))
    call point_phasors(field, x, y, cb, sb)
    call rotation_phasors(field, 0.25_wp, cr, sr)
    err = 0.0_wp
    do k = 0, 7200
      t = k*0.25_wp
      if (mod(k, 256) == 0) then
        call time_phasors(field, t, ca, sa)
      else
        call advance_phasors(ca, sa, cr, sr)
      end if
      call elevation_from_phasors(field, t, ca, sa, cb, sb, eta)
      err = max(err, abs(eta(1) - wave_elevation(field, t, x(1), y(1))), &
                abs(eta(2) - wave_elevation(field, t, x(2), y(2))))
    end do
    call note(state, "max |phasor - direct| [m]", err)
    call check(state, err, 0.0_wp, "phasor path", abs_tol=1e-10_wp)
  end subroutine phasor_path

  !> Over independent uniform phases, the record's mean square has expectation
  !> sum a^2/2 exactly and variance
  !>   sum_p a_p^4 |C(2w_p)|^2/8 + sum_{p<q} a_p^2 a_q^2 (|C(w_p - w_q)|^2 + |C(w_p + w_q)|^2)/2,
  !> C(d) = (1/N) sum_n exp(i d t_n); the mean has variance sum a_p^2 |C(w_p)|^2/2.
  !> Each of 6 seeds must fall within 4.5 standard deviations; the mean z-score of the
  !> mean square within 4.5/sqrt(6). Both frequency layouts (independent per direction, and
  !> shared as eq. 43 is printed).
  subroutine record_statistics(state)
    type(case_state), intent(inout) :: state
    integer :: mode
    do mode = 1, 2
      call statistics_of(state, mode == 1)
    end do
  end subroutine record_statistics

  subroutine statistics_of(state, independent)
    type(case_state), intent(inout) :: state
    logical, intent(in) :: independent
    integer, parameter :: nseed = 6, nt = 7201
    real(wp), parameter :: dt = 0.25_wp
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp) :: eta(nt), ms, mean, m0, var_ms, var_mean, zsum
    integer :: seed, k
    character(len=:), allocatable :: label
    label = trim(merge("independent", "shared     ", independent))
    zsum = 0.0_wp
    do seed = 1, nseed
      rng = new_rng(100 + seed)
      call new_irregular_sea(field, 4.0_wp, 0.7_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, &
                             .true., independent, rng, 0.0_wp)
      do k = 1, nt
        eta(k) = wave_elevation(field, (k - 1)*dt, 10.0_wp, 20.0_wp)
      end do
      ms = sum(eta**2)/nt
      mean = sum(eta)/nt
      m0 = sum(field%amplitude**2)/2
      call moments_variance(field%omega, field%amplitude, nt, dt, var_ms, var_mean)
      if (seed == 1) then
        call note(state, label//" seed 1: mean square / m0", ms/m0)
        call note(state, label//" seed 1: predicted std of mean square / m0", &
                  sqrt(var_ms)/m0)
        call note(state, label//" seed 1: mean [m]", mean)
      end if
      call check(state, ms, m0, "mean square vs discrete m0", abs_tol=4.5_wp*sqrt(var_ms))
      call check(state, mean, 0.0_wp, "zero mean", abs_tol=4.5_wp*sqrt(var_mean))
      zsum = zsum + (ms - m0)/sqrt(var_ms)
      call note(state, label//" z-score of the mean square, seed "//achar(48 + seed), &
                (ms - m0)/sqrt(var_ms))
    end do
    call check(state, zsum/nseed, 0.0_wp, "mean z-score", abs_tol=4.5_wp/sqrt(real(nseed, wp)))
  end subroutine statistics_of

  subroutine moments_variance(w, a, nt, dt, var_ms, var_mean)
    real(wp), intent(in) :: w(:), a(:), dt
    integer, intent(in) :: nt
    real(wp), intent(out) :: var_ms, var_mean
    integer :: p, q
    var_ms = 0.0_wp
    var_mean = 0.0_wp
    do p = 1, size(w)
      var_ms = var_ms + a(p)**4*c2(2*w(p))/8
      var_mean = var_mean + a(p)**2*c2(w(p))/2
      do q = p + 1, size(w)
        var_ms = var_ms + a(p)**2*a(q)**2*(c2(w(p) - w(q)) + c2(w(p) + w(q)))/2
      end do
    end do
  contains
    !> |C(d)|^2 for N samples at spacing dt.
    pure real(wp) function c2(d)
      real(wp), intent(in) :: d
      real(wp) :: den
      den = nt*sin(0.5_wp*d*dt)
      if (abs(den) < 1e-12_wp) then
        c2 = 1.0_wp
      else
        c2 = (sin(0.5_wp*nt*d*dt)/den)**2
      end if
    end function c2
  end subroutine moments_variance

  !> Same seed: bitwise-identical records, also when generated on several OpenMP threads;
  !> another seed: a different record.
  subroutine determinism(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: ns = 8, nt = 400
    real(wp) :: serial(nt, ns), threaded(nt, ns)
    integer :: s
    do s = 1, ns
      call record(s, serial(:, s))
    end do
    !$omp parallel do num_threads(2) schedule(dynamic) default(none) shared(threaded)
    do s = ns, 1, -1
      call record(s, threaded(:, s))
    end do
    !$omp end parallel do
    call check_true(state, all(serial == threaded), "bitwise identical across threads")
    call check_true(state, any(serial(:, 1) /= serial(:, 2)), "seeds 1 and 2 differ")
  contains
    subroutine record(seed, eta)
      integer, intent(in) :: seed
      real(wp), intent(out) :: eta(:)
      type(wave_field_type) :: field
      type(rng_type) :: rng
      integer :: k
      rng = new_rng(seed)
      call new_irregular_sea(field, 2.5_wp, 0.0_wp, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, &
                             .true., .true., rng, 10.0_wp)
      do k = 1, size(eta)
        eta(k) = wave_elevation(field, k*0.5_wp, 0.0_wp, 0.0_wp)
      end do
    end subroutine record
  end subroutine determinism

end module test_sea
