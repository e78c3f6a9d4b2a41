!> The rigging tests' set-up (test_rigging, test_rigging_static, test_block_balance,
!> test_slack): a 6-DOF rigid boat (davit_core_body) of 8500 kg hanging from the two hooks at
!> (+-4.6, 0, -1.55) in b (G4) on the rigging, the ship at rest at the origin, integrated
!> with the project's RK4; and the checks the massive and quasi-static blocks share.
module rigging_fixture
  use davit_kinds, only: wp, gravity
  use davit_error, only: error_type
  use davit_core_rotation, only: rotation_matrix
  use davit_core_pose, only: pose_type
  use davit_rigging_falls_ends, only: falls_ends_type
  use davit_core_body, only: rigid_body_type, body_mass_diagonal, body_w_phi, body_qdot, &
                             body_gravity_force, body_point_force, body_point_velocity, &
                             body_kinetic_energy
  use davit_io_namelist, only: nml_deck, parse_deck
  use davit_io_deck_reader, only: deck_reader_type
  use davit_io_rigging_keys, only: rigging_config, read_rigging
  use davit_rigging_rigging, only: rigging_type, new_rigging
  use davit_solve_integrator, only: ode_problem, integrator_type
  use davit_solve_factory, only: new_integrator
  use harness, only: case_state, check, check_true, note
  implicit none
  private
  public :: nl, boat_mass, weight, cg0, hooks_b, ship_c, ship0, hanging_problem
  public :: make_config, setup, hooks, total_energy, tensions, static_tension, new_rk4
  public :: energy_case, perturb

  character(len=*), parameter :: nl = new_line("a")
  real(wp), parameter :: boat_mass = 8500.0_wp, weight = boat_mass*gravity
  real(wp), parameter :: cg0(3) = [0.0_wp, 13.3_wp, -15.0_wp]
  real(wp), parameter :: hooks_b(3, 2) = reshape([4.6_wp, 0.0_wp, -1.55_wp, &
                                                  -4.6_wp, 0.0_wp, -1.55_wp], [3, 2])
  !> Ship at rest at the origin, ship frame = inertial frame.
  real(wp), parameter :: ship_c(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                                                 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  type(pose_type), parameter :: ship0 = pose_type([0.0_wp, 0.0_wp, 0.0_wp], ship_c, &
                                                  [0.0_wp, 0.0_wp, 0.0_wp], &
                                                  [0.0_wp, 0.0_wp, 0.0_wp])

  !> Boat (y(1:12) = q, u as in davit_system_model) plus the rigging (y(13:)).
  type, extends(ode_problem) :: hanging_problem
    type(rigid_body_type) :: boat
    type(rigging_type) :: rig
  contains
    procedure :: rhs => hanging_rhs
  end type hanging_problem

contains

  !> Rigging config from deck text (defaults for every key not given).
  subroutine make_config(text, cfg, state)
    character(len=*), intent(in) :: text
    type(rigging_config), intent(out) :: cfg
    type(case_state), intent(inout) :: state
    type(nml_deck) :: deck
    type(deck_reader_type) :: r
    type(error_type), allocatable :: error
    call parse_deck("rigging.nml", "&rigging"//nl//text//nl//"/", deck, error)
    if (.not. allocated(error)) then
      call r%init(deck)
      call read_rigging(r, cfg)
      call r%finish(error)
    end if
    call check_true(state, .not. allocated(error), "rigging deck accepted")
    if (allocated(error)) call check_true(state, .false., error%message)
  end subroutine make_config

  !> Problem with the boat level at cg0 (hanging at rest) and the rigging initialised for
  !> hook loads W/2 each; y = [q, u, y_rig].
  subroutine setup(p, text, y, state, residual, mode)
    type(hanging_problem), intent(out) :: p
    character(len=*), intent(in) :: text
    real(wp), allocatable, intent(out) :: y(:)
    type(case_state), intent(inout) :: state
    real(wp), intent(out) :: residual
    character(len=*), intent(in), optional :: mode
    type(rigging_config) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: hook_pos(3, 2), hook_force(3, 2)
    call make_config(text, cfg, state)
    call new_rigging(p%rig, cfg, error)
    call check_true(state, .not. allocated(error), "rigging built")
    p%boat%mass = boat_mass
    p%boat%inertia = [25020.0_wp, 51745.0_wp, 51745.0_wp]
    allocate (y(12 + p%rig%nstate))
    y = 0.0_wp
    y(4:6) = cg0
    hook_pos(:, 1) = cg0 + hooks_b(:, 1)
    hook_pos(:, 2) = cg0 + hooks_b(:, 2)
    hook_force = 0.0_wp
    hook_force(3, :) = -0.5_wp*weight
    call p%rig%initial_state(hook_pos, hook_force, ship0, y(13:), residual, error, mode)
    call check_true(state, .not. allocated(error), "initial equilibrium")
  end subroutine setup

  !> Hook positions and velocities (inertial) of the boat state.
  pure subroutine hooks(y, hook_pos, hook_vel, c)
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: hook_pos(3, 2), hook_vel(3, 2), c(3, 3)
    integer :: a
    c = rotation_matrix(y(1:3))
    do a = 1, 2
      hook_pos(:, a) = matmul(c, y(4:6) + hooks_b(:, a))
      hook_vel(:, a) = matmul(c, body_point_velocity(y(7:12), hooks_b(:, a)))
    end do
  end subroutine hooks

  !> Kane's equations of the boat (eq. 89) with gravity (eq. 13) and the hook forces
  !> (eq. 26), plus the rigging's own derivatives.
  subroutine hanging_rhs(self, t, y, dydt)
    class(hanging_problem), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: hook_pos(3, 2), hook_vel(3, 2), c(3, 3), fh(3, 2), f(6)
    integer :: a
    call hooks(y, hook_pos, hook_vel, c)
    call self%rig%rhs(t, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), dydt(13:), fh)
    f = body_gravity_force(self%boat, c)
    do a = 1, 2
      f = f + body_point_force(hooks_b(:, a), matmul(transpose(c), fh(:, a)))
    end do
    dydt(1:6) = body_qdot(y(1:6), y(7:12))
    dydt(7:12) = (f - body_w_phi(self%boat, y(7:12)))/body_mass_diagonal(self%boat)
  end subroutine hanging_rhs

  !> Boat kinetic + gravity (z down) + rigging energy [J].
  function total_energy(p, y) result(e)
    type(hanging_problem), intent(in) :: p
    real(wp), intent(in) :: y(:)
    real(wp) :: e, hook_pos(3, 2), hook_vel(3, 2), c(3, 3), r(3)
    call hooks(y, hook_pos, hook_vel, c)
    r = matmul(c, y(4:6))
    e = body_kinetic_energy(p%boat, y(7:12)) - boat_mass*gravity*r(3) + &
        p%rig%energy(y(13:), hook_pos, ship0)
  end function total_energy

  !> Cable segment tensions at state y.
  function tensions(p, t, y) result(f)
    type(hanging_problem), intent(in) :: p
    real(wp), intent(in) :: t, y(:)
    real(wp) :: f(p%rig%nseg), sl(p%rig%nlump + 1, 2), hook_pos(3, 2), hook_vel(3, 2)
    real(wp) :: c(3, 3)
    call hooks(y, hook_pos, hook_vel, c)
    call p%rig%observe(t, y(13:), falls_ends_type(hook_pos, hook_vel, ship0), f, sl)
  end function tensions

  !> Static tension per cable part, in closed form: each block hangs on two parts of the
  !> falls and carries W/2 + its weight + its sling's lumps, T = (W/2 + m_b g + n m_p g)/2
  !> (A6). Exact when the parts hang vertical (the decks below set head_spacing = 0); with
  !> the default 0.32 m spacing they lean in by alpha, tan alpha = 0.16/drop, which raises
  !> T by 1/cos(alpha) - 1 < 1e-3 for drops over 3.6 m.
  function static_tension(p) result(t)
    type(hanging_problem), intent(in) :: p
    real(wp) :: t
    t = (0.5_wp*weight + p%rig%block_mass*gravity + &
         p%rig%nlump*p%rig%sling%m_lump*gravity)/2.0_wp
  end function static_tension

  subroutine new_rk4(n, integ)
    integer, intent(in) :: n
    class(integrator_type), allocatable, intent(out) :: integ
    type(error_type), allocatable :: error
    call new_integrator("rk4", n, integ, error)
  end subroutine new_rk4

  subroutine energy_case(state, deck, dt, label)
    type(case_state), intent(inout) :: state
    character(len=*), intent(in) :: deck, label
    real(wp), intent(in) :: dt
    type(hanging_problem) :: p
    class(integrator_type), allocatable :: rk
    real(wp), allocatable :: y(:)
    real(wp) :: res, t, e0, e_static, drift
    integer :: k
    call setup(p, deck//", drum_speed = 0, sling_damping = 0, cable_damping = 0", y, &
               state, res)
    e_static = total_energy(p, y)
    call perturb(p, y)
    e0 = total_energy(p, y)
    call new_rk4(size(y), rk)
    t = 0.0_wp
    drift = 0.0_wp
    do k = 1, nint(100.0_wp/dt)
      call rk%step(p, t, y, dt)
      if (mod(k, 200) == 0) drift = max(drift, abs(total_energy(p, y) - e0))
    end do
    call check(state, drift/abs(e0), 0.0_wp, "energy drift "//label, abs_tol=1.0e-6_wp)
    call note(state, "drift/|E0| "//label, drift/abs(e0))
    call note(state, "drift/(E0 - E_static) "//label, drift/(e0 - e_static))
  end subroutine energy_case

  !> Sway 0.2 m/s, heave 0.01 m/s and pitch 0.01 rad/s of the boat; the blocks and lumps
  !> get the hook velocity scaled by their depth below the davit head, so the chain starts
  !> moving with the pendulum rather than ringing.
  subroutine perturb(p, y)
    type(hanging_problem), intent(in) :: p
    real(wp), intent(inout) :: y(:)
    real(wp) :: hook_pos(3, 2), hook_vel(3, 2), c(3, 3), frac
    integer :: a, k, n, ip
    y(7:12) = [0.0_wp, 0.01_wp, 0.0_wp, 0.0_wp, 0.2_wp, 0.01_wp]
    call hooks(y, hook_pos, hook_vel, c)
    n = p%rig%nlump
    associate (yr => y(13:), rig => p%rig)
      do a = 1, 2
        do k = 1, n
          ! lump k of sling a: 3 entries at the same offset in the lumps' q and u ranges
          ip = 3*n*(a - 1) + 3*(k - 1)
          frac = (yr(rig%lumps%q(1) + ip + 2) + 20.55_wp)/(hook_pos(3, a) + 20.55_wp)
          yr(rig%lumps%u(1) + ip:rig%lumps%u(1) + ip + 2) = frac*hook_vel(:, a)
        end do
        ip = 3*(a - 1)
        frac = (yr(rig%block_r(1) + ip + 2) + 20.55_wp)/(hook_pos(3, a) + 20.55_wp)
        yr(rig%block_v(1) + ip:rig%block_v(1) + ip + 2) = frac*hook_vel(:, a)
      end do
    end associate
  end subroutine perturb

end module rigging_fixture
