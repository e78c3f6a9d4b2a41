!> `davit bench [--quick]`: a fixed set of timings, from decks in the decks folder:
!> (1) the default scene in a regular sea, (2) the same in the irregular sea, (3) the
!> paper-literal level of detail (2 lumps per sling, rotating sheaves) with RK4 at its
!> stability limit, each on one thread; (4) the sea module alone; (5) a small sweep on 1
!> and 2 OpenMP threads and its speed-up. Printed as tables and written under /bench.
!> Speed goals live in the README, never in tests; --quick only shortens the runs.
module davit_bench_suite
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_sweep_keys, only: sweep_config
  use davit_bench_timing, only: timed_run
  use davit_bench_sea, only: bench_sea
  use davit_bench_scenes, only: time_deck, rk4_bound, safety_factor
  use davit_bench_sweep, only: read_bench_sweep, time_sweep
  use davit_bench_study, only: study_result, time_study
  use davit_bench_report, only: bench_record, new_bench_record, load_average, print_report, &
                                print_progress, write_report
  implicit none
  private
  public :: bench_options, run_bench

  type :: bench_options
    !> Short runs (~10 s in all): a smoke test of the bench, not figures to quote.
    logical :: quick = .false.
    !> Folder of the bench decks.
    character(len=:), allocatable :: decks
  end type bench_options

  !> An integrator override: the integrator ("" keeps the deck's) with its tolerances, largest
  !> step and fast substeps.
  type :: method_spec
    !> Integrator override ("" keeps the deck's).
    character(len=16) :: integrator = ""
    !> Relative and absolute tolerances and largest step dt [s] of the override.
    real(wp) :: rtol = 0.0_wp, atol = 0.0_wp, dt = 0.0_wp
    !> Fast substeps of a multirate method (0: the deck's).
    integer :: substeps = 0
  end type method_spec

  !> A variant the three seas are run in: the suffix of the scene's label, the deck's suffix
  !> ("_fast": the fast level of detail) and the method.
  type :: variant_spec
    !> Suffix of the scene's label and of its deck's name.
    character(len=12) :: suffix, deck_suffix = ""
    !> The integrator override.
    type(method_spec) :: method = method_spec()
  end type variant_spec

  !> A scene: label, deck (in the decks folder), simulated time of the full and of the
  !> quick bench [s] (0: the deck's own, i.e. the whole launch to hook release + 5 s), step
  !> at the RK4 stability limit or the deck's, the reference group it is measured against
  !> (bench_reference.h5) and an integrator override (method_spec).
  type :: scene_spec
    !> Label of the scene.
    character(len=32) :: name
    !> Deck file name in the decks folder.
    character(len=48) :: deck
    !> Simulated time of the full and of the quick bench [s] (0: the deck's own).
    real(wp) :: t_full, t_quick
    !> Whether to run at the RK4 stability limit.
    logical :: at_limit
    !> Group of the converged reference (bench_reference.h5).
    character(len=16) :: reference
    !> Integrator override (the default keeps the deck's).
    type(method_spec) :: method = method_spec()
  end type scene_spec

  !> The seas of the default level of detail: each the label of its reference and its deck.
  character(len=*), parameter :: seas(3) = [character(len=16) :: "regular", "irregular", &
                                            "irregular_single"]
  character(len=*), parameter :: sea_decks(3) = [character(len=32) :: "iiib_level5_090", &
                                                 "iiib_level5_090_irregular", &
                                                 "iiib_level5_090_irregular_single"]
  type(method_spec), parameter :: rosw_tight = method_spec("rosw", 1.0e-4_wp, 1.0e-5_wp, 0.02_wp)
  type(variant_spec), parameter :: plain = variant_spec(""), fast = variant_spec("_fast", "_fast")
  type(variant_spec), parameter :: rosw = variant_spec("_rosw", "", rosw_tight)
  type(variant_spec), parameter :: multirate = &
    variant_spec("_multirate", "", method_spec("multirate", 1.0e-4_wp, 1.0e-5_wp, 0.02_wp))
  type(variant_spec), parameter :: mri2 = &
    variant_spec("_mri2", "", method_spec("mri2", 1.0e-4_wp, 1.0e-5_wp, 0.01_wp, 5))
  type(variant_spec), parameter :: mri2b = &
    variant_spec("_mri2b", "", method_spec("mri2b", 1.0e-4_wp, 1.0e-5_wp, 0.01_wp, 5))
  !> The paper-literal level of detail, 20 s at most (its explicit step is 13x smaller).
  type(scene_spec), parameter :: literal_scenes(3) = [ &
    scene_spec("paper_literal", "iiib_level5_090_literal.nml", 20.0_wp, 2.0_wp, .true., &
               "paper_literal"), &
    scene_spec("paper_literal_rosw", "iiib_level5_090_literal.nml", 20.0_wp, 2.0_wp, &
               .false., "paper_literal", rosw_tight), &
    scene_spec("paper_literal_rosw_loose", "iiib_level5_090_literal.nml", 20.0_wp, 2.0_wp, &
               .false., "paper_literal", method_spec("rosw", 3.0e-3_wp, 3.0e-4_wp, 0.02_wp))]

  !> The scenes' converged references (davit_bench_accuracy), in the decks folder.
  character(len=*), parameter :: reference_file = "bench_reference.h5"
  !> The sweep deck; full: whole launches (each to its hook release), quick: 10 s each.
  character(len=*), parameter :: sweep_deck = "bench_sweep.nml"
  real(wp), parameter :: sweep_t_quick = 10.0_wp
  !> The study-level row: an adaptive operability sweep run until its cells converge, on
  !> 2 threads (quick: 5 s launches).
  character(len=*), parameter :: study_deck = "bench_operability.nml"
  real(wp), parameter :: study_t_quick = 5.0_wp
  integer, parameter :: study_threads = 2
  integer, parameter :: sweep_threads(2) = [1, 2]
  !> Seconds each sea-module timing repeats its kernel.
  real(wp), parameter :: sea_budget_full = 0.5_wp, sea_budget_quick = 0.05_wp

contains

  !> Run every benchmark, print the tables on stdout (progress on stderr) and write
  !> `out_path`. The file is created first, so an unwritable path fails before any run.
  subroutine run_bench(opts, out_path, error)
    !> Bench options (quick, decks folder).
    type(bench_options), intent(in) :: opts
    !> Path of the HDF5 file written.
    character(len=*), intent(in) :: out_path
    !> Set when the file cannot be written or a benchmark fails.
    type(error_type), allocatable, intent(out) :: error
    type(bench_record) :: rec
    type(h5_writer_type) :: w
    call w%create(out_path, error)
    if (allocated(error)) return
    rec = new_bench_record(opts%quick, opts%decks)
    call bench_scenes(opts, rec, error)
    if (.not. allocated(error)) call bench_sweep(opts, rec, error)
    if (.not. allocated(error)) call bench_study(opts, out_path, rec, error)
    if (allocated(error)) then
      call w%discard()
      return
    end if
    call bench_sea(merge(sea_budget_quick, sea_budget_full, opts%quick), rec%sea)
    rec%load_end = load_average()
    call print_report(output_unit, rec)
    call write_report(w, rec)
    call w%close(error)
  end subroutine run_bench

  subroutine bench_scenes(opts, rec, error)
    !> Bench options.
    type(bench_options), intent(in) :: opts
    !> What the bench measured, extended with the scenes' rows.
    type(bench_record), intent(inout) :: rec
    !> Set when a scene fails.
    type(error_type), allocatable, intent(out) :: error
    type(timed_run) :: run
    type(scene_spec) :: sc
    type(scene_spec), allocatable :: scenes(:)
    real(wp) :: rate_max
    character(len=:), allocatable :: reference
    integer :: i
    ! a quick run's shortened scenes have no reference to be measured against
    reference = opts%decks//"/"//reference_file
    if (opts%quick) reference = ""
    scenes = bench_scene_list()
    do i = 1, size(scenes)
      sc = scenes(i)
      call time_deck(trim(sc%name), opts%decks//"/"//trim(sc%deck), &
                     merge(sc%t_quick, sc%t_full, opts%quick), sc%at_limit, &
                     reference, trim(sc%reference), trim(sc%method%integrator), &
                     sc%method%rtol, sc%method%atol, sc%method%dt, run, rate_max, error, &
                     sc%method%substeps)
      if (allocated(error)) return
      if (sc%at_limit) then
        rec%rate_max = rate_max
        rec%rk4_limit = rk4_bound/rate_max
        rec%safety = safety_factor
      end if
      call print_progress(error_unit, run)
      rec%runs = [rec%runs, run]
    end do
  end subroutine bench_scenes

  !> The bench's scenes in the order they run and print.
  !> The default level of detail (RK4 1e-3 s, massive blocks, events located) in the
  !> regular and irregular seas; the same scenes with the Rosenbrock-W method (the
  !> rigging implicit) and with the fast level of detail (quasi-static blocks, RK4 1e-2
  !> s); the paper-literal level of detail (2 lumps per sling, rotating sheaves) at RK4's
  !> stability limit and with the Rosenbrock-W method (rtol 1e-4, and 3e-3 as
  !> `paper_literal_rosw_loose`), 20 s (its explicit step is 13x smaller). Quick: the
  !> start of each.
  !> The single-summation sea (100 components, one direction per frequency, instead of
  !> 100 x 13) at the default level of detail, with Rosenbrock-W, and at the fast level
  !> for irregular sweeps (quasi-static blocks, Rosenbrock-W), measured against the
  !> converged reference of that sea. The multirate method (MIS: the ship, the boat's
  !> water and wind once per 0.02 s stage, the rigging, hooks and fenders in 10 RK4
  !> substeps) in the regular and single-summation seas; its chained variant mri2 (one
  !> fast sweep per step) at 0.01 s steps with 5 substeps (run as 3 + 3) in the regular
  !> sea and both irregular ones (the Figs. 20-23 sweeps' integrator), and mri2b (one
  !> fast sweep of exactly 5 substeps of 2e-3 s per 0.01 s step) in the same three.
  pure function bench_scene_list() result(list)
    type(scene_spec), allocatable :: list(:)
    integer :: i
    list = [(on_sea(i, plain), on_sea(i, rosw), on_sea(i, fast), i = 1, size(seas))]
    list = [list, on_sea(1, multirate), on_sea(3, multirate)]
    list = [list, [(on_sea(i, mri2), i = 1, size(seas))]]
    list = [list, [(on_sea(i, mri2b), i = 1, size(seas))]]
    list = [list, literal_scenes]
  end function bench_scene_list

  !> Sea `i` run in variant `v`: the whole launch in the full bench, 20 s in the quick one,
  !> measured against the sea's reference.
  pure type(scene_spec) function on_sea(i, v) result(sc)
    integer, intent(in) :: i
    type(variant_spec), intent(in) :: v
    sc = scene_spec(trim(seas(i))//trim(v%suffix), trim(sea_decks(i))//trim(v%deck_suffix)// &
                    ".nml", 0.0_wp, 20.0_wp, .false., seas(i), v%method)
  end function on_sea

  subroutine bench_sweep(opts, rec, error)
    !> Bench options.
    type(bench_options), intent(in) :: opts
    !> What the bench measured, extended with the sweep's rows and speed-up.
    type(bench_record), intent(inout) :: rec
    !> Set when the sweep fails.
    type(error_type), allocatable, intent(out) :: error
    type(sweep_config) :: s
    type(timed_run) :: runs(size(sweep_threads))
    integer :: i
    call read_bench_sweep(opts%decks//"/"//sweep_deck, merge(sweep_t_quick, 0.0_wp, &
                          opts%quick), s, error)
    if (allocated(error)) return
    do i = 1, size(sweep_threads)
      call time_sweep("sweep", s, sweep_threads(i), runs(i), error)
      if (allocated(error)) return
      call print_progress(error_unit, runs(i))
    end do
    rec%runs = [rec%runs, runs]
    rec%sweep_cases = runs(1)%cases
    rec%speed_up = runs(1)%wall/max(runs(2)%wall, 1.0e-9_wp)
  end subroutine bench_sweep

  !> The operability study: its wall time to converge and how many cells it decided.
  subroutine bench_study(opts, out_path, rec, error)
    !> Bench options.
    type(bench_options), intent(in) :: opts
    !> Path of the HDF5 file written (the scratch summary is this path + ".study.h5").
    character(len=*), intent(in) :: out_path
    !> What the bench measured, extended with the study's row.
    type(bench_record), intent(inout) :: rec
    !> Set when the study fails.
    type(error_type), allocatable, intent(out) :: error
    type(sweep_config) :: s
    type(timed_run) :: run
    type(study_result) :: study
    call read_bench_sweep(opts%decks//"/"//study_deck, merge(study_t_quick, 0.0_wp, &
                          opts%quick), s, error)
    if (allocated(error)) return
    call time_study("operability", s, study_threads, out_path//".study.h5", run, study, error)
    if (allocated(error)) return
    call print_progress(error_unit, run)
    rec%runs = [rec%runs, run]
    rec%study_cells = study%cells
    rec%study_decided = study%decided
  end subroutine bench_study

end module davit_bench_suite
