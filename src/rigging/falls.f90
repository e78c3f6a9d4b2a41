!> The falls of the davit (paper §II.E, eqs. 66-82; review §1.10, G6): the cables (one for
!> reeving A, one per fall for B) from the drum over the ship-fixed sheaves and the movable
!> blocks to their dead ends, with the blocks' weight and the slings' top segments that
!> hang from them. What the rigging's right-hand side and the quasi-static block balance
!> (davit_rigging_block_balance) share: the make-up (falls_type, built from the
!> configuration), the cable tensions for a given drive (drum and sheaves), the initial
!> cable lengths for a hanging boat, and the cables' elastic energy.
module davit_rigging_falls
  use davit_kinds, only: wp
  use davit_core_pose, only: pose_type
  use davit_io_rigging_keys, only: rigging_config
  use davit_rigging_sling_chain, only: sling_chain_type
  use davit_rigging_block_stop, only: block_stop_type, new_block_stop
  use davit_rigging_wire_damping, only: cable_floor
  use davit_rigging_cable, only: cable_type, cable_eval_type, max_nodes, node_drum, &
                                 node_fixed, node_block, &
                                 node_dead, cable_node_kinematics, cable_passages, &
                                 cable_tensions_rotating, cable_tension_quasi_static, &
                                 cable_geometry, cable_energy_rotating
  implicit none
  private
  public :: falls_type, drive_type, max_sheaves
  public :: build_reeving, cable_tensions, set_cable_lengths, add_cable_energy
  public :: cable_unstretched_length, at_rest

  integer, parameter :: max_sheaves = 2*(max_nodes - 2)

  !> The falls: the cables (1 for reeving A, 2 for B) over the sheaves to the two blocks,
  !> the slings' top segments and the blocks' weight; constant after new_rigging.
  type :: falls_type
    !> Cables, rotating sheaves (0 if quasi-static), total cable segments.
    integer :: ncable = 0, nsheave = 0, nseg = 0
    !> Rotating sheaves (with inertia), else quasi-static.
    logical :: rotating = .false.
    !> The cables (1 for reeving A, 2 for B).
    type(cable_type) :: cables(2)
    !> The slings (their top segments hold the blocks).
    type(sling_chain_type) :: sling
    !> Mass of a block [kg], sheave radius [m], sheave friction ratio (1: frictionless).
    real(wp) :: block_mass = 50.0_wp, sheave_radius = 0.16_wp, friction_ratio = 1.0_wp
    !> Quasi-static sheaves: unstretched cable length at zero pay-out, per cable [m].
    real(wp) :: l0_total(2) = 0.0_wp
    !> The blocks' hook stops (davit_rigging_block_stop), the wire's damping ratio and
    !> whether the cables' dashpot is raised to its floor once their lengths are known.
    type(block_stop_type) :: stop
    !> Damping ratio of the wire.
    real(wp) :: wire_zeta = 0.0_wp
    !> Whether the cables' dashpot is raised to its floor once their lengths are known.
    logical :: cable_floor = .false.
  end type falls_type

  !> What moves the cable over its sheaves: drum passage s_drum [m] and pay-out speed
  !> v_drum [m/s], sheave angles theta [rad] and rates omega [rad/s] (rotating sheaves).
  type :: drive_type
    !> Drum passage [m] and pay-out speed [m/s].
    real(wp) :: s_drum = 0.0_wp, v_drum = 0.0_wp
    !> Sheave angles [rad] and rates [rad/s].
    real(wp) :: theta(max_sheaves) = 0.0_wp, omega(max_sheaves) = 0.0_wp
  end type drive_type

contains

  !> Node lists of reeving A (paper Fig. 8, G6) or B (one wire per fall).
  subroutine build_reeving(self, cfg, ea)
    !> The falls, their cables' node lists set.
    type(falls_type), intent(inout) :: self
    !> The &rigging configuration (reeving, geometry).
    type(rigging_config), intent(in) :: cfg
    !> Axial stiffness EA of the wire [N].
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
    self%stop = new_block_stop(cfg%block_stop, ea/cfg%sling_length, cfg%block_mass)
    self%wire_zeta = cfg%wire_damping_ratio
    self%cable_floor = .not. cfg%cable_damping_given
  end subroutine build_reeving

  !> Chords, passages and segment tensions of cable cab (falls' cable c, or a copy of it)
  !> with its nodes at p moving at v.
  pure subroutine cable_tensions(falls, cab, c, drive, p, v, ce)
    !> The falls.
    type(falls_type), intent(in) :: falls
    !> The cable (falls' cable c, or a copy of it).
    type(cable_type), intent(in) :: cab
    !> Index of the cable (1 or 2).
    integer, intent(in) :: c
    !> Drum passage and speed, sheave angles and rates.
    type(drive_type), intent(in) :: drive
    !> Node positions and velocities (3, node), inertial [m, m/s].
    real(wp), intent(in) :: p(3, max_nodes), v(3, max_nodes)
    !> Chords, passages and tensions of the cable.
    type(cable_eval_type), intent(out) :: ce
    real(wp) :: ldot(max_nodes - 1)
    integer :: ns
    ns = falls%nsheave
    call cable_geometry(cab, p, v, ce%lam, ce%l, ldot)
    if (falls%rotating) then
      call cable_passages(cab, drive%s_drum, drive%v_drum, falls%sheave_radius, &
                          drive%theta(1:ns), drive%omega(1:ns), ce%s, ce%sdot)
      call cable_tensions_rotating(cab, ce%l, ldot, ce%s, ce%sdot, ce%f, ce%g)
    else
      ce%s = 0.0_wp
      ce%sdot = 0.0_wp
      call cable_tension_quasi_static(cab, ce%l, ldot, falls%l0_total(c) + drive%s_drum, &
                                      drive%v_drum, falls%friction_ratio, ce%f)
      ce%g = ce%f
    end if
  end subroutine cable_tensions

  !> Unstretched cable lengths for tension T per cable (T = 0 when unstretched).
  subroutine set_cable_lengths(self, br, q, ship, unstretched, residual)
    !> The falls, their unstretched lengths set.
    type(falls_type), intent(inout) :: self
    !> Block positions (3, block), inertial [m]; the forces the blocks must carry (3, block) [N].
    real(wp), intent(in) :: br(3, 2), q(3, 2)
    !> The ship's pose.
    type(pose_type), intent(in) :: ship
    !> Set the lengths to the chords (no tension) instead of the tension each block needs.
    logical, intent(in) :: unstretched
    !> max |Q - T (lam_out - lam_in)|/|Q| over the blocks: how far the falls miss the blocks'
    !> loads.
    real(wp), intent(out) :: residual
    real(wp) :: p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp) :: ldot(max_nodes - 1), sv(3), num, den, t
    integer :: c, i, nseg
    residual = 0.0_wp
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        nseg = cab%nnode - 1
        call cable_node_kinematics(cab, at_rest(ship), br, 0.0_wp*br, p, v)
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
        ! the wire's floor (davit_rigging_wire_damping) unless the deck set the dashpot
        if (self%cable_floor) cab%damping = &
          max(cab%damping, cable_floor(cab, cab%l0_init(1:nseg), self%wire_zeta, self%block_mass))
      end associate
    end do
  end subroutine set_cable_lengths

  !> Adds the cables' elastic energy [J] to en, the blocks at br, the ship at rest at its
  !> pose: sum EA e^2/(2 L0) over taut segments (rotating sheaves), or EA e^2/(2 L0_tot)
  !> of the cable's one stretch e (quasi-static sheaves).
  pure subroutine add_cable_energy(self, drive, ship, br, en)
    !> The falls.
    type(falls_type), intent(in) :: self
    !> Drum passage and speed, sheave angles.
    type(drive_type), intent(in) :: drive
    !> The ship's pose (taken at rest).
    type(pose_type), intent(in) :: ship
    !> Block positions (3, block), inertial [m].
    real(wp), intent(in) :: br(3, 2)
    !> Energy [J], the cables' added.
    real(wp), intent(inout) :: en
    real(wp) :: p(3, max_nodes), v(3, max_nodes), lam(3, max_nodes - 1), l(max_nodes - 1)
    real(wp) :: ldot(max_nodes - 1), s(max_nodes), sdot(max_nodes), stretch
    integer :: c, ns
    ns = self%nsheave
    do c = 1, self%ncable
      associate (cab => self%cables(c))
        call cable_node_kinematics(cab, at_rest(ship), br, 0.0_wp*br, p, v)
        call cable_geometry(cab, p, v, lam, l, ldot)
        if (self%rotating) then
          call cable_passages(cab, drive%s_drum, drive%v_drum, self%sheave_radius, &
                              drive%theta(1:ns), drive%omega(1:ns), s, sdot)
          en = en + cable_energy_rotating(cab, l, s)
        else
          stretch = max(0.0_wp, sum(l(1:cab%nnode - 1)) - self%l0_total(c) - drive%s_drum)
          en = en + 0.5_wp*cab%ea*stretch**2/(self%l0_total(c) + drive%s_drum)
        end if
      end associate
    end do
  end subroutine add_cable_energy

  !> Unstretched length of cable c [m]: sum L0_i = sum L0_i(0) + s_drum (the sheave
  !> passages telescope), or L0_tot(0) + s_drum for quasi-static sheaves.
  pure function cable_unstretched_length(self, drive, c) result(len0)
    !> The falls.
    type(falls_type), intent(in) :: self
    !> Drum passage.
    type(drive_type), intent(in) :: drive
    !> Index of the cable (1 or 2).
    integer, intent(in) :: c
    real(wp) :: len0, s(max_nodes), sdot(max_nodes)
    integer :: i, ns
    ns = self%nsheave
    if (.not. self%rotating) then
      len0 = self%l0_total(c) + drive%s_drum
      return
    end if
    associate (cab => self%cables(c))
      call cable_passages(cab, drive%s_drum, drive%v_drum, self%sheave_radius, &
                          drive%theta(1:ns), drive%omega(1:ns), s, sdot)
      len0 = 0.0_wp
      do i = 1, cab%nnode - 1
        len0 = len0 + cab%l0_init(i) + s(i) - s(i + 1)
      end do
    end associate
  end function cable_unstretched_length

  !> The ship where `ship` is, at rest (statics and energies).
  pure function at_rest(ship) result(pose)
    !> The ship's pose.
    type(pose_type), intent(in) :: ship
    type(pose_type) :: pose
    pose%r = ship%r
    pose%c = ship%c
    pose%v = 0.0_wp
    pose%w = 0.0_wp
  end function at_rest

end module davit_rigging_falls
