!> `davit bench`, the sea module alone: cost per component-point of the wave evaluations
!> (Level 5 irregular sea, 100 x 13 components, 20 points). Speed goals live in the README,
!> never in tests.
module davit_bench_sea
  use, intrinsic :: iso_fortran_env, only: output_unit
  use davit_kinds, only: wp, i8, pi
  use davit_core_random, only: rng_type, new_rng
  use davit_sea_wave_field, only: wave_field_type, new_irregular_sea, wave_elevation, &
                                  wave_kinematics, point_phasors, time_phasors, &
                                  rotation_phasors, advance_phasors, elevation_from_phasors
  use davit_sea_wave_grid, only: wave_grid_type, new_wave_grid, grid_prepare, &
                                 grid_elevation, grid_kinematics
  use davit_boat_strip_sums, only: elevation_sums, kinematic_sums
  implicit none
  private
  public :: bench_result, bench_sea

  !> The sea module's kernels timed by bench_sea.
  integer, parameter :: elevation = 1, kinematics = 2, probes = 3, libm_cos = 4
  !> The strip's sea terms timed by bench_grid.
  integer, parameter :: grid_kinematic = 1, exact_kinematic = 2, exact_elevation = 3, &
                        grid_elevation_terms = 4

  !> One timing: what was timed, its cost and the unit of the cost.
  type :: bench_result
    !> What was timed, and the unit of its cost.
    character(len=:), allocatable :: name, unit
    !> The cost, in that unit.
    real(wp) :: value = 0.0_wp
  end type bench_result

contains

  !> Each timing repeats its kernel for about `budget` seconds (after a 10-repetition
  !> probe that sets the count), so quick and full runs differ only in noise.
  subroutine bench_sea(budget, results)
    !> Seconds each timing repeats its kernel.
    real(wp), intent(in) :: budget
    !> The timings.
    type(bench_result), allocatable, intent(out) :: results(:)
    integer, parameter :: np = 20
    type(wave_field_type) :: field
    type(rng_type) :: rng
    real(wp) :: x(np), y(np), z(np), eta(np), v(3), a(3), p, sink
    real(wp), allocatable :: cb(:, :), sb(:, :), ca(:), sa(:), cr(:), sr(:), th(:), c(:)
    integer(i8) :: r
    integer :: j
    allocate (results(0))
    rng = new_rng(1)
    call new_irregular_sea(field, 4.0_wp, pi/2, 1, pi/6, 100, 13, 0.3_wp, 3.0_wp, .true., &
                           .true., rng, 0.0_wp)
    do j = 1, np
      x(j) = 0.6_wp*j - 6.0_wp
      y(j) = 13.3_wp
      z(j) = 0.5_wp
    end do
    sink = 0.0_wp

    ! 1. elevation at arbitrary (moving) points: one phase evaluation per component-point
    call add(results, "sea: elevation, arbitrary points", "ns/(component*point)", &
             measured(elevation))

    ! 2. kinematics (elevation + velocity + acceleration + pressure, Wheeler stretching)
    call add(results, "sea: kinematics, arbitrary points", "ns/(component*point)", &
             measured(kinematics))

    ! 3. fixed probes: precomputed spatial phasors, time phasors advanced by rotation
    allocate (cb(field%n, np), sb(field%n, np), ca(field%n), sa(field%n), cr(field%n), &
              sr(field%n))
    call point_phasors(field, x, y, cb, sb)
    call time_phasors(field, 0.0_wp, ca, sa)
    call rotation_phasors(field, 0.01_wp, cr, sr)
    call add(results, "sea: elevation, fixed probes (phasors)", "ns/(component*point)", &
             measured(probes))

    ! 4. reference: the libm cosine alone, per phase
    allocate (th(field%n), c(field%n))
    call add(results, "reference: libm cos per phase", "ns/phase", measured(libm_cos))

    ! 5-8. the interpolated sea (&sea kinematics = 'grid', defaults h = 1 m, dt = 0.1 s,
    ! velocity to 3 m): its build per node and sample, and a strip's sea terms per point
    ! from the grid against the exact sums (elevation terms; elevation and velocity terms)
    call bench_grid(budget, field, x, y, results, sink)
    if (sink == 12345.678_wp) write (output_unit, *) sink

  contains

    !> Kernel `which` timed for about `budget` seconds (the count set by a 10-repetition
    !> probe) [ns per unit: component-point, or phase for the libm reference].
    real(wp) function measured(which) result(ns)
      !> The kernel (elevation, kinematics, probes, libm_cos).
      integer, intent(in) :: which
      integer(i8) :: units
      units = int(np, i8)*field%n
      if (which == libm_cos) units = field%n
      ns = timed_ns(which, 10_i8, units)
      ns = timed_ns(which, scaled(budget, ns*1.0e-9_wp*real(units, wp)), units)
    end function measured

    !> Kernel `which` repeated n times [ns per unit, `units` per repetition].
    real(wp) function timed_ns(which, n, units) result(ns)
      !> The kernel.
      integer, intent(in) :: which
      !> Repetitions timed, and units of work per repetition.
      integer(i8), intent(in) :: n, units
      integer(i8) :: c0, c1, rate
      real(wp) :: e
      call system_clock(c0, rate)
      do r = 1, n
        select case (which)
        case (elevation)
          do j = 1, np
            sink = sink + wave_elevation(field, 0.01_wp*r, x(j), y(j))
          end do
        case (kinematics)
          do j = 1, np
            call wave_kinematics(field, 0.01_wp*r, [x(j), y(j), z(j)], e, v, a, p)
            sink = sink + v(1) + p
          end do
        case (probes)
          call advance_phasors(ca, sa, cr, sr)
          call elevation_from_phasors(field, 0.01_wp*r, ca, sa, cb, sb, eta)
          sink = sink + eta(1)
        case default
          th = field%omega*(0.01_wp*r) + field%phase
          c = cos(th)
          sink = sink + c(1)
        end select
      end do
      call system_clock(c1)
      ns = real(c1 - c0, wp)/real(rate, wp)/real(n*units, wp)*1.0e9_wp
    end function timed_ns

  end subroutine bench_sea

  !> The grid's build [ns per node and sample, all fields] and its per-point queries
  !> against the exact sums of the slow clock (davit_boat_strip_waves) [ns per point].
  subroutine bench_grid(budget, field, x, y, results, sink)
    !> Seconds each timing repeats its kernel, and the points' horizontal coordinates x, y [m]
    !> (inertial frame).
    real(wp), intent(in) :: budget, x(:), y(:)
    !> The irregular sea whose grid is built.
    type(wave_field_type), intent(in) :: field
    !> The timings, extended with the grid's.
    type(bench_result), allocatable, intent(inout) :: results(:)
    !> Sum of the results, kept so the compiler cannot drop the timed work.
    real(wp), intent(inout) :: sink
    type(wave_grid_type) :: g
    real(wp) :: xy(2, 2), e(4), v(3, 5), seconds, t
    integer(i8) :: c0, c1, rate, r
    integer :: j, builds
    xy = reshape([minval(x) - 1.4_wp, minval(y) - 1.4_wp, maxval(x) + 1.4_wp, &
                  maxval(y) + 1.4_wp], [2, 2])
    ! build: blocks of 16 samples over the footprint, until the budget is spent
    call system_clock(c0, rate)
    builds = 0
    t = 0.0_wp
    do
      g = new_wave_grid(field, 1.0_wp, 0.1_wp, 0.0_wp, 3.0_wp, .true.)
      call grid_prepare(g, field, t, t + 1.0_wp, xy)
      builds = builds + g%node_builds*g%nt
      t = t + 2.0_wp
      call system_clock(c1)
      if (real(c1 - c0, wp)/real(rate, wp) > budget) exit
    end do
    seconds = real(c1 - c0, wp)/real(rate, wp)
    call add(results, "sea grid: build (22 fields)", "ns/(node*sample)", &
             seconds/real(builds, wp)*1.0e9_wp)
    call grid_prepare(g, field, t - 2.0_wp, t - 1.0_wp, xy)
    ! each repetition's count from a guess of one point's cost [s]
    call add(results, "sea grid: kinematic terms from the grid", "ns/point", &
             grid_ns(grid_kinematic, reps_for(2.0e-7_wp)))
    call add(results, "sea grid: kinematic terms, exact sum", "ns/point", &
             grid_ns(exact_kinematic, reps_for(field%n*5.0e-9_wp)))
    call add(results, "sea grid: elevation terms, exact sum", "ns/point", &
             grid_ns(exact_elevation, reps_for(field%n*2.0e-9_wp)))
    call add(results, "sea grid: elevation terms from the grid", "ns/point", &
             grid_ns(grid_elevation_terms, reps_for(1.0e-7_wp)))

  contains

    !> Repetitions over all the points that fill the budget at `per_point` seconds a point.
    integer(i8) function reps_for(per_point) result(n)
      !> Guessed cost of one point [s].
      real(wp), intent(in) :: per_point
      n = max(1_i8, int(budget/(size(x)*per_point), i8))
    end function reps_for

    !> The strip's sea terms at every point by `which`, `n` times [ns per point].
    real(wp) function grid_ns(which, n) result(ns)
      !> The terms and their source (grid_kinematic, exact_kinematic, exact_elevation,
      !> grid_elevation_terms).
      integer, intent(in) :: which
      !> Repetitions.
      integer(i8), intent(in) :: n
      call system_clock(c0, rate)
      do r = 1, n
        do j = 1, size(x)
          select case (which)
          case (grid_kinematic)
            call grid_kinematics(g, t - 1.9_wp + 1.0e-4_wp*mod(r, 1000_i8), x(j), y(j), &
                                 0.5_wp, e, v)
            sink = sink + e(1) + v(1, 1)
          case (exact_kinematic)
            call kinematic_sums(field, 1.0e-3_wp*r, x(j), y(j), 0.5_wp, e, v)
            sink = sink + e(1) + v(1, 1)
          case (exact_elevation)
            call elevation_sums(field, 1.0e-3_wp*r, x(j), y(j), e)
            sink = sink + e(1)
          case default
            call grid_elevation(g, t - 1.9_wp + 1.0e-4_wp*mod(r, 1000_i8), x(j), y(j), e)
            sink = sink + e(1)
          end select
        end do
      end do
      call system_clock(c1)
      ns = real(c1 - c0, wp)/real(rate, wp)/real(n*size(x), wp)*1.0e9_wp
    end function grid_ns

  end subroutine bench_grid

  !> Repetitions that fill `seconds` given the time of one repetition.
  pure integer(i8) function scaled(seconds, one) result(n)
    !> Seconds to fill, and the time of one repetition [s].
    real(wp), intent(in) :: seconds, one
    n = max(1_i8, int(seconds/max(one, 1.0e-12_wp), i8))
  end function scaled

  subroutine add(results, name, unit, value)
    !> The timings, extended with one.
    type(bench_result), allocatable, intent(inout) :: results(:)
    !> What was timed, and the unit of its cost.
    character(len=*), intent(in) :: name, unit
    !> The cost, in that unit.
    real(wp), intent(in) :: value
    type(bench_result) :: r
    r%name = name
    r%unit = unit
    r%value = value
    results = [results, r]
  end subroutine add

end module davit_bench_sea
