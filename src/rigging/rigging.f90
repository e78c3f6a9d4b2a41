!> The rigging sub-model (paper §II.D-E, eqs. 47-82; review §1.6, §1.10, G4-G8, G26): two
!> lumped-mass slings from the movable blocks to the boat hooks, the cable-pulley system
!> (reeving A or B, rotating or quasi-static sheaves) and the speed-controlled winch.
!>
!> It owns its own states and, over its slice of the state, fills its Kane blocks
!> (davit_core_kane: q_dot at its coordinates; V, W phi and F at its speeds) plus the
!> forces on the two boat hooks; the boat and the ship are inputs (hook positions and
!> velocities, ship pose), so the system assembler couples it to any boat model.
!> Everything is inertial (N, z down): lump and block positions and velocities are
!> inertial, which the design allows in place of the paper's boat-frame components
!> (eq. 47); the Kane mass matrix stays diagonal.
!>
!> State layout y_rig (self%layout, parts in this order; n = lumps per sling, ns =
!> rotating sheaves, 0 if quasi-static):
!>   "lumps"    q: lump positions (3, n, 2): sling 1 (fore) lumps 1..n from the hook up,
!>              then sling 2 (aft); u: lump velocities, same layout
!>   "blocks"   q: block positions (3, 2); u: block velocities (massive blocks)
!>   "sheaves"  q: sheave angles [rad]; u: sheave rates [rad/s]
!>   "drum"     q: drum passage s_drum [m] (paid-out length; speed prescribed, no speed)
!> DOFs (F1): 6n (lumps) + 6 (block translations) + ns sheave rotations + 1 drum = 6n + m + 6
!> with m = ns + 1; with the boat's 6 and the ship's 6 this is the paper's 6n + m + 18.
!>
!> Quasi-static blocks (&rigging blocks = 'quasi_static', review §4.3 item 2): a 50 kg block
!> between its ~6e7 N/m sling and the falls bounces at ~200 Hz (|lambda| = 1259 1/s on the
!> III.B deck, RK4 limit 2.25e-3 s), far above anything the boat feels. Dropping the
!> block's inertia (eq. 82; not its weight) removes that mode: each evaluation finds the
!> block positions where gravity (eq. 78), the cable's pull (eqs. 69, 79) and the top sling
!> segment (eqs. 80-81, corrected 63) balance, by Newton on the 6 block coordinates
!> (davit_rigging_block_balance: the elastic balance, then the dashpots' first-order
!> shift). The blocks are then no DOFs (ndof = 6n + m), but the layout keeps their 12
!> slots, all coordinates with prescribed rates: the first 6 (block_r) hold a copy that
!> follows the solved positions (d/dt = v_b + (r_b - y)/follow_time) and is only the
!> Newton start, so the right-hand side stays a function of (t, y); the other 6 (block_v)
!> are unused and have zero derivative. Keeping the weight keeps the statics of the
!> massive model (parts (W/2 + m_b g)/(2 cos a), F2) and keeps the balance well posed:
!> with its sling slack a block hangs in the cable's V under its weight, where a
!> weightless one would have no unique position.
module davit_rigging_rigging
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use davit_kinds, only: wp, gravity, pi
  use davit_error, only: error_type, fatal_error
  use davit_core_pose, only: pose_type
  use davit_rigging_falls_ends, only: falls_ends_type
  use davit_core_kane, only: kane_v, kane_w_phi, kane_f, kane_rates
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_winch, only: winch_speed
  use davit_rigging_sling_chain, only: max_lumps, chain_forces, chain_energy, new_sling_chain
  use davit_rigging_cable, only: max_nodes, cable_eval_type, cable_node_kinematics, &
                                 cable_node_forces
  use davit_rigging_falls, only: falls_type, drive_type, max_sheaves, &
                                 build_reeving, cable_tensions, set_cable_lengths, &
                                 add_cable_energy, cable_unstretched_length, at_rest
  use davit_rigging_block_balance, only: balance_input_type, solve_blocks
  use davit_rigging_wire_damping, only: sling_dashpot, sling_lump_dashpots
  use davit_rigging_block_stop, only: add_stop_forces, stop_energy
  use davit_rigging_sling_start, only: lay_out_sling, pendulum_velocity, check_start_residual
  use davit_rigging_rigging_state, only: rigging_state_type, set_layout
  implicit none
  private
  public :: rigging_type, new_rigging, max_segments, max_sheaves

  integer, parameter :: max_segments = 2*(max_nodes - 1)
  !> Rate scale of the regularised Coulomb bearing moment M_f tanh(omega/omega_f) [rad/s].
  real(wp), parameter :: omega_friction = 1.0e-2_wp
  !> Relaxation time of the block-position copies towards the solved positions [s]: a
  !> decay rate of 10 1/s, slower than every mode of the boat, so it limits no step.
  real(wp), parameter :: follow_time = 0.1_wp
  !> Quasi-static blocks: stretch over which a segment's dashpot tension grows from 0 to
  !> full [m] (cable_type%ramp). With the paper's law a segment going slack drops from
  !> c de/dt to 0 at once; a massless block has no balance across such a jump (a cable
  !> paid out over a slack sling: 3 kN of dashpot tension at zero stretch against 490 N of
  !> block weight), and the dashpots' shift of the blocks would jump with it. 1e-4 m is
  !> ~200 N of the whole cable's elastic tension (quasi-static sheaves), ~2 kN of a 3 m
  !> part, ~6 kN of a 1 m sling: the loaded rigging (~20 kN per part) never sees it.
  real(wp), parameter :: dashpot_ramp = 1.0e-4_wp

  !> The rigging: its parts and state (davit_rigging_rigging_state) with the Kane blocks,
  !> forces, initial state, energy and observations of the whole.
  type, extends(rigging_state_type) :: rigging_type
  contains
    procedure :: kane_blocks => rigging_kane_blocks
    procedure :: rhs => rigging_rhs
    procedure :: initial_state => rigging_initial_state
    procedure :: energy => rigging_energy
    procedure :: observe => rigging_observe
    procedure :: block_state => rigging_block_state
    procedure :: unstretched_length
  end type rigging_type

  !> What one evaluation yields besides the Kane blocks: the forces on the hooks and on the
  !> blocks (weight, slings, cables), the cable segment tensions (cable 1 from the drum,
  !> then cable 2) and the sling segment tensions (column = sling).
  type :: rig_forces_type
    real(wp) :: hook_force(3, 2), block_f(3, 2), seg(max_segments), sl(max_lumps + 1, 2)
  end type rig_forces_type

contains

  !> Build the rigging from its configuration (review G4-G8, G26 defaults).
  subroutine new_rigging(self, cfg, error)
    !> The rigging built.
    type(rigging_type), intent(out) :: self
    !> The &rigging configuration.
    type(rigging_config), intent(in) :: cfg
    !> Set when the configuration gives no consistent rigging.
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: ea, gear
    if (cfg%lumps < 0 .or. cfg%lumps > max_lumps .or. cfg%block_stop >= cfg%sling_length) then
      call fatal_error(error, "rigging: lumps must be 0..20 and block_stop < sling_length")
      return
    end if
    ea = cfg%youngs_modulus*pi*cfg%wire_diameter**2/4.0_wp
    self%rotating = cfg%sheaves == "rotating"
    self%unstretched = cfg%initial == "unstretched"
    self%static_blocks = cfg%blocks == "quasi_static"
    self%reeving = cfg%reeving
    self%nlump = cfg%lumps
    self%sling = new_sling_chain(cfg%lumps, cfg%sling_length, ea, sling_dashpot(cfg, ea), &
                                 cfg%sling_mass_per_length)
    call sling_lump_dashpots(cfg, self%sling)
    self%block_mass = cfg%block_mass
    self%sheave_radius = cfg%sheave_radius
    self%sheave_inertia = cfg%sheave_inertia
    self%drum_radius = cfg%drum_radius
    self%bearing_friction = cfg%bearing_friction
    self%friction_ratio = cfg%friction_ratio
    ! Kinematic gearing (§1.12): A has 4 falling parts on one cable, B 2 per wire.
    gear = merge(4.0_wp, 2.0_wp, cfg%reeving == "a")
    self%winch%speed = cfg%drum_speed
    if (cfg%winch_mode == "boat") self%winch%speed = gear*cfg%lowering_speed
    self%winch%t_start = cfg%winch_start
    self%winch%t_ramp = cfg%ramp_time
    self%winch%t_stop = cfg%stop_time
    self%winch%t_brake = cfg%brake_time
    call build_reeving(self%falls_type, cfg, ea)
    if (self%static_blocks) then
      self%sling%ramp = dashpot_ramp
      self%cables%ramp = dashpot_ramp
    end if
    call set_layout(self)
  end subroutine new_rigging

  !> Kane blocks of the rigging over its own slice y (size nstate) for given hook
  !> kinematics and ship pose: dydt at the coordinates (kinematic relations: lump and
  !> massive block positions move at their velocities, eq. 51; quasi-static block copies
  !> follow the solved blocks, NaN where the balance failed, unused slots 0; sheave angles
  !> at their rates, eq. 77; the drum at the winch speed) and kane(kane_v / kane_w_phi /
  !> kane_f, i) at every speed i: lumps m_p, 0, segment forces + m_p g N3 (eqs. 53-54,
  !> 59-65); massive blocks m_b, 0, cable + sling + weight (eqs. 73, 78-81); sheaves I, 0,
  !> torque - M_f tanh(omega/omega_f) (eqs. 71, 87). Also the forces ON the two boat hooks
  !> (inertial components).
  pure subroutine rigging_kane_blocks(self, t, y, ends, dydt, kane, hook_force)
    !> The rigging.
    class(rigging_type), intent(in) :: self
    !> Time [s] and the rigging's own state slice.
    real(wp), intent(in) :: t, y(:)
    !> The falls' ends: the hooks' positions and velocities, the ship's pose.
    type(falls_ends_type), intent(in) :: ends
    !> Time derivative of the rigging's states (kinematic rows set); the Kane blocks (mass and
    !> force rows).
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    !> Forces on the two boat hooks (3, hook), inertial [N].
    real(wp), intent(out) :: hook_force(3, 2)
    type(rig_forces_type) :: out
    call evaluate(self, t, y, ends, dydt, kane, out)
    hook_force = out%hook_force
  end subroutine rigging_kane_blocks

  !> Time derivative of the rigging states (kane_blocks, then eq. 89 by kane_rates) and
  !> the forces ON the two boat hooks.
  pure subroutine rigging_rhs(self, t, y, ends, dydt, hook_force)
    !> The rigging.
    class(rigging_type), intent(in) :: self
    !> Time [s] and the rigging's own state slice.
    real(wp), intent(in) :: t, y(:)
    !> The falls' ends: the hooks' positions and velocities, the ship's pose.
    type(falls_ends_type), intent(in) :: ends
    !> Time derivative of the rigging's states.
    real(wp), intent(inout) :: dydt(:)
    !> Forces on the two boat hooks (3, hook), inertial [N].
    real(wp), intent(out) :: hook_force(3, 2)
    real(wp) :: kane(3, self%nstate)
    call self%kane_blocks(t, y, ends, dydt, kane, hook_force)
    call kane_rates(self%layout, kane, dydt)
  end subroutine rigging_rhs

  !> Segment tensions [N] (cable 1 segments from the drum, then cable 2) and sling segment
  !> tensions (segment k above lump k-1, k = 1 at the hook; column = sling).
  pure subroutine rigging_observe(self, t, y, ends, seg_tension, sling_tension)
    !> The rigging.
    class(rigging_type), intent(in) :: self
    !> Time [s] and the rigging's own state slice.
    real(wp), intent(in) :: t, y(:)
    !> The falls' ends: the hooks' positions and velocities, the ship's pose.
    type(falls_ends_type), intent(in) :: ends
    !> Cable segment tensions [N]; sling segment tensions (segment, sling) [N].
    real(wp), intent(out) :: seg_tension(self%nseg), sling_tension(self%nlump + 1, 2)
    real(wp) :: dydt(self%nstate), kane(3, self%nstate)
    type(rig_forces_type) :: out
    call evaluate(self, t, y, ends, dydt, kane, out)
    seg_tension = out%seg(1:self%nseg)
    sling_tension = out%sl(1:self%nlump + 1, :)
  end subroutine rigging_observe

  !> The rigging's Kane blocks and forces (kane_blocks, observe).
  pure subroutine evaluate(self, t, y, ends, dydt, kane, out)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    type(falls_ends_type), intent(in) :: ends
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    type(rig_forces_type), intent(out) :: out
    real(wp) :: torque(max_sheaves), br(3, 2), bv(3, 2)
    type(drive_type) :: drive
    logical :: solved
    drive = rigging_drive(self, y, winch_speed(self%winch, t))
    br(:, 1) = y(self%block_r(1):self%block_r(1) + 2)
    br(:, 2) = y(self%block_r(1) + 3:self%block_r(2))
    bv(:, 1) = y(self%block_v(1):self%block_v(1) + 2)
    bv(:, 2) = y(self%block_v(1) + 3:self%block_v(2))
    solved = .true.
    if (self%static_blocks) then
      call solve_blocks(self%falls_type, balance_input(self, y, ends%hook_pos, ends%hook_vel, &
                        drive), ends%ship, br, bv, solved)
    end if
    out%seg = 0.0_wp
    out%sl = 0.0_wp
    out%block_f = 0.0_wp
    out%block_f(3, :) = self%block_mass*gravity
    call lump_kane(self, y, ends%hook_pos, ends%hook_vel, br, bv, dydt, kane, out)
    call add_stop_forces(self%stop, ends%hook_pos, ends%hook_vel, br, bv, &
                         .not. self%static_blocks, out%block_f, out%hook_force)
    torque = 0.0_wp
    call cable_forces(self, drive, br, bv, ends%ship, out%block_f, torque, out%seg)
    call block_kane(self, y, br, bv, solved, out%block_f, dydt, kane)
    call sheave_kane(self, y, torque, dydt, kane)
    dydt(self%drum%q(1)) = drive%v_drum
  end subroutine evaluate

  !> The winch and sheave states at y with the drum paying out at v_drum.
  pure function rigging_drive(self, y, v_drum) result(drive)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), v_drum
    type(drive_type) :: drive
    integer :: ns
    ns = self%nsheave
    drive%s_drum = y(self%drum%q(1))
    drive%v_drum = v_drum
    drive%theta(1:ns) = y(self%sheaves%q(1):self%sheaves%q(2))
    drive%omega(1:ns) = y(self%sheaves%u(1):self%sheaves%u(2))
  end function rigging_drive

  !> The quasi-static balance's inputs from the rigging: the lower end of each sling's top
  !> segment (the hook with no lumps, else the top lump n) and its velocity, and the drive.
  pure function balance_input(self, y, hook_pos, hook_vel, drive) result(inp)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), hook_pos(3, 2), hook_vel(3, 2)
    type(drive_type), intent(in) :: drive
    type(balance_input_type) :: inp
    integer :: a, n, il(2), iv(2)
    n = self%nlump
    inp%drive = drive
    inp%low_r = hook_pos
    inp%low_v = hook_vel
    inp%hook_r = hook_pos
    inp%hook_v = hook_vel
    if (n == 0) return
    do a = 1, 2
      il = sling_range(self%lumps%q, n, a)
      iv = sling_range(self%lumps%u, n, a)
      inp%low_r(:, a) = y(il(2) - 2:il(2))
      inp%low_v(:, a) = y(iv(2) - 2:iv(2))
    end do
  end function balance_input

  !> Lumps (eqs. 51, 53-54, 59-65): positions move at their velocities; V = m_p, W phi = 0
  !> and F = the segments' forces + the lump's weight m_p g N3 (z down). Adds the top
  !> segments' pull to out%block_f and sets the hook forces and sling tensions.
  pure subroutine lump_kane(self, y, hook_pos, hook_vel, br, bv, dydt, kane, out)
    ! 9 arguments: the chain between the hooks (hook_pos, hook_vel) and the blocks (br,
    ! bv), the state, and the three results it fills (dydt, kane, out).
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), hook_pos(3, 2), hook_vel(3, 2), br(3, 2), bv(3, 2)
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    type(rig_forces_type), intent(inout) :: out
    real(wp) :: f_top(3), f_lump(3, max_lumps)
    integer :: a, k, n, il(2), iv(2)
    n = self%nlump
    do a = 1, 2
      il = sling_range(self%lumps%q, n, a)
      iv = sling_range(self%lumps%u, n, a)
      call chain_forces(self%sling, hook_pos(:, a), hook_vel(:, a), y(il(1):il(2)), &
                        y(iv(1):iv(2)), br(:, a), bv(:, a), f_lump(:, 1:n), f_top, &
                        out%hook_force(:, a), out%sl(1:n + 1, a))
      do k = 1, n
        f_lump(3, k) = f_lump(3, k) + self%sling%m_lump*gravity
      end do
      dydt(il(1):il(2)) = y(iv(1):iv(2))
      kane(kane_v, iv(1):iv(2)) = self%sling%m_lump
      kane(kane_w_phi, iv(1):iv(2)) = 0.0_wp
      do k = 1, n
        kane(kane_f, iv(1) + 3*(k - 1):iv(1) + 3*k - 1) = f_lump(:, k)
      end do
      out%block_f(:, a) = out%block_f(:, a) + f_top
    end do
  end subroutine lump_kane

  !> Blocks. Massive (eqs. 73, 78-81): positions move at their velocities; V = m_b,
  !> W phi = 0, F = block_f. Quasi-static: block_f is the balance's residual (~0); the
  !> copies follow the solved blocks br moving at bv. A balance that fails to converge
  !> poisons them, so the driver's finiteness check stops the run naming a rigging state
  !> instead of going on with wrong forces.
  pure subroutine block_kane(self, y, br, bv, solved, block_f, dydt, kane)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), br(3, 2), bv(3, 2), block_f(3, 2)
    logical, intent(in) :: solved
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    integer :: a, i
    if (self%static_blocks) then
      do a = 1, 2
        i = self%block_r(1) + 3*(a - 1)
        dydt(i:i + 2) = bv(:, a) + (br(:, a) - y(i:i + 2))/follow_time
      end do
      if (.not. solved) dydt(self%block_r(1):self%block_r(2)) = &
        ieee_value(0.0_wp, ieee_quiet_nan)
      dydt(self%block_v(1):self%block_v(2)) = 0.0_wp
    else
      dydt(self%block_r(1):self%block_r(2)) = y(self%block_v(1):self%block_v(2))
      kane(kane_v, self%block_v(1):self%block_v(2)) = self%block_mass
      kane(kane_w_phi, self%block_v(1):self%block_v(2)) = 0.0_wp
      kane(kane_f, self%block_v(1):self%block_v(1) + 2) = block_f(:, 1)
      kane(kane_f, self%block_v(1) + 3:self%block_v(2)) = block_f(:, 2)
    end if
  end subroutine block_kane

  !> Rotating sheaves (eqs. 71, 77, 87): angles move at their rates; V = I, W phi = 0,
  !> F = cable torque - M_f tanh(omega/omega_f) (the bearing's regularised Coulomb moment
  !> opposes the rotation).
  pure subroutine sheave_kane(self, y, torque, dydt, kane)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), torque(max_sheaves)
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    integer :: ns
    ns = self%nsheave
    if (ns == 0) return
    associate (omega => y(self%sheaves%u(1):self%sheaves%u(2)), u => self%sheaves%u)
      dydt(self%sheaves%q(1):self%sheaves%q(2)) = omega
      kane(kane_v, u(1):u(2)) = self%sheave_inertia
      kane(kane_w_phi, u(1):u(2)) = 0.0_wp
      kane(kane_f, u(1):u(2)) = torque(1:ns) - self%bearing_friction*tanh(omega/omega_friction)
    end associate
  end subroutine sheave_kane

  !> Cable forces on the blocks, sheave torques and segment tensions of every cable, with
  !> the blocks at br moving at bv.
  pure subroutine cable_forces(self, drive, br, bv, ship, block_f, torque, seg)
    type(rigging_type), intent(in) :: self
    type(drive_type), intent(in) :: drive
    real(wp), intent(in) :: br(3, 2), bv(3, 2)
    type(pose_type), intent(in) :: ship
    real(wp), intent(inout) :: block_f(3, 2), torque(max_sheaves), seg(max_segments)
    real(wp) :: p(3, max_nodes), v(3, max_nodes)
    type(cable_eval_type) :: ce
    integer :: c, k, nseg
    k = 0
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        nseg = cab%nnode - 1
        call cable_node_kinematics(cab, ship, br, bv, p, v)
        call cable_tensions(self%falls_type, cab, c, drive, p, v, ce)
        call cable_node_forces(cab, ce%lam, ce%f, ce%g, self%sheave_radius, block_f, torque)
        seg(k + 1:k + nseg) = ce%f(1:nseg)
        k = k + nseg
      end associate
    end do
  end subroutine cable_forces

  !> Block positions and velocities (3, block), inertial: the states for massive blocks;
  !> for quasi-static blocks the solved balance at this state (the copies in y are only the
  !> start). solved is .false. if the balance did not converge; iterations: Newton's
  !> balance evaluations; residual: the elastic force left on a block [N].
  pure subroutine rigging_block_state(self, t, y, ends, r, v, solved, iterations, residual)
    !> The rigging.
    class(rigging_type), intent(in) :: self
    !> Time [s] and the rigging's own state slice.
    real(wp), intent(in) :: t, y(:)
    !> The falls' ends: the hooks' positions and velocities, the ship's pose.
    type(falls_ends_type), intent(in) :: ends
    !> Block positions [m] and velocities [m/s] (3, block), inertial.
    real(wp), intent(out) :: r(3, 2), v(3, 2)
    !> Whether the quasi-static balance converged.
    logical, intent(out), optional :: solved
    !> Newton's balance evaluations.
    integer, intent(out), optional :: iterations
    !> Largest elastic force left on a block relative to its load.
    real(wp), intent(out), optional :: residual
    logical :: ok
    integer :: it
    real(wp) :: left
    r = reshape(y(self%block_r(1):self%block_r(2)), [3, 2])
    v = reshape(y(self%block_v(1):self%block_v(2)), [3, 2])
    ok = .true.
    it = 0
    left = 0.0_wp
    if (self%static_blocks) then
      call solve_blocks(self%falls_type, balance_input(self, y, ends%hook_pos, ends%hook_vel, &
                        rigging_drive(self, y, winch_speed(self%winch, t))), ends%ship, r, v, &
                        ok, it, left)
    end if
    if (present(solved)) solved = ok
    if (present(iterations)) iterations = it
    if (present(residual)) residual = left
  end subroutine rigging_block_state

  !> Initial rigging state for a boat hanging at rest with its hooks at hook_pos and needing
  !> the force hook_force from the rigging (e.g. (0, 0, -W/2) each). 'equilibrium': each
  !> sling is laid out along the force it must carry, lump by lump, stretched by T/k
  !> (exact statics); the block then needs the cable force Q, the cable tension T is the
  !> least-squares fit of Q = T (lam_out - lam_in) over the cable's blocks, and the
  !> unstretched lengths are set so every segment carries T. 'unstretched': slings of
  !> natural length along the hook force, cable segments at their chord lengths.
  !> residual: max |Q - T (lam_out - lam_in)|/|Q| over the blocks (0 for consistent
  !> geometry, e.g. a head midway above each hook; option A also needs equal hook loads);
  !> an error if it exceeds 0.2 (davit_rigging_sling_start: not an equilibrium).
  subroutine rigging_initial_state(self, hook_pos, hook_force, ship, y, residual, error, mode, &
                                   hook_vel, heads, head_vel)
    !> The rigging, its cable lengths set.
    class(rigging_type), intent(inout) :: self
    !> Hook positions (3, hook), inertial [m], and the force each needs from the rigging [N].
    real(wp), intent(in) :: hook_pos(3, 2), hook_force(3, 2)
    !> The ship's pose.
    type(pose_type), intent(in) :: ship
    !> The rigging's initial state slice; the equilibrium residual max abs(Q - T (lam_out -
    !> lam_in))/abs(Q).
    real(wp), intent(out) :: y(:), residual
    !> Set when the residual exceeds 0.2 (the heads are not above the hooks).
    type(error_type), allocatable, intent(out) :: error
    !> 'equilibrium' (default) or 'unstretched'.
    character(len=*), intent(in), optional :: mode
    !> The hooks' velocities and the davit heads' positions and velocities: each sling's
    !> lumps and block start as points of a rigid pendulum from its head to its hook (a ship
    !> making headway carries the rigging along; a boat pushed sideways swings it).
    real(wp), intent(in), optional :: hook_vel(3, 2), heads(3, 2), head_vel(3, 2)
    real(wp) :: q(3, 2), br(3, 2), lumps(3, self%nlump)
    logical :: unstretched
    integer :: a, il(2), ib
    unstretched = self%unstretched
    if (present(mode)) unstretched = mode == "unstretched"
    y = 0.0_wp
    do a = 1, 2
      il = sling_range(self%lumps%q, self%nlump, a)
      ib = self%block_r(1) + 3*(a - 1)
      call lay_out_sling(self%sling, self%block_mass, hook_pos(:, a), hook_force(:, a), &
                         unstretched, lumps, y(ib:ib + 2), q(:, a))
      y(il(1):il(2)) = reshape(lumps, [3*self%nlump])
    end do
    if (present(hook_vel) .and. present(heads) .and. present(head_vel)) then
      call move_with_hooks(self, hook_pos, hook_vel, heads, head_vel, y)
    end if
    br = reshape(y(self%block_r(1):self%block_r(2)), [3, 2])
    call set_cable_lengths(self%falls_type, br, q, ship, unstretched, residual)
    call check_start_residual(residual, error)
  end subroutine rigging_initial_state

  !> Velocities of the lumps and (massive) blocks as points of a rigid pendulum from each
  !> head to its hook: v = v_head + s (v_hook - v_head), s the point's distance from the
  !> head over the hook's. Uniform (the ship's) when the boat moves with the ship.
  pure subroutine move_with_hooks(self, hook_pos, hook_vel, heads, head_vel, y)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: hook_pos(3, 2), hook_vel(3, 2), heads(3, 2), head_vel(3, 2)
    real(wp), intent(inout) :: y(:)
    integer :: a, k, il(2), iv(2), ib
    do a = 1, 2
      il = sling_range(self%lumps%q, self%nlump, a)
      iv = sling_range(self%lumps%u, self%nlump, a)
      do k = 1, self%nlump
        y(iv(1) + 3*(k - 1):iv(1) + 3*k - 1) = &
          pendulum_velocity(y(il(1) + 3*(k - 1):il(1) + 3*k - 1), heads(:, a), &
                            hook_pos(:, a), head_vel(:, a), hook_vel(:, a))
      end do
      ib = self%block_r(1) + 3*(a - 1)
      y(self%block_v(1) + 3*(a - 1):self%block_v(1) + 3*a - 1) = &
        pendulum_velocity(y(ib:ib + 2), heads(:, a), hook_pos(:, a), head_vel(:, a), &
                          hook_vel(:, a))
    end do
  end subroutine move_with_hooks

  !> Kinetic (lumps, blocks, sheaves) + gravity (-m g z) + elastic (slings, cables) [J],
  !> with the ship at its pose (its motion plays no part). The drum does work when it pays
  !> out, so this is conserved only with the drum stopped. Quasi-static blocks have no
  !> kinetic energy and sit at their balance.
  pure function rigging_energy(self, y, hook_pos, ship) result(en)
    !> The rigging.
    class(rigging_type), intent(in) :: self
    !> The rigging's own state slice; the hooks' positions (3, hook), inertial [m].
    real(wp), intent(in) :: y(:), hook_pos(3, 2)
    !> The ship's pose (taken at rest).
    type(pose_type), intent(in) :: ship
    real(wp) :: en, br(3, 2), bv(3, 2)
    type(balance_input_type) :: inp
    integer :: a, n, il(2), iv(2)
    logical :: solved
    n = self%nlump
    br = reshape(y(self%block_r(1):self%block_r(2)), [3, 2])
    if (self%static_blocks) then
      ! the blocks where the elastic forces and the weights balance (no motion: no dashpot
      ! forces); with them at that minimum the energy is a potential of the hooks.
      inp = balance_input(self, y, hook_pos, 0.0_wp*hook_pos, rigging_drive(self, y, 0.0_wp))
      inp%low_v = 0.0_wp*inp%low_v
      call solve_blocks(self%falls_type, inp, at_rest(ship), br, bv, solved)
      en = -self%block_mass*gravity*sum(br(3, :))
    else
      en = 0.5_wp*self%block_mass*sum(y(self%block_v(1):self%block_v(2))**2) - &
           self%block_mass*gravity*sum(br(3, :))
    end if
    if (self%nsheave > 0) en = en + 0.5_wp*self%sheave_inertia* &
                               sum(y(self%sheaves%u(1):self%sheaves%u(2))**2)
    do a = 1, 2
      il = sling_range(self%lumps%q, n, a)
      iv = sling_range(self%lumps%u, n, a)
      en = en + chain_energy(self%sling, hook_pos(:, a), y(il(1):il(2)), y(iv(1):iv(2)), &
                             br(:, a))
    end do
    call add_cable_energy(self%falls_type, rigging_drive(self, y, 0.0_wp), ship, br, en)
    en = en + stop_energy(self%stop, hook_pos, br)
  end function rigging_energy

  !> Unstretched length of cable c [m] at the rigging's state y: the falls'
  !> cable_unstretched_length with the drum's passage of y (davit_rigging_falls).
  pure function unstretched_length(self, y, c) result(len0)
    !> The rigging.
    class(rigging_type), intent(in) :: self
    !> The rigging's own state slice.
    real(wp), intent(in) :: y(:)
    !> Index of the cable (1 or 2).
    integer, intent(in) :: c
    real(wp) :: len0
    len0 = cable_unstretched_length(self%falls_type, rigging_drive(self, y, 0.0_wp), c)
  end function unstretched_length

  !> Range in y of sling a's 3 n entries within the lumps' range r (q or u): sling 1 first.
  !> Kept in this module, beside its callers in the right-hand side: gfortran inlines it
  !> here, where a call into davit_rigging_rigging_state cost ~3 % of a launch.
  pure function sling_range(r, n, a) result(s)
    !> The lumps' range (q or u) in the slice; lumps per sling; the sling (1 or 2).
    integer, intent(in) :: r(2), n, a
    integer :: s(2)
    s = [r(1) + 3*n*(a - 1), r(1) + 3*n*a - 1]
  end function sling_range

end module davit_rigging_rigging
