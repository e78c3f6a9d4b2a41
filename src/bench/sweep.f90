!> `davit bench`, a small sweep: the cases of a sweep deck through the sweep's own case
!> runner (davit_sweep_driver's run_case, the launch metrics watching every step), in an
!> OpenMP loop like `davit sweep`'s (dynamic schedule, one system per case and thread), on
!> a given number of threads. No summary file: the bench times the computation.
module davit_bench_sweep
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: int_to_str
  use davit_sweep_keys, only: sweep_config, read_sweep
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_driver, only: prepare_cases, case_row, longest_first
  use davit_sweep_metrics, only: case_result, status_ok
  use davit_bench_timing, only: timed_run, wall_seconds
  implicit none
  private
  public :: read_bench_sweep, time_sweep

contains

  !> Read sweep deck `path`, every case cut to `t_end` seconds (the base deck's t_end when
  !> t_end <= 0; a case still ends at the hook release when the deck says so).
  subroutine read_bench_sweep(path, t_end, s, error)
    !> Path of the sweep deck.
    character(len=*), intent(in) :: path
    !> Simulated time of every case [s] (<= 0: the base deck's t_end).
    real(wp), intent(in) :: t_end
    !> The sweep's settings, every case cut to t_end.
    type(sweep_config), intent(out) :: s
    !> Set when the deck cannot be read.
    type(error_type), allocatable, intent(out) :: error
    call read_sweep(path, s, error)
    if (allocated(error)) return
    if (t_end > 0.0_wp) s%base%simulation%t_end = max(t_end, maxval(s%dts))
  end subroutine read_bench_sweep

  !> Run every case of sweep `s` on `threads` threads and time the whole loop. Simulated
  !> time, steps and RHS evaluations are summed over the cases (the same on any number of
  !> threads: a case does not depend on where it runs). A failed case is an error.
  subroutine time_sweep(name, s, threads, run, error)
    !> Label of the row.
    character(len=*), intent(in) :: name
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> OpenMP threads.
    integer, intent(in) :: threads
    !> The sweep's timings and counts, summed over the cases.
    type(timed_run), intent(out) :: run
    !> Set when a case fails.
    type(error_type), allocatable, intent(out) :: error
    type(sweep_case), allocatable :: cases(:)
    type(case_result), allocatable :: rows(:)
    real(wp) :: clearance0, t0
    integer, allocatable :: order(:)
    integer :: k
    call prepare_cases(s, cases, clearance0, error)
    if (allocated(error)) return
    allocate (rows(size(cases)))
    ! dearest cases first, as davit sweep runs them
    order = [(k, k = 1, size(cases))]
    call longest_first(s, cases, order)
    t0 = wall_seconds()
    !$omp parallel do schedule(dynamic, 1) num_threads(threads) default(none) &
    !$omp shared(s, cases, clearance0, rows, order)
    do k = 1, size(cases)
      call case_row(s, cases(order(k)), clearance0, rows(order(k)))
    end do
    !$omp end parallel do
    run%wall = wall_seconds() - t0
    do k = 1, size(rows)
      if (rows(k)%status /= status_ok) then
        call fatal_error(error, s%filename//": bench sweep case "//int_to_str(k)// &
                         " failed: "//rows(k)%message)
        return
      end if
    end do
    run%name = name
    run%deck = s%filename
    run%cases = size(cases)
    run%threads = threads
    run%dt = s%base%simulation%dt
    run%simulated = sum(rows%end_time)
    run%steps = sum(rows%steps)
    run%rhs_evaluations = sum(rows%rhs_evaluations)
  end subroutine time_sweep

end module davit_bench_sweep
