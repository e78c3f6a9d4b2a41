!> `davit sweep` across MPI ranks (built with -DDAVIT_MPI by `bash make.sh mpi`). Rank 0 is
!> the coordinator: it does everything the OpenMP sweep does around the cases (davit_sweep_
!> driver: set-up, lock, resume, dearest-first order, progress, checkpoints, the summary)
!> but runs none; ranks 1..N-1 are workers that ask for a case index, run it through the
!> same run_case as the OpenMP sweep and send the row back bit for bit (davit_sweep_row_
!> codec). Handing out one case per request balances cases of very different cost, and
!> the coordinator alone writes the summary, so a lost worker only leaves its cases not
!> run in the last checkpoint. A worker with --threads T runs T cases at once: each
!> OpenMP thread asks for its own cases (its thread number is its message tag), the MPI
!> calls serialised in one critical section (MPI_THREAD_SERIALIZED).
!> Without DAVIT_MPI, or on a single rank, this is exactly the OpenMP sweep.
module davit_sweep_mpi_sweep
  !$ use omp_lib, only: omp_get_thread_num
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: iso_c_binding, only: c_int
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: int_to_str
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_metrics, only: case_result
  use davit_sweep_driver, only: sweep_options, sweep_outcome, sweep_run, run_sweep, &
                                start_sweep, finish_sweep, store_case, thread_count, &
                                prepare_cases, case_row, series
  use davit_sweep_row_codec, only: encode_row, decode_row
#ifdef DAVIT_MPI
  use davit_sweep_adaptive, only: refuse_adaptive
  use mpi_f08
#endif
  implicit none
  private
  public :: sweep_anywhere, built_with_mpi

#ifdef DAVIT_MPI
  logical, parameter :: built_with_mpi = .true.
#else
  logical, parameter :: built_with_mpi = .false.
#endif

  !> The coordinator's naps between polls [us] when no request is waiting, doubling from
  !> the first to the longest while none comes: a blocking MPI_Probe spins a core, which
  !> slowed the worker beside it (sharing the node, or SMT siblings) by 13 %; short naps
  !> first keep the answer prompt when requests come thick (millisecond cases), and 1 ms
  !> is nothing against a case of a second.
  integer(c_int), parameter :: first_nap_us = 10, longest_nap_us = 1000

  interface
    integer(c_int) function c_usleep(us) bind(C, name="usleep")
      import :: c_int
      integer(c_int), value :: us
    end function c_usleep
  end interface

contains

  !> Run the sweep: across the MPI world when this build has MPI and the world has more
  !> than one rank, else with OpenMP alone. `report` is true on the process that wrote the
  !> summary (the coordinator): only it has an outcome to print.
  subroutine sweep_anywhere(s, opts, out_path, outcome, report, error)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> Command-line options (threads, resume, progress, series folder).
    type(sweep_options), intent(in) :: opts
    !> Path of the summary file.
    character(len=*), intent(in) :: out_path
    !> Case counts and timings of the sweep (on the coordinator).
    type(sweep_outcome), intent(out) :: outcome
    !> True on the process that wrote the summary.
    logical, intent(out) :: report
    !> Set on a set-up or run error.
    type(error_type), allocatable, intent(out) :: error
#ifdef DAVIT_MPI
    integer :: rank, nranks, provided
    call MPI_Init_thread(MPI_THREAD_SERIALIZED, provided)
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks)
    report = rank == 0
    if (nranks == 1) then
      call run_sweep(s, opts, out_path, outcome, error)
    else if (rank == 0) then
      call coordinate(s, opts, out_path, nranks, outcome, error)
    else
      call work(s, opts, rank, provided >= MPI_THREAD_SERIALIZED)
    end if
    call MPI_Finalize()
#else
    report = .true.
    call run_sweep(s, opts, out_path, outcome, error)
#endif
  end subroutine sweep_anywhere

#ifdef DAVIT_MPI
  !> Rank 0: learn how many worker threads will ask, set the sweep up, serve them, write
  !> the summary. On a set-up error the workers are still answered (with "stop").
  subroutine coordinate(s, opts, out_path, nranks, outcome, error)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> Command-line options.
    type(sweep_options), intent(in) :: opts
    !> Path of the summary file.
    character(len=*), intent(in) :: out_path
    !> Number of MPI ranks (the coordinator and its workers).
    integer, intent(in) :: nranks
    !> Case counts and timings of the sweep.
    type(sweep_outcome), intent(out) :: outcome
    !> Set on a set-up or summary error.
    type(error_type), allocatable, intent(out) :: error
    type(sweep_run) :: run
    integer :: counts(nranks), requesters
    call MPI_Gather(0, 1, MPI_INTEGER, counts, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
    requesters = sum(counts)
    if (len(series(opts)) > 0) then
      ! the time series would be written by many processes into one folder's HDF5 files,
      ! which the summary's single writer does not cover
      call fatal_error(error, "--series is not available across MPI ranks; run the "// &
                       "sweep on one rank (or without mpirun) to write time series")
    else
      call refuse_adaptive(s, "MPI ranks (mpirun -np "//int_to_str(nranks)//")", error)
    end if
    if (.not. allocated(error)) then
      call start_sweep(s, opts, out_path, requesters, int_to_str(nranks - 1)// &
                       " worker rank(s), "//int_to_str(requesters)//" thread(s)", run, error)
    end if
    if (allocated(error)) then
      run%state%todo = 0
      call serve(s, opts, out_path, run, requesters)
      return
    end if
    call serve(s, opts, out_path, run, requesters)
    call finish_sweep(s, opts, out_path, run, outcome, error)
  end subroutine coordinate

  !> Answer every request until each of the `requesters` worker threads has been told to
  !> stop (or has left): a request carries the row of the requester's last case (none on
  !> its first), which is stored, and is answered with the next case, dearest first, or 0.
  subroutine serve(s, opts, out_path, run, requesters)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> Command-line options.
    type(sweep_options), intent(in) :: opts
    !> Path of the summary file.
    character(len=*), intent(in) :: out_path
    !> The sweep's state (cases, rows, pending list), updated with each row received.
    type(sweep_run), intent(inout) :: run
    !> Worker threads that will ask for cases.
    integer, intent(in) :: requesters
    type(MPI_Status) :: status
    type(case_result) :: row
    type(error_type), allocatable :: error
    character(len=:), allocatable :: buf
    integer :: active, next, c, n, reply
    active = requesters
    next = 1
    do while (active > 0)
      call wait_for_request(status)
      call MPI_Get_count(status, MPI_CHARACTER, n)
      if (allocated(buf)) deallocate (buf)
      allocate (character(len=n) :: buf)
      call MPI_Recv(buf, n, MPI_CHARACTER, status%MPI_SOURCE, status%MPI_TAG, &
                    MPI_COMM_WORLD, MPI_STATUS_IGNORE)
      call decode_row(buf, c, row, error)
      if (allocated(error)) then
        write (error_unit, "(a)") "davit sweep: rank "//int_to_str(status%MPI_SOURCE)// &
          ": "//error%message//"; its row is dropped"
        c = 0
      end if
      if (c < 0) then
        active = active - 1
        cycle
      end if
      if (c > 0 .and. c <= size(run%state%results)) then
        call store_case(s, run%cases, c, row, opts, run%state, out_path)
      end if
      reply = 0
      if (next <= run%state%todo) then
        reply = run%pending(next)
        next = next + 1
      end if
      call MPI_Send(reply, 1, MPI_INTEGER, status%MPI_SOURCE, status%MPI_TAG, &
                    MPI_COMM_WORLD)
      if (reply == 0) active = active - 1
    end do
  end subroutine serve

  !> Until a request is waiting (its envelope in `status`), napping between polls.
  subroutine wait_for_request(status)
    !> Envelope (source and tag) of the waiting request.
    type(MPI_Status), intent(out) :: status
    logical :: waiting
    integer(c_int) :: nap
    nap = first_nap_us
    do
      call MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, waiting, status)
      if (waiting) return
      if (c_usleep(nap) /= 0) continue
      nap = min(2*nap, longest_nap_us)
    end do
  end subroutine wait_for_request

  !> A worker rank: its thread count to the coordinator, then cases until told to stop.
  !> Its own errors (the set-up) are reported here and make its threads leave, so the
  !> other ranks finish the sweep.
  subroutine work(s, opts, rank, threads_ok)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> Command-line options (threads).
    type(sweep_options), intent(in) :: opts
    !> This worker's rank.
    integer, intent(in) :: rank
    !> Whether the MPI library can serialise calls from threads (else one thread).
    logical, intent(in) :: threads_ok
    type(sweep_case), allocatable :: cases(:)
    type(error_type), allocatable :: error
    real(wp) :: clearance0
    integer :: nthreads, dummy(1)
    logical :: ready
    nthreads = thread_count(opts%threads, s%base)
    if (.not. threads_ok .and. nthreads > 1) then
      write (error_unit, "(a)") "davit sweep: note: rank "//int_to_str(rank)// &
        ": this MPI library cannot serialise calls from threads; using 1 thread"
      nthreads = 1
    end if
    call MPI_Gather(nthreads, 1, MPI_INTEGER, dummy, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
    call prepare_cases(s, cases, clearance0, error)
    ready = .not. allocated(error)
    if (.not. ready) write (error_unit, "(a)") "davit sweep: rank "//int_to_str(rank)// &
      ": "//error%message
    !$omp parallel num_threads(nthreads) default(none) shared(s, cases, clearance0, ready)
    call work_thread(s, cases, clearance0, ready)
    !$omp end parallel
  end subroutine work

  !> One worker thread: ask (with the last row), run the case received, until case 0.
  subroutine work_thread(s, cases, clearance0, ready)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> All the sweep's cases.
    type(sweep_case), intent(in) :: cases(:)
    !> The base deck's initial clearance [m].
    real(wp), intent(in) :: clearance0
    !> Whether the rank's set-up succeeded (else the thread tells the coordinator and leaves).
    logical, intent(in) :: ready
    type(case_result) :: row
    character(len=:), allocatable :: buf
    integer :: c, tag
    tag = 0
    !$ tag = omp_get_thread_num()
    if (.not. ready) then
      buf = encode_row(-1, row)
      !$omp critical (davit_sweep_mpi)
      call MPI_Send(buf, len(buf), MPI_CHARACTER, 0, tag, MPI_COMM_WORLD)
      !$omp end critical (davit_sweep_mpi)
      return
    end if
    buf = encode_row(0, row)
    do
      !$omp critical (davit_sweep_mpi)
      call MPI_Send(buf, len(buf), MPI_CHARACTER, 0, tag, MPI_COMM_WORLD)
      call MPI_Recv(c, 1, MPI_INTEGER, 0, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE)
      !$omp end critical (davit_sweep_mpi)
      if (c <= 0 .or. c > size(cases)) exit
      call case_row(s, cases(c), clearance0, row)
      buf = encode_row(c, row)
    end do
  end subroutine work_thread
#endif

end module davit_sweep_mpi_sweep
