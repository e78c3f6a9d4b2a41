!> Quasi-static blocks' balance (davit_rigging_block_balance): the water entries that once
!> stopped it, closed-form balances, the slack/taut kinks and a property test over the
!> hooks' documented range of positions and speeds.
module test_block_balance
  use davit_kinds, only: wp, gravity
  use davit_error, only: error_type
  use davit_core_pose, only: pose_type
  use davit_rigging_falls_ends, only: falls_ends_type
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_rigging, only: rigging_type, new_rigging
  use davit_io_config, only: config_type
  use davit_sweep_keys, only: sweep_config, read_sweep
  use davit_sweep_cases, only: sweep_case, build_cases, case_config, initial_clearance
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  use rigging_fixture, only: make_config
  implicit none
  private
  public :: collect_block_balance

  character(len=*), parameter :: nl = new_line("a")
  real(wp), parameter :: weight = 8500.0_wp*gravity
  !> The hooks under the davit heads (the decks' geometry: heads at z = -20.55 m, 0.32 m
  !> sheave spacing, each head midway above its hook), boat level.
  real(wp), parameter :: hooks0(3, 2) = reshape([4.6_wp, 13.3_wp, -16.55_wp, &
                                                 -4.6_wp, 13.3_wp, -16.55_wp], [3, 2])
  real(wp), parameter :: head_z = -20.55_wp, half_spacing = 0.16_wp
  real(wp), parameter :: eye(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                                              0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  type(pose_type), parameter :: ship0 = pose_type([0.0_wp, 0.0_wp, 0.0_wp], eye, &
                                                  [0.0_wp, 0.0_wp, 0.0_wp], &
                                                  [0.0_wp, 0.0_wp, 0.0_wp])

contains

  function collect_block_balance() result(suite)
    type(suite_type) :: suite
    suite%name = "block_balance"
    suite%cases = [new_case("block_balance_series_springs", series_springs), &
                   new_case("block_balance_sling_kink", sling_kink), &
                   new_case("block_balance_resting_on_stop", resting_on_stop), &
                   new_case("block_balance_property_grid", property_grid), &
                   new_case("block_balance_lsa_water_entries", lsa_water_entries)]
  end function collect_block_balance

  !> Quasi-static blocks hanging at rest (W/2 on each hook) on the rigging of `text`;
  !> y: the rigging state.
  subroutine setup(rig, text, y, state)
    type(rigging_type), intent(out) :: rig
    character(len=*), intent(in) :: text
    real(wp), allocatable, intent(out) :: y(:)
    type(case_state), intent(inout) :: state
    type(rigging_config) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: hook_force(3, 2), res
    call make_config("blocks = 'quasi_static', drum_speed = 0"//nl//text, cfg, state)
    call new_rigging(rig, cfg, error)
    call check_true(state, .not. allocated(error), "rigging built")
    allocate (y(rig%nstate))
    y = 0.0_wp
    hook_force = 0.0_wp
    hook_force(3, :) = -0.5_wp*weight
    call rig%initial_state(hooks0, hook_force, ship0, y, res, error)
    call check_true(state, .not. allocated(error), "initial equilibrium")
  end subroutine setup

  !> Springs in series, closed form. Both hooks move down at v_h = 1 m/s, each under its
  !> block (reeving A, quasi-static sheaves, no dashpots): block a hangs on its sling
  !> (k_s = EA_s/l_s, vertical) and on the two chords of its falls, each of length l at
  !> the half-angle a (cos a = h/l, h the depth below the head's sheaves, l^2 = h^2 + r^2)
  !> with the one tension T = EA (L - L0)/L0. Lowering the block by dh lengthens the
  !> cable by 4 cos a dh (both blocks move alike) and turns its chords, so the falls'
  !> upward pull 2 T cos a stiffens by k_c = 8 EA cos^2 a/L0 + 2 T sin^2 a/l; in series
  !> with the sling the block moves at v_b = k_s/(k_s + k_c) v_h (the balance's velocity
  !> is its exact linearisation, so 1e-9 relative), midway under its sheaves, and its
  !> balance 2 T cos a = k_s (D - l_s) + m_b g holds with T = EA (L - L0)/L0.
  subroutine series_springs(state)
    type(case_state), intent(inout) :: state
    type(rigging_type) :: rig
    real(wp), allocatable :: y(:), f(:), sl(:, :)
    real(wp) :: br(3, 2), bv(3, 2), hook_vel(3, 2), h, l, cosa, t, k_s, k_c, stretch, v_exp
    real(wp) :: left
    logical :: solved
    integer :: it
    call setup(rig, "sling_damping = 0, cable_damping = 0", y, state)
    hook_vel = 0.0_wp
    hook_vel(3, :) = 1.0_wp
    call rig%block_state(0.0_wp, y, falls_ends_type(hooks0, hook_vel, ship0), br, bv, solved, &
                         it, left)
    call check_true(state, solved, "balance solved")
    h = br(3, 1) - head_z
    l = hypot(h, half_spacing)
    cosa = h/l
    k_s = rig%sling%k_seg
    stretch = (hooks0(3, 1) - br(3, 1)) - rig%sling%l0_seg
    t = (k_s*stretch + rig%block_mass*gravity)/(2.0_wp*cosa)
    allocate (f(rig%nseg), sl(1, 2))
    call rig%observe(0.0_wp, y, falls_ends_type(hooks0, hook_vel, ship0), f, sl)
    call check(state, f(4), t, "2 T cos a = k_s (D - l_s) + m_b g", rel_tol=1.0e-9_wp)
    call check(state, br(1, 1), hooks0(1, 1), "block 1 midway under its sheaves", &
               abs_tol=1.0e-9_wp)
    call check(state, br(2, 1), hooks0(2, 1), "block 1 in the heads' plane", abs_tol=1.0e-9_wp)
    k_c = 8.0_wp*rig%cables(1)%ea*cosa**2/rig%unstretched_length(y, 1) + &
          2.0_wp*t*(1.0_wp - cosa**2)/l
    v_exp = k_s/(k_s + k_c)
    call check(state, bv(3, 1), v_exp, "block 1: v_b = k_s/(k_s + k_c) v_h", rel_tol=1.0e-9_wp)
    call check(state, bv(3, 2), v_exp, "block 2: v_b = k_s/(k_s + k_c) v_h", rel_tol=1.0e-9_wp)
    call check(state, maxval(abs(bv(1:2, :))), 0.0_wp, "no sideways velocity", abs_tol=1.0e-9_wp)
    call check(state, left, 0.0_wp, "force left on a block [N]", abs_tol=1.0e-4_wp)
    call note(state, "k_s [N/m]", k_s)
    call note(state, "k_c [N/m]", k_c)
    call note(state, "v_b/v_h", bv(3, 1))
    call note(state, "balance evaluations", real(it, wp))
  end subroutine series_springs

  !> The sling's slack kink, taken exactly. The fore hook is raised by u from 0 to 20 mm
  !> (the sling goes slack once u exceeds its stretch plus the block's rise on the falls);
  !> at every u the balance is solved, the sling law is complementary (tension k_s
  !> (D - l_s) > 0 with D > l_s, or none with D <= l_s), block 1's vertical balance
  !> 2 T cos a = S + m_b g holds (1e-9 relative), and the block moves continuously
  !> (its height changes by less than the hook's step between neighbours): no jump and no
  !> lost balance at the kink.
  subroutine sling_kink(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: n = 201
    type(rigging_type) :: rig
    real(wp), allocatable :: y(:), f(:), sl(:, :)
    real(wp) :: hooks(3, 2), hook_vel(3, 2), br(3, 2), bv(3, 2), u, d, s, cosa, z_prev
    real(wp) :: worst_balance, worst_jump, left
    integer :: i, it, nslack, n_bad
    logical :: solved
    call setup(rig, "", y, state)
    allocate (f(rig%nseg), sl(1, 2))
    hook_vel = 0.0_wp
    worst_balance = 0.0_wp
    worst_jump = 0.0_wp
    nslack = 0
    n_bad = 0
    z_prev = 0.0_wp
    do i = 1, n
      u = 0.02_wp*real(i - 1, wp)/real(n - 1, wp)
      hooks = hooks0
      hooks(3, 1) = hooks0(3, 1) - u
      call rig%block_state(0.0_wp, y, falls_ends_type(hooks, hook_vel, ship0), br, bv, solved, &
                           it, left)
      if (.not. solved .or. left > 1.0e-3_wp) n_bad = n_bad + 1
      y(rig%block_r(1):rig%block_r(2)) = reshape(br, [6])
      call rig%observe(0.0_wp, y, falls_ends_type(hooks, hook_vel, ship0), f, sl)
      d = norm2(br(:, 1) - hooks(:, 1))
      s = rig%sling%k_seg*max(0.0_wp, d - rig%sling%l0_seg)
      if (d <= rig%sling%l0_seg) nslack = nslack + 1
      call check(state, sl(1, 1), s, "sling tension = k_s max(0, D - l_s)", abs_tol=1.0e-3_wp)
      cosa = (br(3, 1) - head_z)/hypot(br(3, 1) - head_z, half_spacing)
      worst_balance = max(worst_balance, abs(2.0_wp*f(4)*cosa - s - rig%block_mass*gravity)/ &
                          (s + rig%block_mass*gravity))
      if (i > 1) worst_jump = max(worst_jump, abs(br(3, 1) - z_prev))
      z_prev = br(3, 1)
    end do
    call check(state, real(n_bad, wp), 0.0_wp, "every balance solved (force left < 1 mN)")
    call check_true(state, nslack > 10 .and. nslack < n - 10, "both sides of the kink visited")
    call check(state, worst_balance, 0.0_wp, "2 T cos a = S + m_b g", abs_tol=1.0e-9_wp)
    call check_true(state, worst_jump <= 0.02_wp/real(n - 1, wp), &
                    "block follows the hook continuously")
    call note(state, "raises with the sling slack (of 201)", real(nslack, wp))
    call note(state, "largest step of block 1's height [m]", worst_jump)
  end subroutine sling_kink

  !> The defect behind the failed water entries: a block resting on its hook stop with
  !> both its falls and its sling slack (the drum paid out 10 m over the floating boat,
  !> the hooks 1.2 m up) has no stiffness sideways, and the balance's velocity
  !> -(dF/dr)^(-1) dF/dt was divided by a 1e-3 N/m floor there (100 m/s blocks, whose
  !> position copies then ran away). Now: the block sits on the stop, its weight on it
  !> (k_stop (d - e/2) = m_b g, d its penetration), and moves with its hook (the hooks
  !> moving at (0.5, -0.3, 0.85) m/s): 1e-9 m/s.
  subroutine resting_on_stop(state)
    type(case_state), intent(inout) :: state
    type(rigging_type) :: rig
    real(wp), allocatable :: y(:)
    real(wp) :: hooks(3, 2), hook_vel(3, 2), br(3, 2), bv(3, 2), pen, left
    integer :: a, it
    logical :: solved
    call setup(rig, "", y, state)
    y(rig%drum%q(1)) = 10.0_wp
    hooks = hooks0
    hooks(3, :) = hooks0(3, :) - 1.2_wp
    hooks(1:2, 2) = hooks(1:2, 2) + [0.3_wp, -0.4_wp]
    do a = 1, 2
      hook_vel(:, a) = [0.5_wp, -0.3_wp, 0.85_wp]
    end do
    call rig%block_state(0.0_wp, y, falls_ends_type(hooks, hook_vel, ship0), br, bv, solved, it, &
                         left)
    call check_true(state, solved, "balance solved")
    do a = 1, 2
      pen = rig%stop%height - (hooks(3, a) - br(3, a))
      call check(state, stop_law(rig, pen), rig%block_mass*gravity, &
                 "block on its stop carries its weight", rel_tol=1.0e-9_wp)
      call check(state, maxval(abs(bv(:, a) - hook_vel(:, a))), 0.0_wp, &
                 "block moves with its hook", abs_tol=1.0e-9_wp)
      call check_true(state, norm2(br(1:2, a) - hooks(1:2, a)) < rig%sling%l0_seg, &
                      "sling slack")
    end do
    call note(state, "balance evaluations", real(it, wp))
  end subroutine resting_on_stop

  !> The stop's elastic law (doc/theory/rigging.md, Hook stop): k d^2/(2 e) below the
  !> onset e, then k (d - e/2).
  pure real(wp) function stop_law(rig, d) result(f)
    type(rigging_type), intent(in) :: rig
    real(wp), intent(in) :: d
    if (d < rig%stop%onset) then
      f = rig%stop%k*d**2/(2.0_wp*rig%stop%onset)
    else
      f = rig%stop%k*(d - 0.5_wp*rig%stop%onset)
    end if
  end function stop_law

  !> Property test over the documented ranges: hooks moved sideways by up to 1.5 m each
  !> way (x, y), raised up to 1.5 m (slack slings) or lowered 5 cm (tensions ~4x static),
  !> the drum paid out 0 to 4 m beyond the static length (slack falls), hooks moving at up
  !> to 3.4 m/s (the drum speed at the LSA lowering speed): a 5 x 5 x 5 x 3 grid, 1125
  !> balances, each from the static blocks 1 cm off (a run starts each balance from the
  !> state's position copies, which follow the solved blocks). Every one converges: solved,
  !> and the force left on a block by its links, stop and weight (the fallback's anchor
  !> left out) below 1 mN; the block velocities stay bounded by the hooks' and the drum's
  !> speeds (< 10 m/s; a bounded velocity keeps the position copies from running away).
  subroutine property_grid(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: side(5) = [-1.5_wp, -0.7_wp, 0.0_wp, 0.6_wp, 1.5_wp]
    real(wp), parameter :: up(5) = [-1.5_wp, -0.5_wp, -0.01_wp, 0.0_wp, 0.05_wp]
    real(wp), parameter :: paid(3) = [0.0_wp, 0.05_wp, 4.0_wp]
    type(rigging_type) :: rig
    real(wp), allocatable :: y(:), y0(:)
    real(wp) :: hooks(3, 2), hook_vel(3, 2), br(3, 2), bv(3, 2), left, worst_left, worst_v
    integer :: i, j, k, m, it, n_bad, worst_it, total_it, count
    logical :: solved
    call setup(rig, "", y0, state)
    n_bad = 0
    worst_left = 0.0_wp
    worst_v = 0.0_wp
    worst_it = 0
    total_it = 0
    count = 0
    do m = 1, size(paid)
      do k = 1, size(up)
        do j = 1, size(side)
          do i = 1, size(side)
            y = y0
            y(rig%drum%q(1)) = paid(m)
            y(rig%block_r(1):rig%block_r(2)) = y0(rig%block_r(1):rig%block_r(2)) + 0.01_wp
            hooks = hooks0
            hooks(1, :) = hooks0(1, :) + side(i)
            hooks(2, 1) = hooks0(2, 1) + side(j)
            hooks(2, 2) = hooks0(2, 2) - side(j)
            hooks(3, :) = hooks0(3, :) + up(k)
            hooks(3, 2) = hooks(3, 2) + 0.3_wp*up(k)
            hook_vel(:, 1) = [2.0_wp, -1.0_wp, 3.4_wp]*(side(i) + 0.5_wp)/2.0_wp
            hook_vel(:, 2) = [-1.0_wp, 2.0_wp, -3.4_wp]*(side(j) - 0.5_wp)/2.0_wp
            call rig%block_state(0.0_wp, y, falls_ends_type(hooks, hook_vel, ship0), br, bv, &
                                 solved, it, left)
            if (.not. solved .or. .not. left < 1.0e-3_wp) then
              n_bad = n_bad + 1
              call note(state, "bad", real(it, wp))
              call note(state, "  left", left)
              call note(state, "  ijkm", real(i + 10*j + 100*k + 1000*m, wp))
            end if
            worst_left = max(worst_left, left)
            worst_v = max(worst_v, maxval(abs(bv)))
            worst_it = max(worst_it, it)
            total_it = total_it + it
            count = count + 1
          end do
        end do
      end do
    end do
    call check(state, real(n_bad, wp), 0.0_wp, "balances not solved (of 1125)")
    call check_true(state, worst_v < 10.0_wp, "block speeds bounded (< 10 m/s)")
    call note(state, "largest force left on a block [N]", worst_left)
    call note(state, "largest block speed [m/s]", worst_v)
    call note(state, "most balance evaluations", real(worst_it, wp))
    call note(state, "mean balance evaluations", real(total_it, wp)/real(count, wp))
  end subroutine property_grid

  !> The water entries at the LSA Code's 0.85 m/s (input/sweep_lsa_fast.nml) that stopped
  !> before the balance was globalised, each at ~18 s with the falls paid out over the
  !> floating boat (run diverged, boat roll = NaN: the failed balance poisons the state):
  !> cases 70 (Level 3, 90 deg, 1 B), 180 (Level 4, 45 deg, 1.5 B) and 396 (Level 5, 135
  !> deg, 0.5 B). Each must now run to its end (5 s after the hook release).
  subroutine lsa_water_entries(state)
    type(case_state), intent(inout) :: state
    integer, parameter :: failed(3) = [70, 180, 396]
    type(sweep_config) :: s
    type(sweep_case), allocatable :: cases(:)
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: clearance0
    integer :: i
    character(len=8) :: label
    call read_sweep("input/sweep_lsa_fast.nml", s, error)
    call check_true(state, .not. allocated(error), "sweep deck read")
    if (allocated(error)) return
    call initial_clearance(s%base, clearance0, error)
    call build_cases(s, clearance0, cases)
    do i = 1, size(failed)
      write (label, "(a,i0)") "case ", failed(i)
      call case_config(s, cases(failed(i)), clearance0, cfg)
      call run_to_end(state, cfg, trim(label))
    end do
  end subroutine lsa_water_entries

  !> Runs cfg to its end: no divergence, the hooks released.
  subroutine run_to_end(state, cfg, label)
    type(case_state), intent(inout) :: state
    type(config_type), intent(in) :: cfg
    character(len=*), intent(in) :: label
    type(error_type), allocatable :: error, run_error
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    real(wp), allocatable :: y(:)
    y = new_test_system(sys, cfg)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error)
    if (allocated(run_error)) call note(state, label//": "//run_error%message, 0.0_wp)
    call check_true(state, .not. allocated(run_error) .and. .not. allocated(error), &
                    label//" runs to its end")
    call check_true(state, sys%hist%release_time > 0.0_wp, label//" hooks released")
    call note(state, label//" release [s]", sys%hist%release_time)
  end subroutine run_to_end

end module test_block_balance
