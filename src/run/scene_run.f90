!> How the boat and ship scenes are run (the `run` bindings of davit_run_scene; the sea's
!> is in davit_run_sea_run): a submodule, because the time loop it calls
!> (davit_run_driver) writes the run's scenario, which asks the scene.
submodule (davit_run_scene) davit_run_scene_run
  use davit_run_driver, only: integrate_scene
  use davit_run_recorders, only: boat_recorder, ship_recorder
  use davit_run_launch_log, only: launch_log, new_launch_log
  implicit none

contains

  module procedure boat_run
    type(system_type) :: boat
    type(boat_recorder) :: brec
    type(launch_log) :: log
    real(wp), allocatable :: y(:)
    call self%build_boat(cfg, boat, y, error)
    if (allocated(error)) return
    log = new_launch_log(cfg, boat)
    call integrate_scene(cfg, boat, y, brec, out_path, summary, error, log, progress)
    if (.not. allocated(error)) summary%report = log%report(boat)
  end procedure boat_run

  module procedure ship_run
    type(ship_system_type) :: ship
    type(ship_recorder) :: srec
    real(wp), allocatable :: y(:)
    call build_ship_scene(cfg, ship, y, error)
    if (allocated(error)) return
    call integrate_scene(cfg, ship, y, srec, out_path, summary, error, progress=progress)
  end procedure ship_run

end submodule davit_run_scene_run
