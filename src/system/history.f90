!> What changes only between steps: the fenders' contact phases, the launch's events and
!> the slow caches of the water at the boat. The after-step hook (davit_system_events) is
!> the only writer; the right-hand side reads it as fixed for the step.
module davit_system_history
  use davit_kinds, only: wp
  use davit_core_pose, only: pose_type
  use davit_boat_contact_law, only: fender_state_type
  use davit_boat_surface_watch, only: surface_watch_type
  use davit_boat_strip_waves, only: strip_wave_cache_type
  use davit_boat_bem_water, only: diffraction_cache_type
  use davit_system_parameters, only: nslings
  use davit_sea_wave_grid, only: wave_grid_type
  implicit none
  private
  public :: system_history_type

  !> The launch's history.
  type :: system_history_type
    !> Each fender's contact phase and its records (davit_boat_contact_law), one per fender.
    type(fender_state_type), allocatable :: fender_states(:)
    !> Time of the first fender contact [s]; negative while there has been none.
    real(wp) :: first_contact_time = -1.0_wp
    !> Events on the davit (review G24) [s], negative until they happen: waterborne (the
    !> buoyancy carries the weight, or the hooks carry < 1 % of it, for 1 s; the time the
    !> condition began) and hook release; after release the falls no longer act on the
    !> boat and their states are frozen.
    real(wp) :: waterborne_time = -1.0_wp, release_time = -1.0_wp, afloat_since = -1.0_wp
    !> Where the hooks were when they let go [m] (inertial, one column per sling).
    real(wp) :: released_hooks(3, nslings) = 0.0_wp
    !> The ship's pose when the hooks let go (inertial).
    type(pose_type) :: released_pose
    !> Skips the strip loads while the hull is provably out of the water (exact).
    type(surface_watch_type) :: watch
    !> Slow clock of the water at the strips (`&simulation wave_update`, irregular seas).
    type(strip_wave_cache_type) :: waves
    !> The BEM water model's diffraction load on the same clock (irregular seas).
    type(diffraction_cache_type) :: diffraction
    !> `&sea kinematics = 'grid'`: the elevation around the boat (the watch's and strips'
    !> samples) and, while the hull may be wet, the water velocity at depth.
    type(wave_grid_type) :: surface_grid, volume_grid
  end type system_history_type

end module davit_system_history
