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
  use davit_boat_contact_law, only: phase_free
  use davit_system_parameters, only: system_params_type, fender_gaps
  use davit_system_history, only: system_history_type
  implicit none
  private
  public :: contact_policy_type, contact_max_step

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

  !> Largest step from state (t, y) when the deck's step is dt.
  pure real(wp) function contact_max_step(policy, par, hist, y, dt) result(h)
    !> The deck's contact step policy.
    type(contact_policy_type), intent(in) :: policy
    !> The system's parameters (contact switch, fenders, side plane).
    type(system_params_type), intent(in) :: par
    !> The history (the fenders' contact phases).
    type(system_history_type), intent(in) :: hist
    !> The system's state and the deck's step dt [s].
    real(wp), intent(in) :: y(:), dt
    real(wp) :: delta(par%fenders%nf), delta_dot(par%fenders%nf)
    integer :: j
    h = dt
    if (.not. par%contact .or. policy%dt_contact <= 0.0_wp .or. policy%dt_contact >= dt) return
    if (any(hist%fender_states%phase /= phase_free)) then
      h = policy%dt_contact
      return
    end if
    if (policy%located) return
    call fender_gaps(par, y, delta, delta_dot)
    if (policy%graded) then
      ! half the predicted time to contact -delta/delta_dot of each approaching fender:
      ! the gap is halved each step, down to dt_contact
      do j = 1, par%fenders%nf
        if (delta_dot(j) > 0.0_wp .and. delta(j) + 2.0_wp*dt*delta_dot(j) > 0.0_wp) then
          h = min(h, max(policy%dt_contact, -0.5_wp*delta(j)/delta_dot(j)))
        end if
      end do
    else if (any(delta + 2.0_wp*dt*max(delta_dot, 0.0_wp) > 0.0_wp)) then
      h = policy%dt_contact
    end if
  end function contact_max_step

end module davit_system_contact_policy
