!> Tests build launch systems from decks they trust: new_system and initial_state in one
!> call, stopping the test program on an error (a broken fixture, not a failed check).
module system_fixture
  use davit_kinds, only: wp
  use davit_error, only: error_type
  use davit_io_config, only: config_type, parse_config
  use davit_system_model, only: system_type
  use davit_run_scene, only: new_boat_system
  use davit_solve_rk4, only: rk4_type
  use davit_core_rotation, only: rotation_matrix
  use davit_boat_contact, only: hertz_law_type, hertz_peak
  use davit_ship_ship_model, only: ship_system_type
  use davit_ship_ship_hydro, only: bem_hydro_type
  use davit_ship_manoeuvring, only: mmg_manoeuvring_type
  use davit_ship_bem_loads, only: bem_ship_type
  use davit_boat_water_terms, only: bem_terms_type
  use davit_boat_bem_water, only: boat_bem_type
  implicit none
  private
  public :: new_test_system, nstate, deck_config, drop_cg, system_hertz_peak
  public :: ship_bem, is_bem_ship, boat_bem, is_mmg_ship, ship_rps

  !> State length of a boat on foundation slings (the boat's part alone, eqs. 3-4).
  integer, parameter :: nstate = 12

contains

  function new_test_system(sys, cfg) result(y)
    type(system_type), intent(out) :: sys
    type(config_type), intent(in) :: cfg
    real(wp), allocatable :: y(:)
    type(error_type), allocatable :: error
    call new_boat_system(cfg, sys, y, error)
    if (allocated(error)) error stop "test system: "//error%message
  end function new_test_system

  !> The configuration of a deck given as text (file name "test.nml" in its messages).
  function deck_config(text) result(cfg)
    character(len=*), intent(in) :: text
    type(config_type) :: cfg
    type(error_type), allocatable :: error
    call parse_config("test.nml", text, cfg, error)
    if (allocated(error)) error stop "test deck rejected: "//error%message
  end function deck_config

  !> The boat's inertial CG after n RK4 steps of dt from t = 0, the after-step hook run at
  !> the start and after every step (as the driver does).
  function drop_cg(sys, y, n, dt) result(cg)
    type(system_type), intent(inout) :: sys
    real(wp), intent(inout) :: y(:)
    integer, intent(in) :: n
    real(wp), intent(in) :: dt
    real(wp) :: cg(3), t
    type(rk4_type) :: rk4
    integer :: i
    call rk4%init(size(y))
    t = 0.0_wp
    call sys%after_step(t, y)
    do i = 1, n
      call rk4%step(sys, t, y, dt)
      call sys%after_step(t, y)
    end do
    cg = matmul(rotation_matrix(y(1:3)), y(4:6))
  end function drop_cg

  !> Hertz impact peak (hertz_peak) of the system's fender law; a law that is not a Hertz
  !> law gives huge values, so that a check against them fails.
  subroutine system_hertz_peak(sys, mass, v0, delta_m, f_m)
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: mass, v0
    real(wp), intent(out) :: delta_m, f_m
    delta_m = huge(1.0_wp)
    f_m = huge(1.0_wp)
    select type (law => sys%par%fenders%law)
    class is (hertz_law_type)
      call hertz_peak(law, mass, v0, delta_m, f_m)
    end select
  end subroutine system_hertz_peak


  !> The BEM ship's database, mass and damping (empty for the box ship).
  function ship_bem(ship) result(bem)
    !> The ship.
    type(ship_system_type), intent(in) :: ship
    type(bem_ship_type) :: bem
    select type (h => ship%par%hydro)
    type is (bem_hydro_type)
      bem = h%bem
    end select
  end function ship_bem

  !> Whether the ship's hydrodynamics are the BEM ship's.
  logical function is_bem_ship(ship)
    !> The ship.
    type(ship_system_type), intent(in) :: ship
    is_bem_ship = same_type_as(ship%par%hydro, bem_hydro_type())
  end function is_bem_ship

  !> The boat's BEM water model (empty with the strips alone).
  function boat_bem(sys) result(bem)
    !> The system.
    type(system_type), intent(in) :: sys
    type(boat_bem_type) :: bem
    select type (w => sys%par%water_terms)
    type is (bem_terms_type)
      bem = w%bem
    end select
  end function boat_bem

  !> Whether the ship manoeuvres by the MMG model.
  logical function is_mmg_ship(ship)
    !> The ship.
    type(ship_system_type), intent(in) :: ship
    is_mmg_ship = same_type_as(ship%par%manoeuvring, mmg_manoeuvring_type())
  end function is_mmg_ship

  !> The MMG ship's propeller revolutions [1/s] (0 for Kijima's model).
  real(wp) function ship_rps(ship)
    !> The ship.
    type(ship_system_type), intent(in) :: ship
    ship_rps = 0.0_wp
    select type (m => ship%par%manoeuvring)
    type is (mmg_manoeuvring_type)
      ship_rps = m%rps
    end select
  end function ship_rps

end module system_fixture
