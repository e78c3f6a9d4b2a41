!> The sweep summary file: one row per case (1-D datasets of length ncase), the case inputs
!> under /cases and the results under /results, every dataset with `units` and
!> `description`. It is always written whole (under SUMMARY.h5.tmp, then renamed), at the
!> start, at checkpoints and at the end, so an interrupted sweep leaves a valid summary in
!> which the unfinished cases have status 0. postproc/layout.py holds the same names.
!> HDF5 is not thread-safe here: call these from one thread at a time.
module davit_sweep_summary
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp, i8, davit_version
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_io_hdf5_reader, only: h5_reader_type
  use davit_io_text, only: int_text
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_metrics, only: case_result, status_not_run, not_run_result
  use davit_assess_rules, only: n_checks, check_ids, check_units, check_texts, check_sources
  use davit_sweep_shards, only: shard_spec, shard_text
  implicit none
  private
  public :: write_summary, read_results, read_summary

  character(len=*), parameter :: wave_type_codes = "0 calm, 1 airy (regular, linear), "// &
                                                   "2 stokes2 (regular), 3 irregular"
  character(len=*), parameter :: defined = " (status 1 only; NaN otherwise)"

contains

  !> Write the whole summary to `path` (atomically: `path.tmp`, then renamed). A shard's
  !> summary (shard%count > 0) also records shard_index and shard_count.
  subroutine write_summary(path, s, cases, results, threads, series_dir, shard, error)
    character(len=*), intent(in) :: path, series_dir
    type(sweep_config), intent(in) :: s
    type(sweep_case), intent(in) :: cases(:)
    type(case_result), intent(in) :: results(:)
    integer, intent(in) :: threads
    type(shard_spec), intent(in) :: shard
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
    real(wp), allocatable :: col(:)
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
    col = cases%wind_speed
    call w%write_1d("cases/wind_speed", col, "m/s", "Wind speed", dims="case")
    col = cases%wave_height
    call w%write_1d("cases/wave_height", col, "m", &
                    "Wave height (regular: 2a; irregular: H of eq. 44)", dims="case")
    col = cases%wave_period
    call w%write_1d("cases/wave_period", col, "s", &
                    "Regular-wave period (irregular: sets only the ramp)", dims="case")
    col = cases%angle_deg
    call w%write_1d("cases/angle_deg", col, "deg", &
                    "Encounter angle chi: wave direction from N1 towards N2, ship heading N1", &
                    dims="case")
    col = cases%clearance_b
    call w%write_1d("cases/clearance_b", col, "-", &
                    "Initial fender-to-ship-side distance in boat widths", dims="case")
    col = cases%dt
    call w%write_1d("cases/dt", col, "s", "Time step", dims="case")
    col = cases%phase_deg
    call w%write_1d("cases/phase_deg", col, "deg", "Regular-wave phase epsilon"// &
                    " at the origin at t = 0 (irregular: unused, the seed sets the phases)", &
                    dims="case")
  end subroutine write_cases

  subroutine write_results(w, r)
    type(h5_writer_type), intent(inout) :: w
    type(case_result), intent(in) :: r(:)
    ! each column through an allocatable (heap): an expression or a component of the rows
    ! passed as the argument would be a temporary on the stack, as long as the sweep
    real(wp), allocatable :: col(:)
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
    col = r%min_clearance
    call w%write_1d("results/min_clearance", col, "m", "Smallest fender-to-"// &
                    "ship-side distance over the lowering; negative = indentation"//defined, &
                    dims="case")
    icol = int(r%collided, i8)
    call w%write_1d_int("results/collided", icol, "-", &
                        "1 if min_clearance < 0 (a fender touched the ship), else 0; -1 "// &
                        "if not status 1", dims="case")
    icol = int(r%impacts, i8)
    call w%write_1d_int("results/impacts", icol, "-", "Separate contact "// &
                        "episodes over the lowering; -1 if not status 1", dims="case")
    col = r%peak_horizontal_acceleration
    call w%write_1d("results/peak_horizontal_acceleration", col, &
                    "m/s^2", "Largest horizontal CG acceleration |(a_x, a_y)|, mean over "// &
                    "each step"//defined, dims="case")
    col = r%peak_vertical_acceleration
    call w%write_1d("results/peak_vertical_acceleration", col, &
                    "m/s^2", "Largest vertical CG acceleration |a_z| (gravity not "// &
                    "subtracted: 0 hanging at rest), mean over each step"//defined, dims="case")
    col = r%peak_segment_tension
    call w%write_1d("results/peak_segment_tension", col, "N", &
                    "Largest tension of any cable or sling segment over the lowering"//defined, &
                    dims="case")
    col = r%first_contact_time
    call w%write_1d("results/first_contact_time", col, "s", &
                    "Time of the first fender contact over the lowering; -1 = none"//defined, &
                    dims="case")
    col = r%waterborne_time
    call w%write_1d("results/waterborne_time", col, "s", "Time the boat "// &
                    "became waterborne; -1 = never"//defined, dims="case")
    col = r%end_time
    call w%write_1d("results/end_time", col, "s", "End of the lowering window: "// &
                    "hook release, or the end of the run"//defined, dims="case")
    call write_log_columns(w, r)
    col = r%wall_time
    call w%write_1d("results/wall_time", col, "s", &
                    "Compute time of the case (one thread); NaN if not run", dims="case")
    icol = r%steps
    call w%write_1d_int("results/steps", icol, "-", "Integrator steps", dims="case")
    icol = r%rhs_evaluations
    call w%write_1d_int("results/rhs_evaluations", icol, "-", &
                        "Right-hand-side evaluations of the integrator", dims="case")
  end subroutine write_results

  !> The launch log's columns: peaks, limits and outcome over the run.
  subroutine write_log_columns(w, r)
    type(h5_writer_type), intent(inout) :: w
    type(case_result), intent(in) :: r(:)
    real(wp), allocatable :: col(:)
    character(len=:), allocatable :: texts(:)
    col = r%peak_sling_tension
    call w%write_1d("results/peak_sling_tension", col, "N", "Largest "// &
                    "sling tension over every step until release"//defined, dims="case")
    col = r%peak_fall_tension
    call w%write_1d("results/peak_fall_tension", col, "N", "Largest "// &
                    "cable-segment (fall) tension over every step until release"//defined, &
                    dims="case")
    col = r%max_impact_speed
    call w%write_1d("results/max_impact_speed", col, "m/s", "Fastest "// &
                    "normal impact on the ship's side (0 = none)"//defined, dims="case")
    col = r%peak_seat_acceleration
    call w%write_1d("results/peak_seat_acceleration", col, "m/s^2", &
                    "Largest filtered seat acceleration (&limits seat, seat_filter)"//defined, &
                    dims="case")
    col = r%swl_exceeded_time
    call w%write_1d("results/swl_exceeded_time", col, "s", "First time "// &
                    "a wire tension exceeded the safe working load; -1 = never"//defined, &
                    dims="case")
    col = r%mbl_exceeded_time
    call w%write_1d("results/mbl_exceeded_time", col, "s", "First time "// &
                    "a wire tension exceeded the minimum breaking load; -1 = never"//defined, &
                    dims="case")
    col = r%impact_speed_exceeded_time
    call w%write_1d("results/impact_speed_exceeded_time", col, &
                    "s", "First impact faster than &limits impact_speed; -1 = never"//defined, &
                    dims="case")
    texts = text_column(r, "outcome")
    call w%write_strings("results/outcome", texts, "-", "How the "// &
                         "launch ended: released, waterborne, or not waterborne and why; "// &
                         "empty if not run", dims="case")
    call write_check_columns(w, r)
  end subroutine write_log_columns

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

  !> The results of an earlier summary of the same sweep and shard (resume). Fails with a
  !> clear message when the file is not a summary of this sweep deck, base deck and shard.
  subroutine read_results(path, s, ncase, shard, results, error)
    character(len=*), intent(in) :: path
    type(sweep_config), intent(in) :: s
    integer, intent(in) :: ncase
    type(shard_spec), intent(in) :: shard
    type(case_result), intent(inout) :: results(:)
    type(error_type), allocatable, intent(out) :: error
    type(h5_reader_type) :: f
    call f%open(path, error)
    if (allocated(error)) return
    call check_same_sweep(f, s, ncase, error)
    if (.not. allocated(error)) call check_same_shard(f, shard, error)
    if (.not. allocated(error)) call read_rows(f, results, error)
    call f%close()
    if (allocated(error)) error%message = "cannot resume: "//error%message
  end subroutine read_results

  !> A shard resumes only its own summary; the whole sweep only a whole (or merged) one.
  subroutine check_same_shard(f, shard, error)
    type(h5_reader_type), intent(inout) :: f
    type(shard_spec), intent(in) :: shard
    type(error_type), allocatable, intent(out) :: error
    type(shard_spec) :: stored
    call read_shard(f, stored, error)
    if (allocated(error)) return
    if (stored%index == shard%index .and. stored%count == shard%count) return
    if (stored%count == 0) then
      call fatal_error(error, "'"//f%path//"' is the summary of the whole sweep, not of "// &
                       "shard "//shard_text(shard)//"; resume it without --shard")
    else if (shard%count == 0) then
      call fatal_error(error, "'"//f%path//"' is the summary of shard "// &
                       shard_text(stored)//"; resume it with --shard "//shard_text(stored)// &
                       " or merge the shards (davit sweep --merge)")
    else
      call fatal_error(error, "'"//f%path//"' is the summary of shard "// &
                       shard_text(stored)//", not of shard "//shard_text(shard))
    end if
  end subroutine check_same_shard

  !> The shard a summary records (absent: the whole sweep), checked for 1 <= K <= N.
  subroutine read_shard(f, shard, error)
    type(h5_reader_type), intent(inout) :: f
    type(shard_spec), intent(out) :: shard
    type(error_type), allocatable, intent(out) :: error
    integer(i8) :: k, n
    if (.not. (f%has_attr("shard_index") .or. f%has_attr("shard_count"))) return
    call f%attr_int("shard_index", k, error)
    if (.not. allocated(error)) call f%attr_int("shard_count", n, error)
    if (allocated(error)) return
    if (n < 1 .or. k < 1 .or. k > n .or. n > huge(1)) then
      call fatal_error(error, "'"//f%path//"': shard "//int_text(k)//"/"//int_text(n)// &
                       " is not 1 <= K <= N")
      return
    end if
    shard = shard_spec(int(k), int(n))
  end subroutine read_shard

  !> A whole summary (merge): its sweep's identity (file names and deck texts in `s`), the
  !> cases, the rows, the shard and the thread count.
  subroutine read_summary(path, s, cases, results, shard, threads, series_dir, error)
    character(len=*), intent(in) :: path
    type(sweep_config), intent(out) :: s
    type(sweep_case), allocatable, intent(out) :: cases(:)
    type(case_result), allocatable, intent(out) :: results(:)
    type(shard_spec), intent(out) :: shard
    integer, intent(out) :: threads
    character(len=:), allocatable, intent(out) :: series_dir
    type(error_type), allocatable, intent(out) :: error
    type(h5_reader_type) :: f
    integer(i8) :: n
    call f%open(path, error)
    if (allocated(error)) return
    call f%attr_str("sweep_file", s%filename, error)
    if (.not. allocated(error)) call f%attr_str("sweep_namelist", s%deck_text, error)
    if (.not. allocated(error)) call f%attr_str("base_deck", s%base_deck, error)
    if (.not. allocated(error)) call f%attr_str("base_namelist", s%base%deck_text, error)
    if (.not. allocated(error)) call f%attr_str("series_dir", series_dir, error)
    if (.not. allocated(error)) call f%attr_int("threads", n, error)
    threads = int(min(max(n, 0_i8), int(huge(1), i8)))
    if (.not. allocated(error)) call f%attr_int("ncase", n, error)
    if (.not. allocated(error) .and. (n < 0 .or. n > huge(1))) then
      call fatal_error(error, "'"//path//"': ncase = "//int_text(n)//" is out of range")
    end if
    if (.not. allocated(error)) call read_shard(f, shard, error)
    if (.not. allocated(error)) call read_cases(f, int(n), cases, error)
    ! shards are never adaptive (davit_sweep_adaptive refuses them): every cell ran all
    ! of its realisations, which is what the merged summary's attributes then say
    if (.not. allocated(error)) then
      s%realisations = max(1, maxval(cases%realisation))
      s%max_realisations = s%realisations
      s%realisation_batch = s%realisations
    end if
    if (.not. allocated(error)) then
      allocate (results(n))
      results = not_run_result()
      call read_rows(f, results, error)
    end if
    call f%close()
  end subroutine read_summary

  !> The /cases columns, each of length n (written back unchanged by a merge).
  subroutine read_cases(f, n, cases, error)
    type(h5_reader_type), intent(inout) :: f
    integer, intent(in) :: n
    type(sweep_case), allocatable, intent(out) :: cases(:)
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: col(:)
    integer(i8), allocatable :: iv(:)
    integer(i8), parameter :: top = huge(1)
    ! the index column first: its length checks ncase before anything of that size is made
    call int_column(f, "cases/index", n, 1_i8, int(n, i8), iv, error)
    if (allocated(error)) return
    allocate (cases(n))
    cases%index = int(iv)
    call int_column(f, "cases/realisation", n, 0_i8, top, iv, error)
    if (allocated(error)) return
    cases%realisation = int(iv)
    call int_column(f, "cases/seed", n, -top - 1, top, iv, error)
    if (allocated(error)) return
    cases%seed = int(iv)
    call int_column(f, "cases/level", n, -top - 1, top, iv, error)
    if (allocated(error)) return
    cases%level = int(iv)
    call int_column(f, "cases/wave_type", n, 0_i8, 3_i8, iv, error)
    if (allocated(error)) return
    cases%wave_type = int(iv)
    call int_column(f, "cases/wind", n, 0_i8, 1_i8, iv, error)
    if (allocated(error)) return
    cases%wind = iv == 1
    call real_column(f, "cases/wind_speed", size(cases), col, error)
    if (.not. allocated(error)) cases%wind_speed = col
    if (.not. allocated(error)) call real_column(f, "cases/wave_height", size(cases), col, error)
    if (.not. allocated(error)) cases%wave_height = col
    if (.not. allocated(error)) call real_column(f, "cases/wave_period", size(cases), col, error)
    if (.not. allocated(error)) cases%wave_period = col
    if (.not. allocated(error)) call real_column(f, "cases/angle_deg", size(cases), col, error)
    if (.not. allocated(error)) cases%angle_deg = col
    if (.not. allocated(error)) call real_column(f, "cases/clearance_b", size(cases), col, error)
    if (.not. allocated(error)) cases%clearance_b = col
    if (.not. allocated(error)) call real_column(f, "cases/dt", size(cases), col, error)
    if (.not. allocated(error)) cases%dt = col
    if (.not. allocated(error)) call real_column(f, "cases/phase_deg", size(cases), col, error)
    if (.not. allocated(error)) cases%phase_deg = col
  end subroutine read_cases

  subroutine check_same_sweep(f, s, ncase, error)
    type(h5_reader_type), intent(inout) :: f
    type(sweep_config), intent(in) :: s
    integer, intent(in) :: ncase
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer(i8) :: n
    integer(i8), allocatable :: index(:)
    call f%attr_str("sweep_namelist", text, error)
    if (allocated(error)) return
    if (text /= s%deck_text) then
      call fatal_error(error, "'"//f%path//"' was written by a different sweep deck "// &
                       "(its text differs from '"//s%filename//"'); run without --resume "// &
                       "or restore the deck")
      return
    end if
    call f%attr_str("base_namelist", text, error)
    if (allocated(error)) return
    if (text /= s%base%deck_text) then
      call fatal_error(error, "'"//f%path//"' was written with a different base deck "// &
                       "(its text differs from '"//s%base_path//"'); run without --resume "// &
                       "or restore the deck")
      return
    end if
    call f%attr_int("ncase", n, error)
    if (allocated(error)) return
    if (n /= ncase) call fatal_error(error, "'"//f%path//"' holds a different number of cases")
    if (allocated(error)) return
    call int_column(f, "cases/index", ncase, 1_i8, int(ncase, i8), index, error)
  end subroutine check_same_sweep

  !> Every results column, each checked for presence, length (ncase) and range, so that a
  !> damaged or crafted summary is refused instead of misread.
  subroutine read_rows(f, r, error)
    type(h5_reader_type), intent(inout) :: f
    type(case_result), intent(inout) :: r(:)
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: col(:)
    character(len=:), allocatable :: stem
    integer(i8), allocatable :: iv(:)
    character(len=:), allocatable :: sv(:)
    integer :: i
    call int_column(f, "results/status", size(r), 0_i8, 3_i8, iv, error)
    if (allocated(error)) return
    r%status = int(iv)
    call int_column(f, "results/collided", size(r), -1_i8, 1_i8, iv, error)
    if (allocated(error)) return
    r%collided = int(iv)
    call int_column(f, "results/impacts", size(r), -1_i8, huge(1_i8), iv, error)
    if (allocated(error)) return
    r%impacts = int(min(iv, int(huge(1), i8)))
    call int_column(f, "results/steps", size(r), 0_i8, huge(1_i8), iv, error)
    if (allocated(error)) return
    r%steps = iv
    call int_column(f, "results/rhs_evaluations", size(r), 0_i8, huge(1_i8), iv, error)
    if (allocated(error)) return
    r%rhs_evaluations = iv
    call string_column(f, "results/message", size(r), sv, error)
    if (allocated(error)) return
    do i = 1, size(r)
      r(i)%message = trim(sv(i))
    end do
    call string_column(f, "results/outcome", size(r), sv, error)
    if (allocated(error)) return
    do i = 1, size(r)
      r(i)%outcome = trim(sv(i))
    end do
    call real_column(f, "results/min_clearance", size(r), col, error)
    if (.not. allocated(error)) r%min_clearance = col
    if (.not. allocated(error)) call real_column(f, "results/peak_horizontal_acceleration", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%peak_horizontal_acceleration = col
    if (.not. allocated(error)) call real_column(f, "results/peak_vertical_acceleration", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%peak_vertical_acceleration = col
    if (.not. allocated(error)) call real_column(f, "results/peak_segment_tension", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%peak_segment_tension = col
    if (.not. allocated(error)) call real_column(f, "results/first_contact_time", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%first_contact_time = col
    if (.not. allocated(error)) call real_column(f, "results/waterborne_time", size(r), col, error)
    if (.not. allocated(error)) r%waterborne_time = col
    if (.not. allocated(error)) call real_column(f, "results/end_time", size(r), col, error)
    if (.not. allocated(error)) r%end_time = col
    if (.not. allocated(error)) call real_column(f, "results/wall_time", size(r), col, error)
    if (.not. allocated(error)) r%wall_time = col
    if (.not. allocated(error)) call real_column(f, "results/peak_sling_tension", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%peak_sling_tension = col
    if (.not. allocated(error)) call real_column(f, "results/peak_fall_tension", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%peak_fall_tension = col
    if (.not. allocated(error)) call real_column(f, "results/max_impact_speed", size(r), col, error)
    if (.not. allocated(error)) r%max_impact_speed = col
    if (.not. allocated(error)) call real_column(f, "results/peak_seat_acceleration", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%peak_seat_acceleration = col
    if (.not. allocated(error)) call real_column(f, "results/swl_exceeded_time", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%swl_exceeded_time = col
    if (.not. allocated(error)) call real_column(f, "results/mbl_exceeded_time", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%mbl_exceeded_time = col
    if (.not. allocated(error)) call real_column(f, "results/impact_speed_exceeded_time", &
                                                 size(r), col, error)
    if (.not. allocated(error)) r%impact_speed_exceeded_time = col
    do i = 1, n_checks
      if (allocated(error)) return
      stem = "results/check_"//trim(check_ids(i))
      call real_column(f, stem//"_value", size(r), col, error)
      if (.not. allocated(error)) r%check_value(i) = col
      if (.not. allocated(error)) call real_column(f, stem//"_limit", size(r), col, error)
      if (.not. allocated(error)) r%check_limit(i) = col
      if (.not. allocated(error)) call real_column(f, stem//"_margin", size(r), col, error)
      if (.not. allocated(error)) r%check_margin(i) = col
    end do
    if (allocated(error)) return
    do i = 1, size(r)
      if (r(i)%status == 1 .and. (.not. ieee_is_finite(r(i)%wall_time) .or. &
                                  r(i)%wall_time < 0.0_wp)) then
        call fatal_error(error, "'"//f%path//"': /results/wall_time of case "// &
                         int_text(int(i, i8))//" (status 1) is not a finite time >= 0")
        return
      end if
    end do
  end subroutine read_rows

  !> Integer column `name` of length n with every value in lo..hi.
  subroutine int_column(f, name, n, lo, hi, iv, error)
    type(h5_reader_type), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    integer(i8), intent(in) :: lo, hi
    integer(i8), allocatable, intent(out) :: iv(:)
    type(error_type), allocatable, intent(out) :: error
    integer :: k
    call f%read_1d_int(name, iv, error)
    if (allocated(error)) return
    call check_length(f, name, size(iv), n, error)
    if (allocated(error)) return
    do k = 1, n
      if (iv(k) < lo .or. iv(k) > hi) then
        call fatal_error(error, "'"//f%path//"': /"//name//"("//int_text(int(k, i8))// &
                         ") = "//int_text(iv(k))//" is out of range "//int_text(lo)// &
                         " .. "//int_text(hi))
        return
      end if
    end do
  end subroutine int_column

  !> Real column `name` of length n, into v (allocatable: a column is as long as the sweep,
  !> and the caller's component array would be passed through a temporary on the stack).
  subroutine real_column(f, name, n, v, error)
    type(h5_reader_type), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    real(wp), allocatable, intent(out) :: v(:)
    type(error_type), allocatable, intent(out) :: error
    call f%read_1d(name, v, error)
    if (allocated(error)) return
    call check_length(f, name, size(v), n, error)
  end subroutine real_column

  subroutine string_column(f, name, n, sv, error)
    type(h5_reader_type), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    character(len=:), allocatable, intent(out) :: sv(:)
    type(error_type), allocatable, intent(out) :: error
    call f%read_strings(name, sv, error)
    if (allocated(error)) return
    call check_length(f, name, size(sv), n, error)
  end subroutine string_column

  subroutine check_length(f, name, got, n, error)
    type(h5_reader_type), intent(in) :: f
    character(len=*), intent(in) :: name
    integer, intent(in) :: got, n
    type(error_type), allocatable, intent(out) :: error
    if (got /= n) call fatal_error(error, "'"//f%path//"': /"//name//" has "// &
                                   int_text(int(got, i8))//" rows, the sweep has "// &
                                   int_text(int(n, i8))//" cases")
  end subroutine check_length

end module davit_sweep_summary
