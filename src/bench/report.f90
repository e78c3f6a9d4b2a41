!> `davit bench`: what one bench measured and the conditions it ran under (CPU, compiler,
!> flags, load), printed as Markdown tables and written to HDF5 under /bench. Rates are
!> derived from the stored counts and times (davit_bench_timing) in both.
module davit_bench_report
  use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options
  use davit_kinds, only: wp, i8, davit_version
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_io_text, only: int_text
  use davit_bench_timing, only: timed_run, per_wall
  use davit_bench_sea, only: bench_result
  implicit none
  private
  public :: bench_record, new_bench_record, load_average, print_report, print_progress
  public :: write_report

  !> Everything one `davit bench` measured.
  type :: bench_record
    !> Whether this is the quick bench (shorter runs).
    logical :: quick = .false.
    !> Folder of the decks, CPU model, compiler and its options.
    character(len=:), allocatable :: decks, cpu, compiler, options
    !> One-minute load average of the machine before and after (other jobs' share).
    real(wp) :: load_start = -1.0_wp, load_end = -1.0_wp
    !> Scenes (one thread) and the sweep on each thread count.
    type(timed_run), allocatable :: runs(:)
    !> The sweep row: cases, and wall time on 1 thread / wall time on 2 threads.
    integer :: sweep_cases = 0
    !> Wall time of the sweep on 1 thread over that on 2 threads.
    real(wp) :: speed_up = 0.0_wp
    !> Paper-literal scene: |lambda|max at t = 0 [1/s], RK4 limit [s], safety factor.
    real(wp) :: rate_max = 0.0_wp, rk4_limit = 0.0_wp, safety = 0.0_wp
    !> The sea module alone.
    type(bench_result), allocatable :: sea(:)
    !> The operability study: its cells and how many it decided (its row is in runs).
    integer :: study_cells = 0, study_decided = 0
  end type bench_record

contains

  !> An empty record of the conditions this bench runs under.
  function new_bench_record(quick, decks) result(rec)
    !> Whether this is the quick bench.
    logical, intent(in) :: quick
    !> Folder of the decks.
    character(len=*), intent(in) :: decks
    type(bench_record) :: rec
    rec%quick = quick
    rec%decks = decks
    rec%cpu = cpu_model()
    rec%compiler = compiler_version()
    rec%options = compiler_options()
    rec%load_start = load_average()
    allocate (rec%runs(0), rec%sea(0))
  end function new_bench_record

  !> The one-minute load average (/proc/loadavg), or -1 where there is none: timings
  !> taken beside other jobs are marked as such.
  real(wp) function load_average() result(load)
    integer :: unit, ios
    load = -1.0_wp
    open (newunit=unit, file="/proc/loadavg", status="old", action="read", iostat=ios)
    if (ios /= 0) return
    read (unit, *, iostat=ios) load
    if (ios /= 0) load = -1.0_wp
    close (unit)
  end function load_average

  !> The first "model name" of /proc/cpuinfo, or "unknown".
  function cpu_model() result(name)
    character(len=:), allocatable :: name
    character(len=512) :: line
    integer :: unit, ios, colon
    name = "unknown"
    open (newunit=unit, file="/proc/cpuinfo", status="old", action="read", iostat=ios)
    if (ios /= 0) return
    do
      read (unit, "(a)", iostat=ios) line
      if (ios /= 0) exit
      colon = index(line, ":")
      if (index(line, "model name") == 1 .and. colon > 0) then
        name = trim(adjustl(line(colon + 1:)))
        exit
      end if
    end do
    close (unit)
  end function cpu_model

  !> The tables: runs (rates and real-time factors), the sweep's speed-up, the
  !> paper-literal step, the sea module.
  subroutine print_report(unit, rec)
    !> Output unit of the tables.
    integer, intent(in) :: unit
    !> What the bench measured.
    type(bench_record), intent(in) :: rec
    integer :: i
    write (unit, "(a)") "davit bench ("//trim(merge("quick", "full ", rec%quick))//"): "// &
      rec%cpu//", "//rec%compiler//", load average "//sig(rec%load_start)//" -> "// &
      sig(rec%load_end), "", &
      "| benchmark | deck | threads | dt [s] | simulated [s] | wall [s] | steps | "// &
      "RHS evaluations | RHS/s | steps/s | real-time factor | set-up [s] | worst step / "// &
      "output interval [ms] | CG error before / after "// &
      "first contact [m] | peak sling / segment tension error |", &
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    do i = 1, size(rec%runs)
      associate (r => rec%runs(i))
        write (unit, "(a)") "| "//r%name//" | "//r%deck//" | "//int_text(int(r%threads, i8))// &
          " | "//sig(r%dt)//" | "//sig(r%simulated)//" | "//sig(r%wall)//" | "// &
          int_text(r%steps)//" | "//int_text(r%rhs_evaluations)//" | "// &
          sig(per_wall(r, real(r%rhs_evaluations, wp)))//" | "// &
          sig(per_wall(r, real(r%steps, wp)))//" | "//sig(per_wall(r, r%simulated))//" | "// &
          worst_text(r)//" | "//accuracy_text(r)//" |"
      end associate
    end do
    write (unit, "(a)") "", "Errors against each scene's converged reference ("// &
      "bench_reference.h5 in the decks folder; n/a without one or with --quick)."
    write (unit, "(a)") "", "operability study: "//int_text(int(rec%study_decided, i8))// &
      " of "//int_text(int(rec%study_cells, i8))//" cells decided (Wilson 95 %, risk 5 %) "// &
      "in the 'operability' row's wall time"
    write (unit, "(a)") "", "sweep speed-up, 1 -> 2 threads: "//sig(rec%speed_up)//" ("// &
      int_text(int(rec%sweep_cases, i8))//" cases)", &
      "paper-literal step: "//sig(rec%safety)//" x RK4 limit 2.83/|lambda|max = "// &
      sig(rec%safety*rec%rk4_limit)//" s (|lambda|max = "//sig(rec%rate_max)// &
      " 1/s at t = 0), rounded down to a whole fraction of the output interval", "", &
      "| sea module | value | unit |", "|---|---|---|"
    do i = 1, size(rec%sea)
      write (unit, "(a)") "| "//rec%sea(i)%name//" | "//sig(rec%sea(i)%value)//" | "// &
        rec%sea(i)%unit//" |"
    end do
  end subroutine print_report

  !> "0.031 | 0.85 / 2.1": set-up [s] and worst step / output interval [ms] of a scene;
  !> n/a for a sweep (timed as a whole).
  function worst_text(r) result(s)
    !> A timed run.
    type(timed_run), intent(in) :: r
    character(len=:), allocatable :: s
    if (r%cases > 1 .or. r%worst_step <= 0.0_wp) then
      s = "n/a | n/a"
      return
    end if
    s = sig(r%setup)//" | "//sig(1e3_wp*r%worst_step)//" / "//sig(1e3_wp*r%worst_interval)
  end function worst_text

  !> "2.1e-05 / 3.4e-03 | 0.2 % / 12 %", or n/a.
  function accuracy_text(r) result(s)
    !> A timed run, with its accuracy.
    type(timed_run), intent(in) :: r
    character(len=:), allocatable :: s
    if (.not. r%accuracy%known) then
      s = "n/a | n/a"
      return
    end if
    s = sig(r%accuracy%cg_before)//" / "//sig(r%accuracy%cg_after)//" | "// &
        sig(100.0_wp*r%accuracy%sling)//" % / "//sig(100.0_wp*r%accuracy%segment)//" %"
  end function accuracy_text

  !> "davit bench: regular, 1 thread: 100 s simulated in 2.31 s (43.3x real time)"
  subroutine print_progress(unit, run)
    !> Output unit of the progress line.
    integer, intent(in) :: unit
    !> The run just timed.
    type(timed_run), intent(in) :: run
    write (unit, "(a)") "davit bench: "//run%name//", "//int_text(int(run%threads, i8))// &
      " thread(s): "//sig(run%simulated)//" s simulated in "//sig(run%wall)//" s ("// &
      sig(per_wall(run, run%simulated))//"x real time)"
    flush (unit)
  end subroutine print_progress

  !> Write `rec` under /bench (runs, sweep, paper_literal, sea) of the open file `w`, with
  !> the conditions as root attributes.
  subroutine write_report(w, rec)
    !> The open HDF5 file written.
    type(h5_writer_type), intent(inout) :: w
    !> What the bench measured.
    type(bench_record), intent(in) :: rec
    call w%group("bench")
    call write_runs(w, rec%runs)
    call w%group("bench/sweep")
    call w%write_1d("bench/sweep/speed_up", [rec%speed_up], "-", &
                    "Wall time of the sweep on 1 thread / on 2 threads", dims="scalar")
    call w%group("bench/study")
    call w%write_1d_int("bench/study/cells", [int(rec%study_cells, i8)], "-", &
                        "Cells of the operability study (the 'operability' run)", dims="scalar")
    call w%write_1d_int("bench/study/decided", [int(rec%study_decided, i8)], "-", &
                        "Cells decided at risk 5 % (Wilson 95 % bound on the collision "// &
                        "probability <= 0.05 or lower bound > 0.05)", dims="scalar")
    call w%group("bench/paper_literal")
    call w%write_1d("bench/paper_literal/rate_max", [rec%rate_max], "1/s", &
                    "Largest |eigenvalue| of df/dy at t = 0 (davit modes)", dims="scalar")
    call w%write_1d("bench/paper_literal/rk4_limit", [rec%rk4_limit], "s", &
                    "RK4 stability limit 2.83/rate_max", dims="scalar")
    call w%write_1d("bench/paper_literal/safety_factor", [rec%safety], "-", &
                    "Step = safety_factor x rk4_limit, rounded down to a whole fraction "// &
                    "of the output interval", dims="scalar")
    call write_sea(w, rec%sea)
    call write_attributes(w, rec)
  end subroutine write_report

  subroutine write_runs(w, runs)
    !> The open HDF5 file written.
    type(h5_writer_type), intent(inout) :: w
    !> The timed runs.
    type(timed_run), intent(in) :: runs(:)
    character(len=:), allocatable :: names(:), decks(:)
    integer :: i
    call w%group("bench/runs")
    allocate (character(len=maxval([(len(runs(i)%name), i = 1, size(runs)), 1])) :: &
              names(size(runs)))
    allocate (character(len=maxval([(len(runs(i)%deck), i = 1, size(runs)), 1])) :: &
              decks(size(runs)))
    do i = 1, size(runs)
      names(i) = runs(i)%name
      decks(i) = runs(i)%deck
    end do
    call w%write_strings("bench/runs/name", names, "-", "Benchmark: a scene (regular, "// &
                         "irregular, paper_literal) or the sweep", dims="run")
    call w%write_strings("bench/runs/deck", decks, "-", "Deck run (a sweep deck for sweep)", &
                         dims="run")
    call w%write_1d_int("bench/runs/cases", int(runs%cases, i8), "-", &
                        "Runs timed together: 1 for a scene, the sweep's cases", dims="run")
    call w%write_1d_int("bench/runs/threads", int(runs%threads, i8), "-", "OpenMP threads", &
                        dims="run")
    call w%write_1d("bench/runs/dt", runs%dt, "s", "Time step (near contact dt_contact)", &
                    dims="run")
    call w%write_1d("bench/runs/simulated_time", runs%simulated, "s", &
                    "Simulated time (summed over a sweep's cases)", dims="run")
    call w%write_1d("bench/runs/wall_time", runs%wall, "s", "Wall time: a scene's time "// &
                    "loop, or a sweep's whole parallel loop", dims="run")
    call w%write_1d_int("bench/runs/steps", runs%steps, "-", "Integrator steps (summed)", &
                        dims="run")
    call w%write_1d_int("bench/runs/rhs_evaluations", runs%rhs_evaluations, "-", &
                        "Right-hand-side evaluations (summed)", dims="run")
    call w%write_1d("bench/runs/rhs_per_second", &
                    per_wall(runs, real(runs%rhs_evaluations, wp)), &
                    "1/s", "rhs_evaluations / wall_time", dims="run")
    call w%write_1d("bench/runs/setup_time", runs%setup, "s", "A scene's set-up wall "// &
                    "time: deck read, system built (BEM databases, sea, rigging); 0 for "// &
                    "sweeps", dims="run")
    call w%write_1d("bench/runs/worst_step_wall_time", runs%worst_step, "s", "Longest "// &
                    "wall time of one step of a scene (what a real-time user meets); 0 "// &
                    "for sweeps", dims="run")
    call w%write_1d("bench/runs/worst_interval_wall_time", runs%worst_interval, "s", &
                    "Longest wall time of one output interval of a scene (a frame of a "// &
                    "live display); 0 for sweeps", dims="run")
    call w%write_1d("bench/runs/steps_per_second", per_wall(runs, real(runs%steps, wp)), &
                    "1/s", "steps / wall_time", dims="run")
    call w%write_1d("bench/runs/real_time_factor", per_wall(runs, runs%simulated), "-", &
                    "simulated_time / wall_time", dims="run")
    call w%write_1d_int("bench/runs/accuracy_known", &
                        [(merge(1_i8, 0_i8, runs(i)%accuracy%known), i = 1, size(runs))], &
                        "-", "1 where the run was compared with a converged reference "// &
                        "(the error columns are 0 otherwise)", dims="run")
    call w%write_1d("bench/runs/cg_error_before_contact", runs%accuracy%cg_before, "m", &
                    "Largest boat CG distance from the reference before its first contact", &
                    dims="run")
    call w%write_1d("bench/runs/cg_error_after_contact", runs%accuracy%cg_after, "m", &
                    "Largest boat CG distance from the reference after its first contact", &
                    dims="run")
    call w%write_1d("bench/runs/peak_sling_tension_error", runs%accuracy%sling, "-", &
                    "Largest relative error of a sling's resolved peak tension", dims="run")
    call w%write_1d("bench/runs/peak_segment_tension_error", runs%accuracy%segment, "-", &
                    "Largest relative error of a cable segment's resolved peak tension", dims="run")
  end subroutine write_runs

  subroutine write_sea(w, sea)
    !> The open HDF5 file written.
    type(h5_writer_type), intent(inout) :: w
    !> The sea module's timings.
    type(bench_result), intent(in) :: sea(:)
    character(len=64) :: names(size(sea)), units(size(sea))
    integer :: i
    do i = 1, size(sea)
      names(i) = sea(i)%name
      units(i) = sea(i)%unit
    end do
    call w%group("bench/sea")
    call w%write_strings("bench/sea/name", names, "-", "Sea-module timing", dims="sea_timing")
    call w%write_1d("bench/sea/value", sea%value, "see bench/sea/unit", "Cost", dims="sea_timing")
    call w%write_strings("bench/sea/unit", units, "-", "Unit of each value", dims="sea_timing")
  end subroutine write_sea

  subroutine write_attributes(w, rec)
    !> The open HDF5 file written.
    type(h5_writer_type), intent(inout) :: w
    !> What the bench measured (its conditions).
    type(bench_record), intent(in) :: rec
    call w%attr_str("/", "davit_version", davit_version)
    call w%attr_int("/", "quick", merge(1_i8, 0_i8, rec%quick))
    call w%attr_str("/", "decks", rec%decks)
    call w%attr_str("/", "cpu", rec%cpu)
    call w%attr_str("/", "compiler", rec%compiler)
    call w%attr_str("/", "compiler_options", rec%options)
    call w%attr_real("/", "load_average_start", rec%load_start)
    call w%attr_real("/", "load_average_end", rec%load_end)
  end subroutine write_attributes

  !> Three significant digits: fixed-point from 0.01 to 1e6, else scientific.
  function sig(x) result(s)
    !> Value to format.
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    character(len=16) :: form
    integer :: decimals
    if (x /= 0.0_wp .and. (abs(x) < 0.01_wp .or. abs(x) >= 1.0e6_wp)) then
      write (buf, "(es10.2)") x
    else
      decimals = 0
      if (x /= 0.0_wp) decimals = max(0, 2 - floor(log10(abs(x))))
      write (form, "(a,i0,a)") "(f0.", decimals, ")"
      write (buf, form) x
    end if
    s = trim(adjustl(buf))
    if (s(1:1) == ".") s = "0"//s
    if (s(len(s):len(s)) == ".") s = s(1:len(s) - 1)
  end function sig

end module davit_bench_report
