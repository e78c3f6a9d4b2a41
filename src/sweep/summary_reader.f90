!> Reading a sweep summary back (davit_sweep_summary writes it): the rows of an earlier
!> summary of the same sweep and shard for --resume, and a whole summary for
!> `davit sweep --merge`. Every column is checked (length, range, finiteness) so that a
!> damaged or foreign file is refused with its path and dataset, not read as rows.
module davit_sweep_summary_reader
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use davit_kinds, only: wp, i8
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_reader, only: h5_reader_type
  use davit_io_text, only: int_text
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_metrics, only: case_result, not_run_result
  use davit_assess_rules, only: n_checks, check_ids
  use davit_sweep_shards, only: shard_spec, shard_text
  use davit_sweep_result_columns, only: column_doc, result_columns, n_result_columns, &
                                        nreal_fields, set_reals, case_columns, n_case_columns, &
                                        set_case_fields
  implicit none
  private
  public :: read_results, read_summary

  !> The suffixes of a rule check's three columns, in the order of real_fields.
  character(len=*), parameter :: check_parts(0:2) = [character(len=7) :: "_value", "_limit", &
                                                      "_margin"]

contains

  !> The results of an earlier summary of the same sweep and shard (resume). Fails with a
  !> clear message when the file is not a summary of this sweep deck, base deck and shard.
  subroutine read_results(path, s, ncase, shard, results, error)
    !> Path of the earlier summary.
    character(len=*), intent(in) :: path
    !> The sweep deck it must belong to.
    type(sweep_config), intent(in) :: s
    !> Number of cases of the sweep.
    integer, intent(in) :: ncase
    !> The shard it must hold (count 0: the whole sweep).
    type(shard_spec), intent(in) :: shard
    !> One row per case, read back.
    type(case_result), intent(inout) :: results(:)
    !> Set when the file is not a summary of this sweep and shard, or a column is damaged.
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
    !> Path of the summary.
    character(len=*), intent(in) :: path
    !> The sweep's identity: file names and deck texts.
    type(sweep_config), intent(out) :: s
    !> The cases.
    type(sweep_case), allocatable, intent(out) :: cases(:)
    !> One row per case.
    type(case_result), allocatable, intent(out) :: results(:)
    !> The shard it holds (count 0: the whole sweep).
    type(shard_spec), intent(out) :: shard
    !> Threads recorded.
    integer, intent(out) :: threads
    !> The series folder recorded ("" for none).
    character(len=:), allocatable, intent(out) :: series_dir
    !> Set when the file is not a whole, readable summary.
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
    real(wp), allocatable :: x(:, :)
    integer(i8), allocatable :: iv(:)
    integer :: i
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
    call read_columns(f, "cases", case_columns, n, n_case_columns, x, error)
    if (allocated(error)) return
    do i = 1, n
      call set_case_fields(cases(i), x(:, i))
    end do
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
    call real_columns(f, r, error)
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

  !> The real columns of davit_sweep_result_columns, then the rule checks' values, limits
  !> and margins, each checked by real_column; the rows' reals set where all are read.
  subroutine real_columns(f, r, error)
    type(h5_reader_type), intent(inout) :: f
    type(case_result), intent(inout) :: r(:)
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:, :), col(:)
    integer :: i, k
    call read_columns(f, "results", result_columns, size(r), nreal_fields, x, error)
    if (allocated(error)) return
    do i = 1, n_checks
      do k = 0, 2
        call real_column(f, "results/check_"//trim(check_ids(i))//trim(check_parts(k)), &
                         size(r), col, error)
        if (allocated(error)) return
        x(n_result_columns + k*n_checks + i, :) = col
      end do
    end do
    do i = 1, size(r)
      call set_reals(r(i), x(:, i))
    end do
  end subroutine real_columns

  !> The columns of `table` under `group`, each of length n and checked by real_column,
  !> into the first rows of x (nrow rows, one column per case).
  subroutine read_columns(f, group, table, n, nrow, x, error)
    type(h5_reader_type), intent(inout) :: f
    character(len=*), intent(in) :: group
    type(column_doc), intent(in) :: table(:)
    integer, intent(in) :: n, nrow
    real(wp), allocatable, intent(out) :: x(:, :)
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: col(:)
    integer :: k
    allocate (x(nrow, n))
    do k = 1, size(table)
      call real_column(f, group//"/"//trim(table(k)%name), n, col, error)
      if (allocated(error)) return
      x(k, :) = col
    end do
  end subroutine read_columns

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

end module davit_sweep_summary_reader
