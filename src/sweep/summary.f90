!> The sweep summary file: one row per case (1-D datasets of length ncase), the case inputs
!> under /cases and the results under /results, every dataset with `units` and
!> `description`. It is always written whole (under SUMMARY.h5.tmp, then renamed), at the
!> start, at checkpoints and at the end, so an interrupted sweep leaves a valid summary in
!> which the unfinished cases have status 0. postproc/layout.py holds the same names.
!> HDF5 is not thread-safe here: call these from one thread at a time.
module davit_sweep_summary
  use davit_kinds, only: wp, i8, davit_version
  use davit_error, only: error_type
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_metrics, only: case_result, status_not_run
  use davit_assess_rules, only: n_checks, check_ids, check_units, check_texts, check_sources
  use davit_sweep_shards, only: shard_spec
  use davit_sweep_result_columns, only: column_doc, result_columns, nreal_fields, &
                                        real_fields, case_columns, n_case_columns, case_fields
  use davit_sweep_summary_reader, only: read_results, read_summary
  implicit none
  private
  public :: write_summary
  ! reading lives in davit_sweep_summary_reader; kept public here for the summary's users
  public :: read_results, read_summary

  character(len=*), parameter :: wave_type_codes = "0 calm, 1 airy (regular, linear), "// &
                                                   "2 stokes2 (regular), 3 irregular"
  character(len=*), parameter :: defined = " (status 1 only; NaN otherwise)"

contains

  !> Write the whole summary to `path` (atomically: `path.tmp`, then renamed). A shard's
  !> summary (shard%count > 0) also records shard_index and shard_count.
  subroutine write_summary(path, s, cases, results, threads, series_dir, shard, error)
    !> Path of the summary file; the series folder recorded ("" for none).
    character(len=*), intent(in) :: path, series_dir
    !> The sweep deck.
    type(sweep_config), intent(in) :: s
    !> The cases of the sweep.
    type(sweep_case), intent(in) :: cases(:)
    !> One row per case.
    type(case_result), intent(in) :: results(:)
    !> Threads (or MPI ranks) recorded.
    integer, intent(in) :: threads
    !> The shard this summary holds (count 0: the whole sweep).
    type(shard_spec), intent(in) :: shard
    !> Set when the file cannot be written.
    type(error_type), allocatable, intent(out) :: error
    type(h5_writer_type) :: w
    call w%create(path, error)
    if (allocated(error)) return
    call write_cases(w, cases)
    call write_results(w, results)
    call w%attr_str("/", "davit_version", davit_version)
    call w%attr_str("/", "sweep_file", s%filename)
    call w%attr_str("/", "sweep_namelist", s%deck_text)
    call w%attr_str("/", "base_deck", s%base_deck)
    call w%attr_str("/", "base_namelist", s%base%deck_text)
    call w%attr_int("/", "ncase", int(size(cases), i8))
    call w%attr_int("/", "threads", int(threads, i8))
    call w%attr_int("/", "complete", merge(1_i8, 0_i8, all(results%status /= status_not_run)))
    call w%attr_str("/", "series_dir", series_dir)
    call w%attr_real("/", "target_halfwidth", s%target_halfwidth)
    call w%attr_int("/", "max_realisations", int(s%max_realisations, i8))
    call w%attr_int("/", "realisation_batch", int(s%realisation_batch, i8))
    if (shard%count > 0) then
      call w%attr_int("/", "shard_index", int(shard%index, i8))
      call w%attr_int("/", "shard_count", int(shard%count, i8))
    end if
    call w%close(error)
  end subroutine write_summary

  subroutine write_cases(w, cases)
    type(h5_writer_type), intent(inout) :: w
    type(sweep_case), intent(in) :: cases(:)
    ! each column through an allocatable (heap): an expression or a component of the rows
    ! passed as the argument would be a temporary on the stack, as long as the sweep
    integer(i8), allocatable :: icol(:)
    call w%group("cases")
    icol = int(cases%index, i8)
    call w%write_1d_int("cases/index", icol, "-", "Case number, 1-based", &
                        dims="case")
    icol = int(cases%realisation, i8)
    call w%write_1d_int("cases/realisation", icol, "-", &
                        "Realisation of the combination of the other inputs, 1-based", dims="case")
    icol = int(cases%seed, i8)
    call w%write_1d_int("cases/seed", icol, "-", "Random seed of the case "// &
                        "(SplitMix64 of the base seed and the case index, top 31 bits)", &
                        dims="case")
    icol = int(cases%level, i8)
    call w%write_1d_int("cases/level", icol, "-", &
                        "Sea-state level (3-5: the wave height and wind presets)", dims="case")
    icol = int(cases%wave_type, i8)
    call w%write_1d_int("cases/wave_type", icol, "-", &
                        "Wave type: "//wave_type_codes, dims="case")
    call w%attr_str("cases/wave_type", "codes", wave_type_codes)
    icol = merge(1_i8, 0_i8, cases%wind)
    call w%write_1d_int("cases/wind", icol, "-", &
                        "1 = wind on (along the waves), 0 = no wind", dims="case")
    call write_columns(w, "cases", case_columns, case_matrix(cases))
  end subroutine write_cases

  subroutine write_results(w, r)
    type(h5_writer_type), intent(inout) :: w
    type(case_result), intent(in) :: r(:)
    ! each column through an allocatable (heap): an expression or a component of the rows
    ! passed as the argument would be a temporary on the stack, as long as the sweep
    integer(i8), allocatable :: icol(:)
    character(len=:), allocatable :: texts(:)
    call w%group("results")
    icol = int(r%status, i8)
    call w%write_1d_int("results/status", icol, "-", &
                        "0 not run, 1 ok, 2 failed (see message), 3 not needed "// &
                        "(adaptive realisations: its cell converged; see message)", dims="case")
    texts = text_column(r, "message")
    call w%write_strings("results/message", texts, "-", &
                         "'ok', the error of a failed case, why it was not needed, or "// &
                         "empty when not run", dims="case")
    icol = int(r%collided, i8)
    call w%write_1d_int("results/collided", icol, "-", &
                        "1 if min_clearance < 0 (a fender touched the ship), else 0; -1 "// &
                        "if not status 1", dims="case")
    icol = int(r%impacts, i8)
    call w%write_1d_int("results/impacts", icol, "-", "Separate contact "// &
                        "episodes over the lowering; -1 if not status 1", dims="case")
    texts = text_column(r, "outcome")
    call w%write_strings("results/outcome", texts, "-", "How the "// &
                         "launch ended: released, waterborne, or not waterborne and why; "// &
                         "empty if not run", dims="case")
    call write_real_columns(w, r)
    icol = r%steps
    call w%write_1d_int("results/steps", icol, "-", "Integrator steps", dims="case")
    icol = r%rhs_evaluations
    call w%write_1d_int("results/rhs_evaluations", icol, "-", &
                        "Right-hand-side evaluations of the integrator", dims="case")
  end subroutine write_results

  !> The real columns of davit_sweep_result_columns, each row's reals taken once, then the
  !> rule checks.
  subroutine write_real_columns(w, r)
    type(h5_writer_type), intent(inout) :: w
    type(case_result), intent(in) :: r(:)
    real(wp), allocatable :: x(:, :)
    integer :: i
    allocate (x(nreal_fields, size(r)))
    do i = 1, size(r)
      x(:, i) = real_fields(r(i))
    end do
    call write_columns(w, "results", result_columns, x)
    call write_check_columns(w, r)
  end subroutine write_real_columns

  !> The columns of `table` under `group`, column k from row k of x (case, along the rows).
  subroutine write_columns(w, group, table, x)
    type(h5_writer_type), intent(inout) :: w
    character(len=*), intent(in) :: group
    type(column_doc), intent(in) :: table(:)
    real(wp), intent(in) :: x(:, :)
    ! each column through an allocatable (heap), as long as the sweep
    real(wp), allocatable :: col(:)
    integer :: k
    do k = 1, size(table)
      col = x(k, :)
      call w%write_1d(group//"/"//trim(table(k)%name), col, trim(table(k)%units), &
                      trim(table(k)%text), dims="case")
    end do
  end subroutine write_columns

  !> The cases' reals, one column per case.
  function case_matrix(cases) result(x)
    type(sweep_case), intent(in) :: cases(:)
    real(wp), allocatable :: x(:, :)
    integer :: i
    allocate (x(n_case_columns, size(cases)))
    do i = 1, size(cases)
      x(:, i) = case_fields(cases(i))
    end do
  end function case_matrix

  !> The rule checks (davit_assess_rules, /assessment of a run): value, limit and margin
  !> of each, one column per check and quantity.
  subroutine write_check_columns(w, r)
    type(h5_writer_type), intent(inout) :: w
    type(case_result), intent(in) :: r(:)
    character(len=:), allocatable :: stem, units
    integer :: k
    real(wp), allocatable :: col(:)
    do k = 1, n_checks
      stem = "results/check_"//trim(check_ids(k))
      units = trim(check_units(k))
      col = r%check_value(k)
      call w%write_1d(stem//"_value", col, units, trim(check_texts(k))// &
                      " ("//trim(check_sources(k))//"): measured value; NaN = does not "// &
                      "apply"//defined, dims="case")
      col = r%check_limit(k)
      call w%write_1d(stem//"_limit", col, units, "Its limit"//defined, dims="case")
      col = r%check_margin(k)
      call w%write_1d(stem//"_margin", col, "-", "Relative margin, >= 0 "// &
                      "passes"//defined, dims="case")
    end do
  end subroutine write_check_columns

  !> A text field of every row ('message' or 'outcome'), padded to the longest (unset: empty).
  pure function text_column(r, field) result(texts)
    type(case_result), intent(in) :: r(:)
    character(len=*), intent(in) :: field
    character(len=:), allocatable :: texts(:)
    integer :: i, width
    width = 1
    do i = 1, size(r)
      width = max(width, len(row_text(r(i), field)))
    end do
    allocate (character(len=width) :: texts(size(r)))
    do i = 1, size(r)
      texts(i) = row_text(r(i), field)
    end do
  end function text_column

  pure function row_text(r, field) result(text)
    type(case_result), intent(in) :: r
    character(len=*), intent(in) :: field
    character(len=:), allocatable :: text
    text = ""
    if (field == "message" .and. allocated(r%message)) text = r%message
    if (field == "outcome" .and. allocated(r%outcome)) text = r%outcome
  end function row_text

end module davit_sweep_summary
