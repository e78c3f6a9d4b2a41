!> The fender contact law as an abstract type (paper eqs. 27-28 and their replacements): a
!> law gives the normal force of one fender from its indentation, its rate and its phase
!> (history), advances the phase after an accepted step, and says which phase it would
!> switch to (what event location asks). One extension per law: the rubber fender
!> (davit_boat_rubber_fender_law) and the Hertz laws (davit_boat_contact); the law is built
!> once from the deck (davit_system_law_factory) and the right-hand side, the events
!> and the step policy call its bindings without knowing which law it is.
!>
!> The phase of each fender is history, not a function of the state: the force reads it,
!> `update` advances it after every accepted step.
module davit_boat_contact_law
  use davit_kinds, only: wp
  implicit none
  private
  public :: contact_law_type, fender_state_type, contact_law_names
  public :: phase_free, phase_compression, phase_restitution, phase_separated

  !> The separated phase: the force has vanished at the permanent set delta_p but the point is still
  !> inside the undeformed plane; a new contact needs delta_dot > 0 again, and is measured
  !> from the permanent set (the dent), not from zero.
  integer, parameter :: phase_free = 0, phase_compression = 1, phase_restitution = 2, &
                        phase_separated = 3

  !> The deck's names of the laws (&contact law), in the order the key documents them.
  character(len=*), parameter :: contact_law_names(3) = [character(len=19) :: &
                                                         "rubber_fender", &
                                                         "hertz_elastoplastic", &
                                                         "lankarani_nikravesh"]

  type :: fender_state_type
    !> Contact phase: phase_free, phase_compression, phase_restitution or phase_separated.
    integer :: phase = phase_free
    !> Approach speed at first contact [m/s], recorded maximum indentation [m] and force [N],
    !> permanent set of the last contact at which a new compression starts [m].
    real(wp) :: v0 = 0.0_wp, delta_max = 0.0_wp, f_max = 0.0_wp, offset = 0.0_wp
    !> Rubber fender: exponent p of the unloading path of this contact.
    real(wp) :: exponent = 1.0_wp
  end type fender_state_type

  !> A fender contact law; `restitution` is the coefficient of restitution e_r every law
  !> is built to return.
  type, abstract :: contact_law_type
    !> Coefficient of restitution e_r the law is built to return (0..1).
    real(wp) :: restitution = 0.8_wp
  contains
    procedure(force_i), deferred :: force
    procedure(update_i), deferred :: update
    procedure(next_phase_i), deferred :: next_phase
  end type contact_law_type

  abstract interface
    !> Normal force [N] (>= 0) for indentation delta [m] and its rate delta_dot [m/s]
    !> (positive approaching), in the phase recorded in s.
    pure real(wp) function force_i(self, s, delta, delta_dot) result(f)
      import :: wp, contact_law_type, fender_state_type
      class(contact_law_type), intent(in) :: self
      type(fender_state_type), intent(in) :: s
      real(wp), intent(in) :: delta, delta_dot
    end function force_i

    !> Advance the fender's phase s after an accepted step ending at delta, delta_dot.
    pure subroutine update_i(self, s, delta, delta_dot)
      import :: wp, contact_law_type, fender_state_type
      class(contact_law_type), intent(in) :: self
      type(fender_state_type), intent(inout) :: s
      real(wp), intent(in) :: delta, delta_dot
    end subroutine update_i

    !> The phase `update` would leave s in at delta, delta_dot, without its bookkeeping.
    pure integer function next_phase_i(self, s, delta, delta_dot) result(phase)
      import :: wp, contact_law_type, fender_state_type
      class(contact_law_type), intent(in) :: self
      type(fender_state_type), intent(in) :: s
      real(wp), intent(in) :: delta, delta_dot
    end function next_phase_i
  end interface

end module davit_boat_contact_law
