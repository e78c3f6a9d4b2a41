!> Fender contact with the ship's side (paper eqs. 27-28) with the review's corrections
!> (§1.7): Hertz compression f = K delta^(3/2), K = (4/3) E* sqrt(R); restitution by the
!> corrected elastoplastic law f = f_max ((delta - delta_p)/(delta_max - delta_p))^(3/2),
!> delta_p = delta_max (1 - e^2), using the recorded delta_max and f_max of the actual
!> compression so the force is continuous at the switch (the printed denominator
!> delta - delta_m is singular there). The smooth alternative is Lankarani-Nikravesh,
!> f = K delta^(3/2) (1 + 3 (1 - e^2)/4 delta_dot/v0), clipped at zero.
!>
!> The default law is a rubber fender instead (davit_boat_rubber_fender_law): a published
!> reaction-deflection curve loading and a hysteresis unloading path that returns e^2 of the
!> work; the Hertz laws stay as the paper-literal levels of detail. Both Hertz laws extend
!> contact_law_type (davit_boat_contact_law) through hertz_law_type, which holds K and the
!> phases they share; each gives its own force.
!>
!> The phase of each fender is history, not a function of the state: the force reads it,
!> and `update` advances it after every accepted step. After the force
!> vanishes at the permanent set delta_p the fender is "separated" until it is back out
!> of the plane: treating it as free there would start a new Hertz compression from zero
!> indentation while it moves out, and push it out faster (e = 0.833 instead of 0.8).
module davit_boat_contact
  use davit_kinds, only: wp
  use davit_boat_contact_law, only: contact_law_type, fender_state_type, phase_free, &
                                    phase_compression, phase_restitution, phase_separated
  implicit none
  private
  public :: hertz_law_type, hertz_elastoplastic_law_type, lankarani_nikravesh_law_type
  public :: hertz_stiffness, hertz_peak
  ! the phases and the state, for the modules that read a fender's phase through this one
  public :: fender_state_type, phase_free, phase_compression, phase_restitution, &
            phase_separated

  !> The Hertz laws: stiffness K [N/m^1.5] (eq. 27) and the phases both laws go through.
  type, abstract, extends(contact_law_type) :: hertz_law_type
    !> Hertz stiffness K [N/m^1.5] (eq. 27).
    real(wp) :: k = 0.0_wp
  contains
    procedure :: update => hertz_update
    procedure :: next_phase => hertz_next_phase
  end type hertz_law_type

  !> Hertz compression and the corrected elastoplastic restitution (eqs. 27-28, §1.7).
  type, extends(hertz_law_type) :: hertz_elastoplastic_law_type
  contains
    procedure :: force => elastoplastic_force
  end type hertz_elastoplastic_law_type

  !> The Lankarani-Nikravesh law, Hertz with a hysteresis damping term, clipped at zero.
  type, extends(hertz_law_type) :: lankarani_nikravesh_law_type
  contains
    procedure :: force => lankarani_nikravesh_force
  end type lankarani_nikravesh_law_type

contains

  !> K = (4/3) E* sqrt(R) from the two materials; r_ship <= 0 means a flat ship side (R = R_b).
  pure real(wp) function hertz_stiffness(e_boat, nu_boat, e_ship, nu_ship, r_boat, r_ship) &
    result(k)
    !> Young's moduli [Pa] and Poisson ratios of the boat's and the ship's materials, and the radii
    !> of curvature of the boat and the ship [m] (r_ship <= 0: flat side).
    real(wp), intent(in) :: e_boat, nu_boat, e_ship, nu_ship, r_boat, r_ship
    real(wp) :: e_star, r
    e_star = 1.0_wp/((1.0_wp - nu_boat**2)/e_boat + (1.0_wp - nu_ship**2)/e_ship)
    r = r_boat
    if (r_ship > 0.0_wp) r = r_boat*r_ship/(r_boat + r_ship)
    k = 4.0_wp/3.0_wp*e_star*sqrt(r)
  end function hertz_stiffness

  !> Hertz compression from the offset (the dent of the last contact), the elastoplastic
  !> restitution down to the permanent set, nothing while separated.
  pure real(wp) function elastoplastic_force(self, s, delta, delta_dot) result(f)
    !> The elastoplastic Hertz law.
    class(hertz_elastoplastic_law_type), intent(in) :: self
    !> The fender's contact state (phase, offset, turning point).
    type(fender_state_type), intent(in) :: s
    !> Penetration into the side plane [m] and its rate [m/s] (positive approaching).
    real(wp), intent(in) :: delta, delta_dot
    real(wp) :: dp
    f = 0.0_wp
    if (delta <= 0.0_wp) return
    select case (s%phase)
    case (phase_restitution)
      dp = permanent_set(self, s)
      if (delta > dp) f = s%f_max*((delta - dp)/(s%delta_max - dp))**1.5_wp
    case (phase_separated)
      f = 0.0_wp
    case default
      f = self%k*max(delta - s%offset, 0.0_wp)**1.5_wp
    end select
  end function elastoplastic_force

  !> f = K delta^(3/2) (1 + 3 (1 - e^2)/4 delta_dot/v0), clipped at zero; plain Hertz before
  !> the approach speed v0 is recorded.
  pure real(wp) function lankarani_nikravesh_force(self, s, delta, delta_dot) result(f)
    !> The Lankarani-Nikravesh law.
    class(lankarani_nikravesh_law_type), intent(in) :: self
    !> The fender's contact state (approach speed v0).
    type(fender_state_type), intent(in) :: s
    !> Penetration into the side plane [m] and its rate [m/s] (positive approaching).
    real(wp), intent(in) :: delta, delta_dot
    f = 0.0_wp
    if (delta <= 0.0_wp) return
    if (s%v0 > 0.0_wp) then
      f = max(0.0_wp, self%k*delta**1.5_wp*(1.0_wp + 0.75_wp*(1.0_wp - self%restitution**2)* &
                                            delta_dot/s%v0))
    else
      f = self%k*delta**1.5_wp
    end if
  end function lankarani_nikravesh_force

  !> Advance the fender's phase after an accepted step: first contact records the approach
  !> speed; compression tracks the maximum; the first sign change of delta_dot starts the
  !> restitution (recording delta_max and f_max there); the contact ends when the force
  !> vanishes (delta <= delta_p) or the point is back on its side (delta <= 0).
  pure subroutine hertz_update(self, s, delta, delta_dot)
    !> The Hertz law.
    class(hertz_law_type), intent(in) :: self
    !> The fender's contact state, advanced.
    type(fender_state_type), intent(inout) :: s
    !> Penetration [m] and its rate [m/s] at the end of the accepted step.
    real(wp), intent(in) :: delta, delta_dot
    select case (s%phase)
    case (phase_free)
      if (delta > 0.0_wp) call start_compression(self, s, 0.0_wp, delta, delta_dot)
    case (phase_compression)
      if (delta <= s%offset) then
        s = fender_state_type()
      else if (delta_dot <= 0.0_wp) then
        s%phase = phase_restitution
        s%delta_max = delta
        s%f_max = self%k*(delta - s%offset)**1.5_wp
      end if
    case (phase_restitution)
      if (delta <= 0.0_wp) then
        s = fender_state_type()
      else if (delta <= permanent_set(self, s)) then
        s%offset = permanent_set(self, s)
        s%phase = phase_separated
      end if
    case (phase_separated)
      if (delta <= 0.0_wp) then
        s = fender_state_type()
      else if (delta_dot > 0.0_wp .and. delta > s%offset) then
        call start_compression(self, s, s%offset, delta, delta_dot)
      end if
    case default
      ! no other phase exists (phase_free .. phase_separated): a corrupt one is free
      s = fender_state_type()
    end select
  end subroutine hertz_update

  !> The phase hertz_update would leave the fender in, without its bookkeeping: what event
  !> location asks at every point it tries (davit_system_model's modes). The same branches
  !> as hertz_update; a test holds the two together.
  pure integer function hertz_next_phase(self, s, delta, delta_dot) result(phase)
    !> The Hertz law.
    class(hertz_law_type), intent(in) :: self
    !> The fender's contact state.
    type(fender_state_type), intent(in) :: s
    !> Penetration [m] and its rate [m/s] at the point tried.
    real(wp), intent(in) :: delta, delta_dot
    phase = s%phase
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
      else if (delta <= permanent_set(self, s)) then
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
  end function hertz_next_phase

  !> A new compression from the indentation `offset` (0, or the dent of the last contact).
  pure subroutine start_compression(c, s, offset, delta, delta_dot)
    class(hertz_law_type), intent(in) :: c
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
    class(hertz_law_type), intent(in) :: c
    type(fender_state_type), intent(in) :: s
    permanent_set = s%offset + (s%delta_max - s%offset)*(1.0_wp - c%restitution**2)
  end function permanent_set

  !> Hertz impact of an effective mass m at speed v0 (review A4): energy balance
  !> 1/2 m v0^2 = 2/5 K delta_m^(5/2) gives delta_m and f_m = K delta_m^(3/2).
  pure subroutine hertz_peak(c, mass, v0, delta_m, f_m)
    !> The Hertz law (its stiffness K).
    class(hertz_law_type), intent(in) :: c
    !> Effective mass [kg] and approach speed [m/s].
    real(wp), intent(in) :: mass, v0
    !> Peak penetration [m] and peak force [N].
    real(wp), intent(out) :: delta_m, f_m
    delta_m = (1.25_wp*mass*v0**2/c%k)**0.4_wp
    f_m = c%k*delta_m**1.5_wp
  end subroutine hertz_peak

end module davit_boat_contact
