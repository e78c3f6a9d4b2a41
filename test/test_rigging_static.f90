!> Quasi-static (inertia-free) blocks of the rigging (&rigging blocks = 'quasi_static',
!> review §4.3 item 2): statics, slack slings, energy, the blocks' velocity, the modes they
!> remove and the lowering and launch at steps beyond the massive blocks' limit, on the
!> hanging boat of rigging_fixture.
module test_rigging_static
  use davit_kinds, only: wp, gravity
  use davit_error, only: error_type
  use davit_solve_integrator, only: integrator_type
  use davit_io_config, only: config_type, read_config
  use davit_system_model, only: system_type
  use davit_rigging_falls_ends, only: falls_ends_type
  use system_fixture, only: new_test_system
  use davit_run_recorders, only: boat_recorder
  use davit_run_run_summary, only: run_summary
  use davit_run_driver, only: integrate
  use davit_run_linear_modes, only: linear_modes
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  use rigging_fixture, only: nl, weight, ship0, hanging_problem, setup, hooks, tensions, &
                             static_tension, new_rk4, energy_case, perturb
  implicit none
  private
  public :: collect_rigging_static

contains

  function collect_rigging_static() result(suite)
    type(suite_type) :: suite
    suite%name = "rigging_static"
    suite%cases = [new_case("quasi_static_blocks_statics_W4", static_blocks_statics), &
                   new_case("quasi_static_blocks_slack_sling", static_blocks_slack), &
                   new_case("quasi_static_blocks_energy_A8", static_blocks_energy), &
                   new_case("quasi_static_blocks_velocity", static_blocks_velocity), &
                   new_case("quasi_static_blocks_modes", static_blocks_modes), &
                   new_case("quasi_static_blocks_lowering_large_step", static_blocks_lowering), &
                   new_case("quasi_static_blocks_launch_iiib", static_blocks_launch)]
  end function collect_rigging_static

  ! ---------------------------------------------------------------- quasi-static blocks

  !> Quasi-static blocks keep the statics (F2, A6): the balance solved from starts 0.3 m
  !> off lands on the static equilibrium that initial_state lays out by hand (slings along
  !> their loads, the cable tension fitted to the blocks' loads) within 1e-9 m; every part
  !> then carries (W/2 + m_b g + n m_p g)/(2 cos a) (the weight is kept, so this is W/4
  !> plus the block and sling weights, as with massive blocks), the hooks W/2 each; and
  !> integrated with RK4 for 1 s at steps beyond the massive blocks' limit (2.25e-3 s)
  !> nothing moves. A weightless block would sit higher by its static sag m_b g/k_block
  !> (~7e-6 m), which these tolerances would see.
  subroutine static_blocks_statics(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: decks(4) = [character(len=48) :: &
      "sheaves = 'quasi_static', lumps = 0", "reeving = 'b', lumps = 0", &
      "sheaves = 'rotating', lumps = 0", "reeving = 'b', sheaves = 'rotating', lumps = 1"]
    !> RK4 steps: 5e-3 s with no stiff DOF left; rotating sheaves (~2600 1/s) and lumps keep
    !> theirs (review §4.1).
    real(wp), parameter :: dts(4) = [5.0e-3_wp, 5.0e-3_wp, 5.0e-4_wp, 1.0e-4_wp]
    real(wp), parameter :: offset(3) = [0.1_wp, -0.2_wp, 0.2_wp]
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:), y0(:), f(:)
    real(wp) :: res, t, t_exp, worst, br0(3, 2), br(3, 2), bv(3, 2), hook_pos(3, 2)
    real(wp) :: hook_vel(3, 2), c(3, 3), fh(3, 2), sag
    integer :: i, k, it
    logical :: solved
    real(wp), allocatable :: dydt(:)
    do i = 1, size(decks)
      call setup(p, "head_spacing = 0, blocks = 'quasi_static', sling_damping = 0, "// &
                 "drum_speed = 0"//nl//trim(decks(i)), y, state, res)
      call check_true(state, p%rig%ndof == 6*p%rig%nlump + p%rig%nsheave + 1, &
                      "blocks are no DOFs "//trim(decks(i)))
      br0 = p%rig%block_positions(y(13:))
      t_exp = static_tension(p)
      y(12 + p%rig%block_r(1):12 + p%rig%block_r(1) + 2) = br0(:, 1) + offset
      y(12 + p%rig%block_r(1) + 3:12 + p%rig%block_r(2)) = br0(:, 2) - offset
      call hooks(y, hook_pos, hook_vel, c)
      call p%rig%block_state(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), br, bv, &
                             solved, it)
      call check_true(state, solved, "balance solved "//trim(decks(i)))
      call check(state, maxval(abs(br - br0)), 0.0_wp, "blocks at the static equilibrium "// &
                 trim(decks(i)), abs_tol=1.0e-9_wp)
      call check(state, maxval(abs(bv)), 0.0_wp, "blocks at rest", abs_tol=1.0e-9_wp)
      f = tensions(p, 0.0_wp, y)
      call check(state, maxval(abs(f - t_exp))/t_exp, 0.0_wp, "t=0 parts = T "// &
                 trim(decks(i)), abs_tol=1.0e-9_wp)
      allocate (dydt(p%rig%nstate))
      call p%rig%rhs(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), dydt, fh)
      deallocate (dydt)
      call check(state, fh(3, 1), -0.5_wp*weight, "fore hook W/2", rel_tol=1.0e-9_wp)
      call check(state, fh(3, 2), -0.5_wp*weight, "aft hook W/2", rel_tol=1.0e-9_wp)
      if (i == 1) then
        call note(state, "Newton iterations from 0.3 m off, A QS", real(it, wp))
        sag = p%rig%block_mass*gravity/(p%rig%sling%k_seg + 4.0_wp*p%rig%cables(1)%ea/ &
                                        p%rig%unstretched_length(y(13:), 1))
        call note(state, "static sag m_b g/(k_sling + k_falls) [m]", sag)
        call note(state, "T expected [N]", t_exp)
      end if
      y0 = y
      call new_rk4(size(y), rk)
      t = 0.0_wp
      worst = 0.0_wp
      do k = 1, nint(1.0_wp/dts(i))
        call rk%step(p, t, y, dts(i))
        worst = max(worst, maxval(abs(tensions(p, t, y) - t_exp))/t_exp)
      end do
      call check(state, worst, 0.0_wp, "1 s: parts = T "//trim(decks(i)), abs_tol=1.0e-6_wp)
      call check(state, maxval(abs(y(1:12) - y0(1:12))), 0.0_wp, "boat at rest", &
                 abs_tol=1.0e-9_wp)
    end do
  end subroutine static_blocks_statics

  !> A slack sling cannot hold its block: with the fore hook raised 0.6 m (option A, one
  !> cable tension T over both blocks) block 1 hangs in its V of falls under its weight
  !> alone, 2 T cos a1 = m_b g, at the depth d = r/tan(a1) below its sheave pair (r = half
  !> the head spacing), while block 2 carries its sling: 2 T cos a2 = S2 + m_b g. Block 2's
  !> sling ties it to the fixed aft hook, so the cable can only give up its stretch
  !> (~1 cm): block 1 rises a few mm and T drops from 21 kN to ~m_b g/2.
  subroutine static_blocks_slack(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    real(wp), allocatable :: y(:), f(:), dydt(:), sl(:, :)
    real(wp) :: res, hook_pos(3, 2), hook_vel(3, 2), c(3, 3), br(3, 2), bv(3, 2), fh(3, 2)
    real(wp) :: cos1, cos2, head_z, tension, d_exp
    integer :: it
    logical :: solved
    call setup(p, "blocks = 'quasi_static', drum_speed = 0", y, state, res)
    call hooks(y, hook_pos, hook_vel, c)
    hook_pos(3, 1) = hook_pos(3, 1) - 0.6_wp
    call p%rig%block_state(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), br, bv, &
                           solved, it)
    call check_true(state, solved, "balance solved")
    call note(state, "Newton iterations", real(it, wp))
    allocate (dydt(p%rig%nstate))
    y(12 + p%rig%block_r(1):12 + p%rig%block_r(2)) = reshape(br, [6])
    call p%rig%rhs(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), dydt, fh)
    allocate (f(p%rig%nseg), sl(1, 2))
    call p%rig%observe(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), f, sl)
    tension = f(4)
    head_z = -20.55_wp
    cos1 = (br(3, 1) - head_z)/hypot(br(3, 1) - head_z, 0.16_wp)
    cos2 = (br(3, 2) - head_z)/hypot(br(3, 2) - head_z, 0.16_wp)
    call check(state, norm2(fh(:, 1)), 0.0_wp, "slack sling: no hook force", abs_tol=0.0_wp)
    call check(state, 2.0_wp*tension*cos1, p%rig%block_mass*gravity, "block 1: 2 T cos a = m_b g", &
               rel_tol=1.0e-6_wp)
    call check(state, br(1, 1), 4.6_wp, "block 1 midway under its sheaves", abs_tol=1.0e-9_wp)
    d_exp = 0.16_wp*cos1/sqrt(1.0_wp - cos1**2)
    call check(state, br(3, 1) - head_z, d_exp, "block 1 depth r/tan(a1)", rel_tol=1.0e-6_wp)
    call check(state, 2.0_wp*tension*cos2, -fh(3, 2) + p%rig%block_mass*gravity, &
               "block 2: 2 T cos a = S2 + m_b g", rel_tol=1.0e-6_wp)
    call check_true(state, all(abs(dydt) < huge(1.0_wp)), "finite derivatives")
    call note(state, "block 1 depth below its sheaves [m]", br(3, 1) - head_z)
    call note(state, "cable tension [N]", tension)
  end subroutine static_blocks_slack

  !> A8 with quasi-static blocks: a massless balance between conservative springs leaves a
  !> potential of the hooks (the elastic energy at the balance, whose gradient is the hook
  !> force), so with no damping and the drum stopped the boat + rigging energy is
  !> conserved (1e-6 of |E0| over 100 s) at an RK4 step 2e-3 s.
  subroutine static_blocks_energy(state)
    type(case_state), intent(inout) :: state
    call energy_case(state, "blocks = 'quasi_static', sheaves = 'quasi_static', lumps = 0", &
                     2.0e-3_wp, "QS blocks, QS sheaves, n=0")
  end subroutine static_blocks_energy

  !> The blocks move with their balance: the velocity the dashpots see, bv = -(dF/dr)^(-1)
  !> dF/dt, equals the time derivative of the solved positions along the motion (central
  !> differences over +-h of the whole state, h = 1e-4 s: error ~h^2 |d3r/dt3|, 1e-7
  !> relative here), on a boat swinging and heaving in its falls while the drum pays out
  !> (0.7 m/s, reeving A and B, quasi-static and rotating sheaves, one deck with lumps).
  !> Without dashpots this is exact; with them the balance also moves with the dashpot
  !> offset c v/k, whose rate c a/k bv leaves out (3e-4 to 9e-4 of bv in this case).
  subroutine static_blocks_velocity(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: decks(4) = [character(len=48) :: &
      "sheaves = 'quasi_static', lumps = 0", "reeving = 'b', lumps = 0", &
      "sheaves = 'rotating', lumps = 0", "reeving = 'b', sheaves = 'rotating', lumps = 1"]
    real(wp), parameter :: h = 1.0e-4_wp
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:), dydt(:), yp(:), ym(:)
    real(wp) :: res, t, hook_pos(3, 2), hook_vel(3, 2), c(3, 3), br(3, 2), bv(3, 2)
    real(wp) :: rp(3, 2), rm(3, 2), vdum(3, 2), err
    integer :: i, k
    do i = 1, size(decks)
      call setup(p, "blocks = 'quasi_static', drum_speed = 0.7, ramp_time = 0.1, "// &
                 "cable_damping = 0, sling_damping = 0"//nl//trim(decks(i)), y, state, res)
      call perturb(p, y)
      call new_rk4(size(y), rk)
      t = 0.0_wp
      do k = 1, 2000
        call rk%step(p, t, y, 1.0e-4_wp)
      end do
      allocate (dydt(size(y)))
      call p%rhs(t, y, dydt)
      yp = y + h*dydt
      ym = y - h*dydt
      call hooks(yp, hook_pos, hook_vel, c)
      call p%rig%block_state(t + h, yp(13:), falls_ends_type(hook_pos, hook_vel, ship0), rp, vdum)
      call hooks(ym, hook_pos, hook_vel, c)
      call p%rig%block_state(t - h, ym(13:), falls_ends_type(hook_pos, hook_vel, ship0), rm, vdum)
      call hooks(y, hook_pos, hook_vel, c)
      call p%rig%block_state(t, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), &
                             br, bv)
      err = maxval(abs((rp - rm)/(2.0_wp*h) - bv))/maxval(abs(bv))
      call check(state, err, 0.0_wp, "bv = d/dt of the balance "//trim(decks(i)), &
                 abs_tol=1.0e-5_wp)
      call note(state, "|bv| [m/s] "//trim(decks(i)), maxval(abs(bv)))
      call note(state, "relative difference", err)
      deallocate (dydt)
    end do
  end subroutine static_blocks_velocity

  !> The stiff block mode and what is left (III.B Level 5 deck, reeving A, quasi-static
  !> sheaves, no lumps). Massive blocks: the fastest mode is both blocks bouncing between
  !> sling and falls, omega = sqrt((EA/l_s + 2 (2 cos a)^2 EA/L0)/m_b) (the in-phase mode
  !> stretches the cable through both blocks). Quasi-static blocks: the fastest mode left is
  !> the boat's bounce on the two slings (2 EA/l_s) in series with the falls through the
  !> blocks ((4 cos a)^2 EA/L0), omega = sqrt(k/M) (eigenvalue modulus, damped or not).
  subroutine static_blocks_modes(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    type(system_type) :: sys
    real(wp), allocatable :: y(:)
    real(wp) :: rate_m, rate_q, omega, br(3, 2), drop, cosa, ea, l0, k_s, k_c, omega_block
    real(wp) :: omega_bounce
    call read_config("input/iiib_level5_090.nml", cfg, error)
    call check_true(state, .not. allocated(error), "deck read")
    if (allocated(error)) return
    call linear_modes(cfg, rate_m, omega, error)
    cfg%rigging%blocks = "quasi_static"
    call linear_modes(cfg, rate_q, omega, error)
    y = new_test_system(sys, cfg)
    br = sys%par%rig%block_positions(y(13:))
    drop = br(3, 1) - cfg%rigging%head_fore(3)
    cosa = drop/hypot(drop, 0.5_wp*cfg%rigging%head_spacing)
    ea = sys%par%rig%cables(1)%ea
    l0 = sys%par%rig%unstretched_length(y(13:), 1)
    k_s = ea/cfg%rigging%sling_length
    k_c = (2.0_wp*cosa)**2*ea/l0
    omega_block = sqrt((k_s + 2.0_wp*k_c)/cfg%rigging%block_mass)
    omega_bounce = sqrt(1.0_wp/(1.0_wp/(2.0_wp*k_s) + 1.0_wp/(4.0_wp*k_c))/cfg%boat%mass)
    call check(state, rate_m, omega_block, "massive: |lambda|max = block mode", rel_tol=0.02_wp)
    call check(state, rate_q, omega_bounce, "quasi-static: |lambda|max = boat bounce", &
               rel_tol=0.01_wp)
    call note(state, "massive |lambda|max [1/s]", rate_m)
    call note(state, "block mode sqrt((k_s + 2 k_c)/m_b) [rad/s]", omega_block)
    call note(state, "quasi-static |lambda|max [1/s]", rate_q)
    call note(state, "boat bounce sqrt(k/M) [rad/s]", omega_bounce)
    call note(state, "RK4 limit massive 2.83/|lambda| [s]", 2.83_wp/rate_m)
    call note(state, "RK4 limit quasi-static [s]", 2.83_wp/rate_q)
  end subroutine static_blocks_modes

  !> The calm lowering deck (reeving A, drum ramped to 0.7 m/s over 1 s), the whole 100 s:
  !> quasi-static blocks with RK4 at dt = 1e-2 s (4.4x the massive blocks' limit 2.25e-3
  !> s) run through the water entry and the hook release and follow the massive-block
  !> reference at dt = 1e-3 s. In calm air the blocks' inertia only shows through the
  !> ramp: it excites the boat's bounce (omega ~55 rad/s) with amplitude ~a_ramp/omega^2 =
  !> 0.175/55^2 = 5.8e-5 m, whose frequency the blocks (their ~100 kg share against 8500
  !> kg) shift by < 1 %, and loads the falls by 2 m_b a_ramp (18 N, 1e-6 m of stretch); in
  !> the water the hooks unload within ~1 s. So the CG paths must agree to the bounce
  !> amplitude, 6e-5 m; waterborne and release to one step of the coarser run.
  subroutine static_blocks_lowering(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type), target :: sys_m, sys_q
    type(boat_recorder) :: rec_m, rec_q
    type(run_summary) :: sum_m, sum_q
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    real(wp) :: diff, speed
    integer :: n, k4, k6
    call read_config("input/lowering.nml", cfg, error)
    call check_true(state, .not. allocated(error), "deck read")
    if (allocated(error)) return
    cfg%simulation%dt = 1.0e-3_wp
    y = new_test_system(sys_m, cfg)
    call integrate(cfg%simulation, sys_m, y, rec_m, sum_m, run_error, error)
    call check_true(state, .not. allocated(run_error), "massive reference runs")
    cfg%rigging%blocks = "quasi_static"
    cfg%simulation%dt = 1.0e-2_wp
    y = new_test_system(sys_q, cfg)
    call integrate(cfg%simulation, sys_q, y, rec_q, sum_q, run_error, error)
    call check_true(state, .not. allocated(run_error), "quasi-static at dt = 1e-2 runs")
    n = min(rec_m%n, rec_q%n)
    call check_true(state, n == rec_m%n .and. rec_m%n == nint(100.0_wp/0.02_wp) + 1, &
                    "all samples")
    diff = maxval(norm2(rec_m%position(:, 1:n) - rec_q%position(:, 1:n), 1))
    call check(state, diff, 0.0_wp, "CG paths agree", abs_tol=6.0e-5_wp)
    k4 = nint(40.0_wp/0.02_wp) + 1
    k6 = nint(60.0_wp/0.02_wp) + 1
    speed = (rec_q%position(3, k6) - rec_q%position(3, k4))/(rec_q%time(k6) - rec_q%time(k4))
    call check(state, speed, 0.7_wp/4.0_wp, "boat comes down at drum/4", rel_tol=0.01_wp)
    call check(state, sys_q%hist%waterborne_time, sys_m%hist%waterborne_time, "waterborne", &
               abs_tol=1.0e-2_wp)
    call check(state, sys_q%hist%release_time, sys_m%hist%release_time, "release", &
               abs_tol=1.0e-2_wp)
    call note(state, "max CG difference over 100 s [m]", diff)
    call note(state, "waterborne massive [s]", sys_m%hist%waterborne_time)
    call note(state, "waterborne quasi-static [s]", sys_q%hist%waterborne_time)
    call note(state, "RHS massive dt=1e-3", real(sum_m%rhs_evaluations, wp))
    call note(state, "RHS quasi-static dt=1e-2", real(sum_q%rhs_evaluations, wp))
    call note(state, "wall massive [s]", sum_m%wall_time)
    call note(state, "wall quasi-static [s]", sum_q%wall_time)
  end subroutine static_blocks_lowering

  !> The III.B Level 5 launch (beam sea, ship rolling, the boat swinging ~3 m, fender
  !> impacts from 38 s, waterborne and released at ~82 s). (1) Before any impact, what
  !> quasi-static blocks change is the blocks' inertia in the slow motions (the swing
  !> carries them along): first order in m_b, so the CG difference from the massive
  !> blocks over the first 20 s must shrink tenfold with a tenfold lighter block (5 kg,
  !> massive at dt = 5e-4 s), within 10 %. (2) At RK4 dt = 1e-2 s the run gets through the
  !> impacts, the slack slings and the water entry to the hook release.
  subroutine static_blocks_launch(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: d50, d5, release
    logical :: ok
    call read_config("input/iiib_level5_090.nml", cfg, error)
    call check_true(state, .not. allocated(error), "deck read")
    if (allocated(error)) return
    cfg%simulation%t_end = 20.0_wp
    d50 = cg_difference(cfg, 50.0_wp, 1.0e-3_wp)
    d5 = cg_difference(cfg, 5.0_wp, 5.0e-4_wp)
    call check(state, d50/d5, 10.0_wp, "CG difference ~ m_b", rel_tol=0.1_wp)
    call note(state, "max CG difference 0-20 s, m_b = 50 kg [m]", d50)
    call note(state, "max CG difference 0-20 s, m_b = 5 kg [m]", d5)
    cfg%simulation%t_end = 84.0_wp
    cfg%rigging%blocks = "quasi_static"
    cfg%simulation%dt = 1.0e-2_wp
    call launch(cfg, ok, release)
    call check_true(state, ok, "quasi-static launch at dt = 1e-2 runs 84 s")
    call check_true(state, release > 80.0_wp, "hooks released after the water entry")
    call note(state, "release [s]", release)
  end subroutine static_blocks_launch

  !> Largest boat CG distance between massive blocks of mass m_b (RK4 at dt) and
  !> quasi-static ones of the same weight (RK4 at 1e-2 s) over cfg's run.
  function cg_difference(base, m_b, dt) result(d)
    type(config_type), intent(in) :: base
    real(wp), intent(in) :: m_b, dt
    real(wp) :: d
    type(config_type) :: cfg
    type(system_type), target :: sys_m, sys_q
    type(boat_recorder) :: rec_m, rec_q
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    integer :: n
    cfg = base
    cfg%rigging%block_mass = m_b
    cfg%simulation%dt = dt
    y = new_test_system(sys_m, cfg)
    call integrate(cfg%simulation, sys_m, y, rec_m, summary, run_error, error)
    cfg%rigging%blocks = "quasi_static"
    cfg%simulation%dt = 1.0e-2_wp
    y = new_test_system(sys_q, cfg)
    call integrate(cfg%simulation, sys_q, y, rec_q, summary, run_error, error)
    n = min(rec_m%n, rec_q%n)
    d = maxval(norm2(rec_m%position(:, 1:n) - rec_q%position(:, 1:n), 1))
  end function cg_difference

  !> Runs cfg; ok if it completed; release: the hook release time [s] (< 0: none).
  subroutine launch(cfg, ok, release)
    type(config_type), intent(in) :: cfg
    logical, intent(out) :: ok
    real(wp), intent(out) :: release
    type(system_type), target :: sys
    type(boat_recorder) :: rec
    type(run_summary) :: summary
    type(error_type), allocatable :: error, run_error
    real(wp), allocatable :: y(:)
    y = new_test_system(sys, cfg)
    call integrate(cfg%simulation, sys, y, rec, summary, run_error, error)
    ok = .not. allocated(run_error) .and. .not. allocated(error)
    release = sys%hist%release_time
  end subroutine launch

end module test_rigging_static
