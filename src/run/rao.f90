!> `davit rao`: the ship alone in regular linear waves, one run per (frequency, heading),
!> run in parallel with OpenMP (one independent ship per thread). Each response is fitted
!> over whole periods after the transient as x = m + R cos(w t + phi), so the amplitude
!> R/zeta and the phase phi are relative to the wave elevation zeta cos(w t) at the ship's
!> initial CG position. DOFs: surge, sway (inertial x, y), heave (up), roll, pitch, yaw.
!> A soft mooring (surge and sway 300 s, yaw 60 s, 70 % of critical) holds the mean
!> position and heading: a free ship at zero speed otherwise turns by tens of degrees in
!> oblique seas during a run (26 deg in 400 s at 135 deg, 7.5 s waves), which is not what
!> an RAO describes.
!>
!> A run that fails (its scene cannot be built, or its state stops being finite, or the ship
!> capsizes: roll or pitch beyond 90 deg) is not an RAO: its amplitude and phase are written
!> as NaN, `rao/failed` marks it, the root attribute `complete` is 0, and `davit rao` names
!> each failed (frequency, heading) with its reason and exits non-zero. The scene is built
!> once before any run, so a deck whose ship cannot be built (an unresolvable database)
!> fails before anything is written.
module davit_run_rao
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use davit_kinds, only: wp, pi, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_text, only: fmt_real, fmt_fixed
  use davit_io_config, only: config_type
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_solve_rk4, only: rk4_type
  use davit_ship_ship_model, only: ship_system_type
  use davit_run_ship_scene, only: build_ship_scene
  use davit_run_run_summary, only: run_summary
  use davit_run_scenario, only: write_root_attributes
  implicit none
  private
  public :: rao_case, run_rao

  !> Soft mooring in RAO runs: natural periods of surge, sway, yaw [s] and damping ratio.
  !> Yaw is held stiffer: in oblique seas second-order yaw moments (the wave pitch moment
  !> tipped by the roll, the rigid-body p q (I_yy - I_xx)) of ~1.8 MN m turned the ship 25 deg
  !> on a 300 s yaw spring; on 60 s it stays within about 1 deg, and the spring changes the
  !> first-order yaw response by (60 s / T)^2... at most 12 % at 0.3 rad/s.
  real(wp), parameter :: mooring_period(3) = [300.0_wp, 300.0_wp, 60.0_wp]
  real(wp), parameter :: mooring_zeta = 0.7_wp
  !> Roll or pitch [rad] beyond which a run has capsized (no longer a linear response).
  real(wp), parameter :: capsize_angle = 0.5_wp*pi
  !> Length of one failed run's reason in the report.
  integer, parameter :: reason_len = 240

contains

  !> Response amplitude per unit wave amplitude and phase [rad] of the 6 DOFs at one
  !> frequency and relative heading.
  subroutine rao_case(base, omega, heading, amplitude, phase, error)
    !> The RAO deck's configuration (the ship, its sea).
    type(config_type), intent(in) :: base
    !> Wave frequency [rad/s] and heading relative to the ship [rad].
    real(wp), intent(in) :: omega, heading
    !> Per DOF, the response amplitude per unit wave amplitude [m/m, rad/m] and its phase [rad].
    real(wp), intent(out) :: amplitude(6), phase(6)
    !> Set when the run fails.
    type(error_type), allocatable, intent(out) :: error
    type(config_type) :: cfg
    type(ship_system_type) :: ship
    type(rk4_type) :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: t, dt, period, t0, x(6), ca(6), sa(6), mean(6), zeta
    integer(i8) :: i, n0, nmeas
    cfg = base
    period = 2.0_wp*pi/omega
    zeta = cfg%rao%amplitude
    cfg%sea%wave_type = "airy"
    cfg%sea%height = 2.0_wp*zeta
    cfg%sea%period = period
    cfg%sea%direction = cfg%ship%heading + heading
    ! phase such that eta = zeta cos(w t) at the initial CG position
    cfg%sea%phase = omega**2/9.81_wp*(cfg%ship%position(1)*cos(cfg%sea%direction) + &
                                      cfg%ship%position(2)*sin(cfg%sea%direction))
    cfg%sea%ramp_time = 2.0_wp*period
    cfg%wind%speed = 0.0_wp
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) return
    ! hold the mean position and heading (frequency-domain RAO convention) with a soft,
    ! well-damped mooring far below the wave band
    call ship%set_mooring(mooring_period, mooring_zeta, y)
    ! an integer number of steps per period, so the fit spans whole periods exactly
    dt = period/real(max(1, nint(period/cfg%rao%dt)), wp)
    t0 = 2.0_wp*period + cfg%rao%settle_time
    n0 = nint(t0/dt, i8)
    nmeas = nint(cfg%rao%measure_periods*period/dt, i8)
    call rk%init(size(y))
    t = 0.0_wp
    ca = 0; sa = 0; mean = 0
    do i = 1, n0 + nmeas
      call rk%step(ship, t, y, dt)
      t = real(i, wp)*dt
      call ship%after_step(t, y)
      if (.not. all(ieee_is_finite(y))) then
        call fatal_error(error, "the state stopped being finite (diverged) at t = "// &
                         fmt_fixed(t, 2)//" s")
        return
      end if
      associate (q => y(ship%par%layout%parts(1)%q(1):ship%par%layout%parts(1)%q(2)))
        ! surge, sway, heave (up), roll, pitch, yaw
        x = [q(4), q(5), -q(6), q(1), q(2), q(3)]
      end associate
      if (abs(x(4)) > capsize_angle .or. abs(x(5)) > capsize_angle) then
        call fatal_error(error, "roll or pitch beyond 90 deg (capsized) at t = "// &
                         fmt_fixed(t, 2)//" s")
        return
      end if
      if (i > n0) then
        ca = ca + x*cos(omega*t)
        sa = sa + x*sin(omega*t)
        mean = mean + x
      end if
    end do
    ca = 2.0_wp*ca/nmeas
    sa = 2.0_wp*sa/nmeas
    amplitude = sqrt(ca**2 + sa**2)/zeta
    phase = atan2(-sa, ca)
    if (.not. all(ieee_is_finite(amplitude)) .or. .not. all(ieee_is_finite(phase))) then
      call fatal_error(error, "the fitted amplitude or phase is not finite")
    end if
  end subroutine rao_case

  subroutine run_rao(cfg, out_path, summary, error)
    !> The RAO deck's configuration.
    type(config_type), intent(in) :: cfg
    !> Path of the HDF5 file written.
    character(len=*), intent(in) :: out_path
    !> Steps, evaluations, wall time and completion of the runs.
    type(run_summary), intent(out) :: summary
    !> Set when a run fails or the file cannot be written.
    type(error_type), allocatable, intent(out) :: error
    type(h5_writer_type) :: writer
    type(error_type), allocatable :: none, case_error
    type(ship_system_type) :: probe
    real(wp), allocatable :: amp(:, :, :), pha(:, :, :), failed_at(:, :), y(:)
    character(len=reason_len), allocatable :: reason(:)
    integer :: nw, nh, c, iw, ih, failed
    integer(i8) :: clock0, clock1, rate
    real(wp) :: dofs(6)
    ! the scene once, so that a deck whose ship cannot be built fails before any output
    call build_ship_scene(cfg, probe, y, error)
    if (allocated(error)) return
    call writer%create(out_path, error)
    if (allocated(error)) return
    nw = size(cfg%rao%omegas)
    nh = size(cfg%rao%headings)
    allocate (amp(6, nw, nh), pha(6, nw, nh), failed_at(nw, nh), reason(nw*nh))
    reason = ""
    failed_at = 0.0_wp
    call system_clock(clock0, rate)
    !$omp parallel do schedule(dynamic) default(none) private(iw, ih, case_error) &
    !$omp shared(cfg, nw, nh, amp, pha, reason, failed_at)
    do c = 1, nw*nh
      iw = 1 + mod(c - 1, nw)
      ih = 1 + (c - 1)/nw
      call rao_case(cfg, cfg%rao%omegas(iw), cfg%rao%headings(ih), amp(:, iw, ih), &
                    pha(:, iw, ih), case_error)
      if (allocated(case_error)) then
        ! no half-measured numbers: a failed run's response is NaN, never zero
        amp(:, iw, ih) = ieee_value(0.0_wp, ieee_quiet_nan)
        pha(:, iw, ih) = ieee_value(0.0_wp, ieee_quiet_nan)
        failed_at(iw, ih) = 1.0_wp
        reason(c) = case_error%message
      end if
    end do
    !$omp end parallel do
    call system_clock(clock1)
    failed = count(failed_at > 0.0_wp)
    summary%wall_time = real(clock1 - clock0, wp)/real(rate, wp)
    summary%complete = failed == 0
    dofs = [1, 2, 3, 4, 5, 6]
    call writer%group("rao")
    call writer%write_1d("rao/omega", cfg%rao%omegas, "rad/s", "Wave frequency", dims="omega")
    call writer%write_1d("rao/heading", cfg%rao%headings, "rad", &
                         "Wave direction relative to the ship's heading (0 following, "// &
                         "90 from port, 180 head sea)", dims="heading")
    call writer%write_1d("rao/dof", dofs, "-", &
                         "1 surge, 2 sway, 3 heave (up), 4 roll, 5 pitch, 6 yaw", dims="dof")
    call writer%write_3d("rao/amplitude", amp, "m/m (DOF 1-3), rad/m (DOF 4-6)", &
                         "Response amplitude per unit wave amplitude, (dof, omega, heading); "// &
                         "NaN where the run failed", dims="dof omega heading")
    call writer%write_3d("rao/phase", pha, "rad", &
                         "Phase of the response relative to the wave elevation at the ship; "// &
                         "NaN where the run failed", dims="dof omega heading")
    call writer%write_2d("rao/failed", failed_at, "-", &
                         "1 where the run of that (omega, heading) failed (diverged, "// &
                         "capsized or not built), 0 where it was measured", &
                         dims="omega heading")
    call write_root_attributes(writer, cfg, summary, "rk4", none, scenario=.false.)
    call writer%close(error)
    if (allocated(error)) return
    if (failed > 0) call fatal_error(error, failure_report(cfg, failed_at, reason, out_path))
  end subroutine run_rao

  !> Which runs failed and why, one line each (the output file keeps the others).
  function failure_report(cfg, failed_at, reason, out_path) result(text)
    type(config_type), intent(in) :: cfg
    real(wp), intent(in) :: failed_at(:, :)
    character(len=*), intent(in) :: reason(:), out_path
    character(len=:), allocatable :: text
    integer :: iw, ih, nw
    nw = size(failed_at, 1)
    text = "rao: "//fmt_real(real(count(failed_at > 0.0_wp), wp))//" of "// &
           fmt_real(real(size(failed_at), wp))//" runs failed ('"//out_path// &
           "' keeps the others; complete = 0, rao/failed marks them, their values are NaN):"
    do ih = 1, size(failed_at, 2)
      do iw = 1, nw
        if (failed_at(iw, ih) <= 0.0_wp) cycle
        text = text//new_line("a")//"  omega "//fmt_real(cfg%rao%omegas(iw))// &
               " rad/s, heading "//fmt_real(cfg%rao%headings(ih)*180.0_wp/pi)//" deg: "// &
               trim(reason(iw + (ih - 1)*nw))
      end do
    end do
  end function failure_report

end module davit_run_rao
