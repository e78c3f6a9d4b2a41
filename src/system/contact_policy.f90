!> The step policy of contact (the only step policy the launch's physics imposes).
!>
!> The contact phases switch only between steps (after_step), and the Hertz force rises
!> over milliseconds: while any fender is in contact, or its indentation extrapolated
!> over the next two steps of size dt would be positive, steps are limited to dt_contact.
!> This locates the contact onset to within dt_contact (an event location by step
!> limiting that keeps the step sequence deterministic) and resolves the impact. With
!> `contact_approach = 'graded'` the approach steps are instead half the predicted time
!> to contact (at least dt_contact): the same onset resolution in ~log2(dt/dt_contact)
!> steps rather than 2 dt/dt_contact, which matters at large dt (quasi-static blocks).
!> With `contact_approach = 'event'` the approach takes dt and the onset is located as an
!> event (davit_solve_event_location): the step is cut exactly at it.
module davit_system_contact_policy
  use davit_kinds, only: wp
  use davit_boat_contact_law, only: phase_free, fender_state_type
  implicit none
  private
  public :: contact_policy_type, limits_steps, contact_max_step

  !> How steps are limited around fender contact (&simulation's contact keys).
  type :: contact_policy_type
    !> Step while a fender is in contact or about to be (0: no limit) [s].
    real(wp) :: dt_contact = 0.0_wp
    !> Approach steps graded by the predicted time to contact (else the two-step window).
    logical :: graded = .false.
    !> Approach at dt: the onset (and every phase switch) is located as an event on the
    !> integrator's dense output (davit_solve_event_location) instead.
    logical :: located = .false.
  end type contact_policy_type

contains

  !> Whether the policy limits steps at all: contact acts and 0 < dt_contact < dt.
  pure logical function limits_steps(policy, contact, dt)
    !> The deck's contact step policy.
    type(contact_policy_type), intent(in) :: policy
    !> Whether the fenders' contact with the ship's side acts (&contact enabled).
    logical, intent(in) :: contact
    !> The deck's step [s].
    real(wp), intent(in) :: dt
    limits_steps = contact .and. policy%dt_contact > 0.0_wp .and. policy%dt_contact < dt
  end function limits_steps

  !> Largest step from a state where each fender is in its contact phase `states` at
  !> indentation delta [m] (> 0 into the side) with rate delta_dot [m/s] (> 0 approaching),
  !> when the deck's step is dt and the policy limits steps (limits_steps).
  pure real(wp) function contact_max_step(policy, states, delta, delta_dot, dt) result(h)
    !> The deck's contact step policy.
    type(contact_policy_type), intent(in) :: policy
    !> Each fender's contact phase (the history's).
    type(fender_state_type), intent(in) :: states(:)
    !> Each fender's indentation [m] and its rate [m/s] (fender_gaps).
    real(wp), intent(in) :: delta(:), delta_dot(:)
    !> The deck's step [s].
    real(wp), intent(in) :: dt
    integer :: j
    h = dt
    if (any(states%phase /= phase_free)) then
      h = policy%dt_contact
      return
    end if
    if (policy%located) return
    if (policy%graded) then
      ! half the predicted time to contact -delta/delta_dot of each approaching fender:
      ! the gap is halved each step, down to dt_contact
      do j = 1, size(delta)
        if (delta_dot(j) > 0.0_wp .and. delta(j) + 2.0_wp*dt*delta_dot(j) > 0.0_wp) then
          h = min(h, max(policy%dt_contact, -0.5_wp*delta(j)/delta_dot(j)))
        end if
      end do
    else if (any(delta + 2.0_wp*dt*max(delta_dot, 0.0_wp) > 0.0_wp)) then
      h = policy%dt_contact
    end if
  end function contact_max_step

end module davit_system_contact_policy
