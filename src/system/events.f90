!> The after-step hook of the launch: the only writer of the history. On each accepted
!> state it refreshes the surface watch and the strips' slow clock of the water, watches
!> for the boat becoming waterborne and releases the hooks (review G24), and advances each
!> fender's contact phase (eqs. 27-34), noting the first contact.
module davit_system_events
  use davit_kinds, only: wp, gravity, rho_water
  use davit_core_rotation, only: rotation_matrix
  use davit_boat_contact_law, only: phase_compression, fender_state_type
  use davit_boat_fenders, only: fender_set_type
  use davit_boat_strip_waves, only: strip_wave_cache_type, strip_waves_due, &
                                    strip_waves_open, strip_waves_sample, strip_waves_surface, &
                                    strip_waves_renew_loads, strip_waves_bounds
  use davit_boat_surface_watch, only: surface_watch_type, watch_refresh, watch_set, watch_due, &
                                      strip_surely_dry, watch_set_window, hull_surely_dry
  use davit_system_parameters, only: system_params_type, nslings, ship_pose, side_plane, &
                                     hook_kinematics, fender_gaps, falls_ends_at
  use davit_system_history, only: system_history_type
  use davit_system_boat_loads, only: water_loads
  use davit_system_observables, only: rigging_state
  use davit_sea_wave_grid, only: wave_grid_type, grid_prepare
  use davit_sea_wave_field, only: wave_field_type
  use davit_boat_hull, only: boat_hull_type
  use davit_boat_strip_loads, only: strip_model_type
  use davit_core_layout, only: state_part_type
  implicit none
  private
  public :: advance_history, release_hooks

contains

  !> Advance the history on the accepted state (t, y).
  subroutine advance_history(par, hist, t, y)
    !> The system's parameters.
    type(system_params_type), intent(in) :: par
    !> The history (surface watch, strips' water samples, events, fender phases written).
    type(system_history_type), intent(inout) :: hist
    !> Time [s] and state of the accepted step's end.
    real(wp), intent(in) :: t, y(:)
    real(wp) :: c(3, 3), r(3)
    logical :: due
    associate (q => y(par%boat_part%q(1):par%boat_part%q(2)))
      ! the boat's pose, once for the watch and the strips' window
      c = rotation_matrix(q(1:3))
      r = matmul(c, q(4:6))
      ! with the strips' slow clock summing exactly, each window sets the watch (below)
      due = .false.
      if (.not. hist%waves%enabled .or. hist%surface_grid%enabled) then
        call watch_due(hist%watch, par%water, t, c, r, due)
      end if
      if (due) then
        if (hist%surface_grid%enabled) then
          call prepare_grid(par%water%hull, par%sea, hist%surface_grid, t, &
                            hist%watch%interval, c, r)
          call watch_refresh(hist%watch, par%water, par%sea, t, c, r, hist%surface_grid)
        else
          call watch_refresh(hist%watch, par%water, par%sea, t, c, r)
        end if
      end if
      ! the BEM water's lagged immersion s (0 for the strips alone)
      call refresh_strip_waves(par, hist, t, c, r, q(3), &
                               y(par%boat_part%u(1):par%boat_part%u(2)), &
                               par%water_terms%immersion(y(par%radiation_part%q(1): &
                                                           par%radiation_part%q(2))))
    end associate
    if (par%on_davit .and. hist%release_time < 0.0_wp) call watch_waterborne(par, hist, t, y)
    if (par%contact) then
      block
        real(wp) :: delta(par%fenders%nf), delta_dot(par%fenders%nf)
        call fender_gaps(par%fenders, side_plane(par%side_y, ship_pose(par%with_ship, &
                         par%ship_part, par%ship_rest, y)), par%boat_part, y, delta, delta_dot)
        call advance_contact(par%fenders, t, delta, delta_dot, hist%fender_states, &
                             hist%first_contact_time)
      end block
    end if
  end subroutine advance_history

  !> Open the strips' window when due and sample the water at the strips the hull may wet
  !> within it: otherwise the stages of a hull just above the crests would all take the
  !> exact sums. Summed exactly, the window's samples at the strip centres bound the
  !> surface over it (the watch's window) and decide which strips may wet, the boat
  !> lowered by how far it can move in the window; with the grids, the watch's Lipschitz
  !> bound at the window's end.
  subroutine refresh_strip_waves(par, hist, t, c, r, yaw, u, immersion)
    type(system_params_type), intent(in) :: par
    type(system_history_type), intent(inout) :: hist
    !> Time [s], the boat's rotation (boat -> inertial), CG position (inertial) [m], yaw [rad].
    real(wp), intent(in) :: t, c(3, 3), r(3), yaw
    !> The boat's speeds (Kane order: angular [rad/s], then linear [m/s]).
    real(wp), intent(in) :: u(6)
    !> The BEM water's lagged immersion (0 without it): its diffraction acts while > 0.
    real(wp), intent(in) :: immersion
    logical :: due, maybe_wet(par%water%hull%n)
    real(wp) :: travel
    call strip_waves_due(hist%waves, t, due)
    if (.not. due) then
      ! section loads whose own window ended, and sections that got wet, are sampled now
      call strip_waves_renew_loads(hist%waves, par%water%hull, par%sea, t, c, r)
      return
    end if
    if (hist%surface_grid%enabled) then
      call strips_maybe_wet(hist%watch, par%water, t + hist%waves%clock%interval, c, r, &
                            maybe_wet)
      if (any(maybe_wet)) then
        associate (span => hist%waves%clock%interval)
          call prepare_grid(par%water%hull, par%sea, hist%surface_grid, t, span, c, r)
          call prepare_grid(par%water%hull, par%sea, hist%volume_grid, t, span, c, r, maybe_wet)
        end associate
        call strip_waves_open(hist%waves, par%water%hull, par%sea, t, c, r, hist%surface_grid)
        call strip_waves_sample(hist%waves, par%water%hull, par%sea, c, r, maybe_wet, &
                                hist%volume_grid)
      end if
    else
      call strip_waves_open(hist%waves, par%water%hull, par%sea, t, c, r)
      call refresh_watch_from_strips(hist%waves, par%sea, par%water%hull%n, t, hist%watch)
      travel = boat_travel(par%water%hull, u, hist%waves%clock%interval)
      call strips_maybe_wet(hist%watch, par%water, t, c, r + [0.0_wp, 0.0_wp, travel], &
                            maybe_wet)
      call strip_waves_sample(hist%waves, par%water%hull, par%sea, c, r, maybe_wet)
    end if
    ! the diffraction acts only on a wet hull (lagged immersion s > 0), on the same window
    call par%water_terms%refresh(par%sea, hist%waves%clock, r, yaw, &
                                 any(maybe_wet) .or. immersion > 0.0_wp, hist%diffraction)
  end subroutine refresh_strip_waves

  !> Which strips may touch the water at time t with the boat at (c, r): none where the
  !> watch's test of the whole hull proves it dry (it implies every strip's), else each
  !> strip that strip_surely_dry cannot prove dry.
  pure subroutine strips_maybe_wet(watch, water, t, c, r, maybe_wet)
    type(surface_watch_type), intent(in) :: watch
    type(strip_model_type), intent(in) :: water
    real(wp), intent(in) :: t, c(3, 3), r(3)
    logical, intent(out) :: maybe_wet(:)
    integer :: k
    maybe_wet = .false.
    if (watch%valid) then
      if (hull_surely_dry(watch, water, t, c, r)) return
    end if
    do k = 1, water%hull%n
      maybe_wet(k) = .not. strip_surely_dry(watch, water, k, t, c, r)
    end do
  end subroutine strips_maybe_wet

  !> How far a point of the hull can move within one of the strips' windows [m]: its
  !> CG's speed and its spin times its half length, over the window (the speeds of now).
  pure real(wp) function boat_travel(hull, u, interval) result(travel)
    type(boat_hull_type), intent(in) :: hull
    !> The boat's speeds (Kane order: angular [rad/s], then linear [m/s]).
    real(wp), intent(in) :: u(6)
    !> The window's length [s].
    real(wp), intent(in) :: interval
    travel = (norm2(u(4:6)) + norm2(u(1:3))*0.5_wp*hull%length)*interval
  end function boat_travel

  !> The window just opened sampled the exact elevation at every strip centre at t: the
  !> surface watch takes it instead of summing the sea again (its next refresh comes an
  !> interval later; the strips' windows, renewed at least as often, keep it fresh).
  subroutine refresh_watch_from_strips(waves, sea, n, t, watch)
    !> The strips' slow clock of the water, just refreshed.
    type(strip_wave_cache_type), intent(in) :: waves
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> Number of strips of the hull.
    integer, intent(in) :: n
    !> Time [s].
    real(wp), intent(in) :: t
    !> The surface watch, set from the strips' samples.
    type(surface_watch_type), intent(inout) :: watch
    real(wp) :: xy(2, n), eta(n), grad(2, n), eta_up(n), slope_up(n)
    call strip_waves_surface(waves, sea, xy, eta, grad)
    call watch_set(watch, t, xy, eta, grad)
    call strip_waves_bounds(waves, sea, eta_up, slope_up)
    call watch_set_window(watch, waves%clock%window, eta_up, slope_up)
  end subroutine refresh_watch_from_strips

  !> Make grid g of the sea hold the footprint of the boat's strip hull h (the corners of
  !> its strips, or of those in `only`; boat at (c, r)) over [t, t + span].
  subroutine prepare_grid(h, sea, g, t, span, c, r, only)
    type(boat_hull_type), intent(in) :: h
    type(wave_field_type), intent(in) :: sea
    type(wave_grid_type), intent(inout) :: g
    real(wp), intent(in) :: t, span, c(3, 3), r(3)
    logical, intent(in), optional :: only(:)
    real(wp) :: xy(2, 2*h%n), half
    integer :: k, m
    m = 0
    half = 0.5_wp*maxval(h%breadth)
    do k = 1, h%n
      if (present(only)) then
        if (.not. only(k)) cycle
      end if
      xy(:, m + 1) = r(1:2) + c(1:2, 1)*h%x(k) + c(1:2, 2)*half
      xy(:, m + 2) = r(1:2) + c(1:2, 1)*h%x(k) - c(1:2, 2)*half
      m = m + 2
    end do
    if (m > 0) call grid_prepare(g, sea, t, t + span, xy(:, 1:m))
  end subroutine prepare_grid

  !> Each fender's contact phase on the accepted state, from its indentation and rate
  !> (eqs. 29-33); the first contact.
  subroutine advance_contact(fenders, t, delta, delta_dot, states, first_contact_time)
    !> The fenders and their contact law.
    type(fender_set_type), intent(in) :: fenders
    !> Time of the accepted state [s].
    real(wp), intent(in) :: t
    !> Each fender's indentation [m] and its rate [m/s] (fender_gaps).
    real(wp), intent(in) :: delta(:), delta_dot(:)
    !> Each fender's contact phase, advanced.
    type(fender_state_type), intent(inout) :: states(:)
    !> Time of the first contact [s] (negative until then), set at it.
    real(wp), intent(inout) :: first_contact_time
    integer :: j
    do j = 1, fenders%nf
      call fenders%law%update(states(j), delta(j), delta_dot(j))
      if (states(j)%phase == phase_compression .and. first_contact_time < 0.0_wp) then
        first_contact_time = t
      end if
    end do
  end subroutine advance_contact

  !> Waterborne when rho g V >= W or the hooks carry < 1 % of W, held for 1 s; the hooks
  !> open release_delay later. Checked only when the keel can reach the water (CG less
  !> than 10 m above the still water), so the hanging phase costs nothing. Above that
  !> height the boat is not afloat: the hold restarts (a boat swinging on its falls went
  !> above it with slack hooks and came back with slack hooks seconds later; the old hold
  !> spanned the gap and released the hooks 10 m above the water).
  subroutine watch_waterborne(par, hist, t, y)
    type(system_params_type), intent(in) :: par
    type(system_history_type), intent(inout) :: hist
    real(wp), intent(in) :: t, y(:)
    real(wp), parameter :: hold = 1.0_wp
    if (.not. keel_can_reach_water(par%boat_part, y)) then
      hist%afloat_since = -1.0_wp
      return
    end if
    if (hist%waterborne_time < 0.0_wp) then
      if (.not. afloat(par, hist, t, y)) then
        hist%afloat_since = -1.0_wp
      else if (hist%afloat_since < 0.0_wp) then
        hist%afloat_since = t
      else if (t - hist%afloat_since >= hold) then
        hist%waterborne_time = hist%afloat_since
      end if
    end if
    if (par%release .and. hist%waterborne_time >= 0.0_wp .and. &
        t >= hist%waterborne_time + hold + par%release_delay) call release_hooks(par, hist, t, y)
  end subroutine watch_waterborne

  !> Open the hooks at the accepted state (t, y): the falls freeze where the hooks are.
  subroutine release_hooks(par, hist, t, y)
    !> The system's parameters.
    type(system_params_type), intent(in) :: par
    !> The history (release time, hook positions and ship's pose at release written).
    type(system_history_type), intent(inout) :: hist
    !> Time [s] and state of the release.
    real(wp), intent(in) :: t, y(:)
    real(wp) :: hook_vel(3, nslings)
    hist%release_time = t
    call hook_kinematics(par%boat_part, par%hooks, y, hist%released_hooks, hook_vel)
    hist%released_pose = ship_pose(par%with_ship, par%ship_part, par%ship_rest, y)
  end subroutine release_hooks

  !> The CG is less than 10 m above the still water.
  pure logical function keel_can_reach_water(boat_part, y)
    type(state_part_type), intent(in) :: boat_part
    real(wp), intent(in) :: y(:)
    real(wp) :: c(3, 3), r(3)
    associate (q => y(boat_part%q(1):boat_part%q(2)))
      c = rotation_matrix(q(1:3))
      r = matmul(c, q(4:6))
    end associate
    keel_can_reach_water = .not. r(3) < -10.0_wp
  end function keel_can_reach_water

  !> The buoyancy carries the weight, or the hooks carry less than 1 % of it (asked only
  !> before the release, watch_waterborne).
  logical function afloat(par, hist, t, y)
    type(system_params_type), intent(in) :: par
    type(system_history_type), intent(in) :: hist
    real(wp), intent(in) :: t, y(:)
    real(wp), parameter :: hook_fraction = 0.01_wp
    real(wp) :: c(3, 3), r(3), fw(6), volume, weight
    real(wp) :: seg(par%rig%nseg), sling(par%rig%nlump + 1, 2), paid
    real(wp) :: lumps(3, par%rig%nlump, 2)
    weight = par%boat%mass*gravity
    associate (q => y(par%boat_part%q(1):par%boat_part%q(2)), &
               u => y(par%boat_part%u(1):par%boat_part%u(2)))
      c = rotation_matrix(q(1:3))
      r = matmul(c, q(4:6))
      call water_loads(par%water, par%sea, hist%watch, hist%waves, t, c, r, u, fw, volume)
    end associate
    afloat = rho_water*gravity*volume >= weight
    if (afloat) return
    call rigging_state(par%rig, t, y(par%rig_slice(1):par%rig_slice(2)), &
                       falls_ends_at(par%boat_part, par%hooks, ship_pose(par%with_ship, &
                                     par%ship_part, par%ship_rest, y), y), &
                       .false., seg, sling, paid, lumps)
    afloat = sum(sling(1, :)) < hook_fraction*weight
  end function afloat

end module davit_system_events
