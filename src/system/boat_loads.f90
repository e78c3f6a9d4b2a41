!> The lifeboat's Kane blocks (eq. 12) and its generalized active forces: gravity (eq. 13),
!> the foundation slings (eq. 26), water by strip theory (eqs. 18-25), wind (eqs. 14-17, at
!> the CG) and fender contact with the ship's side (eq. 34). The davit rigging's hook
!> forces (eq. 26) are added by the assembler, which evaluates the rigging. With the BEM
!> water model (davit_boat_bem_water) the boat's mass block is M + s A(inf), filled as its
!> modal masses (the layout's modal coupled block), and it advances its water states.
module davit_system_boat_loads
  use davit_kinds, only: wp
  use davit_core_rotation, only: rotation_matrix
  use davit_core_kane, only: kane_v, kane_w_phi, kane_f
  use davit_core_body, only: body_mass_diagonal, body_w_phi, body_qdot, &
                             body_gravity_force, body_point_force, body_point_velocity
  use davit_rigging_elastic_sling, only: elastic_sling_type, sling_hook_force
  use davit_sea_wind, only: wind_velocity
  use davit_boat_strip_loads, only: strip_model_type, strip_loads
  use davit_boat_strip_waves, only: strip_wave_cache_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_boat_fenders, only: side_plane_type, fender_set_type, fender_loads
  use davit_boat_contact_law, only: fender_state_type
  use davit_boat_surface_watch, only: surface_watch_type, surely_dry
  use davit_system_parameters, only: system_params_type, nslings
  use davit_system_history, only: system_history_type
  use davit_solve_integrator, only: part_slow, part_fast
  implicit none
  private
  public :: boat_kane_blocks, water_loads
  public :: loads_all, loads_slow, loads_fast

  !> Which of the boat's terms boat_kane_blocks forms (the multirate split,
  !> davit_solve_multirate): all of them; the slow ones (water by strips and BEM with the
  !> BEM states' rates, wind); the fast ones (q_dot, W phi, gravity, foundation slings,
  !> fenders). Slow plus fast is all, term by term. The two parts are the integrator's
  !> (ode_problem%rhs_part's part_slow, part_fast), so a part passes straight through.
  integer, parameter :: loads_all = 0, loads_slow = part_slow, loads_fast = part_fast

contains

  !> q_dot (eqs. 5-6) and the Kane blocks V, W phi, F of the boat at (q, u), with the ship's
  !> side at `side`; with the BEM water model, the rates xdot of its water states x (part
  !> "boat_radiation"; empty otherwise). `part` (loads_all by default) selects the terms;
  !> V is the whole mass block in every part.
  pure subroutine boat_kane_blocks(par, hist, t, q, u, x, side, qdot, xdot, kane, part)
    !> The system's parameters (boat, slings, water and wind models, fenders).
    type(system_params_type), intent(in) :: par
    !> The history (fender phases, surface watch, the water on the slow clocks).
    type(system_history_type), intent(in) :: hist
    !> Time [s]; the boat's coordinates q (Euler angles [rad], CG position in body
    !> components [m], eq. 3) and speeds u (omega [rad/s], v [m/s], body components);
    !> its BEM water states x (immersion, radiation memory; empty without them).
    real(wp), intent(in) :: t, q(6), u(6), x(:)
    !> The ship's side plane the fenders touch (inertial).
    type(side_plane_type), intent(in) :: side
    !> Rates of q and of x, and the rows V, W phi, F of the boat's six speeds (Kane order,
    !> moments [N m] first, then forces [N]).
    real(wp), intent(out) :: qdot(6), xdot(:), kane(3, 6)
    !> loads_all (default), loads_slow or loads_fast.
    integer, intent(in), optional :: part
    logical :: slow, fast
    slow = .true.
    fast = .true.
    if (present(part)) then
      slow = part /= loads_fast
      fast = part /= loads_slow
    end if
    kane(kane_v, :) = body_mass_diagonal(par%boat)
    if (fast) then
      qdot = body_qdot(q, u)
      kane(kane_w_phi, :) = body_w_phi(par%boat, u)
    else
      qdot = 0.0_wp
      kane(kane_w_phi, :) = 0.0_wp
    end if
    call boat_forces(par, hist, t, q, u, x, side, kane(kane_f, :), xdot, kane(kane_v, :), &
                     slow, fast)
  end subroutine boat_kane_blocks

  !> Generalized active forces f on the boat but the davit's hook forces; with the BEM
  !> water model, its states' rates and the modal masses v of M + s A(inf). Only the slow
  !> terms, or only the fast ones, where one of `slow`, `fast` is false (the BEM states
  !> then have no rates in the fast part, and the modal masses come from their immersion
  !> state alone, as boat_bem_loads forms them for s >= 0).
  pure subroutine boat_forces(par, hist, t, q, u, x, side, f, xdot, v, slow, fast)
    type(system_params_type), intent(in) :: par
    type(system_history_type), intent(in) :: hist
    real(wp), intent(in) :: t, q(6), u(6), x(:)
    type(side_plane_type), intent(in) :: side
    real(wp), intent(out) :: f(6), xdot(:)
    real(wp), intent(inout) :: v(6)
    logical, intent(in) :: slow, fast
    real(wp) :: c(3, 3), r(3)
    c = rotation_matrix(q(1:3))
    r = matmul(c, q(4:6))
    if (fast) then
      f = body_gravity_force(par%boat, c)
      if (par%slings_attached) call sling_forces(par%slings, par%hooks, c, r, u, f)
    else
      f = 0.0_wp
    end if
    if (slow) then
      call slow_forces(par, hist, t, q, u, x, c, r, f, xdot, v)
    else
      xdot = 0.0_wp
      call par%water_terms%modal_masses(x, v)
    end if
    if (fast .and. par%contact) call fender_forces(par%fenders, hist%fender_states, side, c, r, &
                                                  u, f)
  end subroutine boat_forces

  !> The foundation slings' hook forces (eq. 26) added to f.
  pure subroutine sling_forces(slings, hooks, c, r, u, f)
    !> The slings, one per hook.
    type(elastic_sling_type), intent(in) :: slings(nslings)
    !> Hook points in the boat frame [m], one column per sling.
    real(wp), intent(in) :: hooks(3, nslings)
    !> The boat's rotation (body -> inertial), CG position (inertial) [m] and speeds.
    real(wp), intent(in) :: c(3, 3), r(3), u(6)
    !> Generalized forces (Kane order), the slings' added.
    real(wp), intent(inout) :: f(6)
    real(wp) :: fh(3), tension
    integer :: i
    do i = 1, nslings
      call sling_hook_force(slings(i), r + matmul(c, hooks(:, i)), &
                            matmul(c, body_point_velocity(u, hooks(:, i))), fh, tension)
      f = f + body_point_force(hooks(:, i), matmul(transpose(c), fh))
    end do
  end subroutine sling_forces

  !> Water (strips, BEM) and wind added to f, the BEM states' rates and modal masses.
  pure subroutine slow_forces(par, hist, t, q, u, x, c, r, f, xdot, v)
    type(system_params_type), intent(in) :: par
    type(system_history_type), intent(in) :: hist
    real(wp), intent(in) :: t, q(6), u(6), x(:), c(3, 3), r(3)
    real(wp), intent(inout) :: f(6), v(6)
    real(wp), intent(out) :: xdot(:)
    real(wp) :: fw(6), volume
    call water_loads(par%water, par%sea, hist%watch, hist%waves, t, c, r, u, fw, volume)
    f = f + fw
    call par%water_terms%add_loads(par%sea, t, c, r, q(3), u, volume, x, hist%diffraction, &
                                   xdot, f, v)
    f(4:6) = f(4:6) + par%air%force(u(4:6) - matmul(wind_velocity(par%wind), c), &
                                    max(0.0_wp, 1.0_wp - volume/par%hull_volume))
  end subroutine slow_forces

  !> The fenders' contact loads (eq. 34) added to f.
  pure subroutine fender_forces(fenders, states, side, c, r, u, f)
    !> The fenders and their contact law.
    type(fender_set_type), intent(in) :: fenders
    !> Each fender's contact phase (the history's).
    type(fender_state_type), intent(in) :: states(:)
    !> The ship's side plane the fenders touch (inertial).
    type(side_plane_type), intent(in) :: side
    !> The boat's rotation (body -> inertial), CG position (inertial) [m] and speeds.
    real(wp), intent(in) :: c(3, 3), r(3), u(6)
    !> Generalized forces (Kane order), the contact's added.
    real(wp), intent(inout) :: f(6)
    real(wp) :: fw(6), force(fenders%nf)
    call fender_loads(fenders, states, side, c, r, u, fw, force)
    f = f + fw
  end subroutine fender_forces

  !> Strip water loads (eqs. 18-25) and wet volume, exactly zero without forming them
  !> while the surface watch proves the hull dry; from the strips' slow clock where it
  !> covers t.
  pure subroutine water_loads(water, sea, watch, waves, t, c, r, u, f, volume)
    !> The strip model of the boat in the water.
    type(strip_model_type), intent(in) :: water
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> The surface watch (the history's), which proves the hull dry.
    type(surface_watch_type), intent(in) :: watch
    !> The strips' slow clock of the water (the history's).
    type(strip_wave_cache_type), intent(in) :: waves
    !> Time [s], the boat's rotation (body -> inertial), CG position (inertial) [m] and
    !> speeds (omega [rad/s], v [m/s], body components).
    real(wp), intent(in) :: t, c(3, 3), r(3), u(6)
    !> Generalized forces of the water (Kane order) [N m, N] and the wet volume [m^3].
    real(wp), intent(out) :: f(6), volume
    if (surely_dry(watch, water, t, c, r)) then
      f = 0.0_wp
      volume = 0.0_wp
    else
      call strip_loads(water, sea, t, c, r, u, f, volume, waves)
    end if
  end subroutine water_loads

end module davit_system_boat_loads
