!> `davit sweep --merge OUT.h5 SHARD.h5 ...`: join the summaries of the shards of one sweep
!> (--shard K/N) into the summary a single run writes. Rows are copied as read, so the
!> merged file holds the very bits each shard computed. Every input is read and checked
!> before anything is written: shards of another sweep or base deck (their stored texts
!> differ), of another N, given twice, or finishing one case twice are refused. Missing
!> shards are allowed: their cases stay "not run", and `--resume` on the merged summary
!> (a whole-sweep summary) completes them.
module davit_sweep_merge
  use davit_error, only: error_type, fatal_error
  use davit_io_hdf5_writer, only: check_output_path, acquire_lock, release_lock
  use davit_io_files, only: same_file
  use davit_io_namelist, only: int_to_str
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_cases, only: sweep_case
  use davit_sweep_metrics, only: case_result, status_not_run, status_ok, status_failed
  use davit_sweep_shards, only: shard_spec, shard_text
  use davit_sweep_summary, only: write_summary, read_summary
  implicit none
  private
  public :: merge_outcome, merge_shards

  type :: merge_outcome
    !> Cases in the merged summary, and how many of them are ok, failed and not run.
    integer :: ncase = 0, ok = 0, failed = 0, not_run = 0
    !> N of the shards, and the shards (K) that were not given.
    integer :: count = 0
    !> The shards (K) that were not given.
    integer, allocatable :: missing(:)
    !> The sweep deck as the shards name it (to tell how to resume the merged summary).
    character(len=:), allocatable :: sweep_file
  end type merge_outcome

  !> One shard summary as read.
  type :: shard_file
    !> The sweep's settings and identity (file names and deck texts) as stored.
    type(sweep_config) :: s
    !> The sweep's cases.
    type(sweep_case), allocatable :: cases(:)
    !> The shard's rows, one per case (cases of other shards not run).
    type(case_result), allocatable :: results(:)
    !> Which shard (K/N) the file holds.
    type(shard_spec) :: shard
    !> OpenMP threads the shard ran with.
    integer :: threads = 1
    !> Directory of the per-case series files, as stored.
    character(len=:), allocatable :: series_dir
  end type shard_file

contains

  !> Merge shard summaries `inputs` (trailing blanks ignored) into `out_path`.
  subroutine merge_shards(out_path, inputs, outcome, error)
    !> Path of the merged summary, and the shard summaries (trailing blanks ignored).
    character(len=*), intent(in) :: out_path, inputs(:)
    !> Case counts of the merged summary and the missing shards.
    type(merge_outcome), intent(out) :: outcome
    !> Set when an input is unreadable or incompatible, or the output cannot be written.
    type(error_type), allocatable, intent(out) :: error
    type(shard_file) :: first, next
    logical, allocatable :: given(:)
    integer, allocatable :: owner(:)
    integer :: i, threads
    logical :: own_lock
    call check_output_path(out_path, error)
    if (allocated(error)) return
    if (is_an_input(out_path, inputs)) then
      call fatal_error(error, "cannot merge: the output '"//out_path//"' is also an input; "// &
                       "name a new file")
      return
    end if
    call read_shard_file(trim(inputs(1)), first, error)
    if (allocated(error)) return
    allocate (given(first%shard%count), owner(size(first%cases)))
    given = .false.
    owner = 0
    threads = first%threads
    do i = 1, size(inputs)
      if (i > 1) call read_shard_file(trim(inputs(i)), next, error)
      if (allocated(error)) return
      if (i == 1) next = first
      call check_compatible(first, trim(inputs(1)), next, trim(inputs(i)), error)
      if (.not. allocated(error)) call take_rows(next, i, inputs, given, owner, first%results, &
                                                 error)
      if (allocated(error)) return
      threads = max(threads, next%threads)
    end do
    call acquire_lock(out_path, own_lock, error)
    if (allocated(error)) return
    call write_summary(out_path, first%s, first%cases, first%results, threads, &
                       first%series_dir, shard_spec(), error)
    if (own_lock) call release_lock(out_path)
    if (allocated(error)) return
    outcome%ncase = size(first%cases)
    outcome%ok = count(first%results%status == status_ok)
    outcome%failed = count(first%results%status == status_failed)
    outcome%not_run = count(first%results%status == status_not_run)
    outcome%count = first%shard%count
    outcome%sweep_file = first%s%filename
    outcome%missing = pack([(i, i = 1, size(given))], .not. given)
  end subroutine merge_shards

  !> Whether `out_path` names one of `inputs`: by text, or as the same file (device and
  !> inode: `./a1.h5` and `a1.h5`, `$PWD/a1.h5`, links), which the merge would overwrite.
  logical function is_an_input(out_path, inputs)
    !> Path of the merged summary, and the shard summaries.
    character(len=*), intent(in) :: out_path, inputs(:)
    integer :: i
    is_an_input = .true.
    do i = 1, size(inputs)
      if (inputs(i) == out_path .or. same_file(out_path, trim(inputs(i)))) return
    end do
    is_an_input = .false.
  end function is_an_input

  !> A shard summary; a whole-sweep summary is refused (it has no slice to merge).
  subroutine read_shard_file(path, f, error)
    !> Path of the shard summary.
    character(len=*), intent(in) :: path
    !> The shard summary as read.
    type(shard_file), intent(out) :: f
    !> Set when the file cannot be read or is a whole-sweep summary.
    type(error_type), allocatable, intent(out) :: error
    call read_summary(path, f%s, f%cases, f%results, f%shard, f%threads, f%series_dir, error)
    if (allocated(error)) then
      error%message = "cannot merge: "//error%message
      return
    end if
    if (f%shard%count == 0) call fatal_error(error, "cannot merge: '"//path//"' is not a "// &
      "shard summary (it has no shard_index/shard_count; write shards with --shard K/N)")
  end subroutine read_shard_file

  !> Shard `b` must come from the sweep deck, base deck, case count and N of shard `a`.
  subroutine check_compatible(a, a_path, b, b_path, error)
    !> The two shard summaries compared.
    type(shard_file), intent(in) :: a, b
    !> Their paths, for the message.
    character(len=*), intent(in) :: a_path, b_path
    !> Set when b's sweep deck, base deck, case count or N differ from a's.
    type(error_type), allocatable, intent(out) :: error
    character(len=:), allocatable :: why
    why = ""
    if (b%s%deck_text /= a%s%deck_text) then
      why = "was written by a different sweep deck"
    else if (b%s%base%deck_text /= a%s%base%deck_text) then
      why = "was written with a different base deck"
    else if (size(b%cases) /= size(a%cases)) then
      why = "holds a different number of cases"
    else if (b%shard%count /= a%shard%count) then
      why = "is shard "//shard_text(b%shard)//", of another number of shards"
    end if
    if (len(why) > 0) call fatal_error(error, "cannot merge: '"//b_path//"' "//why// &
                                       " (compared with '"//a_path//"', shard "// &
                                       shard_text(a%shard)//")")
  end subroutine check_compatible

  !> Copy the finished rows of input i into `results`; a shard given twice or a case
  !> finished in two inputs is an overlap.
  subroutine take_rows(f, i, inputs, given, owner, results, error)
    !> The shard summary whose rows are taken.
    type(shard_file), intent(in) :: f
    !> Its index in inputs.
    integer, intent(in) :: i
    !> The shard summary paths, for the messages.
    character(len=*), intent(in) :: inputs(:)
    !> Which shards (K) have been given so far.
    logical, intent(inout) :: given(:)
    !> Per case, the index of the input that finished it (0 = none yet).
    integer, intent(inout) :: owner(:)
    !> The merged rows, receiving the finished rows of this input.
    type(case_result), intent(inout) :: results(:)
    !> Set on an overlap (a shard given twice or a case finished twice).
    type(error_type), allocatable, intent(out) :: error
    integer :: c
    if (given(f%shard%index)) then
      call fatal_error(error, "cannot merge: shard "//shard_text(f%shard)//" is given "// &
                       "twice ('"//trim(inputs(i))//"' overlaps an earlier input)")
      return
    end if
    given(f%shard%index) = .true.
    do c = 1, size(results)
      if (f%results(c)%status == status_not_run) cycle
      if (owner(c) /= 0) then
        call fatal_error(error, "cannot merge: case "//int_to_str(c)//" was run in both '"// &
                         trim(inputs(owner(c)))//"' and '"//trim(inputs(i))//"' (the "// &
                         "shards overlap)")
        return
      end if
      owner(c) = i
      results(c) = f%results(c)
    end do
  end subroutine take_rows

end module davit_sweep_merge
