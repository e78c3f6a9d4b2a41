!> The rubber fender as a contact law (the default, in place of the paper's eqs. 27-28):
!> the published reaction-deflection curve loading and the hysteresis unloading path that
!> returns e_r^2 of the work (davit_boat_rubber_fender), with the phases a rubber fender
!> goes through: compression on the loading curve until delta_dot <= 0, then the unloading
!> path of that turning point until it is back at zero deflection (no permanent set);
!> pushed in past the turning point, it loads again.
module davit_boat_rubber_fender_law
  use davit_kinds, only: wp
  use davit_boat_contact_law, only: contact_law_type, fender_state_type, phase_free, &
                                    phase_compression, phase_restitution
  use davit_boat_rubber_fender, only: rubber_loading, rubber_unloading, &
                                      rubber_unloading_exponent
  implicit none
  private
  public :: rubber_fender_law_type, new_rubber_fender_law

  type, extends(contact_law_type) :: rubber_fender_law_type
    !> Diameter D [m] and rated reaction R_r at 60 % deflection [N].
    real(wp) :: diameter = 0.0_wp, rated_reaction = 0.0_wp
  contains
    procedure :: force => rubber_force
    procedure :: update => rubber_update
    procedure :: next_phase => rubber_next_phase
  end type rubber_fender_law_type

contains

  !> Rubber fender law: diameter d [m], rated reaction r_rated [N] at 60 % deflection,
  !> coefficient of restitution e_r.
  pure function new_rubber_fender_law(d, r_rated, restitution) result(c)
    !> Fender diameter [m], rated reaction [N] at 60 % deflection, coefficient of restitution
    !> (0..1).
    real(wp), intent(in) :: d, r_rated, restitution
    type(rubber_fender_law_type) :: c
    c%diameter = d
    c%rated_reaction = r_rated
    c%restitution = restitution
  end function new_rubber_fender_law

  !> The loading curve, or the unloading path of this contact's turning point.
  pure real(wp) function rubber_force(self, s, delta, delta_dot) result(f)
    !> The rubber fender law.
    class(rubber_fender_law_type), intent(in) :: self
    !> The fender's contact state (phase, turning point, exponent).
    type(fender_state_type), intent(in) :: s
    !> Deflection [m] and its rate [m/s] (positive approaching).
    real(wp), intent(in) :: delta, delta_dot
    f = 0.0_wp
    if (delta <= 0.0_wp) return
    if (s%phase == phase_restitution) then
      f = rubber_unloading(self%diameter, self%rated_reaction, s%f_max, s%exponent, delta)
    else
      f = rubber_loading(self%diameter, self%rated_reaction, delta)
    end if
  end function rubber_force

  !> The phases after an accepted step; the unloading exponent of a turning point is
  !> solved once here.
  pure subroutine rubber_update(self, s, delta, delta_dot)
    !> The rubber fender law.
    class(rubber_fender_law_type), intent(in) :: self
    !> The fender's contact state, advanced.
    type(fender_state_type), intent(inout) :: s
    !> Deflection [m] and its rate [m/s] at the end of the accepted step.
    real(wp), intent(in) :: delta, delta_dot
    if (delta <= 0.0_wp) then
      s = fender_state_type()
      return
    end if
    select case (s%phase)
    case (phase_free)
      s%phase = phase_compression
      s%v0 = max(delta_dot, tiny(1.0_wp))
    case (phase_compression)
      if (delta_dot <= 0.0_wp) then
        s%phase = phase_restitution
        s%delta_max = delta
        s%f_max = rubber_loading(self%diameter, self%rated_reaction, delta)
        s%exponent = rubber_unloading_exponent(self%diameter, self%rated_reaction, delta, &
                                               self%restitution)
      end if
    case (phase_restitution)
      if (delta > s%delta_max) s%phase = phase_compression
    case default
      ! phase_separated: the rubber law never enters it; left as it is, as
      ! rubber_next_phase says (the two are held together by a test)
      continue
    end select
  end subroutine rubber_update

  !> The phase rubber_update would set, without the root solve for the exponent.
  pure integer function rubber_next_phase(self, s, delta, delta_dot) result(phase)
    !> The rubber fender law.
    class(rubber_fender_law_type), intent(in) :: self
    !> The fender's contact state.
    type(fender_state_type), intent(in) :: s
    !> Deflection [m] and its rate [m/s] at the point tried.
    real(wp), intent(in) :: delta, delta_dot
    phase = s%phase
    if (delta <= 0.0_wp) then
      phase = phase_free
    else if (s%phase == phase_free) then
      phase = phase_compression
    else if (s%phase == phase_compression .and. delta_dot <= 0.0_wp) then
      phase = phase_restitution
    else if (s%phase == phase_restitution .and. delta > s%delta_max) then
      phase = phase_compression
    end if
  end function rubber_next_phase

end module davit_boat_rubber_fender_law
