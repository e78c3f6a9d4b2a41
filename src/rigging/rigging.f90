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
module davit_rigging_rigging
  use davit_kinds, only: wp, gravity, pi
  use davit_error, only: error_type, fatal_error
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_winch, only: winch_type, winch_speed
  use davit_rigging_sling_chain, only: sling_chain_type, max_lumps, chain_forces, &
                                       chain_energy, new_sling_chain
  use davit_rigging_cable, only: cable_type, max_nodes, node_drum, node_fixed, node_block, &
                                 node_dead, cable_node_kinematics, cable_passages, &
                                 cable_tensions_rotating, cable_tension_quasi_static, &
                                 cable_node_forces, cable_energy_rotating, cable_geometry
  implicit none
  private
  public :: rigging_type, new_rigging, max_segments, max_sheaves

  integer, parameter :: max_segments = 2*(max_nodes - 1)
  integer, parameter :: max_sheaves = 2*(max_nodes - 2)
  !> Rate scale of the regularised Coulomb bearing moment M_f tanh(omega/omega_f) [rad/s].
  real(wp), parameter :: omega_friction = 1.0e-2_wp

  type :: rigging_type
    !> Sizes: state length, DOFs (F1), cables (1 for A, 2 for B), total cable segments,
    !> rotating sheaves, lumps per sling.
    integer :: nstate = 0, ndof = 0, ncable = 0, nseg = 0, nsheave = 0, nlump = 0
    !> Offsets into y_rig (see the module header).
    integer :: ilr = 1, ilv = 1, ibr = 1, ibv = 1, ith = 1, iom = 1, idr = 1
    logical :: rotating = .false., unstretched = .false.
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
    self%ndof = 6*n + 6 + self%nsheave + 1
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
    real(wp) :: block_f(3, 2), torque(max_sheaves), f_top(3), v_drum
    integer :: a, n, il, iv, ib, ibv, ns
    n = self%nlump
    ns = self%nsheave
    v_drum = winch_speed(self%winch, t)
    seg = 0.0_wp
    sl = 0.0_wp
    block_f = 0.0_wp
    block_f(3, :) = self%block_mass*gravity
    do a = 1, 2
      il = self%ilr + 3*n*(a - 1)
      iv = self%ilv + 3*n*(a - 1)
      ib = self%ibr + 3*(a - 1)
      ibv = self%ibv + 3*(a - 1)
      call chain_forces(self%sling, hook_pos(:, a), hook_vel(:, a), y(il:il + 3*n - 1), &
                        y(iv:iv + 3*n - 1), y(ib:ib + 2), y(ibv:ibv + 2), &
                        dydt(iv:iv + 3*n - 1), f_top, hook_force(:, a), sl(1:n + 1, a))
      dydt(il:il + 3*n - 1) = y(iv:iv + 3*n - 1)
      block_f(:, a) = block_f(:, a) + f_top
    end do
    torque = 0.0_wp
    call cable_forces(self, y, v_drum, ship_r, ship_c, ship_v, ship_w, block_f, torque, seg)
    dydt(self%ibr:self%ibr + 5) = y(self%ibv:self%ibv + 5)
    dydt(self%ibv:self%ibv + 5) = reshape(block_f, [6])/self%block_mass
    if (ns > 0) then
      associate (omega => y(self%iom:self%iom + ns - 1))
        dydt(self%ith:self%ith + ns - 1) = omega
        dydt(self%iom:self%iom + ns - 1) = (torque(1:ns) - self%bearing_friction* &
                                            tanh(omega/omega_friction))/self%sheave_inertia
      end associate
    end if
    dydt(self%idr) = v_drum
  end subroutine evaluate

  !> Cable forces on the blocks, sheave torques and segment tensions of every cable.
  pure subroutine cable_forces(self, y, v_drum, ship_r, ship_c, ship_v, ship_w, block_f, &
                               torque, seg)
    type(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), v_drum, ship_r(3), ship_c(3, 3), ship_v(3), ship_w(3)
    real(wp), intent(inout) :: block_f(3, 2), torque(max_sheaves), seg(max_segments)
    real(wp) :: p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp) :: ldot(max_nodes - 1), s(max_nodes), sdot(max_nodes), f(max_nodes - 1)
    real(wp) :: g(max_nodes - 1), br(3, 2), bv(3, 2)
    integer :: c, k, nseg, ns
    ns = self%nsheave
    br = reshape(y(self%ibr:self%ibr + 5), [3, 2])
    bv = reshape(y(self%ibv:self%ibv + 5), [3, 2])
    k = 0
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        nseg = cab%nnode - 1
        call cable_node_kinematics(cab, ship_r, ship_c, ship_v, ship_w, br, bv, p, v)
        call cable_geometry(cab, p, v, lam, l, ldot)
        if (self%rotating) then
          call cable_passages(cab, y(self%idr), v_drum, self%sheave_radius, &
                              y(self%ith:self%ith + ns - 1), y(self%iom:self%iom + ns - 1), &
                              s, sdot)
          call cable_tensions_rotating(cab, l, ldot, s, sdot, f, g)
        else
          call cable_tension_quasi_static(cab, l, ldot, self%l0_total(c) + y(self%idr), &
                                          v_drum, self%friction_ratio, f)
          g = f
        end if
        call cable_node_forces(cab, lam, f, g, self%sheave_radius, block_f, torque)
        seg(k + 1:k + nseg) = f(1:nseg)
        k = k + nseg
      end associate
    end do
  end subroutine cable_forces

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
  pure function rigging_energy(self, y, hook_pos, ship_r, ship_c) result(en)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:), hook_pos(3, 2), ship_r(3), ship_c(3, 3)
    real(wp) :: en, br(3, 2), p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1)
    real(wp) :: l(max_nodes - 1), ldot(max_nodes - 1), s(max_nodes), sdot(max_nodes)
    real(wp) :: zero3(3), stretch
    integer :: a, c, n, il, iv, ns
    n = self%nlump
    ns = self%nsheave
    zero3 = 0.0_wp
    br = reshape(y(self%ibr:self%ibr + 5), [3, 2])
    en = 0.5_wp*self%block_mass*sum(y(self%ibv:self%ibv + 5)**2) - &
         self%block_mass*gravity*sum(br(3, :))
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

  !> Block positions (3, block), inertial [m].
  pure function block_positions(self, y) result(r)
    class(rigging_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: r(3, 2)
    r = reshape(y(self%ibr:self%ibr + 5), [3, 2])
  end function block_positions

end module davit_rigging_rigging
