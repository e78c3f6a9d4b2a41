!> Fender contact with the ship's side (paper eqs. 27-28) with the review's corrections
!> (§1.7): Hertz compression f = K delta^(3/2), K = (4/3) E* sqrt(R); restitution by the
!> corrected elastoplastic law f = f_max ((delta - delta_p)/(delta_max - delta_p))^(3/2),
!> delta_p = delta_max (1 - e^2), using the recorded delta_max and f_max of the actual
!> compression so the force is continuous at the switch (the printed denominator
!> delta - delta_m is singular there). The smooth alternative is Lankarani-Nikravesh,
!> f = K delta^(3/2) (1 + 3 (1 - e^2)/4 delta_dot/v0), clipped at zero.
!>
!> The default law is a rubber fender instead (`law_rubber_fender`, davit_boat_rubber_fender):
!> a published reaction-deflection curve loading and a hysteresis unloading path that
!> returns e^2 of the work; the Hertz laws stay as the paper-literal levels of detail.
!>
!> The phase of each fender is history, not a function of the state: the force routine
!> reads it, and fender_update advances it after every accepted step. After the force
!> vanishes at the permanent set delta_p the fender is "separated" until it is back out
!> of the plane: treating it as free there would start a new Hertz compression from zero
!> indentation while it moves out, and push it out faster (e = 0.833 instead of 0.8).
module davit_boat_contact
  use davit_kinds, only: wp
  use davit_boat_rubber_fender, only: rubber_loading, rubber_unloading, &
                                      rubber_unloading_exponent
  implicit none
  private
  public :: contact_law_type, fender_state_type, new_contact_law, contact_force
  public :: fender_update, fender_next_phase, hertz_peak, law_hertz_elastoplastic
  public :: law_lankarani_nikravesh
  public :: law_rubber_fender, new_rubber_fender_law
  public :: phase_free, phase_compression, phase_restitution, phase_separated

  integer, parameter :: law_hertz_elastoplastic = 1, law_lankarani_nikravesh = 2, &
                        law_rubber_fender = 3
  !> The separated phase: the force has vanished at the permanent set delta_p but the point is still
  !> inside the undeformed plane; a new contact needs delta_dot > 0 again, and is measured
  !> from the permanent set (the dent), not from zero.
  integer, parameter :: phase_free = 0, phase_compression = 1, phase_restitution = 2, &
                        phase_separated = 3

  type :: contact_law_type
    integer :: law = law_hertz_elastoplastic
    !> Hertz stiffness K [N/m^1.5] and coefficient of restitution.
    real(wp) :: k = 0.0_wp, restitution = 0.8_wp
    !> Rubber fender: diameter D [m] and rated reaction R_r at 60 % deflection [N].
    real(wp) :: diameter = 0.0_wp, rated_reaction = 0.0_wp
  end type contact_law_type

  type :: fender_state_type
    integer :: phase = phase_free
    !> Approach speed at first contact [m/s], recorded maximum indentation [m] and force [N],
    !> permanent set of the last contact at which a new compression starts [m].
    real(wp) :: v0 = 0.0_wp, delta_max = 0.0_wp, f_max = 0.0_wp, offset = 0.0_wp
    !> Rubber fender: exponent p of the unloading path of this contact.
    real(wp) :: exponent = 1.0_wp
  end type fender_state_type

contains

  !> Law from the two materials; r_ship <= 0 means a flat ship side (R = R_b).
  pure function new_contact_law(law, e_boat, nu_boat, e_ship, nu_ship, r_boat, r_ship, &
                                restitution) result(c)
    integer, intent(in) :: law
    real(wp), intent(in) :: e_boat, nu_boat, e_ship, nu_ship, r_boat, r_ship, restitution
    type(contact_law_type) :: c
    real(wp) :: e_star, r
    e_star = 1.0_wp/((1.0_wp - nu_boat**2)/e_boat + (1.0_wp - nu_ship**2)/e_ship)
    r = r_boat
    if (r_ship > 0.0_wp) r = r_boat*r_ship/(r_boat + r_ship)
    c%law = law
    c%k = 4.0_wp/3.0_wp*e_star*sqrt(r)
    c%restitution = restitution
  end function new_contact_law

  !> Rubber fender law: diameter d [m], rated reaction r_rated [N] at 60 % deflection.
  pure function new_rubber_fender_law(d, r_rated, restitution) result(c)
    real(wp), intent(in) :: d, r_rated, restitution
    type(contact_law_type) :: c
    c%law = law_rubber_fender
    c%diameter = d
    c%rated_reaction = r_rated
    c%restitution = restitution
  end function new_rubber_fender_law

  !> Normal force [N] (>= 0) for indentation delta [m] and its rate (positive approaching).
  pure real(wp) function contact_force(c, s, delta, delta_dot) result(f)
    type(contact_law_type), intent(in) :: c
    type(fender_state_type), intent(in) :: s
    real(wp), intent(in) :: delta, delta_dot
    real(wp) :: dp
    f = 0.0_wp
    if (delta <= 0.0_wp) return
    select case (c%law)
    case (law_rubber_fender)
      if (s%phase == phase_restitution) then
        f = rubber_unloading(c%diameter, c%rated_reaction, s%f_max, s%exponent, delta)
      else
        f = rubber_loading(c%diameter, c%rated_reaction, delta)
      end if
    case (law_lankarani_nikravesh)
      if (s%v0 > 0.0_wp) then
        f = max(0.0_wp, c%k*delta**1.5_wp*(1.0_wp + 0.75_wp*(1.0_wp - c%restitution**2)* &
                                           delta_dot/s%v0))
      else
        f = c%k*delta**1.5_wp
      end if
    case default
      select case (s%phase)
      case (phase_restitution)
        dp = permanent_set(c, s)
        if (delta > dp) f = s%f_max*((delta - dp)/(s%delta_max - dp))**1.5_wp
      case (phase_separated)
        f = 0.0_wp
      case default
        f = c%k*max(delta - s%offset, 0.0_wp)**1.5_wp
      end select
    end select
  end function contact_force

  !> Advance the fender's phase after an accepted step: first contact records the approach
  !> speed; compression tracks the maximum; the first sign change of delta_dot starts the
  !> restitution (recording delta_max and f_max there); the contact ends when the force
  !> vanishes (delta <= delta_p) or the point is back on its side (delta <= 0).
  pure subroutine fender_update(c, s, delta, delta_dot)
    type(contact_law_type), intent(in) :: c
    type(fender_state_type), intent(inout) :: s
    real(wp), intent(in) :: delta, delta_dot
    if (c%law == law_rubber_fender) then
      call rubber_update(c, s, delta, delta_dot)
      return
    end if
    select case (s%phase)
    case (phase_free)
      if (delta > 0.0_wp) call start_compression(c, s, 0.0_wp, delta, delta_dot)
    case (phase_compression)
      if (delta <= s%offset) then
        s = fender_state_type()
      else if (delta_dot <= 0.0_wp) then
        s%phase = phase_restitution
        s%delta_max = delta
        s%f_max = c%k*(delta - s%offset)**1.5_wp
      end if
    case (phase_restitution)
      if (delta <= 0.0_wp) then
        s = fender_state_type()
      else if (delta <= permanent_set(c, s)) then
        s%offset = permanent_set(c, s)
        s%phase = phase_separated
      end if
    case (phase_separated)
      if (delta <= 0.0_wp) then
        s = fender_state_type()
      else if (delta_dot > 0.0_wp .and. delta > s%offset) then
        call start_compression(c, s, s%offset, delta, delta_dot)
      end if
    case default
      ! no other phase exists (phase_free .. phase_separated): a corrupt one is free
      s = fender_state_type()
    end select
  end subroutine fender_update

  !> The phase fender_update would leave the fender in, without its bookkeeping (the
  !> rubber fender's unloading exponent is a root solve): what event location asks at
  !> every point it tries (davit_system_model's modes). The same branches as
  !> fender_update and rubber_update; a test holds the two together.
  pure integer function fender_next_phase(c, s, delta, delta_dot) result(phase)
    type(contact_law_type), intent(in) :: c
    type(fender_state_type), intent(in) :: s
    real(wp), intent(in) :: delta, delta_dot
    phase = s%phase
    if (c%law == law_rubber_fender) then
      if (delta <= 0.0_wp) then
        phase = phase_free
      else if (s%phase == phase_free) then
        phase = phase_compression
      else if (s%phase == phase_compression .and. delta_dot <= 0.0_wp) then
        phase = phase_restitution
      else if (s%phase == phase_restitution .and. delta > s%delta_max) then
        phase = phase_compression
      end if
      return
    end if
    select case (s%phase)
    case (phase_free)
      if (delta > 0.0_wp) phase = phase_compression
    case (phase_compression)
      if (delta <= s%offset) then
        phase = phase_free
      else if (delta_dot <= 0.0_wp) then
        phase = phase_restitution
      end if
    case (phase_restitution)
      if (delta <= 0.0_wp) then
        phase = phase_free
      else if (delta <= permanent_set(c, s)) then
        phase = phase_separated
      end if
    case (phase_separated)
      if (delta <= 0.0_wp) then
        phase = phase_free
      else if (delta_dot > 0.0_wp .and. delta > s%offset) then
        phase = phase_compression
      end if
    case default
      ! no other phase exists (phase_free .. phase_separated): a corrupt one is free
      phase = phase_free
    end select
  end function fender_next_phase

  !> The rubber fender's phases: compression on the loading curve until delta_dot <= 0, then
  !> the unloading path of this turning point (its exponent solved once here) until the
  !> fender is back at zero deflection; pushed in past the turning point, it loads again.
  pure subroutine rubber_update(c, s, delta, delta_dot)
    type(contact_law_type), intent(in) :: c
    type(fender_state_type), intent(inout) :: s
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
        s%f_max = rubber_loading(c%diameter, c%rated_reaction, delta)
        s%exponent = rubber_unloading_exponent(c%diameter, c%rated_reaction, delta, &
                                               c%restitution)
      end if
    case (phase_restitution)
      if (delta > s%delta_max) s%phase = phase_compression
    case default
      ! phase_separated: the rubber law never enters it; left as it is, as
      ! fender_next_phase says (the two are held together by a test)
      continue
    end select
  end subroutine rubber_update

  !> A new compression from the indentation `offset` (0, or the dent of the last contact).
  pure subroutine start_compression(c, s, offset, delta, delta_dot)
    type(contact_law_type), intent(in) :: c
    type(fender_state_type), intent(inout) :: s
    real(wp), intent(in) :: offset, delta, delta_dot
    s%phase = phase_compression
    s%offset = offset
    s%v0 = max(delta_dot, tiny(1.0_wp))
    s%delta_max = delta
    s%f_max = c%k*max(delta - offset, 0.0_wp)**1.5_wp
  end subroutine start_compression

  !> delta_p = offset + (delta_max - offset)(1 - e^2): the energy returned over the
  !> restitution is then e^2 times that absorbed in compression.
  pure real(wp) function permanent_set(c, s)
    type(contact_law_type), intent(in) :: c
    type(fender_state_type), intent(in) :: s
    permanent_set = s%offset + (s%delta_max - s%offset)*(1.0_wp - c%restitution**2)
  end function permanent_set

  !> Hertz impact of an effective mass m at speed v0 (review A4): energy balance
  !> 1/2 m v0^2 = 2/5 K delta_m^(5/2) gives delta_m and f_m = K delta_m^(3/2).
  pure subroutine hertz_peak(c, mass, v0, delta_m, f_m)
    type(contact_law_type), intent(in) :: c
    real(wp), intent(in) :: mass, v0
    real(wp), intent(out) :: delta_m, f_m
    delta_m = (1.25_wp*mass*v0**2/c%k)**0.4_wp
    f_m = c%k*delta_m**1.5_wp
  end subroutine hertz_peak

end module davit_boat_contact
