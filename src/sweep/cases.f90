!> The cases of a sweep: the Cartesian product of the swept values (realisations vary
!> fastest), each case's seed, and the run configuration of a case.
!>
!> Seeds: case i (1-based) gets the i-th output of SplitMix64 (Steele, Lea and Flood 2014)
!> started at the base seed, truncated to its top 31 bits (the deck's seed range). So a
!> case's seed depends only on the base seed and its index, never on threads or order.
!> Every cell (combination of the other inputs) has max_realisations slots (= realisations
!> unless adaptive), so an adaptive sweep's case indices and seeds are fixed by the deck,
!> whichever of them the rounds end up running.
!>
!> Clearance: the initial fender-to-side distance is set by moving the boat and both davit
!> heads (or, on the foundation slings, their anchors) together along the ship's s2 axis,
!> so the boat still hangs plumb in its static equilibrium.
module davit_sweep_cases
  use davit_kinds, only: wp, i8, pi
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type, level_wave_height, level_wind_speed
  use davit_core_random, only: rng_type, new_rng, rng_uniform
  use davit_core_rotation, only: rotation_matrix
  use davit_sea_spectrum, only: spectrum_peak_omega
  use davit_system_model, only: system_type
  use davit_run_scene, only: new_boat_system
  use davit_sweep_keys, only: sweep_config, wave_type_names, case_count
  implicit none
  private
  public :: sweep_case, build_cases, case_config, initial_clearance, splitmix64, case_seed

  !> The inputs of one case, as recorded in the summary.
  type :: sweep_case
    !> Case index (1-based), realisation, seed, sea-state level and wave type (0-based index
    !> into wave_type_names).
    integer :: index = 0, realisation = 0, seed = 0, level = 0, wave_type = 0
    !> Whether the wind is on.
    logical :: wind = .false.
    !> Significant (or regular) wave height [m], wave period [s] and wave direction [deg].
    real(wp) :: wave_height = 0.0_wp, wave_period = 0.0_wp, angle_deg = 0.0_wp
    !> Wind speed [m/s], initial clearance in boat beams, and time step [s].
    real(wp) :: wind_speed = 0.0_wp, clearance_b = 0.0_wp, dt = 0.0_wp
    !> Regular-wave phase epsilon [deg] (that of the base deck unless drawn).
    real(wp) :: phase_deg = 0.0_wp
  end type sweep_case

  !> Random stream of the regular-wave phase (the irregular sea draws on stream 0).
  integer, parameter :: phase_stream = 7

contains

  !> Every combination of the swept values: case k's position in each list is the digit of
  !> k - 1 in the mixed radix (wave types, levels, heights, periods, wind, angles,
  !> clearances, dts, realisations up to max_realisations), so realisations vary fastest
  !> and cell j holds cases (j - 1) max_realisations + 1 .. j max_realisations.
  !> `clearance0` is the base
  !> deck's initial clearance [m] (recorded when clearances are not swept).
  subroutine build_cases(s, clearance0, cases)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The base deck's initial clearance [m].
    real(wp), intent(in) :: clearance0
    !> All the sweep's cases, in index order.
    type(sweep_case), allocatable, intent(out) :: cases(:)
    integer :: sizes(9), digit(9), k, d, rest
    sizes = [size(s%wave_types), size(s%levels), size(s%heights), size(s%periods), &
             size(s%winds), size(s%angles_deg), size(s%clearances_b), size(s%dts), &
             s%max_realisations]
    ! counted in 64 bits: read_sweep refused a list beyond max_cases (a default integer)
    allocate (cases(case_count(s)))
    do k = 1, size(cases)
      rest = k - 1
      do d = size(sizes), 1, -1
        digit(d) = mod(rest, sizes(d)) + 1
        rest = rest/sizes(d)
      end do
      cases(k) = one_case(s, k, digit, clearance0)
    end do
  end subroutine build_cases

  !> Case k from the positions of its values in each list (the order of build_cases).
  function one_case(s, k, digit, clearance0) result(c)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> Case index k, and its value's position in each list (the mixed-radix digits).
    integer, intent(in) :: k, digit(9)
    !> The base deck's initial clearance [m].
    real(wp), intent(in) :: clearance0
    type(sweep_case) :: c
    type(rng_type) :: rng
    real(wp) :: u
    c%index = k
    c%wave_type = findloc(wave_type_names, s%wave_types(digit(1)), dim=1) - 1
    c%level = s%levels(digit(2))
    c%wave_height = s%heights(digit(3))
    if (s%has_levels .and. .not. s%has_heights) c%wave_height = level_wave_height(c%level)
    c%wave_period = s%periods(digit(4))
    if ((s%has_levels .or. s%has_heights) .and. .not. s%has_periods) then
      c%wave_period = 2.0_wp*pi/spectrum_peak_omega(c%wave_height)
    end if
    c%wind = s%winds(digit(5))
    c%wind_speed = 0.0_wp
    if (c%wind) c%wind_speed = wind_on_speed(s, c%level)
    c%angle_deg = s%angles_deg(digit(6))
    c%clearance_b = s%clearances_b(digit(7))
    if (.not. s%has_clearances) c%clearance_b = clearance0/s%base%boat%beam
    c%dt = s%dts(digit(8))
    c%realisation = digit(9)
    c%seed = case_seed(s%base_seed, k)
    c%phase_deg = s%base%sea%phase*180.0_wp/pi
    if (s%random_phase .and. (c%wave_type == 1 .or. c%wave_type == 2)) then
      rng = new_rng(c%seed, phase_stream)
      call rng_uniform(rng, u)
      c%phase_deg = 360.0_wp*u
    end if
  end function one_case

  !> Wind speed of a case with the wind on: the level preset when levels are swept, else the
  !> base deck's speed (or its level's preset if the base deck has no wind).
  pure real(wp) function wind_on_speed(s, level) result(speed)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> Sea-state level of the case.
    integer, intent(in) :: level
    speed = s%base%wind%speed
    if (s%has_levels .or. speed <= 0.0_wp) speed = level_wind_speed(level)
  end function wind_on_speed

  !> The run configuration of case c: the base deck with the case's sea, wind, seed, step and
  !> clearance. `clearance0` is the base deck's initial clearance [m].
  subroutine case_config(s, c, clearance0, cfg)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The case.
    type(sweep_case), intent(in) :: c
    !> The base deck's initial clearance [m].
    real(wp), intent(in) :: clearance0
    !> The case's run configuration.
    type(config_type), intent(out) :: cfg
    real(wp) :: ramp_periods
    cfg = s%base
    cfg%simulation%seed = c%seed
    cfg%simulation%dt = c%dt
    cfg%simulation%integrator = s%integrator
    cfg%simulation%substeps = s%substeps
    ramp_periods = s%base%sea%ramp_time/s%base%sea%period
    cfg%sea%level = c%level
    cfg%sea%wave_type = trim(wave_type_names(c%wave_type))
    cfg%sea%height = c%wave_height
    cfg%sea%period = c%wave_period
    cfg%sea%ramp_time = ramp_periods*c%wave_period
    cfg%sea%direction = c%angle_deg*pi/180.0_wp
    cfg%sea%phase = c%phase_deg*pi/180.0_wp
    cfg%wind%speed = c%wind_speed
    if (s%has_angles) cfg%wind%direction = cfg%sea%direction
    call case_sources(s, c, cfg)
    if (s%has_clearances) call move_outboard(cfg, c%clearance_b*cfg%boat%beam - clearance0)
  end subroutine case_config

  !> Where case c's height, period and wind came from (stored with each series file's
  !> scenario): the sweep's lists and presets, or the base deck's sources.
  subroutine case_sources(s, c, cfg)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The case.
    type(sweep_case), intent(in) :: c
    !> The case's run configuration, whose sources are set.
    type(config_type), intent(inout) :: cfg
    character(len=:), allocatable :: preset
    preset = "sweep: level "//achar(iachar("0") + modulo(c%level, 10))//" preset"
    if (s%has_heights) then
      cfg%sea%height_source = "sweep: heights"
    else if (s%has_levels) then
      cfg%sea%height_source = preset
    end if
    if (s%has_periods) then
      cfg%sea%period_source = "sweep: periods"
    else if (s%has_levels .or. s%has_heights) then
      cfg%sea%period_source = "sweep: peak period of eq. 44 for the height"
    end if
    if (.not. c%wind) then
      cfg%wind%speed_source = "sweep: wind off"
    else if (s%has_levels .or. s%base%wind%speed <= 0.0_wp) then
      cfg%wind%speed_source = preset
    end if
    if (s%has_angles) cfg%wind%direction_source = "sweep: along the waves"
  end subroutine case_sources

  !> Move the boat and the points it hangs from by d [m] along the ship's s2 axis (the
  !> side plane's normal), which changes the initial clearance by exactly d.
  subroutine move_outboard(cfg, d)
    !> The configuration whose boat and hanging points are moved.
    type(config_type), intent(inout) :: cfg
    !> Distance d [m] along the ship's s2 axis.
    real(wp), intent(in) :: d
    real(wp) :: s2(3)
    s2 = matmul(rotation_matrix([cfg%ship%list, cfg%ship%trim, cfg%ship%heading]), &
                [0.0_wp, 1.0_wp, 0.0_wp])
    cfg%boat%position = cfg%boat%position + d*s2
    ! davit heads are in the ship frame, the foundation anchors inertial
    cfg%rigging%head_fore(2) = cfg%rigging%head_fore(2) + d
    cfg%rigging%head_aft(2) = cfg%rigging%head_aft(2) + d
    cfg%slings%anchor_fore = cfg%slings%anchor_fore + d*s2
    cfg%slings%anchor_aft = cfg%slings%anchor_aft + d*s2
  end subroutine move_outboard

  !> The initial fender-to-side clearance [m] of a configuration (the system at t = 0).
  subroutine initial_clearance(cfg, clearance, error)
    !> The configuration at t = 0.
    type(config_type), intent(in) :: cfg
    !> Initial fender-to-side clearance [m].
    real(wp), intent(out) :: clearance
    !> Set when the system cannot be built from the configuration.
    type(error_type), allocatable, intent(out) :: error
    type(system_type) :: sys
    real(wp), allocatable :: y(:), force(:)
    clearance = 0.0_wp
    call new_boat_system(cfg, sys, y, error)
    if (allocated(error)) return
    allocate (force(sys%par%fenders%nf))
    call sys%contact_state(y, clearance, force)
  end subroutine initial_clearance

  !> Seed of case `index` (1-based): the top 31 bits of SplitMix64's index-th output from
  !> state `base`, in 0 .. 2^31 - 1.
  pure integer function case_seed(base, index)
    !> Base seed and case index (1-based).
    integer, intent(in) :: base, index
    integer(i8) :: z
    z = splitmix64(int(base, i8), int(index, i8))
    case_seed = int(ishft(z, -33))
  end function case_seed

  !> The n-th output (n >= 1) of SplitMix64 seeded with `seed`, as a 64-bit pattern:
  !> z = seed + n*0x9E3779B97F4A7C15 (mod 2^64), then the variant-13 finaliser. Unsigned
  !> 64-bit products are formed from 16-bit limbs, so no signed integer ever overflows.
  pure integer(i8) function splitmix64(seed, n) result(z)
    !> Seed (the generator's state) and the output's number n >= 1.
    integer(i8), intent(in) :: seed, n
    integer(i8), parameter :: golden(4) = [int(z'7C15', i8), int(z'7F4A', i8), &
                                           int(z'79B9', i8), int(z'9E37', i8)]
    integer(i8), parameter :: m1(4) = [int(z'E5B9', i8), int(z'1CE4', i8), &
                                       int(z'476D', i8), int(z'BF58', i8)]
    integer(i8), parameter :: m2(4) = [int(z'11EB', i8), int(z'1331', i8), &
                                       int(z'49BB', i8), int(z'94D0', i8)]
    z = add64(seed, mul64(limbs(n), golden))
    z = mul64(limbs(ieor(z, ishft(z, -30))), m1)
    z = mul64(limbs(ieor(z, ishft(z, -27))), m2)
    z = ieor(z, ishft(z, -31))
  end function splitmix64

  !> The four 16-bit limbs of a 64-bit pattern, least significant first.
  pure function limbs(x) result(l)
    !> A 64-bit pattern.
    integer(i8), intent(in) :: x
    integer(i8) :: l(4)
    integer :: k
    do k = 1, 4
      l(k) = ibits(x, 16*(k - 1), 16)
    end do
  end function limbs

  !> The 64-bit pattern of four 16-bit limbs (carries above bit 63 dropped).
  pure integer(i8) function pattern(l) result(x)
    !> Four 16-bit limbs, least significant first.
    integer(i8), intent(in) :: l(4)
    integer :: k
    x = 0
    do k = 1, 4
      x = ior(x, ishft(iand(l(k), int(z'FFFF', i8)), 16*(k - 1)))
    end do
  end function pattern

  !> a * b mod 2^64 from limbs; every partial sum stays below 2^36.
  pure integer(i8) function mul64(a, b) result(x)
    !> Limbs of the two factors a and b.
    integer(i8), intent(in) :: a(4), b(4)
    integer(i8) :: r(4), carry
    integer :: i, k
    carry = 0
    do k = 1, 4
      r(k) = carry
      do i = 1, k
        r(k) = r(k) + a(i)*b(k - i + 1)
      end do
      carry = ishft(r(k), -16)
      r(k) = iand(r(k), int(z'FFFF', i8))
    end do
    x = pattern(r)
  end function mul64

  !> a + b mod 2^64 for 64-bit patterns.
  pure integer(i8) function add64(a, b) result(x)
    !> The two 64-bit patterns added.
    integer(i8), intent(in) :: a, b
    integer(i8) :: la(4), lb(4), r(4), carry
    integer :: k
    la = limbs(a)
    lb = limbs(b)
    carry = 0
    do k = 1, 4
      r(k) = la(k) + lb(k) + carry
      carry = ishft(r(k), -16)
      r(k) = iand(r(k), int(z'FFFF', i8))
    end do
    x = pattern(r)
  end function add64

end module davit_sweep_cases
