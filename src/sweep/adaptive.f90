!> Adaptive realisations (issue 16): a sweep with &sweep target_halfwidth > 0 runs in
!> rounds. Every cell (one combination of the swept inputs other than the realisation)
!> starts with `realisations`; after each round a cell stops when the 95 % Wilson
!> half-width of its collision probability, over its status-ok cases, is at most the
!> target, or when it has max_realisations; each open cell gets realisation_batch more.
!>
!> Deterministic: the case list has max_realisations slots per cell (davit_sweep_cases), so
!> a case's index and seed depend only on its cell and realisation, and which cases a
!> round runs depends only on the results of the rounds before it, never on threads or the
!> order in which cases finish. A resume replays the rounds from the stored rows. The
!> slots a converged cell never needed get status 3 (not needed) with the reason, so they
!> cannot be mistaken for the unrun cases of an interrupted sweep.
!>
!> The rounds need every result of a cell in one process, so --shard and MPI are refused.
module davit_sweep_adaptive
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_namelist, only: int_to_str
  use davit_io_text, only: fmt_fixed
  use davit_assess_statistics, only: wilson_halfwidth
  use davit_sweep_keys, only: sweep_config
  use davit_sweep_metrics, only: case_result, status_not_run, status_ok, status_failed, &
                                 status_not_needed
  implicit none
  private
  public :: adaptive, cell_converged, refuse_adaptive, adaptive_plan, new_plan, &
            round_cases, close_round, mark_not_needed, plan_text, fmt_width

  !> Where the rounds stand: realisations scheduled per cell (the first scheduled(j) of
  !> cell j), which cells are still open, and the rounds closed so far.
  type :: adaptive_plan
    !> Realisation slots per cell (max_realisations) and rounds closed so far.
    integer :: slots = 1, rounds = 0
    !> Realisations scheduled per cell: the first scheduled(j) slots of cell j.
    integer, allocatable :: scheduled(:)
    !> Whether each cell is still open (not yet stopped by the rule).
    logical, allocatable :: open(:)
  end type adaptive_plan

contains

  pure logical function adaptive(s)
    !> The sweep's settings (adaptive when target_halfwidth > 0).
    type(sweep_config), intent(in) :: s
    adaptive = s%target_halfwidth > 0.0_wp
  end function adaptive

  !> The stopping rule: `runs` realisations have run (ok or failed), n of them ok and k of
  !> those collided. Stop at the cap, or when the 95 % Wilson half-width of k/n is at most
  !> the target (n = 0 gives 0.5: nothing is known yet).
  pure logical function cell_converged(k, n, runs, target, cap) result(done)
    !> Collided cases k, ok cases n, realisations run, and the cap max_realisations.
    integer, intent(in) :: k, n, runs, cap
    !> Target 95 % Wilson half-width of the collision probability.
    real(wp), intent(in) :: target
    done = runs >= cap .or. wilson_halfwidth(k, n) <= target
  end function cell_converged

  !> An adaptive sweep cannot be split (`how`: "--shard K/N", "MPI ranks"): a cell's next
  !> round depends on all of its results.
  subroutine refuse_adaptive(s, how, error)
    !> The sweep's settings (its target_halfwidth and realisations go into the message).
    type(sweep_config), intent(in) :: s
    !> How the sweep would be split ("--shard K/N", "MPI ranks").
    character(len=*), intent(in) :: how
    !> The refusal.
    type(error_type), allocatable, intent(out) :: error
    if (.not. adaptive(s)) return
    call fatal_error(error, "'"//s%filename//"': &sweep target_halfwidth > 0 (adaptive "// &
                     "realisations) cannot run across "//how//": the rounds need all of a "// &
                     "cell's results in one process; run the sweep whole (OpenMP threads), "// &
                     "or set target_halfwidth = 0")
  end subroutine refuse_adaptive

  !> The first round: every cell open with `realisations` scheduled.
  function new_plan(s, ncase) result(plan)
    !> The sweep's settings (realisations, max_realisations).
    type(sweep_config), intent(in) :: s
    !> Number of case slots of the sweep (cells times max_realisations).
    integer, intent(in) :: ncase
    type(adaptive_plan) :: plan
    plan%slots = s%max_realisations
    allocate (plan%scheduled(ncase/plan%slots), plan%open(ncase/plan%slots))
    plan%scheduled = min(s%realisations, plan%slots)
    plan%open = .true.
  end function new_plan

  !> The cases this round still has to run: the scheduled slots of open cells that are not
  !> done (a stray status 3 among them, e.g. from an edited file, runs again).
  function round_cases(plan, results) result(pending)
    !> Where the rounds stand.
    type(adaptive_plan), intent(in) :: plan
    !> The sweep's rows, one per case slot.
    type(case_result), intent(in) :: results(:)
    integer, allocatable :: pending(:)
    ! as long as the sweep: allocatable (heap), not automatic (the stack)
    logical, allocatable :: due(:)
    integer :: j, c, n
    allocate (due(size(results)))
    due = .false.
    do j = 1, size(plan%open)
      if (plan%open(j)) due((j - 1)*plan%slots + 1:(j - 1)*plan%slots + plan%scheduled(j)) = &
        .true.
    end do
    due = due .and. (results%status == status_not_run .or. results%status == status_not_needed)
    allocate (pending(count(due)))
    n = 0
    do c = 1, size(results)
      if (.not. due(c)) cycle
      n = n + 1
      pending(n) = c
    end do
  end function round_cases

  !> After a round whose cases all ran: close the cells the rule stops, give the others
  !> the next batch (up to the cap).
  subroutine close_round(s, results, plan)
    !> The sweep's settings (target, cap, batch).
    type(sweep_config), intent(in) :: s
    !> The sweep's rows, one per case slot.
    type(case_result), intent(in) :: results(:)
    !> Where the rounds stand, advanced by one round.
    type(adaptive_plan), intent(inout) :: plan
    integer :: j, k, n, runs
    plan%rounds = plan%rounds + 1
    do j = 1, size(plan%open)
      if (.not. plan%open(j)) cycle
      call cell_counts(plan, results, j, k, n, runs)
      if (cell_converged(k, n, runs, s%target_halfwidth, s%max_realisations)) then
        plan%open(j) = .false.
      else
        plan%scheduled(j) = min(plan%scheduled(j) + s%realisation_batch, plan%slots)
      end if
    end do
  end subroutine close_round

  !> Collisions k among the n ok cases of the `runs` scheduled (and run) slots of cell j.
  pure subroutine cell_counts(plan, results, j, k, n, runs)
    !> Where the rounds stand.
    type(adaptive_plan), intent(in) :: plan
    !> The sweep's rows, one per case slot.
    type(case_result), intent(in) :: results(:)
    !> The cell's index.
    integer, intent(in) :: j
    !> Collided cases k, ok cases n, and scheduled slots that ran (ok or failed).
    integer, intent(out) :: k, n, runs
    integer :: first, last
    first = (j - 1)*plan%slots + 1
    last = first + plan%scheduled(j) - 1
    runs = count(results(first:last)%status == status_ok .or. &
                 results(first:last)%status == status_failed)
    n = count(results(first:last)%status == status_ok)
    k = count(results(first:last)%status == status_ok .and. results(first:last)%collided == 1)
  end subroutine cell_counts

  !> Status 3 and the reason for the slots a closed cell did not need.
  subroutine mark_not_needed(s, plan, results)
    !> The sweep's settings (target, cap) for the reason text.
    type(sweep_config), intent(in) :: s
    !> Where the rounds stand.
    type(adaptive_plan), intent(in) :: plan
    !> The sweep's rows; the unneeded slots of closed cells get status 3 and the reason.
    type(case_result), intent(inout) :: results(:)
    integer :: j, k, n, runs, c
    character(len=:), allocatable :: why
    do j = 1, size(plan%open)
      if (plan%open(j) .or. plan%scheduled(j) >= plan%slots) cycle
      call cell_counts(plan, results, j, k, n, runs)
      why = "not needed: cell's 95 % half-width "//fmt_width(wilson_halfwidth(k, n))// &
            " <= "//fmt_width(s%target_halfwidth)//" after "//int_to_str(runs)// &
            " realisations ("//int_to_str(k)//" of "//int_to_str(n)//" ok cases collided)"
      do c = (j - 1)*plan%slots + plan%scheduled(j) + 1, j*plan%slots
        if (results(c)%status /= status_not_run .and. results(c)%status /= status_not_needed) then
          cycle
        end if
        results(c)%status = status_not_needed
        results(c)%message = why
      end do
    end do
  end subroutine mark_not_needed

  !> "round 2: 3 of 4 cells stopped (2 at 95 % half-width <= 0.1, 1 at max_realisations
  !> 40), 1 open (widest 0.1312); next round 4 cases" for the progress line.
  function plan_text(s, plan, results) result(text)
    !> The sweep's settings (target, cap).
    type(sweep_config), intent(in) :: s
    !> Where the rounds stand.
    type(adaptive_plan), intent(in) :: plan
    !> The sweep's rows, one per case slot.
    type(case_result), intent(in) :: results(:)
    character(len=:), allocatable :: text
    integer :: j, k, n, runs, capped
    real(wp) :: widest
    capped = 0
    widest = 0.0_wp
    do j = 1, size(plan%open)
      call cell_counts(plan, results, j, k, n, runs)
      if (.not. plan%open(j) .and. runs >= s%max_realisations) capped = capped + 1
      ! an open cell's scheduled slots include the next batch: its width is that of the
      ! realisations run so far
      if (plan%open(j)) widest = max(widest, wilson_halfwidth(k, n))
    end do
    text = "round "//int_to_str(plan%rounds)//": "//int_to_str(count(.not. plan%open))// &
           " of "//int_to_str(size(plan%open))//" cells stopped ("// &
           int_to_str(count(.not. plan%open) - capped)//" at 95 % half-width <= "// &
           fmt_width(s%target_halfwidth)//", "//int_to_str(capped)//" at max_realisations "// &
           int_to_str(s%max_realisations)//"), "//int_to_str(count(plan%open))//" open"
    if (any(plan%open)) text = text//" (widest "//fmt_width(widest)//"); next round "// &
                               int_to_str(size(round_cases(plan, results)))//" cases"
  end function plan_text

  !> A half-width with 4 decimals ("0.0812").
  function fmt_width(x) result(text)
    !> Half-width to format.
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    text = fmt_fixed(x, 4)
  end function fmt_width

end module davit_sweep_adaptive
