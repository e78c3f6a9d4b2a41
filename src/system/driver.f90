!> One run: build the system, integrate with a fixed step, record at the output interval and
!> write the HDF5 file. A non-finite state stops the run with a diagnostic naming the time and
!> the offending quantity; the partial record is still written, marked incomplete.
module davit_system_driver
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_io_deck_reader, only: fmt_real
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_solve_integrator, only: integrator_type
  use davit_solve_factory, only: new_integrator
  use davit_system_model, only: system_type, new_system, nstate, boat_u
  use davit_system_run_summary, only: run_summary, write_root_attributes
  use davit_system_sea_run, only: run_sea
  implicit none
  private
  public :: run_summary, run_simulation

  !> Recorded time series, (components, samples).
  type :: record_type
    integer :: n = 0
    real(wp), allocatable :: time(:), position(:, :), euler(:, :), velocity(:, :)
    real(wp), allocatable :: angular_velocity(:, :), acceleration(:, :), tension(:, :)
    real(wp), allocatable :: energy(:)
  end type record_type

  !> Speeds beyond this (m/s, rad/s) are a numerical blow-up, not a lifeboat.
  real(wp), parameter :: speed_limit = 1.0e3_wp

  character(len=*), parameter :: state_names(nstate) = [character(len=14) :: &
    "boat roll", "boat pitch", "boat yaw", "boat q4", "boat q5", "boat q6", &
    "boat omega1", "boat omega2", "boat omega3", "boat v1", "boat v2", "boat v3"]

contains

  !> Run the deck's scene and write `out_path`.
  subroutine run_simulation(cfg, out_path, summary, error)
    type(config_type), intent(in) :: cfg
    character(len=*), intent(in) :: out_path
    type(run_summary), intent(out) :: summary
    type(error_type), allocatable, intent(out) :: error
    select case (cfg%simulation%scene)
    case ("sea")
      call run_sea(cfg, out_path, summary, error)
    case default
      call run_hanging_boat(cfg, out_path, summary, error)
    end select
  end subroutine run_simulation

  subroutine run_hanging_boat(cfg, out_path, summary, error)
    type(config_type), intent(in) :: cfg
    character(len=*), intent(in) :: out_path
    type(run_summary), intent(out) :: summary
    type(error_type), allocatable, intent(out) :: error
    type(system_type) :: sys
    class(integrator_type), allocatable :: integ
    type(h5_writer_type) :: writer
    type(record_type) :: rec
    type(error_type), allocatable :: run_error, io_error
    real(wp) :: y(nstate), t, dt
    integer(i8) :: nsteps, every, i, clock0, clock1, rate
    integer :: bad

    call new_system(sys, cfg)
    y = sys%initial_state(cfg)
    call new_integrator(cfg%simulation%integrator, nstate, integ, error)
    if (allocated(error)) return
    call writer%create(out_path, error)
    if (allocated(error)) return

    dt = cfg%simulation%dt
    nsteps = nint(cfg%simulation%t_end/dt, i8)
    every = max(1_i8, nint(cfg%simulation%output_interval/dt, i8))
    call allocate_record(rec, int(nsteps/every) + 1)
    t = 0.0_wp
    call record(rec, sys, t, y)
    call system_clock(clock0, rate)
    do i = 1, nsteps
      call integ%step(sys, t, y, dt)
      t = real(i, wp)*dt
      bad = first_bad(y)
      if (bad > 0) then
        call fatal_error(run_error, "run diverged at t = "//fmt_real(t)//" s: "// &
                         trim(state_names(bad))//" = "//fmt_real(y(bad))//" is not finite"// &
                         " or beyond "//fmt_real(speed_limit)//" (step size dt = "// &
                         fmt_real(dt)//" s may exceed the stability limit)")
        exit
      end if
      if (mod(i, every) == 0) call record(rec, sys, t, y)
    end do
    call system_clock(clock1)
    summary%steps = integ%steps
    summary%rhs_evaluations = integ%rhs_evaluations
    summary%wall_time = real(clock1 - clock0, wp)/real(rate, wp)
    summary%samples = rec%n
    summary%complete = .not. allocated(run_error)

    call write_output(writer, cfg, rec, summary, integ%name(), run_error)
    call writer%close(io_error)
    if (allocated(run_error)) then
      call move_alloc(run_error, error)
      error%message = error%message//"; partial output kept in '"//out_path// &
                      "' (attribute complete = 0)"
    else if (allocated(io_error)) then
      call move_alloc(io_error, error)
    end if
  end subroutine run_hanging_boat

  !> Index of the first non-finite state component, or of a speed beyond any physical
  !> value (|u| > speed_limit, m/s or rad/s), which marks a numerical blow-up early.
  pure integer function first_bad(y)
    real(wp), intent(in) :: y(:)
    integer :: k
    first_bad = 0
    do k = 1, size(y)
      if (.not. ieee_is_finite(y(k)) .or. &
          (k >= boat_u(1) .and. k <= boat_u(2) .and. abs(y(k)) > speed_limit)) then
        first_bad = k
        return
      end if
    end do
  end function first_bad

  subroutine allocate_record(rec, n)
    type(record_type), intent(out) :: rec
    integer, intent(in) :: n
    allocate (rec%time(n), rec%position(3, n), rec%euler(3, n), rec%velocity(3, n), &
              rec%angular_velocity(3, n), rec%acceleration(3, n), rec%tension(2, n), &
              rec%energy(n))
  end subroutine allocate_record

  subroutine record(rec, sys, t, y)
    type(record_type), intent(inout) :: rec
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: t, y(:)
    integer :: k
    if (rec%n >= size(rec%time)) return
    rec%n = rec%n + 1
    k = rec%n
    rec%time(k) = t
    call sys%observe(t, y, rec%position(:, k), rec%euler(:, k), rec%velocity(:, k), &
                     rec%angular_velocity(:, k), rec%acceleration(:, k))
    rec%tension(:, k) = sys%sling_tensions(y)
    rec%energy(k) = sys%energy(y)
  end subroutine record

  subroutine write_output(w, cfg, rec, summary, integrator, run_error)
    type(h5_writer_type), intent(inout) :: w
    type(config_type), intent(in) :: cfg
    type(record_type), intent(in) :: rec
    type(run_summary), intent(in) :: summary
    character(len=*), intent(in) :: integrator
    type(error_type), allocatable, intent(in) :: run_error
    integer :: n
    n = rec%n
    call w%write_1d("time", rec%time(1:n), "s", "Simulation time of each sample")
    call w%group("boat")
    call w%write_2d("boat/position", rec%position(:, 1:n), "m", &
                    "Lifeboat CG position, inertial frame N (x, y horizontal, z down)")
    call w%write_2d("boat/euler", rec%euler(:, 1:n), "rad", &
                    "Lifeboat roll, pitch, yaw (ZYX Euler angles, eq. 2)")
    call w%write_2d("boat/velocity", rec%velocity(:, 1:n), "m/s", &
                    "Lifeboat CG velocity, inertial frame N")
    call w%write_2d("boat/angular_velocity", rec%angular_velocity(:, 1:n), "rad/s", &
                    "Lifeboat angular velocity, boat-frame components (u1, u2, u3)")
    call w%write_2d("boat/acceleration", rec%acceleration(:, 1:n), "m/s^2", &
                    "Lifeboat CG acceleration, inertial frame N (gravity not subtracted)")
    call w%group("slings")
    call w%write_2d("slings/tension", rec%tension(:, 1:n), "N", &
                    "Sling tension (fore, aft), spring plus dashpot, tension-only")
    call w%group("diagnostics")
    call w%write_1d("diagnostics/energy", rec%energy(1:n), "J", &
                    "Total mechanical energy: kinetic + gravity (-m g z) + elastic")
    call write_root_attributes(w, cfg, summary, integrator, run_error)
  end subroutine write_output

end module davit_system_driver
