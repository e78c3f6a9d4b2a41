!> The named layout of the state vector y = [... ; q_part ; u_part ; ...].
!>
!> Every body or subsystem registers its generalized coordinates q and speeds u (eqs. 3-4,
!> 47, 66-67) as one part: its q block and then its u block are appended to y. A part
!> with no speeds (the drum passage, prescribed by the winch; quasi-static block copies)
!> registers q only. A subsystem with a layout of its own (the rigging) is appended whole,
!> its parts shifted. This module alone turns names into index ranges: nothing else
!> writes literal slices of y.
!>
!> The mass matrix V of eq. 89 is diagonal (eq. 12) except where a body registers a coupled
!> block of its speeds (a ship with its infinite-frequency added mass A(inf), whose
!> surge-pitch and sway-roll-yaw terms are not zero): the layout keeps that block's
!> inverse, and eq. 89 there reads u_dot = V^-1 (F - W phi). A block whose mass varies in
!> time (a lifeboat's M + s A(inf), s its immersion) is registered in modal form instead:
!> V = M^(1/2) Q (I + s Lambda) Q^T M^(1/2) from the generalized eigenproblem A x = lambda M x,
!> so V^-1 = P diag(1/d) P^T with the constant P = M^(-1/2) Q and the body filling the modal
!> masses d = 1 + s lambda as its V (no factorisation in the right-hand side).
module davit_core_layout
  use davit_kinds, only: wp
  implicit none
  private
  public :: state_layout_type, state_part_type, coupled_block_type, max_parts

  integer, parameter :: max_parts = 16

  !> Index ranges [first, last] in y of a part's coordinates and speeds (last = first - 1
  !> when empty).
  type :: state_part_type
    !> Name the part is registered and looked up by.
    character(len=16) :: name = ""
    !> Index ranges [first, last] in y of the part's coordinates q and speeds u.
    integer :: q(2) = [1, 0], u(2) = [1, 0]
  end type state_part_type

  !> Speeds y(u(1):u(2)) whose mass block is full, and its inverse; or (modal) the
  !> constant modal matrix P of a time-varying block, V^-1 = P diag(1/V_k) P^T with the
  !> body's V_k.
  type :: coupled_block_type
    !> Index range [first, last] in y of the block's speeds.
    integer :: u(2) = [1, 0]
    !> Inverse mass matrix V^-1 of the block, or (modal) the constant modal matrix P.
    real(wp), allocatable :: v_inv(:, :)
    !> True where the block is time-varying and stored in modal form.
    logical :: modal = .false.
  end type coupled_block_type

  type :: state_layout_type
    !> State length and number of speeds.
    integer :: n = 0, nu = 0, nparts = 0
    !> The registered parts, in state order (the first nparts are used).
    type(state_part_type) :: parts(max_parts)
    !> The coupled mass blocks (absent when V is diagonal everywhere).
    type(coupled_block_type), allocatable :: coupled(:)
  contains
    procedure :: add => layout_add
    procedure :: couple => layout_couple
    procedure :: append => layout_append
    procedure :: part => layout_part
  end type state_layout_type

contains

  !> Register a part of nq coordinates followed by nu speeds; returns its ranges.
  subroutine layout_add(self, name, nq, nu, part)
    !> The layout the part is appended to.
    class(state_layout_type), intent(inout) :: self
    !> Name of the part (at most 16 characters are kept).
    character(len=*), intent(in) :: name
    !> Number of coordinates nq and of speeds nu of the part.
    integer, intent(in) :: nq, nu
    !> The part's index ranges in y.
    type(state_part_type), intent(out), optional :: part
    type(state_part_type) :: p
    p%name = name
    p%q = [self%n + 1, self%n + nq]
    p%u = [self%n + nq + 1, self%n + nq + nu]
    self%nparts = self%nparts + 1
    self%parts(self%nparts) = p
    self%n = self%n + nq + nu
    self%nu = self%nu + nu
    if (present(part)) part = p
  end subroutine layout_add

  !> Append every part of a subsystem's own layout; returns the offset of its first state
  !> (its y(1) is this layout's y(offset + 1)).
  subroutine layout_append(self, sub, offset)
    !> The layout the subsystem is appended to.
    class(state_layout_type), intent(inout) :: self
    !> The subsystem's own layout (its indices start at 1).
    type(state_layout_type), intent(in) :: sub
    !> Offset of the subsystem's first state in this layout.
    integer, intent(out) :: offset
    integer :: i
    offset = self%n
    do i = 1, sub%nparts
      associate (p => sub%parts(i))
        call self%add(p%name, p%q(2) - p%q(1) + 1, p%u(2) - p%u(1) + 1)
      end associate
    end do
    if (.not. allocated(sub%coupled)) return
    do i = 1, size(sub%coupled)
      call self%couple(sub%coupled(i)%u + offset, sub%coupled(i)%v_inv, sub%coupled(i)%modal)
    end do
  end subroutine layout_append

  !> The speeds y(u(1):u(2)) have a full mass block: of inverse `matrix` (V^-1), or with
  !> modal, time-varying of constant modal matrix `matrix` (P): V^-1 = P diag(1/V_k) P^T
  !> with the V_k the body fills.
  subroutine layout_couple(self, u, matrix, modal)
    !> The layout the block is registered in.
    class(state_layout_type), intent(inout) :: self
    !> Index range [first, last] in y of the block's speeds.
    integer, intent(in) :: u(2)
    !> V^-1 of the block, or with modal the constant modal matrix P.
    real(wp), intent(in) :: matrix(:, :)
    !> True for a time-varying block given in modal form (default false).
    logical, intent(in), optional :: modal
    logical :: is_modal
    is_modal = .false.
    if (present(modal)) is_modal = modal
    if (.not. allocated(self%coupled)) allocate (self%coupled(0))
    self%coupled = [self%coupled, coupled_block_type(u, matrix, is_modal)]
  end subroutine layout_couple

  !> The part registered as name (an empty part if there is none).
  pure function layout_part(self, name) result(p)
    !> The layout searched.
    class(state_layout_type), intent(in) :: self
    !> Name of the part.
    character(len=*), intent(in) :: name
    type(state_part_type) :: p
    integer :: i
    do i = 1, self%nparts
      if (self%parts(i)%name == name) then
        p = self%parts(i)
        return
      end if
    end do
  end function layout_part

end module davit_core_layout
