!> The ship as a 6-DOF rigid body (paper §II.C, eqs. 35-41) with the review's corrections:
!> direction-dependent added mass handled by computing omega x (M v) and omega x (I omega)
!> explicitly (review §1.2, 1.1 eq. 89), Froude-Krylov box loads in closed form summed over
!> all wave components (review §1.8), hydrostatic restoring and radiation damping
!> (G10-G12), zero-speed cross-flow drag for sway and yaw, surge resistance, and wind
!> (eq. 46, G14). One-way coupled: the davit loads do not act on the ship (review §1.11).
!>
!> One state part "ship": q = Euler angles (roll, pitch, yaw; eq. 2) and CG position in the
!> inertial frame (the MMG convention; qdot = C v); u = angular velocity and velocity in
!> ship axes. ship_kane_blocks gives its Kane blocks to whichever system holds it.
!>
!> Two levels of detail: the paper's box ('fk_box': Froude-Krylov box loads, constant
!> strip-theory added masses, hydrostatic and damping coefficients from Table 1), and the
!> BEM ship ('bem', davit_ship_bem_loads: Cummins' equation from a Capytaine database,
!> whose radiation memory adds a second part "ship_radiation" of states to the layout).
!> The manoeuvring, cross-flow, resistance, wind and heading-keeping loads serve both.
!> A ship making way (either manoeuvring model) is split in two time scales: the
!> manoeuvring forces in the horizontal-body frame, the linear seakeeping (wave loads,
!> radiation memory) about a frame moving at the headway along the initial heading, so
!> the waves are met at their encounter frequencies and the memory (zero-speed kernels)
!> sees only the motions about the steady forward speed.
module davit_ship_ship_model
  use davit_kinds, only: wp, pi, rho_water
  use davit_core_rotation, only: rotation_matrix, euler_rates
  use davit_core_kane, only: kane_rates, kane_at_rest
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_ship_bem_loads, only: bem_ship_type, bem_wave_coefficients, bem_restoring, &
                                  bem_memory, turn_to_body
  use davit_ship_ship_blocks, only: box_blocks, bem_blocks
  use davit_core_quadrature, only: gx => gauss8_x, gw => gauss8_w
  use davit_solve_integrator, only: ode_problem
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_ramp, wave_chunk, &
                                  component_phases
  use davit_sea_wind, only: wind_type, wind_velocity
  use davit_ship_hull, only: hull_type
  use davit_ship_froude_krylov, only: fk_box_load, fk_transfer
  use davit_ship_wind_load, only: ship_wind_load
  use davit_ship_mmg, only: mmg_type, mmg_self_propulsion
  use davit_ship_mmg_loads, only: mmg_body_load
  use davit_ship_rudder, only: rudder_type, rudder_order, rudder_rate, rudder_switch, &
                               autopilot_order, autopilot_states
  use davit_ship_wave_drift, only: drift_none, drift_coefficients, drift_load
  implicit none
  private
  public :: ship_system_type, new_ship_system, ship_loads, ship_state

  !> Surge resistance coefficient on the wetted surface (review G12; Mumford's surface).
  real(wp), parameter :: surge_ct = 0.003_wp
  !> Gauss points along the hull for the cross-flow drag integral.
  integer, parameter :: ngauss = 8

  type, extends(ode_problem) :: ship_system_type
    type(hull_type) :: hull
    type(wave_field_type) :: sea
    type(wind_type) :: wind
    logical :: frozen = .false.
    !> Equilibrium CG depth [m], wetted surface [m^2], constant thrust [N] that holds the
    !> initial headway against the surge resistance.
    real(wp) :: z_eq = 0.0_wp, wetted = 0.0_wp, thrust = 0.0_wp
    !> Froude-Krylov loads about G of each component for heading psi_ref:
    !> load = fk_sin(:, i) sin(Phi_i) + fk_cos(:, i) cos(Phi_i).
    real(wp), allocatable :: fk_sin(:, :), fk_cos(:, :)
    real(wp) :: psi_ref = 0.0_wp
    !> Linear seakeeping: wave phases taken at the initial position of O' (review §1.8's
    !> position phase with the mean position), so a slow drift does not feed back into
    !> the excitation. With the current position instead, the Froude-Krylov sway force
    !> gains a second-order mean part and the ship drifts at ~1 m/s in 2 m beam waves.
    logical :: phase_at_initial = .true.
    real(wp) :: origin(2) = 0.0_wp
    !> The seakeeping frame of a ship making way (any headway): it moves at U along
    !> the initial heading, frame_velocity = U (cos psi_0, sin psi_0) [m/s], so the linear
    !> wave loads see the phase at origin + frame_velocity t, hence the encounter
    !> frequency omega_e = omega - k U cos(beta); the radiation memory is fed the speeds
    !> relative to it, (u - U, v, w) (frame_speed = U). Zero: the frame at rest.
    real(wp) :: frame_velocity(2) = 0.0_wp, frame_speed = 0.0_wp
    !> Optional soft mooring of surge, sway and yaw (stiffness and damping), used by the RAO
    !> runs to hold the mean position and heading as a frequency-domain RAO assumes, and as
    !> the heading (and station) keeping of the 'launch' scene, where an integral term
    !> (moor_i, on the states of part "ship_control": the time integrals of the errors)
    !> takes out steady offsets such as the wind's yaw moment (a PID autopilot or DP).
    !> Anchored at `anchor` (x, y, yaw); zero = off.
    real(wp) :: moor_k(3) = 0.0_wp, moor_c(3) = 0.0_wp, moor_i(3) = 0.0_wp
    real(wp) :: anchor(3) = 0.0_wp
    type(state_part_type) :: control
    !> Slow clock of the Froude-Krylov loads (`&simulation wave_update`; 0: off): with the
    !> phases at the initial position they depend on time alone, so they are sampled with
    !> their rates on the grid k wave_dt and interpolated by cubic Hermite in between
    !> (error ~ (omega wave_dt)^4/384 of each component). Stages outside the window
    !> [wave_t(1), wave_t(2)] are evaluated directly.
    real(wp) :: wave_dt = 0.0_wp
    logical :: wave_cached = .false.
    real(wp) :: wave_t(2) = 0.0_wp, wave_f(6, 2) = 0.0_wp, wave_d(6, 2) = 0.0_wp
    !> The ship's state: part "ship" (rigid body) and, for the BEM ship, part
    !> "ship_radiation" (its memory states); body and radiation are their ranges.
    type(state_layout_type) :: layout
    type(state_part_type) :: body, radiation
    !> The BEM ship in place of the box's hydrodynamics.
    logical :: bem = .false.
    type(bem_ship_type) :: hydro
    !> The MMG manoeuvring model (set_mmg) in place of the cross-flow drag, Kijima
    !> derivatives and constant thrust: its coefficients, the propeller revolutions
    !> [1/s], the steering, and the rudder angle's state part "ship_rudder".
    logical :: mmg_on = .false.
    type(mmg_type) :: mmg
    real(wp) :: rps = 0.0_wp
    type(rudder_type) :: steer
    !> The autopilot's states (integral, wave filter): part "ship_autopilot" (PID only).
    type(state_part_type) :: rudder, autopilot
    !> The BEM ship's wave drift (davit_ship_wave_drift: drift_none, drift_mean, drift_newman)
    !> and its coefficients a_i sqrt(|D_i|) sign(D_i) (surge, sway, yaw) at heading psi_ref.
    integer :: drift = drift_none
    real(wp), allocatable :: drift_coef(:, :)
  contains
    procedure :: rhs => ship_rhs
    procedure :: kane_blocks => ship_kane_blocks
    procedure :: refresh_heading
    procedure :: after_step => ship_after_step
    procedure :: set_mooring
    procedure :: set_mmg
    procedure :: set_drift
  end type ship_system_type

  !> Yaw drift [rad] after which the Froude-Krylov coefficients are recomputed.
  real(wp), parameter :: heading_tolerance = 0.5_wp*pi/180.0_wp

contains

  subroutine new_ship_system(self, hull, sea, wind, frozen, position, heading, &
                             phase_at_initial, headway, bem)
    ! 10 arguments: the ship's parts as the deck gives them (hull, sea, wind, pose, switches)
    type(ship_system_type), intent(out) :: self
    type(hull_type), intent(in) :: hull
    type(wave_field_type), intent(in) :: sea
    type(wind_type), intent(in) :: wind
    logical, intent(in) :: frozen, phase_at_initial
    real(wp), intent(in) :: position(3), heading, headway
    type(bem_ship_type), intent(in), optional :: bem
    real(wp) :: z_eq, water(6), air(6)
    z_eq = position(3)
    self%phase_at_initial = phase_at_initial
    self%origin = position(1:2) - [cos(heading), sin(heading)]*hull%cg_x
    if (present(bem)) then
      ! the database's loads are about the CG, their phases at its horizontal position
      self%bem = .true.
      self%hydro = bem
      self%origin = position(1:2)
    end if
    self%hull = hull
    self%sea = sea
    self%wind = wind
    self%frozen = frozen
    self%z_eq = z_eq
    ! Mumford's wetted surface 1.7 L d + V/d
    self%wetted = 1.7_wp*hull%lpp*hull%draught + hull%mass/rho_water/hull%draught
    ! the engine setting that holds the headway in still air and calm water: water and air
    ! resistance at that speed
    water = crossflow(hull, self%wetted, [headway, 0.0_wp, 0.0_wp], 0.0_wp)
    air = ship_wind_load(hull%wind, [-headway, 0.0_wp, 0.0_wp])
    self%thrust = 0.0_wp
    if (hull%empirical) self%thrust = -(water(1) + air(1))
    ! a ship making way (either manoeuvring model) meets the waves at omega_e: the
    ! seakeeping frame moves at the headway along the initial heading
    self%frame_speed = headway
    self%frame_velocity = headway*[cos(heading), sin(heading)]
    allocate (self%fk_sin(6, sea%n), self%fk_cos(6, sea%n))
    call self%refresh_heading(heading)
    call self%layout%add("ship", 6, 6, self%body)
    if (.not. self%bem) return
    call self%layout%add("ship_radiation", self%hydro%db%nrad, 0, self%radiation)
    call self%layout%couple(self%body%u, self%hydro%v_inv)
  end subroutine new_ship_system

  !> The state part of a ship at attitude euler, CG position, angular velocity omega and
  !> velocity v (ship axes): q then u, as the layout registers them.
  pure function ship_state(self, euler, position, omega, v) result(y)
    class(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: euler(3), position(3), omega(3), v(3)
    real(wp) :: y(self%layout%n)
    y = 0.0_wp
    y(self%body%q(1):self%body%u(2)) = [euler, position, omega, v]
  end function ship_state

  !> Recompute the heading-dependent Froude-Krylov coefficients (chi = gamma - psi). The
  !> time loop calls this when the yaw has drifted, so the RHS stays free of it.
  pure subroutine refresh_heading(self, psi)
    class(ship_system_type), intent(inout) :: self
    real(wp), intent(in) :: psi
    real(wp) :: raw(6)
    integer :: i
    self%psi_ref = psi
    if (self%bem) then
      call bem_wave_coefficients(self%hydro, self%sea, psi, self%fk_sin, self%fk_cos)
      if (self%drift /= drift_none) call drift_coefficients(self%hydro%db, self%sea, psi, &
                                                            self%drift_coef)
      return
    end if
    associate (s => self%sea, h => self%hull)
      do i = 1, s%n
        ! X, Y, K, M go with sin(Phi), Z and N with cos(Phi); split before the transfer to
        ! G, which mixes them (M_G gets x_G Z, N_G gets -x_G Y)
        raw = fk_box_load(h%box, s%amplitude(i), s%k(i), s%direction(i) - psi, 0.5_wp*pi)
        raw([3, 6]) = 0.0_wp
        self%fk_sin(:, i) = fk_transfer(raw, h%cg_x, h%cg_z)
        raw = fk_box_load(h%box, s%amplitude(i), s%k(i), s%direction(i) - psi, 0.0_wp)
        raw([1, 2, 4, 5]) = 0.0_wp
        self%fk_cos(:, i) = fk_transfer(raw, h%cg_x, h%cg_z)
      end do
    end associate
  end subroutine refresh_heading

  !> Switch the BEM ship's wave drift to `level` (its database must hold the coefficients:
  !> davit_system_build checks).
  pure subroutine set_drift(self, level)
    class(ship_system_type), intent(inout) :: self
    integer, intent(in) :: level
    self%drift = level
    if (level == drift_none .or. .not. self%bem) return
    if (allocated(self%drift_coef)) deallocate (self%drift_coef)
    allocate (self%drift_coef(3, self%sea%n))
    call self%refresh_heading(self%psi_ref)
  end subroutine set_drift

  !> Soft mooring with the given natural periods [s] (surge, sway, yaw) and damping ratio,
  !> anchored at the current state; with `integral`, a PID: integral gain k w/10 (integral
  !> time 10/w, slow against the period), its states registered as part "ship_control".
  subroutine set_mooring(self, period, zeta, y, integral)
    class(ship_system_type), intent(inout) :: self
    real(wp), intent(in) :: period(3), zeta, y(:)
    logical, intent(in), optional :: integral
    real(wp) :: inertia(3)
    associate (q => y(self%body%q(1):self%body%q(2)))
      self%anchor = [q(4), q(5), q(3)]
    end associate
    inertia = [self%hull%mass + self%hull%added_mass(1:2), &
               self%hull%inertia(3) + self%hull%added_inertia(3)]
    if (self%bem) inertia = [self%hydro%mass + self%hydro%db%added_mass_inf(1, 1), &
                             self%hydro%mass + self%hydro%db%added_mass_inf(2, 2), &
                             self%hydro%inertia(3) + self%hydro%db%added_mass_inf(6, 6)]
    ! a period <= 0 leaves that motion free
    self%moor_k = 0.0_wp
    where (period > 0.0_wp) self%moor_k = inertia*(2.0_wp*pi/period)**2
    self%moor_c = 2.0_wp*zeta*sqrt(self%moor_k*inertia)
    if (.not. present(integral)) return
    if (.not. integral .or. self%control%q(2) >= self%control%q(1)) return
    self%moor_i = self%moor_k*sqrt(self%moor_k/inertia)/10.0_wp
    if (any(self%moor_i > 0.0_wp)) call self%layout%add("ship_control", 3, 0, self%control)
  end subroutine set_mooring

  !> Switch to the MMG manoeuvring model p with the steering `steer` (its heading: the
  !> initial one) and the propeller at `rps` (0: the self-propulsion point at `headway`);
  !> the rudder angle joins the state as part "ship_rudder". The seakeeping frame moves at
  !> `headway` along the initial heading (new_ship_system; the two-time-scale split:
  !> manoeuvring in the horizontal-body frame, seakeeping about this steady motion).
  subroutine set_mmg(self, p, steer, rps, headway)
    class(ship_system_type), intent(inout) :: self
    type(mmg_type), intent(in) :: p
    type(rudder_type), intent(in) :: steer
    real(wp), intent(in) :: rps, headway
    real(wp) :: air(6), extra
    self%mmg_on = .true.
    self%mmg = p
    self%steer = steer
    self%steer%heading = self%psi_ref
    self%rps = rps
    ! the self-propulsion point overcomes the hull's R_0 and the windage in still air
    extra = 0.0_wp
    if (self%hull%empirical) then
      air = ship_wind_load(self%hull%wind, [-headway, 0.0_wp, 0.0_wp])
      extra = -air(1)
    end if
    if (rps <= 0.0_wp) self%rps = mmg_self_propulsion(p, headway, extra)
    call self%layout%add("ship_rudder", 1, 0, self%rudder)
    if (autopilot_states(steer) > 0) then
      call self%layout%add("ship_autopilot", autopilot_states(steer), 0, self%autopilot)
    end if
  end subroutine set_mmg

  subroutine ship_after_step(self, t, y)
    class(ship_system_type), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp) :: yaw
    yaw = y(self%body%q(1) + 2)
    if (self%mmg_on) call rudder_switch(self%steer, t, yaw)
    if (abs(yaw - self%psi_ref) > heading_tolerance) then
      call self%refresh_heading(yaw)
      self%wave_cached = .false.
    end if
    if (self%wave_dt > 0.0_wp .and. self%phase_at_initial .and. &
        self%sea%kind /= wave_none .and. .not. self%frozen) call advance_wave_clock(self, t)
  end subroutine ship_after_step

  !> Keep the Hermite window of the Froude-Krylov loads on the grid interval that holds t:
  !> shift by one interval (one new sample) or, after a jump or a heading refresh, resample
  !> both ends.
  subroutine advance_wave_clock(self, t)
    type(ship_system_type), intent(inout) :: self
    real(wp), intent(in) :: t
    real(wp) :: t0
    t0 = self%wave_dt*floor(t/self%wave_dt)
    if (self%wave_cached .and. t0 == self%wave_t(1)) return
    if (self%wave_cached .and. t0 == self%wave_t(2)) then
      self%wave_t(1) = self%wave_t(2)
      self%wave_f(:, 1) = self%wave_f(:, 2)
      self%wave_d(:, 1) = self%wave_d(:, 2)
    else
      self%wave_t(1) = t0
      call fk_unramped(self, t0, self%wave_f(:, 1), self%wave_d(:, 1))
    end if
    self%wave_t(2) = t0 + self%wave_dt
    call fk_unramped(self, self%wave_t(2), self%wave_f(:, 2), self%wave_d(:, 2))
    self%wave_cached = .true.
  end subroutine advance_wave_clock

  !> Froude-Krylov loads (heading frame, without the start-up ramp) at the initial position
  !> and their time derivatives.
  subroutine fk_unramped(self, t, load, rate)
    type(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(out) :: load(6), rate(6)
    real(wp) :: s(wave_chunk), cs(wave_chunk), o(2), we(wave_chunk)
    integer :: j, i0, i1, m
    load = 0.0_wp
    rate = 0.0_wp
    o = phase_origin(self, t)
    associate (sea => self%sea)
      do i0 = 1, sea%n, wave_chunk
        m = min(wave_chunk, sea%n - i0 + 1)
        i1 = i0 + m - 1
        call component_phases(sea, i0, m, t, o(1), o(2), s, cs)
        ! the phase's rate: the encounter frequency in the moving frame
        we(1:m) = sea%omega(i0:i1) - sea%kx(i0:i1)*self%frame_velocity(1) - &
                  sea%ky(i0:i1)*self%frame_velocity(2)
        do j = 1, 6
          load(j) = load(j) + sum(self%fk_sin(j, i0:i1)*s(1:m)) + &
                    sum(self%fk_cos(j, i0:i1)*cs(1:m))
          rate(j) = rate(j) + sum(we(1:m)*(self%fk_sin(j, i0:i1)*cs(1:m) - &
                                           self%fk_cos(j, i0:i1)*s(1:m)))
        end do
      end do
    end associate
  end subroutine fk_unramped

  !> Cubic Hermite interpolation of the cached loads at t in the window.
  pure function fk_interpolated(self, t) result(load)
    type(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp) :: load(6), h, s, h00, h10, h01, h11
    h = self%wave_t(2) - self%wave_t(1)
    s = (t - self%wave_t(1))/h
    h00 = (1.0_wp + 2.0_wp*s)*(1.0_wp - s)**2
    h10 = s*(1.0_wp - s)**2
    h01 = s*s*(3.0_wp - 2.0_wp*s)
    h11 = s*s*(s - 1.0_wp)
    load = h00*self%wave_f(:, 1) + h10*h*self%wave_d(:, 1) + h01*self%wave_f(:, 2) + &
           h11*h*self%wave_d(:, 2)
  end function fk_interpolated

  !> The ship alone: its Kane blocks and eq. 89.
  subroutine ship_rhs(self, t, y, dydt)
    class(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: kane(3, size(y))
    call self%kane_blocks(t, y, dydt, kane)
    call kane_rates(self%layout, kane, dydt)
  end subroutine ship_rhs

  !> Kane blocks of the ship over its own slice of the state (eqs. 35-41 with review
  !> §1.2): q_dot from eq. (5) and the MMG q_dot = C v; V = rigid-body plus added mass and
  !> inertia (the BEM ship: a full block with A(inf), V = 1 here and its inverse in the
  !> layout); W phi = omega x (I_g omega) and omega x (M v); F = all external loads (the
  !> BEM ship's minus its radiation memory, whose states it advances). A frozen ship has
  !> no rates.
  subroutine ship_kane_blocks(self, t, y, dydt, kane)
    class(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    real(wp) :: c(3, 3), m(3, 3), load(6), mu(6), vh(3)
    if (self%frozen) then
      call kane_at_rest(dydt, kane)
      return
    end if
    associate (b => self%body, r => self%radiation)
      associate (q => y(b%q(1):b%q(2)), u => y(b%u(1):b%u(2)))
        c = rotation_matrix(q(1:3))
        load = ship_loads(self, t, q, u, c)
        dydt(b%q(1):b%q(1) + 2) = euler_rates(q(1:3), u(1:3))
        dydt(b%q(1) + 3:b%q(2)) = matmul(c, u(4:6))
        if (self%mmg_on) call mmg_blocks(self, t, q, u, c, y, load, dydt)
        if (self%control%q(2) >= self%control%q(1)) then
          call integral_control(self, q, c, y(self%control%q(1):self%control%q(2)), load, &
                                dydt(self%control%q(1):self%control%q(2)))
        end if
        if (self%bem) then
          ! the memory of Cummins' equation in the seakeeping frame (bem_loads): fed the
          ! speeds resolved there relative to the frame's own (u - U: zero-speed memory
          ! functions about the steady forward motion), its load turned into ship axes
          m = level_to_body(q(3), c)
          vh = matmul(transpose(m), u(4:6))
          if (self%frame_speed /= 0.0_wp) vh(1) = vh(1) - self%frame_speed
          call bem_memory(self%hydro%db, y(r%q(1):r%q(2)), [vh, matmul(transpose(m), u(1:3))], &
                          dydt(r%q(1):r%q(2)), mu)
          call bem_blocks(self%hydro, self%hull%restrained, u, m, load - turn_to_body(m, mu), &
                          kane(:, b%u(1):b%u(2)))
        else
          call box_blocks(self%hull, u, level_to_body(q(3), c), load, kane(:, b%u(1):b%u(2)))
        end if
      end associate
    end associate
  end subroutine ship_kane_blocks

  !> The MMG loads at the rudder angle of state y, added to `load`, and the rates of the
  !> steering gear and of the autopilot's integral (into dydt).
  pure subroutine mmg_blocks(self, t, q, u, c, y, load, dydt)
    type(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t, q(6), u(6), c(3, 3), y(:)
    real(wp), intent(inout) :: load(6), dydt(:)
    real(wp) :: a(2), order
    integer :: k, j
    ! the horizontal added masses that the ship's mass matrix holds: the MMG set's on the
    ! box (davit_ship_hull), the BEM ship's A(inf) (its memory adds the rest at low frequency)
    a = self%hull%added_mass(1:2)
    if (self%bem) a = [self%hydro%db%added_mass_inf(1, 1), self%hydro%db%added_mass_inf(2, 2)]
    associate (delta => y(self%rudder%q(1)))
      load = load + mmg_body_load(self%mmg, self%hull%cg_x, a(1), a(2), &
                                  level_to_body(q(3), c), u, delta, self%rps)
      if (self%autopilot%q(2) >= self%autopilot%q(1)) then
        k = self%autopilot%q(1)
        j = self%autopilot%q(2)
        call autopilot_order(self%steer, t, q(3), u(3), y(k:j), order, dydt(k:j))
      else
        order = rudder_order(self%steer, t, q(3), u(3))
      end if
      dydt(self%rudder%q(1)) = rudder_rate(self%steer, delta, order)
    end associate
  end subroutine mmg_blocks

  !> The integral term of the heading and station keeping: its states z integrate the
  !> errors (inertial x, y of the CG; yaw), and -k_i z adds to the loads (ship axes).
  pure subroutine integral_control(self, q, c, z, load, zdot)
    type(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: q(6), c(3, 3), z(3)
    real(wp), intent(inout) :: load(6)
    real(wp), intent(out) :: zdot(3)
    zdot = [q(4) - self%anchor(1), q(5) - self%anchor(2), q(3) - self%anchor(3)]
    load(1:3) = load(1:3) + matmul(transpose(c), [-self%moor_i(1:2)*z(1:2), 0.0_wp])
    load(6) = load(6) - self%moor_i(3)*z(3)
  end subroutine integral_control


  !> All external loads (X, Y, Z, K, M, N) in ship axes about G.
  function ship_loads(self, t, q, u, c) result(load)
    class(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t, q(6), u(6), c(3, 3)
    real(wp) :: load(6)
    real(wp) :: fz, wz, p, vrel(3), o(2)
    associate (h => self%hull, om => u(1:3), v => u(4:6))
      p = om(1)
      if (self%bem) then
        ! the database's hydrostatics; radiation damping is the memory (ship_kane_blocks)
        load = bem_restoring(self%hydro, q(6) - self%z_eq, q(1) - h%list, q(2) - h%trim, &
                             level_to_body(q(3), c))
        load(4) = load(4) - self%hydro%b44*p - h%b44q*abs(p)*p
      else
        ! hydrostatic restoring about the equilibrium (weight and buoyancy cancel there)
        fz = -h%c33*(q(6) - self%z_eq)
        ! radiation damping of heave acts on the vertical velocity in N
        wz = dot_product(c(3, :), v)
        fz = fz - h%b33*wz
        load(1:3) = fz*c(3, :)
        load(4) = -h%c44*(q(1) - h%list) - h%b44*p - h%b44q*abs(p)*p
        load(5) = -h%c55*(q(2) - h%trim) - h%b55*om(2)
        load(6) = 0.0_wp
      end if
      if (h%empirical) then
        if (.not. self%mmg_on) then
          load = load + crossflow(h, self%wetted, v, om(3)) + manoeuvring(h, v, om(3))
          load(1) = load(1) + self%thrust
        end if
        vrel = matmul(transpose(c), wind_velocity(self%wind)) - v
        load = load + ship_wind_load(h%wind, vrel)
      end if
      if (self%sea%kind /= wave_none) load = load + heading_to_body(wave_loads(self, t, q, c), &
                                                                    q(1:3), c)
      if (self%drift /= drift_none .and. self%sea%kind /= wave_none) then
        o = phase_origin(self, t)
        load = load + heading_to_body(drift_load(self%drift, self%sea, self%drift_coef, t, &
                                                 o(1), o(2)), q(1:3), c)
      end if
      if (any(self%moor_k > 0.0_wp)) load = load + mooring(self, q, u, c)
    end associate
  end function ship_loads

  !> Horizontal spring-dashpot on the CG (inertial x, y) and on the yaw angle.
  pure function mooring(self, q, u, c) result(load)
    class(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: q(6), u(6), c(3, 3)
    real(wp) :: load(6), f(3), vn(3)
    vn = matmul(c, u(4:6))
    f(1:2) = -self%moor_k(1:2)*(q(4:5) - self%anchor(1:2)) - self%moor_c(1:2)*vn(1:2)
    f(3) = 0.0_wp
    load(1:3) = matmul(transpose(c), f)
    load(4:5) = 0.0_wp
    load(6) = -self%moor_k(3)*(q(3) - self%anchor(3)) - self%moor_c(3)*u(3)
  end function mooring

  !> The box loads are those of the upright box at the ship's heading (linear seakeeping):
  !> they act in the yawed, level frame and are turned into the rolled and pitched ship axes,
  !> F_b = C^T Rz(psi) F_h, so that a heeled ship does not tip its sway force into heave.
  pure function heading_to_body(load, euler, c) result(out)
    real(wp), intent(in) :: load(6), euler(3), c(3, 3)
    real(wp) :: out(6)
    out = turn_to_body(level_to_body(euler(3), c), load)
  end function heading_to_body

  !> m = C^T Rz(psi): components in the level frame yawed by psi (the seakeeping frame)
  !> to ship axes.
  pure function level_to_body(psi, c) result(m)
    real(wp), intent(in) :: psi, c(3, 3)
    real(wp) :: m(3, 3)
    m = matmul(transpose(c), rotation_matrix([0.0_wp, 0.0_wp, psi]))
  end function level_to_body


  !> Where the linear wave loads take the waves' phase at time t: the CG's (box: O''s)
  !> initial horizontal position carried along by the seakeeping frame.
  pure function phase_origin(self, t) result(o)
    type(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp) :: o(2)
    o = self%origin + self%frame_velocity*t
  end function phase_origin

  !> Zero-speed cross-flow drag for sway and yaw, -1/2 rho d C_D |v + x r| (v + x r) along
  !> the hull, and surge resistance -1/2 rho S C_T |u| u (review G12).
  pure function crossflow(h, wetted, v, r) result(load)
    type(hull_type), intent(in) :: h
    real(wp), intent(in) :: wetted, v(3), r
    real(wp) :: load(6), x, vl, half
    integer :: k
    load = 0.0_wp
    half = 0.5_wp*h%lpp
    do k = 1, ngauss
      x = half*gx(k)
      vl = v(2) + x*r
      load(2) = load(2) - gw(k)*half*abs(vl)*vl
      load(6) = load(6) - gw(k)*half*abs(vl)*vl*x
    end do
    load([2, 6]) = 0.5_wp*rho_water*h%draught*h%cd*load([2, 6])
    load(1) = -0.5_wp*rho_water*wetted*surge_ct*abs(v(1))*v(1)
  end function crossflow

  !> Linear MMG hull forces (Kijima), written dimensionally so they vanish smoothly as the
  !> forward speed u -> 0 (no division by U): Y = 1/2 rho L d |u| (Y'_v v + Y'_r L r), and
  !> N alike with one more L. The lifting-hull derivatives hold for small drift angles when
  !> making way, so they scale with the forward speed |u|, not |V|: a ship drifting
  !> sideways at zero headway (drift angle 90 deg) feels only the cross-flow drag.
  pure function manoeuvring(h, v, r) result(load)
    type(hull_type), intent(in) :: h
    real(wp), intent(in) :: v(3), r
    real(wp) :: load(6), q
    load = 0.0_wp
    q = 0.5_wp*rho_water*h%lpp*h%draught*abs(v(1))
    load(2) = q*(h%yv*v(2) + h%yr*h%lpp*r)
    load(6) = q*h%lpp*(h%nv*v(2) + h%nr*h%lpp*r)
  end function manoeuvring

  !> Froude-Krylov loads of all components at the ship's position: the phase of each
  !> component at O' (review §1.8, "position phase").
  function wave_loads(self, t, q, c) result(load)
    class(ship_system_type), intent(in) :: self
    real(wp), intent(in) :: t, q(6), c(3, 3)
    real(wp) :: load(6), o(3), s(wave_chunk), cs(wave_chunk)
    integer :: j, i0, i1, m
    associate (sea => self%sea)
      if (self%wave_cached .and. t >= self%wave_t(1) .and. t <= self%wave_t(2)) then
        load = wave_ramp(sea, t)*fk_interpolated(self, t)
        return
      end if
      if (self%phase_at_initial) then
        o(1:2) = phase_origin(self, t)
      else
        o = q(4:6) - matmul(c, [self%hull%cg_x, 0.0_wp, self%hull%cg_z])
      end if
      load = 0.0_wp
      do i0 = 1, sea%n, wave_chunk
        m = min(wave_chunk, sea%n - i0 + 1)
        i1 = i0 + m - 1
        call component_phases(sea, i0, m, t, o(1), o(2), s, cs)
        do j = 1, 6
          load(j) = load(j) + sum(self%fk_sin(j, i0:i1)*s(1:m)) + &
                    sum(self%fk_cos(j, i0:i1)*cs(1:m))
        end do
      end do
      load = wave_ramp(sea, t)*load
    end associate
  end function wave_loads

end module davit_ship_ship_model
