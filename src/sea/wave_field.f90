!> The wave field: regular Airy and Stokes second-order waves and the short-crested
!> irregular sea of paper eq. (43) with the review's amplitude (§1.9):
!>   eta = sum_i a_i cos(theta_i),  theta_i = w_i t + eps_i - k_i (x cos g_i + y sin g_i),
!>   a_ij = sqrt(2 S_i dw D_j),  deep water k = w^2/g,
!> where S_i dw is the exact integral of S over bin i (closed form), i.e. S_i is the bin
!> average of S, not S at the (jittered) frequency: the discrete variance then equals the
!> band's m0 exactly instead of scattering by ~1 % with the jitter.
!> Directions g are propagation directions in the inertial frame, from N1 towards N2.
!> Frame N has z down, so the free surface is z = -eta and depth below it is z + eta.
!>
!> Kinematics are linear (also for Stokes-2: in deep water the second-order potential
!> vanishes, so only the elevation gets the k a^2/2 cos(2 theta) term), evaluated with
!> Wheeler stretching: the decay exp(-k d) uses the depth d = z + eta below the
!> instantaneous surface, so crests do not blow the high-frequency components up; points
!> above the surface get zero velocity and pressure.
!>
!> Speed: components sit in contiguous arrays; phases are evaluated in chunks with the
!> vectorisable fast_sincos; for fixed points (probes) the spatial phasors are precomputed
!> and the time phasors advanced by rotation, so an evaluation is a dot product.
module davit_sea_wave_field
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_core_fastmath, only: fast_sincos
  use davit_core_random, only: rng_type, rng_uniform
  use davit_sea_spectrum, only: spectrum_m0, spectrum_band_fraction
  use davit_sea_spreading, only: spreading_weights, spreading_quantiles
  implicit none
  private
  public :: wave_field_type, wave_none, wave_airy, wave_stokes2, wave_irregular
  public :: new_calm_sea, new_regular_wave, new_irregular_sea, new_single_sum_sea, wave_ramp
  public :: single_random, single_equal_energy
  public :: wave_elevation, wave_kinematics
  public :: point_phasors, time_phasors, rotation_phasors, advance_phasors
  public :: elevation_from_phasors, wave_chunk, component_phases

  integer, parameter :: wave_none = 0, wave_airy = 1, wave_stokes2 = 2, wave_irregular = 3
  !> Directions of the single-summation sea: drawn at random from the spreading, or the
  !> medians of nd equal-energy sectors, each used once per nd frequencies.
  integer, parameter :: single_random = 1, single_equal_energy = 2
  !> Components processed per block (fits the stack and L1 cache). Every loop over the
  !> components works in blocks of this size: scratch arrays sized by the number of
  !> components would live on the stack (-fstack-arrays) and overflow it for large seas
  !> (5000 x 361 components are 14 MB per array, issue 19 class 1).
  integer, parameter :: chunk = 128
  integer, parameter :: wave_chunk = chunk

  type :: wave_field_type
    !> Wave model: wave_none, wave_airy, wave_stokes2 or wave_irregular.
    integer :: kind = wave_none
    !> Number of wave components.
    integer :: n = 0
    !> Per component: frequency omega [rad/s], wave number k [1/m] and its components
    !> kx, ky along N1, N2 [1/m], amplitude [m] and phase eps [rad].
    real(wp), allocatable :: omega(:), k(:), kx(:), ky(:), amplitude(:), phase(:)
    !> Propagation direction of each component [rad], and its cosine and sine.
    real(wp), allocatable :: direction(:), cos_dir(:), sin_dir(:)
    !> Smooth start: forcing scaled by (1 - cos(pi t/T))/2 for t < ramp_time [s].
    real(wp) :: ramp_time = 0.0_wp
  end type wave_field_type

contains

  pure subroutine new_calm_sea(field)
    !> The field, made calm (no components).
    type(wave_field_type), intent(out) :: field
    field%kind = wave_none
    call allocate_components(field, 0)
  end subroutine new_calm_sea

  !> Regular wave of height H = 2a (exact at second order, review §1.9) and period T.
  pure subroutine new_regular_wave(field, kind, height, period, direction, phase, ramp_time)
    !> The field made.
    type(wave_field_type), intent(out) :: field
    !> Wave model, wave_airy or wave_stokes2.
    integer, intent(in) :: kind
    !> Height H [m], period T [s], propagation direction from N1 towards N2 [rad], phase
    !> [rad] and ramp time [s] of the smooth start.
    real(wp), intent(in) :: height, period, direction, phase, ramp_time
    call allocate_components(field, 1)
    field%kind = kind
    field%omega(1) = 2.0_wp*pi/period
    field%amplitude(1) = 0.5_wp*height
    field%phase(1) = phase
    field%direction(1) = direction
    field%ramp_time = ramp_time
    call finish_components(field)
  end subroutine new_regular_wave

  !> Short-crested sea: nf frequency bins in (w_min, w_max) times nd directions over
  !> mean +- window with cos-2s weights (renormalised). With `jitter` each frequency is drawn
  !> uniformly inside its bin; with `independent` every (frequency, direction) component
  !> draws its own frequency, otherwise the nd directions of a bin share one (eq. 43
  !> literally). Sharing makes the sea non-ergodic: at a fixed point the directions of one
  !> bin interfere at a fixed phase, so a 30-min record's variance scatters by about +-18 %
  !> between seeds instead of about +-7 % (predicted std for H = 4 m, tested).
  !> Random numbers are drawn in a fixed order: for each bin, the shared jitter (if not
  !> independent), then for each direction its jitter (if independent) and its phase.
  subroutine new_irregular_sea(field, height, direction, s, window, nf, nd, w_min, w_max, &
                               jitter, independent, rng, ramp_time)
    !> The field made.
    type(wave_field_type), intent(out) :: field
    !> Height H [m], mean propagation direction from N1 towards N2 [rad], half-width of
    !> the direction window [rad], band limits w_min, w_max [rad/s] and ramp time [s].
    real(wp), intent(in) :: height, direction, window, w_min, w_max, ramp_time
    !> Spreading exponent s, number of frequency bins nf and of directions nd.
    integer, intent(in) :: s, nf, nd
    !> Frequencies drawn inside their bins (jitter), one per component (independent).
    logical, intent(in) :: jitter, independent
    !> The random-number generator the frequencies and phases are drawn from.
    type(rng_type), intent(inout) :: rng
    real(wp) :: dw, u, w, gam(nd), weight(nd), bin_m0
    integer :: i, j, c
    call allocate_components(field, nf*nd)
    field%kind = wave_irregular
    field%ramp_time = ramp_time
    dw = (w_max - w_min)/real(nf, wp)
    call spreading_weights(nd, window, s, gam, weight)
    c = 0
    do i = 1, nf
      bin_m0 = spectrum_m0(height)*spectrum_band_fraction(w_min + (i - 1)*dw, &
                                                          w_min + i*dw, height)
      w = w_min + (real(i, wp) - 0.5_wp)*dw
      if (jitter .and. .not. independent) w = draw_in_bin(rng, w_min, dw, i)
      do j = 1, nd
        c = c + 1
        if (jitter .and. independent) w = draw_in_bin(rng, w_min, dw, i)
        field%omega(c) = w
        field%direction(c) = direction + gam(j)
        field%amplitude(c) = sqrt(2.0_wp*bin_m0*weight(j))
        call rng_uniform(rng, u)
        field%phase(c) = 2.0_wp*pi*u
      end do
    end do
    call finish_components(field)
  end subroutine new_irregular_sea

  !> Single-summation short-crested sea: nf frequency bins, ONE direction each (as in
  !> OrcaFlex's and WAMIT's "single summation" or Jefferys' equal-energy method), so the
  !> sea has nf components instead of nf x nd; each carries its whole bin's energy,
  !> a_i = sqrt(2 S_i dw), so Hs and the frequency spectrum are exactly those of the double
  !> summation (eq. 43). The directions follow the truncated cos-2s spreading of eq. 45:
  !> `mode` single_random draws each from its inverse distribution; single_equal_energy
  !> splits the spreading into nd sectors of equal energy and gives each consecutive run of
  !> nd frequencies every sector's median once, in a random order (a monotone assignment
  !> would make the crest pattern spiral with frequency). Unlike eq. 43 with shared
  !> frequencies, no two components share a frequency, so the sea is ergodic at any point.
  !> Random numbers, for each run of nd bins (equal energy): nd - 1 for the order; then
  !> for each bin: its jitter (if jitter), its direction (random), its phase.
  subroutine new_single_sum_sea(field, height, direction, s, window, nf, nd, w_min, w_max, &
                                jitter, mode, rng, ramp_time)
    !> The field made.
    type(wave_field_type), intent(out) :: field
    !> Height H [m], mean propagation direction from N1 towards N2 [rad], half-width of
    !> the direction window [rad], band limits w_min, w_max [rad/s] and ramp time [s].
    real(wp), intent(in) :: height, direction, window, w_min, w_max, ramp_time
    !> Spreading exponent s, number of frequency bins nf, number of sectors nd and the
    !> direction mode (single_random or single_equal_energy).
    integer, intent(in) :: s, nf, nd, mode
    !> Frequencies drawn inside their bins when true.
    logical, intent(in) :: jitter
    !> The random-number generator the order, frequencies, directions and phases come from.
    type(rng_type), intent(inout) :: rng
    real(wp) :: dw, u, w, sector(nd), gam(1)
    integer :: i, order(nd)
    call allocate_components(field, nf)
    field%kind = wave_irregular
    field%ramp_time = ramp_time
    dw = (w_max - w_min)/real(nf, wp)
    call spreading_quantiles([((real(i, wp) - 0.5_wp)/real(nd, wp), i = 1, nd)], window, s, &
                             sector)
    do i = 1, nf
      if (mode == single_equal_energy .and. mod(i - 1, nd) == 0) call shuffle(rng, order)
      w = w_min + (real(i, wp) - 0.5_wp)*dw
      if (jitter) w = draw_in_bin(rng, w_min, dw, i)
      field%omega(i) = w
      if (mode == single_equal_energy) then
        field%direction(i) = direction + sector(order(mod(i - 1, nd) + 1))
      else
        call rng_uniform(rng, u)
        call spreading_quantiles([u], window, s, gam)
        field%direction(i) = direction + gam(1)
      end if
      field%amplitude(i) = sqrt(2.0_wp*spectrum_m0(height)* &
                                spectrum_band_fraction(w_min + (i - 1)*dw, w_min + i*dw, height))
      call rng_uniform(rng, u)
      field%phase(i) = 2.0_wp*pi*u
    end do
    call finish_components(field)
  end subroutine new_single_sum_sea

  !> A random permutation of 1..n (Fisher-Yates, n - 1 draws).
  subroutine shuffle(rng, order)
    !> The random-number generator (n - 1 draws).
    type(rng_type), intent(inout) :: rng
    !> The permutation of 1..n, n its size.
    integer, intent(out) :: order(:)
    integer :: i, j, tmp
    real(wp) :: u
    order = [(i, i = 1, size(order))]
    do i = size(order), 2, -1
      call rng_uniform(rng, u)
      j = min(int(u*real(i, wp)) + 1, i)
      tmp = order(i)
      order(i) = order(j)
      order(j) = tmp
    end do
  end subroutine shuffle

  !> Uniform frequency inside bin i of width dw starting at w_min.
  real(wp) function draw_in_bin(rng, w_min, dw, i) result(w)
    !> The random-number generator (one draw).
    type(rng_type), intent(inout) :: rng
    !> Lower end of the band [rad/s] and width of a bin [rad/s].
    real(wp), intent(in) :: w_min, dw
    !> Index of the bin, from 1.
    integer, intent(in) :: i
    real(wp) :: u
    call rng_uniform(rng, u)
    w = w_min + (real(i - 1, wp) + u)*dw
  end function draw_in_bin

  pure subroutine allocate_components(field, n)
    !> The field whose component arrays are allocated.
    type(wave_field_type), intent(inout) :: field
    !> Number of components.
    integer, intent(in) :: n
    field%n = n
    allocate (field%omega(n), field%k(n), field%kx(n), field%ky(n), field%amplitude(n), &
              field%phase(n), field%direction(n), field%cos_dir(n), field%sin_dir(n))
  end subroutine allocate_components

  !> Deep-water dispersion k = w^2/g and wave-number components.
  pure subroutine finish_components(field)
    !> The field whose wave numbers and direction cosines are filled.
    type(wave_field_type), intent(inout) :: field
    field%k = field%omega**2/gravity
    field%cos_dir = cos(field%direction)
    field%sin_dir = sin(field%direction)
    field%kx = field%k*field%cos_dir
    field%ky = field%k*field%sin_dir
  end subroutine finish_components

  !> Ramp factor (1 - cos(pi t/T))/2 for t < T, then 1.
  pure real(wp) function wave_ramp(field, t) result(r)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time [s].
    real(wp), intent(in) :: t
    r = 1.0_wp
    if (t <= 0.0_wp .and. field%ramp_time > 0.0_wp) then
      r = 0.0_wp
    else if (t < field%ramp_time) then
      r = 0.5_wp*(1.0_wp - cos(pi*t/field%ramp_time))
    end if
  end function wave_ramp

  !> Surface elevation eta(x, y, t) [m], positive up.
  pure real(wp) function wave_elevation(field, t, x, y) result(eta)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time t [s] and horizontal position x, y in the inertial frame N [m].
    real(wp), intent(in) :: t, x, y
    real(wp) :: s(chunk), c(chunk)
    eta = 0.0_wp
    if (field%kind == wave_none) return
    call ramped_elevation(field, t, x, y, wave_ramp(field, t), eta, s, c)
  end function wave_elevation

  !> The elevation at (x, y) at time t: the components' sum of a cos(theta), ramped by r
  !> (with the second-order Stokes term of a regular 'stokes2' wave); s, c keep the last
  !> block's sin(theta), cos(theta) (every component's while n <= chunk).
  pure subroutine ramped_elevation(field, t, x, y, r, eta, s, c)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time t [s], horizontal position x, y in the inertial frame N [m], ramp factor r.
    real(wp), intent(in) :: t, x, y, r
    !> Elevation eta [m], positive up; s, c the last block's sin and cos of the phases.
    real(wp), intent(out) :: eta, s(:), c(:)
    integer :: i0, m
    eta = 0.0_wp
    do i0 = 1, field%n, chunk
      m = min(chunk, field%n - i0 + 1)
      call component_phases(field, i0, m, t, x, y, s, c)
      eta = eta + sum(field%amplitude(i0:i0 + m - 1)*c(1:m))
    end do
    if (field%kind == wave_stokes2) then
      eta = r*eta + stokes_correction(field, eta, r)
    else
      eta = r*eta
    end if
  end subroutine ramped_elevation

  !> Second-order Stokes term k a^2/2 cos(2 theta) of the (ramped) regular wave, from the
  !> unramped first-order elevation eta1 = a cos(theta): cos(2 theta) = 2 cos^2 - 1.
  pure real(wp) function stokes_correction(field, eta1, r) result(e2)
    !> The regular wave field.
    type(wave_field_type), intent(in) :: field
    !> Unramped first-order elevation eta1 [m] and ramp factor r.
    real(wp), intent(in) :: eta1, r
    real(wp) :: a, ct
    a = field%amplitude(1)
    ct = eta1/a
    e2 = 0.5_wp*field%k(1)*(r*a)**2*(2.0_wp*ct*ct - 1.0_wp)
  end function stokes_correction

  !> Elevation, water velocity and acceleration (inertial, z down) and dynamic pressure at
  !> the point p = (x, y, z). The phases are evaluated once: the elevation (needed first for
  !> the stretched depth) and the kinematics share them.
  pure subroutine wave_kinematics(field, t, p, eta, velocity, acceleration, pressure)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time t [s] and point p in the inertial frame N, z down [m].
    real(wp), intent(in) :: t, p(3)
    !> Elevation eta [m] (positive up), water velocity [m/s] and acceleration [m/s^2]
    !> (inertial, z down) and dynamic pressure [Pa] at p.
    real(wp), intent(out) :: eta, velocity(3), acceleration(3), pressure
    real(wp) :: s(chunk), c(chunk), e(chunk), r, d
    integer :: i0, m
    velocity = 0.0_wp
    acceleration = 0.0_wp
    pressure = 0.0_wp
    eta = 0.0_wp
    if (field%kind == wave_none) return
    r = wave_ramp(field, t)
    call ramped_elevation(field, t, p(1), p(2), r, eta, s, c)
    d = p(3) + eta
    if (d < 0.0_wp) return
    ! a exp(-k d) w: the orbital speed of each component at the stretched depth (one block:
    ! the phases of the elevation pass are still in s, c)
    do i0 = 1, field%n, chunk
      m = min(chunk, field%n - i0 + 1)
      if (field%n > chunk) call component_phases(field, i0, m, t, p(1), p(2), s, c)
      associate (a => field%amplitude(i0:i0 + m - 1), k => field%k(i0:i0 + m - 1), &
                 w => field%omega(i0:i0 + m - 1), cg => field%cos_dir(i0:i0 + m - 1), &
                 sg => field%sin_dir(i0:i0 + m - 1))
        e(1:m) = a*exp(-k*d)
        pressure = pressure + sum(e(1:m)*c(1:m))
        e(1:m) = e(1:m)*w
        velocity(1) = velocity(1) + sum(e(1:m)*c(1:m)*cg)
        velocity(2) = velocity(2) + sum(e(1:m)*c(1:m)*sg)
        velocity(3) = velocity(3) + sum(e(1:m)*s(1:m))
        e(1:m) = e(1:m)*w
        acceleration(1) = acceleration(1) - sum(e(1:m)*s(1:m)*cg)
        acceleration(2) = acceleration(2) - sum(e(1:m)*s(1:m)*sg)
        acceleration(3) = acceleration(3) + sum(e(1:m)*c(1:m))
      end associate
    end do
    pressure = r*rho_water*gravity*pressure
    velocity = r*velocity
    acceleration = r*acceleration
  end subroutine wave_kinematics

  !> sin and cos of the phases theta_i = w_i t + eps_i - kx_i x - ky_i y of the m components
  !> from i0 on, into s(1:m), c(1:m) (m <= wave_chunk: no scratch sized by the sea).
  pure subroutine component_phases(field, i0, m, t, x, y, s, c)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> First component i0 and number m of components (m <= wave_chunk).
    integer, intent(in) :: i0, m
    !> Time t [s] and horizontal position x, y in the inertial frame N [m].
    real(wp), intent(in) :: t, x, y
    !> sin and cos of the m phases, in s(1:m) and c(1:m).
    real(wp), intent(out) :: s(:), c(:)
    real(wp) :: th(chunk)
    integer :: i1
    i1 = i0 + m - 1
    th(1:m) = field%omega(i0:i1)*t + field%phase(i0:i1) - field%kx(i0:i1)*x - &
              field%ky(i0:i1)*y
    call fast_sincos(th(1:m), s(1:m), c(1:m))
  end subroutine component_phases

  !> Spatial phasors of fixed points: cb = cos(k . x), sb = sin(k . x), shape (n, np).
  pure subroutine point_phasors(field, x, y, cb, sb)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Horizontal positions x, y of the fixed points in the inertial frame N [m].
    real(wp), intent(in) :: x(:), y(:)
    !> cos(k . x) and sin(k . x), shape (components, points).
    real(wp), intent(out) :: cb(:, :), sb(:, :)
    real(wp) :: th(chunk)
    integer :: j, i0, i1
    do j = 1, size(x)
      do i0 = 1, field%n, chunk
        i1 = min(field%n, i0 + chunk - 1)
        th(1:i1 - i0 + 1) = field%kx(i0:i1)*x(j) + field%ky(i0:i1)*y(j)
        call fast_sincos(th(1:i1 - i0 + 1), sb(i0:i1, j), cb(i0:i1, j))
      end do
    end do
  end subroutine point_phasors

  !> Time phasors a cos(w t + eps), a sin(w t + eps).
  pure subroutine time_phasors(field, t, ca, sa)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time [s].
    real(wp), intent(in) :: t
    !> Time phasors a cos(w t + eps) and a sin(w t + eps) [m], one per component.
    real(wp), intent(out) :: ca(:), sa(:)
    call phase_sincos(field, t, .true., sa, ca)
    ca = field%amplitude*ca
    sa = field%amplitude*sa
  end subroutine time_phasors

  !> Rotation factors cos(w dt), sin(w dt) for advancing time phasors by dt.
  pure subroutine rotation_phasors(field, dt, cr, sr)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time step dt the phasors are advanced by [s].
    real(wp), intent(in) :: dt
    !> cos(w dt) and sin(w dt), one per component.
    real(wp), intent(out) :: cr(:), sr(:)
    call phase_sincos(field, dt, .false., sr, cr)
  end subroutine rotation_phasors

  !> sin and cos of every component's phase w t (+ eps with with_phase), a chunk at a time.
  pure subroutine phase_sincos(field, t, with_phase, s, c)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time [s].
    real(wp), intent(in) :: t
    !> True to add each component's phase eps to w t.
    logical, intent(in) :: with_phase
    !> sin and cos of the phases, one per component.
    real(wp), intent(out) :: s(:), c(:)
    real(wp) :: th(chunk)
    integer :: i0, i1
    do i0 = 1, field%n, chunk
      i1 = min(field%n, i0 + chunk - 1)
      if (with_phase) then
        th(1:i1 - i0 + 1) = field%omega(i0:i1)*t + field%phase(i0:i1)
      else
        th(1:i1 - i0 + 1) = field%omega(i0:i1)*t
      end if
      call fast_sincos(th(1:i1 - i0 + 1), s(i0:i1), c(i0:i1))
    end do
  end subroutine phase_sincos

  !> Advance time phasors by the rotation (cr, sr): angle addition, no trigonometry.
  pure subroutine advance_phasors(ca, sa, cr, sr)
    !> Time phasors a cos(w t + eps), a sin(w t + eps) [m], advanced in place.
    real(wp), intent(inout) :: ca(:), sa(:)
    !> Rotation factors cos(w dt), sin(w dt).
    real(wp), intent(in) :: cr(:), sr(:)
    real(wp) :: tmp
    integer :: i
    do i = 1, size(ca)
      tmp = ca(i)*cr(i) - sa(i)*sr(i)
      sa(i) = sa(i)*cr(i) + ca(i)*sr(i)
      ca(i) = tmp
    end do
  end subroutine advance_phasors

  !> eta at fixed points from phasors: cos(A - B) = cos A cos B + sin A sin B.
  pure subroutine elevation_from_phasors(field, t, ca, sa, cb, sb, eta)
    !> The wave field.
    type(wave_field_type), intent(in) :: field
    !> Time t [s], time phasors ca, sa [m] and spatial phasors cb, sb (point_phasors).
    real(wp), intent(in) :: t, ca(:), sa(:), cb(:, :), sb(:, :)
    !> Elevation eta [m] at each fixed point, positive up.
    real(wp), intent(out) :: eta(:)
    real(wp) :: r, eta1
    integer :: j
    r = wave_ramp(field, t)
    do j = 1, size(eta)
      eta1 = sum(ca*cb(:, j) + sa*sb(:, j))
      eta(j) = r*eta1
      if (field%kind == wave_stokes2) eta(j) = eta(j) + stokes_correction(field, eta1, r)
    end do
  end subroutine elevation_from_phasors

end module davit_sea_wave_field
