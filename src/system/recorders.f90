!> What each integrated scene records, and how it names its state components in
!> diagnostics. The time loop in davit_system_driver only calls these methods.
module davit_system_recorders
  use davit_kinds, only: wp
  use davit_core_rotation, only: rotation_matrix
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_io_namelist, only: int_to_str
  use davit_system_model, only: system_type, nstate
  implicit none
  private
  public :: recorder_type, boat_recorder, ship_recorder

  type, abstract :: recorder_type
    integer :: n = 0
    real(wp), allocatable :: time(:)
  contains
    procedure(init_interface), deferred :: init
    procedure(sample_interface), deferred :: sample
    procedure(write_interface), deferred :: write
    procedure(name_interface), deferred :: state_name
    procedure :: speed_range => body_speed_range
  end type recorder_type

  abstract interface
    subroutine init_interface(self, nmax)
      import :: recorder_type
      class(recorder_type), intent(inout) :: self
      integer, intent(in) :: nmax
    end subroutine init_interface
    subroutine sample_interface(self, t, y)
      import :: recorder_type, wp
      class(recorder_type), intent(inout) :: self
      real(wp), intent(in) :: t, y(:)
    end subroutine sample_interface
    subroutine write_interface(self, w)
      import :: recorder_type, h5_writer_type
      class(recorder_type), intent(in) :: self
      type(h5_writer_type), intent(inout) :: w
    end subroutine write_interface
    pure function name_interface(self, k) result(name)
      import :: recorder_type
      class(recorder_type), intent(in) :: self
      integer, intent(in) :: k
      character(len=:), allocatable :: name
    end function name_interface
  end interface

  character(len=*), parameter :: body_names(12) = [character(len=7) :: "roll", "pitch", &
    "yaw", "q4", "q5", "q6", "omega1", "omega2", "omega3", "v1", "v2", "v3"]

  !> The hanging boat: CG kinematics, sling tensions, energy.
  type, extends(recorder_type) :: boat_recorder
    !> The integrated system itself (not a copy): its fender phases and first contact time
    !> are history that the time loop advances.
    type(system_type), pointer :: sys => null()
    real(wp), allocatable :: position(:, :), euler(:, :), velocity(:, :)
    real(wp), allocatable :: angular_velocity(:, :), acceleration(:, :), tension(:, :)
    real(wp), allocatable :: energy(:), clearance(:), contact_force(:, :)
    !> Full rigging only: cable segment tensions, paid-out length, sheave angles, lumps.
    real(wp), allocatable :: segment_tension(:, :), paid_out(:), pulley_angle(:, :)
    real(wp), allocatable :: lumps(:, :, :)
    !> Moving ship only: its CG position and Euler angles.
    real(wp), allocatable :: ship_position(:, :), ship_euler(:, :)
  contains
    procedure :: init => boat_init
    procedure :: sample => boat_sample
    procedure :: write => boat_write
    procedure :: state_name => boat_state_name
  end type boat_recorder

  !> The ship alone: CG position and velocity (inertial), attitude, body rates.
  type, extends(recorder_type) :: ship_recorder
    real(wp), allocatable :: position(:, :), euler(:, :), velocity(:, :)
    real(wp), allocatable :: angular_velocity(:, :)
  contains
    procedure :: init => ship_init
    procedure :: sample => ship_sample
    procedure :: write => ship_write
    procedure :: state_name => ship_state_name
  end type ship_recorder

contains

  !> Indices of the speeds in y (a rigid body's u in y(7:12) by default).
  pure function body_speed_range(self) result(r)
    class(recorder_type), intent(in) :: self
    integer :: r(2)
    r = [7, 12]
  end function body_speed_range

  subroutine boat_init(self, nmax)
    class(boat_recorder), intent(inout) :: self
    integer, intent(in) :: nmax
    allocate (self%time(nmax), self%position(3, nmax), self%euler(3, nmax), &
              self%velocity(3, nmax), self%angular_velocity(3, nmax), &
              self%acceleration(3, nmax), self%tension(2, nmax), self%energy(nmax), &
              self%clearance(nmax), self%contact_force(self%sys%fenders%nf, nmax))
    if (self%sys%on_davit) then
      associate (rig => self%sys%rig)
        allocate (self%segment_tension(rig%nseg, nmax), self%paid_out(nmax), &
                  self%pulley_angle(rig%nsheave, nmax), self%lumps(3, 2*rig%nlump, nmax))
      end associate
    end if
    if (self%sys%with_ship) allocate (self%ship_position(3, nmax), self%ship_euler(3, nmax))
  end subroutine boat_init

  subroutine boat_sample(self, t, y)
    class(boat_recorder), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    integer :: k
    if (self%n >= size(self%time)) return
    self%n = self%n + 1
    k = self%n
    self%time(k) = t
    call self%sys%observe(t, y, self%position(:, k), self%euler(:, k), self%velocity(:, k), &
                          self%angular_velocity(:, k), self%acceleration(:, k))
    self%tension(:, k) = self%sys%sling_tensions(y)
    if (self%sys%on_davit) call sample_rigging(self, t, y, k)
    if (self%sys%with_ship) then
      self%ship_euler(:, k) = y(self%sys%iship:self%sys%iship + 2)
      self%ship_position(:, k) = y(self%sys%iship + 3:self%sys%iship + 5)
    end if
    self%energy(k) = self%sys%energy(y)
    call self%sys%contact_state(y, self%clearance(k), self%contact_force(:, k))
  end subroutine boat_sample

  !> Rigging observables of sample k; the slings' tension is that of their hook segment.
  subroutine sample_rigging(self, t, y, k)
    class(boat_recorder), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    integer, intent(in) :: k
    real(wp) :: sling(self%sys%rig%nlump + 1, 2), lumps(3, self%sys%rig%nlump, 2)
    call self%sys%rigging_state(t, y, self%segment_tension(:, k), sling, self%paid_out(k), &
                                lumps)
    self%tension(:, k) = sling(1, :)
    self%pulley_angle(:, k) = self%sys%rig%sheave_angles(y(nstate + 1:))
    self%lumps(:, :, k) = reshape(lumps, [3, 2*self%sys%rig%nlump])
  end subroutine sample_rigging

  subroutine boat_write(self, w)
    class(boat_recorder), intent(in) :: self
    type(h5_writer_type), intent(inout) :: w
    integer :: n
    n = self%n
    call w%write_1d("time", self%time(1:n), "s", "Simulation time of each sample")
    call w%group("boat")
    call w%write_2d("boat/position", self%position(:, 1:n), "m", &
                    "Lifeboat CG position, inertial frame N (x, y horizontal, z down)")
    call w%write_2d("boat/euler", self%euler(:, 1:n), "rad", &
                    "Lifeboat roll, pitch, yaw (ZYX Euler angles, eq. 2)")
    call w%write_2d("boat/velocity", self%velocity(:, 1:n), "m/s", &
                    "Lifeboat CG velocity, inertial frame N")
    call w%write_2d("boat/angular_velocity", self%angular_velocity(:, 1:n), "rad/s", &
                    "Lifeboat angular velocity, boat-frame components (u1, u2, u3)")
    call w%write_2d("boat/acceleration", self%acceleration(:, 1:n), "m/s^2", &
                    "Lifeboat CG acceleration, inertial frame N (gravity not subtracted)")
    call w%group("slings")
    call w%write_2d("slings/tension", self%tension(:, 1:n), "N", &
                    "Sling tension (fore, aft), spring plus dashpot, tension-only")
    if (self%sys%on_davit) call write_rigging(self, w)
    if (self%sys%with_ship) then
      call w%group("ship")
      call w%write_2d("ship/position", self%ship_position(:, 1:n), "m", &
                      "Ship CG position, inertial frame N (z down)")
      call w%write_2d("ship/euler", self%ship_euler(:, 1:n), "rad", &
                      "Ship roll, pitch, yaw (ZYX Euler angles, eq. 2)")
    end if
    call w%group("contact")
    call w%write_1d("contact/clearance", self%clearance(1:n), "m", &
                    "Smallest fender-to-ship-side distance; negative = penetration")
    call w%write_2d("contact/force", self%contact_force(:, 1:n), "N", &
                    "Normal contact force of each fender (one contact per fender)")
    call w%group("events")
    call w%write_1d("events/first_contact_time", [self%sys%first_contact_time], "s", &
                    "Time of the first fender contact; -1 = no contact")
    if (self%sys%on_davit) then
      call w%write_1d("events/lowering_start_time", [self%sys%rig%winch%t_start], "s", &
                      "Time the drum starts paying out")
      call w%write_1d("events/waterborne_time", [self%sys%waterborne_time], "s", &
                      "Time the boat became waterborne (buoyancy >= weight or hooks < 1 % "// &
                      "of it, held 1 s); -1 = never")
      call w%write_1d("events/release_time", [self%sys%release_time], "s", &
                      "Time both hooks were released; -1 = never")
    end if
    call w%write_1d("events/end_time", [self%time(max(n, 1))], "s", &
                    "Time of the last sample (the end of the run, or where it stopped)")
    call w%group("diagnostics")
    call w%write_1d("diagnostics/energy", self%energy(1:n), "J", &
                    "Mechanical energy of the conservative part in air: kinetic + "// &
                    "gravity (-m g z) + elastic slings")
  end subroutine boat_write

  subroutine write_rigging(self, w)
    class(boat_recorder), intent(in) :: self
    type(h5_writer_type), intent(inout) :: w
    integer :: n
    n = self%n
    call w%group("rigging")
    call w%write_2d("rigging/segment_tension", self%segment_tension(:, 1:n), "N", &
                    "Cable segment tensions from the drum (cable 1, then cable 2 for "// &
                    "reeving B), tension-only")
    call w%write_1d("rigging/paid_out", self%paid_out(1:n), "m", &
                    "Cable paid out by the drum since t = 0")
    if (self%sys%rig%nsheave > 0) then
      call w%write_2d("rigging/pulley_angle", self%pulley_angle(:, 1:n), "rad", &
                      "Rotation of each rotating sheave since t = 0")
    end if
    if (self%sys%rig%nlump > 0) then
      call w%write_3d("slings/lump_position", self%lumps(:, :, 1:n), "m", &
                      "Sling lump positions, inertial (fore sling lumps from the hook up, "// &
                      "then aft)")
    end if
  end subroutine write_rigging

  pure function boat_state_name(self, k) result(name)
    class(boat_recorder), intent(in) :: self
    integer, intent(in) :: k
    character(len=:), allocatable :: name
    if (self%sys%with_ship .and. k >= self%sys%iship) then
      name = "ship "//trim(body_names(k - self%sys%iship + 1))
    else if (k > size(body_names)) then
      name = "rigging state "//int_to_str(k - size(body_names))//" of "// &
             int_to_str(self%sys%rig%nstate)
    else
      name = "boat "//trim(body_names(k))
    end if
  end function boat_state_name


  subroutine ship_init(self, nmax)
    class(ship_recorder), intent(inout) :: self
    integer, intent(in) :: nmax
    allocate (self%time(nmax), self%position(3, nmax), self%euler(3, nmax), &
              self%velocity(3, nmax), self%angular_velocity(3, nmax))
  end subroutine ship_init

  subroutine ship_sample(self, t, y)
    class(ship_recorder), intent(inout) :: self
    real(wp), intent(in) :: t, y(:)
    integer :: k
    if (self%n >= size(self%time)) return
    self%n = self%n + 1
    k = self%n
    self%time(k) = t
    self%euler(:, k) = y(1:3)
    self%position(:, k) = y(4:6)
    self%angular_velocity(:, k) = y(7:9)
    self%velocity(:, k) = matmul(rotation_matrix(y(1:3)), y(10:12))
  end subroutine ship_sample

  subroutine ship_write(self, w)
    class(ship_recorder), intent(in) :: self
    type(h5_writer_type), intent(inout) :: w
    integer :: n
    n = self%n
    call w%write_1d("time", self%time(1:n), "s", "Simulation time of each sample")
    call w%group("ship")
    call w%write_2d("ship/position", self%position(:, 1:n), "m", &
                    "Ship CG position, inertial frame N (z down)")
    call w%write_2d("ship/euler", self%euler(:, 1:n), "rad", &
                    "Ship roll, pitch, yaw (ZYX Euler angles, eq. 2)")
    call w%write_2d("ship/velocity", self%velocity(:, 1:n), "m/s", &
                    "Ship CG velocity, inertial frame N")
    call w%write_2d("ship/angular_velocity", self%angular_velocity(:, 1:n), "rad/s", &
                    "Ship angular velocity, ship-frame components")
  end subroutine ship_write

  pure function ship_state_name(self, k) result(name)
    class(ship_recorder), intent(in) :: self
    integer, intent(in) :: k
    character(len=:), allocatable :: name
    if (k >= 4 .and. k <= 6) then
      name = "ship "//trim(merge("x", merge("y", "z", k == 5), k == 4))
    else
      name = "ship "//trim(body_names(k))
    end if
  end function ship_state_name

end module davit_system_recorders
