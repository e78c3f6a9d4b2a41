!> Build a launch system from a validated configuration: parameters and layout, history,
!> contact step policy and (where the scene moves the ship: 'launch') the 6-DOF ship; and its
!> initial state.
module davit_system_build
  use davit_kinds, only: wp, gravity, rho_water
  use davit_error, only: error_type, fatal_error
  use davit_core_rotation, only: rotation_matrix
  use davit_core_pose, only: pose_type, pose_point, pose_point_velocity
  use davit_io_config, only: config_type
  use davit_io_search_path, only: find_file, folder_of
  use davit_rigging_elastic_sling, only: elastic_sling_type
  use davit_system_sea_builder, only: build_wave_field, build_wind
  use davit_boat_hull, only: new_boat_hull
  use davit_boat_strip_loads, only: strip_model_type, new_strip_model
  use davit_boat_strip_level, only: strip_level_type
  use davit_boat_bem_water, only: boat_bem_type, new_boat_bem
  use davit_boat_water_terms, only: strips_alone_type, bem_terms_type
  use davit_system_boat_loads, only: water_loads
  use davit_core_body, only: body_mass_diagonal
  use davit_boat_contact_law, only: contact_law_type, fender_state_type
  use davit_boat_wind_loads, only: boat_wind_type
  use davit_io_ship_keys, only: ship_config
  use davit_system_contact_policy, only: contact_policy_type
  use davit_system_law_factory, only: new_contact_law, new_boat_wind, new_strip_level, &
                                      new_wave_drift
  use davit_boat_fenders, only: fender_set_type, new_fender_set
  use davit_boat_strip_waves, only: strip_wave_cache_type, new_strip_wave_cache
  use davit_boat_surface_watch, only: surface_watch_type, new_surface_watch
  use davit_core_slow_clock, only: slow_clock_type, new_slow_clock, clock_grid, clock_reach
  use davit_rigging_rigging, only: rigging_type, new_rigging
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_ship_hull, only: hull_type, new_hull
  use davit_ship_mmg, only: mmg_type
  use davit_ship_rudder, only: rudder_type, notch_period
  use davit_ship_ship_model, only: ship_system_type, new_ship_system, ship_state
  use davit_ship_ship_hydro, only: bem_hydro_type, box_hydro_type
  use davit_ship_bem_database, only: bem_database_type, read_bem_database
  use davit_ship_bem_loads, only: bem_ship_type, new_bem_ship
  use davit_ship_wave_drift, only: wave_drift_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_sea_wave_grid, only: wave_grid_type, new_wave_grid, grid_error_bounds
  use davit_sea_wind, only: wind_type
  use davit_system_parameters, only: system_params_type, ship_pose, hook_kinematics, nslings
  use davit_system_model, only: system_type
  implicit none
  private
  public :: new_system, initial_state, ship_initial_state, new_ship

  !> Refresh interval of the surface watch [s]: long enough to cost nothing (one strip-load
  !> evaluation per interval), short enough for its bound to stay well below the height
  !> of a boat hanging 15 m up (rate bound ~30 m/s in a 1300-component Level 5 sea). A
  !> longer window of the strips' slow clock sets it instead: each window refreshes the
  !> watch from its own samples, and a watch refreshed in between would sum the sea again.
  real(wp), parameter :: surface_watch_interval = 0.05_wp

contains

  !> Build the system from a validated configuration, for the scene that asks
  !> (davit_run_scene: where the boat hangs, whether the ship moves).
  subroutine new_system(self, cfg, on_davit, with_ship, error)
    !> The system built: parameters, history, layout and integrator choices.
    type(system_type), intent(out) :: self
    !> The deck's configuration, validated.
    type(config_type), intent(in) :: cfg
    !> The boat hangs on the davit's full rigging (else on the foundation slings).
    logical, intent(in) :: on_davit
    !> The 6-DOF ship moves in the sea with the boat (else it stays in its &ship pose).
    logical, intent(in) :: with_ship
    !> Allocated when a part cannot be built (e.g. a database that cannot be read).
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: ea
    associate (par => self%par, s => cfg%slings)
      par%boat%mass = cfg%boat%mass
      par%boat%inertia = cfg%boat%inertia
      call par%layout%add("boat", 6, 6, par%boat_part)
      par%hooks(:, 1) = s%hook_fore
      par%hooks(:, 2) = s%hook_aft
      ea = s%youngs_modulus*acos(-1.0_wp)*s%diameter**2/4.0_wp
      par%slings(1) = elastic_sling_type(s%anchor_fore, s%length, ea, s%damping)
      par%slings(2) = elastic_sling_type(s%anchor_aft, s%length, ea, s%damping)
      par%on_davit = on_davit
      par%slings_attached = s%attached .and. .not. par%on_davit
    end associate
    associate (par => self%par, hist => self%hist)
      call new_boat_environment(cfg, par%water, par%hull_volume, par%air, par%sea, par%wind, &
                                error)
      if (allocated(error)) return
      call new_water_caches(cfg, par%sea, par%water%hull%n, hist%watch, hist%waves, &
                            hist%surface_grid, hist%volume_grid)
      if (cfg%boat%water_model == "bem") then
        call new_boat_water(par, cfg, error)
        if (allocated(error)) return
      else
        allocate (par%water_terms, source=strips_alone_type())
      end if
      ! the ship's side at rest, the fenders and the contact step policy
      par%contact = cfg%contact%enabled
      self%policy = contact_policy_type(cfg%simulation%dt_contact, &
                                        cfg%simulation%contact_approach == "graded", &
                                        cfg%simulation%contact_approach == "event")
      par%ship_rest = rest_pose(cfg%ship)
      par%side_y = cfg%contact%side_y
      call new_fenders(cfg, par%fenders, hist%fender_states, error)
      if (allocated(error)) return
      if (par%on_davit) then
        call new_davit(par%rig, par%layout, par%rig_slice, cfg, error)
        if (allocated(error)) return
        par%release = cfg%rigging%release
        par%release_delay = cfg%rigging%release_delay
      end if
      if (.not. with_ship) return
      call new_moving_ship(cfg, par%sea, par%wind, self%ship, par%layout, par%ship_part, &
                           par%ship_slice, error)
      if (.not. allocated(error)) par%with_ship = .true.
    end associate
  end subroutine new_system

  !> The boat's BEM water model (&boat water_model = 'bem'): its database, its states
  !> (immersion, radiation memory) as part "boat_radiation" after the boat's, and the
  !> boat's speeds registered as a modal coupled block (M + s A(inf)). The roll damping's
  !> stiffness is the strips' metacentric one, m g h_m.
  subroutine new_boat_water(par, cfg, error)
    type(system_params_type), intent(inout) :: par
    type(config_type), intent(in) :: cfg
    type(error_type), allocatable, intent(out) :: error
    type(bem_database_type) :: db
    type(boat_bem_type) :: bem
    associate (b => cfg%boat)
      call read_bem_database(beside(cfg%filename, b%database), db, error)
      if (.not. allocated(error)) then
        call new_boat_bem(db, par%sea, body_mass_diagonal(par%boat), b%roll_damping, &
                          b%mass*gravity*par%water%metacentric_height, b%full_immersion, &
                          b%mass/rho_water, bem, error)
      end if
      if (allocated(error)) then
        error%message = cfg%filename//": &boat: database = '"//b%database//"': "// &
                        error%message
        return
      end if
    end associate
    allocate (par%water_terms, source=bem_terms_type(bem=bem))
    call par%water_terms%add_states(par%layout, par%boat_part, par%radiation_part)
  end subroutine new_boat_water

  !> The davit rigging in place of the foundation slings, its parts after the boat's.
  subroutine new_davit(rig, layout, rig_slice, cfg, error)
    !> The davit rigging, built.
    type(rigging_type), intent(inout) :: rig
    !> The system's state layout, the rigging's parts appended.
    type(state_layout_type), intent(inout) :: layout
    !> First and last state index of the rigging.
    integer, intent(out) :: rig_slice(2)
    type(config_type), intent(in) :: cfg
    type(error_type), allocatable, intent(out) :: error
    integer :: offset
    call new_rigging(rig, cfg%rigging, error)
    if (allocated(error)) return
    call layout%append(rig%layout, offset)
    rig_slice = [offset + 1, offset + rig%nstate]
  end subroutine new_davit

  !> The 6-DOF ship of the 'launch' scene, in the same sea and wind as the boat, keeping
  !> its heading (and station) as the deck says; its state appended to the layout.
  subroutine new_moving_ship(cfg, sea, wind, ship, layout, ship_part, ship_slice, error)
    type(config_type), intent(in) :: cfg
    !> The sea and wind the boat is in.
    type(wave_field_type), intent(in) :: sea
    type(wind_type), intent(in) :: wind
    !> The ship, built.
    type(ship_system_type), intent(inout) :: ship
    !> The system's state layout, the ship's parts appended.
    type(state_layout_type), intent(inout) :: layout
    !> The ship's rigid-body part of the state, and its first and last state index.
    type(state_part_type), intent(out) :: ship_part
    integer, intent(out) :: ship_slice(2)
    type(error_type), allocatable, intent(out) :: error
    integer :: offset
    call new_ship(ship, cfg, sea, wind, error)
    if (allocated(error)) return
    associate (s => cfg%ship)
      call ship%set_mooring([s%station_period, s%station_period, s%heading_period], &
                            s%heading_damping, ship_initial_state(ship, cfg), integral=.true.)
    end associate
    call layout%append(ship%par%layout, offset)
    ship_part = layout%part("ship")
    ship_slice = [offset + 1, offset + ship%par%layout%n]
  end subroutine new_moving_ship

  !> The ship of the deck in the sea and wind given: the paper's box or (&ship model =
  !> 'bem') the BEM ship of its database.
  subroutine new_ship(ship, cfg, sea, wind, error)
    !> The ship built.
    type(ship_system_type), intent(out) :: ship
    !> The deck's configuration (&ship, &simulation).
    type(config_type), intent(in) :: cfg
    !> The sea the ship floats in.
    type(wave_field_type), intent(in) :: sea
    !> The wind on it.
    type(wind_type), intent(in) :: wind
    !> Allocated when its BEM database cannot be read or does not fit the deck.
    type(error_type), allocatable, intent(out) :: error
    type(hull_type) :: hull
    type(bem_database_type) :: db
    type(bem_ship_type) :: bem
    type(slow_clock_type) :: clock
    class(wave_drift_type), allocatable :: drift
    call new_hull(hull, cfg%ship, error)
    if (allocated(error)) return
    clock = new_slow_clock(cfg%simulation%wave_update, clock_grid)
    associate (s => cfg%ship)
      if (s%model == "bem") then
        call read_bem_database(beside(cfg%filename, s%database), db, error)
        if (s%roll_gyradius > 0.0_wp) db%mass(4, 4) = db%mass(1, 1)*s%roll_gyradius**2
        if (.not. allocated(error)) call new_bem_ship(db, s%zeta_roll, bem, error)
        if (allocated(error)) then
          error%message = cfg%filename//": &ship: database = '"//s%database//"': "// &
                          error%message
          return
        end if
        call new_ship_system(ship, hull, sea, wind, s%frozen, s%position, s%heading, &
                             s%wave_phase == "initial", s%headway, clock, &
                             bem_hydro_type(bem=bem))
        if (s%drift /= "none" .and. .not. db%has_drift) then
          call fatal_error(error, cfg%filename//": &ship: drift = '"//s%drift//"' needs "// &
                           "the mean drift coefficients (davit_drift), which database '"// &
                           s%database//"' lacks: rebuild it with davit-post bem build, "// &
                           "or set drift = 'none'")
          return
        end if
        call new_wave_drift(s%drift, drift, error)
        if (allocated(error)) then
          error%message = cfg%filename//": "//error%message
          return
        end if
        if (allocated(drift)) call ship%set_drift(drift)
      else if (s%drift /= "none") then
        call fatal_error(error, cfg%filename//": &ship: drift = '"//s%drift//"' needs "// &
                         "model = 'bem' (allowed with model = '"//s%model//"': 'none'): "// &
                         "the drift coefficients come from its BEM database")
        return
      else
        call new_ship_system(ship, hull, sea, wind, s%frozen, s%position, s%heading, &
                             s%wave_phase == "initial", s%headway, clock, &
                             box_hydro_type())
      end if
      if (s%manoeuvring == "mmg") call new_mmg(ship, cfg)
    end associate
  end subroutine new_ship

  !> The MMG manoeuvring model of group &mmg on the box or BEM ship, with its dimensions.
  subroutine new_mmg(ship, cfg)
    type(ship_system_type), intent(inout) :: ship
    type(config_type), intent(in) :: cfg
    type(mmg_type) :: p
    type(rudder_type) :: steer
    associate (s => cfg%ship)
      p = s%mmg
      p%lpp = s%lpp
      p%draught = s%draught
      steer = s%rudder
      ! the autopilot's notch at the waves' encounter period (the frame moves at the headway)
      if (steer%notch_encounter .and. ship%par%sea%n > 0) then
        steer%notch = notch_period(ship%par%sea%omega, ship%par%sea%kx, ship%par%sea%ky, &
                                   ship%par%sea%amplitude, ship%par%frame_velocity)
      end if
      call ship%set_mmg(p, steer, s%rps, s%headway)
    end associate
  end subroutine new_mmg

  !> A data file named in deck `deck`: `path` as given if absolute; else the first that
  !> exists of the deck's folder and each folder of DAVIT_PATH (davit_io_search_path);
  !> else the deck's folder (whose open then fails naming it).
  function beside(deck, path) result(full)
    character(len=*), intent(in) :: deck, path
    character(len=:), allocatable :: full
    logical :: found
    call find_file(folder_of(deck), path, full, found)
  end function beside

  !> Strip hull, water and wind loads, and the sea and wind they act in.
  subroutine new_boat_environment(cfg, water, hull_volume, air, sea, wind, error)
    type(config_type), intent(in) :: cfg
    !> The boat's strip model in the water, and its hull volume [m^3].
    type(strip_model_type), intent(out) :: water
    real(wp), intent(out) :: hull_volume
    !> Wind drag and lift on the boat.
    class(boat_wind_type), allocatable, intent(out) :: air
    !> The sea and the mean wind.
    type(wave_field_type), intent(out) :: sea
    type(wind_type), intent(out) :: wind
    type(error_type), allocatable, intent(out) :: error
    class(strip_level_type), allocatable :: level
    associate (b => cfg%boat)
      call new_strip_level(b, level)
      water = new_strip_model(new_boat_hull(b%length, b%beam, b%height, b%keel, &
                                            b%breadth_exponent, b%strips), &
                              b%drag_coefficients, b%metacentric_height, b%zeta, &
                              b%mass, b%inertia, level, b%roll_restoring == "paper")
      hull_volume = sum(water%hull%breadth)*water%hull%thickness*b%height
      call new_boat_wind(b, air, error)
      if (allocated(error)) then
        error%message = cfg%filename//": "//error%message
        return
      end if
      call build_wave_field(cfg%sea, cfg%simulation%seed, 0, sea)
      wind = build_wind(cfg%wind)
    end associate
  end subroutine new_boat_environment

  !> The water's slow caches at the boat (the history's): the surface watch, the strips'
  !> slow clock and, with &sea kinematics = 'grid', the surface and volume grids.
  subroutine new_water_caches(cfg, sea, n, watch, waves, surface_grid, volume_grid)
    type(config_type), intent(in) :: cfg
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> Number of strips of the boat's hull.
    integer, intent(in) :: n
    !> The surface watch and the strips' slow clock, built.
    type(surface_watch_type), intent(out) :: watch
    type(strip_wave_cache_type), intent(out) :: waves
    !> The grids of the sea around the boat, built when kinematics = 'grid'.
    type(wave_grid_type), intent(inout) :: surface_grid, volume_grid
    watch = new_surface_watch(sea, n, max(surface_watch_interval, &
                                          cfg%simulation%wave_update))
    waves = new_strip_wave_cache(sea, n, new_slow_clock(cfg%simulation%wave_update, clock_reach))
    if (cfg%sea%grid%kinematics /= "grid") return
    associate (g => cfg%sea%grid)
      surface_grid = new_wave_grid(sea, g%spacing, g%time_step, g%margin, g%depth, .false.)
      volume_grid = new_wave_grid(sea, g%spacing, g%time_step, g%margin, g%depth, .true.)
    end associate
    watch%grid_error = grid_error_bounds(surface_grid, sea)
  end subroutine new_water_caches

  !> The ship at rest in its deck attitude (list, trim, heading) and position, moving at
  !> its headway.
  pure function rest_pose(ship) result(pose)
    !> The deck's &ship values.
    type(ship_config), intent(in) :: ship
    type(pose_type) :: pose
    real(wp) :: cs(3, 3)
    cs = rotation_matrix([ship%list, ship%trim, ship%heading])
    pose = pose_type(ship%position, cs, matmul(cs, [ship%headway, 0.0_wp, 0.0_wp]), 0.0_wp)
  end function rest_pose

  !> The boat's fenders and their contact law (&contact), each fender's contact phase.
  subroutine new_fenders(cfg, fenders, states, error)
    type(config_type), intent(in) :: cfg
    !> The fenders, built.
    type(fender_set_type), intent(out) :: fenders
    !> Each fender's contact phase, one per fender.
    type(fender_state_type), allocatable, intent(out) :: states(:)
    type(error_type), allocatable, intent(out) :: error
    class(contact_law_type), allocatable :: law
    call new_contact_law(cfg%contact, law, error)
    if (allocated(error)) then
      error%message = cfg%filename//": "//error%message
      return
    end if
    associate (k => cfg%contact)
      fenders = new_fender_set(k%fender_x, k%fender_y, k%fender_z, k%fender_points, law)
      allocate (states(size(k%fender_x)))
    end associate
  end subroutine new_fenders

  !> Initial y from inertial position/velocity and Euler angles / body rates; on the davit,
  !> the rigging starts in static equilibrium with W/2 on each hook (or unstretched, as
  !> &rigging initial says; the quasi-static sheaves' unstretched lengths are set here).
  subroutine initial_state(self, cfg, y, error)
    !> The system (the rigging's unstretched lengths set here).
    type(system_type), intent(inout) :: self
    !> The deck's configuration (initial pose, rigging start).
    type(config_type), intent(in) :: cfg
    !> The initial state vector.
    real(wp), allocatable, intent(out) :: y(:)
    !> Allocated when the rigging's start cannot be balanced.
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: c(3, 3), hook_pos(3, nslings), hook_vel(3, nslings), residual
    real(wp) :: heads(3, nslings), head_vel(3, nslings)
    type(pose_type) :: pose
    allocate (y(self%par%layout%n))
    associate (par => self%par, b => self%par%boat_part, s => self%par%ship_part)
      if (par%with_ship) y(par%ship_slice(1):par%ship_slice(2)) = &
        ship_initial_state(self%ship, cfg)
      c = rotation_matrix(cfg%boat%euler)
      y(b%q(1):b%q(2)) = [cfg%boat%euler, matmul(transpose(c), cfg%boat%position)]
      y(b%u(1):b%u(2)) = [cfg%boat%angular_velocity, matmul(transpose(c), cfg%boat%velocity)]
      ! the wet volume (a water-load evaluation) only where the terms have states to start
      associate (x => par%radiation_part%q)
        if (x(2) >= x(1)) call par%water_terms%start_states(initial_wet_volume(par%water, &
                                                           par%sea, self%hist%watch, &
                                                           self%hist%waves, b, y), y(x(1):x(2)))
      end associate
      if (.not. par%on_davit) return
      call hook_kinematics(b, par%hooks, y, hook_pos, hook_vel)
      pose = ship_pose(par%with_ship, s, par%ship_rest, y)
      heads(:, 1) = pose_point(pose, cfg%rigging%head_fore)
      heads(:, 2) = pose_point(pose, cfg%rigging%head_aft)
      head_vel(:, 1) = pose_point_velocity(pose, cfg%rigging%head_fore)
      head_vel(:, 2) = pose_point_velocity(pose, cfg%rigging%head_aft)
      call par%rig%initial_state(hook_pos, hook_loads(heads, hook_pos, par%boat%mass), &
                                 pose, y(par%rig_slice(1):par%rig_slice(2)), &
                                 residual, error, hook_vel=hook_vel, heads=heads, &
                                 head_vel=head_vel)
    end associate
  end subroutine initial_state

  !> Each hook's load at the start: W/2 upwards, along the line from the hook to its davit
  !> head (head_fore for the fore hook), so that slings and falls start in line. A boat
  !> hanging plumb gets W/2 straight up; one held off the plumb line (against the side of a
  !> ship listed away from it) starts with its falls leaning, the lean's horizontal pull
  !> taken by the ship's side once the fenders touch.
  pure function hook_loads(heads, hook_pos, mass) result(f)
    real(wp), intent(in) :: heads(3, nslings), hook_pos(3, nslings), mass
    real(wp) :: f(3, nslings), up(3)
    integer :: a
    do a = 1, nslings
      up = heads(:, a) - hook_pos(:, a)
      f(:, a) = [0.0_wp, 0.0_wp, -0.5_wp*mass*gravity]
      ! only a head above its hook gives a lean (else the plain weight, the error path)
      if (up(3) < 0.0_wp) f(:, a) = (0.5_wp*mass*gravity/(-up(3)))*up
    end do
  end function hook_loads

  !> The hull's wet volume [m^3] in its initial pose (the water terms' initial states
  !> take it).
  pure real(wp) function initial_wet_volume(water, sea, watch, waves, boat_part, y) &
    result(volume)
    !> The strip model of the boat in the water, the sea, the surface watch and the strips'
    !> slow clock (the water_loads' parts).
    type(strip_model_type), intent(in) :: water
    type(wave_field_type), intent(in) :: sea
    type(surface_watch_type), intent(in) :: watch
    type(strip_wave_cache_type), intent(in) :: waves
    !> The boat's rigid-body part of the state.
    type(state_part_type), intent(in) :: boat_part
    !> The initial state (the boat's part set).
    real(wp), intent(in) :: y(:)
    real(wp) :: c(3, 3), f(6)
    associate (q => y(boat_part%q(1):boat_part%q(2)), &
               u => y(boat_part%u(1):boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      call water_loads(water, sea, watch, waves, 0.0_wp, c, matmul(c, q(4:6)), u, f, volume)
    end associate
  end function initial_wet_volume

  !> The ship at rest in its equilibrium attitude: list, trim, heading; CG at the deck's
  !> position; making its headway; no radiation memory yet.
  pure function ship_initial_state(ship, cfg) result(y)
    !> The ship (its state layout).
    type(ship_system_type), intent(in) :: ship
    !> The deck's configuration (&ship pose and headway).
    type(config_type), intent(in) :: cfg
    real(wp) :: y(ship%par%layout%n)
    y = ship_state(ship, [cfg%ship%list, cfg%ship%trim, cfg%ship%heading], &
                   cfg%ship%position, [0.0_wp, 0.0_wp, 0.0_wp], &
                   [cfg%ship%headway, 0.0_wp, 0.0_wp])
  end function ship_initial_state

end module davit_system_build
