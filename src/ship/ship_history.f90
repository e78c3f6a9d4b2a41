!> What the time loop updates on the 6-DOF ship between steps (davit_ship_ship_model's
!> after-step hook is its writer; the right-hand side reads it as fixed for the step): the
!> heading-dependent wave coefficients, the slow clock of the Froude-Krylov loads with its
!> samples, the steering's switches, and the station and heading set-point (moved by an
!> operator between steps, davit_capi_session). What never changes is in
!> davit_ship_ship_parameters.
module davit_ship_ship_history
  use davit_kinds, only: wp
  use davit_core_slow_clock, only: slow_clock_type, clock_kept, clock_shifted
  use davit_sea_wave_field, only: wave_ramp, wave_chunk, component_phases
  use davit_ship_rudder, only: rudder_type
  use davit_ship_ship_parameters, only: ship_params_type, phase_origin
  implicit none
  private
  public :: ship_history_type, refresh_heading, advance_wave_clock, wave_loads

  !> The ship's history.
  type :: ship_history_type
    !> The heading [rad] the wave coefficients are for (refreshed when the yaw drifts).
    real(wp) :: psi_ref = 0.0_wp
    !> Froude-Krylov loads about G of each component for heading psi_ref:
    !> load = fk_sin(:, i) sin(Phi_i) + fk_cos(:, i) cos(Phi_i) [N, N m].
    real(wp), allocatable :: fk_sin(:, :), fk_cos(:, :)
    !> The BEM ship's wave drift coefficients a_i sqrt(|D_i|) sign(D_i) (surge, sway, yaw)
    !> at heading psi_ref (allocated with a drift level).
    real(wp), allocatable :: drift_coef(:, :)
    !> The mooring's set-point: x, y [m] of the CG and yaw [rad] (davit_ship_ship_model's
    !> set_mooring; the yaw moved by set_heading).
    real(wp) :: anchor(3) = 0.0_wp
    !> The MMG steering (davit_ship_rudder): its heading and the zig-zag's switches.
    type(rudder_type) :: steer
    !> Slow clock of the Froude-Krylov loads (davit_core_slow_clock, rule clock_grid;
    !> `&simulation wave_update`, off at 0): with the phases at the initial position they
    !> depend on time alone, so they are sampled with their rates (wave_f, wave_d) on the
    !> grid k h and interpolated by cubic Hermite in between. Stages outside the window are
    !> evaluated directly.
    type(slow_clock_type) :: clock
    !> The samples at the window's two ends: loads [N, N m] and their rates (heading frame,
    !> without the start-up ramp).
    real(wp) :: wave_f(6, 2) = 0.0_wp, wave_d(6, 2) = 0.0_wp
  end type ship_history_type

contains

  !> Recompute the heading-dependent Froude-Krylov (and drift) coefficients for heading
  !> psi (chi = gamma - psi). The time loop calls this when the yaw has drifted, so the
  !> RHS stays free of it.
  pure subroutine refresh_heading(hist, par, psi)
    !> The history (psi_ref, fk_sin, fk_cos, drift_coef written).
    type(ship_history_type), intent(inout) :: hist
    !> The ship's parameters.
    type(ship_params_type), intent(in) :: par
    !> Heading [rad].
    real(wp), intent(in) :: psi
    hist%psi_ref = psi
    call par%hydro%heading_coefficients(par%hull, par%sea, psi, hist%fk_sin, hist%fk_cos, &
                                        hist%drift_coef)
  end subroutine refresh_heading

  !> Keep the Hermite window of the Froude-Krylov loads on the grid interval that holds t:
  !> shift by one interval (one new sample) or, after a jump or a heading refresh, resample
  !> both ends.
  subroutine advance_wave_clock(hist, par, t)
    !> The history (clock and samples written).
    type(ship_history_type), intent(inout) :: hist
    !> The ship's parameters.
    type(ship_params_type), intent(in) :: par
    !> End of the accepted step [s].
    real(wp), intent(in) :: t
    integer :: action
    call hist%clock%tick(t, action)
    if (action == clock_kept) return
    if (action == clock_shifted) then
      hist%wave_f(:, 1) = hist%wave_f(:, 2)
      hist%wave_d(:, 1) = hist%wave_d(:, 2)
    else
      call fk_unramped(hist, par, hist%clock%window(1), hist%wave_f(:, 1), hist%wave_d(:, 1))
    end if
    call fk_unramped(hist, par, hist%clock%window(2), hist%wave_f(:, 2), hist%wave_d(:, 2))
  end subroutine advance_wave_clock

  !> Froude-Krylov loads (heading frame, without the start-up ramp) at the initial position
  !> and their time derivatives.
  subroutine fk_unramped(hist, par, t, load, rate)
    type(ship_history_type), intent(in) :: hist
    type(ship_params_type), intent(in) :: par
    real(wp), intent(in) :: t
    real(wp), intent(out) :: load(6), rate(6)
    real(wp) :: s(wave_chunk), cs(wave_chunk), o(2), we(wave_chunk)
    integer :: j, i0, i1, m
    load = 0.0_wp
    rate = 0.0_wp
    o = phase_origin(par, t)
    associate (sea => par%sea)
      do i0 = 1, sea%n, wave_chunk
        m = min(wave_chunk, sea%n - i0 + 1)
        i1 = i0 + m - 1
        call component_phases(sea, i0, m, t, o(1), o(2), s, cs)
        ! the phase's rate: the encounter frequency in the moving frame
        we(1:m) = sea%omega(i0:i1) - sea%kx(i0:i1)*par%frame_velocity(1) - &
                  sea%ky(i0:i1)*par%frame_velocity(2)
        do j = 1, 6
          load(j) = load(j) + sum(hist%fk_sin(j, i0:i1)*s(1:m)) + &
                    sum(hist%fk_cos(j, i0:i1)*cs(1:m))
          rate(j) = rate(j) + sum(we(1:m)*(hist%fk_sin(j, i0:i1)*cs(1:m) - &
                                           hist%fk_cos(j, i0:i1)*s(1:m)))
        end do
      end do
    end associate
  end subroutine fk_unramped

  !> Froude-Krylov loads (heading frame) of all components at time t [s] for the ship at
  !> q, c: the phase of each component at O' (review §1.8, "position phase"), from the
  !> slow clock's window where it covers t.
  function wave_loads(par, hist, t, q, c) result(load)
    !> The ship's parameters.
    type(ship_params_type), intent(in) :: par
    !> The history (coefficients, clock and samples).
    type(ship_history_type), intent(in) :: hist
    !> Time [s], the ship's q (Euler angles, CG position) and rotation matrix.
    real(wp), intent(in) :: t, q(6), c(3, 3)
    real(wp) :: load(6), o(3), s(wave_chunk), cs(wave_chunk)
    integer :: j, i0, i1, m
    associate (sea => par%sea)
      if (hist%clock%covers(t)) then
        load = wave_ramp(sea, t)*hist%clock%interpolate(hist%wave_f(:, 1), hist%wave_d(:, 1), &
                                                        hist%wave_f(:, 2), hist%wave_d(:, 2), t)
        return
      end if
      if (par%phase_at_initial) then
        o(1:2) = phase_origin(par, t)
      else
        o = q(4:6) - matmul(c, [par%hull%cg_x, 0.0_wp, par%hull%cg_z])
      end if
      load = 0.0_wp
      do i0 = 1, sea%n, wave_chunk
        m = min(wave_chunk, sea%n - i0 + 1)
        i1 = i0 + m - 1
        call component_phases(sea, i0, m, t, o(1), o(2), s, cs)
        do j = 1, 6
          load(j) = load(j) + sum(hist%fk_sin(j, i0:i1)*s(1:m)) + &
                    sum(hist%fk_cos(j, i0:i1)*cs(1:m))
        end do
      end do
      load = wave_ramp(sea, t)*load
    end associate
  end function wave_loads

end module davit_ship_ship_history
