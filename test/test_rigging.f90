!> Rigging: lumped-mass slings, cable-pulley system and winch (paper §II.D-E, review §1.6,
!> §1.10, F1, F2, A6-A8, A10), coupled to a 6-DOF rigid boat (davit_core_body) hanging from
!> the two hooks at (+-4.6, 0, -1.55) in b (G4), integrated with the project's RK4.
module test_rigging
  use davit_kinds, only: wp, gravity
  use davit_error, only: error_type
  use davit_core_rotation, only: rotation_matrix
  use davit_core_pose, only: pose_type
  use davit_rigging_falls_ends, only: falls_ends_type
  use davit_core_kane, only: kane_v, kane_w_phi, kane_f
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_rigging, only: new_rigging
  use davit_rigging_winch, only: winch_passage
  use davit_solve_integrator, only: integrator_type
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  use davit_rigging_sling_chain, only: sling_chain_type, new_sling_chain
  use davit_rigging_sling_start, only: lay_out_sling, pendulum_velocity, check_start_residual
  use rigging_fixture, only: nl, boat_mass, weight, cg0, hooks_b, ship_c, ship0, &
                             hanging_problem, make_config, setup, hooks, tensions, &
                             static_tension, new_rk4, energy_case, perturb
  implicit none
  private
  public :: collect_rigging

contains

  function collect_rigging() result(suite)
    type(suite_type) :: suite
    suite%name = "rigging"
    suite%cases = [new_case("dof_count_F1", dof_count), &
                   new_case("statics_W4_A6", statics), &
                   new_case("ship_pose_moves_davit", ship_pose), &
                   new_case("kane_blocks_lump_weight_bearing_friction", kane_blocks), &
                   new_case("initial_state_rejects_misplaced_head", misplaced_head), &
                   new_case("unstretched_start_settles_fig13_F2", settle), &
                   new_case("gearing_A7", gearing), &
                   new_case("energy_conservation_A8", energy_conservation), &
                   new_case("cable_length_conservation_and_payout", cable_length), &
                   new_case("bounce_frequency_A10", bounce), &
                   new_case("friction_while_lowering", friction), &
                   new_case("sling_start_hanging_chain", sling_start_chain)]
  end function collect_rigging

  ! ---------------------------------------------------------------- tests

  !> F1: the paper counts 6 (boat) + 6 (ship) + m (sheave and drum rotations) + 6n + 6 (3
  !> translations per lump, n per sling, and per movable block) = 6n + m + 18. Our rigging
  !> carries 6n lump + 6 block translations + ns sheave rotations + 1 drum passage; with the
  !> paper's layout (reeving A: lead, 2 fore-head, 1 aft-head and 2 block sheaves, ns = 6,
  !> plus the drum: m = 7) its DOFs + 12 must equal 6n + m + 18. Each DOF has a coordinate
  !> and a speed except the speed-controlled drum (passage only).
  subroutine dof_count(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    real(wp), allocatable :: y(:)
    real(wp) :: res
    integer :: i, n
    character(len=1) :: digit
    integer, parameter :: lumps(3) = [0, 2, 3]
    do i = 1, size(lumps)
      n = lumps(i)
      write (digit, "(i1)") n
      call setup(p, "sheaves = 'rotating', lumps = "//digit, y, state, res)
      call check(state, real(p%rig%ndof + 12, wp), real(6*n + 7 + 18, wp), "6n+m+18, A, n="//digit)
      call check(state, real(p%rig%nstate, wp), real(2*(p%rig%ndof - 1) + 1, wp), "nstate")
      call setup(p, "reeving = 'b', sheaves = 'rotating', lumps = "//digit, y, state, res)
      call check(state, real(p%rig%ndof + 12, wp), real(6*n + 7 + 18, wp), "6n+m+18, B")
      call setup(p, "sheaves = 'quasi_static', lumps = "//digit, y, state, res)
      call check(state, real(p%rig%ndof + 12, wp), real(6*n + 1 + 18, wp), "QS: m = drum")
    end do
    call note(state, "dof (A, rotating, n=3) + boat + ship", real(6*3 + 7 + 18, wp))
  end subroutine dof_count

  !> A6: in the equilibrium start every cable part carries (W/2 + m_b g + n m_p g)/(2 cos a)
  !> (= W/4 plus block and sling weights), every sling segment W/2 plus the lumps below the
  !> hook... above it, and nothing moves over 1 s of coupled integration (1e-6 relative).
  subroutine statics(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: decks(4) = [character(len=48) :: &
      "sheaves = 'rotating', lumps = 2", "sheaves = 'quasi_static', lumps = 0", &
      "reeving = 'b', sheaves = 'rotating', lumps = 1", "reeving = 'b', lumps = 0"]
    !> RK4 steps inside the stable limits of review §4.1 (lumps need the smallest).
    real(wp), parameter :: dts(4) = [5.0e-5_wp, 2.0e-4_wp, 1.0e-4_wp, 2.0e-4_wp]
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:), y0(:), f(:)
    real(wp) :: res, t, t_exp, worst
    integer :: i, k
    do i = 1, size(decks)
      call setup(p, "head_spacing = 0, sling_damping = 0, drum_speed = 0"//nl// &
                 trim(decks(i)), y, state, res)
      call check(state, res, 0.0_wp, "block force residual "//trim(decks(i)), abs_tol=1.0e-12_wp)
      t_exp = static_tension(p)
      f = tensions(p, 0.0_wp, y)
      call check(state, maxval(abs(f - t_exp))/t_exp, 0.0_wp, "t=0 parts = T "// &
                 trim(decks(i)), abs_tol=1.0e-9_wp)
      y0 = y
      call new_rk4(size(y), rk)
      t = 0.0_wp
      worst = 0.0_wp
      do k = 1, nint(1.0_wp/dts(i))
        call rk%step(p, t, y, dts(i))
        if (mod(k, 100) == 0) worst = max(worst, maxval(abs(tensions(p, t, y) - t_exp))/t_exp)
      end do
      call check(state, worst, 0.0_wp, "1 s: parts = T "//trim(decks(i)), abs_tol=1.0e-6_wp)
      call check(state, maxval(abs(y(1:12) - y0(1:12))), 0.0_wp, "boat at rest", &
                 abs_tol=1.0e-9_wp)
      if (i == 1) then
        call note(state, "W/4 [N]", 0.25_wp*weight)
        call note(state, "T expected, A rotating n=2 [N]", t_exp)
        call note(state, "T model [N]", f(3))
        call note(state, "max rel deviation over 1 s", worst)
      end if
    end do
  end subroutine statics

  !> Fixed sheaves and drum move with the ship: ship and boat both 0.5 m higher and 1 m
  !> forward give the same equilibrium (zero rigging accelerations); with the ship then
  !> rolled by 0.1 rad the rigging is no longer in equilibrium.
  subroutine ship_pose(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    real(wp), allocatable :: y(:), dydt(:)
    real(wp) :: hook_pos(3, 2), hook_vel(3, 2), c(3, 3), fh(3, 2), res, sr(3), sc(3, 3)
    real(wp) :: hook_force(3, 2)
    type(error_type), allocatable :: error
    sr = [1.0_wp, 0.0_wp, -0.5_wp]
    call setup(p, "sheaves = 'rotating', lumps = 1", y, state, res)
    y(4:6) = y(4:6) + sr
    call hooks(y, hook_pos, hook_vel, c)
    hook_force = 0.0_wp
    hook_force(3, :) = -0.5_wp*weight
    call p%rig%initial_state(hook_pos, hook_force, pose_type(sr, ship_c, ship0%v, ship0%w), &
                             y(13:), res, error)
    call check_true(state, .not. allocated(error), "initial equilibrium with moved ship")
    call check(state, res, 0.0_wp, "residual with moved ship", abs_tol=1.0e-12_wp)
    allocate (dydt(p%rig%nstate))
    call p%rig%rhs(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, &
                   pose_type(sr, ship_c, ship0%v, ship0%w)), dydt, fh)
    call check(state, maxval(abs(dydt(p%rig%lumps%u(1):p%rig%drum%q(1) - 1))), 0.0_wp, &
               "rigging at rest with moved ship", abs_tol=1.0e-6_wp)
    call check(state, sum(fh(3, :)), -weight, "hooks carry W", rel_tol=1.0e-9_wp)
    sc = rotation_matrix([0.1_wp, 0.0_wp, 0.0_wp])
    call p%rig%rhs(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, &
                   pose_type(sr, sc, ship0%v, ship0%w)), dydt, fh)
    call check_true(state, maxval(abs(dydt(p%rig%blocks%u(1):p%rig%blocks%u(2)))) > 1.0_wp, &
                    "rolled ship moves the blocks")
  end subroutine ship_pose

  !> The rigging's Kane blocks (eqs. 53-54, 87), by hand. A lump at rest, pulled 2 cm
  !> sideways off its equilibrium (~1 kN of net segment force against ~20 N of weight, so
  !> a lost or flipped weight is 1e4 times the tolerance), feels its two segments' spring forces,
  !> -T1 e1 + T2 e2 (T = k (D - l0), e along the sling upwards), plus its own weight
  !> +m_p g N3 (z down): F = that, V = m_p, W phi = 0. A sheave turning at omega feels the
  !> cable torque and the bearing's regularised Coulomb moment, which opposes the rotation:
  !> F = torque - M_f tanh(omega/omega_f) (omega_f = 0.01 rad/s), V = I, W phi = 0; the
  !> torque is the same rigging's F without bearing friction.
  subroutine kane_blocks(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: mf = 20.0_wp, omega_f = 1.0e-2_wp
    real(wp), parameter :: omega(2) = [0.02_wp, -0.005_wp]
    type(hanging_problem) :: p, p0
    real(wp), allocatable :: y(:), y0(:), dydt(:), kane(:, :), kane0(:, :)
    real(wp) :: res, hook_pos(3, 2), hook_vel(3, 2), c(3, 3), fh(3, 2), r1(3), br(3, 2)
    real(wp) :: d1(3), d2(3), f_exp(3)
    integer :: iv, iom
    call setup(p, "sheaves = 'rotating', lumps = 1, sling_damping = 0, bearing_friction = 20", &
               y, state, res)
    call setup(p0, "sheaves = 'rotating', lumps = 1, sling_damping = 0", y0, state, res)
    associate (rig => p%rig)
      ! lump 1 of sling 1 moved off its equilibrium; two sheaves set turning
      y(12 + rig%lumps%q(1):12 + rig%lumps%q(1) + 2) = &
        y(12 + rig%lumps%q(1):12 + rig%lumps%q(1) + 2) + [0.0_wp, 0.02_wp, 0.0_wp]
      y(12 + rig%sheaves%u(1):12 + rig%sheaves%u(1) + 1) = omega
      y0 = y
      call hooks(y, hook_pos, hook_vel, c)
      allocate (dydt(rig%nstate), kane(3, rig%nstate), kane0(3, rig%nstate))
      kane = 0.0_wp
      call rig%kane_blocks(0.0_wp, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), dydt, &
                           kane, fh)
      call p0%rig%kane_blocks(0.0_wp, y0(13:), falls_ends_type(hook_pos, hook_vel, ship0), dydt, &
                              kane0, fh)
      r1 = y(12 + rig%lumps%q(1):12 + rig%lumps%q(1) + 2)
      br = rig%block_positions(y(13:))
      d1 = r1 - hook_pos(:, 1)
      d2 = br(:, 1) - r1
      f_exp = -rig%sling%k_seg*(norm2(d1) - rig%sling%l0_seg)*d1/norm2(d1) + &
              rig%sling%k_seg*(norm2(d2) - rig%sling%l0_seg)*d2/norm2(d2)
      f_exp(3) = f_exp(3) + rig%sling%m_lump*gravity
      iv = rig%lumps%u(1)
      call check(state, maxval(abs(kane(kane_f, iv:iv + 2) - f_exp))/norm2(f_exp), 0.0_wp, &
                 "lump F = segment forces + m_p g N3", abs_tol=1.0e-9_wp)
      call check(state, kane(kane_v, iv), rig%sling%m_lump, "lump V = m_p", rel_tol=0.0_wp)
      call check(state, maxval(abs(kane(kane_w_phi, iv:iv + 2))), 0.0_wp, "lump W phi = 0", &
                 abs_tol=0.0_wp)
      iom = rig%sheaves%u(1)
      call check(state, kane(kane_f, iom) - kane0(kane_f, iom), -mf*tanh(omega(1)/omega_f), &
                 "sheave turning forwards: F = torque - M_f tanh(omega/omega_f)", &
                 rel_tol=1.0e-9_wp)
      call check(state, kane(kane_f, iom + 1) - kane0(kane_f, iom + 1), &
                 -mf*tanh(omega(2)/omega_f), "sheave turning backwards: bearing opposes", &
                 rel_tol=1.0e-9_wp)
      call check_true(state, kane(kane_f, iom + 1) > kane0(kane_f, iom + 1), &
                      "backwards: friction raises F")
      call check(state, kane(kane_v, iom), rig%sheave_inertia, "sheave V = I", rel_tol=0.0_wp)
      call check(state, kane(kane_w_phi, iom), 0.0_wp, "sheave W phi = 0", abs_tol=0.0_wp)
    end associate
  end subroutine kane_blocks

  !> A fore davit head 2.5 m to the side of its hook (4 m above it) has the falls pull
  !> some 40 deg off the block's vertical load (the block hangs on its 1 m sling, 3 m below
  !> the head): the one tension of reeving A, fitted to both blocks, leaves most of block
  !> 1's load unbalanced (residual ~0.7, beyond 0.2), and initial_state reports an error
  !> instead of starting the run off its equilibrium.
  subroutine misplaced_head(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    type(rigging_config) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: y(100), hook_pos(3, 2), hook_force(3, 2), res
    call make_config("head_fore = 4.6, 15.8, -20.55", cfg, state)
    call new_rigging(p%rig, cfg, error)
    call check_true(state, .not. allocated(error), "rigging built")
    hook_pos(:, 1) = cg0 + hooks_b(:, 1)
    hook_pos(:, 2) = cg0 + hooks_b(:, 2)
    hook_force = 0.0_wp
    hook_force(3, :) = -0.5_wp*weight
    call p%rig%initial_state(hook_pos, hook_force, ship0, y(1:p%rig%nstate), res, error)
    call check_true(state, allocated(error), "misplaced head reported")
    call check_true(state, res > 0.2_wp, "residual beyond 0.2")
    call note(state, "residual", res)
  end subroutine misplaced_head

  !> Fig. 13 / F2: from an unstretched start (option A, rotating sheaves, n = 0, default
  !> cable dashpots 1e4 N s/m per segment, G26) the tension overshoots, then settles; mean
  !> over [3, 8] s = W/4 (+ block weight) within 5 %, all sections agree within 2 % after
  !> 3 s, and the settling time into a 5 % band is 2.5 +- 1.5 s (F2).
  subroutine settle(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:), f(:), mean(:)
    real(wp) :: res, t, dt, t_exp, peak, t_settle, dev3, devm
    integer :: k, nmean
    call setup(p, "sheaves = 'rotating', lumps = 0, drum_speed = 0", y, state, res, &
               mode="unstretched")
    call setup(p, "sheaves = 'rotating', lumps = 0, drum_speed = 0", y, state, res)
    t_exp = static_tension(p)
    call setup(p, "sheaves = 'rotating', lumps = 0, drum_speed = 0", y, state, res, &
               mode="unstretched")
    call check(state, maxval(tensions(p, 0.0_wp, y)), 0.0_wp, "unstretched at t=0", &
               abs_tol=1.0e-9_wp)
    call new_rk4(size(y), rk)
    dt = 2.0e-4_wp
    t = 0.0_wp
    allocate (mean(p%rig%nseg))
    mean = 0.0_wp
    nmean = 0
    peak = 0.0_wp
    t_settle = 0.0_wp
    dev3 = 0.0_wp
    devm = 0.0_wp
    do k = 1, nint(8.0_wp/dt)
      call rk%step(p, t, y, dt)
      f = tensions(p, t, y)
      peak = max(peak, maxval(f))
      if (abs(f(4) - t_exp) > 0.05_wp*t_exp) t_settle = t
      if (t > 3.0_wp) then
        dev3 = max(dev3, maxval(abs(f - t_exp))/t_exp)
        devm = max(devm, abs(sum(f)/size(f) - t_exp)/t_exp)
      end if
      if (t > 3.0_wp) then
        mean = mean + f
        nmean = nmean + 1
      end if
    end do
    mean = mean/nmean
    call check(state, sum(mean)/size(mean), t_exp, "mean tension [3,8] s", rel_tol=0.05_wp)
    call check(state, (maxval(mean) - minval(mean))/t_exp, 0.0_wp, "sections agree", &
               abs_tol=0.02_wp)
    call check(state, dev3, 0.0_wp, "every section within 5 % after 3 s", abs_tol=0.05_wp)
    call check(state, t_settle, 2.5_wp, "settling time", abs_tol=1.5_wp)
    call note(state, "expected (W + 2 m_b g)/4 [N]", t_exp)
    call note(state, "mean tension [3,8] s [N]", sum(mean)/size(mean))
    call note(state, "peak/static", peak/t_exp)
    call note(state, "settling time into +-5 % [s]", t_settle)
    call note(state, "max |f - T|/T after 3 s, any segment", dev3)
    call note(state, "max |mean f - T|/T after 3 s", devm)
  end subroutine settle

  !> A7: steady boat lowering speed = v_drum/4 (option A: 4 falling parts on one cable) or
  !> v_drum/2 (option B), within 1 %, measured from the CG height at 4 and 6 s (ramp 1 s);
  !> the drum passage equals the closed-form integral of the speed profile.
  subroutine gearing(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: decks(3) = [character(len=40) :: &
      "reeving = 'a'", "reeving = 'b'", "reeving = 'a', sheaves = 'rotating'"]
    real(wp), parameter :: ratio(3) = [4.0_wp, 2.0_wp, 4.0_wp]
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: res, t, dt, z4, speed
    integer :: i, k
    do i = 1, size(decks)
      call setup(p, trim(decks(i))//", drum_speed = 0.7, ramp_time = 1", y, state, res)
      call new_rk4(size(y), rk)
      dt = 2.0e-4_wp
      t = 0.0_wp
      do k = 1, nint(6.0_wp/dt)
        call rk%step(p, t, y, dt)
        if (k == nint(4.0_wp/dt)) z4 = y(6)
      end do
      speed = (y(6) - z4)/2.0_wp
      call check(state, speed, 0.7_wp/ratio(i), "boat speed "//trim(decks(i)), rel_tol=0.01_wp)
      call check(state, p%rig%paid_out(y(13:)), winch_passage(p%rig%winch, t), &
                 "paid out", abs_tol=1.0e-9_wp)
      call note(state, "boat speed "//trim(decks(i))//" [m/s]", speed)
    end do
  end subroutine gearing

  !> A8: no damping, no friction, drum stopped: total energy (boat + rigging) drifts less
  !> than 1e-6 of |E0| over 100 s (gravity datum: still water) while the boat swings and
  !> pitches. Rotating sheaves with n = 2 lumps at dt = 5e-5 s, and quasi-static sheaves
  !> with n = 0 at dt = 2e-4 s (stable-step table, review §4.1).
  subroutine energy_conservation(state)
    type(case_state), intent(inout) :: state
    call energy_case(state, "sheaves = 'rotating', lumps = 2", 5.0e-5_wp, "rotating n=2")
    call energy_case(state, "sheaves = 'quasi_static', lumps = 0", 2.0e-4_wp, "QS n=0")
  end subroutine energy_conservation

  !> Drum stopped: the unstretched cable length (sum L0_i(0) + s_i - s_(i+1), eq. 66-67) is
  !> conserved while the swinging boat runs cable over the sheaves; paying out, it grows by
  !> exactly the drum passage.
  subroutine cable_length(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: res, t, dt, len0, dev, turn
    integer :: k
    call setup(p, "sheaves = 'rotating', lumps = 0, drum_speed = 0", y, state, res)
    call perturb(p, y)
    len0 = p%rig%unstretched_length(y(13:), 1)
    call new_rk4(size(y), rk)
    dt = 2.0e-4_wp
    t = 0.0_wp
    dev = 0.0_wp
    turn = 0.0_wp
    do k = 1, nint(10.0_wp/dt)
      call rk%step(p, t, y, dt)
      dev = max(dev, abs(p%rig%unstretched_length(y(13:), 1) - len0))
      turn = max(turn, maxval(abs(p%rig%sheave_angles(y(13:)))))
    end do
    call check(state, dev/len0, 0.0_wp, "unstretched length, drum stopped", abs_tol=1.0e-13_wp)
    call check_true(state, turn > 1.0e-4_wp, "sheaves turned")
    call note(state, "largest sheave angle [rad]", turn)
    call setup(p, "sheaves = 'rotating', lumps = 0, drum_speed = 0.7", y, state, res)
    len0 = p%rig%unstretched_length(y(13:), 1)
    call new_rk4(size(y), rk)
    t = 0.0_wp
    do k = 1, nint(3.0_wp/dt)
      call rk%step(p, t, y, dt)
    end do
    call check(state, p%rig%unstretched_length(y(13:), 1) - len0, &
               winch_passage(p%rig%winch, t), "grows by the pay-out", abs_tol=1.0e-9_wp)
  end subroutine cable_length

  !> A10: boat bounce on its falls (option B, drum stopped, no damping). Linearised per
  !> fall: M/2 on the sling spring EA/l_s, in series with the block m_b on the cable, whose
  !> two falling parts at half-angle a give k_b = EA (2 cos a)^2/L0_cable. The lower root of
  !> the 2-DOF system must match the period measured from upward zero crossings (10 %).
  subroutine bounce(state)
    type(case_state), intent(inout) :: state
    call bounce_case(state, "reeving = 'b', sheaves = 'quasi_static', lumps = 0", 1.0e-4_wp)
    call bounce_case(state, "reeving = 'b', sheaves = 'rotating', lumps = 2", 5.0e-5_wp)
  end subroutine bounce

  subroutine bounce_case(state, deck, dt)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: deck
    real(wp), intent(in) :: dt
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: res, t, z_eq, prev, first, last, omega, omega_lin, ks, kb, m1, m2, br(3, 2)
    real(wp) :: drop, cosa, bq, ea
    integer :: k, ncross
    call setup(p, deck//", drum_speed = 0, sling_damping = 0, cable_damping = 0", y, state, res)
    z_eq = y(6)
    br = p%rig%block_positions(y(13:))
    drop = br(3, 1) + 20.55_wp
    cosa = drop/hypot(drop, 0.16_wp)
    ea = p%rig%cables(1)%ea
    ks = ea/1.0_wp
    kb = ea*(2.0_wp*cosa)**2/p%rig%unstretched_length(y(13:), 1)
    m1 = 0.5_wp*boat_mass
    m2 = p%rig%block_mass
    bq = ks*m2 + (ks + kb)*m1
    omega_lin = sqrt((bq - sqrt(bq**2 - 4.0_wp*m1*m2*ks*kb))/(2.0_wp*m1*m2))
    y(12) = 0.01_wp
    call new_rk4(size(y), rk)
    t = 0.0_wp
    prev = 0.0_wp
    ncross = 0
    do k = 1, nint(1.0_wp/dt)
      call rk%step(p, t, y, dt)
      if (prev < 0.0_wp .and. y(6) - z_eq >= 0.0_wp) then
        last = t - dt*(y(6) - z_eq)/(y(6) - z_eq - prev)
        if (ncross == 0) first = last
        ncross = ncross + 1
      end if
      prev = y(6) - z_eq
    end do
    omega = 2.0_wp*acos(-1.0_wp)*(ncross - 1)/(last - first)
    call check(state, omega, omega_lin, "bounce omega "//deck, rel_tol=0.1_wp)
    call note(state, "bounce omega measured [rad/s] "//deck, omega)
    call note(state, "bounce omega linearised [rad/s]", omega_lin)
  end subroutine bounce_case

  !> Friction while lowering (option B, steady pay-out, means over [4, 6] s):
  !> quasi-static sheaves with ratio rho: the load side pulls the cable over each sheave,
  !> so the block parts carry f4 = rho f3 with f3 + f4 = (W/2 + m_b g)/cos a, and the drum
  !> pull is f1 = f3/rho^2. Rotating sheaves with bearing moment M_f: a steadily turning
  !> sheave needs r (f_out - f_in) = M_f, so each sheave adds M_f/r (eq. 71 corrected).
  subroutine friction(state)
    type(case_state), intent(inout) :: state
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:), f(:), mean(:)
    real(wp) :: res, t, dt, load, br(3, 2), drop, cosa
    real(wp), parameter :: rho = 1.05_wp, mf = 20.0_wp
    integer :: k, nmean, i
    do i = 1, 2
      if (i == 1) then
        call setup(p, "reeving = 'b', friction_ratio = 1.05", y, state, res)
      else
        call setup(p, "reeving = 'b', sheaves = 'rotating', bearing_friction = 20", y, &
                   state, res)
      end if
      call new_rk4(size(y), rk)
      dt = 2.0e-4_wp
      t = 0.0_wp
      allocate (mean(p%rig%nseg))
      mean = 0.0_wp
      nmean = 0
      do k = 1, nint(6.0_wp/dt)
        call rk%step(p, t, y, dt)
        if (t > 4.0_wp) then
          f = tensions(p, t, y)
          mean = mean + f
          nmean = nmean + 1
        end if
      end do
      mean = mean/nmean
      br = p%rig%block_positions(y(13:))
      drop = br(3, 1) + 20.55_wp
      cosa = drop/hypot(drop, 0.16_wp)
      load = (0.5_wp*weight + p%rig%block_mass*gravity)/cosa
      call check(state, mean(3) + mean(4), load, "block parts carry the load", rel_tol=0.01_wp)
      if (i == 1) then
        call check(state, mean(4)/mean(3), rho, "QS: f4/f3 = rho", rel_tol=1.0e-3_wp)
        call check(state, mean(1)/mean(3), 1.0_wp/rho**2, "QS: drum pull", rel_tol=1.0e-3_wp)
        call note(state, "QS drum pull / load-side part", mean(1)/mean(4))
      else
        call check(state, mean(4) - mean(3), mf/p%rig%sheave_radius, "block sheave M_f/r", &
                   rel_tol=0.02_wp)
        call check(state, mean(2) - mean(1), mf/p%rig%sheave_radius, "guide sheave M_f/r", &
                   rel_tol=0.02_wp)
        call note(state, "rotating: f4 - f3 [N]", mean(4) - mean(3))
        call note(state, "M_f/r [N]", mf/p%rig%sheave_radius)
      end if
      deallocate (mean)
    end do
  end subroutine friction

  !> The start's sling lay-out against the statics of a hanging chain
  !> (davit_rigging_sling_start): hook load W/2 straight up, n = 3 lumps of m_p on a 3 m
  !> sling of EA = 6.3e7 N: segment k carries T_k = W/2 + (k-1) m_p g and is
  !> l0 + T_k/k_seg long, so the block sits L + ((n+1) W/2 + n(n+1)/2 m_p g)/k_seg above
  !> the hook and needs Q = W/2 + n m_p g + m_b g from the cable; without lumps a slanted
  !> load lays the sling along itself, stretched by |F|/k. A rigid pendulum's velocity is
  !> the head's at the head, the hook's at (and beyond) the hook and their mean midway; a
  !> start residual over 0.2 is refused.
  subroutine sling_start_chain(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: ea = 6.3e7_wp, length = 3.0_wp, mu = 2.0_wp, m_b = 50.0_wp
    real(wp), parameter :: hook(3) = [1.0_wp, 2.0_wp, -15.0_wp]
    type(sling_chain_type) :: ch
    type(error_type), allocatable :: error
    real(wp) :: lumps(3, 3), none(3, 0), block(3), q(3), f(3), k, mp, drop, v(3)
    real(wp) :: head(3), vh(3), vk(3)
    integer :: j
    ch = new_sling_chain(3, length, ea, 0.0_wp, mu)
    k = ea/(length/4.0_wp)
    mp = mu*length/4.0_wp
    call lay_out_sling(ch, m_b, hook, [0.0_wp, 0.0_wp, -0.5_wp*weight], .false., lumps, &
                       block, q)
    drop = length + (4.0_wp*0.5_wp*weight + 6.0_wp*mp*gravity)/k
    call check(state, hook(3) - block(3), drop, "block height above the hook", &
               abs_tol=1.0e-12_wp)
    call check(state, hook(3) - lumps(3, 1), length/4.0_wp + 0.5_wp*weight/k, "lump 1 height", &
               abs_tol=1.0e-12_wp)
    call check(state, norm2(block(1:2) - hook(1:2)) + norm2(lumps(1:2, 3) - hook(1:2)), &
               0.0_wp, "chain vertical", abs_tol=1.0e-12_wp)
    call check(state, -q(3), 0.5_wp*weight + 3.0_wp*mp*gravity + m_b*gravity, &
               "cable force Q on the block", abs_tol=1.0e-6_wp)
    call lay_out_sling(ch, m_b, hook, [0.0_wp, 0.0_wp, -0.5_wp*weight], .true., lumps, &
                       block, q)
    call check(state, hook(3) - block(3), length, "unstretched: natural length", &
               abs_tol=1.0e-12_wp)
    ch = new_sling_chain(0, length, ea, 0.0_wp, mu)
    f = [3.0e3_wp, -4.0e3_wp, -12.0e3_wp]
    call lay_out_sling(ch, m_b, hook, f, .false., none, block, q)
    do j = 1, 3
      call check(state, block(j) - hook(j), (length + 13.0e3_wp*length/ea)*f(j)/13.0e3_wp, &
                 "slanted sling along its load", abs_tol=1.0e-12_wp)
    end do
    head = [0.0_wp, 2.0_wp, -20.0_wp]
    vh = [1.0_wp, 0.0_wp, 0.0_wp]
    vk = [0.0_wp, 3.0_wp, 1.0_wp]
    v = pendulum_velocity(head, head, hook, vh, vk)
    call check(state, norm2(v - vh), 0.0_wp, "pendulum: head", abs_tol=1.0e-15_wp)
    v = pendulum_velocity(0.5_wp*(head + hook), head, hook, vh, vk)
    call check(state, norm2(v - 0.5_wp*(vh + vk)), 0.0_wp, "pendulum: midway", &
               abs_tol=1.0e-15_wp)
    v = pendulum_velocity(2.0_wp*hook - head, head, hook, vh, vk)
    call check(state, norm2(v - vk), 0.0_wp, "pendulum: beyond the hook", abs_tol=1.0e-15_wp)
    call check_start_residual(0.19_wp, error)
    call check_true(state, .not. allocated(error), "residual 0.19 accepted")
    call check_start_residual(0.21_wp, error)
    call check_true(state, allocated(error), "residual 0.21 refused")
  end subroutine sling_start_chain

end module test_rigging
