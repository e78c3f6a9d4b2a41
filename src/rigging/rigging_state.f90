!> The rigging's parts and state: the falls plus the lumps, sheaves, winch and drum, the
!> state layout (parts "lumps", "blocks", "sheaves", "drum"), and what is read straight
!> from the state vector (paid-out length, angles, lump and block positions).
!> davit_rigging_rigging extends it with the forces, the Kane blocks and the statics.
module davit_rigging_rigging_state
  use davit_kinds, only: wp
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_rigging_winch, only: winch_type
  use davit_rigging_falls, only: falls_type
  implicit none
  private
  public :: rigging_state_type, set_layout

  !> The falls (cables, top sling segments, blocks; davit_rigging_block_balance) plus the
  !> lumps, the sheaves' dynamics, the winch and the state layout.
  type, extends(falls_type) :: rigging_state_type
    !> The sizes: state length, DOFs (F1), lumps per sling.
    integer :: nstate = 0, ndof = 0, nlump = 0
    !> The rigging's own state layout (parts "lumps", "blocks", "sheaves", "drum"), and
    !> those parts; block_r, block_v: where the block positions and velocities are (the
    !> blocks' q and u, or for quasi-static blocks the two halves of their 12 q slots).
    type(state_layout_type) :: layout
    !> The parts of the layout: lumps, blocks, sheaves, drum.
    type(state_part_type) :: lumps, blocks, sheaves, drum
    !> First and last index of the block positions and of the block velocities in the slice.
    integer :: block_r(2) = [1, 0], block_v(2) = [1, 0]
    !> Whether the start is unstretched (Fig. 13) rather than the static equilibrium.
    logical :: unstretched = .false.
    !> Quasi-static (inertia-free) blocks: positions solved from the force balance.
    logical :: static_blocks = .false.
    !> Reeving 'a' (paper Fig. 8) or 'b' (one wire per fall).
    character(len=1) :: reeving = "a"
    !> The winch driving the drum.
    type(winch_type) :: winch
    !> Polar inertia of a sheave [kg m^2], drum radius [m], Coulomb bearing moment [N m].
    real(wp) :: sheave_inertia = 0.19_wp, drum_radius = 0.25_wp, bearing_friction = 0.0_wp
  contains
    procedure :: paid_out, sheave_angles, drum_angle, lump_positions, block_positions
  end type rigging_state_type

contains

  !> The rigging's layout (parts in state order, see the module header) and its DOFs: the
  !> speeds plus the drum's passage, prescribed by the winch (F1).
  subroutine set_layout(self)
    !> The rigging, its layout set.
    class(rigging_state_type), intent(inout) :: self
    integer :: n
    n = self%nlump
    call self%layout%add("lumps", 6*n, 6*n, self%lumps)
    if (self%static_blocks) then
      call self%layout%add("blocks", 12, 0, self%blocks)
      self%block_r = [self%blocks%q(1), self%blocks%q(1) + 5]
      self%block_v = [self%blocks%q(1) + 6, self%blocks%q(2)]
    else
      call self%layout%add("blocks", 6, 6, self%blocks)
      self%block_r = self%blocks%q
      self%block_v = self%blocks%u
    end if
    call self%layout%add("sheaves", self%nsheave, self%nsheave, self%sheaves)
    call self%layout%add("drum", 1, 0, self%drum)
    self%nstate = self%layout%n
    self%ndof = self%layout%nu + 1
  end subroutine set_layout

  !> Paid-out length at the drum s_drum [m].
  pure function paid_out(self, y) result(s)
    !> The rigging.
    class(rigging_state_type), intent(in) :: self
    !> The rigging's own state slice.
    real(wp), intent(in) :: y(:)
    real(wp) :: s
    s = y(self%drum%q(1))
  end function paid_out

  !> Drum angle s_drum/r_d [rad].
  pure function drum_angle(self, y) result(theta)
    !> The rigging.
    class(rigging_state_type), intent(in) :: self
    !> The rigging's own state slice.
    real(wp), intent(in) :: y(:)
    real(wp) :: theta
    theta = self%paid_out(y)/self%drum_radius
  end function drum_angle

  !> Sheave angles [rad] (empty with quasi-static sheaves).
  pure function sheave_angles(self, y) result(theta)
    !> The rigging.
    class(rigging_state_type), intent(in) :: self
    !> The rigging's own state slice.
    real(wp), intent(in) :: y(:)
    real(wp) :: theta(self%nsheave)
    theta = y(self%sheaves%q(1):self%sheaves%q(2))
  end function sheave_angles

  !> Lump positions (3, lump, sling), inertial [m].
  pure function lump_positions(self, y) result(r)
    !> The rigging.
    class(rigging_state_type), intent(in) :: self
    !> The rigging's own state slice.
    real(wp), intent(in) :: y(:)
    real(wp) :: r(3, self%nlump, 2)
    r = reshape(y(self%lumps%q(1):self%lumps%q(2)), [3, self%nlump, 2])
  end function lump_positions

  !> Block positions (3, block), inertial [m], as stored in the state: for quasi-static
  !> blocks the copies that follow the solved positions (block_state gives those).
  pure function block_positions(self, y) result(r)
    !> The rigging.
    class(rigging_state_type), intent(in) :: self
    !> The rigging's own state slice.
    real(wp), intent(in) :: y(:)
    real(wp) :: r(3, 2)
    r = reshape(y(self%block_r(1):self%block_r(2)), [3, 2])
  end function block_positions

end module davit_rigging_rigging_state
