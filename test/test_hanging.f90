!> The foundation's physical system: the III.B lifeboat hanging from two fixed points on two
!> massless elastic slings. Statics, small-oscillation periods against closed forms (review
!> A9), energy conservation and RK4 convergence order.
module test_hanging
  use davit_kinds, only: wp, pi, gravity
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_system_model, only: system_type
  use system_fixture, only: new_test_system, nstate
  use davit_solve_rk4, only: rk4_type
  use test_problems, only: oscillator
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_hanging


  real(wp), parameter :: hook_height = 1.55_wp

contains

  function collect_hanging() result(suite)
    type(suite_type) :: suite
    suite%name = "hanging_boat"
    suite%cases = [new_case("static_half_weight_each_sling", static_hanging), &
                   new_case("surge_pendulum_period", surge_period), &
                   new_case("sway_roll_double_pendulum_A9", sway_roll_periods), &
                   new_case("axial_bounce_frequency", bounce_frequency), &
                   new_case("energy_conserved_without_damping", energy_conservation), &
                   new_case("rk4_order_oscillator", rk4_order_oscillator), &
                   new_case("rk4_order_swinging_boat", rk4_order_boat)]
  end function collect_hanging

  !> Default configuration (III.B boat, 3 m slings), with anchors placed `fall` above the
  !> hooks and unstretched length chosen so the slings are at static equilibrium at t = 0
  !> (T = W/2 = EA (L - l0)/l0) unless `unstretched`.
  function hanging_config(fall, damping, unstretched) result(cfg)
    real(wp), intent(in) :: fall, damping
    logical, intent(in) :: unstretched
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    real(wp) :: ea
    call parse_config("test.nml", "", cfg, error)
    ! The analytic pendulum and spring checks need the boat in still air, off the ship.
    cfg%wind%speed = 0.0_wp
    cfg%boat%wind_drag_coefficient = 0.0_wp
    cfg%boat%lift_coefficient = 0.0_wp
    cfg%contact%enabled = .false.
    ! the 12-state boat of the paper's strips (in the air the BEM terms are nil anyway)
    cfg%boat%water_model = "paper"
    ea = cfg%slings%youngs_modulus*pi*cfg%slings%diameter**2/4.0_wp
    cfg%slings%damping = damping
    cfg%slings%anchor_fore = cfg%boat%position + cfg%slings%hook_fore - [0.0_wp, 0.0_wp, fall]
    cfg%slings%anchor_aft = cfg%boat%position + cfg%slings%hook_aft - [0.0_wp, 0.0_wp, fall]
    if (unstretched) then
      cfg%slings%length = fall
    else
      cfg%slings%length = fall/(1.0_wp + 0.5_wp*cfg%boat%mass*gravity/ea)
    end if
  end function hanging_config

  !> Integrate n steps of RK4 from y, sampling signal(y) every step into s(0:n).
  subroutine integrate(sys, y, dt, n, component, s)
    type(system_type), intent(in) :: sys
    real(wp), intent(inout) :: y(:)
    real(wp), intent(in) :: dt
    integer, intent(in) :: n, component
    real(wp), intent(out), optional :: s(0:)
    type(rk4_type) :: rk
    real(wp) :: t
    integer :: i
    call rk%init(size(y))
    t = 0.0_wp
    if (present(s)) s(0) = signal(y, component)
    do i = 1, n
      call rk%step(sys, t, y, dt)
      if (present(s)) s(i) = signal(y, component)
    end do
  end subroutine integrate

  !> component 1..3: inertial CG position; 4: roll angle.
  pure real(wp) function signal(y, component)
    real(wp), intent(in) :: y(:)
    integer, intent(in) :: component
    real(wp) :: c1, s1, c2, s2, c3, s3, r(3)
    if (component == 4) then
      signal = y(1)
      return
    end if
    s1 = sin(y(1)); c1 = cos(y(1)); s2 = sin(y(2)); c2 = cos(y(2))
    s3 = sin(y(3)); c3 = cos(y(3))
    r(1) = c2*c3*y(4) + (s1*s2*c3 - s3*c1)*y(5) + (c1*s2*c3 + s3*s1)*y(6)
    r(2) = c2*s3*y(4) + (s1*s2*s3 + c1*c3)*y(5) + (c1*s2*s3 - c3*s1)*y(6)
    r(3) = -s2*y(4) + s1*c2*y(5) + c1*c2*y(6)
    signal = r(component)
  end function signal

  !> Mean period from upward crossings of the signal's mean, linearly interpolated.
  real(wp) function period_of(s, dt) result(period)
    real(wp), intent(in) :: s(0:), dt
    real(wp) :: mean, first, last
    integer :: i, ncross
    mean = sum(s)/size(s)
    ncross = 0
    first = 0.0_wp
    last = 0.0_wp
    do i = 1, ubound(s, 1)
      if (s(i - 1) < mean .and. s(i) >= mean) then
        last = (real(i - 1, wp) + (mean - s(i - 1))/(s(i) - s(i - 1)))*dt
        if (ncross == 0) first = last
        ncross = ncross + 1
      end if
    end do
    period = -1.0_wp
    if (ncross >= 2) period = (last - first)/real(ncross - 1, wp)
  end function period_of

  subroutine static_hanging(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate), tension(2), weight
    cfg = hanging_config(3.0_wp, 1.0e4_wp, unstretched=.true.)
    y = new_test_system(sys, cfg)
    call integrate(sys, y, 1.0e-3_wp, 30000, 3)
    tension = sys%sling_tensions(y)
    weight = cfg%boat%mass*gravity
    call note(state, "fore tension/(W/2) - 1", tension(1)/(0.5_wp*weight) - 1.0_wp)
    call note(state, "aft tension/(W/2) - 1", tension(2)/(0.5_wp*weight) - 1.0_wp)
    call check(state, tension(1), 0.5_wp*weight, "fore sling tension = W/2", rel_tol=1e-6_wp)
    call check(state, tension(2), 0.5_wp*weight, "aft sling tension = W/2", rel_tol=1e-6_wp)
    call check(state, y(1), 0.0_wp, "roll stays zero", abs_tol=1e-9_wp)
    call check(state, y(2), 0.0_wp, "pitch stays zero", abs_tol=1e-9_wp)
    call check(state, y(3), 0.0_wp, "yaw stays zero", abs_tol=1e-9_wp)
  end subroutine static_hanging

  !> Parallel slings of length L: the boat translates fore-aft as a simple pendulum,
  !> T = 2 pi sqrt(L/g) (sling stretch is included in L by construction).
  subroutine surge_period(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp), parameter :: fall = 3.0_wp, dt = 1.0e-3_wp
    real(wp) :: y(nstate), s(0:20000)
    cfg = hanging_config(fall, 0.0_wp, unstretched=.false.)
    cfg%boat%velocity = [0.05_wp, 0.0_wp, 0.0_wp]
    y = new_test_system(sys, cfg)
    call integrate(sys, y, dt, ubound(s, 1), 1, s)
    call note(state, "surge period [s]", period_of(s, dt))
    call note(state, "2 pi sqrt(L/g) [s]", 2.0_wp*pi*sqrt(fall/gravity))
    call check(state, period_of(s, dt), 2.0_wp*pi*sqrt(fall/gravity), "surge period", &
               rel_tol=5e-3_wp)
  end subroutine surge_period

  !> Review A9: sway of the hook line (angle alpha) coupled with roll (psi, hooks h above the
  !> CG): M = [[m L^2, m L h], [m L h, m h^2 + I_xx]], K = diag(m g L, m g h). Each mode is
  !> started on its own mode shape and its period measured. Also checks the closed form
  !> against the review's tabulated 4.66/2.06 s (L = 3 m) and 6.90/2.54 s (L = 10 m).
  subroutine sway_roll_periods(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: falls(2) = [3.0_wp, 10.0_wp]
    real(wp), parameter :: review(2, 2) = reshape([4.66_wp, 2.06_wp, 6.90_wp, 2.54_wp], [2, 2])
    real(wp), parameter :: dt = 1.0e-3_wp
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate), m, ixx, l, h, m11, m12, m22, k11, k22, a, b, c, w2(2), v(2)
    real(wp), allocatable :: s(:)
    integer :: i, mode, n
    h = hook_height
    do i = 1, size(falls)
      l = falls(i)
      cfg = hanging_config(l, 0.0_wp, unstretched=.false.)
      m = cfg%boat%mass
      ixx = cfg%boat%inertia(1)
      m11 = m*l*l; m12 = m*l*h; m22 = m*h*h + ixx
      k11 = m*gravity*l; k22 = m*gravity*h
      ! det(K - w2 M) = 0
      a = m11*m22 - m12*m12
      b = -(k11*m22 + k22*m11)
      c = k11*k22
      w2 = [(-b - sqrt(b*b - 4*a*c))/(2*a), (-b + sqrt(b*b - 4*a*c))/(2*a)]
      do mode = 1, 2
        call check(state, 2*pi/sqrt(w2(mode)), review(mode, i), "A9 closed form vs review", &
                   rel_tol=5e-3_wp)
        v = [w2(mode)*m12, k11 - w2(mode)*m11]
        v = v/maxval(abs([l*v(1), h*v(2)]))*0.05_wp
        ! hook y = L alpha; CG y = L alpha + h psi; roll = -psi (eq. 2 sign convention)
        cfg%boat%position(2) = cfg%slings%anchor_fore(2) + l*v(1) + h*v(2)
        cfg%boat%euler = [-v(2), 0.0_wp, 0.0_wp]
        y = new_test_system(sys, cfg)
        n = nint(4.5_wp*2*pi/sqrt(w2(mode))/dt)
        if (allocated(s)) deallocate (s)
        allocate (s(0:n))
        call integrate(sys, y, dt, n, 4, s)
        call note(state, "L="//trim(merge("3 ", "10", i == 1))//" mode "//achar(48 + mode)// &
                  " simulated period [s]", period_of(s, dt))
        call note(state, "L="//trim(merge("3 ", "10", i == 1))//" mode "//achar(48 + mode)// &
                  " analytic period [s]", 2*pi/sqrt(w2(mode)))
        call check(state, period_of(s, dt), 2*pi/sqrt(w2(mode)), "A9 mode period", &
                   rel_tol=0.01_wp)
      end do
    end do
  end subroutine sway_roll_periods

  !> Vertical bounce of the boat on the two slings: omega = sqrt(2 EA/(l0 m)).
  subroutine bounce_frequency(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp), parameter :: dt = 1.0e-4_wp
    real(wp) :: y(nstate), s(0:10000), ea, omega
    cfg = hanging_config(3.0_wp, 0.0_wp, unstretched=.false.)
    cfg%boat%velocity = [0.0_wp, 0.0_wp, 0.01_wp]
    y = new_test_system(sys, cfg)
    call integrate(sys, y, dt, ubound(s, 1), 3, s)
    ea = cfg%slings%youngs_modulus*pi*cfg%slings%diameter**2/4.0_wp
    omega = sqrt(2.0_wp*ea/cfg%slings%length/cfg%boat%mass)
    call note(state, "bounce period [s]", period_of(s, dt))
    call note(state, "2 pi sqrt(l0 m/(2 EA)) [s]", 2*pi/omega)
    call check(state, period_of(s, dt), 2*pi/omega, "bounce period", rel_tol=1e-3_wp)
  end subroutine bounce_frequency

  !> Undamped, the total energy (kinetic + gravity + elastic) is conserved: drift over 100 s
  !> below 1e-6 of the initial kinetic energy of a 3-D swing.
  subroutine energy_conservation(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate), e0, ke0, emax, e
    type(rk4_type) :: rk
    real(wp) :: t
    integer :: i
    cfg = hanging_config(3.0_wp, 0.0_wp, unstretched=.false.)
    cfg%boat%velocity = [0.3_wp, 0.5_wp, 0.0_wp]
    cfg%boat%angular_velocity = [0.05_wp, 0.0_wp, 0.03_wp]
    y = new_test_system(sys, cfg)
    e0 = sys%energy(y)
    ke0 = 0.5_wp*(cfg%boat%mass*0.34_wp + cfg%boat%inertia(1)*0.05_wp**2 + &
                  cfg%boat%inertia(3)*0.03_wp**2)
    call rk%init(nstate)
    t = 0.0_wp
    emax = 0.0_wp
    do i = 1, 200000
      call rk%step(sys, t, y, 5.0e-4_wp)
      if (mod(i, 100) == 0) then
        e = sys%energy(y)
        emax = max(emax, abs(e - e0))
      end if
    end do
    call note(state, "max |E - E0|/KE0", emax/ke0)
    call check(state, emax/ke0, 0.0_wp, "max |E - E0|/KE0 over 100 s", abs_tol=1e-6_wp)
    call check_true(state, maxval(abs(y(1:3))) > 1e-3_wp, "the boat really moved in 3-D")
  end subroutine energy_conservation

  subroutine rk4_order_oscillator(state)
    type(case_state), intent(inout) :: state
    type(oscillator) :: osc
    type(rk4_type) :: rk
    real(wp) :: y(2), t, err(2), dt
    integer :: k, i
    call rk%init(2)
    do k = 1, 2
      dt = 0.1_wp/2**(k - 1)
      y = [1.0_wp, 0.0_wp]
      t = 0.0_wp
      do i = 1, nint(10.0_wp/dt)
        call rk%step(osc, t, y, dt)
      end do
      err(k) = abs(y(1) - cos(10.0_wp))
    end do
    call note(state, "error ratio", err(1)/err(2))
    call check(state, err(1)/err(2), 16.0_wp, "error ratio when dt halves", rel_tol=0.2_wp)
    call check_true(state, rk%rhs_evaluations == 4*(100 + 200), "4 RHS evaluations per step")
  end subroutine rk4_order_oscillator

  !> Self-convergence on the coupled swinging boat: differences between successive halvings
  !> of dt fall 16x.
  subroutine rk4_order_boat(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(system_type) :: sys
    real(wp) :: y(nstate, 3), y0(nstate), dt
    integer :: k
    cfg = hanging_config(3.0_wp, 1.0e4_wp, unstretched=.true.)
    cfg%boat%velocity = [0.3_wp, 0.5_wp, 0.0_wp]
    cfg%boat%angular_velocity = [0.05_wp, 0.0_wp, 0.03_wp]
    y0 = new_test_system(sys, cfg)
    do k = 1, 3
      dt = 4.0e-3_wp/2**(k - 1)
      y(:, k) = y0
      call integrate(sys, y(:, k), dt, nint(2.0_wp/dt), 1)
    end do
    call note(state, "self-convergence ratio", norm2(y(:, 1) - y(:, 2))/norm2(y(:, 2) - y(:, 3)))
    call check(state, norm2(y(:, 1) - y(:, 2))/norm2(y(:, 2) - y(:, 3)), 16.0_wp, &
               "self-convergence ratio", rel_tol=0.2_wp)
  end subroutine rk4_order_boat

end module test_hanging
