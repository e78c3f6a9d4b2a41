!> Slack rigging (issue 12): the wires' damping (davit_rigging_wire_damping) and the blocks'
!> hook stops (davit_rigging_block_stop). Every expected value comes from the deck's stated
!> inputs (20 mm wire, E = 200 GPa, 1 m sling, 50 kg block, wire damping ratio 0.02, stop
!> 0.3 m above the hook with damping ratio 0.3 and a 1e-4 m onset) and closed forms, never
!> from the code under test.
module test_slack
  use davit_kinds, only: wp, gravity, pi
  use davit_error, only: error_type
  use davit_core_pose, only: pose_type
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_rigging, only: rigging_type, new_rigging
  use davit_rigging_falls_ends, only: falls_ends_type
  use davit_rigging_sling_chain, only: sling_chain_type, chain_forces
  use davit_rigging_block_stop, only: stop_force
  use davit_rigging_cable, only: ramp_factor, ramp_slope
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_solve_factory, only: new_integrator
  use rigging_fixture, only: make_config
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_slack

  !> The stated inputs: axial stiffness EA [N], sling length [m], block mass [kg], wire
  !> damping ratio, stop height [m], its damping ratio and onset [m].
  real(wp), parameter :: ea = 200.0e9_wp*pi*0.02_wp**2/4.0_wp, sling_l = 1.0_wp
  real(wp), parameter :: m_b = 50.0_wp, zeta_w = 0.02_wp
  real(wp), parameter :: stop_h = 0.3_wp, zeta_s = 0.3_wp, onset = 1.0e-4_wp
  real(wp), parameter :: ship_c(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                                                 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  type(pose_type), parameter :: ship0 = pose_type([0.0_wp, 0.0_wp, 0.0_wp], ship_c, &
                                                  [0.0_wp, 0.0_wp, 0.0_wp], &
                                                  [0.0_wp, 0.0_wp, 0.0_wp])
  !> Hooks of a level boat hanging under the default davit heads (G4): 4 m below them.
  real(wp), parameter :: hook0(3, 2) = reshape([4.6_wp, 13.3_wp, -16.55_wp, &
                                                -4.6_wp, 13.3_wp, -16.55_wp], [3, 2])

  !> The rigging alone, its hooks moved by a prescribed motion: hook0 + amp sin(w t).
  type, extends(ode_problem) :: heave_problem
    type(rigging_type) :: rig
    real(wp) :: amp(3) = 0.0_wp, w = 1.0_wp
  contains
    procedure :: rhs => heave_rhs
  end type heave_problem

contains

  function collect_slack() result(suite)
    type(suite_type) :: suite
    suite%name = "slack"
    suite%cases = [new_case("dashpot_coefficients_and_signs", coefficients), &
                   new_case("dropped_block_snatch_and_log_decrement", dropped_block), &
                   new_case("slack_falls_heaving_hooks_massive", heave_massive), &
                   new_case("slack_falls_heaving_hooks_quasi_static", heave_static), &
                   new_case("dashpot_ramp_smooth_step_and_slope", dashpot_ramp)]
  end function collect_slack

  !> Rigging from deck text (defaults for every key not given).
  subroutine make_rigging(text, rig, state)
    character(len=*), intent(in) :: text
    type(rigging_type), intent(out) :: rig
    type(case_state), intent(inout) :: state
    type(rigging_config) :: cfg
    type(error_type), allocatable :: error
    call make_config(text, cfg, state)
    call new_rigging(rig, cfg, error)
    call check_true(state, .not. allocated(error), "rigging built")
  end subroutine make_rigging

  !> Hook positions, velocities and accelerations at t.
  pure subroutine hook_motion(p, t, r, v, a)
    class(heave_problem), intent(in) :: p
    real(wp), intent(in) :: t
    real(wp), intent(out) :: r(3, 2), v(3, 2), a(3, 2)
    integer :: k
    do k = 1, 2
      r(:, k) = hook0(:, k) + p%amp*sin(p%w*t)
      v(:, k) = p%amp*p%w*cos(p%w*t)
      a(:, k) = -p%amp*p%w**2*sin(p%w*t)
    end do
  end subroutine hook_motion

  subroutine heave_rhs(self, t, y, dydt)
    class(heave_problem), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: r(3, 2), v(3, 2), a(3, 2), fh(3, 2)
    call hook_motion(self, t, r, v, a)
    call self%rig%rhs(t, y, falls_ends_type(r, v, ship0), dydt, fh)
  end subroutine heave_rhs

  !> The dashpot's share at stretch e over a ramp of length a is the smooth step
  !> phi = 3 x^2 - 2 x^3, x = e/a clamped to [0, 1]: 0 when slack, 1/2 at mid-ramp, 1 from
  !> e = a on and always 1 with a = 0; its slope is 6 x (1 - x)/a, 3/(2a) at mid-ramp, 0
  !> outside the ramp and with a = 0, and agrees with a central difference of phi inside it
  !> (h = 1e-6 a: truncation 2 (h/a)^2, rounding ~1e-10, relative).
  subroutine dashpot_ramp(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: a = 0.02_wp, h = 1.0e-6_wp*a
    real(wp) :: e, fd
    integer :: i
    call check(state, ramp_factor(-1.0e-3_wp, a), 0.0_wp, "slack: share 0", abs_tol=0.0_wp)
    call check(state, ramp_factor(0.5_wp*a, a), 0.5_wp, "mid-ramp: share 1/2", &
               abs_tol=1.0e-15_wp)
    call check(state, ramp_factor(0.25_wp*a, a), 0.15625_wp, "quarter: 3/16 - 2/64", &
               abs_tol=1.0e-15_wp)
    call check(state, ramp_factor(2.0_wp*a, a), 1.0_wp, "beyond the ramp: share 1", &
               abs_tol=0.0_wp)
    call check(state, ramp_factor(-1.0_wp, 0.0_wp), 1.0_wp, "no ramp: share 1", &
               abs_tol=0.0_wp)
    call check(state, ramp_slope(0.5_wp*a, a), 1.5_wp/a, "mid-ramp slope 3/(2a)", &
               rel_tol=1.0e-14_wp)
    call check(state, ramp_slope(-1.0e-3_wp, a), 0.0_wp, "slack: slope 0", abs_tol=0.0_wp)
    call check(state, ramp_slope(2.0_wp*a, a), 0.0_wp, "beyond: slope 0", abs_tol=0.0_wp)
    call check(state, ramp_slope(0.01_wp, 0.0_wp), 0.0_wp, "no ramp: slope 0", &
               abs_tol=0.0_wp)
    do i = 1, 9
      e = 0.1_wp*real(i, wp)*a
      fd = (ramp_factor(e + h, a) - ramp_factor(e - h, a))/(2.0_wp*h)
      call check(state, ramp_slope(e, a), fd, "slope = d share/de (central difference)", &
                 rel_tol=1.0e-8_wp)
    end do
  end subroutine dashpot_ramp

  !> (c) The dashpots' coefficients and signs. A sling stretched by x = 1 mm whose block
  !> moves away from (towards) the hook at 0.5 m/s carries k x + c 0.5 (k x - c 0.5), with
  !> k = EA/l and c = 2 zeta sqrt(k m_b); given sling_damping = 0 it carries k x. The
  !> cable keeps G26's 1e4 N s/m (above the wire's floor). A block 2 mm into its stop,
  !> closing (opening) at 0.1 m/s, is pushed up by k (d - e/2) + c_s 0.1 (- c_s 0.1),
  !> c_s = 2 zeta_s sqrt(k m_b).
  subroutine coefficients(state)
    type(case_state), intent(inout) :: state
    type(rigging_type) :: rig, rig0
    real(wp) :: k, c, cs, x, f_lump(3, 0), f_top(3), f_hook(3), ten(1), r(3), f(3)
    real(wp), parameter :: zero(3) = 0.0_wp, none(3, 0) = 0.0_wp
    integer :: s
    call make_rigging("", rig, state)
    call make_rigging("sling_damping = 0", rig0, state)
    k = ea/sling_l
    c = 2.0_wp*zeta_w*sqrt(k*m_b)
    x = 1.0e-3_wp
    r = [0.0_wp, 0.0_wp, -(sling_l + x)]
    do s = -1, 1, 2
      call chain_forces(rig%sling, zero, zero, none, none, r, [0.0_wp, 0.0_wp, -0.5_wp*s], &
                        f_lump, f_top, f_hook, ten)
      call check(state, ten(1), k*x + s*c*0.5_wp, "sling k x + c v, sign "// &
                 merge("+", "-", s > 0), rel_tol=1.0e-12_wp)
      call check(state, f_top(3), k*x + s*c*0.5_wp, "pull on the block, down", rel_tol=1.0e-12_wp)
      call chain_forces(rig0%sling, zero, zero, none, none, r, [0.0_wp, 0.0_wp, -0.5_wp*s], &
                        f_lump, f_top, f_hook, ten)
      call check(state, ten(1), k*x, "sling_damping = 0 given: k x", rel_tol=1.0e-12_wp)
    end do
    call check(state, rig%cables(1)%damping, 1.0e4_wp, "cable dashpot (G26)", rel_tol=0.0_wp)
    cs = 2.0_wp*zeta_s*sqrt(k*m_b)
    r = [0.0_wp, 0.0_wp, -(stop_h - 2.0e-3_wp)]
    do s = -1, 1, 2
      f = stop_force(rig%stop, zero, zero, r, [0.0_wp, 0.0_wp, 0.1_wp*s], .true.)
      call check(state, -f(3), k*(2.0e-3_wp - 0.5_wp*onset) + s*cs*0.1_wp, &
                 "stop pushes the block up, sign "//merge("+", "-", s > 0), rel_tol=1.0e-12_wp)
    end do
    call note(state, "sling dashpot 2 zeta sqrt(k m_b) [N s/m]", c)
  end subroutine coefficients

  !> (a) A block on its sling, the hook fixed above it, released from rest with the sling
  !> slack by h = 5 cm. It falls to v0 = sqrt(2 g h) and is snatched: m x'' = m g - k x -
  !> c x' (x the stretch, x(0) = 0, x'(0) = v0), solved in closed form
  !> x = x_s + e^(-zeta w t) (A cos w_d t + B sin w_d t), x_s = m g/k, A = -x_s,
  !> B = (v0 - zeta w x_s)/w_d; the tension F = k x + c x' (it jumps to c v0 at the
  !> snatch) peaks once, then falls to 0 while the block still moves up (the tension-only
  !> clip: F = 0 at x_e = -c x'_e/k > 0) and the block flies free, to come back at
  !> v1 = sqrt(x'_e^2 - 2 g x_e). So each peak is the closed form's at the speed the
  !> last left, and ln(P_i/P_i+1) is the half-cycle decrement of the damping ratio,
  !> ~ pi zeta/sqrt(1 - zeta^2) (a little more: the clip ends the pull early). Integrated
  !> here with RK4 at 1e-6 s (350 steps per block period).
  subroutine dropped_block(state)
    type(case_state), intent(inout) :: state
    type(rigging_type) :: rig
    real(wp), parameter :: h = 0.05_wp, dt = 1.0e-6_wp
    integer, parameter :: npeak = 3
    real(wp) :: peak(npeak), expect(npeak), v, v_next, z, k, c
    integer :: i
    call make_rigging("", rig, state)
    k = ea/sling_l
    c = 2.0_wp*zeta_w*sqrt(k*m_b)
    v = sqrt(2.0_wp*gravity*h)
    do i = 1, npeak
      call snatch(k, c, v, expect(i), v_next)
      v = v_next
    end do
    z = sling_l - h
    call drop(rig%sling, z, dt, peak)
    call check(state, peak(1), expect(1), "first snatch = closed form", rel_tol=1.0e-3_wp)
    call check(state, peak(1), sqrt(2.0_wp*gravity*h)*sqrt(k*m_b), &
               "first snatch ~ v0 sqrt(k m) (1 + O(zeta))", rel_tol=0.05_wp)
    do i = 1, npeak - 1
      call check(state, log(peak(i)/peak(i + 1)), log(expect(i)/expect(i + 1)), &
                 "decrement of peak "//achar(48 + i), rel_tol=0.02_wp)
      call check(state, log(peak(i)/peak(i + 1)), pi*zeta_w/sqrt(1.0_wp - zeta_w**2), &
                 "~ pi zeta/sqrt(1 - zeta^2)", rel_tol=0.25_wp)
    end do
    call note(state, "first snatch [N]", peak(1))
    call note(state, "closed form [N]", expect(1))
    call note(state, "ln(P1/P2)", log(peak(1)/peak(2)))
    call note(state, "closed form ln(P1/P2)", log(expect(1)/expect(2)))
  end subroutine dropped_block

  !> The closed-form snatch (dropped_block) of m_b on k, c at speed v0: the peak tension and
  !> the speed v1 of the next snatch (sampled on 2e5 points of the first half period).
  pure subroutine snatch(k, c, v0, peak, v1)
    real(wp), intent(in) :: k, c, v0
    real(wp), intent(out) :: peak, v1
    integer, parameter :: n = 200000
    real(wp) :: w, zeta, wd, xs, a, b, t, x, xd, f, fmax
    integer :: i
    w = sqrt(k/m_b)
    zeta = c/(2.0_wp*sqrt(k*m_b))
    wd = w*sqrt(1.0_wp - zeta**2)
    xs = m_b*gravity/k
    a = -xs
    b = (v0 - zeta*w*xs)/wd
    fmax = 0.0_wp
    v1 = 0.0_wp
    do i = 0, n
      t = pi/wd*real(i, wp)/real(n, wp)
      x = xs + exp(-zeta*w*t)*(a*cos(wd*t) + b*sin(wd*t))
      xd = exp(-zeta*w*t)*((b*wd - zeta*w*a)*cos(wd*t) - (a*wd + zeta*w*b)*sin(wd*t))
      f = k*x + c*xd
      fmax = max(fmax, f)
      if (f <= 0.0_wp) then
        v1 = sqrt(xd**2 - 2.0_wp*gravity*x)
        exit
      end if
    end do
    peak = fmax
  end subroutine snatch

  !> RK4 of the block hanging at depth z below a fixed hook on the sling's law
  !> (chain_forces), from rest; the largest tension of each of the first snatches.
  subroutine drop(sling, z0, dt, peak)
    type(sling_chain_type), intent(in) :: sling
    real(wp), intent(in) :: z0, dt
    real(wp), intent(out) :: peak(:)
    real(wp) :: s(2), k1(2), k2(2), k3(2), k4(2), f
    integer :: n
    logical :: pulling
    s = [z0, 0.0_wp]
    peak = 0.0_wp
    n = 0
    pulling = .false.
    do while (n <= size(peak))
      k1 = deriv(s)
      k2 = deriv(s + 0.5_wp*dt*k1)
      k3 = deriv(s + 0.5_wp*dt*k2)
      k4 = deriv(s + dt*k3)
      s = s + dt/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
      f = tension(s)
      if (f > 0.0_wp .and. .not. pulling) n = n + 1
      pulling = f > 0.0_wp
      if (pulling .and. n <= size(peak)) peak(n) = max(peak(n), f)
    end do
  contains
    function tension(q) result(t)
      real(wp), intent(in) :: q(2)
      real(wp) :: t, f_lump(3, 0), f_top(3), f_hook(3), ten(1)
      real(wp), parameter :: zero(3) = 0.0_wp, none(3, 0) = 0.0_wp
      call chain_forces(sling, zero, zero, none, none, [0.0_wp, 0.0_wp, q(1)], &
                        [0.0_wp, 0.0_wp, q(2)], f_lump, f_top, f_hook, ten)
      t = ten(1)
    end function tension
    function deriv(q) result(d)
      real(wp), intent(in) :: q(2)
      real(wp) :: d(2)
      d = [q(2), gravity - tension(q)/m_b]
    end function deriv
  end subroutine drop

  !> (b) Slack falls over heaving hooks, massive blocks. The drum has paid out 6 m more
  !> than the unloaded rigging needs (reeving A: the blocks could drop 1.5 m), so the blocks
  !> fall 0.7 m onto their stops and the cable goes slack; the hooks then heave 0.5 m and
  !> sway 0.3 m with a 4 s period (hook speed 0.79 m/s, acceleration 1.2 m/s^2 < g, and
  !> 0.74 m/s^2 across, below the stop's friction mu g = 2.9 m/s^2). The blocks ride their
  !> hooks: the slings stay below the snatch of the block at the hooks' largest speed,
  !> v_h sqrt(k m_b) = 44 kN (without the stop each block would drop through its hook and
  !> be snatched a sling length below it at ~6 m/s: ~340 kN); after 3 periods (hooks at
  !> rest position, accelerating at 0) each block sits 0.3 m above its hook, and the hook
  !> carries its weight m_b g.
  subroutine heave_massive(state)
    type(case_state), intent(inout) :: state
    call heave_case(state, "drum_speed = 0", 2.0e-4_wp, [0.3_wp, 0.0_wp, -0.5_wp])
  end subroutine heave_massive

  !> (b) As heave_massive with quasi-static blocks (their balance includes the stop, so a
  !> block with both its links slack rests on the stop instead of having no balance); no
  !> sideways hook motion (a quasi-static block has no inertia for friction to act on).
  subroutine heave_static(state)
    type(case_state), intent(inout) :: state
    call heave_case(state, "blocks = 'quasi_static', drum_speed = 0", 1.0e-3_wp, &
                    [0.0_wp, 0.0_wp, -0.5_wp])
  end subroutine heave_static

  subroutine heave_case(state, deck, dt, amp)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: deck
    real(wp), intent(in) :: dt, amp(3)
    type(heave_problem) :: p
    class(integrator_type), allocatable :: rk
    type(error_type), allocatable :: error
    real(wp), allocatable :: y(:), dydt(:), seg(:), sl(:, :)
    real(wp) :: t, res, worst, bound, r(3, 2), v(3, 2), a(3, 2), fh(3, 2), br(3, 2), bv(3, 2)
    real(wp) :: lo, hi
    integer :: i
    logical :: solved, finite
    call make_rigging(deck, p%rig, state)
    p%amp = amp
    p%w = 2.0_wp*pi/4.0_wp
    allocate (y(p%rig%nstate), dydt(p%rig%nstate), seg(p%rig%nseg), sl(1, 2))
    call p%rig%initial_state(hook0, 0.0_wp*hook0, ship0, y, res, error)
    call check_true(state, .not. allocated(error), "unloaded rigging's equilibrium")
    y(p%rig%drum%q(1)) = 6.0_wp
    call new_integrator("rk4", size(y), rk, error)
    t = 0.0_wp
    worst = 0.0_wp
    finite = .true.
    lo = huge(1.0_wp)
    hi = -huge(1.0_wp)
    do i = 1, nint(12.0_wp/dt)
      call rk%step(p, t, y, dt)
      call hook_motion(p, t, r, v, a)
      call p%rig%observe(t, y, falls_ends_type(r, v, ship0), seg, sl)
      worst = max(worst, maxval(sl))
      finite = finite .and. all(abs(y) < huge(1.0_wp))
      if (t < 4.0_wp) cycle
      ! the block's offset from its hook along the sway, from the second period on
      call p%rig%block_state(t, y, falls_ends_type(r, v, ship0), br, bv)
      lo = min(lo, br(1, 1) - r(1, 1))
      hi = max(hi, br(1, 1) - r(1, 1))
    end do
    bound = norm2(amp)*p%w*sqrt(ea/sling_l*m_b)
    call check_true(state, finite, "finite state")
    call check_true(state, worst < bound, "largest sling tension below the snatch bound")
    call hook_motion(p, t, r, v, a)
    call p%rig%block_state(t, y, falls_ends_type(r, v, ship0), br, bv, solved)
    call check_true(state, solved, "blocks' balance (or states) valid")
    call p%rig%rhs(t, y, falls_ends_type(r, v, ship0), dydt, fh)
    do i = 1, 2
      call check(state, r(3, i) - br(3, i), stop_h, "block rests on its stop", abs_tol=1.0e-3_wp)
      call check(state, fh(3, i), m_b*(gravity - a(3, i)), "hook carries the block", &
                 rel_tol=0.02_wp)
    end do
    call check(state, maxval(seg), 0.0_wp, "cable slack", abs_tol=0.0_wp)
    ! friction carries the block with the hook's sway (free, it would swing +-0.3 m about
    ! it); the friction's regularisation below v_slip = 0.05 m/s lets it creep by
    ! 2 m_b a_x v_slip/(mu m_b (g - a_z) w) ~ 2 cm
    call check(state, hi - lo, 0.0_wp, "block rides its hook's sway", abs_tol=0.05_wp)
    call note(state, "block's travel along the sway, last 2 periods [m]", hi - lo)
    call note(state, "largest sling tension [N]", worst)
    call note(state, "snatch bound [N]", bound)
  end subroutine heave_case

end module test_slack
