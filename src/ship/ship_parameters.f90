!> What the 6-DOF ship is: set at build (davit_ship_ship_model's new_ship_system and its
!> set_mooring, set_mmg, set_drift) and read only afterwards, by the right-hand side and the
!> after-step hook. What the time loop updates is in davit_ship_ship_history; the state
!> itself (attitude, position, speeds, memory, rudder) is the solver's vector y, laid out
!> by `layout`.
module davit_ship_ship_parameters
  use davit_kinds, only: wp
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_sea_wind, only: wind_type
  use davit_ship_hull, only: hull_type
  use davit_ship_ship_hydro, only: ship_hydro_type
  use davit_ship_manoeuvring, only: manoeuvring_type
  use davit_ship_wave_drift, only: wave_drift_type
  implicit none
  private
  public :: ship_params_type, phase_origin

  !> The ship's hull, environment, switches and state layout.
  type :: ship_params_type
    !> The box hull (Table 1: dimensions, mass, strip-theory coefficients, windage).
    type(hull_type) :: hull
    !> The sea and wind the ship is in.
    type(wave_field_type) :: sea
    !> The wind (davit_sea_wind).
    type(wind_type) :: wind
    !> A frozen ship has no rates (it stays in its initial pose).
    logical :: frozen = .false.
    !> Equilibrium CG depth [m], wetted surface [m^2], constant thrust [N] that holds the
    !> initial headway against the surge resistance.
    real(wp) :: z_eq = 0.0_wp, wetted = 0.0_wp, thrust = 0.0_wp
    !> Linear seakeeping: wave phases taken at the initial position of O' (review §1.8's
    !> position phase with the mean position), so a slow drift does not feed back into
    !> the excitation. With the current position instead, the Froude-Krylov sway force
    !> gains a second-order mean part and the ship drifts at ~1 m/s in 2 m beam waves.
    logical :: phase_at_initial = .true.
    !> That initial horizontal position [m] (box: O'; BEM ship: the CG).
    real(wp) :: origin(2) = 0.0_wp
    !> The seakeeping frame of a ship making way (any headway): it moves at the headway U
    !> along the initial heading, frame_velocity = U (cos psi_0, sin psi_0) [m/s], so the linear
    !> wave loads see the phase at origin + frame_velocity t, hence the encounter
    !> frequency omega_e = omega - k U cos(beta); the radiation memory is fed the speeds
    !> relative to it, (u - U, v, w) (frame_speed = U [m/s]). Zero: the frame at rest.
    real(wp) :: frame_velocity(2) = 0.0_wp, frame_speed = 0.0_wp
    !> Optional soft mooring of surge, sway and yaw (stiffness [N/m, N m/rad] and damping),
    !> used by the RAO runs to hold the mean position and heading as a frequency-domain RAO
    !> assumes, and as the heading (and station) keeping of the 'launch' scene, where an
    !> integral term (moor_i, on the states of part "ship_control": the time integrals of
    !> the errors) takes out steady offsets such as the wind's yaw moment (a PID autopilot
    !> or DP). Zero = off; the set-point is the history's `anchor`.
    real(wp) :: moor_k(3) = 0.0_wp, moor_c(3) = 0.0_wp, moor_i(3) = 0.0_wp
    !> The ship's state: part "ship" (rigid body: body) and, for the BEM ship, part
    !> "ship_radiation" (its memory states: radiation); the mooring's integral states
    !> "ship_control" (control), the MMG rudder angle "ship_rudder" (rudder) and the
    !> autopilot's states "ship_autopilot" (autopilot, PID only).
    type(state_layout_type) :: layout
    !> The parts' ranges in the ship's own state.
    type(state_part_type) :: body, radiation, control, rudder, autopilot
    !> The hydrodynamics' level (davit_ship_ship_hydro): the paper's box or the BEM ship
    !> (Cummins' equation from a Capytaine database), chosen at build.
    class(ship_hydro_type), allocatable :: hydro
    !> The manoeuvring model (davit_ship_manoeuvring): Kijima's derivatives, cross-flow
    !> drag and constant thrust, or (set_mmg) the MMG model with its propeller
    !> revolutions; the steering is in the history (its zig-zag switches).
    class(manoeuvring_type), allocatable :: manoeuvring
    !> The BEM ship's wave drift level (davit_ship_wave_drift: drift_mean, drift_newman;
    !> not allocated: no drift load); its heading-dependent coefficients are in the history.
    class(wave_drift_type), allocatable :: drift
  end type ship_params_type

contains

  !> Where the linear wave loads take the waves' phase at time t [s]: the CG's (box: O''s)
  !> initial horizontal position carried along by the seakeeping frame.
  pure function phase_origin(par, t) result(o)
    !> The ship's parameters.
    type(ship_params_type), intent(in) :: par
    !> Time [s].
    real(wp), intent(in) :: t
    real(wp) :: o(2)
    o = par%origin + par%frame_velocity*t
  end function phase_origin

end module davit_ship_ship_parameters
