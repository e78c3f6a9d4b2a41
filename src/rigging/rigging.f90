!> The rigging sub-model (paper §II.D-E, eqs. 47-82; review §1.6, §1.10, G4-G8, G26): two
!> lumped-mass slings from the movable blocks to the boat hooks, the cable-pulley system
!> (reeving A or B, rotating or quasi-static sheaves) and the speed-controlled winch.
!>
!> It owns its own states and returns their derivatives plus the forces on the two boat
!> hooks; the boat and the ship are inputs (hook positions/velocities, ship pose), so the
!> system assembler couples it to any boat model. Everything is inertial (N, z down): lump
!> and block positions and velocities are inertial, which the design allows in place of
!> the paper's boat-frame components (eq. 47); the Kane mass matrix stays diagonal.
!>
!> State layout y_rig (n = lumps per sling, ns = rotating sheaves, 0 if quasi-static):
!>   y(ilr : ilr+6n-1)  lump positions, (3, n, 2): sling 1 (fore) lumps 1..n from the hook
!>                      up, then sling 2 (aft)
!>   y(ilv : ilv+6n-1)  lump velocities, same layout
!>   y(ibr : ibr+5)     block positions (3, 2);  y(ibv : ibv+5) block velocities
!>   y(ith : ith+ns-1)  sheave angles [rad];     y(iom : iom+ns-1) sheave rates [rad/s]
!>   y(idr)             drum passage s_drum [m] (paid-out length; speed prescribed)
!> DOFs (F1): 6n (lumps) + 6 (block translations) + ns sheave rotations + 1 drum = 6n + m + 6
!> with m = ns + 1; with the boat's 6 and the ship's 6 this is the paper's 6n + m + 18.
!>
!> Quasi-static blocks (&rigging blocks = 'quasi_static', review §4.3 item 2): a 50 kg block
!> between its ~6e7 N/m sling and the falls bounces at ~200 Hz (|lambda| = 1259 1/s on the
!> III.B deck, RK4 limit 2.25e-3 s), far above anything the boat feels. Dropping the
!> block's inertia (eq. 82; not its weight) removes that mode: each evaluation finds the
!> block positions where gravity (eq. 78), the cable's pull (eqs. 69, 79) and the top sling
!> segment (eqs. 80-81, corrected 63) balance, by Newton on the 6 block coordinates (see
!> solve_blocks: the elastic balance, then the dashpots' first-order shift). The
!> blocks are then no DOFs (ndof = 6n + m), but the layout stays: y(ibr) holds a copy that
!> follows the solved positions (d/dt = v_b + (r_b - y)/follow_time) and is only the
!> Newton start, so the right-hand side stays a function of (t, y); y(ibv) is unused and
!> has zero derivative. Keeping the weight keeps the statics of the massive model (parts
!> (W/2 + m_b g)/(2 cos a), F2) and keeps the balance well posed: with its sling slack a
!> block hangs in the cable's V under its weight, where a weightless one would have no
!> unique position.
module davit_rigging_rigging
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use davit_kinds, only: wp, gravity, pi
  use davit_error, only: error_type, fatal_error
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_winch, only: winch_type, winch_speed
  use davit_rigging_sling_chain, only: sling_chain_type, max_lumps, chain_forces, &
                                       chain_energy, new_sling_chain, top_segment_tangent
  use davit_rigging_cable, only: cable_type, max_nodes, node_drum, node_fixed, node_block, &
                                 node_dead, cable_node_kinematics, cable_passages, &
                                 cable_tensions_rotating, cable_tension_quasi_static, &
                                 cable_node_forces, cable_energy_rotating, cable_geometry, &
                                 cable_block_tangent_rotating, &
                                 cable_block_tangent_quasi_static
  implicit none
  private
  public :: rigging_type, new_rigging, max_segments, max_sheaves

  integer, parameter :: max_segments = 2*(max_nodes - 1)
  integer, parameter :: max_sheaves = 2*(max_nodes - 2)
  !> Rate scale of the regularised Coulomb bearing moment M_f tanh(omega/omega_f) [rad/s].
  real(wp), parameter :: omega_friction = 1.0e-2_wp
  !> Quasi-static blocks. Newton on the elastic balance stops after a step of at most
  !> newton_tol [m]: convergence is quadratic there (analytic tangents, smooth while the
  !> active set holds), so what remains is below 1e-12 m, which keeps finite-difference
  !> Jacobians of the right-hand side (davit modes, RODAS3) clean; from an RK4 stage's
  !> start that takes 3 evaluations of the balance (start, step, dashpots). A step moves a
  !> block by at most newton_cap [m] (a block falling onto its cable after the drum paid
  !> out over a slack sling); newton_floor [N/m] on the diagonal keeps the matrix regular
  !> while a block has no taut link (stiffnesses are 1e2 to 1e8 N/m, so it changes the
  !> converged answer not at all).
  real(wp), parameter :: newton_tol = 1.0e-9_wp, newton_cap = 2.0_wp
  real(wp), parameter :: newton_floor = 1.0e-3_wp
  integer, parameter :: newton_max = 50, search_max = 12, max_switches = 8
  !> A Newton step is cut back when it overshoots the balance along its line by more than
  !> search_ratio of the force component it started with (solve_blocks); 0.1 leaves the
  !> quadratic regime alone (there the overshoot is ~|step|/l of it).
  real(wp), parameter :: search_ratio = 0.1_wp
  !> The dashpots shift a block by ~c v/k ~ 1e-4 m on taut links; dashpot_cap [m] bounds
  !> that shift where the links are so slack that a small dashpot force would move the
  !> block far across (it is then not first order in c/k any more).
  real(wp), parameter :: dashpot_cap = 1.0e-3_wp
  !> Fallback of solve_blocks: anchor stiffness m_b/anchor_time^2 (2e4 N/m for 50 kg),
  !> above a nearly slack block's pendulum stiffness (~1e2 to 1e3 N/m), far below a taut
  !> link's (1e7 N/m along it).
  real(wp), parameter :: anchor_time = 0.05_wp
  !> A sling counts as slack at the balance if its continued tension is below -k kink_tol
  !> (and as taut if its tension-only value is above k kink_tol); kink_tol [m] of stretch
  !> is far below what Newton leaves (< 1e-12 m) and far below anything physical.
  real(wp), parameter :: kink_tol = 1.0e-11_wp
  !> ... and is corrected during the iterations once it is off by more than gross_stretch
  !> [m] of stretch (6 kN on the default sling), which no converging iterate comes near.
  real(wp), parameter :: gross_stretch = 1.0e-4_wp
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

  type :: rigging_type
    !> Sizes: state length, DOFs (F1), cables (1 for A, 2 for B), total cable segments,
    !> rotating sheaves, lumps per sling.
    integer :: nstate = 0, ndof = 0, ncable = 0, nseg = 0, nsheave = 0, nlump = 0
    !> Offsets into y_rig (see the module header).
    integer :: ilr = 1, ilv = 1, ibr = 1, ibv = 1, ith = 1, iom = 1, idr = 1
    logical :: rotating = .false., unstretched = .false.
    !> Quasi-static (inertia-free) blocks: positions solved from the force balance.
    logical :: static_blocks = .false.
    character(len=1) :: reeving = "a"
    type(cable_type) :: cables(2)
    type(sling_chain_type) :: sling
    type(winch_type) :: winch
    real(wp) :: block_mass = 50.0_wp, sheave_radius = 0.16_wp, sheave_inertia = 0.19_wp
    real(wp) :: drum_radius = 0.25_wp, bearing_friction = 0.0_wp, friction_ratio = 1.0_wp
    !> Quasi-static sheaves: unstretched cable length at zero pay-out, per cable [m].
    real(wp) :: l0_total(2) = 0.0_wp
  contains
    procedure :: rhs => rigging_rhs
    procedure :: initial_state => rigging_initial_state
    procedure :: energy => rigging_energy
    procedure :: observe => rigging_observe
    procedure :: paid_out, sheave_angles, drum_angle, lump_positions, block_positions
    procedure :: block_state => rigging_block_state
    procedure :: unstretched_length
  end type rigging_type

contains

  !> Build the rigging from its configuration (review G4-G8, G26 defaults).
  subroutine new_rigging(self, cfg, error)
    type(rigging_type), intent(out) :: self
    type(rigging_config), intent(in) :: cfg
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: ea, gear
    if (cfg%lumps < 0 .or. cfg%lumps > max_lumps) then
      call fatal_error(error, "rigging: lumps must be 0.."//"20")
      return
    end if
    ea = cfg%youngs_modulus*pi*cfg%wire_diameter**2/4.0_wp
    self%rotating = cfg%sheaves == "rotating"
    self%unstretched = cfg%initial == "unstretched"
    self%static_blocks = cfg%blocks == "quasi_static"
    self%reeving = cfg%reeving
    self%nlump = cfg%lumps
    self%sling = new_sling_chain(cfg%lumps, cfg%sling_length, ea, cfg%sling_damping, &
                                 cfg%sling_mass_per_length)
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
    call build_reeving(self, cfg, ea)
    if (self%static_blocks) then
      self%sling%ramp = dashpot_ramp
      self%cables%ramp = dashpot_ramp
    end if
    call set_layout(self)
  end subroutine new_rigging

  !> Node lists of reeving A (paper Fig. 8, G6) or B (one wire per fall).
  subroutine build_reeving(self, cfg, ea)
    type(rigging_type), intent(inout) :: self
    type(rigging_config), intent(in) :: cfg
    real(wp), intent(in) :: ea
    real(wp) :: h(3), heads(3, 2), lead(3), drum(3)
    integer :: a, c, i, ns
    h = [0.5_wp*cfg%head_spacing, 0.0_wp, 0.0_wp]
    heads(:, 1) = cfg%head_fore
    heads(:, 2) = cfg%head_aft
    if (cfg%reeving == "a") then
      self%ncable = 1
      associate (cab => self%cables(1))
        cab%nnode = 8
        cab%kind(1:8) = [node_drum, node_fixed, node_fixed, node_block, node_fixed, &
                         node_fixed, node_block, node_dead]
        cab%p_ship(:, 1) = cfg%drum_position
        cab%p_ship(:, 2) = cfg%lead_sheave
        cab%p_ship(:, 3) = heads(:, 1) - h
        cab%block(4) = 1
        cab%p_ship(:, 5) = heads(:, 1) + h
        cab%p_ship(:, 6) = heads(:, 2) + h
        cab%block(7) = 2
        cab%p_ship(:, 8) = heads(:, 2) - h
      end associate
    else
      self%ncable = 2
      do a = 1, 2
        ! The wire's drum exit and guide sheave sit at its head's x; the head sheave is on
        ! the inboard side (towards x = 0), the dead end outboard.
        drum = [heads(1, a), cfg%drum_position(2:3)]
        lead = [heads(1, a), cfg%lead_sheave(2:3)]
        associate (cab => self%cables(a))
          cab%nnode = 5
          cab%kind(1:5) = [node_drum, node_fixed, node_fixed, node_block, node_dead]
          cab%p_ship(:, 1) = drum
          cab%p_ship(:, 2) = lead
          cab%p_ship(:, 3) = heads(:, a) - sign(1.0_wp, heads(1, a))*h
          cab%block(4) = a
          cab%p_ship(:, 5) = heads(:, a) + sign(1.0_wp, heads(1, a))*h
        end associate
      end do
    end if
    ns = 0
    do c = 1, self%ncable
      self%cables(c)%ea = ea
      self%cables(c)%damping = cfg%cable_damping
      self%cables(c)%sheave = 0
      if (.not. self%rotating) cycle
      do i = 2, self%cables(c)%nnode - 1
        ns = ns + 1
        self%cables(c)%sheave(i) = ns
      end do
    end do
    self%nsheave = ns
    self%nseg = sum(self%cables(1:self%ncable)%nnode) - self%ncable
  end subroutine build_reeving

  subroutine set_layout(self)
    type(rigging_type), intent(inout) :: self
    integer :: n
    n = self%nlump
    self%ilr = 1
    self%ilv = self%ilr + 6*n
    self%ibr = self%ilv + 6*n
    self%ibv = self%ibr + 6
    self%ith = self%ibv + 6
    self%iom = self%ith + self%nsheave
    self%idr = self%iom + self%nsheave
    self%nstate = self%idr
    self%ndof = 6*n + merge(0, 6, self%static_blocks) + self%nsheave + 1
  end subroutine set_layout

  !> Time derivative of the rigging states and the forces ON the two boat hooks (inertial
  !> components) for given hook kinematics and ship pose (ship_c maps ship to inertial
  !> components, ship_w is the ship's angular velocity in inertial components).
  pure subroutine rigging_rhs(self, t, y, hook_pos, hook_vel, ship_r, ship_c, ship_v, &
                              ship_w, dydt, hook_force)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:), hook_pos(3, 2), hook_vel(3, 2)
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(out) :: dydt(:), hook_force(3, 2)
    real(wp) :: seg(max_segments), sl(max_lumps + 1, 2)
    call evaluate(self, t, y, hook_pos, hook_vel, ship_r, ship_c, ship_v, ship_w, dydt, &
                  hook_force, seg, sl)
  end subroutine rigging_rhs

  !> Segment tensions [N] (cable 1 segments from the drum, then cable 2) and sling segment
  !> tensions (segment k above lump k-1, k = 1 at the hook; column = sling).
  pure subroutine rigging_observe(self, t, y, hook_pos, hook_vel, ship_r, ship_c, ship_v, &
                                  ship_w, seg_tension, sling_tension)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:), hook_pos(3, 2), hook_vel(3, 2)
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(out) :: seg_tension(self%nseg), sling_tension(self%nlump + 1, 2)
    real(wp) :: seg(max_segments), sl(max_lumps + 1, 2), dydt(self%nstate), fh(3, 2)
    call evaluate(self, t, y, hook_pos, hook_vel, ship_r, ship_c, ship_v, ship_w, dydt, &
                  fh, seg, sl)
    seg_tension = seg(1:self%nseg)
    sling_tension = sl(1:self%nlump + 1, :)
  end subroutine rigging_observe

  pure subroutine evaluate(self, t, y, hook_pos, hook_vel, ship_r, ship_c, ship_v, ship_w, &
                           dydt, hook_force, seg, sl)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:), hook_pos(3, 2), hook_vel(3, 2)
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(out) :: dydt(:), hook_force(3, 2)
    real(wp), intent(out) :: seg(max_segments), sl(max_lumps + 1, 2)
    real(wp) :: block_f(3, 2), torque(max_sheaves), f_top(3), v_drum, br(3, 2), bv(3, 2)
    real(wp) :: low_r(3, 2), low_v(3, 2)
    integer :: a, n, il, iv, ns
    logical :: solved
    n = self%nlump
    ns = self%nsheave
    v_drum = winch_speed(self%winch, t)
    br(:, 1) = y(self%ibr:self%ibr + 2)
    br(:, 2) = y(self%ibr + 3:self%ibr + 5)
    bv(:, 1) = y(self%ibv:self%ibv + 2)
    bv(:, 2) = y(self%ibv + 3:self%ibv + 5)
    if (self%static_blocks) then
      call sling_low_ends(self, y, hook_pos, hook_vel, low_r, low_v)
      call solve_blocks(self, y, low_r, low_v, v_drum, ship_r, ship_c, ship_v, ship_w, br, &
                        bv, solved)
    end if
    seg = 0.0_wp
    sl = 0.0_wp
    block_f = 0.0_wp
    block_f(3, :) = self%block_mass*gravity
    do a = 1, 2
      il = self%ilr + 3*n*(a - 1)
      iv = self%ilv + 3*n*(a - 1)
      call chain_forces(self%sling, hook_pos(:, a), hook_vel(:, a), y(il:il + 3*n - 1), &
                        y(iv:iv + 3*n - 1), br(:, a), bv(:, a), &
                        dydt(iv:iv + 3*n - 1), f_top, hook_force(:, a), sl(1:n + 1, a))
      dydt(il:il + 3*n - 1) = y(iv:iv + 3*n - 1)
      block_f(:, a) = block_f(:, a) + f_top
    end do
    torque = 0.0_wp
    call cable_forces(self, y, br, bv, v_drum, ship_r, ship_c, ship_v, ship_w, block_f, &
                      torque, seg)
    if (self%static_blocks) then
      ! block_f is the balance's residual (~0); the copies follow the solved blocks. A
      ! balance that fails to converge poisons them, so the driver's finiteness check stops
      ! the run naming a rigging state instead of going on with wrong forces.
      dydt(self%ibr:self%ibr + 2) = bv(:, 1) + (br(:, 1) - y(self%ibr:self%ibr + 2))/follow_time
      dydt(self%ibr + 3:self%ibr + 5) = bv(:, 2) + &
                                        (br(:, 2) - y(self%ibr + 3:self%ibr + 5))/follow_time
      if (.not. solved) dydt(self%ibr:self%ibr + 5) = ieee_value(0.0_wp, ieee_quiet_nan)
      dydt(self%ibv:self%ibv + 5) = 0.0_wp
    else
      dydt(self%ibr:self%ibr + 5) = y(self%ibv:self%ibv + 5)
      dydt(self%ibv:self%ibv + 2) = block_f(:, 1)/self%block_mass
      dydt(self%ibv + 3:self%ibv + 5) = block_f(:, 2)/self%block_mass
    end if
    if (ns > 0) then
      associate (omega => y(self%iom:self%iom + ns - 1))
        dydt(self%ith:self%ith + ns - 1) = omega
        dydt(self%iom:self%iom + ns - 1) = (torque(1:ns) - self%bearing_friction* &
                                            tanh(omega/omega_friction))/self%sheave_inertia
      end associate
    end if
    dydt(self%idr) = v_drum
  end subroutine evaluate

  !> Cable forces on the blocks, sheave torques and segment tensions of every cable, with
  !> the blocks at br moving at bv.
  pure subroutine cable_forces(self, y, br, bv, v_drum, ship_r, ship_c, ship_v, ship_w, &
                               block_f, torque, seg)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), br(3, 2), bv(3, 2), v_drum
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(inout) :: block_f(3, 2), torque(max_sheaves), seg(max_segments)
    real(wp) :: p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp) :: s(max_nodes), sdot(max_nodes), f(max_nodes - 1), g(max_nodes - 1)
    integer :: c, k, nseg
    k = 0
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        nseg = cab%nnode - 1
        call cable_node_kinematics(cab, ship_r, ship_c, ship_v, ship_w, br, bv, p, v)
        call cable_tensions(self, cab, c, y, p, v, v_drum, lam, l, s, sdot, f, g)
        call cable_node_forces(cab, lam, f, g, self%sheave_radius, block_f, torque)
        seg(k + 1:k + nseg) = f(1:nseg)
        k = k + nseg
      end associate
    end do
  end subroutine cable_forces

  !> Chords (lam, l), passages (s, sdot; rotating sheaves) and segment tensions f (g drives
  !> the sheaves) of cable cab (one of self's, c its index) with its nodes at p moving at v.
  pure subroutine cable_tensions(self, cab, c, y, p, v, v_drum, lam, l, s, sdot, f, g)
    type(rigging_type), intent(in) :: self
    type(cable_type), intent(in) :: cab
    integer, intent(in) :: c
    real(wp), intent(in) :: y(:), p(3, max_nodes), v(3, max_nodes), v_drum
    real(wp), intent(out) :: lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp), intent(out) :: s(max_nodes), sdot(max_nodes), f(max_nodes - 1)
    real(wp), intent(out) :: g(max_nodes - 1)
    real(wp) :: ldot(max_nodes - 1)
    integer :: ns
    ns = self%nsheave
    call cable_geometry(cab, p, v, lam, l, ldot)
    if (self%rotating) then
      call cable_passages(cab, y(self%idr), v_drum, self%sheave_radius, &
                          y(self%ith:self%ith + ns - 1), y(self%iom:self%iom + ns - 1), &
                          s, sdot)
      call cable_tensions_rotating(cab, l, ldot, s, sdot, f, g)
    else
      s = 0.0_wp
      sdot = 0.0_wp
      call cable_tension_quasi_static(cab, l, ldot, self%l0_total(c) + y(self%idr), v_drum, &
                                      self%friction_ratio, f)
      g = f
    end if
  end subroutine cable_tensions

  !> Lower end of each sling's top segment: the hook (no lumps) or the top lump n.
  pure subroutine sling_low_ends(self, y, hook_pos, hook_vel, low_r, low_v)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), hook_pos(3, 2), hook_vel(3, 2)
    real(wp), intent(out) :: low_r(3, 2), low_v(3, 2)
    integer :: a, n, il, iv
    n = self%nlump
    low_r = hook_pos
    low_v = hook_vel
    if (n == 0) return
    do a = 1, 2
      il = self%ilr + 3*n*(a - 1) + 3*(n - 1)
      iv = self%ilv + 3*n*(a - 1) + 3*(n - 1)
      low_r(:, a) = y(il:il + 2)
      low_v(:, a) = y(iv:iv + 2)
    end do
  end subroutine sling_low_ends

  !> Quasi-static blocks: positions br (in: the start, e.g. the state's copies) where the
  !> net force on each block, cable pull + top sling segment + weight m_b g, vanishes, and
  !> their velocities bv on that balance. Both blocks together (6 coordinates): with
  !> quasi-static sheaves on reeving A one tension couples them.
  !>
  !> First the elastic balance (no dashpots): it minimises a convex potential (elastic
  !> energies - m_b g z) whose gradient and Hessian are -F and -dF/dr, so it is unique and
  !> symmetric, and it is well posed whenever the cable is taut, which the weight ensures
  !> (a tension-only sling pulls its block towards the hook; only the cable holds it up).
  !> Along the motion dF/dr dr + dF/dt = 0, so the blocks move at bv = -(dF/dr)^(-1) dF/dt,
  !> dF/dt the force rate due to everything else (hooks or lumps, ship-fixed nodes, drum,
  !> sheaves) at fixed blocks. Then the dashpots, at that velocity, shift the blocks by
  !> (-dF/dr)^(-1) F_dashpot, ~1e-4 m: the slow motion of the massive model to first
  !> order in c/k (its block lags the same way); left out are O((c v/k)^2/l) and the
  !> dashpots' response to accelerations, O(c a/k).
  !>
  !> Newton with: an active set for the slings' slack kink (D = l0, where Newton would
  !> cycle between the sides): each sling is held (its law continued smoothly through
  !> D = l0) or free (left out), guessed at the start, corrected once converged (a held
  !> sling that would push, or a free one that would pull, changes side) or at once when
  !> off by gross_stretch; steps capped at newton_cap per block and cut back where they
  !> overshoot (search_ratio); the diagonal floor newton_floor for a block with no taut
  !> link. After newton_max iterations the best iterate is taken if the force left on
  !> each block is below its weight, else solved = .false.; iterations counts the balance
  !> evaluations (3 from an RK4 stage's start: start, step, dashpots).
  pure subroutine newton_blocks(self, y, low_r, low_v, v_drum, ship_r, ship_c, ship_v, &
                                ship_w, k_anchor, br, bv, solved, iterations)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), low_r(3, 2), low_v(3, 2), v_drum
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(inout) :: br(3, 2)
    real(wp), intent(out) :: bv(3, 2)
    logical, intent(out) :: solved
    real(wp), intent(in) :: k_anchor
    integer, intent(out) :: iterations
    real(wp) :: b(6), v(6), res(6), jac(6, 6), rate(6), x(6, 2), step(6), b_try(6), anchor(6)
    real(wp) :: pn(3, max_nodes, 2), vn(3, max_nodes, 2), f_sling(2), f_real(2)
    real(wp) :: res_t(6), jac_t(6, 6), rate_t(6), fs_t(2), fr_t(2), res_d(6), f_tol, f_gross
    real(wp) :: g, g_lo, g_hi, g_tol, a_lo, a_hi, alpha, longest, best_norm, b_best(6)
    integer :: it, c, nswitch, nbal, ls, side
    logical :: taut(2), changed
    ! the ship-fixed nodes once (blocks at rest in vn); block_balance places the blocks
    do c = 1, self%ncable
      call cable_node_kinematics(self%cables(c), ship_r, ship_c, ship_v, ship_w, br, &
                                 0.0_wp*br, pn(:, :, c), vn(:, :, c))
    end do
    b(1:3) = br(:, 1)
    b(4:6) = br(:, 2)
    anchor = b
    v = 0.0_wp
    nswitch = 0
    solved = .false.
    f_tol = self%sling%k_seg*kink_tol
    f_gross = self%sling%k_seg*gross_stretch
    ! which slings hold their blocks: guessed at the start, then corrected (active set)
    do c = 1, 2
      call top_segment_tangent(self%sling, low_r(:, c), low_v(:, c), br(:, c), 0.0_wp*br(:, c), &
                               x(1:3, 1), f_sling(c), f_real(c), jac(1:3, 1:3))
      taut(c) = f_real(c) > 0.0_wp
    end do
    call block_balance(self, y, b, v, low_r, low_v, v_drum, pn, vn, taut, anchor, k_anchor, &
                       res, jac, rate, f_sling, f_real, res_d)
    nbal = 1
    best_norm = huge(1.0_wp)
    b_best = b
    do it = 1, newton_max
      ! (-dF/dr + floor) x = [F, dF/dt]: x(:, 1) the Newton step, x(:, 2) the velocity.
      call newton_matrix(jac)
      x(:, 1) = res
      x(:, 2) = rate
      call dense_solve(jac, x)
      step = x(:, 1)
      longest = max(norm2(step(1:3)), norm2(step(4:6)))
      if (longest > newton_cap) step = step*(newton_cap/longest)
      if (maxval(abs(step)) <= newton_tol) then
        b = b + step
        ! converged with these slings holding: a held sling must pull, a free one must not
        changed = .false.
        do c = 1, 2
          if (taut(c) .and. f_sling(c) < -f_tol .or. .not. taut(c) .and. f_real(c) > f_tol) then
            taut(c) = .not. taut(c)
            changed = .true.
          end if
        end do
        if (.not. changed) then
          solved = .true.
          exit
        end if
        nswitch = nswitch + 1
        if (nswitch > max_switches) exit
        call block_balance(self, y, b, v, low_r, low_v, v_drum, pn, vn, taut, anchor, k_anchor, &
                           res, jac, rate, f_sling, f_real, res_d)
        nbal = nbal + 1
        best_norm = huge(1.0_wp)
        cycle
      end if
      ! Line search: along the step the force component g(alpha) = step . F(b + alpha step)
      ! starts positive, g(0) = F . (-dF/dr)^(-1) F, and falls (the potential is convex).
      ! A whole step leaves g(1) ~ 0 (quadratic convergence) and is taken; one that
      ! overshoots, g(1) < -search_ratio g(0) (a far start, a kink where a link goes slack,
      ! the soft swing of a block on slack links), is cut back to where g is within
      ! search_ratio g(0) of zero, by regula falsi (Illinois) on [0, 1].
      b_try = b + step
      call block_balance(self, y, b_try, v, low_r, low_v, v_drum, pn, vn, taut, anchor, &
                         k_anchor, res_t, jac_t, rate_t, fs_t, fr_t, res_d)
      nbal = nbal + 1
      g_lo = dot_product(res, step)
      g_hi = dot_product(res_t, step)
      if (g_lo > 0.0_wp .and. g_hi < -search_ratio*g_lo) then
        g_tol = search_ratio*g_lo
        a_lo = 0.0_wp
        a_hi = 1.0_wp
        side = 0
        do ls = 1, search_max
          alpha = a_hi - g_hi*(a_hi - a_lo)/(g_hi - g_lo)
          b_try = b + alpha*step
          call block_balance(self, y, b_try, v, low_r, low_v, v_drum, pn, vn, taut, anchor, &
                             k_anchor, res_t, jac_t, rate_t, fs_t, fr_t, res_d)
          nbal = nbal + 1
          g = dot_product(res_t, step)
          if (abs(g) <= g_tol) exit
          if (g < 0.0_wp) then
            a_hi = alpha
            g_hi = g
            if (side == -1) g_lo = 0.5_wp*g_lo
            side = -1
          else
            a_lo = alpha
            g_lo = g
            if (side == 1) g_hi = 0.5_wp*g_hi
            side = 1
          end if
        end do
      end if
      b = b_try
      res = res_t
      jac = jac_t
      rate = rate_t
      f_sling = fs_t
      f_real = fr_t
      if (max(norm2(res(1:3)), norm2(res(4:6))) < best_norm) then
        best_norm = max(norm2(res(1:3)), norm2(res(4:6)))
        b_best = b
      end if
      ! a guess that is plainly wrong (a free sling stretched, or a held one pushing, by
      ! more than gross_stretch) is corrected at once rather than after converging to it
      if (nswitch < max_switches .and. any(taut .and. f_sling < -f_gross .or. &
                                           .not. taut .and. f_real > f_gross)) then
        taut = taut .neqv. (taut .and. f_sling < -f_gross .or. &
                            .not. taut .and. f_real > f_gross)
        nswitch = nswitch + 1
        call block_balance(self, y, b, v, low_r, low_v, v_drum, pn, vn, taut, anchor, k_anchor, &
                           res, jac, rate, f_sling, f_real, res_d)
        nbal = nbal + 1
        best_norm = huge(1.0_wp)
        b_best = b
      end if
    end do
    if (.not. solved) then
      ! Newton stalled (links near slack: soft and kinked): take the best iterate (of
      ! this active set) if the force left on each block, and the force a sling would
      ! have on the wrong side of its kink, are below the block's weight. Neglecting the
      ! block's inertia already errs by m_b a, of that size when slack slings jerk the
      ! block about; taut links converge in 2-3 evaluations.
      b = b_best
      call block_balance(self, y, b, v, low_r, low_v, v_drum, pn, vn, taut, anchor, k_anchor, &
                         res, jac, rate, f_sling, f_real, res_d)
      nbal = nbal + 1
      solved = max(norm2(res(1:3)), norm2(res(4:6))) <= self%block_mass*gravity .and. &
               all(.not. taut .or. f_sling >= -self%block_mass*gravity) .and. &
               all(taut .or. f_real <= self%block_mass*gravity)
      call newton_matrix(jac)
      x(:, 2) = rate
      call dense_solve(jac, x)
    end if
    ! the velocity on the balance (from the last tangent, within newton_tol of it), then
    ! the dashpots at that velocity and the shift by what is left (their force, and the
    ! balance's own ~1e-6 N), capped at dashpot_cap
    v = x(:, 2)
    call block_balance(self, y, b, v, low_r, low_v, v_drum, pn, vn, taut, anchor, k_anchor, &
                       res, jac, rate, f_sling, f_real, res_d, dashpots=.true.)
    nbal = nbal + 1
    call newton_matrix(jac)
    x(:, 1) = res + res_d
    x(:, 2) = 0.0_wp
    call dense_solve(jac, x)
    step = x(:, 1)
    ! only where the sling holds: a free block would be moved by the cable's dashpot
    ! alone, along links so slack that the shift would no longer be small (and could
    ! take up its sling's slack, which the balance has not seen)
    if (.not. taut(1)) step(1:3) = 0.0_wp
    if (.not. taut(2)) step(4:6) = 0.0_wp
    longest = max(norm2(step(1:3)), norm2(step(4:6)))
    if (longest > dashpot_cap) step = step*(dashpot_cap/longest)
    b = b + step
    br(:, 1) = b(1:3)
    br(:, 2) = b(4:6)
    bv(:, 1) = v(1:3)
    bv(:, 2) = v(4:6)
    iterations = nbal
  end subroutine newton_blocks

  !> The balance of the quasi-static blocks (newton_blocks). Where it fails (slack or
  !> nearly slack links in a violent phase: a hook unloaded by a wave or an impact, the
  !> falls paid out over a waterborne boat) the blocks are tied by anchor_stiffness to
  !> their start (the state's copies) and the balance solved again: the copies follow the
  !> solved blocks, so the anchor acts like the block's inertia over anchor_time, letting
  !> it drift rather than jump to where its slack links would put it.
  pure subroutine solve_blocks(self, y, low_r, low_v, v_drum, ship_r, ship_c, ship_v, ship_w, &
                               br, bv, solved, iterations)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), low_r(3, 2), low_v(3, 2), v_drum
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(inout) :: br(3, 2)
    real(wp), intent(out) :: bv(3, 2)
    logical, intent(out) :: solved
    integer, intent(out), optional :: iterations
    real(wp) :: b0(3, 2)
    integer :: n1, n2
    b0 = br
    call newton_blocks(self, y, low_r, low_v, v_drum, ship_r, ship_c, ship_v, ship_w, &
                       0.0_wp, br, bv, solved, n1)
    n2 = 0
    if (.not. solved) then
      br = b0
      call newton_blocks(self, y, low_r, low_v, v_drum, ship_r, ship_c, ship_v, ship_w, &
                         self%block_mass/anchor_time**2, br, bv, solved, n2)
    end if
    if (present(iterations)) iterations = n1 + n2
  end subroutine solve_blocks

  !> -jac + newton_floor I, the matrix of solve_blocks' Newton step.
  pure subroutine newton_matrix(jac)
    real(wp), intent(inout) :: jac(6, 6)
    integer :: j
    jac = -jac
    do j = 1, 6
      jac(j, j) = jac(j, j) + newton_floor
    end do
  end subroutine newton_matrix

  !> The elastic balance on the two blocks at positions b: net force res (cable and top
  !> sling segments where held, without their dashpots, and weight), its Jacobian
  !> jac = d res/d b and its rate at fixed blocks, rate = d res/dt; f_sling: the top
  !> segments' elastic tensions continued through slack (< 0 there), f_real: their
  !> tension-only values; res_d (if dashpots, else 0): the dashpots' force on the blocks
  !> moving at v (cable, and held slings). pn, vn: the cables' ship-fixed node positions
  !> and velocities (block nodes zero in vn: the rate is taken with the blocks at rest).
  !> With k_anchor > 0 a spring k_anchor ties each block to anchor (solve_blocks' fallback).
  pure subroutine block_balance(self, y, b, v, low_r, low_v, v_drum, pn, vn, taut, anchor, &
                                k_anchor, res, jac, rate, f_sling, f_real, res_d, dashpots)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), b(6), v(6), low_r(3, 2), low_v(3, 2), v_drum
    real(wp), intent(in) :: pn(3, max_nodes, 2), vn(3, max_nodes, 2), anchor(6), k_anchor
    logical, intent(in) :: taut(2)
    logical, intent(in), optional :: dashpots
    real(wp), intent(out) :: res(6), jac(6, 6), rate(6), f_sling(2), f_real(2), res_d(6)
    type(sling_chain_type) :: sling_el
    type(cable_type) :: cab_el
    real(wp) :: br(3, 2), bv(3, 2), f_top(3), k(3, 3), block_f(3, 2), torque(max_sheaves)
    real(wp) :: p(3, max_nodes), vv(3, max_nodes), lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp) :: s(max_nodes), sdot(max_nodes), f(max_nodes - 1), g(max_nodes - 1)
    real(wp) :: damp_f(3, 2), f_damped(3), fs_damped, fr_damped, k_damped(3, 3)
    integer :: a, c, i
    logical :: with_dashpots
    with_dashpots = .false.
    if (present(dashpots)) with_dashpots = dashpots
    br(:, 1) = b(1:3)
    br(:, 2) = b(4:6)
    bv(:, 1) = v(1:3)
    bv(:, 2) = v(4:6)
    sling_el = self%sling
    sling_el%c_seg = 0.0_wp
    jac = 0.0_wp
    rate = 0.0_wp
    block_f = 0.0_wp
    block_f(3, :) = self%block_mass*gravity
    damp_f = 0.0_wp
    do a = 1, 2
      call top_segment_tangent(sling_el, low_r(:, a), low_v(:, a), br(:, a), bv(:, a), &
                               f_top, f_sling(a), f_real(a), k)
      if (.not. taut(a)) cycle
      if (with_dashpots) then
        call top_segment_tangent(self%sling, low_r(:, a), low_v(:, a), br(:, a), bv(:, a), &
                                 f_damped, fs_damped, fr_damped, k_damped)
        damp_f(:, a) = f_damped - f_top
      end if
      block_f(:, a) = block_f(:, a) + f_top
      jac(3*a - 2:3*a, 3*a - 2:3*a) = k
      rate(3*a - 2:3*a) = -matmul(k, low_v(:, a))
    end do
    torque = 0.0_wp
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        p = pn(:, :, c)
        vv = vn(:, :, c)
        do i = 1, cab%nnode
          if (cab%kind(i) /= node_block) cycle
          p(:, i) = br(:, cab%block(i))
          vv(:, i) = bv(:, cab%block(i))
        end do
        ! without the dashpots (the same cable with c = 0); asked for, also with them:
        ! the difference is the dashpots' share
        if (with_dashpots) then
          call cable_tensions(self, cab, c, y, p, vv, v_drum, lam, l, s, sdot, f, g)
          call cable_node_forces(cab, lam, f, g, self%sheave_radius, damp_f, torque)
        end if
        cab_el = cab
        cab_el%damping = 0.0_wp
        call cable_tensions(self, cab_el, c, y, p, vv, v_drum, lam, l, s, sdot, f, g)
        call cable_node_forces(cab_el, lam, f, g, self%sheave_radius, block_f, torque)
        if (with_dashpots) call cable_node_forces(cab_el, lam, -f, -g, self%sheave_radius, &
                                                  damp_f, torque)
        if (self%rotating) then
          call cable_block_tangent_rotating(cab_el, lam, l, f, s, sdot, vv, vn(:, :, c), &
                                            jac, rate)
        else
          call cable_block_tangent_quasi_static(cab_el, lam, l, f, self%l0_total(c) + &
                                                y(self%idr), v_drum, self%friction_ratio, &
                                                vv, vn(:, :, c), jac, rate)
        end if
      end associate
    end do
    res(1:3) = block_f(:, 1)
    res(4:6) = block_f(:, 2)
    if (k_anchor > 0.0_wp) then
      res = res - k_anchor*(b - anchor)
      do i = 1, 6
        jac(i, i) = jac(i, i) - k_anchor
      end do
    end if
    res_d(1:3) = damp_f(:, 1)
    res_d(4:6) = damp_f(:, 2)
  end subroutine block_balance

  !> Solves a x = b in place (b holds x on return) by Gaussian elimination with partial
  !> pivoting; a is overwritten. For the small, regular 6 x 6 systems of solve_blocks.
  pure subroutine dense_solve(a, b)
    real(wp), intent(inout) :: a(6, 6), b(6, 2)
    real(wp) :: row(6), rhs(2), m
    integer :: i, j, k, piv
    do j = 1, 6
      piv = j - 1 + maxloc(abs(a(j:6, j)), 1)
      if (piv /= j) then
        row = a(j, :)
        a(j, :) = a(piv, :)
        a(piv, :) = row
        rhs = b(j, :)
        b(j, :) = b(piv, :)
        b(piv, :) = rhs
      end if
      do i = j + 1, 6
        m = a(i, j)/a(j, j)
        a(i, j + 1:6) = a(i, j + 1:6) - m*a(j, j + 1:6)
        b(i, :) = b(i, :) - m*b(j, :)
      end do
    end do
    do j = 6, 1, -1
      do k = j + 1, 6
        b(j, :) = b(j, :) - a(j, k)*b(k, :)
      end do
      b(j, :) = b(j, :)/a(j, j)
    end do
  end subroutine dense_solve

  !> Block positions and velocities (3, block), inertial: the states for massive blocks;
  !> for quasi-static blocks the solved balance at this state (the copies in y are only the
  !> start). solved is .false. if the balance did not converge; iterations: Newton's.
  pure subroutine rigging_block_state(self, t, y, hook_pos, hook_vel, ship_r, ship_c, ship_v, &
                                      ship_w, r, v, solved, iterations)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:), hook_pos(3, 2), hook_vel(3, 2)
    real(wp), intent(in) :: ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(out) :: r(3, 2), v(3, 2)
    logical, intent(out), optional :: solved
    integer, intent(out), optional :: iterations
    real(wp) :: low_r(3, 2), low_v(3, 2)
    logical :: ok
    integer :: it
    r = reshape(y(self%ibr:self%ibr + 5), [3, 2])
    v = reshape(y(self%ibv:self%ibv + 5), [3, 2])
    ok = .true.
    it = 0
    if (self%static_blocks) then
      call sling_low_ends(self, y, hook_pos, hook_vel, low_r, low_v)
      call solve_blocks(self, y, low_r, low_v, winch_speed(self%winch, t), ship_r, ship_c, &
                        ship_v, ship_w, r, v, ok, it)
    end if
    if (present(solved)) solved = ok
    if (present(iterations)) iterations = it
  end subroutine rigging_block_state

  !> Initial rigging state for a boat hanging at rest with its hooks at hook_pos and needing
  !> the force hook_force from the rigging (e.g. (0, 0, -W/2) each). 'equilibrium': each
  !> sling is laid out along the force it must carry, lump by lump, stretched by T/k
  !> (exact statics); the block then needs the cable force Q, the cable tension T is the
  !> least-squares fit of Q = T (lam_out - lam_in) over the cable's blocks, and the
  !> unstretched lengths are set so every segment carries T. 'unstretched': slings of
  !> natural length along the hook force, cable segments at their chord lengths.
  !> residual: max |Q - T (lam_out - lam_in)|/|Q| over the blocks (0 for consistent
  !> geometry, e.g. a head midway above each hook; option A also needs equal hook loads).
  subroutine rigging_initial_state(self, hook_pos, hook_force, ship_r, ship_c, y, residual, &
                                   mode)
    class(rigging_type), intent(inout) :: self
    real(wp), intent(in) :: hook_pos(3, 2), hook_force(3, 2), ship_r(3), ship_c(3, 3)
    real(wp), intent(out) :: y(:), residual
    character(len=*), intent(in), optional :: mode
    real(wp) :: q(3, 2), br(3, 2)
    logical :: unstretched
    integer :: a
    unstretched = self%unstretched
    if (present(mode)) unstretched = mode == "unstretched"
    y = 0.0_wp
    do a = 1, 2
      call place_sling(self, a, hook_pos(:, a), hook_force(:, a), unstretched, y, q(:, a))
    end do
    br = reshape(y(self%ibr:self%ibr + 5), [3, 2])
    call set_cable_lengths(self, br, q, ship_r, ship_c, unstretched, residual)
  end subroutine rigging_initial_state

  !> Lay out sling a from its hook: segment k carries F_k = F_hook - (k-1) m_p g N3 (lump
  !> statics), along F_k, stretched by |F_k|/k_seg; returns the cable force Q its block needs.
  pure subroutine place_sling(self, a, hook, f_hook, unstretched, y, q)
    type(rigging_type), intent(in) :: self
    integer, intent(in) :: a
    real(wp), intent(in) :: hook(3), f_hook(3)
    logical, intent(in) :: unstretched
    real(wp), intent(inout) :: y(:)
    real(wp), intent(out) :: q(3)
    real(wp) :: node(3), fk(3), up(3), ez(3)
    integer :: k, n, il
    n = self%nlump
    ez = [0.0_wp, 0.0_wp, 1.0_wp]
    up = -ez
    if (norm2(f_hook) > 0.0_wp) up = f_hook/norm2(f_hook)
    node = hook
    il = self%ilr + 3*n*(a - 1)
    do k = 1, n + 1
      fk = f_hook - real(k - 1, wp)*self%sling%m_lump*gravity*ez
      if (unstretched .or. norm2(fk) <= 0.0_wp) then
        node = node + self%sling%l0_seg*up
      else
        node = node + (self%sling%l0_seg + norm2(fk)/self%sling%k_seg)*fk/norm2(fk)
      end if
      if (k <= n) y(il + 3*(k - 1):il + 3*k - 1) = node
    end do
    y(self%ibr + 3*(a - 1):self%ibr + 3*a - 1) = node
    q = fk - self%block_mass*gravity*ez
  end subroutine place_sling

  !> Unstretched cable lengths for tension T per cable (T = 0 when unstretched).
  subroutine set_cable_lengths(self, br, q, ship_r, ship_c, unstretched, residual)
    type(rigging_type), intent(inout) :: self
    real(wp), intent(in) :: br(3, 2), q(3, 2), ship_r(3), ship_c(3, 3)
    logical, intent(in) :: unstretched
    real(wp), intent(out) :: residual
    real(wp) :: p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp) :: ldot(max_nodes - 1), zero3(3), sv(3), num, den, t
    integer :: c, i, nseg
    zero3 = 0.0_wp
    residual = 0.0_wp
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        nseg = cab%nnode - 1
        call cable_node_kinematics(cab, ship_r, ship_c, zero3, zero3, br, &
                                   0.0_wp*br, p, v)
        call cable_geometry(cab, p, v, lam, l, ldot)
        num = 0.0_wp
        den = 0.0_wp
        do i = 2, nseg
          if (cab%kind(i) /= node_block) cycle
          sv = lam(:, i) - lam(:, i - 1)
          num = num + dot_product(q(:, cab%block(i)), sv)
          den = den + dot_product(sv, sv)
        end do
        t = 0.0_wp
        if (.not. unstretched .and. den > 0.0_wp) t = max(0.0_wp, num/den)
        do i = 2, nseg
          if (cab%kind(i) /= node_block .or. unstretched) cycle
          sv = lam(:, i) - lam(:, i - 1)
          residual = max(residual, norm2(q(:, cab%block(i)) - t*sv)/norm2(q(:, cab%block(i))))
        end do
        cab%l0_init(1:nseg) = l(1:nseg)/(1.0_wp + t/cab%ea)
        self%l0_total(c) = sum(l(1:nseg))/(1.0_wp + t/cab%ea)
      end associate
    end do
  end subroutine set_cable_lengths

  !> Kinetic (lumps, blocks, sheaves) + gravity (-m g z) + elastic (slings, cables) [J].
  !> The drum does work when it pays out, so this is conserved only with the drum stopped.
  !> Quasi-static blocks have no kinetic energy and sit at their balance.
  pure function rigging_energy(self, y, hook_pos, ship_r, ship_c) result(en)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), hook_pos(3, 2), ship_r(3), ship_c(3, 3)
    real(wp) :: en, br(3, 2), p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1)
    real(wp) :: l(max_nodes - 1), ldot(max_nodes - 1), s(max_nodes), sdot(max_nodes)
    real(wp) :: zero3(3), stretch, bv(3, 2), lr(3, 2), lv(3, 2)
    integer :: a, c, n, il, iv, ns
    logical :: solved
    n = self%nlump
    ns = self%nsheave
    zero3 = 0.0_wp
    if (self%static_blocks) then
      ! the blocks where the elastic forces and the weights balance (no motion: no dashpot
      ! forces); with them at that minimum the energy is a potential of the hooks.
      br = reshape(y(self%ibr:self%ibr + 5), [3, 2])
      call sling_low_ends(self, y, hook_pos, 0.0_wp*hook_pos, lr, lv)
      call solve_blocks(self, y, lr, 0.0_wp*lv, 0.0_wp, ship_r, ship_c, zero3, zero3, br, &
                        bv, solved)
      en = -self%block_mass*gravity*sum(br(3, :))
    else
      br = reshape(y(self%ibr:self%ibr + 5), [3, 2])
      en = 0.5_wp*self%block_mass*sum(y(self%ibv:self%ibv + 5)**2) - &
           self%block_mass*gravity*sum(br(3, :))
    end if
    if (ns > 0) en = en + 0.5_wp*self%sheave_inertia*sum(y(self%iom:self%iom + ns - 1)**2)
    do a = 1, 2
      il = self%ilr + 3*n*(a - 1)
      iv = self%ilv + 3*n*(a - 1)
      en = en + chain_energy(self%sling, hook_pos(:, a), y(il:il + 3*n - 1), &
                             y(iv:iv + 3*n - 1), br(:, a))
    end do
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        call cable_node_kinematics(cab, ship_r, ship_c, zero3, zero3, br, 0.0_wp*br, p, v)
        call cable_geometry(cab, p, v, lam, l, ldot)
        if (self%rotating) then
          call cable_passages(cab, y(self%idr), 0.0_wp, self%sheave_radius, &
                              y(self%ith:self%ith + ns - 1), y(self%iom:self%iom + ns - 1), &
                              s, sdot)
          en = en + cable_energy_rotating(cab, l, s)
        else
          stretch = max(0.0_wp, sum(l(1:cab%nnode - 1)) - self%l0_total(c) - y(self%idr))
          en = en + 0.5_wp*cab%ea*stretch**2/(self%l0_total(c) + y(self%idr))
        end if
      end associate
    end do
  end function rigging_energy

  !> Unstretched length of cable c [m]: sum L0_i = sum L0_i(0) + s_drum (the sheave
  !> passages telescope), or L0_tot(0) + s_drum for quasi-static sheaves.
  pure function unstretched_length(self, y, c) result(len0)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    integer, intent(in) :: c
    real(wp) :: len0, s(max_nodes), sdot(max_nodes)
    integer :: i, ns
    ns = self%nsheave
    if (.not. self%rotating) then
      len0 = self%l0_total(c) + y(self%idr)
      return
    end if
    associate (cab => self%cables(c))
      call cable_passages(cab, y(self%idr), 0.0_wp, self%sheave_radius, &
                          y(self%ith:self%ith + ns - 1), y(self%iom:self%iom + ns - 1), s, sdot)
      len0 = 0.0_wp
      do i = 1, cab%nnode - 1
        len0 = len0 + cab%l0_init(i) + s(i) - s(i + 1)
      end do
    end associate
  end function unstretched_length

  !> Paid-out length at the drum s_drum [m].
  pure function paid_out(self, y) result(s)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: s
    s = y(self%idr)
  end function paid_out

  !> Drum angle s_drum/r_d [rad].
  pure function drum_angle(self, y) result(theta)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: theta
    theta = y(self%idr)/self%drum_radius
  end function drum_angle

  !> Sheave angles [rad] (empty with quasi-static sheaves).
  pure function sheave_angles(self, y) result(theta)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: theta(self%nsheave)
    theta = y(self%ith:self%ith + self%nsheave - 1)
  end function sheave_angles

  !> Lump positions (3, lump, sling), inertial [m].
  pure function lump_positions(self, y) result(r)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: r(3, self%nlump, 2)
    r = reshape(y(self%ilr:self%ilr + 6*self%nlump - 1), [3, self%nlump, 2])
  end function lump_positions

  !> Block positions (3, block), inertial [m], as stored in the state: for quasi-static
  !> blocks the copies that follow the solved positions (block_state gives those).
  pure function block_positions(self, y) result(r)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: r(3, 2)
    r = reshape(y(self%ibr:self%ibr + 5), [3, 2])
  end function block_positions

end module davit_rigging_rigging
