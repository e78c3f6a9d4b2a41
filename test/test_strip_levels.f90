!> The strips' levels of detail as extensions of strip_level_type (davit_boat_strip_level):
!> the factory builds each from `&boat water_model`, and each level's roll stiffness in
!> calm water against its closed form, so that a changed coefficient or sign in either
!> level fails: the paper level's metacentric moment (eq. 24, corrected: restoring), the
!> pressure level's integrated pressure on wall-sided sections (the wall-sided formula).
module test_strip_levels
  use davit_kinds, only: wp, gravity, rho_water
  use davit_io_config, only: boat_config
  use davit_core_rotation, only: rotation_matrix
  use davit_sea_wave_field, only: wave_field_type, new_calm_sea
  use davit_boat_hull, only: boat_hull_type, new_boat_hull
  use davit_boat_strip_level, only: strip_level_type, paper_strip_level_type, &
                                    pressure_strip_level_type
  use davit_boat_strip_loads, only: strip_model_type, new_strip_model, strip_loads
  use davit_system_law_factory, only: new_strip_level
  use harness, only: suite_type, case_state, new_case, check, check_true, note
  implicit none
  private
  public :: collect_strip_levels

  !> The test hull: 11.5 x 2.8 x 3.1 m, CG 1.1 m above the keel, 20 rectangular sections
  !> (breadth b_k = 2.8 (1 - |2 x_k / L|^4.3)), 8 t.
  real(wp), parameter :: mass = 8000.0_wp, keel = 1.1_wp
  !> The paper's metacentric height h_m [m].
  real(wp), parameter :: h_paper = 2.0_wp

contains

  function collect_strip_levels() result(suite)
    type(suite_type) :: suite
    suite%name = "strip_levels"
    suite%cases = [new_case("factory_builds_each_level_from_water_model", factory_levels), &
                   new_case("paper_level_roll_moment_is_eq_24", paper_roll), &
                   new_case("pressure_level_roll_moment_is_wall_sided", pressure_roll)]
  end function collect_strip_levels

  !> 'paper' gives the paper's strips; 'pressure', and 'bem' (whose strips serve the
  !> surface watch), the pressure-integrated sections.
  subroutine factory_levels(state)
    type(case_state), intent(inout) :: state
    call check_true(state, is_paper(level_of("paper")), "paper -> paper_strip_level_type")
    call check_true(state, is_pressure(level_of("pressure")), &
                    "pressure -> pressure_strip_level_type")
    call check_true(state, is_pressure(level_of("bem")), "bem -> pressure_strip_level_type")
  end subroutine factory_levels

  !> The paper level (h_m = 2 m) heeled by phi = 0.1 rad about its waterline centre in calm
  !> water, no drag or damping: the buoyancy acts on the centreline, so the roll moment is
  !> eq. 24's T1 = -rho g h_m sin(phi) V alone, V = m / rho (the heel keeps the volume of
  !> wall-sided sections while the bottom stays wet: tan(phi) b/2 = 0.14 m < T_0).
  subroutine paper_roll(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: phi = 0.1_wp
    real(wp) :: f(6), volume
    call heeled_loads(level_of("paper"), .true., phi, f, volume)
    call check(state, volume, mass/rho_water, "volume kept by the heel", rel_tol=1e-12_wp)
    call check(state, f(1), -rho_water*gravity*h_paper*sin(phi)*mass/rho_water, &
               "T1 = -rho g h_m sin(phi) V", rel_tol=1e-12_wp)
    call note(state, "paper roll moment at 0.1 rad [N m]", f(1))
  end subroutine paper_roll

  !> The pressure level (the hull's own GM_T) heeled as above by 0.05 and 0.1 rad: the
  !> pressure on wall-sided sections gives the wall-sided formula
  !> M = -rho g V sin(phi) (GM_T + BM tan(phi)^2 / 2), with the test's own hand arithmetic:
  !> T_0 = V / A_wp, A_wp = sum b_k t_s, BM = I_T / V, I_T = sum b_k^3 t_s / 12,
  !> GM_T = T_0 / 2 + BM - KG (KG = 1.1 m above the keel).
  subroutine pressure_roll(state)
    type(case_state), intent(inout) :: state
    type(boat_hull_type) :: hull
    real(wp) :: f(6), volume, v0, t0, bm, gm, phi
    integer :: j
    hull = test_hull()
    v0 = mass/rho_water
    t0 = v0/(sum(hull%breadth)*hull%thickness)
    bm = sum(hull%breadth**3)*hull%thickness/12.0_wp/v0
    gm = 0.5_wp*t0 + bm - keel
    call note(state, "hand GM_T [m]", gm)
    do j = 1, 2
      phi = 0.05_wp*j
      call heeled_loads(level_of("pressure"), .false., phi, f, volume)
      call check(state, volume, v0, "volume kept by the heel", rel_tol=1e-12_wp)
      call check(state, f(1), -rho_water*gravity*v0*sin(phi)*(gm + 0.5_wp*bm*tan(phi)**2), &
                 "wall-sided roll moment", rel_tol=1e-10_wp)
    end do
  end subroutine pressure_roll

  !> The strip loads of the test hull at level `level` (roll stiffness h_m with paper_roll)
  !> heeled by phi about b1, its centreline waterline point on the calm surface: the CG
  !> (KG - T_0) above it, z down.
  subroutine heeled_loads(level, paper_roll, phi, f, volume)
    class(strip_level_type), intent(in) :: level
    logical, intent(in) :: paper_roll
    real(wp), intent(in) :: phi
    real(wp), intent(out) :: f(6), volume
    type(strip_model_type) :: s
    type(wave_field_type) :: calm
    type(boat_hull_type) :: hull
    real(wp) :: t0, c(3, 3)
    hull = test_hull()
    s = new_strip_model(hull, [0.0_wp, 0.0_wp, 0.0_wp], h_paper, [0.0_wp, 0.0_wp, 0.0_wp], &
                        mass, [1.0e4_wp, 5.0e4_wp, 5.0e4_wp], level, paper_roll)
    call new_calm_sea(calm)
    t0 = mass/rho_water/(sum(hull%breadth)*hull%thickness)
    c = rotation_matrix([phi, 0.0_wp, 0.0_wp])
    ! the centreline point (0, 0, KG - T_0) of the body at the origin
    call strip_loads(s, calm, 0.0_wp, c, -(keel - t0)*c(:, 3), &
                     [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], f, volume)
  end subroutine heeled_loads

  function test_hull() result(hull)
    type(boat_hull_type) :: hull
    hull = new_boat_hull(11.5_wp, 2.8_wp, 3.1_wp, keel, 4.3_wp, 20)
  end function test_hull

  !> The factory's level for `&boat water_model = name`.
  function level_of(name) result(level)
    character(len=*), intent(in) :: name
    class(strip_level_type), allocatable :: level
    type(boat_config) :: b
    b%water_model = name
    call new_strip_level(b, level)
  end function level_of

  logical function is_paper(level)
    class(strip_level_type), intent(in) :: level
    is_paper = .false.
    select type (level)
    type is (paper_strip_level_type)
      is_paper = .true.
    end select
  end function is_paper

  logical function is_pressure(level)
    class(strip_level_type), intent(in) :: level
    is_pressure = .false.
    select type (level)
    type is (pressure_strip_level_type)
      is_pressure = .true.
    end select
  end function is_pressure

end module test_strip_levels
