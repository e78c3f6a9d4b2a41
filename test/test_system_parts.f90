!> The system's parts as the narrow routines take them (davit_system_parameters,
!> davit_system_observables) and the deck's key sequences that two groups share
!> (davit_io_shared_keys): each against rigid-body kinematics, Hooke's law or the
!> documented defaults and ranges, with no system built around them.
module test_system_parts
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use harness, only: suite_type, new_case, case_state, check, check_true
  use davit_core_pose, only: pose_type
  use davit_core_layout, only: state_part_type
  use davit_rigging_elastic_sling, only: elastic_sling_type
  use davit_io_config, only: config_type, parse_config
  use davit_sweep_keys, only: sweep_config, parse_sweep
  use davit_system_parameters, only: nslings, hook_kinematics, ship_pose, falls_ends_type, &
                                     falls_ends_at
  use davit_system_observables, only: sling_tensions
  implicit none
  private
  public :: collect_system_parts

  real(wp), parameter :: half_pi = 2.0_wp*atan(1.0_wp)
  !> The deck's default hook points (boat frame) [m], fore and aft.
  real(wp), parameter :: hooks(3, nslings) = reshape([4.6_wp, 0.0_wp, -1.55_wp, &
                                                      -4.6_wp, 0.0_wp, -1.55_wp], [3, 2])

contains

  function collect_system_parts() result(suite)
    type(suite_type) :: suite
    suite%name = "system_parts"
    suite%cases = [new_case("hooks_move_with_the_boat_as_a_rigid_body", hooks_rigid), &
                   new_case("ship_pose_at_rest_or_from_its_state", ship_poses), &
                   new_case("foundation_slings_hooke_and_dashpot", slings_hooke), &
                   new_case("fore_aft_and_wire_keys_shared_by_two_groups", shared_keys), &
                   new_case("integrator_keys_shared_by_simulation_and_sweep", integrator_keys)]
  end function collect_system_parts

  !> Hook i at r + C p_i moving at C (v + omega x p_i) (eqs. 3-6; q(4:6) is the CG in body
  !> components), read from the boat's part wherever it sits in y.
  subroutine hooks_rigid(state)
    type(case_state), intent(inout) :: state
    type(state_part_type) :: boat
    type(falls_ends_type) :: ends
    type(pose_type) :: ship
    real(wp) :: y(14), pos(3, nslings), vel(3, nslings)
    boat%q = [3, 8]
    boat%u = [9, 14]
    y = -99.0_wp
    ! level boat, CG at (1, 2, 3), yawing at 1 rad/s and surging at 0.5 m/s
    y(3:8) = [0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 2.0_wp, 3.0_wp]
    y(9:14) = [0.0_wp, 0.0_wp, 1.0_wp, 0.5_wp, 0.0_wp, 0.0_wp]
    call hook_kinematics(boat, hooks, y, pos, vel)
    call close3(pos(:, 1), [5.6_wp, 2.0_wp, 1.45_wp], "level: fore hook at r + p")
    call close3(pos(:, 2), [-3.6_wp, 2.0_wp, 1.45_wp], "level: aft hook at r + p")
    call close3(vel(:, 1), [0.5_wp, 4.6_wp, 0.0_wp], "level: fore hook v + omega x p")
    call close3(vel(:, 2), [0.5_wp, -4.6_wp, 0.0_wp], "level: aft hook v + omega x p")
    ! yawed +90 deg (body x -> inertial y), CG at the origin, surging at 1 m/s
    y(3:8) = [0.0_wp, 0.0_wp, half_pi, 0.0_wp, 0.0_wp, 0.0_wp]
    y(9:14) = [0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp]
    call hook_kinematics(boat, hooks, y, pos, vel)
    call close3(pos(:, 1), [0.0_wp, 4.6_wp, -1.55_wp], "yawed: fore hook on +y")
    call close3(vel(:, 2), [0.0_wp, 1.0_wp, 0.0_wp], "yawed: surge along +y")
    ship = pose_type([7.0_wp, 8.0_wp, 9.0_wp], reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                     1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3]), 0.0_wp, 0.0_wp)
    ends = falls_ends_at(boat, hooks, ship, y)
    call close3(ends%hook_pos(:, 1), [0.0_wp, 4.6_wp, -1.55_wp], "falls' ends: the hooks")
    call close3(ends%ship%r, [7.0_wp, 8.0_wp, 9.0_wp], "falls' ends: the ship as given")
  contains
    subroutine close3(a, b, what)
      real(wp), intent(in) :: a(3), b(3)
      character(len=*), intent(in) :: what
      integer :: k
      do k = 1, 3
        call check(state, a(k), b(k), what, abs_tol=1.0e-12_wp)
      end do
    end subroutine close3
  end subroutine hooks_rigid

  !> At rest the deck's pose; moving, the CG from q(4:6) (inertial), velocity C u(4:6) and
  !> angular velocity C u(1:3): a yawed (+90 deg) ship surging at 2 m/s moves along +y.
  subroutine ship_poses(state)
    type(case_state), intent(inout) :: state
    type(state_part_type) :: part
    type(pose_type) :: rest, pose
    real(wp), parameter :: r_moving(3) = [10.0_wp, -5.0_wp, 0.0_wp], &
                           v_moving(3) = [0.0_wp, 2.0_wp, 0.0_wp], &
                           w_moving(3) = [0.0_wp, 0.0_wp, 0.1_wp]
    real(wp) :: y(12)
    integer :: k
    part%q = [1, 6]
    part%u = [7, 12]
    rest = pose_type([1.0_wp, 2.0_wp, 3.0_wp], reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                     1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3]), [0.5_wp, 0.0_wp, &
                     0.0_wp], 0.0_wp)
    y = [0.0_wp, 0.0_wp, half_pi, 10.0_wp, -5.0_wp, 0.0_wp, &
         0.0_wp, 0.0_wp, 0.1_wp, 2.0_wp, 0.0_wp, 0.0_wp]
    pose = ship_pose(.false., part, rest, y)
    call check_true(state, all(pose%r == rest%r) .and. all(pose%v == rest%v), &
                    "at rest: the deck's pose, whatever the state")
    pose = ship_pose(.true., part, rest, y)
    do k = 1, 3
      call check(state, pose%r(k), r_moving(k), "moving: CG from q(4:6)", abs_tol=1.0e-12_wp)
      call check(state, pose%v(k), v_moving(k), "moving: C u(4:6)", abs_tol=1.0e-12_wp)
      call check(state, pose%w(k), w_moving(k), "moving: C u(1:3)", abs_tol=1.0e-12_wp)
    end do
  end subroutine ship_poses

  !> Foundation slings straight above their hooks (z down): T = EA/l0 s + c ds/dt when
  !> taut, 0 when slack, and both 0 once detached. l0 = 3 m, EA = 1e6 N, c = 1e4 N s/m;
  !> the fore sling 1 cm stretched, the aft one 10 cm short; the boat sinking at 0.2 m/s.
  subroutine slings_hooke(state)
    type(case_state), intent(inout) :: state
    type(state_part_type) :: boat
    type(elastic_sling_type) :: slings(nslings)
    real(wp) :: y(12), t(nslings)
    boat%q = [1, 6]
    boat%u = [7, 12]
    y = 0.0_wp
    y(12) = 0.2_wp
    slings(1) = elastic_sling_type(hooks(:, 1) - [0.0_wp, 0.0_wp, 3.01_wp], 3.0_wp, 1.0e6_wp, &
                                   1.0e4_wp)
    slings(2) = elastic_sling_type(hooks(:, 2) - [0.0_wp, 0.0_wp, 2.9_wp], 3.0_wp, 1.0e6_wp, &
                                   1.0e4_wp)
    t = sling_tensions(.true., slings, boat, hooks, y)
    call check(state, t(1), 1.0e6_wp/3.0_wp*0.01_wp + 1.0e4_wp*0.2_wp, &
               "taut: k s + c v = 5333.3 N", rel_tol=1.0e-9_wp)
    call check(state, t(2), 0.0_wp, "slack: no tension", abs_tol=0.0_wp)
    t = sling_tensions(.false., slings, boat, hooks, y)
    call check_true(state, all(t == 0.0_wp), "detached: no tension")
  end subroutine slings_hooke

  !> &slings hook_/anchor_ and &rigging head_ pairs, and both groups' wire diameter and
  !> Young's modulus: the documented defaults (the paper's III.B geometry, 20 mm, 200 GPa),
  !> a deck's value read into its own side only, and the same ranges refused in each group
  !> with file, line, group, key and range.
  subroutine shared_keys(state)
    type(case_state), intent(inout) :: state
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    call parse_config("t.nml", "", cfg, error)
    call check_true(state, .not. allocated(error), "empty deck accepted")
    if (allocated(error)) return
    call check_true(state, all(cfg%slings%hook_fore == [4.6_wp, 0.0_wp, -1.55_wp]) .and. &
                    all(cfg%slings%hook_aft == [-4.6_wp, 0.0_wp, -1.55_wp]), "hooks' defaults")
    call check_true(state, all(cfg%slings%anchor_fore == [4.6_wp, 13.3_wp, -19.55_wp]) .and. &
                    all(cfg%slings%anchor_aft == [-4.6_wp, 13.3_wp, -19.55_wp]), &
                    "anchors' defaults")
    call check_true(state, all(cfg%rigging%head_fore == [4.6_wp, 13.3_wp, -20.55_wp]) .and. &
                    all(cfg%rigging%head_aft == [-4.6_wp, 13.3_wp, -20.55_wp]), &
                    "davit heads' defaults")
    call check_true(state, cfg%slings%diameter == 0.02_wp .and. &
                    cfg%rigging%wire_diameter == 0.02_wp .and. &
                    cfg%slings%youngs_modulus == 200.0e9_wp .and. &
                    cfg%rigging%youngs_modulus == 200.0e9_wp, "wires' defaults")
    call parse_config("t.nml", "&rigging head_aft = -4.0, 12.0, -20.0 /", cfg, error)
    call check_true(state, .not. allocated(error), "head_aft accepted")
    if (allocated(error)) return
    call check_true(state, all(cfg%rigging%head_aft == [-4.0_wp, 12.0_wp, -20.0_wp]) .and. &
                    all(cfg%rigging%head_fore == [4.6_wp, 13.3_wp, -20.55_wp]), &
                    "head_aft read, head_fore kept")
    call refused("&rigging wire_diameter = 0.6 /", "t.nml:1: &rigging: wire_diameter = 0.6: "// &
                 "out of range; allowed: 0 < wire_diameter <= 0.5 [m]")
    call refused("&slings diameter = 0.0 /", "t.nml:1: &slings: diameter = 0.0: out of "// &
                 "range; allowed: 0 < diameter <= 0.5 [m]")
    call refused("&slings youngs_modulus = 1.0e13 /", "t.nml:1: &slings: youngs_modulus = "// &
                 "1.0e13: out of range; allowed: 1e6 <= youngs_modulus <= 1e12 [Pa]")
    call refused("&rigging head_aft = -4.6, 13.3, -2000.0 /", "t.nml:1: &rigging: head_aft "// &
                 "= -4.6, 13.3, -2000.0: out of range; allowed: -1000 <= head_aft <= 1000 "// &
                 "(3 values) [m]")
    call refused("&slings hook_fore = 4.6, 0.0, -60.0 /", "t.nml:1: &slings: hook_fore = "// &
                 "4.6, 0.0, -60.0: out of range; allowed: -50 <= hook_fore <= 50 (3 values) [m]")
  contains
    subroutine refused(text, message)
      character(len=*), intent(in) :: text, message
      type(config_type) :: bad
      type(error_type), allocatable :: err
      call parse_config("t.nml", text, bad, err)
      call check_true(state, allocated(err), text//" refused")
      if (allocated(err)) call check_true(state, index(err%message, message) > 0, &
                                          "message: "//err%message)
    end subroutine refused
  end subroutine shared_keys

  !> &simulation and &sweep read integrator and substeps through one routine: the same
  !> eight choices (rk4, dopri5, rosenbrock, rosw, multirate, multirate2, mri2, mri2b) and
  !> the same range 1..10000, refused with each group's name; the defaults rk4 and 10.
  subroutine integrator_keys(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: choices = "allowed: one of 'rk4' 'dopri5' 'rosenbrock' "// &
      "'rosw' 'multirate' 'multirate2' 'mri2' 'mri2b'"
    type(config_type) :: cfg
    type(sweep_config) :: sweep
    type(error_type), allocatable :: error
    call parse_config("t.nml", "", cfg, error)
    call check_true(state, .not. allocated(error), "empty deck accepted")
    if (allocated(error)) return
    call check_true(state, cfg%simulation%integrator == "rk4" .and. &
                    cfg%simulation%substeps == 10, "defaults: rk4, 10 substeps")
    call parse_config("t.nml", "&simulation integrator = 'mri2b', substeps = 10000 /", cfg, &
                      error)
    call check_true(state, .not. allocated(error), "mri2b and 10000 substeps accepted")
    if (.not. allocated(error)) call check_true(state, cfg%simulation%integrator == "mri2b" &
                                                .and. cfg%simulation%substeps == 10000, &
                                                "mri2b, 10000 read")
    call parse_config("t.nml", "&simulation integrator = 'euler' /", cfg, error)
    call expect("&simulation integrator = 'euler'", "t.nml:1: &simulation: integrator = "// &
                "'euler': unknown choice; "//choices)
    call parse_config("t.nml", "&simulation substeps = 0 /", cfg, error)
    call expect("&simulation substeps = 0", "t.nml:1: &simulation: substeps = 0: out of "// &
                "range; allowed: 1 <= substeps <= 10000 (integer)")
    call parse_sweep("s.nml", "&sweep base_deck = 'none.nml', integrator = 'euler' /", sweep, &
                     error)
    call expect("&sweep integrator = 'euler'", "s.nml:1: &sweep: integrator = 'euler': "// &
                "unknown choice; "//choices)
    call parse_sweep("s.nml", "&sweep base_deck = 'none.nml', substeps = 10001 /", sweep, error)
    call expect("&sweep substeps = 10001", "s.nml:1: &sweep: substeps = 10001: out of range; "// &
                "allowed: 1 <= substeps <= 10000 (integer)")
  contains
    subroutine expect(what, message)
      character(len=*), intent(in) :: what, message
      call check_true(state, allocated(error), what//" refused")
      if (allocated(error)) call check_true(state, index(error%message, message) > 0, &
                                            "message: "//error%message)
    end subroutine expect
  end subroutine integrator_keys

end module test_system_parts
