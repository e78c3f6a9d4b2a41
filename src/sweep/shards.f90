!> Job arrays for `davit sweep --shard K/N`: the K-th of N deterministic slices of a sweep's
!> case list. The slices are dealt round-robin over every case in the dearest-first order
!> (longest_first), so each shard gets a like share of cheap and dear cases and the N jobs
!> of an array end at about the same time. The order depends only on the deck, so every
!> job of the array computes the same slices without talking to the others.
module davit_sweep_shards
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: int_to_str
  use davit_sweep_keys, only: sweep_config, wave_type_names
  use davit_sweep_cases, only: sweep_case
  implicit none
  private
  public :: shard_spec, parse_shard, shard_text, shard_mask, longest_first

  !> Shard `index` of `count`; count = 0 is the whole sweep (no --shard).
  type :: shard_spec
    !> Shard number (1-based) and number of shards; count = 0 is the whole sweep.
    integer :: index = 0, count = 0
  end type shard_spec

contains

  !> "K/N" with 1 <= K <= N (digits only).
  subroutine parse_shard(text, shard, error)
    !> The "K/N" text of --shard.
    character(len=*), intent(in) :: text
    !> The parsed shard.
    type(shard_spec), intent(out) :: shard
    !> Set when the text is not "K/N" with 1 <= K <= N.
    type(error_type), allocatable, intent(out) :: error
    integer :: slash, ios_k, ios_n
    slash = index(text, "/")
    ios_k = 1
    ios_n = 1
    if (slash > 1 .and. slash < len(text)) then
      if (verify(text(:slash - 1), "0123456789") == 0 .and. &
          verify(text(slash + 1:), "0123456789") == 0 .and. len(text) < 20) then
        read (text(:slash - 1), *, iostat=ios_k) shard%index
        read (text(slash + 1:), *, iostat=ios_n) shard%count
      end if
    end if
    if (ios_k /= 0 .or. ios_n /= 0) then
      call fatal_error(error, "option --shard needs K/N (shard K of N, e.g. 2/8), got '"// &
                       text//"'")
    else if (shard%count < 1) then
      call fatal_error(error, "option --shard K/N needs N >= 1, got '"//text//"'")
    else if (shard%index < 1 .or. shard%index > shard%count) then
      call fatal_error(error, "option --shard K/N needs 1 <= K <= N, got '"//text//"'")
    end if
    if (allocated(error)) shard = shard_spec()
  end subroutine parse_shard

  !> "K/N", or "whole" for the whole sweep.
  function shard_text(shard) result(text)
    !> The shard to describe.
    type(shard_spec), intent(in) :: shard
    character(len=:), allocatable :: text
    if (shard%count == 0) then
      text = "whole"
    else
      text = int_to_str(shard%index)//"/"//int_to_str(shard%count)
    end if
  end function shard_text

  !> Which cases belong to `shard`: every count-th case of the dearest-first order,
  !> starting at the index-th (all of them for the whole sweep). Arrays as long as the
  !> sweep are allocatable (heap), never automatic (the stack under -fstack-arrays).
  function shard_mask(s, cases, shard) result(mine)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> All the sweep's cases.
    type(sweep_case), intent(in) :: cases(:)
    !> The shard whose cases are selected.
    type(shard_spec), intent(in) :: shard
    logical, allocatable :: mine(:)
    integer, allocatable :: order(:)
    integer :: k
    allocate (mine(size(cases)))
    if (shard%count == 0) then
      mine = .true.
      return
    end if
    allocate (order(size(cases)))
    do k = 1, size(cases)
      order(k) = k
    end do
    call longest_first(s, cases, order)
    mine = .false.
    do k = shard%index, size(order), shard%count
      mine(order(k)) = .true.
    end do
  end function shard_mask

  !> Order the cases to run by their expected cost, dearest first (stable: equal costs keep
  !> their order), so that no thread is left with a long case at the end while the others
  !> idle (issue 14). Only the order of work changes: every row is stored under its own
  !> index, so the summary is the same in any order. A merge sort: n log n for any case
  !> list up to the sweep's cap (an insertion sort was n^2: hours for 10^6 cases).
  subroutine longest_first(s, cases, pending)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> All the sweep's cases.
    type(sweep_case), intent(in) :: cases(:)
    !> Pending case indices, reordered longest expected run first.
    integer, intent(inout) :: pending(:)
    real(wp), allocatable :: cost(:), cost_work(:)
    integer, allocatable :: work(:)
    integer :: i, width, lo
    allocate (cost(size(pending)), cost_work(size(pending)), work(size(pending)))
    do i = 1, size(pending)
      cost(i) = expected_cost(s, cases(pending(i)))
    end do
    width = 1
    do while (width < size(pending))
      do lo = 1, size(pending), 2*width
        call merge_runs(cost, pending, lo, min(lo + width - 1, size(pending)), &
                        min(lo + 2*width - 1, size(pending)), cost_work, work)
      end do
      width = 2*width
    end do
  end subroutine longest_first

  !> Merge the sorted runs lo..mid and mid+1..hi (dearest first; ties from the left run
  !> first, which keeps the sort stable).
  pure subroutine merge_runs(cost, pending, lo, mid, hi, cost_work, work)
    !> Expected costs of the pending cases and their merge work array.
    real(wp), intent(inout) :: cost(:), cost_work(:)
    !> Pending case indices and their merge work array, reordered with the costs.
    integer, intent(inout) :: pending(:), work(:)
    !> Start, end of the left run and end of the right run (indices into pending).
    integer, intent(in) :: lo, mid, hi
    integer :: i, j, k
    logical :: left
    if (mid >= hi) return
    i = lo
    j = mid + 1
    do k = lo, hi
      left = j > hi
      if (.not. left .and. i <= mid) left = cost(i) >= cost(j)
      if (left) then
        cost_work(k) = cost(i)
        work(k) = pending(i)
        i = i + 1
      else
        cost_work(k) = cost(j)
        work(k) = pending(j)
        j = j + 1
      end if
    end do
    cost(lo:hi) = cost_work(lo:hi)
    pending(lo:hi) = work(lo:hi)
  end subroutine merge_runs

  !> Relative cost of a case: steps (1/dt) times the work per step, which the wave sums of
  !> an irregular sea's components (n_frequencies x n_directions) dominate (README
  !> Benchmark: ~1 RHS of the default scene per 100 components).
  pure real(wp) function expected_cost(s, c) result(cost)
    !> The sweep's settings.
    type(sweep_config), intent(in) :: s
    !> The case whose cost is estimated.
    type(sweep_case), intent(in) :: c
    real(wp) :: dt, components
    dt = merge(c%dt, s%base%simulation%dt, c%dt > 0.0_wp)
    components = 1.0_wp
    if (wave_type_names(c%wave_type) == "irregular") components = &
      real(s%base%sea%n_frequencies, wp)*real(s%base%sea%n_directions, wp)
    cost = (1.0_wp + components/100.0_wp)/dt
  end function expected_cost

end module davit_sweep_shards
