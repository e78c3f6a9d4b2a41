!> Small laws tested directly, each against its closed form: the foundation sling's Hooke
!> spring and axial dashpot (tension-only), the wire's dashpot as a fraction of critical, the
!> seafarer's words for where the waves come from, a path's folder, and the peak-load watch
!> on a tension history whose exceedances are known in closed form, and the contact step
!> policy's rules on gaps whose time to contact is known.
module test_small_laws
  use davit_kinds, only: wp, pi
  use davit_rigging_elastic_sling, only: elastic_sling_type, sling_hook_force, sling_energy
  use davit_rigging_wire_damping, only: wire_dashpot
  use davit_run_scenario, only: coming_from
  use davit_io_search_path, only: folder_of
  use davit_run_load_peaks, only: load_peaks
  use davit_boat_contact_law, only: fender_state_type, phase_compression
  use davit_system_contact_policy, only: contact_policy_type, limits_steps, contact_max_step
  use harness, only: suite_type, case_state, new_case, check, check_true
  implicit none
  private
  public :: collect_small_laws

contains

  function collect_small_laws() result(suite)
    type(suite_type) :: suite
    suite%name = "small_laws"
    suite%cases = [new_case("elastic_sling_hooke_dashpot_tension_only", elastic_sling), &
                   new_case("wire_dashpot_fraction_of_critical", wire_critical), &
                   new_case("waves_coming_from_in_eight_sectors", coming_from_sectors), &
                   new_case("folder_of_a_path", folder_of_paths), &
                   new_case("load_peaks_half_sine_exceedances", half_sine_peaks), &
                   new_case("contact_step_policy_window_graded_located", contact_steps)]
  end function collect_small_laws

  !> A sling of l0 = 1 m, EA = 1e6 N (k = EA/l0 = 1e6 N/m), c = 100 N s/m from an anchor at
  !> the origin: stretched 1 cm and opening at 0.2 m/s, T = k 0.01 + c 0.2 = 10020 N pulling
  !> the hook back to the anchor; slack (0.99 m): nothing; closing at 20 m/s while stretched
  !> 1 mm, k 0.001 - c 20 = -1000 N, which a rope cannot push: 0 (eq. 58). Its energy
  !> 1/2 k s^2 = 50 J at 1 cm, and the spring force is -dE/dx (central difference).
  subroutine elastic_sling(state)
    type(case_state), intent(inout) :: state
    type(elastic_sling_type) :: s
    real(wp) :: force(3), tension, de
    s%anchor = 0.0_wp
    s%length = 1.0_wp
    s%ea = 1.0e6_wp
    s%damping = 100.0_wp
    call sling_hook_force(s, [0.0_wp, 0.0_wp, 1.01_wp], [0.0_wp, 0.0_wp, 0.2_wp], force, tension)
    call check(state, tension, 10020.0_wp, "T = k s + c v", rel_tol=1.0e-12_wp)
    call check(state, force(3), -10020.0_wp, "force on the hook towards the anchor", &
               rel_tol=1.0e-12_wp)
    call check(state, norm2(force(1:2)), 0.0_wp, "no sideways force", abs_tol=0.0_wp)
    call sling_hook_force(s, [0.0_wp, 0.0_wp, 0.99_wp], [0.0_wp, 0.0_wp, 0.2_wp], force, tension)
    call check(state, tension, 0.0_wp, "slack: no tension", abs_tol=0.0_wp)
    call sling_hook_force(s, [0.0_wp, 0.0_wp, 1.001_wp], [0.0_wp, 0.0_wp, -20.0_wp], force, &
                          tension)
    call check(state, tension, 0.0_wp, "closing fast: tension-only, not -1000 N", &
               abs_tol=0.0_wp)
    call check(state, sling_energy(s, [0.0_wp, 0.0_wp, 1.01_wp]), 50.0_wp, "E = k s^2/2", &
               rel_tol=1.0e-12_wp)
    s%damping = 0.0_wp
    de = (sling_energy(s, [0.0_wp, 0.0_wp, 1.0101_wp]) - &
          sling_energy(s, [0.0_wp, 0.0_wp, 1.0099_wp]))/2.0e-4_wp
    call sling_hook_force(s, [0.0_wp, 0.0_wp, 1.01_wp], [0.0_wp, 0.0_wp, 0.0_wp], force, tension)
    call check(state, -de, force(3), "force = -dE/dx", rel_tol=1.0e-9_wp)
  end subroutine elastic_sling

  !> c = 2 zeta sqrt(k m): at zeta = 1 the oscillator m x'' + c x' + k x = 0 is critically
  !> damped (c^2 = 4 k m); k = 4e6 N/m, m = 100 kg gives c = 4e4 N s/m; zeta = 0.05 of it.
  subroutine wire_critical(state)
    type(case_state), intent(inout) :: state
    real(wp) :: c
    c = wire_dashpot(1.0_wp, 4.0e6_wp, 100.0_wp)
    call check(state, c, 4.0e4_wp, "critical c = 2 sqrt(k m)", rel_tol=1.0e-14_wp)
    call check(state, c**2 - 4.0_wp*4.0e6_wp*100.0_wp, 0.0_wp, "discriminant zero", &
               abs_tol=1.0e-6_wp*c**2)
    call check(state, wire_dashpot(0.05_wp, 4.0e6_wp, 100.0_wp), 0.05_wp*c, "zeta = 0.05", &
               rel_tol=1.0e-14_wp)
  end subroutine wire_critical

  !> Directions are where the waves travel towards, from the bow towards starboard (the
  !> deck convention of README.md): travelling towards 180 (aft) they come from ahead (head
  !> seas), towards 0 from astern, towards 90 (starboard) from port, towards 270 from
  !> starboard, towards 135 from the port bow (315 deg), towards 45 from the port quarter;
  !> 22 deg rounds to the nearest sector (0); towards -45 (the port bow) they come from the
  !> starboard quarter.
  subroutine coming_from_sectors(state)
    type(case_state), intent(inout) :: state
    call check_true(state, coming_from(180.0_wp) == "from ahead (head seas)", "180")
    call check_true(state, coming_from(0.0_wp) == "from astern (following seas)", "0")
    call check_true(state, coming_from(90.0_wp) == "from port (on the beam)", "90")
    call check_true(state, coming_from(270.0_wp) == "from starboard (on the beam)", "270")
    call check_true(state, coming_from(135.0_wp) == "from the port bow", "135")
    call check_true(state, coming_from(45.0_wp) == "from the port quarter", "45")
    call check_true(state, coming_from(22.0_wp) == "from astern (following seas)", "22")
    call check_true(state, coming_from(-45.0_wp) == "from the starboard quarter", "-45")
  end subroutine coming_from_sectors

  !> The folder part of a path keeps its trailing "/"; a bare name has none.
  subroutine folder_of_paths(state)
    type(case_state), intent(inout) :: state
    call check_true(state, folder_of("input/decks/a.nml") == "input/decks/", "two folders")
    call check_true(state, folder_of("a.nml") == "", "bare name")
    call check_true(state, folder_of("/a.h5") == "/", "root")
  end subroutine folder_of_paths

  !> Two half-sine pulses T(t) = T0 sin(pi t/tau) (tau = 2 s, T0 = 60 kN, then 0 for 1 s,
  !> then the pulse again) sampled every h = 1e-3 s against an MBL of 120 kN with factor 6
  !> (SWL 20 kN): the peak is T0 at t = tau/2 = 1 s; the SWL is first exceeded at
  !> t1 = tau/pi asin(SWL/T0) = 0.21635 s, each pulse stays above it tau - 2 t1 = 1.5673 s
  !> (the watch sums the steps that end above it: within h per crossing), it is exceeded
  !> twice, and the MBL never. The sling (T/2 here) peaks with the segment.
  subroutine half_sine_peaks(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: tau = 2.0_wp, t0 = 60.0e3_wp, h = 1.0e-3_wp
    type(load_peaks) :: p
    real(wp) :: t, tension, t1
    integer :: k
    call p%init(1, 1, 120.0e3_wp, 6.0_wp, 3.5_wp)
    do k = 1, nint(5.0_wp/h)
      t = k*h
      tension = 0.0_wp
      if (t <= tau) tension = t0*sin(pi*t/tau)
      if (t >= tau + 1.0_wp) tension = t0*sin(pi*(t - tau - 1.0_wp)/tau)
      call p%update(t, [tension], [0.5_wp*tension])
    end do
    t1 = tau/pi*asin(20.0e3_wp/t0)
    call check(state, p%segment(1), t0, "peak T0", rel_tol=1.0e-12_wp)
    call check(state, p%segment_time(1), tau/2.0_wp, "peak at tau/2", abs_tol=0.5_wp*h)
    call check(state, p%sling(1), 0.5_wp*t0, "sling peak", rel_tol=1.0e-12_wp)
    call check(state, p%swl%first, t1, "SWL first exceeded", abs_tol=h)
    call check(state, p%swl%duration, 2.0_wp*(tau - 2.0_wp*t1), "time above the SWL", &
               abs_tol=4.0_wp*h)
    call check_true(state, p%swl%count == 2, "two excursions above the SWL")
    call check_true(state, p%mbl%count == 0 .and. p%mbl%first < 0.0_wp, "MBL never reached")
  end subroutine half_sine_peaks

  !> The contact step policy with dt = 0.1 s and dt_contact = 0.01 s. It acts only with
  !> contact on and 0 < dt_contact < dt. 'window': a fender 0.15 m off approaching at 1 m/s
  !> reaches the side within two steps (-0.15 + 2 x 0.1 x 1 > 0): dt_contact; 0.25 m off it
  !> does not, nor does a receding one: dt. 'graded': half the time to contact, 0.15/1/2 =
  !> 0.075 s, never below dt_contact (0.015 m off: 0.0075 -> 0.01 s), the nearest fender's.
  !> A fender in contact: dt_contact; 'event' (located): dt while every fender is free.
  subroutine contact_steps(state)
    type(case_state), intent(inout) :: state
    type(contact_policy_type) :: p
    type(fender_state_type) :: free(2), touching(2)
    real(wp), parameter :: dt = 0.1_wp
    p%dt_contact = 0.01_wp
    touching(2)%phase = phase_compression
    call check_true(state, limits_steps(p, .true., dt), "limits with contact on")
    call check_true(state, .not. limits_steps(p, .false., dt), "no limit with contact off")
    call check_true(state, .not. limits_steps(p, .true., 0.01_wp), "no limit at dt_contact = dt")
    call check_true(state, .not. limits_steps(contact_policy_type(), .true., dt), &
                    "no limit at dt_contact = 0")
    call check(state, contact_max_step(p, free, [-0.15_wp, -1.0_wp], [1.0_wp, 0.0_wp], dt), &
               0.01_wp, "window: contact within two steps", abs_tol=0.0_wp)
    call check(state, contact_max_step(p, free, [-0.25_wp, -1.0_wp], [1.0_wp, 0.0_wp], dt), &
               dt, "window: contact beyond two steps", abs_tol=0.0_wp)
    call check(state, contact_max_step(p, free, [-0.05_wp, -1.0_wp], [-1.0_wp, 0.0_wp], dt), &
               dt, "window: receding", abs_tol=0.0_wp)
    call check(state, contact_max_step(p, touching, [-0.5_wp, -1.0_wp], [0.0_wp, 0.0_wp], dt), &
               0.01_wp, "in contact", abs_tol=0.0_wp)
    p%graded = .true.
    call check(state, contact_max_step(p, free, [-0.15_wp, -1.0_wp], [1.0_wp, 0.0_wp], dt), &
               0.075_wp, "graded: half the time to contact", rel_tol=1.0e-14_wp)
    call check(state, contact_max_step(p, free, [-0.15_wp, -0.015_wp], [1.0_wp, 1.0_wp], dt), &
               0.01_wp, "graded: the nearest fender, not below dt_contact", abs_tol=0.0_wp)
    p%graded = .false.
    p%located = .true.
    call check(state, contact_max_step(p, free, [-0.15_wp, -1.0_wp], [1.0_wp, 0.0_wp], dt), &
               dt, "event: dt while free", abs_tol=0.0_wp)
    call check(state, contact_max_step(p, touching, [-0.5_wp, -1.0_wp], [0.0_wp, 0.0_wp], dt), &
               0.01_wp, "event: in contact", abs_tol=0.0_wp)
  end subroutine contact_steps

end module test_small_laws
