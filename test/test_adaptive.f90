!> Adaptive realisations (issue 16): the Wilson score interval against Newcombe (1998,
!> Stat Med 17:857, Table I, method 3), the stopping rule, the &sweep keys and their
!> checks, the case layout (cells x max_realisations) and the rounds replayed on made-up
!> results (which cases each round runs depends only on the results).
module test_adaptive
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_assess_statistics, only: wilson_interval, wilson_halfwidth, z95
  use davit_sweep_keys, only: sweep_config, parse_sweep
  use davit_sweep_cases, only: sweep_case, build_cases, case_seed
  use davit_sweep_metrics, only: case_result, status_ok, status_not_run, status_not_needed
  use davit_sweep_adaptive, only: cell_converged, adaptive_plan, new_plan, round_cases, &
                                  close_round, mark_not_needed
  use davit_bench_study, only: cell_verdicts
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_adaptive

  character(len=*), parameter :: sweep_file = "input/test_sweep.nml"
  character(len=*), parameter :: base = "&sweep base_deck = 'iiib_level5_090.nml', "

contains

  function collect_adaptive() result(suite)
    type(suite_type) :: suite
    suite%name = "adaptive"
    suite%cases = [new_case("wilson_newcombe_table_i", newcombe_table), &
                   new_case("wilson_edges_and_closed_form", wilson_edges), &
                   new_case("stopping_rule", stopping_rule), &
                   new_case("adaptive_keys_and_checks", adaptive_keys), &
                   new_case("cells_times_max_realisations_layout", layout), &
                   new_case("rounds_replayed_from_results", rounds), &
                   new_case("bench_study_cell_verdicts", study_verdicts)]
  end function collect_adaptive

  !> Newcombe's Table I, method 3 (score interval without continuity correction), to the
  !> four decimals he gives.
  subroutine newcombe_table(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: k(4) = [81, 15, 0, 1], n(4) = [263, 148, 20, 29]
    real(wp), parameter :: lower(4) = [0.2553_wp, 0.0624_wp, 0.0_wp, 0.0061_wp]
    real(wp), parameter :: upper(4) = [0.3662_wp, 0.1605_wp, 0.1611_wp, 0.1718_wp]
    real(wp) :: b(2)
    integer :: i
    character(len=16) :: label
    do i = 1, 4
      write (label, "(i0,a,i0)") k(i), "/", n(i)
      b = wilson_interval(k(i), n(i))
      call check(state, b(1), lower(i), trim(label)//" lower", abs_tol=5e-5_wp)
      call check(state, b(2), upper(i), trim(label)//" upper", abs_tol=5e-5_wp)
      b = wilson_interval(k(i), n(i), z95)
      call check(state, b(2), upper(i), trim(label)//" upper, z given", abs_tol=5e-5_wp)
    end do
  end subroutine newcombe_table

  !> n = 0 knows nothing: [0, 1]; k = 0 gives [0, z^2/(n + z^2)] and k = n its mirror, so
  !> the half-width is z^2/(2(n + z^2)); the interval is symmetric under k -> n - k.
  subroutine wilson_edges(state)
    type(case_state), intent(inout) :: state
    real(wp) :: b(2), z2
    z2 = z95**2
    b = wilson_interval(0, 0)
    call check_true(state, b(1) == 0.0_wp .and. b(2) == 1.0_wp, "n = 0: [0, 1]")
    call check(state, wilson_halfwidth(0, 0), 0.5_wp, "n = 0 half-width", abs_tol=0.0_wp)
    b = wilson_interval(0, 16)
    call check(state, b(1), 0.0_wp, "0/16 lower", abs_tol=1e-15_wp)
    call check(state, b(2), z2/(16.0_wp + z2), "0/16 upper", rel_tol=1e-14_wp)
    call check(state, wilson_halfwidth(16, 16), z2/(2.0_wp*(16.0_wp + z2)), &
               "16/16 half-width", rel_tol=1e-14_wp)
    b = wilson_interval(7, 10)
    call check(state, 1.0_wp - b(2), minval(wilson_interval(3, 10)), "3/10 mirrors 7/10", &
               abs_tol=1e-15_wp)
  end subroutine wilson_edges

  !> Stop at the cap, or once the half-width is <= the target: with none colliding the
  !> 95 % half-width drops below 0.1 at n = 16 (n >= 4 z^2 = 15.4), not at 15.
  subroutine stopping_rule(state)
    type(case_state), intent(inout) :: state
    call check_true(state, .not. cell_converged(0, 15, 15, 0.1_wp, 100), "0/15 open")
    call check_true(state, cell_converged(0, 16, 16, 0.1_wp, 100), "0/16 stops")
    call check_true(state, cell_converged(16, 16, 16, 0.1_wp, 100), "16/16 stops")
    call check_true(state, .not. cell_converged(8, 16, 16, 0.1_wp, 100), "8/16 open")
    call check_true(state, cell_converged(8, 16, 16, 0.1_wp, 16), "8/16 at the cap")
    call check_true(state, .not. cell_converged(0, 0, 5, 0.1_wp, 100), &
                    "all failed: nothing known, open")
    call check_true(state, cell_converged(0, 0, 5, 0.1_wp, 5), "all failed at the cap")
  end subroutine stopping_rule

  !> The keys are documented deck keys with ranges; the cap must hold the first round, and
  !> the cap and batch need a target.
  subroutine adaptive_keys(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    s = accepted(base//"realisations = 4 /")
    call check_true(state, s%target_halfwidth == 0.0_wp .and. s%max_realisations == 4 .and. &
                    s%realisation_batch == 4, "off: cap and batch = realisations")
    s = accepted(base//"realisations = 4, target_halfwidth = 0.05, max_realisations = 50 /")
    call check_true(state, s%max_realisations == 50 .and. s%realisation_batch == 4, &
                    "batch defaults to realisations")
    call refused(state, base//"target_halfwidth = 0.6 /", "target_halfwidth", "range")
    call refused(state, base//"realisations = 4, target_halfwidth = 0.1, "// &
                 "max_realisations = 3 /", "max_realisations = 3", "must be >= realisations")
    call refused(state, base//"max_realisations = 10 /", "max_realisations", &
                 "needs target_halfwidth > 0")
    call refused(state, base//"realisation_batch = 2 /", "realisation_batch", &
                 "needs target_halfwidth > 0")
  end subroutine adaptive_keys

  !> 2 cells x max_realisations 5: realisation r of cell j is case 5(j - 1) + r with the
  !> seed of that index, whatever the first round's size.
  subroutine layout(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    integer :: i
    s = accepted(base//"clearances_b = 1.0, 2.0, realisations = 2, "// &
                 "target_halfwidth = 0.2, max_realisations = 5, base_seed = 3 /")
    call build_cases(s, 1.5_wp, cases)
    call check_true(state, size(cases) == 10, "10 cases")
    call check_true(state, all(cases%realisation == [(mod(i - 1, 5) + 1, i = 1, 10)]), &
                    "five slots per cell")
    call check_true(state, all(cases%seed == [(case_seed(3, i), i = 1, 10)]), &
                    "seed of the fixed index")
  end subroutine layout

  !> Three cells of up to 12, first 4, batches of 3, target 0.2 (with k = 0 the half-width
  !> z^2/(2(n + z^2)) is <= 0.2 from n = 1.5 z^2 = 5.8): cell 1 never collides and
  !> stops after round 2 (n = 7), cell 2 collides half the time and runs to the cap, cell 3
  !> is still unrun (an interrupted sweep) so nothing of it is decided.
  subroutine rounds(state)
    type(case_state), intent(inout) :: state
    type(sweep_config) :: s
    type(adaptive_plan) :: plan
    type(case_result) :: r(36)
    integer, allocatable :: pending(:)
    integer :: i
    s = accepted(base//"clearances_b = 1.0, 2.0, 3.0, realisations = 4, "// &
                 "target_halfwidth = 0.2, max_realisations = 12, realisation_batch = 3 /")
    plan = new_plan(s, 36)
    pending = round_cases(plan, r)
    call check_true(state, all(pending == [1, 2, 3, 4, 13, 14, 15, 16, 25, 26, 27, 28]), &
                    "round 1: first 4 of each cell")
    ! what the rounds will have run: cell 1 up to its stop at 7, cell 2 to the cap
    do i = 1, 24
      if (i > 7 .and. i <= 12) cycle
      r(i)%status = status_ok
      r(i)%collided = merge(0, mod(i, 2), i <= 12)
    end do
    call close_round(s, r, plan)
    call check_true(state, all(plan%scheduled == [7, 7, 7]) .and. all(plan%open), &
                    "0/4 is 0.245 wide: all open, 3 more each")
    call close_round(s, r, plan)
    call check_true(state, all(plan%open .eqv. [.false., .true., .true.]), &
                    "0/7 (0.1772) stops; 3/7 and 0/0 stay open")
    call check_true(state, all(plan%scheduled == [7, 10, 10]), "cap not yet reached")
    call close_round(s, r, plan)
    call close_round(s, r, plan)
    call check_true(state, all(plan%scheduled == [7, 12, 12]) .and. .not. plan%open(2), &
                    "half colliding: stops at the cap 12")
    call mark_not_needed(s, plan, r)
    call check_true(state, all(r(8:12)%status == status_not_needed), "cell 1: 8..12 not needed")
    if (allocated(r(8)%message)) then
      call check_true(state, index(r(8)%message, "not needed: cell's 95 % half-width "// &
                      "0.1772 <= 0.2000 after 7 realisations") == 1, "the reason: "//r(8)%message)
    end if
    call check_true(state, all(r(13:36)%status /= status_not_needed), &
                    "capped and undecided cells: none")
    call check_true(state, all(r(25:36)%status == status_not_run), "cell 3 still unrun")
  end subroutine rounds

  function accepted(text) result(s)
    character(len=*), intent(in) :: text
    type(sweep_config) :: s
    type(error_type), allocatable :: error
    call parse_sweep(sweep_file, text, s, error)
    if (allocated(error)) error stop "test sweep deck rejected: "//error%message
  end function accepted

  subroutine refused(state, text, key, why)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: text, key, why
    type(sweep_config) :: s
    type(error_type), allocatable :: error
    call parse_sweep(sweep_file, text, s, error)
    call check_true(state, allocated(error), "refused: "//text)
    if (.not. allocated(error)) return
    call check_true(state, index(error%message, key) > 0 .and. index(error%message, why) > 0, &
                    "message names "//key//" and "//why//": "//error%message)
  end subroutine refused

  !> The bench's study row judges cells as the operability table does (risk 5 %, Wilson
  !> 95 %): 0 of 84 has the upper bound z^2/(n + z^2) = 0.0437 <= 0.05 (decided), 0 of 60
  !> has 0.0602 (undecided), 20 of 40 a lower bound of 0.35 > 0.05 (decided), 2 of 40
  !> straddles 0.05 (undecided); cases not finished do not count.
  subroutine study_verdicts(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: sizes(4) = [84, 60, 40, 40], hits(4) = [0, 0, 20, 2]
    logical, allocatable :: done(:), hit(:)
    real(wp), allocatable :: key(:)
    integer :: c, i, cells, decided
    allocate (done(0), hit(0), key(0))
    do c = 1, 4
      done = [done, [(.true., i = 1, sizes(c))], [(.false., i = 1, 7)]]
      hit = [hit, [(i <= hits(c), i = 1, sizes(c))], [(.true., i = 1, 7)]]
      key = [key, [(real(c, wp), i = 1, sizes(c) + 7)]]
    end do
    call cell_verdicts(done, hit, key, cells, decided)
    call check_true(state, cells == 4, "four cells")
    call check_true(state, decided == 2, "0/84 and 20/40 decided, 0/60 and 2/40 not")
    call cell_verdicts(done(1:91), hit(1:91), key(1:91), cells, decided)
    call check_true(state, cells == 1 .and. decided == 1, "0 of 84 decided")
    call cell_verdicts(done(92:158), hit(92:158), key(92:158), cells, decided)
    call check_true(state, cells == 1 .and. decided == 0, "0 of 60 undecided")
  end subroutine study_verdicts

end module test_adaptive
