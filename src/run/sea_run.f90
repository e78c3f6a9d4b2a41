!> The 'sea' scene: the wave field alone, recorded at fixed probes. The probes' spatial
!> phasors are computed once and the time phasors advanced by rotation (recomputed exactly
!> every `resync` samples so round-off cannot accumulate), so a sample costs one dot
!> product per probe. The `run` binding of the 'sea' scene (davit_run_scene), a submodule
!> like davit_run_scene_run.
submodule (davit_run_scene) davit_run_sea_run
  use davit_kinds, only: i8
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_sea_wave_field, only: wave_field_type, point_phasors, time_phasors, &
                                  rotation_phasors, advance_phasors, elevation_from_phasors
  use davit_system_sea_builder, only: build_wave_field
  use davit_run_scenario, only: write_root_attributes
  use davit_run_recorders, only: write_components
  implicit none

  integer, parameter :: resync = 256

contains

  module procedure sea_run
    type(wave_field_type) :: field
    type(h5_writer_type) :: writer
    type(error_type), allocatable :: none
    real(wp), allocatable :: cb(:, :), sb(:, :), ca(:), sa(:), cr(:), sr(:)
    real(wp), allocatable :: eta(:, :), time(:), probes(:, :)
    real(wp) :: dt_out
    integer :: nout, np, n, k
    integer(i8) :: clock0, clock1, rate

    call build_wave_field(cfg%sea, cfg%simulation%seed, 0, field)
    call writer%create(out_path, error)
    if (allocated(error)) return
    call system_clock(clock0, rate)
    np = size(cfg%sea%probes_x)
    n = field%n
    dt_out = cfg%simulation%output_interval
    nout = int(cfg%simulation%t_end/dt_out + 1.0e-9_wp) + 1
    allocate (cb(n, np), sb(n, np), ca(n), sa(n), cr(n), sr(n), eta(np, nout), time(nout))
    call point_phasors(field, cfg%sea%probes_x, cfg%sea%probes_y, cb, sb)
    call rotation_phasors(field, dt_out, cr, sr)
    do k = 1, nout
      time(k) = real(k - 1, wp)*dt_out
      if (mod(k - 1, resync) == 0) then
        call time_phasors(field, time(k), ca, sa)
      else
        call advance_phasors(ca, sa, cr, sr)
      end if
      call elevation_from_phasors(field, time(k), ca, sa, cb, sb, eta(:, k))
    end do
    call system_clock(clock1)
    summary%wall_time = real(clock1 - clock0, wp)/real(rate, wp)
    summary%samples = nout
    summary%complete = .true.

    allocate (probes(3, np))
    probes(1, :) = cfg%sea%probes_x
    probes(2, :) = cfg%sea%probes_y
    probes(3, :) = 0.0_wp
    call writer%write_1d("time", time, "s", "Simulation time of each sample", dims="time")
    call writer%group("sea")
    call writer%write_2d("sea/elevation", eta, "m", &
                         "Surface elevation eta at each probe, positive up (eq. 43)", &
                         dims="probe time")
    call writer%write_2d("sea/probe_position", probes, "m", &
                         "Probe positions (x, y, z) in the inertial frame", dims="component probe")
    call write_components(writer, field)
    call write_root_attributes(writer, cfg, summary, "none", none)
    call writer%attr_str("/sea", "wave_type", cfg%sea%wave_type)
    call writer%attr_real("/sea", "ramp_time", field%ramp_time)
    call writer%close(error)
  end procedure sea_run

end submodule davit_run_sea_run
