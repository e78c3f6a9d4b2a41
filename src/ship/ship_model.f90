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
!>
!> The ship is split as the boat's system is: its parameters (davit_ship_ship_parameters,
!> set at build) and its history (davit_ship_ship_history, written by the after-step hook
!> only), the state being the solver's vector.
module davit_ship_ship_model
  use davit_kinds, only: wp, pi, rho_water
  use davit_core_rotation, only: rotation_matrix, euler_rates
  use davit_core_kane, only: kane_rates, kane_at_rest
  use davit_core_slow_clock, only: slow_clock_type
  use davit_ship_bem_loads, only: turn_to_body
  use davit_ship_ship_hydro, only: ship_hydro_type, level_to_body
  use davit_ship_ship_parameters, only: ship_params_type, phase_origin
  use davit_ship_ship_history, only: ship_history_type, refresh_heading, advance_wave_clock, &
                                     wave_loads
  use davit_solve_integrator, only: ode_problem
  use davit_sea_wave_field, only: wave_field_type, wave_none
  use davit_sea_wind, only: wind_type, wind_velocity
  use davit_ship_hull, only: hull_type
  use davit_ship_wind_load, only: ship_wind_load
  use davit_ship_mmg, only: mmg_type, mmg_self_propulsion
  use davit_ship_rudder, only: rudder_type, autopilot_states
  use davit_ship_manoeuvring, only: kijima_type, mmg_manoeuvring_type, crossflow
  use davit_ship_wave_drift, only: wave_drift_type, drift_load
  implicit none
  private
  public :: ship_system_type, new_ship_system, ship_loads, ship_state

  !> The ship as an ODE problem: its parameters (set at build) and its history (written by
  !> the after-step hook and set_heading only); its state is the solver's vector, laid out
  !> by par%layout.
  type, extends(ode_problem) :: ship_system_type
    !> Hull, environment, switches and state layout (davit_ship_ship_parameters): written
    !> by new_ship_system and the set_* switches at build, read only afterwards.
    type(ship_params_type) :: par
    !> Heading-dependent coefficients, slow clock, steering and set-point
    !> (davit_ship_ship_history).
    type(ship_history_type), private :: hist
  contains
    procedure :: rhs => ship_rhs
    procedure :: kane_blocks => ship_kane_blocks
    procedure :: after_step => ship_after_step
    procedure :: set_mooring
    procedure :: set_mmg
    procedure :: set_drift
    procedure :: set_heading
    procedure :: heading_setpoint
    procedure :: heading_reference
    procedure :: wave_clock
    procedure :: wave_coefficients
  end type ship_system_type

  !> Yaw drift [rad] after which the Froude-Krylov coefficients are recomputed.
  real(wp), parameter :: heading_tolerance = 0.5_wp*pi/180.0_wp

contains

  subroutine new_ship_system(self, hull, sea, wind, frozen, position, heading, &
                             phase_at_initial, headway, clock, hydro)
    ! 11 arguments: the ship's parts as the deck gives them (hull, sea, wind, pose, switches,
    ! slow clock)
    !> The ship built.
    type(ship_system_type), intent(out) :: self
    !> Its hull: dimensions, mass and inertia, empirical load coefficients.
    type(hull_type), intent(in) :: hull
    !> The sea it floats in.
    type(wave_field_type), intent(in) :: sea
    !> The wind on its superstructure.
    type(wind_type), intent(in) :: wind
    !> A ship held still (no rates); wave phases taken at the initial position.
    logical, intent(in) :: frozen, phase_at_initial
    !> Initial CG position (inertial) [m], heading [rad] and headway [m/s].
    real(wp), intent(in) :: position(3), heading, headway
    !> The slow clock of the Froude-Krylov loads (rule clock_grid; interval 0: off).
    type(slow_clock_type), intent(in) :: clock
    !> The level of its hydrodynamics: the paper's box or the BEM ship.
    class(ship_hydro_type), intent(in) :: hydro
    real(wp) :: water(6), air(6)
    self%hist%clock = clock
    associate (par => self%par)
      par%phase_at_initial = phase_at_initial
      allocate (par%hydro, source=hydro)
      allocate (par%manoeuvring, source=kijima_type())
      par%origin = hydro%wave_origin(hull, position, heading)
      par%hull = hull
      par%sea = sea
      par%wind = wind
      par%frozen = frozen
      par%z_eq = position(3)
      ! Mumford's wetted surface 1.7 L d + V/d
      par%wetted = 1.7_wp*hull%lpp*hull%draught + hull%mass/rho_water/hull%draught
      ! the engine setting that holds the headway in still air and calm water: water and
      ! air resistance at that speed
      water = crossflow(hull, par%wetted, [headway, 0.0_wp, 0.0_wp], 0.0_wp)
      air = ship_wind_load(hull%wind, [-headway, 0.0_wp, 0.0_wp])
      par%thrust = 0.0_wp
      if (hull%empirical) par%thrust = -(water(1) + air(1))
      ! a ship making way (either manoeuvring model) meets the waves at omega_e: the
      ! seakeeping frame moves at the headway along the initial heading
      par%frame_speed = headway
      par%frame_velocity = headway*[cos(heading), sin(heading)]
      allocate (self%hist%fk_sin(6, sea%n), self%hist%fk_cos(6, sea%n))
      call refresh_heading(self%hist, par, heading)
      call par%layout%add("ship", 6, 6, par%body)
      call hydro%add_states(par%layout, par%body, par%radiation)
    end associate
  end subroutine new_ship_system

  !> The state part of a ship at attitude euler, CG position, angular velocity omega and
  !> velocity v (ship axes): q then u, as the layout registers them.
  pure function ship_state(self, euler, position, omega, v) result(y)
    !> The ship (its state layout).
    class(ship_system_type), intent(in) :: self
    !> Euler angles [rad], CG position (inertial) [m], angular velocity [rad/s] and CG
    !> velocity [m/s] (ship axes).
    real(wp), intent(in) :: euler(3), position(3), omega(3), v(3)
    real(wp) :: y(self%par%layout%n)
    y = 0.0_wp
    y(self%par%body%q(1):self%par%body%u(2)) = [euler, position, omega, v]
  end function ship_state

  !> Switch the BEM ship's wave drift to `level` (its database must hold the coefficients:
  !> davit_system_build checks).
  subroutine set_drift(self, level)
    !> The BEM ship whose drift level is set.
    class(ship_system_type), intent(inout) :: self
    !> drift_mean or drift_newman (davit_ship_wave_drift).
    class(wave_drift_type), intent(in) :: level
    if (allocated(self%par%drift)) deallocate (self%par%drift)
    allocate (self%par%drift, source=level)
    if (allocated(self%hist%drift_coef)) deallocate (self%hist%drift_coef)
    allocate (self%hist%drift_coef(3, self%par%sea%n))
    call refresh_heading(self%hist, self%par, self%hist%psi_ref)
  end subroutine set_drift

  !> Soft mooring with the given natural periods [s] (surge, sway, yaw) and damping ratio,
  !> anchored at the current state; with `integral`, a PID: integral gain k w/10 (integral
  !> time 10/w, slow against the period), its states registered as part "ship_control".
  subroutine set_mooring(self, period, zeta, y, integral)
    !> The ship moored (its gains and, with `integral`, its control states).
    class(ship_system_type), intent(inout) :: self
    !> Natural periods of surge, sway and yaw [s], damping ratio [-], the state anchored at.
    real(wp), intent(in) :: period(3), zeta, y(:)
    !> Whether to add the integral term (a PID autopilot or DP).
    logical, intent(in), optional :: integral
    real(wp) :: inertia(3)
    associate (par => self%par)
      associate (q => y(par%body%q(1):par%body%q(2)))
        self%hist%anchor = [q(4), q(5), q(3)]
      end associate
      inertia = par%hydro%horizontal_inertia(par%hull)
      ! a period <= 0 leaves that motion free
      par%moor_k = 0.0_wp
      where (period > 0.0_wp) par%moor_k = inertia*(2.0_wp*pi/period)**2
      par%moor_c = 2.0_wp*zeta*sqrt(par%moor_k*inertia)
      if (.not. present(integral)) return
      if (.not. integral .or. par%control%q(2) >= par%control%q(1)) return
      par%moor_i = par%moor_k*sqrt(par%moor_k/inertia)/10.0_wp
      if (any(par%moor_i > 0.0_wp)) call par%layout%add("ship_control", 3, 0, par%control)
    end associate
  end subroutine set_mooring

  !> Switch to the MMG manoeuvring model p with the steering `steer` (its heading: the
  !> initial one) and the propeller at `rps` (0: the self-propulsion point at `headway`);
  !> the rudder angle joins the state as part "ship_rudder". The seakeeping frame moves at
  !> `headway` along the initial heading (new_ship_system; the two-time-scale split:
  !> manoeuvring in the horizontal-body frame, seakeeping about this steady motion).
  subroutine set_mmg(self, p, steer, rps, headway)
    !> The ship switched to MMG manoeuvring.
    class(ship_system_type), intent(inout) :: self
    !> The MMG coefficients (hull, propeller, rudder).
    type(mmg_type), intent(in) :: p
    !> The steering: manoeuvre or autopilot, gains, limits.
    type(rudder_type), intent(in) :: steer
    !> Propeller revolutions [1/s] (0: self-propulsion) and headway [m/s].
    real(wp), intent(in) :: rps, headway
    real(wp) :: air(6), extra, n
    associate (par => self%par, psi => self%hist%psi_ref)
      self%hist%steer = steer
      self%hist%steer%heading = psi
      n = rps
      ! the self-propulsion point overcomes the hull's R_0 and the windage in still air
      extra = 0.0_wp
      if (par%hull%empirical) then
        air = ship_wind_load(par%hull%wind, [-headway, 0.0_wp, 0.0_wp])
        extra = -air(1)
      end if
      if (rps <= 0.0_wp) n = mmg_self_propulsion(p, headway, extra)
      deallocate (par%manoeuvring)
      allocate (par%manoeuvring, source=mmg_manoeuvring_type(mmg=p, rps=n))
      call par%layout%add("ship_rudder", 1, 0, par%rudder)
      if (autopilot_states(steer) > 0) then
        call par%layout%add("ship_autopilot", autopilot_states(steer), 0, par%autopilot)
      end if
    end associate
  end subroutine set_mmg

  !> Move the heading set-point of the heading keeping to psi [rad] (an operator turning
  !> the ship between steps).
  pure subroutine set_heading(self, psi)
    !> The ship whose set-point moves.
    class(ship_system_type), intent(inout) :: self
    !> New set-point [rad].
    real(wp), intent(in) :: psi
    self%hist%anchor(3) = psi
  end subroutine set_heading

  !> The heading set-point of the heading keeping [rad].
  pure real(wp) function heading_setpoint(self)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    heading_setpoint = self%hist%anchor(3)
  end function heading_setpoint

  !> The heading [rad] the wave coefficients are computed for.
  pure real(wp) function heading_reference(self)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    heading_reference = self%hist%psi_ref
  end function heading_reference

  !> The slow clock of the Froude-Krylov loads (a copy: its window and whether it holds).
  pure function wave_clock(self) result(clock)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    type(slow_clock_type) :: clock
    clock = self%hist%clock
  end function wave_clock

  !> Froude-Krylov coefficients (sin, cos parts) of DOF j for wave component i at the
  !> reference heading [N, N m].
  pure function wave_coefficients(self, j, i) result(coef)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    !> DOF (1..6: X, Y, Z, K, M, N) and wave component.
    integer, intent(in) :: j, i
    real(wp) :: coef(2)
    coef = [self%hist%fk_sin(j, i), self%hist%fk_cos(j, i)]
  end function wave_coefficients

  !> The after-step hook: the steering's switches, the heading-dependent coefficients when
  !> the yaw has drifted, and the slow clock of the Froude-Krylov loads.
  subroutine ship_after_step(self, t, y)
    !> The ship, its history advanced.
    class(ship_system_type), intent(inout) :: self
    !> Time [s] and the accepted state.
    real(wp), intent(in) :: t, y(:)
    real(wp) :: yaw
    associate (par => self%par, hist => self%hist)
      yaw = y(par%body%q(1) + 2)
      call par%manoeuvring%switch(hist%steer, t, yaw)
      if (abs(yaw - hist%psi_ref) > heading_tolerance) then
        call refresh_heading(hist, par, yaw)
        call hist%clock%invalidate()
      end if
      if (hist%clock%enabled() .and. par%phase_at_initial .and. &
          par%sea%kind /= wave_none .and. .not. par%frozen) call advance_wave_clock(hist, par, t)
    end associate
  end subroutine ship_after_step

  !> The ship alone: its Kane blocks and eq. 89.
  subroutine ship_rhs(self, t, y, dydt)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    !> Time [s].
    real(wp), intent(in) :: t
    !> The ship's state.
    real(wp), intent(in) :: y(:)
    !> Its rates.
    real(wp), intent(out) :: dydt(:)
    real(wp) :: kane(3, size(y))
    call self%kane_blocks(t, y, dydt, kane)
    call kane_rates(self%par%layout, kane, dydt)
  end subroutine ship_rhs

  !> Kane blocks of the ship over its own slice of the state (eqs. 35-41 with review
  !> §1.2): q_dot from eq. (5) and the MMG q_dot = C v; V = rigid-body plus added mass and
  !> inertia (the BEM ship: a full block with A(inf), V = 1 here and its inverse in the
  !> layout); W phi = omega x (I_g omega) and omega x (M v); F = all external loads (the
  !> BEM ship's minus its radiation memory, whose states it advances). A frozen ship has
  !> no rates.
  subroutine ship_kane_blocks(self, t, y, dydt, kane)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    !> Time [s] and the state.
    real(wp), intent(in) :: t, y(:)
    !> The rates of its q and of its other states, and its Kane blocks (davit_core_kane).
    real(wp), intent(inout) :: dydt(:), kane(:, :)
    real(wp) :: c(3, 3), load(6)
    if (self%par%frozen) then
      call kane_at_rest(dydt, kane)
      return
    end if
    associate (par => self%par, b => self%par%body, r => self%par%radiation, &
               z => self%par%control%q)
      associate (q => y(b%q(1):b%q(2)), u => y(b%u(1):b%u(2)))
        c = rotation_matrix(q(1:3))
        load = ship_loads(self, t, q, u, c)
        dydt(b%q(1):b%q(1) + 2) = euler_rates(q(1:3), u(1:3))
        dydt(b%q(1) + 3:b%q(2)) = matmul(c, u(4:6))
        call par%manoeuvring%add_steering(par%hull, par%hydro, self%hist%steer, par%rudder, &
                                          par%autopilot, t, q, u, c, y, load, dydt)
        if (z(2) >= z(1)) then
          call integral_control(par%moor_i, self%hist%anchor, q, c, y(z(1):z(2)), load, &
                                dydt(z(1):z(2)))
        end if
        call par%hydro%blocks(par%hull, par%frame_speed, q, u, c, load, &
                              y(r%q(1):r%q(2)), dydt(r%q(1):r%q(2)), kane(:, b%u(1):b%u(2)))
      end associate
    end associate
  end subroutine ship_kane_blocks

  !> The integral term of the heading and station keeping: its states z integrate the
  !> errors from the set-point `anchor` (inertial x, y of the CG; yaw), and -k_i z adds to
  !> the loads (ship axes).
  pure subroutine integral_control(moor_i, anchor, q, c, z, load, zdot)
    real(wp), intent(in) :: moor_i(3), anchor(3), q(6), c(3, 3), z(3)
    real(wp), intent(inout) :: load(6)
    real(wp), intent(out) :: zdot(3)
    zdot = [q(4) - anchor(1), q(5) - anchor(2), q(3) - anchor(3)]
    load(1:3) = load(1:3) + matmul(transpose(c), [-moor_i(1:2)*z(1:2), 0.0_wp])
    load(6) = load(6) - moor_i(3)*z(3)
  end subroutine integral_control

  !> All external loads (X, Y, Z, K, M, N) in ship axes about G.
  function ship_loads(self, t, q, u, c) result(load)
    !> The ship.
    class(ship_system_type), intent(in) :: self
    !> Time [s], Euler angles and CG position [rad, m], speeds (Kane order), rotation ship
    !> -> inertial.
    real(wp), intent(in) :: t, q(6), u(6), c(3, 3)
    real(wp) :: load(6)
    real(wp) :: vrel(3), o(2)
    associate (par => self%par, h => self%par%hull, om => u(1:3), v => u(4:6))
      load = par%hydro%still_water(h, par%z_eq, q, u, c)
      if (h%empirical) then
        call par%manoeuvring%add_hull_loads(h, par%wetted, par%thrust, u, load)
        vrel = matmul(transpose(c), wind_velocity(par%wind)) - v
        load = load + ship_wind_load(h%wind, vrel)
      end if
      if (par%sea%kind /= wave_none) load = load + &
                                            heading_to_body(wave_loads(par, self%hist, t, q, c), &
                                                            q(1:3), c)
      if (allocated(par%drift) .and. par%sea%kind /= wave_none) then
        o = phase_origin(par, t)
        load = load + heading_to_body(drift_load(par%drift, par%sea, self%hist%drift_coef, t, &
                                                 o(1), o(2)), q(1:3), c)
      end if
      if (any(par%moor_k > 0.0_wp)) load = load + mooring(par, self%hist%anchor, q, u, c)
    end associate
  end function ship_loads

  !> Horizontal spring-dashpot on the CG (inertial x, y) and on the yaw angle, about the
  !> set-point `anchor`.
  pure function mooring(par, anchor, q, u, c) result(load)
    type(ship_params_type), intent(in) :: par
    real(wp), intent(in) :: anchor(3), q(6), u(6), c(3, 3)
    real(wp) :: load(6), f(3), vn(3)
    vn = matmul(c, u(4:6))
    f(1:2) = -par%moor_k(1:2)*(q(4:5) - anchor(1:2)) - par%moor_c(1:2)*vn(1:2)
    f(3) = 0.0_wp
    load(1:3) = matmul(transpose(c), f)
    load(4:5) = 0.0_wp
    load(6) = -par%moor_k(3)*(q(3) - anchor(3)) - par%moor_c(3)*u(3)
  end function mooring

  !> The box loads are those of the upright box at the ship's heading (linear seakeeping):
  !> they act in the yawed, level frame and are turned into the rolled and pitched ship axes,
  !> F_b = C^T Rz(psi) F_h, so that a heeled ship does not tip its sway force into heave.
  pure function heading_to_body(load, euler, c) result(out)
    real(wp), intent(in) :: load(6), euler(3), c(3, 3)
    real(wp) :: out(6)
    out = turn_to_body(level_to_body(euler(3), c), load)
  end function heading_to_body

end module davit_ship_ship_model
