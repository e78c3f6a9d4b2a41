!> `davit bench`, the study-level row: what users come for is not one launch but a decided
!> operability table, so an adaptive operability sweep (davit sweep's own driver, rounds of
!> realisations until each cell's Wilson half-width reaches the deck's target) is run whole
!> into a scratch summary, timed, and its cells judged as the operability table judges them
!> (postproc/operability.py): at risk 5 % with Wilson 95 % intervals of the collision
!> probability, a cell is decided when its upper bound is <= the risk (acceptable) or its
!> lower bound is above it (not acceptable), else undecided.
module davit_bench_study
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_reader, only: h5_reader_type
  use davit_assess_statistics, only: wilson_interval
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_driver, only: sweep_options, sweep_outcome, run_sweep
  use davit_bench_timing, only: timed_run
  implicit none
  private
  public :: study_result, time_study, cell_verdicts

  !> The operability table's risk level (postproc/operability.py RISK).
  real(wp), parameter :: risk = 0.05_wp

  type :: study_result
    !> Cells of the sweep, how many are decided, launches run (not counting those the
    !> converged cells did not need).
    integer :: cells = 0, decided = 0, launches = 0
  end type study_result

contains

  !> Run the adaptive sweep `s` on `threads` threads into `scratch` (removed afterwards)
  !> and time it; `run` gets the totals (wall time of the whole sweep, its launches),
  !> `study` the cells' verdicts. A failed launch is an error: its cell's verdict would mean
  !> nothing.
  subroutine time_study(name, s, threads, scratch, run, study, error)
    !> Label of the row, and the scratch summary's path (removed afterwards).
    character(len=*), intent(in) :: name, scratch
    !> The adaptive sweep.
    type(sweep_config), intent(in) :: s
    !> OpenMP threads.
    integer, intent(in) :: threads
    !> Totals of the whole sweep (wall time, launches, steps).
    type(timed_run), intent(out) :: run
    !> The cells' verdicts.
    type(study_result), intent(out) :: study
    !> Set when the sweep fails or a launch fails.
    type(error_type), allocatable, intent(out) :: error
    type(sweep_options) :: opts
    type(sweep_outcome) :: outcome
    opts%threads = threads
    opts%quiet = .true.
    call remove(scratch)
    call run_sweep(s, opts, scratch, outcome, error)
    if (.not. allocated(error) .and. outcome%failed > 0) then
      call fatal_error(error, s%filename//": a launch of the bench's operability study failed")
    end if
    if (.not. allocated(error)) call read_verdicts(scratch, study, run, error)
    call remove(scratch)
    if (allocated(error)) return
    run%name = name
    run%deck = s%filename
    run%cases = outcome%ok
    run%threads = outcome%threads
    run%dt = s%base%simulation%dt
    run%wall = outcome%wall_time
    study%launches = outcome%ok
  end subroutine time_study

  !> The cells' verdicts, simulated time, steps and RHS evaluations from the summary.
  subroutine read_verdicts(path, study, run, error)
    !> Path of the sweep's summary.
    character(len=*), intent(in) :: path
    !> The cells' verdicts.
    type(study_result), intent(inout) :: study
    !> The totals, receiving simulated time, steps and RHS evaluations.
    type(timed_run), intent(inout) :: run
    !> Set when the summary cannot be read.
    type(error_type), allocatable, intent(out) :: error
    type(h5_reader_type) :: h5
    real(wp), allocatable :: angle(:), clearance(:), end_time(:)
    integer(i8), allocatable :: status(:), collided(:), level(:), wave(:), steps(:), rhs(:)
    call h5%open(path, error)
    if (allocated(error)) return
    call h5%read_1d_int("results/status", status, error)
    if (.not. allocated(error)) call h5%read_1d_int("results/collided", collided, error)
    if (.not. allocated(error)) call h5%read_1d_int("cases/level", level, error)
    if (.not. allocated(error)) call h5%read_1d_int("cases/wave_type", wave, error)
    if (.not. allocated(error)) call h5%read_1d("cases/angle_deg", angle, error)
    if (.not. allocated(error)) call h5%read_1d("cases/clearance_b", clearance, error)
    if (.not. allocated(error)) call h5%read_1d("results/end_time", end_time, error)
    if (.not. allocated(error)) call h5%read_1d_int("results/steps", steps, error)
    if (.not. allocated(error)) call h5%read_1d_int("results/rhs_evaluations", rhs, error)
    call h5%close()
    if (allocated(error)) return
    run%simulated = sum(end_time, mask=status == 1)
    run%steps = sum(steps, mask=status == 1)
    run%rhs_evaluations = sum(rhs, mask=status == 1)
    call cell_verdicts(status == 1, collided > 0, &
                       real(level, wp)*1e6_wp + real(wave, wp)*1e4_wp + angle*10.0_wp + &
                       clearance*0.01_wp, study%cells, study%decided)
  end subroutine read_verdicts

  !> Cells (cases with equal `key`) among the finished cases `done`, and how many of them
  !> are decided at the risk level: Wilson 95 % upper bound <= risk or lower bound > risk
  !> of the share of `hit` cases. A cell with no finished case is undecided.
  pure subroutine cell_verdicts(done, hit, key, cells, decided)
    !> Which cases finished, and which of them collided.
    logical, intent(in) :: done(:), hit(:)
    !> The cell key of each case (equal within a cell).
    real(wp), intent(in) :: key(:)
    !> Number of cells and how many are decided.
    integer, intent(out) :: cells, decided
    logical :: seen(size(key))
    real(wp) :: bounds(2)
    integer :: i, k, n
    cells = 0
    decided = 0
    seen = .false.
    do i = 1, size(key)
      if (seen(i)) cycle
      where (key == key(i)) seen = .true.
      cells = cells + 1
      n = count(done .and. key == key(i))
      k = count(done .and. hit .and. key == key(i))
      if (n == 0) cycle
      bounds = wilson_interval(k, n)
      if (bounds(2) <= risk .or. bounds(1) > risk) decided = decided + 1
    end do
  end subroutine cell_verdicts

  !> Delete `path` if it exists (the scratch summary and its lock).
  subroutine remove(path)
    !> Path of the file to delete.
    character(len=*), intent(in) :: path
    integer :: unit, ios
    logical :: exists
    inquire (file=path, exist=exists)
    if (exists) then
      open (newunit=unit, file=path, status="old", iostat=ios)
      if (ios == 0) close (unit, status="delete")
    end if
    inquire (file=path//".lock", exist=exists)
    if (exists) then
      open (newunit=unit, file=path//".lock", status="old", iostat=ios)
      if (ios == 0) close (unit, status="delete")
    end if
  end subroutine remove

end module davit_bench_study
