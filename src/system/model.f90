!> The assembled multibody system and its Kane right-hand side (eqs. 12, 89).
!>
!> State vector y = [q; u]: q = (theta1..3, q4..6) and u = (omega_b, v_b) of the lifeboat
!> (eqs. 3-4). The assembler only sums each force model's generalized force and forms
!> u_dot = (F - W phi)/V (eq. 89) and q_dot from eqs. (5)-(6). Force models are pure
!> functions of (t, state): gravity (eq. 13), the rigging (eq. 26; here the foundation's two
!> massless slings, which the full cable-pulley rigging replaces behind the same hook-force
!> role), water by strip theory (eqs. 18-25), wind (eqs. 14-17) and fender contact with the
!> ship's side (eq. 34). The only history, the fenders' contact phases, is advanced after
!> each accepted step (after_step), never inside the RHS.
module davit_system_model
  use davit_kinds, only: wp, gravity, rho_water
  use davit_core_rotation, only: rotation_matrix, cross
  use davit_core_body, only: rigid_body_type, body_mass_diagonal, body_w_phi, body_qdot, &
                             body_gravity_force, body_point_force, body_point_velocity, &
                             body_inertial_position, body_kinetic_energy
  use davit_rigging_elastic_sling, only: elastic_sling_type, sling_hook_force, sling_energy
  use davit_solve_integrator, only: ode_problem
  use davit_io_config, only: config_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_sea_wind, only: wind_type, wind_velocity
  use davit_sea_builder, only: build_wave_field, build_wind
  use davit_boat_hull, only: new_boat_hull
  use davit_boat_strip_loads, only: strip_model_type, new_strip_model, strip_loads
  use davit_boat_wind_loads, only: boat_wind_type, boat_wind_force, lift_symmetric, &
                                   lift_literal
  use davit_boat_contact, only: fender_state_type, fender_update, new_contact_law, &
                                law_hertz_elastoplastic, law_lankarani_nikravesh, &
                                phase_compression, phase_free
  use davit_boat_fenders, only: side_plane_type, fender_set_type, new_fender_set, &
                                fender_probe, fender_loads
  use davit_rigging_rigging, only: rigging_type, new_rigging
  use davit_core_pose, only: ship_pose_type => pose_type
  use davit_boat_strip_waves, only: strip_wave_cache_type, new_strip_wave_cache, &
                                    strip_waves_due, strip_waves_refresh
  use davit_boat_surface_watch, only: surface_watch_type, new_surface_watch, watch_refresh, &
                                      surely_dry, strip_surely_dry
  use davit_error, only: error_type
  use davit_ship_hull, only: hull_type, new_hull
  use davit_ship_ship_model, only: ship_system_type, new_ship_system, ship_nstate
  use davit_system_ship_scene, only: ship_initial_state
  implicit none
  private
  public :: system_type, new_system, nstate, boat_q, boat_u

  !> States of the boat; the full rigging's follow them (y(nstate+1:)).
  integer, parameter :: nstate = 12
  !> Index ranges of the boat's coordinates and speeds in y.
  integer, parameter :: boat_q(2) = [1, 6], boat_u(2) = [7, 12]
  integer, parameter :: nslings = 2
  !> Refresh interval of the surface watch [s]: long enough to cost nothing (one strip-load
  !> evaluation per interval), short enough for its bound to stay well below the height
  !> of a boat hanging 15 m up (rate bound ~30 m/s in a 1300-component Level 5 sea).
  real(wp), parameter :: surface_watch_interval = 0.05_wp

  type, extends(ode_problem) :: system_type
    type(rigid_body_type) :: boat
    !> Hook points in the boat frame, one column per sling.
    real(wp) :: hooks(3, nslings) = 0.0_wp
    type(elastic_sling_type) :: slings(nslings)
    logical :: slings_attached = .true.
    type(strip_model_type) :: water
    type(boat_wind_type) :: air
    type(wave_field_type) :: sea
    type(wind_type) :: wind
    !> Skips the strip loads while the hull is provably out of the water (exact).
    type(surface_watch_type) :: watch
    !> Slow clock of the water at the strips (`&simulation wave_update`, irregular seas).
    type(strip_wave_cache_type) :: waves
    !> Hull volume (dry fraction of the wind loads) [m^3].
    real(wp) :: hull_volume = 0.0_wp
    logical :: contact = .false.
    type(fender_set_type) :: fenders
    type(side_plane_type) :: side
    type(fender_state_type), allocatable :: fender_states(:)
    !> Time of the first fender contact [s]; negative while there has been none.
    real(wp) :: first_contact_time = -1.0_wp
    !> The full davit rigging ('lowering' and 'launch' scenes) in place of the foundation
    !> slings; total state length n.
    logical :: on_davit = .false.
    type(rigging_type) :: rig
    integer :: n = nstate
    !> The ship carrying the davit and the side plane: at rest in its deck pose, or
    !> ('launch') a 6-DOF ship in the sea and wind whose 12 states start at y(iship),
    !> one-way coupled as in the paper (the davit loads do not act on it).
    type(ship_pose_type) :: ship_rest
    logical :: with_ship = .false.
    type(ship_system_type) :: ship
    integer :: iship = 0
    !> Ship-frame y of the side plane [m].
    real(wp) :: side_y = 0.0_wp
    !> Events on the davit (review G24) [s], negative until they happen: waterborne (the
    !> buoyancy carries the weight, or the hooks carry < 1 % of it, for 1 s; the time the
    !> condition began) and hook release; after release the falls no longer act on the boat
    !> and their states are frozen.
    real(wp) :: waterborne_time = -1.0_wp, release_time = -1.0_wp, afloat_since = -1.0_wp
    logical :: release = .true.
    real(wp) :: release_delay = 0.0_wp
    !> Step while a fender is in contact or about to be (0: no limit) [s].
    real(wp) :: dt_contact = 0.0_wp
    !> Approach steps: graded by the predicted time to contact (else the two-step window).
    logical :: graded_approach = .false.
    !> Where the hooks were when they let go (inertial) [m].
    real(wp) :: released_hooks(3, nslings) = 0.0_wp
    type(ship_pose_type) :: released_pose
  contains
    procedure :: rhs => system_rhs
    procedure :: initial_state
    procedure :: energy
    procedure :: sling_tensions
    procedure :: observe
    procedure :: after_step => system_after_step
    procedure :: max_step => system_max_step
    procedure :: contact_state
    procedure :: hook_kinematics
    procedure :: rigging_state
  end type system_type

contains

  !> Build the system from a validated configuration.
  subroutine new_system(self, cfg, error)
    type(system_type), intent(out) :: self
    type(config_type), intent(in) :: cfg
    type(error_type), allocatable, intent(out), optional :: error
    type(error_type), allocatable :: rig_error
    real(wp) :: ea
    real(wp), allocatable :: y(:)
    self%boat%mass = cfg%boat%mass
    self%boat%inertia = cfg%boat%inertia
    self%hooks(:, 1) = cfg%slings%hook_fore
    self%hooks(:, 2) = cfg%slings%hook_aft
    ea = cfg%slings%youngs_modulus*acos(-1.0_wp)*cfg%slings%diameter**2/4.0_wp
    self%slings(1) = elastic_sling_type(cfg%slings%anchor_fore, cfg%slings%length, ea, &
                                        cfg%slings%damping)
    self%slings(2) = elastic_sling_type(cfg%slings%anchor_aft, cfg%slings%length, ea, &
                                        cfg%slings%damping)
    self%on_davit = cfg%simulation%scene == "lowering" .or. cfg%simulation%scene == "launch"
    self%slings_attached = cfg%slings%attached .and. .not. self%on_davit
    call new_boat_environment(self, cfg)
    call new_side_contact(self, cfg)
    if (self%on_davit) then
      call new_rigging(self%rig, cfg%rigging, rig_error)
      if (allocated(rig_error)) then
        if (present(error)) call move_alloc(rig_error, error)
        return
      end if
      self%n = nstate + self%rig%nstate
      self%release = cfg%rigging%release
      self%release_delay = cfg%rigging%release_delay
    end if
    if (cfg%simulation%scene == "launch") call new_moving_ship(self, cfg, rig_error)
    ! the rigging's initial equilibrium, checked once here for every caller of new_system
    if (self%on_davit .and. .not. allocated(rig_error)) y = self%initial_state(cfg, rig_error)
    if (allocated(rig_error) .and. present(error)) call move_alloc(rig_error, error)
  end subroutine new_system

  !> The 6-DOF ship of the 'ship' scene, in the same sea and wind as the boat.
  subroutine new_moving_ship(self, cfg, error)
    type(system_type), intent(inout) :: self
    type(config_type), intent(in) :: cfg
    type(error_type), allocatable, intent(out), optional :: error
    type(error_type), allocatable :: hull_error
    type(hull_type) :: hull
    call new_hull(hull, cfg%ship, hull_error)
    if (allocated(hull_error)) then
      if (present(error)) call move_alloc(hull_error, error)
      return
    end if
    call new_ship_system(self%ship, hull, self%sea, self%wind, cfg%ship%frozen, &
                         cfg%ship%position, cfg%ship%heading, &
                         cfg%ship%wave_phase == "initial", cfg%ship%headway)
    self%ship%wave_dt = cfg%simulation%wave_update
    self%with_ship = .true.
    self%iship = self%n + 1
    self%n = self%n + ship_nstate
  end subroutine new_moving_ship

  !> Strip hull, water and wind loads, and the sea and wind they act in.
  subroutine new_boat_environment(self, cfg)
    type(system_type), intent(inout) :: self
    type(config_type), intent(in) :: cfg
    associate (b => cfg%boat)
      self%water = new_strip_model(new_boat_hull(b%length, b%beam, b%height, b%keel, &
                                                 b%breadth_exponent, b%strips), &
                                   b%drag_coefficients, b%metacentric_height, b%zeta, &
                                   b%mass, b%inertia)
      self%hull_volume = sum(self%water%hull%breadth)*self%water%hull%thickness*b%height
      self%air = boat_wind_type(b%wind_areas, b%wind_drag_coefficient, b%lift_coefficient, &
                                b%lift_diameter, b%length, &
                                merge(lift_literal, lift_symmetric, b%lift_form == "literal"))
    end associate
    call build_wave_field(cfg%sea, cfg%simulation%seed, 0, self%sea)
    self%wind = build_wind(cfg%wind)
    self%watch = new_surface_watch(self%sea, self%water%hull%n, surface_watch_interval)
    self%waves = new_strip_wave_cache(self%sea, self%water%hull%n, cfg%simulation%wave_update)
  end subroutine new_boat_environment

  !> The ship's side plane at ship-frame y = side_y, normal +s2, for the ship at rest in its
  !> deck attitude (list, trim, heading) and position; the fenders and their contact law.
  subroutine new_side_contact(self, cfg)
    type(system_type), intent(inout) :: self
    type(config_type), intent(in) :: cfg
    real(wp) :: cs(3, 3)
    integer :: law
    self%contact = cfg%contact%enabled
    self%dt_contact = cfg%simulation%dt_contact
    self%graded_approach = cfg%simulation%contact_approach == "graded"
    cs = rotation_matrix([cfg%ship%list, cfg%ship%trim, cfg%ship%heading])
    self%ship_rest%r = cfg%ship%position
    self%ship_rest%c = cs
    self%ship_rest%v = matmul(cs, [cfg%ship%headway, 0.0_wp, 0.0_wp])
    self%side_y = cfg%contact%side_y
    associate (k => cfg%contact)
      law = merge(law_lankarani_nikravesh, law_hertz_elastoplastic, &
                  k%law == "lankarani_nikravesh")
      self%fenders = new_fender_set(k%fender_x, k%fender_y, k%fender_z, k%fender_points, &
                                    new_contact_law(law, k%youngs_boat, k%poisson_boat, &
                                                    k%youngs_ship, k%poisson_ship, &
                                                    k%radius_boat, k%radius_ship, &
                                                    k%restitution))
      allocate (self%fender_states(size(k%fender_x)))
    end associate
  end subroutine new_side_contact

  !> Initial y from inertial position/velocity and Euler angles / body rates; on the davit,
  !> the rigging starts in static equilibrium with W/2 on each hook (or unstretched, as
  !> &rigging initial says).
  function initial_state(self, cfg, error) result(y)
    class(system_type), intent(inout) :: self
    type(config_type), intent(in) :: cfg
    type(error_type), allocatable, intent(out), optional :: error
    type(error_type), allocatable :: rig_error
    real(wp), allocatable :: y(:)
    real(wp) :: c(3, 3), hook_pos(3, 2), hook_vel(3, 2), residual
    type(ship_pose_type) :: pose
    allocate (y(self%n))
    if (self%with_ship) y(self%iship:self%iship + ship_nstate - 1) = ship_initial_state(cfg)
    c = rotation_matrix(cfg%boat%euler)
    y(1:3) = cfg%boat%euler
    y(4:6) = matmul(transpose(c), cfg%boat%position)
    y(7:9) = cfg%boat%angular_velocity
    y(10:12) = matmul(transpose(c), cfg%boat%velocity)
    if (.not. self%on_davit) return
    call self%hook_kinematics(y, hook_pos, hook_vel)
    pose = ship_pose(self, y)
    call self%rig%initial_state(hook_pos, spread([0.0_wp, 0.0_wp, &
                                -0.5_wp*self%boat%mass*gravity], 2, 2), pose, &
                                y(nstate + 1:nstate + self%rig%nstate), residual, rig_error)
    if (allocated(rig_error) .and. present(error)) call move_alloc(rig_error, error)
  end function initial_state

  !> The ship's pose at state y.
  pure function ship_pose(self, y) result(pose)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    type(ship_pose_type) :: pose
    if (.not. self%with_ship) then
      pose = self%ship_rest
      return
    end if
    associate (ys => y(self%iship:self%iship + ship_nstate - 1))
      pose%c = rotation_matrix(ys(1:3))
      pose%r = ys(4:6)
      pose%v = matmul(pose%c, ys(10:12))
      pose%w = matmul(pose%c, ys(7:9))
    end associate
  end function ship_pose

  !> The ship's side plane (ship-frame y = side_y, normal +s2) carried by the ship.
  pure function side_plane(self, pose) result(plane)
    class(system_type), intent(in) :: self
    type(ship_pose_type), intent(in) :: pose
    type(side_plane_type) :: plane
    plane%origin = pose%r
    plane%point = pose%r + pose%c(:, 2)*self%side_y
    plane%normal = pose%c(:, 2)
    plane%velocity = pose%v
    plane%angular_velocity = pose%w
  end function side_plane

  !> Inertial positions and velocities of the two hooks at state y.
  pure subroutine hook_kinematics(self, y, hook_pos, hook_vel)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: hook_pos(3, 2), hook_vel(3, 2)
    real(wp) :: c(3, 3), r(3)
    integer :: i
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    do i = 1, nslings
      hook_pos(:, i) = r + matmul(c, self%hooks(:, i))
      hook_vel(:, i) = matmul(c, body_point_velocity(y(boat_u(1):boat_u(2)), self%hooks(:, i)))
    end do
  end subroutine hook_kinematics

  !> Kane's equations: y' = (q_dot, (F - W phi)/V).
  subroutine system_rhs(self, t, y, dydt)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: f(6), hook_pos(3, 2), hook_vel(3, 2), hook_force(3, 2), c(3, 3)
    type(ship_pose_type) :: pose
    integer :: i, j
    pose = ship_pose(self, y)
    if (self%with_ship) then
      j = self%iship
      call self%ship%rhs(t, y(j:j + ship_nstate - 1), dydt(j:j + ship_nstate - 1))
    end if
    associate (q => y(boat_q(1):boat_q(2)), u => y(boat_u(1):boat_u(2)))
      f = boat_forces(self, t, q, u, side_plane(self, pose))
      if (self%on_davit .and. self%release_time >= 0.0_wp) then
        dydt(nstate + 1:nstate + self%rig%nstate) = 0.0_wp
      else if (self%on_davit) then
        ! Eq. (26): the rigging's hook forces through the hooks' partial velocities.
        call self%hook_kinematics(y, hook_pos, hook_vel)
        j = nstate + self%rig%nstate
        call self%rig%rhs(t, y(nstate + 1:j), hook_pos, hook_vel, pose, dydt(nstate + 1:j), &
                          hook_force)
        c = rotation_matrix(q(1:3))
        do i = 1, nslings
          f = f + body_point_force(self%hooks(:, i), matmul(hook_force(:, i), c))
        end do
      end if
      dydt(boat_q(1):boat_q(2)) = body_qdot(q, u)
      dydt(boat_u(1):boat_u(2)) = (f - body_w_phi(self%boat, u))/body_mass_diagonal(self%boat)
    end associate
  end subroutine system_rhs

  !> Generalized active forces on the boat: gravity (eq. 13), slings (eq. 26), water
  !> (eqs. 18-25), wind (eqs. 14-17, at the CG) and fender contact (eq. 34).
  pure function boat_forces(self, t, q, u, side) result(f)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t, q(6), u(6)
    type(side_plane_type), intent(in) :: side
    real(wp) :: f(6), c(3, 3), r(3), fh(3), tension, fw(6), volume, force(self%fenders%nf)
    integer :: i
    c = rotation_matrix(q(1:3))
    r = matmul(c, q(4:6))
    f = body_gravity_force(self%boat, c)
    if (self%slings_attached) then
      do i = 1, nslings
        call sling_hook_force(self%slings(i), r + matmul(c, self%hooks(:, i)), &
                              matmul(c, body_point_velocity(u, self%hooks(:, i))), fh, tension)
        f = f + body_point_force(self%hooks(:, i), matmul(transpose(c), fh))
      end do
    end if
    call water_loads(self, t, c, r, u, fw, volume)
    f = f + fw
    f(4:6) = f(4:6) + boat_wind_force(self%air, u(4:6) - matmul(wind_velocity(self%wind), c), &
                                      max(0.0_wp, 1.0_wp - volume/self%hull_volume))
    if (self%contact) then
      call fender_loads(self%fenders, self%fender_states, side, c, r, u, fw, force)
      f = f + fw
    end if
  end function boat_forces

  !> Strip water loads (eqs. 18-25) and wet volume, exactly zero without forming them
  !> while the surface watch proves the hull dry; from the strips' slow clock where it
  !> covers t.
  pure subroutine water_loads(self, t, c, r, u, f, volume)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t, c(3, 3), r(3), u(6)
    real(wp), intent(out) :: f(6), volume
    if (surely_dry(self%watch, self%water, t, c, r)) then
      f = 0.0_wp
      volume = 0.0_wp
    else
      call strip_loads(self%water, self%sea, t, c, r, u, f, volume, self%waves)
    end if
  end subroutine water_loads

  !> Advance each fender's contact phase on the accepted state; note the first contact;
  !> on the davit, watch for waterborne and release the hooks.
  subroutine system_after_step(self, t, y)
    class(system_type), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp) :: c(3, 3), r(3), delta(self%fenders%nf), delta_dot(self%fenders%nf)
    integer :: deepest(self%fenders%nf), j
    logical :: due, maybe_wet(self%water%hull%n)
    if (self%with_ship) call self%ship%after_step(t, y(self%iship:self%iship + ship_nstate - 1))
    if (.not. self%watch%valid .or. t - self%watch%t >= self%watch%interval) then
      c = rotation_matrix(y(1:3))
      call watch_refresh(self%watch, self%water, self%sea, t, c, matmul(c, y(4:6)))
    end if
    ! Sample the water at the strips the hull may wet within the window (the watch's
    ! bound at its far end): otherwise the stages of a hull just above the crests would
    ! all take the exact sums.
    call strip_waves_due(self%waves, t, due)
    if (due) then
      c = rotation_matrix(y(1:3))
      r = matmul(c, y(4:6))
      do j = 1, self%water%hull%n
        maybe_wet(j) = .not. strip_surely_dry(self%watch, self%water, j, &
                                              t + self%waves%window, c, r)
      end do
      if (any(maybe_wet)) call strip_waves_refresh(self%waves, self%water%hull, self%sea, t, &
                                                   c, r, maybe_wet)
    end if
    if (self%on_davit .and. self%release_time < 0.0_wp) call watch_waterborne(self, t, y)
    if (.not. self%contact) return
    c = rotation_matrix(y(1:3))
    call fender_probe(self%fenders, side_plane(self, ship_pose(self, y)), c, &
                      matmul(c, y(4:6)), y(boat_u(1):boat_u(2)), deepest, delta, delta_dot)
    do j = 1, self%fenders%nf
      call fender_update(self%fenders%law, self%fender_states(j), delta(j), delta_dot(j))
      if (self%fender_states(j)%phase == phase_compression .and. &
          self%first_contact_time < 0.0_wp) self%first_contact_time = t
    end do
  end subroutine system_after_step

  !> The contact phases switch only between steps (after_step), and the Hertz force rises
  !> over milliseconds: while any fender is in contact, or its indentation extrapolated
  !> over the next two steps of size dt would be positive, steps are limited to dt_contact.
  !> This locates the contact onset to within dt_contact (an event location by step
  !> limiting that keeps the step sequence deterministic) and resolves the impact. With
  !> `contact_approach = 'graded'` the approach steps are instead half the predicted time
  !> to contact (at least dt_contact): the same onset resolution in ~log2(dt/dt_contact)
  !> steps rather than 2 dt/dt_contact, which matters at large dt (quasi-static blocks).
  pure real(wp) function system_max_step(self, t, y, dt) result(h)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:), dt
    real(wp) :: c(3, 3), delta(self%fenders%nf), delta_dot(self%fenders%nf)
    integer :: deepest(self%fenders%nf), j
    h = dt
    if (.not. self%contact .or. self%dt_contact <= 0.0_wp .or. self%dt_contact >= dt) return
    if (any(self%fender_states%phase /= phase_free)) then
      h = self%dt_contact
      return
    end if
    c = rotation_matrix(y(1:3))
    call fender_probe(self%fenders, side_plane(self, ship_pose(self, y)), c, &
                      matmul(c, y(4:6)), y(boat_u(1):boat_u(2)), deepest, delta, delta_dot)
    if (self%graded_approach) then
      ! half the predicted time to contact -delta/delta_dot of each approaching fender:
      ! the gap is halved each step, down to dt_contact
      do j = 1, self%fenders%nf
        if (delta_dot(j) > 0.0_wp .and. delta(j) + 2.0_wp*dt*delta_dot(j) > 0.0_wp) &
          h = min(h, max(self%dt_contact, -0.5_wp*delta(j)/delta_dot(j)))
      end do
    else if (any(delta + 2.0_wp*dt*max(delta_dot, 0.0_wp) > 0.0_wp)) then
      h = self%dt_contact
    end if
  end function system_max_step

  !> Waterborne when rho g V >= W or the hooks carry < 1 % of W, held for 1 s; the hooks
  !> open release_delay later. Checked only when the keel can reach the water (CG less
  !> than 10 m above the still water), so the hanging phase costs nothing.
  subroutine watch_waterborne(self, t, y)
    type(system_type), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), parameter :: hold = 1.0_wp, hook_fraction = 0.01_wp
    real(wp) :: c(3, 3), r(3), fw(6), volume, weight
    real(wp) :: seg(self%rig%nseg), sling(self%rig%nlump + 1, 2), paid
    real(wp) :: lumps(3, self%rig%nlump, 2), hook_vel(3, nslings)
    logical :: afloat
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    if (r(3) < -10.0_wp) return
    if (self%waterborne_time < 0.0_wp) then
      weight = self%boat%mass*gravity
      call water_loads(self, t, c, r, y(boat_u(1):boat_u(2)), fw, volume)
      afloat = rho_water*gravity*volume >= weight
      if (.not. afloat) then
        call self%rigging_state(t, y, seg, sling, paid, lumps)
        afloat = sum(sling(1, :)) < hook_fraction*weight
      end if
      if (.not. afloat) then
        self%afloat_since = -1.0_wp
      else if (self%afloat_since < 0.0_wp) then
        self%afloat_since = t
      else if (t - self%afloat_since >= hold) then
        self%waterborne_time = self%afloat_since
      end if
    end if
    if (self%release .and. self%waterborne_time >= 0.0_wp .and. &
        t >= self%waterborne_time + hold + self%release_delay) then
      self%release_time = t
      call self%hook_kinematics(y, self%released_hooks, hook_vel)
      self%released_pose = ship_pose(self, y)
    end if
  end subroutine watch_waterborne

  !> Smallest fender-to-side distance [m] (negative = penetration) and each fender's
  !> normal force [N] at state y.
  subroutine contact_state(self, y, clearance, force)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: clearance, force(:)
    real(wp) :: c(3, 3), r(3), delta(self%fenders%nf), delta_dot(self%fenders%nf), f(6)
    integer :: deepest(self%fenders%nf)
    type(side_plane_type) :: plane
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    plane = side_plane(self, ship_pose(self, y))
    call fender_probe(self%fenders, plane, c, r, y(boat_u(1):boat_u(2)), deepest, delta, &
                      delta_dot)
    clearance = -maxval(delta)
    force = 0.0_wp
    if (self%contact) call fender_loads(self%fenders, self%fender_states, plane, c, r, &
                                        y(boat_u(1):boat_u(2)), f, force)
  end subroutine contact_state

  !> Mechanical energy of the conservative part in air: kinetic + gravity (N3 down, so
  !> -m g z) + elastic slings [J].
  pure function energy(self, y) result(e)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: e, c(3, 3), r(3)
    type(ship_pose_type) :: pose
    integer :: i
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    e = body_kinetic_energy(self%boat, y(boat_u(1):boat_u(2))) - self%boat%mass*gravity*r(3)
    if (self%on_davit) then
      pose = ship_pose(self, y)
      e = e + self%rig%energy(y(nstate + 1:nstate + self%rig%nstate), spread(r, 2, 2) + &
                              matmul(c, self%hooks), pose)
    end if
    if (.not. self%slings_attached) return
    do i = 1, nslings
      e = e + sling_energy(self%slings(i), r + matmul(c, self%hooks(:, i)))
    end do
  end function energy

  !> Rigging observables at state y: cable segment tensions [N], sling segment tensions
  !> (row 1 at the hook; zero once the hooks are released) [N], paid-out length [m] and lump
  !> positions (inertial) [m].
  pure subroutine rigging_state(self, t, y, seg, sling, paid, lumps)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: seg(:), sling(:, :), paid, lumps(:, :, :)
    real(wp) :: hook_pos(3, 2), hook_vel(3, 2), tr
    type(ship_pose_type) :: pose
    call self%hook_kinematics(y, hook_pos, hook_vel)
    pose = ship_pose(self, y)
    tr = t
    if (self%release_time >= 0.0_wp) then
      ! The falls are not simulated after release (their states are frozen): report them
      ! as they were when the hooks let go, not stretched by the boat and ship moving on.
      hook_pos = self%released_hooks
      hook_vel = 0.0_wp
      pose = self%released_pose
      tr = self%release_time
    end if
    associate (yr => y(nstate + 1:nstate + self%rig%nstate))
      call self%rig%observe(tr, yr, hook_pos, hook_vel, pose, seg, sling)
      ! Released hooks carry nothing: the frozen slings would otherwise report the stretch
      ! to wherever the boat has moved on the waves (MN on a 4 m sea, III.A decks).
      if (self%release_time >= 0.0_wp) sling = 0.0_wp
      paid = self%rig%paid_out(yr)
      if (self%rig%nlump > 0) lumps = self%rig%lump_positions(yr)
    end associate

  end subroutine rigging_state

  !> Tensions [N] of the foundation slings at state y (zero when detached or on the davit,
  !> where rigging_state gives the sling tensions).
  pure function sling_tensions(self, y) result(tension)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp) :: tension(nslings), c(3, 3), r(3), fh(3)
    integer :: i
    tension = 0.0_wp
    if (.not. self%slings_attached) return
    c = rotation_matrix(y(1:3))
    r = matmul(c, y(4:6))
    do i = 1, nslings
      call sling_hook_force(self%slings(i), r + matmul(c, self%hooks(:, i)), &
                            matmul(c, body_point_velocity(y(boat_u(1):boat_u(2)), &
                                                          self%hooks(:, i))), fh, tension(i))
    end do
  end function sling_tensions

  !> Inertial-frame observables of the boat: position, velocity and acceleration of the CG
  !> (a = C (u_dot + omega x v), eq. 8), Euler angles and body angular velocity.
  subroutine observe(self, t, y, position, euler, velocity, angular_velocity, acceleration)
    class(system_type), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: position(3), euler(3), velocity(3), angular_velocity(3)
    real(wp), intent(out) :: acceleration(3)
    real(wp) :: c(3, 3), dydt(self%n)
    associate (u => y(boat_u(1):boat_u(2)))
      call self%rhs(t, y, dydt)
      c = rotation_matrix(y(1:3))
      position = body_inertial_position(y(boat_q(1):boat_q(2)))
      euler = y(1:3)
      velocity = matmul(c, u(4:6))
      angular_velocity = u(1:3)
      acceleration = matmul(c, dydt(boat_u(1) + 3:boat_u(2)) + cross(u(1:3), u(4:6)))
    end associate
  end subroutine observe

end module davit_system_model
