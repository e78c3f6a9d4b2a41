!> The ship's hydrodynamics as a level of detail (&ship model), chosen once at build: the
!> paper's box ('fk_box': Froude-Krylov box loads in closed form, constant strip-theory
!> added masses, hydrostatic and damping coefficients of Table 1 and the review's G10-G12)
!> or Cummins' equation from a BEM database ('bem', davit_ship_bem_loads: A(inf),
!> radiation memory states, diffraction, the mesh's hydrostatics and mass). The ship's
!> right-hand side, after-step hook and builders call these bindings and never ask which
!> level it is; the loads both levels share (manoeuvring, cross-flow, wind, heading
!> keeping) stay in davit_ship_ship_model.
module davit_ship_ship_hydro
  use davit_kinds, only: wp, pi
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_core_rotation, only: rotation_matrix
  use davit_sea_wave_field, only: wave_field_type
  use davit_ship_bem_loads, only: bem_ship_type, bem_wave_coefficients, bem_restoring, &
                                 bem_memory, turn_to_body, bem_speed_load
  use davit_ship_froude_krylov, only: fk_box_load, fk_transfer
  use davit_ship_hull, only: hull_type
  use davit_ship_ship_blocks, only: box_blocks, bem_blocks
  use davit_ship_wave_drift, only: drift_coefficients
  implicit none
  private
  public :: ship_hydro_type, box_hydro_type, bem_hydro_type, level_to_body

  !> A level of the ship's hydrodynamics.
  type, abstract :: ship_hydro_type
  contains
    procedure(origin_i), deferred :: wave_origin
    procedure(add_states_i), deferred :: add_states
    procedure(coefficients_i), deferred :: heading_coefficients
    procedure(still_water_i), deferred :: still_water
    procedure(blocks_i), deferred :: blocks
    procedure(masses_i), deferred :: horizontal_added_mass
    procedure(masses_i), deferred :: horizontal_inertia
  end type ship_hydro_type

  !> The paper's box: its data are the hull's (davit_ship_hull).
  type, extends(ship_hydro_type) :: box_hydro_type
  contains
    procedure :: wave_origin => box_origin
    procedure :: add_states => box_states
    procedure :: heading_coefficients => box_coefficients
    procedure :: still_water => box_still_water
    procedure :: blocks => box_hydro_blocks
    procedure :: horizontal_added_mass => box_added_mass
    procedure :: horizontal_inertia => box_inertia
  end type box_hydro_type

  !> The BEM ship: Cummins' equation from its database.
  type, extends(ship_hydro_type) :: bem_hydro_type
    !> The database, mass and damping (davit_ship_bem_loads).
    type(bem_ship_type) :: bem
  contains
    procedure :: wave_origin => bem_origin
    procedure :: add_states => bem_states
    procedure :: heading_coefficients => bem_coefficients
    procedure :: still_water => bem_still_water
    procedure :: blocks => bem_hydro_blocks
    procedure :: horizontal_added_mass => bem_added_mass
    procedure :: horizontal_inertia => bem_inertia
  end type bem_hydro_type

  abstract interface
    !> The horizontal point whose initial position the linear wave loads take their
    !> phase at [m].
    pure function origin_i(self, hull, position, heading) result(o)
      import :: ship_hydro_type, hull_type, wp
      !> The level.
      class(ship_hydro_type), intent(in) :: self
      !> The hull (CG forward of the box's O').
      type(hull_type), intent(in) :: hull
      !> Initial CG position (inertial) [m] and heading [rad].
      real(wp), intent(in) :: position(3), heading
      real(wp) :: o(2)
    end function origin_i

    !> Register the level's own states after the rigid body's part `body`.
    subroutine add_states_i(self, layout, body, radiation)
      import :: ship_hydro_type, state_layout_type, state_part_type
      !> The level.
      class(ship_hydro_type), intent(in) :: self
      !> The ship's state layout, parts added.
      type(state_layout_type), intent(inout) :: layout
      !> The rigid body's part (its speeds get the level's mass block).
      type(state_part_type), intent(in) :: body
      !> The radiation memory's part (left empty without one).
      type(state_part_type), intent(inout) :: radiation
    end subroutine add_states_i

    !> The wave load coefficients of every component at heading psi: the loads about G
    !> are fk_sin(:, i) sin(Phi_i) + fk_cos(:, i) cos(Phi_i) [N, N m]; with drift_coef
    !> allocated, the wave drift coefficients too (surge, sway, yaw).
    pure subroutine coefficients_i(self, hull, sea, psi, fk_sin, fk_cos, drift_coef)
      import :: ship_hydro_type, hull_type, wave_field_type, wp
      !> The level.
      class(ship_hydro_type), intent(in) :: self
      !> The hull (the box's dimensions, G's position).
      type(hull_type), intent(in) :: hull
      !> The sea (amplitudes, wave numbers, directions).
      type(wave_field_type), intent(in) :: sea
      !> Heading [rad].
      real(wp), intent(in) :: psi
      !> The coefficients (6, components) [N, N m].
      real(wp), intent(inout) :: fk_sin(:, :), fk_cos(:, :)
      !> The drift coefficients (3, components), written where allocated.
      real(wp), allocatable, intent(inout) :: drift_coef(:, :)
    end subroutine coefficients_i

    !> Hydrostatic restoring about the equilibrium and the damping of the level, in ship
    !> axes about G (X, Y, Z [N], K, M, N [N m]).
    pure function still_water_i(self, hull, z_eq, q, u, c) result(load)
      import :: ship_hydro_type, hull_type, wp
      !> The level.
      class(ship_hydro_type), intent(in) :: self
      !> The hull (list, trim, the quadratic roll damping; the box's coefficients).
      type(hull_type), intent(in) :: hull
      !> Equilibrium CG depth [m], Euler angles and CG position [rad, m], speeds (Kane
      !> order), rotation ship -> inertial.
      real(wp), intent(in) :: z_eq, q(6), u(6), c(3, 3)
      real(wp) :: load(6)
    end function still_water_i

    !> The Kane blocks of the ship's six speeds under the external loads `load`, and the
    !> rates of the level's own states x (its radiation memory).
    pure subroutine blocks_i(self, hull, frame_speed, q, u, c, load, x, xdot, kane)
      import :: ship_hydro_type, hull_type, wp
      !> The level.
      class(ship_hydro_type), intent(in) :: self
      !> The hull (masses, restrained DOFs, forward-speed terms, trim).
      type(hull_type), intent(in) :: hull
      !> Speed of the seakeeping frame [m/s], Euler angles and CG position [rad, m], speeds
      !> (Kane order), rotation ship -> inertial, external loads in ship axes about G.
      real(wp), intent(in) :: frame_speed, q(6), u(6), c(3, 3), load(6)
      !> The level's own states (none for the box).
      real(wp), intent(in) :: x(:)
      !> Their rates.
      real(wp), intent(inout) :: xdot(:)
      !> Rows V, W phi, F of the six speeds (davit_core_kane).
      real(wp), intent(out) :: kane(3, 6)
    end subroutine blocks_i

    !> Masses in the horizontal plane: surge and sway [kg], yaw [kg m^2] (the added
    !> masses the mass matrix holds, or those and the rigid body's).
    pure function masses_i(self, hull) result(m)
      import :: ship_hydro_type, hull_type, wp
      !> The level.
      class(ship_hydro_type), intent(in) :: self
      !> The hull.
      type(hull_type), intent(in) :: hull
      real(wp) :: m(3)
    end function masses_i
  end interface

contains

  !> m = C^T Rz(psi): components in the level frame yawed by psi (the seakeeping frame)
  !> to ship axes.
  pure function level_to_body(psi, c) result(m)
    !> Yaw [rad] and rotation ship -> inertial.
    real(wp), intent(in) :: psi, c(3, 3)
    real(wp) :: m(3, 3)
    m = matmul(transpose(c), rotation_matrix([0.0_wp, 0.0_wp, psi]))
  end function level_to_body

  !> The box's phases are taken at its O', cg_x aft of G.
  pure function box_origin(self, hull, position, heading) result(o)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> Initial CG position (inertial) [m] and heading [rad].
    real(wp), intent(in) :: position(3), heading
    real(wp) :: o(2)
    o = position(1:2) - [cos(heading), sin(heading)]*hull%cg_x
  end function box_origin

  !> The database's loads are about the CG: their phases at its horizontal position.
  pure function bem_origin(self, hull, position, heading) result(o)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> Initial CG position (inertial) [m] and heading [rad].
    real(wp), intent(in) :: position(3), heading
    real(wp) :: o(2)
    o = position(1:2)
  end function bem_origin

  !> The box has no states of its own.
  subroutine box_states(self, layout, body, radiation)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The ship's state layout, parts added.
    type(state_layout_type), intent(inout) :: layout
    !> The rigid body's part (its speeds get the level's mass block).
    type(state_part_type), intent(in) :: body
    !> The radiation memory's part (left empty without one).
    type(state_part_type), intent(inout) :: radiation
  end subroutine box_states

  !> The radiation memory's states (part "ship_radiation") and M + A(inf) as the speeds'
  !> full mass block.
  subroutine bem_states(self, layout, body, radiation)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The ship's state layout, parts added.
    type(state_layout_type), intent(inout) :: layout
    !> The rigid body's part (its speeds get the level's mass block).
    type(state_part_type), intent(in) :: body
    !> The radiation memory's part (left empty without one).
    type(state_part_type), intent(inout) :: radiation
    call layout%add("ship_radiation", self%bem%db%nrad, 0, radiation)
    call layout%couple(body%u, self%bem%v_inv)
  end subroutine bem_states

  !> The upright box's Froude-Krylov loads (review §1.8): X, Y, K, M go with sin(Phi), Z
  !> and N with cos(Phi), split before the transfer to G, which mixes them (M_G gets
  !> x_G Z, N_G gets -x_G Y). The box has no drift coefficients (zero).
  pure subroutine box_coefficients(self, hull, sea, psi, fk_sin, fk_cos, drift_coef)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> The sea (amplitudes, wave numbers, directions).
    type(wave_field_type), intent(in) :: sea
    !> Heading [rad].
    real(wp), intent(in) :: psi
    !> The coefficients (6, components) [N, N m].
    real(wp), intent(inout) :: fk_sin(:, :), fk_cos(:, :)
    !> The drift coefficients (3, components), written where allocated.
    real(wp), allocatable, intent(inout) :: drift_coef(:, :)
    real(wp) :: raw(6)
    integer :: i
    if (allocated(drift_coef)) drift_coef = 0.0_wp
    do i = 1, sea%n
      raw = fk_box_load(hull%box, sea%amplitude(i), sea%k(i), sea%direction(i) - psi, &
                        0.5_wp*pi)
      raw([3, 6]) = 0.0_wp
      fk_sin(:, i) = fk_transfer(raw, hull%cg_x, hull%cg_z)
      raw = fk_box_load(hull%box, sea%amplitude(i), sea%k(i), sea%direction(i) - psi, 0.0_wp)
      raw([1, 2, 4, 5]) = 0.0_wp
      fk_cos(:, i) = fk_transfer(raw, hull%cg_x, hull%cg_z)
    end do
  end subroutine box_coefficients

  !> The database's Froude-Krylov and diffraction loads, and its mean drift.
  pure subroutine bem_coefficients(self, hull, sea, psi, fk_sin, fk_cos, drift_coef)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> The sea (amplitudes, wave numbers, directions).
    type(wave_field_type), intent(in) :: sea
    !> Heading [rad].
    real(wp), intent(in) :: psi
    !> The coefficients (6, components) [N, N m].
    real(wp), intent(inout) :: fk_sin(:, :), fk_cos(:, :)
    !> The drift coefficients (3, components), written where allocated.
    real(wp), allocatable, intent(inout) :: drift_coef(:, :)
    call bem_wave_coefficients(self%bem, sea, psi, fk_sin, fk_cos)
    if (allocated(drift_coef)) call drift_coefficients(self%bem%db, sea, psi, drift_coef)
  end subroutine bem_coefficients

  !> Restoring about the equilibrium (weight and buoyancy cancel there) and Table 1's
  !> damping (G10-G12); the heave damping acts on the vertical velocity in N.
  pure function box_still_water(self, hull, z_eq, q, u, c) result(load)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> Equilibrium CG depth [m], Euler angles and CG position [rad, m], speeds (Kane
    !> order), rotation ship -> inertial.
    real(wp), intent(in) :: z_eq, q(6), u(6), c(3, 3)
    real(wp) :: load(6), fz, wz, p
    associate (h => hull, om => u(1:3), v => u(4:6))
      p = om(1)
      fz = -h%c33*(q(6) - z_eq)
      wz = dot_product(c(3, :), v)
      fz = fz - h%b33*wz
      load(1:3) = fz*c(3, :)
      load(4) = -h%c44*(q(1) - h%list) - h%b44*p - h%b44q*abs(p)*p
      load(5) = -h%c55*(q(2) - h%trim) - h%b55*om(2)
      load(6) = 0.0_wp
    end associate
  end function box_still_water

  !> The database's hydrostatics and the viscous roll damping; the radiation damping is
  !> the memory (bem_hydro_blocks).
  pure function bem_still_water(self, hull, z_eq, q, u, c) result(load)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> Equilibrium CG depth [m], Euler angles and CG position [rad, m], speeds (Kane
    !> order), rotation ship -> inertial.
    real(wp), intent(in) :: z_eq, q(6), u(6), c(3, 3)
    real(wp) :: load(6), p
    p = u(1)
    load = bem_restoring(self%bem, q(6) - z_eq, q(1) - hull%list, q(2) - hull%trim, &
                         level_to_body(q(3), c))
    load(4) = load(4) - self%bem%b44*p - hull%b44q*abs(p)*p
  end function bem_still_water

  !> The box's constant added masses in the seakeeping frame (box_blocks).
  pure subroutine box_hydro_blocks(self, hull, frame_speed, q, u, c, load, x, xdot, kane)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> Speed of the seakeeping frame [m/s], Euler angles and CG position [rad, m], speeds
    !> (Kane order), rotation ship -> inertial, external loads in ship axes about G.
    real(wp), intent(in) :: frame_speed, q(6), u(6), c(3, 3), load(6)
    !> The level's own states (none for the box).
    real(wp), intent(in) :: x(:)
    !> Their rates.
    real(wp), intent(inout) :: xdot(:)
    !> Rows V, W phi, F of the six speeds (davit_core_kane).
    real(wp), intent(out) :: kane(3, 6)
    call box_blocks(hull, u, level_to_body(q(3), c), load, kane)
  end subroutine box_hydro_blocks

  !> The memory of Cummins' equation in the seakeeping frame (bem_loads): fed the speeds
  !> resolved there relative to the frame's own (u - U: zero-speed memory functions about
  !> the steady forward motion), its load turned into ship axes; with speed_terms, the
  !> body-frame heave speed w + U theta and the forward-speed loads (bem_speed_load).
  pure subroutine bem_hydro_blocks(self, hull, frame_speed, q, u, c, load, x, xdot, kane)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    !> Speed of the seakeeping frame [m/s], Euler angles and CG position [rad, m], speeds
    !> (Kane order), rotation ship -> inertial, external loads in ship axes about G.
    real(wp), intent(in) :: frame_speed, q(6), u(6), c(3, 3), load(6)
    !> The level's own states (none for the box).
    real(wp), intent(in) :: x(:)
    !> Their rates.
    real(wp), intent(inout) :: xdot(:)
    !> Rows V, W phi, F of the six speeds (davit_core_kane).
    real(wp), intent(out) :: kane(3, 6)
    real(wp) :: m(3, 3), mu(6), vh(3), wh(3)
    m = level_to_body(q(3), c)
    vh = matmul(transpose(m), u(4:6))
    if (frame_speed /= 0.0_wp) vh(1) = vh(1) - frame_speed
    if (hull%speed_terms) vh(3) = vh(3) + frame_speed*(q(2) - hull%trim)
    wh = matmul(transpose(m), u(1:3))
    call bem_memory(self%bem%db, x, [vh, wh], xdot, mu)
    if (hull%speed_terms) mu = mu - bem_speed_load(self%bem, x, [vh, wh], frame_speed, &
                                                   hull%speed_sway_yaw)
    call bem_blocks(self%bem, hull%restrained, u, m, load - turn_to_body(m, mu), kane)
  end subroutine bem_hydro_blocks

  !> The box's horizontal added masses (the MMG set's where set: davit_ship_hull).
  pure function box_added_mass(self, hull) result(m)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    real(wp) :: m(3)
    m = [hull%added_mass(1:2), hull%added_inertia(3)]
  end function box_added_mass

  !> The BEM ship's A(inf) (its memory adds the rest at low frequency).
  pure function bem_added_mass(self, hull) result(m)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    real(wp) :: m(3)
    m = [self%bem%db%added_mass_inf(1, 1), self%bem%db%added_mass_inf(2, 2), &
         self%bem%db%added_mass_inf(6, 6)]
  end function bem_added_mass

  !> The box's rigid-body and added masses of surge, sway and yaw.
  pure function box_inertia(self, hull) result(m)
    !> The level.
    class(box_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    real(wp) :: m(3)
    m = [hull%mass + hull%added_mass(1:2), hull%inertia(3) + hull%added_inertia(3)]
  end function box_inertia

  !> The database's rigid-body mass and inertia with A(inf).
  pure function bem_inertia(self, hull) result(m)
    !> The level.
    class(bem_hydro_type), intent(in) :: self
    !> The hull (CG forward of the box's O').
    type(hull_type), intent(in) :: hull
    real(wp) :: m(3)
    m = [self%bem%mass, self%bem%mass, self%bem%inertia(3)] + self%horizontal_added_mass(hull)
  end function bem_inertia

end module davit_ship_ship_hydro
