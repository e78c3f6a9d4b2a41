!> The scene (&simulation scene) as a type, chosen once by its name in `new_scene` (the one
!> place besides the deck reader that reads the name): the boat scenes ('hanging_boat',
!> 'lowering' on the davit, 'launch' from the moving ship) are one family that differs
!> only in what the boat hangs from and whether the ship moves; 'ship' is the ship alone
!> and 'sea' the wave field alone. Callers ask the bindings what differs: whether there is
!> a boat, whether it hangs on the davit's rigging, whether the 6-DOF ship moves with it,
!> whether wind acts, what the run holds in memory, how it is run and linearised. How a
!> scene is run (`run`) is in the submodules davit_run_scene_run (src/run/scene_run.f90)
!> and davit_run_sea_run (src/run/sea_run.f90), because the time loop it calls writes the
!> scenario, which asks the scene.
module davit_run_scene
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: config_type
  use davit_io_text, only: join_text
  use davit_solve_integrator, only: ode_problem
  use davit_system_model, only: system_type
  use davit_system_build, only: new_system, initial_state
  use davit_ship_ship_model, only: ship_system_type
  use davit_run_ship_scene, only: build_ship_scene
  use davit_run_run_summary, only: run_summary
  use davit_run_progress, only: progress_meter
  implicit none
  private
  public :: scene_type, new_scene, scene_names, new_boat_system

  !> The scenes' names, as &simulation scene gives them.
  character(len=*), parameter :: scene_names(5) = [character(len=12) :: "hanging_boat", &
                                                   "lowering", "launch", "sea", "ship"]

  !> The seat trace's grid interval [s] (davit_run_seat_trace).
  real(wp), parameter :: seat_dt = 1.0e-3_wp
  !> Bytes per wave component beyond the sea's own tables, measured (peak resident set over
  !> the component count, 3e5 and 1.8e6 components): the boat's BEM diffraction table
  !> interpolated per component and the ship's Froude-Krylov tables (2600 B), the ship's
  !> tables alone (200 B).
  real(wp), parameter :: bytes_component_boat = 2600.0_wp, bytes_component_ship = 200.0_wp
  real(wp), parameter :: bytes_component_sea = 12.0_wp*8.0_wp

  !> A scene: what a run simulates. The defaults are those of a scene without a boat, in
  !> the wind.
  type, abstract :: scene_type
  contains
    !> Whether the scene has the lifeboat (the launch system of davit_system_build).
    procedure :: has_boat => answer_no
    !> Whether the boat hangs on the davit's full rigging (else on the foundation slings).
    procedure :: on_davit => answer_no
    !> Whether the 6-DOF ship moves in the sea with the boat (else it stays in its pose).
    procedure :: carries_ship => answer_no
    !> Whether the wind acts on the scene's bodies.
    procedure :: feels_wind => answer_yes
    !> The boat's system and initial state (an error for a scene without a boat).
    procedure :: build_boat
    !> Memory the run holds [bytes]: recorded samples, seat trace, wave components.
    procedure(memory_interface), deferred :: memory_parts
    !> The scene's system and its state at t = 0, what `davit modes` linearises (an error
    !> for a scene without dynamics).
    procedure :: start_problem => no_problem
    !> Run the scene and write its output file.
    procedure(run_interface), deferred :: run
  end type scene_type

  !> The boat scenes' family; as itself, the boat hanging on its two slings from fixed
  !> points ('hanging_boat').
  type, extends(scene_type) :: boat_scene_type
  contains
    procedure :: has_boat => boat_has_boat
    procedure :: memory_parts => boat_memory
    procedure :: start_problem => boat_problem
    procedure :: run => boat_run
  end type boat_scene_type

  !> The boat on the davit's rigging from the ship at rest in its pose ('lowering').
  type, extends(boat_scene_type) :: lowering_scene_type
  contains
    procedure :: on_davit => lowering_on_davit
  end type lowering_scene_type

  !> The same from the 6-DOF ship moving in the sea and wind ('launch').
  type, extends(lowering_scene_type) :: launch_scene_type
  contains
    procedure :: carries_ship => launch_carries_ship
  end type launch_scene_type

  !> The ship alone in its sea and wind ('ship': free decay and RAO runs).
  type, extends(scene_type) :: ship_scene_type
  contains
    procedure :: memory_parts => ship_memory
    procedure :: start_problem => ship_problem
    procedure :: run => ship_run
  end type ship_scene_type

  !> The wave field alone, recorded at the &sea probes ('sea').
  type, extends(scene_type) :: sea_scene_type
  contains
    procedure :: feels_wind => sea_feels_wind
    procedure :: memory_parts => sea_memory
    procedure :: run => sea_run
  end type sea_scene_type

  abstract interface
    !> (recorded samples, seat trace, wave components) [bytes].
    pure function memory_interface(self, cfg, samples, n_comp) result(parts)
      import :: scene_type, config_type, wp
      !> The scene.
      class(scene_type), intent(in) :: self
      !> The run's configuration.
      type(config_type), intent(in) :: cfg
      !> Samples recorded; wave components realised.
      real(wp), intent(in) :: samples, n_comp
      real(wp) :: parts(3)
    end function memory_interface

    !> Run the scene and write `out_path`.
    subroutine run_interface(self, cfg, out_path, summary, error, progress)
      import :: scene_type, config_type, run_summary, error_type, progress_meter
      !> The scene.
      class(scene_type), intent(in) :: self
      !> The checked configuration of the run.
      type(config_type), intent(in) :: cfg
      !> Path of the HDF5 file written.
      character(len=*), intent(in) :: out_path
      !> Steps, evaluations, wall time and completion of the run.
      type(run_summary), intent(out) :: summary
      !> Set when the run cannot be set up, its file not written or it diverged.
      type(error_type), allocatable, intent(out) :: error
      !> Progress line at a terminal (absent: none).
      type(progress_meter), intent(inout), optional :: progress
    end subroutine run_interface
  end interface

  interface
    !> The boat scenes: build the boat's system, integrate it into the boat recorder under
    !> the launch log, and report the launch.
    module subroutine boat_run(self, cfg, out_path, summary, error, progress)
      !> The scene.
      class(boat_scene_type), intent(in) :: self
      !> The checked configuration of the run.
      type(config_type), intent(in) :: cfg
      !> Path of the HDF5 file written.
      character(len=*), intent(in) :: out_path
      !> Steps, evaluations, wall time, completion and the launch's report.
      type(run_summary), intent(out) :: summary
      !> Set when the run cannot be set up, its file not written or it diverged.
      type(error_type), allocatable, intent(out) :: error
      !> Progress line at a terminal (absent: none).
      type(progress_meter), intent(inout), optional :: progress
    end subroutine boat_run

    !> The ship alone, integrated into the ship recorder.
    module subroutine ship_run(self, cfg, out_path, summary, error, progress)
      !> The scene.
      class(ship_scene_type), intent(in) :: self
      !> The checked configuration of the run.
      type(config_type), intent(in) :: cfg
      !> Path of the HDF5 file written.
      character(len=*), intent(in) :: out_path
      !> Steps, evaluations, wall time and completion of the run.
      type(run_summary), intent(out) :: summary
      !> Set when the run cannot be set up, its file not written or it diverged.
      type(error_type), allocatable, intent(out) :: error
      !> Progress line at a terminal (absent: none).
      type(progress_meter), intent(inout), optional :: progress
    end subroutine ship_run

    !> The wave field alone at the probes (no time loop).
    module subroutine sea_run(self, cfg, out_path, summary, error, progress)
      !> The scene.
      class(sea_scene_type), intent(in) :: self
      !> The checked configuration of the run.
      type(config_type), intent(in) :: cfg
      !> Path of the HDF5 file written.
      character(len=*), intent(in) :: out_path
      !> Wall time and completion of the run.
      type(run_summary), intent(out) :: summary
      !> Set when the sea cannot be built or the file not written.
      type(error_type), allocatable, intent(out) :: error
      !> Progress line at a terminal (unused: the sea has no time loop).
      type(progress_meter), intent(inout), optional :: progress
    end subroutine sea_run
  end interface

contains

  !> The scene named `name` (&simulation scene); an unknown name is an error naming the key
  !> and the allowed values.
  subroutine new_scene(name, scene, error)
    !> The scene's name.
    character(len=*), intent(in) :: name
    !> The scene, allocated to its extension.
    class(scene_type), allocatable, intent(out) :: scene
    !> Set when `name` names no scene.
    type(error_type), allocatable, intent(out) :: error
    select case (name)
    case ("hanging_boat")
      allocate (boat_scene_type :: scene)
    case ("lowering")
      allocate (lowering_scene_type :: scene)
    case ("launch")
      allocate (launch_scene_type :: scene)
    case ("ship")
      allocate (ship_scene_type :: scene)
    case ("sea")
      allocate (sea_scene_type :: scene)
    case default
      call fatal_error(error, "&simulation scene = '"//name//"': no such scene; allowed: "// &
                       join_text(scene_names, ", "))
    end select
  end subroutine new_scene

  !> The boat's launch system of the deck's scene and its state at t = 0 (what the sweep,
  !> the library, the bench and the tests build).
  subroutine new_boat_system(cfg, sys, y, error)
    !> The deck's configuration.
    type(config_type), intent(in) :: cfg
    !> The boat's system built.
    type(system_type), intent(out) :: sys
    !> Its initial state.
    real(wp), allocatable, intent(out) :: y(:)
    !> Set when the deck's scene is unknown or has no boat, or its system cannot be built.
    type(error_type), allocatable, intent(out) :: error
    class(scene_type), allocatable :: scene
    call new_scene(cfg%simulation%scene, scene, error)
    if (allocated(error)) return
    call scene%build_boat(cfg, sys, y, error)
  end subroutine new_boat_system

  pure logical function answer_yes(self)
    !> The scene.
    class(scene_type), intent(in) :: self
    answer_yes = .true.
  end function answer_yes

  pure logical function answer_no(self)
    !> The scene.
    class(scene_type), intent(in) :: self
    answer_no = .false.
  end function answer_no

  !> The boat scenes have the boat.
  pure logical function boat_has_boat(self)
    !> The scene.
    class(boat_scene_type), intent(in) :: self
    boat_has_boat = .true.
  end function boat_has_boat

  !> 'lowering' (and 'launch') hang the boat on the davit's rigging.
  pure logical function lowering_on_davit(self)
    !> The scene.
    class(lowering_scene_type), intent(in) :: self
    lowering_on_davit = .true.
  end function lowering_on_davit

  !> 'launch' moves the ship with the boat.
  pure logical function launch_carries_ship(self)
    !> The scene.
    class(launch_scene_type), intent(in) :: self
    launch_carries_ship = .true.
  end function launch_carries_ship

  !> The 'sea' scene has no body the wind could act on.
  pure logical function sea_feels_wind(self)
    !> The scene.
    class(sea_scene_type), intent(in) :: self
    sea_feels_wind = .false.
  end function sea_feels_wind

  !> The boat's launch system, hanging where the scene says, and its state at t = 0.
  subroutine build_boat(self, cfg, sys, y, error)
    !> The scene.
    class(scene_type), intent(in) :: self
    !> The deck's configuration.
    type(config_type), intent(in) :: cfg
    !> The boat's system built.
    type(system_type), intent(out) :: sys
    !> Its initial state.
    real(wp), allocatable, intent(out) :: y(:)
    !> Set when the scene has no boat or its system cannot be built.
    type(error_type), allocatable, intent(out) :: error
    if (.not. self%has_boat()) then
      call fatal_error(error, cfg%filename//": &simulation scene = '"//cfg%simulation%scene// &
                       "' has no boat")
      return
    end if
    call new_system(sys, cfg, self%on_davit(), self%carries_ship(), error)
    if (allocated(error)) return
    call initial_state(sys, cfg, y, error)
  end subroutine build_boat

  !> The boat recorder's fields (position, Euler angles, velocities, accelerations,
  !> tensions, energy, clearance, fender forces, cable segments, sheaves, ship pose) and the
  !> sling lumps; the seat trace: 3 velocities per ms, doubled while it grows, and the
  !> filter's copies; the components' tables with the boat's and the interpolated sea's.
  pure function boat_memory(self, cfg, samples, n_comp) result(parts)
    !> The scene.
    class(boat_scene_type), intent(in) :: self
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> Samples recorded; wave components realised.
    real(wp), intent(in) :: samples, n_comp
    real(wp) :: parts(3)
    real(wp) :: per_sample
    per_sample = 96.0_wp + 6.0_wp*real(cfg%rigging%lumps, wp)
    parts(2) = 8.0_wp*3.0_wp*4.0_wp*cfg%simulation%t_end/seat_dt
    parts(3) = n_comp*(bytes_component_sea + bytes_component_boat) + grid_bytes(cfg, n_comp)
    parts(1) = 8.0_wp*per_sample*samples
  end function boat_memory

  !> The ship recorder's fields; the components' tables with the ship's.
  pure function ship_memory(self, cfg, samples, n_comp) result(parts)
    !> The scene.
    class(ship_scene_type), intent(in) :: self
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> Samples recorded; wave components realised.
    real(wp), intent(in) :: samples, n_comp
    real(wp) :: parts(3)
    real(wp) :: per_sample
    parts = 0.0_wp
    per_sample = 32.0_wp
    parts(3) = n_comp*(bytes_component_sea + bytes_component_ship)
    parts(1) = 8.0_wp*per_sample*samples
  end function ship_memory

  !> Elevation (probes, samples) and time; spatial phasors (components, probes) x 2.
  pure function sea_memory(self, cfg, samples, n_comp) result(parts)
    !> The scene.
    class(sea_scene_type), intent(in) :: self
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> Samples recorded; wave components realised.
    real(wp), intent(in) :: samples, n_comp
    real(wp) :: parts(3)
    real(wp) :: per_sample, np
    parts = 0.0_wp
    np = real(size(cfg%sea%probes_x), wp)
    per_sample = np + 1.0_wp
    parts(3) = n_comp*(bytes_component_sea + 16.0_wp*np + 32.0_wp)
    parts(1) = 8.0_wp*per_sample*samples
  end function sea_memory

  !> The interpolated sea's two grids (davit_sea_wave_grid; `&sea kinematics = 'grid'`):
  !> spatial phasors (2 n per node) over a box of side (L + B + 2 margin)/h + 4 nodes (the
  !> boat's footprint at any heading) and the block's time phasors (2 n per field and
  !> sample, 16 samples; 4 + 4 + 3 nl fields), and the fields themselves [bytes].
  pure real(wp) function grid_bytes(cfg, n_comp) result(bytes)
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    real(wp), intent(in) :: n_comp
    real(wp) :: nodes, fields
    bytes = 0.0_wp
    if (cfg%sea%grid%kinematics /= "grid" .or. cfg%sea%wave_type /= "irregular") return
    associate (g => cfg%sea%grid)
      nodes = ((cfg%boat%length + cfg%boat%beam + 2.0_wp*g%margin)/g%spacing + 4.0_wp)**2
      fields = 8.0_wp + 3.0_wp*(real(ceiling(g%depth/g%spacing), wp) + 3.0_wp)
    end associate
    bytes = 8.0_wp*(2.0_wp*n_comp*(2.0_wp*nodes + 16.0_wp*fields) + 16.0_wp*fields*nodes)
  end function grid_bytes

  !> The boat's launch system at t = 0.
  subroutine boat_problem(self, cfg, problem, y, error)
    !> The scene.
    class(boat_scene_type), intent(in) :: self
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> The boat's system built.
    class(ode_problem), allocatable, intent(out) :: problem
    !> Its initial state.
    real(wp), allocatable, intent(out) :: y(:)
    !> Set when the system cannot be built.
    type(error_type), allocatable, intent(out) :: error
    type(system_type), allocatable :: sys
    allocate (sys)
    call self%build_boat(cfg, sys, y, error)
    call move_alloc(sys, problem)
  end subroutine boat_problem

  !> The ship alone at t = 0.
  subroutine ship_problem(self, cfg, problem, y, error)
    !> The scene.
    class(ship_scene_type), intent(in) :: self
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> The ship's system built.
    class(ode_problem), allocatable, intent(out) :: problem
    !> Its initial state.
    real(wp), allocatable, intent(out) :: y(:)
    !> Set when the ship cannot be built.
    type(error_type), allocatable, intent(out) :: error
    type(ship_system_type), allocatable :: ship
    allocate (ship)
    call build_ship_scene(cfg, ship, y, error)
    call move_alloc(ship, problem)
  end subroutine ship_problem

  !> A scene without dynamics of its own (the sea) has nothing to linearise.
  subroutine no_problem(self, cfg, problem, y, error)
    !> The scene.
    class(scene_type), intent(in) :: self
    !> The run's configuration.
    type(config_type), intent(in) :: cfg
    !> Not allocated.
    class(ode_problem), allocatable, intent(out) :: problem
    !> Not allocated.
    real(wp), allocatable, intent(out) :: y(:)
    !> Always set.
    type(error_type), allocatable, intent(out) :: error
    call fatal_error(error, cfg%filename//": &simulation: scene = '"// &
                     cfg%simulation%scene//"' has no dynamics to linearise")
  end subroutine no_problem

end module davit_run_scene
