!> The scenes as types (davit_run_scene): the factory builds each scene from its name and
!> refuses an unknown one with the allowed list; each scene answers what differs (boat,
!> davit, moving ship, wind) as the deck's documentation of &simulation scene states; the
!> boat scenes build the system those answers describe, and the scenes without a boat
!> refuse to.
module test_scene
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type
  use davit_system_model, only: system_type
  use davit_solve_integrator, only: ode_problem
  use davit_run_scene, only: scene_type, new_scene, scene_names
  use system_fixture, only: deck_config, nstate
  use harness, only: suite_type, case_state, new_case, check_true
  implicit none
  private
  public :: collect_scene

contains

  function collect_scene() result(suite)
    type(suite_type) :: suite
    suite%name = "scene"
    suite%cases = [new_case("scene_factory_names_and_answers", factory_answers), &
                   new_case("scene_factory_refuses_unknown_name", unknown_name), &
                   new_case("scene_builds_the_system_it_describes", builds_system), &
                   new_case("scene_without_boat_refuses_boat_and_sea_modes", no_boat)]
  end function collect_scene

  !> &simulation scene: 'hanging_boat' (two slings from fixed points), 'lowering' (the
  !> full rigging from the davit of the ship at rest), 'launch' (the same from the moving
  !> 6-DOF ship), 'sea' (the wave field alone), 'ship' (the ship alone in sea and wind).
  subroutine factory_answers(state)
    type(case_state), intent(inout) :: state
    character(len=12), parameter :: names(5) = [character(len=12) :: "hanging_boat", &
                                                "lowering", "launch", "sea", "ship"]
    ! has_boat, on_davit, carries_ship, feels_wind for each name above
    logical, parameter :: expected(4, 5) = reshape([ &
      .true., .false., .false., .true., &
      .true., .true., .false., .true., &
      .true., .true., .true., .true., &
      .false., .false., .false., .false., &
      .false., .false., .false., .true.], [4, 5])
    class(scene_type), allocatable :: scene
    type(error_type), allocatable :: error
    integer :: i
    call check_true(state, size(scene_names) == size(names) .and. &
                    all(scene_names == names), "the factory's list is the deck's five scenes")
    do i = 1, size(names)
      call new_scene(trim(names(i)), scene, error)
      call check_true(state, .not. allocated(error) .and. allocated(scene), &
                      trim(names(i))//" is built")
      if (.not. allocated(scene)) cycle
      call check_true(state, scene%has_boat() .eqv. expected(1, i), trim(names(i))//": boat")
      call check_true(state, scene%on_davit() .eqv. expected(2, i), trim(names(i))//": davit")
      call check_true(state, scene%carries_ship() .eqv. expected(3, i), &
                      trim(names(i))//": moving ship")
      call check_true(state, scene%feels_wind() .eqv. expected(4, i), trim(names(i))//": wind")
    end do
  end subroutine factory_answers

  subroutine unknown_name(state)
    type(case_state), intent(inout) :: state
    class(scene_type), allocatable :: scene
    type(error_type), allocatable :: error
    integer :: i
    call new_scene("hanging", scene, error)
    call check_true(state, allocated(error), "'hanging' is refused")
    call check_true(state, .not. allocated(scene), "and no scene is built")
    if (.not. allocated(error)) return
    call check_true(state, index(error%message, "&simulation scene = 'hanging'") > 0, &
                    "the message names the key and the value: "//error%message)
    do i = 1, size(scene_names)
      call check_true(state, index(error%message, trim(scene_names(i))) > 0, &
                      "the message lists '"//trim(scene_names(i))//"'")
    end do
  end subroutine unknown_name

  !> With the paper's strips (no states of their own), the hanging boat's state is the
  !> boat's alone (eqs. 3-4: 6 coordinates, 6 speeds); the lowering adds the rigging's
  !> states (eqs. 47-82); the launch adds the ship's on top (6 + 6, and the integrals of
  !> its surge, sway and yaw keeping).
  subroutine builds_system(state)
    type(case_state), intent(inout) :: state
    character(len=*), parameter :: rest = ", dt = 1.0e-3, output_interval = 0.1 / "// &
      "&wind speed = 0.0 / &sea wave_type = 'calm' / &boat water_model = 'paper' /"
    type(system_type) :: sys
    real(wp), allocatable :: y(:)
    integer :: n_lowering
    call build("hanging_boat", sys, y)
    call check_true(state, size(y) == nstate, "hanging boat: the boat's 12 states")
    call check_true(state, .not. sys%par%on_davit .and. .not. sys%par%with_ship, &
                    "hanging boat: on slings, no moving ship")
    call build("lowering", sys, y)
    n_lowering = size(y)
    call check_true(state, n_lowering > nstate, "lowering: the rigging's states added")
    call check_true(state, sys%par%on_davit .and. .not. sys%par%with_ship, &
                    "lowering: on the davit, ship at rest")
    call build("launch", sys, y)
    call check_true(state, size(y) == n_lowering + 15, "launch: the ship's 6 coordinates, "// &
                    "6 speeds and its station and heading keeping's 3 integrals added")
    call check_true(state, sys%par%on_davit .and. sys%par%with_ship, &
                    "launch: on the davit, ship moving")
  contains
    subroutine build(name, sys, y)
      character(len=*), intent(in) :: name
      type(system_type), intent(out) :: sys
      real(wp), allocatable, intent(out) :: y(:)
      class(scene_type), allocatable :: scene
      type(error_type), allocatable :: error
      type(config_type) :: cfg
      cfg = deck_config("&simulation scene = '"//name//"'"//rest)
      call new_scene(name, scene, error)
      if (.not. allocated(error)) call scene%build_boat(cfg, sys, y, error)
      call check_true(state, .not. allocated(error), name//" builds")
      if (allocated(error)) allocate (y(0))
    end subroutine build
  end subroutine builds_system

  subroutine no_boat(state)
    type(case_state), intent(inout) :: state
    class(scene_type), allocatable :: scene
    type(error_type), allocatable :: error
    type(system_type) :: sys
    type(config_type) :: cfg
    real(wp), allocatable :: y(:)
    class(ode_problem), allocatable :: problem
    cfg = deck_config("&simulation scene = 'sea', dt = 0.01, t_end = 1.0 /")
    call new_scene("sea", scene, error)
    if (allocated(error)) error stop "test scene: "//error%message
    call scene%build_boat(cfg, sys, y, error)
    call check_true(state, allocated(error), "the sea builds no boat")
    if (allocated(error)) call check_true(state, index(error%message, "has no boat") > 0, &
                                          "and says so: "//error%message)
    deallocate (error)
    call scene%start_problem(cfg, problem, y, error)
    call check_true(state, allocated(error), "the sea has no dynamics to linearise")
    if (allocated(error)) call check_true(state, index(error%message, "no dynamics") > 0, &
                                          "and says so: "//error%message)
  end subroutine no_boat

end module test_scene
