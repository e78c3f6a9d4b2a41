!> Command line of davit. Only this program turns errors into exit codes:
!> 0 success, 1 bad input or failed run, 2 usage error.
program davit
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use davit_kinds, only: wp, davit_version
  use davit_error, only: error_type, fatal_error
  use davit_io_search_path, only: find_file, folder_of
  use davit_io_config, only: config_type, read_config, document_keys
  use davit_io_deck_reader, only: key_doc
  use davit_io_namelist, only: int_to_str
  use davit_run_driver, only: run_simulation
  use davit_run_scenario, only: scenario_text
  use davit_run_run_summary, only: run_summary
  use davit_run_progress, only: progress_meter, new_progress_meter, stderr_is_terminal
  use davit_bench_suite, only: bench_options, run_bench
  use davit_run_rao, only: run_rao
  use davit_sweep_keys, only: sweep_config, read_sweep, document_sweep_keys
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_driver, only: sweep_options, sweep_outcome, prepare_cases
  use davit_sweep_shards, only: parse_shard, shard_text
  use davit_sweep_merge, only: merge_outcome, merge_shards
  use davit_sweep_mpi_sweep, only: sweep_anywhere
  use davit_run_linear_modes, only: linear_modes
  use davit_core_blas_threads, only: single_threaded_blas, stop_idle_blas_workers
  use davit_io_text, only: join_ints
  implicit none

  interface
    function c_mkdir(path, mode) bind(C, name="mkdir") result(status)
      import :: c_int, c_char
      !> Path of the folder, NUL-terminated.
      character(kind=c_char), intent(in) :: path(*)
      !> Permission bits.
      integer(c_int), value :: mode
      integer(c_int) :: status
    end function c_mkdir
  end interface

  !> A file of the bench decks' folder (davit bench finds the folder by it).
  character(len=*), parameter :: bench_marker = "bench_sweep.nml"
  character(len=:), allocatable :: command
  integer :: nargs

  call single_threaded_blas()
  call stop_idle_blas_workers()
  nargs = command_argument_count()
  if (nargs < 1) call usage_error("missing subcommand")
  command = argument(1)
  ! `davit SUBCOMMAND --help` (or -h anywhere after it): that subcommand's usage, exit 0
  if (asks_help(nargs)) then
    call print_command_help(command)
    stop
  end if
  select case (command)
  case ("-h", "--help", "help")
    call print_help()
  case ("-V", "--version", "version")
    write (output_unit, "(a)") "davit "//davit_version
  case ("run")
    call cmd_run(.false.)
  case ("rao")
    call cmd_run(.true.)
  case ("sweep")
    call cmd_sweep()
  case ("keys")
    call cmd_keys()
  case ("modes")
    call cmd_modes()
  case ("bench")
    call cmd_bench()
  case default
    call usage_error("unknown subcommand or option '"//command//"'")
  end select

contains

  !> `run` and `rao` take the same arguments: one deck and an optional output file. A run
  !> draws its progress on stderr when that is a terminal.
  subroutine cmd_run(rao)
    !> `davit rao` (else `davit run`).
    logical, intent(in) :: rao
    character(len=:), allocatable :: deck, out, arg
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(run_summary) :: summary
    type(progress_meter) :: progress
    integer :: i
    deck = ""
    out = ""
    i = 2
    do while (i <= nargs)
      arg = argument(i)
      select case (arg)
      case ("-o", "--output")
        if (i == nargs) call usage_error("option "//arg//" needs a file name")
        out = argument(i + 1)
        i = i + 2
      case default
        if (arg(1:1) == "-") call usage_error("unknown option '"//arg//"' for '"// &
                                              argument(1)//"'")
        if (len(deck) > 0) call usage_error("'"//argument(1)//"' takes one deck, got '"// &
                                            deck//"' and '"//arg//"'")
        deck = arg
        i = i + 1
      end select
    end do
    if (len(deck) == 0) call usage_error("'"//argument(1)//"' needs a deck file: davit "// &
                                         argument(1)//" DECK.nml")
    call refuse_empty_names()
    call read_config(deck, cfg, error)
    if (allocated(error)) call fail(error)
    if (len(out) == 0) out = default_output(deck)
    if (rao) then
      call run_rao(cfg, out, summary, error)
    else
      ! what this run simulates, before it starts (stored as /scenario too)
      write (output_unit, "(a)") scenario_text(cfg)
      flush (output_unit)
      progress = new_progress_meter(stderr_is_terminal())
      call run_simulation(cfg, out, summary, error, progress)
    end if
    if (allocated(error)) call fail(error)
    write (output_unit, "(a,i0,a,i0,a,f0.3,a)") "davit: wrote '"//out//"' (", summary%steps, &
      " steps, ", summary%rhs_evaluations, " RHS evaluations, ", summary%wall_time, " s)"
    if (allocated(summary%report)) then
      if (len(summary%report) > 0) write (output_unit, "(a)") summary%report
    end if
  end subroutine cmd_run

  !> `sweep SWEEP.nml [-o SUMMARY.h5] [--threads N] [--resume] [--quiet] [--series DIR]
  !> [--max-cases K] [--checkpoint S] [--dry-run] [--shard K/N]`, or
  !> `sweep --merge OUT.h5 SHARD.h5...`
  subroutine cmd_sweep()
    character(len=:), allocatable :: deck, out, arg
    type(sweep_config) :: sweep
    type(sweep_options) :: opts
    type(sweep_outcome) :: outcome
    type(error_type), allocatable :: error
    logical :: dry_run, report
    integer :: i, seconds
    deck = ""
    out = ""
    dry_run = .false.
    if (any([(argument(i) == "--merge", i = 2, nargs)])) then
      call cmd_merge()
      return
    end if
    i = 2
    do while (i <= nargs)
      arg = argument(i)
      select case (arg)
      case ("-o", "--output")
        call take_value(i, out)
      case ("--shard")
        call take_shard(i, opts)
      case ("--threads")
        call take_int(i, 1, opts%threads)
      case ("--series")
        call take_value(i, opts%series_dir)
      case ("--max-cases")
        call take_int(i, 1, opts%max_cases)
      case ("--checkpoint")
        call take_int(i, 0, seconds)
        opts%checkpoint_interval = real(seconds, wp)
      case ("--resume", "--quiet", "--dry-run")
        if (arg == "--resume") opts%resume = .true.
        if (arg == "--quiet") opts%quiet = .true.
        if (arg == "--dry-run") dry_run = .true.
        i = i + 1
      case default
        if (arg(1:1) == "-") call usage_error("unknown option '"//arg//"' for 'sweep'")
        if (len(deck) > 0) call usage_error("'sweep' takes one deck, got '"//deck// &
                                            "' and '"//arg//"'")
        deck = arg
        i = i + 1
      end select
    end do
    if (len(deck) == 0) call usage_error("'sweep' needs a sweep deck: davit sweep SWEEP.nml")
    call refuse_empty_names()
    call read_sweep(deck, sweep, error)
    if (allocated(error)) call fail(error)
    if (dry_run) then
      call sweep_dry_run(sweep)
      return
    end if
    if (len(out) == 0) out = default_output(deck)
    call sweep_anywhere(sweep, opts, out, outcome, report, error)
    if (allocated(error)) call fail(error)
    if (.not. report) return
    write (output_unit, "(a,i0,a,i0,a,i0,a,i0,a,f0.1,a,i0,a)") "davit: wrote '"//out// &
      "' (", outcome%ncase, " cases: ", outcome%ok, " ok, ", outcome%failed, " failed, ", &
      outcome%not_run, " not run"//not_needed_note(outcome)//"; ", outcome%wall_time, &
      " s on ", outcome%threads, " thread(s))"//shard_line(opts, outcome)
  end subroutine cmd_sweep

  !> ", N not needed" when an adaptive sweep's converged cells left cases out.
  function not_needed_note(outcome) result(note)
    !> The sweep's counts.
    type(sweep_outcome), intent(in) :: outcome
    character(len=:), allocatable :: note
    note = ""
    if (outcome%not_needed > 0) note = ", "//int_to_str(outcome%not_needed)//" not needed"
  end function not_needed_note

  !> " for shard K/N (M of its cases)" after a shard's summary line.
  function shard_line(opts, outcome) result(line)
    !> The sweep's options (the shard).
    type(sweep_options), intent(in) :: opts
    !> The sweep's counts.
    type(sweep_outcome), intent(in) :: outcome
    character(len=:), allocatable :: line
    line = ""
    if (opts%shard%count > 0) line = " for shard "//shard_text(opts%shard)//" ("// &
                                     int_to_str(outcome%shard_cases)//" of its cases)"
  end function shard_line

  !> The K/N of --shard (option i); advances i past both.
  subroutine take_shard(i, opts)
    !> Index of the --shard option, advanced past its value.
    integer, intent(inout) :: i
    !> The sweep's options, their shard set.
    type(sweep_options), intent(inout) :: opts
    character(len=:), allocatable :: v
    type(error_type), allocatable :: error
    call take_value(i, v)
    call parse_shard(v, opts%shard, error)
    if (allocated(error)) call usage_error(error%message)
  end subroutine take_shard

  !> `sweep --merge OUT.h5 SHARD.h5... [--quiet]`: join shard summaries.
  subroutine cmd_merge()
    character(len=:), allocatable :: out, arg, inputs(:)
    type(merge_outcome) :: outcome
    type(error_type), allocatable :: error
    logical :: quiet
    integer :: i, n, width
    out = ""
    quiet = .false.
    width = maxval([(len(argument(i)), i = 1, nargs)])
    allocate (character(len=width) :: inputs(nargs))
    n = 0
    i = 2
    do while (i <= nargs)
      arg = argument(i)
      select case (arg)
      case ("--merge")
        if (len(out) > 0) call usage_error("option --merge is given twice")
        call take_value(i, out)
      case ("--quiet")
        quiet = .true.
        i = i + 1
      case default
        if (arg(1:min(1, len(arg))) == "-") call usage_error("option '"//arg// &
          "' does not go with --merge (davit sweep --merge OUT.h5 SHARD.h5...)")
        n = n + 1
        inputs(n) = arg
        i = i + 1
      end select
    end do
    call refuse_empty_names()
    if (n == 0) call usage_error("'sweep --merge' needs the shard summaries: davit sweep "// &
                                 "--merge OUT.h5 SHARD1.h5 SHARD2.h5...")
    call merge_shards(out, inputs(1:n), outcome, error)
    if (allocated(error)) call fail(error)
    if (size(outcome%missing) > 0 .and. .not. quiet) write (error_unit, "(a)") &
      "davit sweep: note: shard(s) "//join_ints(outcome%missing)//" of "// &
      int_to_str(outcome%count)//" missing: their "//int_to_str(outcome%not_run)// &
      " case(s) stay not run; complete them with davit sweep "//outcome%sweep_file// &
      " --resume -o "//out
    write (output_unit, "(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a)") "davit: wrote '"//out//"' (", &
      outcome%ncase, " cases: ", outcome%ok, " ok, ", outcome%failed, " failed, ", &
      outcome%not_run, " not run; from ", n, " of ", outcome%count, " shards)"
  end subroutine cmd_merge

  !> The value of option i (the next argument); advances i past both.
  subroutine take_value(i, v)
    !> Index of the option, advanced past its value.
    integer, intent(inout) :: i
    !> The option's value.
    character(len=:), allocatable, intent(out) :: v
    if (i == nargs) call usage_error("option "//argument(i)//" needs a value")
    v = argument(i + 1)
    i = i + 2
  end subroutine take_value

  !> The integer value (>= lowest) of option i; advances i past both.
  subroutine take_int(i, lowest, n)
    !> Index of the option, advanced past its value.
    integer, intent(inout) :: i
    !> Smallest value allowed.
    integer, intent(in) :: lowest
    !> The option's value.
    integer, intent(out) :: n
    character(len=:), allocatable :: name, v
    integer :: ios
    name = argument(i)
    call take_value(i, v)
    read (v, *, iostat=ios) n
    if (ios /= 0 .or. verify(v, "0123456789") /= 0) n = lowest - 1
    if (n < lowest) call usage_error("option "//name//" needs an integer >= "// &
                                     int_to_str(lowest)//", got '"//v//"'")
  end subroutine take_int

  !> An empty file or folder name after -o, --output or --series is a usage error (it would
  !> otherwise silently mean the default output or no series).
  subroutine refuse_empty_names()
    integer :: k
    character(len=:), allocatable :: a
    do k = 2, nargs - 1
      a = argument(k)
      if (a == "-o" .or. a == "--output" .or. a == "--series" .or. a == "--merge") then
        if (len_trim(argument(k + 1)) == 0) call usage_error("option "//a// &
                                                              " needs a name, got ''")
      end if
    end do
  end subroutine refuse_empty_names

  !> Check the decks and print the number of cases, without running any.
  subroutine sweep_dry_run(sweep)
    !> The sweep deck.
    type(sweep_config), intent(in) :: sweep
    type(sweep_case), allocatable :: cases(:)
    type(error_type), allocatable :: error
    real(wp) :: clearance0
    call prepare_cases(sweep, cases, clearance0, error)
    if (allocated(error)) call fail(error)
    write (output_unit, "(a,i0,a,f0.4,a)") "davit: '"//sweep%filename//"': ", size(cases), &
      " cases on base deck '"//sweep%base_deck//"' (its initial clearance ", clearance0, &
      " m)"//adaptive_note(sweep)
  end subroutine sweep_dry_run

  !> "; at most: adaptive realisations ..." for a sweep with target_halfwidth > 0, whose
  !> case count is every cell's max_realisations slots.
  function adaptive_note(sweep) result(note)
    !> The sweep deck.
    type(sweep_config), intent(in) :: sweep
    character(len=:), allocatable :: note
    note = ""
    if (sweep%target_halfwidth > 0.0_wp) note = "; at most: adaptive realisations run "// &
      int_to_str(sweep%realisations)//" to "//int_to_str(sweep%max_realisations)// &
      " per cell"
  end function adaptive_note

  !> Fastest rates of the deck's system at t = 0 and the RK4 step limit they imply.
  subroutine cmd_modes()
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: rate, omega
    if (nargs /= 2) call usage_error("'modes' needs one deck: davit modes DECK.nml")
    call read_config(argument(2), cfg, error)
    if (allocated(error)) call fail(error)
    call linear_modes(cfg, rate, omega, error)
    if (allocated(error)) call fail(error)
    write (output_unit, "(a,es12.5,a)") "rate_max = ", rate, &
      " 1/s (largest |eigenvalue| of df/dy at t = 0)"
    write (output_unit, "(a,es12.5,a)") "omega_max = ", omega, " rad/s (largest |Im|)"
    write (output_unit, "(a,es12.5,a)") "rk4_limit = ", 2.83_wp/rate, " s (2.83/rate_max)"
  end subroutine cmd_modes

  !> `bench [--quick] [-o FILE.h5] [--decks DIR]`: default output out/bench.h5, decks input/.
  subroutine cmd_bench()
    type(bench_options) :: opts
    type(error_type), allocatable :: error
    character(len=:), allocatable :: out, arg
    integer :: i
    opts%decks = ""
    out = ""
    i = 2
    do while (i <= nargs)
      arg = argument(i)
      select case (arg)
      case ("--quick")
        opts%quick = .true.
        i = i + 1
      case ("-o", "--output")
        call take_value(i, out)
      case ("--decks")
        call take_value(i, opts%decks)
      case default
        call usage_error("unknown option '"//arg//"' for 'bench'")
      end select
    end do
    if (len(opts%decks) == 0) call find_bench_decks(opts%decks)
    if (len(out) == 0) out = default_output("bench")
    call run_bench(opts, out, error)
    if (allocated(error)) call fail(error)
    write (output_unit, "(a)") "davit: wrote '"//out//"'"
  end subroutine cmd_bench

  !> The bench decks' folder without --decks: input/ of the current folder (a checkout),
  !> else the DAVIT_PATH folder that holds them (the installed share/davit/input), as
  !> `davit run` finds its data files.
  subroutine find_bench_decks(decks)
    !> The bench decks' folder found (empty on entry: --decks was not given).
    character(len=:), allocatable, intent(inout) :: decks
    character(len=:), allocatable :: full, searched
    type(error_type), allocatable :: error
    logical :: found
    call find_file("input", bench_marker, full, found, searched)
    if (.not. found) then
      call fatal_error(error, "bench: no bench decks ('"//bench_marker//"') in "// &
                       searched//" (input/ here, then DAVIT_PATH); name their folder "// &
                       "with --decks DIR")
      call fail(error)
    end if
    decks = folder_of(full)
    decks = decks(1:len(decks) - 1)
  end subroutine find_bench_decks

  !> Print every deck key as a Markdown table per group (the README tables).
  subroutine cmd_keys()
    type(key_doc), allocatable :: docs(:), sweep_docs(:)
    character(len=:), allocatable :: group
    integer :: i
    if (nargs > 1) call usage_error("'keys' takes no arguments")
    call document_keys(docs)
    call document_sweep_keys(sweep_docs)
    docs = [docs, sweep_docs]
    group = ""
    do i = 1, size(docs)
      if (docs(i)%group /= group) then
        group = docs(i)%group
        if (i > 1) write (output_unit, "(a)") ""
        write (output_unit, "(a)") "#### `&"//group//"`", "", &
          "| key | default | allowed | units | meaning |", "|---|---|---|---|---|"
      end if
      write (output_unit, "(a)") "| `"//docs(i)%key//"` | "//docs(i)%default//" | "// &
        docs(i)%allowed//" | "//docs(i)%units//" | "//docs(i)%description//" |"
    end do
  end subroutine cmd_keys

  !> out/<deck name without .nml>.h5, creating out/ if needed.
  function default_output(deck) result(path)
    !> Path of the deck.
    character(len=*), intent(in) :: deck
    character(len=:), allocatable :: path, base
    integer :: slash, dot, status
    slash = index(deck, "/", back=.true.)
    base = deck(slash + 1:)
    dot = index(base, ".", back=.true.)
    if (dot > 1) base = base(1:dot - 1)
    status = c_mkdir("out"//c_null_char, int(o'755', c_int))
    path = "out/"//base//".h5"
  end function default_output

  subroutine print_help()
    write (output_unit, "(a)") &
      "davit "//davit_version//": lifeboat launch from a ship's davit in rough seas", &
      "", &
      "usage:", &
      "  davit run DECK.nml [-o OUT.h5]   run a scenario; default output out/DECK.h5", &
      "  davit rao DECK.nml [-o OUT.h5]   ship response amplitude operators (&rao, &ship)", &
      "  davit sweep SWEEP.nml [-o SUMMARY.h5] [--threads N] [--resume] [--quiet]", &
      "              [--series DIR] [--max-cases K] [--checkpoint S] [--dry-run]", &
      "              [--shard K/N]", &
      "                                   run every case of a sweep deck (&sweep) in", &
      "                                   parallel; default summary out/SWEEP.h5;", &
      "                                   --shard K/N runs only the K-th of N slices", &
      "                                   (job arrays); the MPI build (bash make.sh", &
      "                                   mpi) under mpirun -np N spreads the cases", &
      "                                   over N - 1 worker ranks", &
      "  davit sweep --merge OUT.h5 SHARD.h5...", &
      "                                   join shard summaries into one summary", &
      "  davit keys                       print every deck key (Markdown tables)", &
      "  davit modes DECK.nml             fastest rates at t = 0 and the RK4 step limit", &
      "  davit bench [--quick] [-o OUT.h5] [--decks DIR]", &
      "                                   time fixed scenes, the sea module and a small", &
      "                                   sweep on 1 and 2 threads (decks from DIR,", &
      "                                   default input/ or DAVIT_PATH); default out/bench.h5", &
      "  davit --help | -h                this help", &
      "  davit --version | -V             print the version", &
      "", &
      "exit status: 0 success, 1 bad input or failed run, 2 usage error"
  end subroutine print_help

  !> True when an argument after the subcommand is -h or --help.
  logical function asks_help(nargs)
    !> Number of command-line arguments.
    integer, intent(in) :: nargs
    integer :: i
    asks_help = .false.
    do i = 2, nargs
      if (argument(i) == "-h" .or. argument(i) == "--help") asks_help = .true.
    end do
  end function asks_help

  !> The usage of one subcommand (the general help for an unknown one).
  subroutine print_command_help(command)
    !> The subcommand.
    character(len=*), intent(in) :: command
    select case (command)
    case ("run")
      write (output_unit, "(a)") &
        "usage: davit run DECK.nml [-o OUT.h5]", &
        "  run the scenario of DECK.nml (scene = hanging_boat, lowering, launch, sea or", &
        "  ship) and write its record; default output out/DECK.h5", &
        "  -o, --output OUT.h5   the output file (written whole: a temporary, then renamed)", &
        "  data files (BEM databases) are found beside the deck, then on DAVIT_PATH"
    case ("rao")
      write (output_unit, "(a)") &
        "usage: davit rao DECK.nml [-o OUT.h5]", &
        "  the ship's response amplitude operators (&rao, &ship): one run per heading and", &
        "  frequency; default output out/DECK.h5", &
        "  -o, --output OUT.h5   the output file (written whole: a temporary, then renamed)"
    case ("sweep")
      write (output_unit, "(a)") &
        "usage: davit sweep SWEEP.nml [-o SUMMARY.h5] [options]", &
        "       davit sweep --merge OUT.h5 SHARD.h5...", &
        "  run every case of a sweep deck (&sweep) in parallel; default out/SWEEP.h5", &
        "  -o, --output SUMMARY.h5  the summary", &
        "  --threads N              OpenMP threads (default OMP_NUM_THREADS)", &
        "  --resume                 keep the finished cases of an existing summary", &
        "  --quiet                  no progress lines", &
        "  --series DIR             one time-series file per case in DIR", &
        "  --max-cases K            stop after K newly finished cases (resumable)", &
        "  --checkpoint S           rewrite the summary every S seconds (default 30)", &
        "  --dry-run                list the cases and stop", &
        "  --shard K/N              run only the K-th of N slices of the cases", &
        "  --merge OUT.h5 SHARD...  join shard summaries into one summary"
    case ("bench")
      write (output_unit, "(a)") &
        "usage: davit bench [--quick] [-o OUT.h5] [--decks DIR]", &
        "  time fixed scenes, the sea module, a small sweep on 1 and 2 threads and an", &
        "  operability study; decks from DIR (default input/ or DAVIT_PATH); default", &
        "  output out/bench.h5; --quick: short runs that check the bench itself"
    case ("keys")
      write (output_unit, "(a)") "usage: davit keys", &
        "  print every deck key: group, default, allowed range, units, meaning (Markdown)"
    case ("modes")
      write (output_unit, "(a)") "usage: davit modes DECK.nml", &
        "  the fastest rates of the deck's system linearised at t = 0 and RK4's step limit"
    case default
      call print_help()
    end select
  end subroutine print_command_help

  function argument(i) result(arg)
    !> Index of the argument.
    integer, intent(in) :: i
    character(len=:), allocatable :: arg
    integer :: n
    call get_command_argument(i, length=n)
    allocate (character(len=n) :: arg)
    if (n > 0) call get_command_argument(i, arg)
  end function argument

  subroutine usage_error(message)
    !> What is wrong with the command line.
    character(len=*), intent(in) :: message
    write (error_unit, "(a)") "davit: error: "//message, &
      "usage: davit run|rao DECK.nml [-o OUT.h5] | davit sweep SWEEP.nml [options] | "// &
      "davit keys | davit bench [--quick] [-o OUT.h5] | davit --help | davit --version"
    stop 2, quiet=.true.
  end subroutine usage_error

  subroutine fail(error)
    !> The error, printed before the exit.
    type(error_type), intent(in) :: error
    flush (output_unit)
    write (error_unit, "(a)") "davit: error: "//error%message
    flush (error_unit)
    stop 1, quiet=.true.
  end subroutine fail

end program davit
