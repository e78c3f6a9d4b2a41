!> What each integrated scene records, and how it names its state components in
!> diagnostics. The time loop in davit_run_driver only calls these methods.
module davit_run_recorders
  use davit_kinds, only: wp
  use davit_core_rotation, only: rotation_matrix
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_io_namelist, only: int_to_str
  use davit_solve_integrator, only: ode_problem
  use davit_core_layout, only: state_part_type
  use davit_system_model, only: system_type
  use davit_ship_ship_model, only: ship_system_type
  use davit_sea_wave_field, only: wave_field_type, wave_none
  implicit none
  private
  public :: recorder_type, boat_recorder, ship_recorder, write_components

  type, abstract :: recorder_type
    !> Number of samples taken.
    integer :: n = 0
    !> Sample times [s].
    real(wp), allocatable :: time(:)
  contains
    procedure(init_interface), deferred :: init
    procedure(sample_interface), deferred :: sample
    procedure(write_interface), deferred :: write
    procedure(name_interface), deferred :: state_name
    procedure(speeds_interface), deferred :: speed_range
  end type recorder_type

  abstract interface
    subroutine init_interface(self, problem, nmax)
      import :: recorder_type, ode_problem
      class(recorder_type), intent(inout) :: self
      class(ode_problem), intent(in) :: problem
      integer, intent(in) :: nmax
    end subroutine init_interface
    subroutine sample_interface(self, problem, t, y)
      import :: recorder_type, ode_problem, wp
      class(recorder_type), intent(inout) :: self
      class(ode_problem), intent(in) :: problem
      real(wp), intent(in) :: t, y(:)
    end subroutine sample_interface
    subroutine write_interface(self, problem, w)
      import :: recorder_type, ode_problem, h5_writer_type
      class(recorder_type), intent(in) :: self
      class(ode_problem), intent(in) :: problem
      type(h5_writer_type), intent(inout) :: w
    end subroutine write_interface
    !> The name of state component k in a diagnostic.
    pure function name_interface(self, problem, k) result(name)
      import :: recorder_type, ode_problem
      class(recorder_type), intent(in) :: self
      class(ode_problem), intent(in) :: problem
      integer, intent(in) :: k
      character(len=:), allocatable :: name
    end function name_interface
    !> Indices [first, last] of the speeds a blow-up shows in first.
    pure function speeds_interface(self, problem) result(r)
      import :: recorder_type, ode_problem
      class(recorder_type), intent(in) :: self
      class(ode_problem), intent(in) :: problem
      integer :: r(2)
    end function speeds_interface
  end interface

  character(len=*), parameter :: body_names(12) = [character(len=7) :: "roll", "pitch", &
    "yaw", "q4", "q5", "q6", "omega1", "omega2", "omega3", "v1", "v2", "v3"]

  !> The boat on its slings or davit: CG kinematics, tensions, contact, energy.
  type, extends(recorder_type) :: boat_recorder
    !> CG position (inertial) [m], Euler angles [rad], CG velocity (inertial) [m/s], per sample.
    real(wp), allocatable :: position(:, :), euler(:, :), velocity(:, :)
    !> Angular velocity (body) [rad/s], CG acceleration [m/s^2], sling tensions [N], per sample.
    real(wp), allocatable :: angular_velocity(:, :), acceleration(:, :), tension(:, :)
    !> Energy [J], clearance to the ship's side [m], fender contact forces [N], per sample.
    real(wp), allocatable :: energy(:), clearance(:), contact_force(:, :)
    !> Full rigging only: cable segment tensions, paid-out length, sheave angles, lumps,
    !> movable blocks.
    real(wp), allocatable :: segment_tension(:, :), paid_out(:), pulley_angle(:, :)
    !> Lump positions and movable block positions, inertial [m], per sample.
    real(wp), allocatable :: lumps(:, :, :), blocks(:, :, :)
    !> Moving ship only: its CG position, Euler angles and heading error (yaw minus the
    !> heading it keeps).
    real(wp), allocatable :: ship_position(:, :), ship_euler(:, :), heading_error(:)
  contains
    procedure :: init => boat_init
    procedure :: sample => boat_sample
    procedure :: write => boat_write
    procedure :: state_name => boat_state_name
    procedure :: speed_range => boat_speed_range
  end type boat_recorder

  !> The ship alone: CG position and velocity (inertial), attitude, body rates.
  type, extends(recorder_type) :: ship_recorder
    !> CG position (inertial) [m], Euler angles [rad], CG velocity (inertial) [m/s], per sample.
    real(wp), allocatable :: position(:, :), euler(:, :), velocity(:, :)
    !> Angular velocity (body) [rad/s], per sample.
    real(wp), allocatable :: angular_velocity(:, :)
    !> The MMG ship's rudder angle (allocated only with &ship manoeuvring = 'mmg').
    real(wp), allocatable :: rudder(:)
  contains
    procedure :: init => ship_init
    procedure :: sample => ship_sample
    procedure :: write => ship_write
    procedure :: state_name => ship_state_name
    procedure :: speed_range => ship_speed_range
  end type ship_recorder

contains

  pure function boat_speed_range(self, problem) result(r)
    !> The recorder.
    class(boat_recorder), intent(in) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    integer :: r(2)
    select type (problem)
    type is (system_type)
      r = problem%par%boat_part%u
    end select
  end function boat_speed_range

  subroutine boat_init(self, problem, nmax)
    !> The recorder, allocated.
    class(boat_recorder), intent(inout) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> Largest number of samples.
    integer, intent(in) :: nmax
    select type (problem)
    type is (system_type)
      associate (par => problem%par, rig => problem%par%rig)
        allocate (self%time(nmax), self%position(3, nmax), self%euler(3, nmax), &
                  self%velocity(3, nmax), self%angular_velocity(3, nmax), &
                  self%acceleration(3, nmax), self%tension(2, nmax), self%energy(nmax), &
                  self%clearance(nmax), self%contact_force(par%fenders%nf, nmax))
        if (par%on_davit) allocate (self%segment_tension(rig%nseg, nmax), &
                                    self%paid_out(nmax), self%pulley_angle(rig%nsheave, nmax), &
                                    self%lumps(3, 2*rig%nlump, nmax), &
                                    self%blocks(3, 2, nmax))
        if (par%with_ship) allocate (self%ship_position(3, nmax), self%ship_euler(3, nmax), &
                                     self%heading_error(nmax))
      end associate
    end select
  end subroutine boat_init

  subroutine boat_sample(self, problem, t, y)
    !> The recorder.
    class(boat_recorder), intent(inout) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> Sample time [s] and the state there.
    real(wp), intent(in) :: t, y(:)
    integer :: k
    if (self%n >= size(self%time)) return
    select type (sys => problem)
    type is (system_type)
      self%n = self%n + 1
      k = self%n
      self%time(k) = t
      call sys%observe(t, y, self%position(:, k), self%euler(:, k), self%velocity(:, k), &
                       self%angular_velocity(:, k), self%acceleration(:, k))
      self%tension(:, k) = sys%sling_tensions(y)
      if (sys%par%on_davit) call sample_rigging(self, sys, t, y, k)
      if (sys%par%with_ship) then
        associate (q => y(sys%par%ship_part%q(1):sys%par%ship_part%q(2)))
          self%ship_euler(:, k) = q(1:3)
          self%ship_position(:, k) = q(4:6)
          self%heading_error(k) = q(3) - sys%ship%heading_setpoint()
        end associate
      end if
      self%energy(k) = sys%energy(y)
      call sys%contact_state(y, self%clearance(k), self%contact_force(:, k))
    end select
  end subroutine boat_sample

  !> Rigging observables of sample k; the slings' tension is that of their hook segment.
  subroutine sample_rigging(self, sys, t, y, k)
    class(boat_recorder), intent(inout) :: self
    type(system_type), intent(in) :: sys
    real(wp), intent(in) :: t, y(:)
    integer, intent(in) :: k
    real(wp) :: sling(sys%par%rig%nlump + 1, 2), lumps(3, sys%par%rig%nlump, 2)
    call sys%rigging_state(t, y, self%segment_tension(:, k), sling, self%paid_out(k), lumps)
    self%tension(:, k) = sling(1, :)
    associate (rig => sys%par%rig_slice)
      self%pulley_angle(:, k) = sys%par%rig%sheave_angles(y(rig(1):rig(2)))
    end associate
    self%lumps(:, :, k) = reshape(lumps, [3, 2*sys%par%rig%nlump])
    self%blocks(:, :, k) = sys%par%rig%block_positions(y(sys%par%rig_slice(1):sys%par%rig_slice(2)))
  end subroutine sample_rigging

  subroutine boat_write(self, problem, w)
    !> The recorder.
    class(boat_recorder), intent(in) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    integer :: n
    select type (sys => problem)
    type is (system_type)
      n = self%n
      call w%write_1d("time", self%time(1:n), "s", "Simulation time of each sample", dims="time")
      call w%group("boat")
      call w%write_2d("boat/position", self%position(:, 1:n), "m", &
                      "Lifeboat CG position, inertial frame N (x, y horizontal, z down)", &
                      dims="component time")
      call w%write_2d("boat/euler", self%euler(:, 1:n), "rad", &
                      "Lifeboat roll, pitch, yaw (ZYX Euler angles, eq. 2)", dims="angle time")
      call w%write_2d("boat/velocity", self%velocity(:, 1:n), "m/s", &
                      "Lifeboat CG velocity, inertial frame N", dims="component time")
      call w%write_2d("boat/angular_velocity", self%angular_velocity(:, 1:n), "rad/s", &
                      "Lifeboat angular velocity, boat-frame components (u1, u2, u3)", &
                      dims="component time")
      call w%write_2d("boat/acceleration", self%acceleration(:, 1:n), "m/s^2", &
                      "Lifeboat CG acceleration, inertial frame N (gravity not subtracted)", &
                      dims="component time")
      call w%group("slings")
      call w%write_2d("slings/tension", self%tension(:, 1:n), "N", &
                      "Sling tension (fore, aft), spring plus dashpot, tension-only", &
                      dims="sling time")
      if (sys%par%on_davit) call write_rigging(self, sys%par%rig%nsheave, sys%par%rig%nlump, w)
      if (sys%par%with_ship) then
        call write_ship_pose(w, self%ship_position(:, 1:n), self%ship_euler(:, 1:n))
        call w%write_1d("ship/heading_error", self%heading_error(1:n), "rad", &
                        "Ship yaw minus the heading it keeps (its initial heading; "// &
                        "&ship heading_period)", dims="time")
      end if
      call write_sea(sys%par%sea, w)
      call w%group("contact")
      call w%write_1d("contact/clearance", self%clearance(1:n), "m", &
                      "Smallest fender-to-ship-side distance; negative = penetration", dims="time")
      call w%write_2d("contact/force", self%contact_force(:, 1:n), "N", &
                      "Normal contact force of each fender (one contact per fender)", &
                      dims="fender time")
      call w%group("events")
      call w%write_1d("events/first_contact_time", [sys%hist%first_contact_time], "s", &
                      "Time of the first fender contact; -1 = no contact", dims="scalar")
      if (sys%par%on_davit) then
        call w%write_1d("events/lowering_start_time", [sys%par%rig%winch%t_start], "s", &
                        "Time the drum starts paying out", dims="scalar")
        call w%write_1d("events/waterborne_time", [sys%hist%waterborne_time], "s", &
                        "Time the boat became waterborne (buoyancy >= weight or hooks < 1 % "// &
                        "of it, held 1 s); -1 = never", dims="scalar")
        call w%write_1d("events/release_time", [sys%hist%release_time], "s", &
                        "Time both hooks were released; -1 = never", dims="scalar")
      end if
      call w%write_1d("events/end_time", [self%time(max(n, 1))], "s", &
                      "Time of the last sample (the end of the run, or where it stopped)", &
                      dims="scalar")
      call w%group("diagnostics")
      call w%write_1d("diagnostics/energy", self%energy(1:n), "J", &
                      "Mechanical energy of the conservative part in air: kinetic + "// &
                      "gravity (-m g z) + elastic slings", dims="time")
    end select
  end subroutine boat_write

  !> The realised sea of a launch (its components, wave type and ramp), so that the surface
  !> can be rebuilt anywhere afterwards (scene, animation); nothing for calm water.
  subroutine write_sea(sea, w)
    type(wave_field_type), intent(in) :: sea
    type(h5_writer_type), intent(inout) :: w
    character(len=*), parameter :: names(3) = [character(len=9) :: "airy", "stokes2", &
                                                "irregular"]
    if (sea%kind == wave_none) return
    call w%group("sea")
    call write_components(w, sea)
    call w%attr_str("/sea", "wave_type", trim(names(sea%kind)))
    call w%attr_real("/sea", "ramp_time", sea%ramp_time)
  end subroutine write_sea

  subroutine write_rigging(self, nsheave, nlump, w)
    class(boat_recorder), intent(in) :: self
    integer, intent(in) :: nsheave, nlump
    type(h5_writer_type), intent(inout) :: w
    integer :: n
    n = self%n
    call w%group("rigging")
    call w%write_2d("rigging/segment_tension", self%segment_tension(:, 1:n), "N", &
                    "Cable segment tensions from the drum (cable 1, then cable 2 for "// &
                    "reeving B), tension-only", dims="segment time")
    call w%write_1d("rigging/paid_out", self%paid_out(1:n), "m", &
                    "Cable paid out by the drum since t = 0", dims="time")
    if (nsheave > 0) then
      call w%write_2d("rigging/pulley_angle", self%pulley_angle(:, 1:n), "rad", &
                      "Rotation of each rotating sheave since t = 0", dims="sheave time")
    end if
    call w%write_3d("rigging/block_position", self%blocks(:, :, 1:n), "m", &
                    "Movable block positions (fore, aft), inertial; quasi-static blocks: "// &
                    "the state's copy that follows the solved balance (0.1 s lag)", &
                    dims="component block time")
    if (nlump > 0) then
      call w%write_3d("slings/lump_position", self%lumps(:, :, 1:n), "m", &
                      "Sling lump positions, inertial (fore sling lumps from the hook up, "// &
                      "then aft)", dims="component lump time")
    end if
  end subroutine write_rigging

  pure function boat_state_name(self, problem, k) result(name)
    !> The recorder.
    class(boat_recorder), intent(in) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> Index into the state vector.
    integer, intent(in) :: k
    character(len=:), allocatable :: name
    name = "state "//int_to_str(k)
    select type (sys => problem)
    type is (system_type)
      associate (b => sys%par%boat_part, s => sys%par%ship_part)
        if (sys%par%with_ship .and. k >= s%q(1)) then
          name = "ship "//trim(body_names(k - s%q(1) + 1))
        else if (k > b%u(2)) then
          name = "rigging state "//int_to_str(k - sys%par%rig_slice(1) + 1)//" of "// &
                 int_to_str(sys%par%rig%nstate)
        else
          name = "boat "//trim(body_names(k - b%q(1) + 1))
        end if
      end associate
    end select
  end function boat_state_name

  pure function ship_speed_range(self, problem) result(r)
    !> The recorder.
    class(ship_recorder), intent(in) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    integer :: r(2)
    select type (problem)
    type is (ship_system_type)
      r = problem%par%layout%parts(1)%u
    end select
  end function ship_speed_range

  subroutine ship_init(self, problem, nmax)
    !> The recorder, allocated.
    class(ship_recorder), intent(inout) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> Largest number of samples.
    integer, intent(in) :: nmax
    allocate (self%time(nmax), self%position(3, nmax), self%euler(3, nmax), &
              self%velocity(3, nmax), self%angular_velocity(3, nmax))
    select type (problem)
    type is (ship_system_type)
      ! a steered ship (the MMG model) has a rudder angle among its states
      if (problem%par%rudder%q(2) >= problem%par%rudder%q(1)) allocate (self%rudder(nmax))
    end select
  end subroutine ship_init

  subroutine ship_sample(self, problem, t, y)
    !> The recorder.
    class(ship_recorder), intent(inout) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> Sample time [s] and the state there.
    real(wp), intent(in) :: t, y(:)
    type(state_part_type) :: p
    integer :: k
    if (self%n >= size(self%time)) return
    self%n = self%n + 1
    k = self%n
    select type (problem)
    type is (ship_system_type)
      p = problem%par%layout%parts(1)
      if (allocated(self%rudder)) self%rudder(k) = y(problem%par%rudder%q(1))
    end select
    self%time(k) = t
    associate (q => y(p%q(1):p%q(2)), u => y(p%u(1):p%u(2)))
      self%euler(:, k) = q(1:3)
      self%position(:, k) = q(4:6)
      self%angular_velocity(:, k) = u(1:3)
      self%velocity(:, k) = matmul(rotation_matrix(q(1:3)), u(4:6))
    end associate
  end subroutine ship_sample

  subroutine ship_write(self, problem, w)
    !> The recorder.
    class(ship_recorder), intent(in) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    integer :: n
    n = self%n
    call w%write_1d("time", self%time(1:n), "s", "Simulation time of each sample", dims="time")
    call write_ship_pose(w, self%position(:, 1:n), self%euler(:, 1:n))
    call w%write_2d("ship/velocity", self%velocity(:, 1:n), "m/s", &
                    "Ship CG velocity, inertial frame N", dims="component time")
    call w%write_2d("ship/angular_velocity", self%angular_velocity(:, 1:n), "rad/s", &
                    "Ship angular velocity, ship-frame components", dims="component time")
    if (allocated(self%rudder)) call w%write_1d("ship/rudder", self%rudder(1:n), "rad", &
                                                "Rudder angle, positive turns to starboard "// &
                                                "(&mmg)", dims="time")
  end subroutine ship_write

  !> The /ship group with the ship's CG position and Euler angles, (3, sample) each: the
  !> ship scene's and the launch's.
  subroutine write_ship_pose(w, position, euler)
    type(h5_writer_type), intent(inout) :: w
    real(wp), intent(in) :: position(:, :), euler(:, :)
    call w%group("ship")
    call w%write_2d("ship/position", position, "m", &
                    "Ship CG position, inertial frame N (z down)", dims="component time")
    call w%write_2d("ship/euler", euler, "rad", &
                    "Ship roll, pitch, yaw (ZYX Euler angles, eq. 2)", dims="angle time")
  end subroutine write_ship_pose

  pure function ship_state_name(self, problem, k) result(name)
    !> The recorder.
    class(ship_recorder), intent(in) :: self
    !> The system recorded.
    class(ode_problem), intent(in) :: problem
    !> Index into the state vector.
    integer, intent(in) :: k
    character(len=:), allocatable :: name
    if (k >= 4 .and. k <= 6) then
      name = "ship "//trim(merge("x", merge("y", "z", k == 5), k == 4))
    else
      name = "ship "//trim(body_names(k))
    end if
  end function ship_state_name

  !> The realised component table: enough to rebuild the sea anywhere (eq. 43).
  subroutine write_components(w, field)
    !> The open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The realised sea.
    type(wave_field_type), intent(in) :: field
    call w%group("sea/components")
    call w%write_1d("sea/components/omega", field%omega, "rad/s", "Component frequency", &
                    dims="wave_component")
    call w%write_1d("sea/components/wavenumber", field%k, "rad/m", &
                    "Component wave number, deep water k = omega^2/g", dims="wave_component")
    call w%write_1d("sea/components/direction", field%direction, "rad", &
                    "Propagation direction from N1 towards N2", dims="wave_component")
    call w%write_1d("sea/components/amplitude", field%amplitude, "m", &
                    "Amplitude a = sqrt(2 S dw D_j) (regular: H/2)", dims="wave_component")
    call w%write_1d("sea/components/phase", field%phase, "rad", &
                    "Phase eps in cos(w t + eps - k (x cos g + y sin g))", dims="wave_component")
  end subroutine write_components

end module davit_run_recorders
