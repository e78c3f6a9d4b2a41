!> `davit sweep`: every case of a sweep deck, run in parallel with OpenMP over cases
!> (dynamic schedule: cases differ in cost). Each case builds its own system from its own
!> copy of the configuration inside the thread, so nothing mutable is shared; the one
!> critical section (store_case) stores a finished row, reports progress and does all
!> HDF5 output during the loop (Debian's HDF5 is not thread-safe). A case that fails
!> (diverges) is recorded with its message and the sweep goes on. The summary is written
!> whole at the start, at checkpoints and at the end, so an interrupted sweep leaves a
!> valid summary that --resume completes without recomputing finished cases.
!> With --shard K/N only that slice of the cases runs (davit_sweep_shards), for job arrays
!> whose summaries `davit sweep --merge` joins. With &sweep target_halfwidth > 0 the cases
!> run in rounds (davit_sweep_adaptive), each round through the same parallel loop.
module davit_sweep_driver
  !$ use omp_lib, only: omp_get_max_threads, omp_get_num_procs
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_io_hdf5_writer, only: h5_writer_type, check_output_path, acquire_lock, release_lock
  use davit_io_namelist, only: int_to_str
  use davit_io_deck_reader, only: fmt_real
  use davit_system_model, only: system_type
  use davit_run_scene, only: new_boat_system
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_scenario, only: write_root_attributes
  use davit_run_driver, only: integrate
  use davit_run_launch_log, only: new_launch_log
  use davit_run_budget, only: check_run_budget, memory_limit, run_memory_estimate
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_cases, only: sweep_case, build_cases, case_config, initial_clearance
  use davit_sweep_metrics, only: launch_metrics, case_result, status_not_run, status_ok, &
                                 status_failed, status_not_needed, not_run_result
  use davit_sweep_summary, only: write_summary, read_results
  use davit_sweep_progress, only: sweep_state, report_progress, seconds_since
  use davit_sweep_shards, only: shard_spec, shard_mask, shard_text, longest_first
  use davit_sweep_adaptive, only: adaptive, refuse_adaptive, adaptive_plan, new_plan, &
                                  round_cases, close_round, mark_not_needed, plan_text, &
                                  fmt_width
  implicit none
  private
  public :: sweep_options, sweep_outcome, run_sweep, prepare_cases, run_case, longest_first
  public :: case_row
  ! for the MPI sweep (davit_sweep_mpi_sweep), which shares the set-up, rows and summary
  public :: sweep_state, sweep_run, start_sweep, finish_sweep, store_case, thread_count
  public :: series

  type :: sweep_options
    !> OpenMP threads; 0 = OMP_NUM_THREADS (or the runtime's default).
    integer :: threads = 0
    !> Keep the finished cases of an existing summary of the same sweep.
    logical :: resume = .false.
    !> No progress lines on stderr.
    logical :: quiet = .false.
    !> Folder for one time-series file per case (empty = none).
    character(len=:), allocatable :: series_dir
    !> Stop after this many newly finished cases (0 = all), leaving a resumable summary.
    integer :: max_cases = 0
    !> Seconds between rewrites of the summary while the sweep runs.
    real(wp) :: checkpoint_interval = 30.0_wp
    !> Seconds between progress lines.
    real(wp) :: progress_interval = 5.0_wp
    !> Run only this slice of the cases (--shard K/N; count 0 = all of them).
    type(shard_spec) :: shard
  end type sweep_options

  type :: sweep_outcome
    !> Cases of the sweep, finished ok, failed, left not run, run by this call; OpenMP threads
    !> used.
    integer :: ncase = 0, ok = 0, failed = 0, not_run = 0, ran = 0, threads = 1
    !> Cases an adaptive sweep's converged cells did not need (status 3).
    integer :: not_needed = 0
    !> Cases of the shard run (ncase for the whole sweep).
    integer :: shard_cases = 0
    !> Wall time of the sweep [s].
    real(wp) :: wall_time = 0.0_wp
  end type sweep_outcome

  !> A sweep under way: its cases, the base deck's clearance, the shared state, the cases
  !> to run (dearest first; the first state%todo of them), the shard's cases, and whether
  !> this process holds the summary's lock.
  type :: sweep_run
    !> The cases of the sweep.
    type(sweep_case), allocatable :: cases(:)
    !> The base deck's initial clearance to the ship's side [m].
    real(wp) :: clearance0 = 0.0_wp
    !> Rows, counters and clocks the critical section shares.
    type(sweep_state) :: state
    !> The cases to run, dearest first (the first state%todo of them).
    integer, allocatable :: pending(:)
    !> Per case, whether it belongs to this shard.
    logical, allocatable :: mine(:)
    !> Whether this process holds the summary's lock.
    logical :: own_lock = .false.
  end type sweep_run

  interface
    function c_mkdir(path, mode) bind(C, name="mkdir") result(status)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
      integer(c_int) :: status
    end function c_mkdir
  end interface

contains

  !> Run (or resume) the sweep and write the summary `out_path`.
  subroutine run_sweep(s, opts, out_path, outcome, error)
    !> The sweep deck (base deck, varied values).
    type(sweep_config), intent(in) :: s
    !> Threads, resume, progress, series folder, shard.
    type(sweep_options), intent(in) :: opts
    !> Path of the summary file.
    character(len=*), intent(in) :: out_path
    !> Counts and wall time of the sweep.
    type(sweep_outcome), intent(out) :: outcome
    !> Set when the sweep cannot start or its summary cannot be written.
    type(error_type), allocatable, intent(out) :: error
    type(sweep_run) :: run
    integer :: nthreads

    nthreads = thread_count(opts%threads, s%base)
    call start_sweep(s, opts, out_path, nthreads, int_to_str(nthreads)//" thread(s)", run, &
                     error)
    if (allocated(error)) return
    if (adaptive(s)) then
      call run_rounds(s, run, opts, out_path, nthreads)
    else
      call run_pending(s, run%cases, run%pending, run%clearance0, opts, run%state, out_path, &
                       nthreads)
    end if
    call finish_sweep(s, opts, out_path, run, outcome, error)
  end subroutine run_sweep

  !> Adaptive realisations: each round's pending cases, dearest first, through the same
  !> parallel loop; then the stopping rule on the complete round. A --max-cases budget
  !> that runs out mid-round ends the sweep with that round's rest not run, so a resume
  !> replays the same rounds from the stored rows.
  subroutine run_rounds(s, run, opts, out_path, nthreads)
    type(sweep_config), intent(in) :: s
    type(sweep_run), intent(inout) :: run
    type(sweep_options), intent(in) :: opts
    character(len=*), intent(in) :: out_path
    integer, intent(in) :: nthreads
    type(adaptive_plan) :: plan
    integer, allocatable :: pending(:)
    integer :: ntodo
    plan = new_plan(s, size(run%cases))
    do
      pending = round_cases(plan, run%state%results)
      call longest_first(s, run%cases, pending)
      ntodo = size(pending)
      if (opts%max_cases > 0) ntodo = max(0, min(ntodo, opts%max_cases - run%state%done))
      run%state%todo = run%state%done + ntodo
      if (ntodo > 0) call run_pending(s, run%cases, pending(:ntodo), run%clearance0, opts, &
                                      run%state, out_path, nthreads)
      if (ntodo < size(pending)) exit
      call close_round(s, run%state%results, plan)
      ! at once, so that every later checkpoint tells these slots from unrun ones
      call mark_not_needed(s, plan, run%state%results)
      if (.not. opts%quiet) write (error_unit, "(a)") "davit sweep: "// &
        plan_text(s, plan, run%state%results)
      if (.not. any(plan%open)) exit
    end do
  end subroutine run_rounds

  !> The first state%todo pending cases on `nthreads` threads (dynamic: cases differ in
  !> cost; a shared counter rather than the loop index caps them at --max-cases).
  subroutine run_pending(s, cases, pending, clearance0, opts, state, out_path, nthreads)
    type(sweep_config), intent(in) :: s
    type(sweep_case), intent(in) :: cases(:)
    integer, intent(in) :: pending(:), nthreads
    real(wp), intent(in) :: clearance0
    type(sweep_options), intent(in) :: opts
    type(sweep_state), intent(inout) :: state
    character(len=*), intent(in) :: out_path
    integer :: k, claimed, slot
    claimed = 0
    !$omp parallel do schedule(dynamic, 1) num_threads(nthreads) default(none) &
    !$omp shared(s, cases, pending, clearance0, opts, state, out_path) &
    !$omp private(slot) shared(claimed)
    do k = 1, size(pending)
      !$omp atomic capture
      claimed = claimed + 1
      slot = claimed
      !$omp end atomic
      if (slot > state%todo) cycle
      call run_and_store(s, cases, pending(k), clearance0, opts, state, out_path)
    end do
    !$omp end parallel do
  end subroutine run_pending

  !> Everything before the first case: decks, output name and lock, series folder, the
  !> earlier summary when resuming (all checked before the summary is touched), the cases
  !> to run dearest first, a valid summary from the start and the opening progress line.
  !> `nthreads` goes into the summary, `where` into the progress line. The lock is held
  !> on success only (finish_sweep releases it).
  subroutine start_sweep(s, opts, out_path, nthreads, where, run, error)
    !> The sweep deck.
    type(sweep_config), intent(in) :: s
    !> Threads, resume, progress, series folder, shard.
    type(sweep_options), intent(in) :: opts
    !> Path of the summary file; where the sweep runs, for the opening progress line.
    character(len=*), intent(in) :: out_path, where
    !> Threads (or MPI ranks) recorded in the summary.
    integer, intent(in) :: nthreads
    !> The sweep under way.
    type(sweep_run), intent(out) :: run
    !> Set when a deck, the output, the lock, the series folder or the earlier summary is refused.
    type(error_type), allocatable, intent(out) :: error
    if (opts%shard%count > 0) call refuse_adaptive(s, "shards (--shard K/N)", error)
    if (allocated(error)) return
    call prepare_cases(s, run%cases, run%clearance0, error)
    if (allocated(error)) return
    call check_output_path(out_path, error)
    if (allocated(error)) return
    if (len(series(opts)) > 0) then
      if (series(opts) == out_path) then
        call fatal_error(error, "the series folder and the summary are both '"//out_path// &
                         "'; name two different paths")
        return
      end if
    end if
    call acquire_lock(out_path, run%own_lock, error)
    if (allocated(error)) return
    call open_summary(s, opts, out_path, nthreads, where, run, error)
    if (allocated(error) .and. run%own_lock) call release_lock(out_path)
  end subroutine start_sweep

  subroutine open_summary(s, opts, out_path, nthreads, where, run, error)
    type(sweep_config), intent(in) :: s
    type(sweep_options), intent(in) :: opts
    character(len=*), intent(in) :: out_path, where
    integer, intent(in) :: nthreads
    type(sweep_run), intent(inout) :: run
    type(error_type), allocatable, intent(out) :: error
    logical :: exists
    integer :: k, n
    if (len(series(opts)) > 0) call make_folder(series(opts), error)
    if (allocated(error)) return
    allocate (run%state%results(size(run%cases)))
    run%state%results = not_run_result()
    inquire (file=out_path, exist=exists)
    if (opts%resume .and. exists) then
      call read_results(out_path, s, size(run%cases), opts%shard, run%state%results, error)
      if (allocated(error)) return
    end if
    run%mine = shard_mask(s, run%cases, opts%shard)
    ! the unrun cases of this shard, built on the heap (an index array as long as the
    ! sweep would otherwise be a temporary on the stack)
    allocate (run%pending(count(run%state%results%status == status_not_run .and. run%mine)))
    n = 0
    do k = 1, size(run%cases)
      if (run%state%results(k)%status /= status_not_run .or. .not. run%mine(k)) cycle
      n = n + 1
      run%pending(n) = k
    end do
    call longest_first(s, run%cases, run%pending)
    run%state%threads = nthreads
    run%state%todo = size(run%pending)
    if (opts%max_cases > 0) run%state%todo = min(run%state%todo, opts%max_cases)
    ! a valid summary from the start (also checks that the path is writable)
    call write_summary(out_path, s, run%cases, run%state%results, nthreads, series(opts), &
                       opts%shard, error)
    if (allocated(error)) return
    call system_clock(run%state%clock0, run%state%rate)
    run%state%last_progress = run%state%clock0
    run%state%last_checkpoint = run%state%clock0
    if (opts%quiet) return
    if (adaptive(s)) then
      write (error_unit, "(a)") "davit sweep: adaptive realisations, "// &
        int_to_str(size(run%cases)/s%max_realisations)//" cells of up to "// &
        int_to_str(s%max_realisations)//" realisations (first "// &
        int_to_str(s%realisations)//", then "//int_to_str(s%realisation_batch)// &
        " per round until the 95 % half-width <= "//fmt_width(s%target_halfwidth)// &
        ") on "//where
    else
      write (error_unit, "(a)") "davit sweep: "//int_to_str(run%state%todo)//" of "// &
        int_to_str(size(run%cases))//" cases to run on "//where// &
        shard_note(opts%shard, count(run%mine))
    end if
  end subroutine open_summary

  !> The final summary, the outcome, and the lock released.
  subroutine finish_sweep(s, opts, out_path, run, outcome, error)
    !> The sweep deck.
    type(sweep_config), intent(in) :: s
    !> Threads, resume, progress, series folder, shard.
    type(sweep_options), intent(in) :: opts
    !> Path of the summary file.
    character(len=*), intent(in) :: out_path
    !> The sweep under way; its lock released.
    type(sweep_run), intent(inout) :: run
    !> Counts and wall time of the sweep.
    type(sweep_outcome), intent(out) :: outcome
    !> Set when the final summary cannot be written (or an I/O failure during the loop).
    type(error_type), allocatable, intent(out) :: error
    call write_summary(out_path, s, run%cases, run%state%results, run%state%threads, &
                       series(opts), opts%shard, error)
    if (.not. allocated(error) .and. allocated(run%state%io_error)) then
      call move_alloc(run%state%io_error, error)
    end if
    outcome%ncase = size(run%cases)
    outcome%ok = count(run%state%results%status == status_ok)
    outcome%failed = count(run%state%results%status == status_failed)
    outcome%not_run = count(run%state%results%status == status_not_run)
    outcome%not_needed = count(run%state%results%status == status_not_needed)
    outcome%ran = run%state%done
    outcome%threads = run%state%threads
    outcome%shard_cases = count(run%mine)
    outcome%wall_time = seconds_since(run%state, run%state%clock0)
    if (run%own_lock) call release_lock(out_path)
  end subroutine finish_sweep

  !> The cases of the sweep and the base deck's initial clearance [m].
  subroutine prepare_cases(s, cases, clearance0, error)
    !> The sweep deck.
    type(sweep_config), intent(in) :: s
    !> The cases of the sweep.
    type(sweep_case), allocatable, intent(out) :: cases(:)
    !> The base deck's initial clearance to the ship's side [m].
    real(wp), intent(out) :: clearance0
    !> Set when a case's deck is refused.
    type(error_type), allocatable, intent(out) :: error
    call initial_clearance(s%base, clearance0, error)
    if (allocated(error)) return
    call build_cases(s, clearance0, cases)
  end subroutine prepare_cases

  !> One case on this thread, then its row (and series file) in the critical section.
  subroutine run_and_store(s, cases, c, clearance0, opts, state, out_path)
    type(sweep_config), intent(in) :: s
    type(sweep_case), intent(in) :: cases(:)
    integer, intent(in) :: c
    real(wp), intent(in) :: clearance0
    type(sweep_options), intent(in) :: opts
    type(sweep_state), intent(inout) :: state
    character(len=*), intent(in) :: out_path
    type(config_type) :: cfg
    type(system_type) :: sys
    type(boat_recorder) :: rec
    type(case_result) :: row
    type(error_type), allocatable :: run_error
    call case_config(s, cases(c), clearance0, cfg)
    call run_case(cfg, s%stop_at_release, sys, rec, row, run_error)
    !$omp critical (davit_sweep_io)
    call store_case(s, cases, c, row, opts, state, out_path)
    if (len(series(opts)) > 0 .and. allocated(rec%time)) then
      call write_series(series_path(opts, c), cfg, sys, rec, row, run_error, state)
    end if
    !$omp end critical (davit_sweep_io)
  end subroutine run_and_store

  !> One case with its own configuration, system and recorder (locals of the calling
  !> thread), for the runners that keep only its row (the bench, the MPI workers).
  subroutine case_row(s, c, clearance0, row)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The case.
    type(sweep_case), intent(in) :: c
    !> The base deck's initial clearance [m].
    real(wp), intent(in) :: clearance0
    !> The case's summary row.
    type(case_result), intent(out) :: row
    type(config_type) :: cfg
    type(system_type) :: sys
    type(boat_recorder) :: rec
    type(error_type), allocatable :: run_error
    call case_config(s, c, clearance0, cfg)
    call run_case(cfg, s%stop_at_release, sys, rec, row, run_error)
  end subroutine case_row

  !> Run one case: build its system, integrate with the launch metrics watching every step,
  !> return its row. A failed run gives a row of status failed with the message.
  subroutine run_case(cfg, stop_at_release, sys, rec, row, run_error)
    !> The case's configuration.
    type(config_type), intent(in) :: cfg
    !> End the run at the release (the sweep's metrics need nothing after it).
    logical, intent(in) :: stop_at_release
    !> The case's system, built here.
    type(system_type), intent(out) :: sys
    !> The case's time series (written only with a series folder).
    type(boat_recorder), intent(out) :: rec
    !> The case's row of the summary.
    type(case_result), intent(out) :: row
    !> Why the run failed (unallocated: it did not).
    type(error_type), allocatable, intent(out) :: run_error
    type(launch_metrics) :: metrics
    type(run_summary) :: summary
    type(error_type), allocatable :: error
    real(wp), allocatable :: y(:)
    integer(i8) :: clock0, clock1, rate
    call system_clock(clock0, rate)
    ! Set-up runs one thread at a time, under the lock that also guards the summary's
    ! writes: it reads the BEM databases with the serial HDF5 library, which is not
    ! thread-safe.
    !$omp critical (davit_sweep_io)
    call check_run_budget(cfg, error, in_sweep=.true.)
    if (.not. allocated(error)) call new_boat_system(cfg, sys, y, error)
    if (.not. allocated(error)) then
      metrics%stop_at_release = stop_at_release
      metrics%log = new_launch_log(cfg, sys)
    end if
    !$omp end critical (davit_sweep_io)
    if (.not. allocated(error)) then
      call integrate(cfg%simulation, sys, y, rec, summary, run_error, error, metrics)
    end if
    if (allocated(error)) call move_alloc(error, run_error)
    ! The row's texts (outcome, message) are built one thread at a time: gfortran keeps the
    ! length of a deferred-length function result in a static variable, so two threads
    ! building texts at once could garble them (seen as 1-5 in 3000 short cases)
    !$omp critical (davit_sweep_io)
    if (allocated(run_error)) then
      row = not_run_result()
      row%status = status_failed
      row%message = run_error%message
    else
      row = metrics%result(sys)
    end if
    !$omp end critical (davit_sweep_io)
    row%steps = summary%steps
    row%rhs_evaluations = summary%rhs_evaluations
    call system_clock(clock1)
    row%wall_time = real(clock1 - clock0, wp)/real(rate, wp)
  end subroutine run_case

  !> Inside the critical section: store row c, report progress, checkpoint when due.
  subroutine store_case(s, cases, c, row, opts, state, out_path)
    !> The sweep deck.
    type(sweep_config), intent(in) :: s
    !> The cases of the sweep.
    type(sweep_case), intent(in) :: cases(:)
    !> Index of the case stored.
    integer, intent(in) :: c
    !> The case's row.
    type(case_result), intent(in) :: row
    !> Progress and checkpoint intervals, series folder, shard.
    type(sweep_options), intent(in) :: opts
    !> Rows, counters and clocks, the row stored.
    type(sweep_state), intent(inout) :: state
    !> Path of the summary file (checkpoints).
    character(len=*), intent(in) :: out_path
    type(error_type), allocatable :: error
    integer(i8) :: now
    state%results(c) = row
    state%done = state%done + 1
    if (row%status == status_failed) then
      state%failed = state%failed + 1
      if (.not. opts%quiet) write (error_unit, "(a)") "davit sweep: case "// &
        int_to_str(c)//" failed: "//row%message
    end if
    call system_clock(now)
    if (.not. opts%quiet .and. (state%done == state%todo .or. &
        seconds_since(state, state%last_progress) >= opts%progress_interval)) then
      call report_progress(state)
      state%last_progress = now
    end if
    if (state%done < state%todo .and. &
        seconds_since(state, state%last_checkpoint) >= opts%checkpoint_interval) then
      call write_summary(out_path, s, cases, state%results, state%threads, series(opts), &
                         opts%shard, error)
      if (allocated(error) .and. .not. allocated(state%io_error)) then
        call move_alloc(error, state%io_error)
      end if
      state%last_checkpoint = now
    end if
  end subroutine store_case

  !> The case's time series (the run file layout) under the series folder; inside the
  !> critical section.
  subroutine write_series(path, cfg, sys, rec, row, run_error, state)
    character(len=*), intent(in) :: path
    type(config_type), intent(in) :: cfg
    type(system_type), intent(in) :: sys
    type(boat_recorder), intent(in) :: rec
    type(case_result), intent(in) :: row
    type(error_type), allocatable, intent(in) :: run_error
    type(sweep_state), intent(inout) :: state
    type(h5_writer_type) :: w
    type(run_summary) :: summary
    type(error_type), allocatable :: error
    call w%create(path, error)
    if (.not. allocated(error)) then
      summary%steps = row%steps
      summary%rhs_evaluations = row%rhs_evaluations
      summary%wall_time = row%wall_time
      summary%samples = rec%n
      summary%complete = row%status == status_ok
      call rec%write(sys, w)
      call write_root_attributes(w, cfg, summary, cfg%simulation%integrator, run_error)
      call w%close(error)
    end if
    if (allocated(error) .and. .not. allocated(state%io_error)) then
      call move_alloc(error, state%io_error)
    end if
  end subroutine write_series

  !> " (shard K/N: M cases)" for a shard, else nothing.
  function shard_note(shard, ncase) result(note)
    type(shard_spec), intent(in) :: shard
    integer, intent(in) :: ncase
    character(len=:), allocatable :: note
    note = ""
    if (shard%count > 0) note = " (shard "//shard_text(shard)//": "//int_to_str(ncase)// &
                                " cases)"
  end function shard_note

  function series(opts) result(dir)
    !> The sweep's options.
    type(sweep_options), intent(in) :: opts
    character(len=:), allocatable :: dir
    dir = ""
    if (allocated(opts%series_dir)) dir = opts%series_dir
  end function series

  !> SERIES_DIR/case_000017.h5
  function series_path(opts, c) result(path)
    type(sweep_options), intent(in) :: opts
    integer, intent(in) :: c
    character(len=:), allocatable :: path
    character(len=12) :: name
    write (name, "(a,i6.6)") "case_", c
    path = series(opts)//"/"//trim(name)//".h5"
  end function series_path

  !> Create folder `path` if needed (its parent must exist) and check that files can be
  !> written there, before any case runs.
  subroutine make_folder(path, error)
    character(len=*), intent(in) :: path
    type(error_type), allocatable, intent(out) :: error
    integer :: status, unit
    status = c_mkdir(path//c_null_char, int(o'755', c_int))
    open (newunit=unit, file=path//"/.davit_write_test", status="replace", iostat=status)
    if (status /= 0) then
      call fatal_error(error, "cannot write into the series folder '"//path//"'")
      return
    end if
    close (unit, status="delete")
  end subroutine make_folder

  !> Threads of the sweep: the request (or the runtime's default), at most
  !> max(64, 4 x the processors): each thread holds a system and a stack, and an absurd
  !> request (--threads 100000) would fail to start them; and no more than hold their cases
  !> (the base deck's memory estimate) within the memory limit together. The results do not
  !> depend on the thread count.
  integer function thread_count(requested, base) result(n)
    !> Threads asked for (--threads; 0: the runtime's default).
    integer, intent(in) :: requested
    !> The base deck (its memory estimate).
    type(config_type), intent(in) :: base
    integer :: cap, fit
    character(len=:), allocatable :: source
    n = 1
    cap = 64
    source = "OMP_NUM_THREADS="
    !$ n = omp_get_max_threads()
    !$ cap = max(64, 4*omp_get_num_procs())
    if (requested > 0) then
      n = requested
      source = "--threads "
    end if
    if (n > cap) then
      write (error_unit, "(a)") "davit sweep: note: "//source//int_to_str(n)// &
        " is more than "//int_to_str(cap)//" (4 x the processors, at least 64); using "// &
        int_to_str(cap)
      n = cap
    end if
    fit = int(max(1.0_wp, min(real(n, wp), memory_limit(base)/run_memory_estimate(base))))
    if (fit < n) then
      write (error_unit, "(a)") "davit sweep: note: "//int_to_str(n)//" thread(s) would "// &
        "hold more than &simulation max_memory (or 80 % of physical memory) with one case "// &
        "each; using "//int_to_str(fit)
      n = fit
    end if
  end function thread_count

end module davit_sweep_driver
