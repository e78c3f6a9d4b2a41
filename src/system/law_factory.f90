!> The one place a force law is chosen by its name in the deck: the &contact group's `law`
!> becomes an extension of contact_law_type, the &boat group's `lift_form` one of
!> boat_wind_type, its `water_model` the strips' strip_level_type and the &ship group's
!> `drift` a wave_drift_type, once, at build; everything after calls their bindings
!> (force, update, next_phase; force; surfaces, add_sections; force) without asking which
!> law it is.
module davit_system_law_factory
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: contact_config, boat_config
  use davit_io_text, only: join_text
  use davit_boat_contact_law, only: contact_law_type, contact_law_names
  use davit_boat_contact, only: hertz_elastoplastic_law_type, lankarani_nikravesh_law_type, &
                                hertz_stiffness
  use davit_boat_rubber_fender_law, only: new_rubber_fender_law
  use davit_boat_wind_loads, only: boat_wind_type, symmetric_lift_wind_type, &
                                   literal_lift_wind_type, lift_form_names
  use davit_boat_strip_level, only: strip_level_type, strip_level_paper, strip_level_pressure
  use davit_ship_wave_drift, only: wave_drift_type, drift_mean, drift_newman, drift_names
  implicit none
  private
  public :: new_contact_law, new_boat_wind, new_strip_level, new_wave_drift

contains

  !> The &contact law: the rubber fender's curve, or a Hertz law from the two materials
  !> (eq. 27's K); an unknown name is an error naming the key and the allowed values.
  subroutine new_contact_law(k, law, error)
    !> The &contact group as read from the deck.
    type(contact_config), intent(in) :: k
    !> The law, allocated to its extension.
    class(contact_law_type), allocatable, intent(out) :: law
    !> Set when `law` names no contact law (the message names the key and the allowed values).
    type(error_type), allocatable, intent(out) :: error
    select case (k%law)
    case ("rubber_fender")
      allocate (law, source=new_rubber_fender_law(k%fender_diameter, k%fender_reaction, &
                                                  k%restitution))
    case ("hertz_elastoplastic")
      allocate (law, source=hertz_elastoplastic_law_type(restitution=k%restitution, &
                                                         k=stiffness(k)))
    case ("lankarani_nikravesh")
      allocate (law, source=lankarani_nikravesh_law_type(restitution=k%restitution, &
                                                         k=stiffness(k)))
    case default
      call fatal_error(error, "&contact law = '"//k%law//"': no such contact law; allowed: "// &
                       join_text(contact_law_names, ", "))
    end select
  end subroutine new_contact_law

  pure real(wp) function stiffness(k)
    type(contact_config), intent(in) :: k
    stiffness = hertz_stiffness(k%youngs_boat, k%poisson_boat, k%youngs_ship, k%poisson_ship, &
                                k%radius_boat, k%radius_ship)
  end function stiffness

  !> Wind drag (eq. 15) and the &boat lift_form's lift (eq. 16) on the boat; an unknown
  !> form is an error naming the key and the allowed values.
  subroutine new_boat_wind(b, air, error)
    !> The &boat group as read from the deck.
    type(boat_config), intent(in) :: b
    !> The wind loads, allocated to the lift form's extension.
    class(boat_wind_type), allocatable, intent(out) :: air
    !> Set when `lift_form` names no lift form (the message names the key and the allowed
    !> values).
    type(error_type), allocatable, intent(out) :: error
    select case (b%lift_form)
    case ("symmetric")
      allocate (air, source=symmetric_lift_wind_type(b%wind_areas, b%wind_drag_coefficient, &
                                                     b%lift_coefficient, b%lift_diameter, &
                                                     b%length))
    case ("literal")
      allocate (air, source=literal_lift_wind_type(b%wind_areas, b%wind_drag_coefficient, &
                                                   b%lift_coefficient, b%lift_diameter, &
                                                   b%length))
    case default
      call fatal_error(error, "&boat lift_form = '"//b%lift_form//"': no such lift form; "// &
                       "allowed: "//join_text(lift_form_names, ", "))
    end select
  end subroutine new_boat_wind

  !> The strips' level of detail of the &boat water_model: the paper's strips for 'paper',
  !> the pressure-integrated sections otherwise ('pressure'; with 'bem' the strips serve
  !> the surface watch and the hull's volume).
  subroutine new_strip_level(b, level)
    !> The &boat group as read from the deck.
    type(boat_config), intent(in) :: b
    !> The level, allocated to its extension.
    class(strip_level_type), allocatable, intent(out) :: level
    if (b%water_model == "paper") then
      allocate (level, source=strip_level_paper)
    else
      allocate (level, source=strip_level_pressure)
    end if
  end subroutine new_strip_level

  !> The BEM ship's wave drift level of the &ship drift: not allocated for 'none' (no drift
  !> load); an unknown name is an error naming the key and the allowed values.
  subroutine new_wave_drift(name, drift, error)
    !> The value of `&ship drift`.
    character(len=*), intent(in) :: name
    !> The level, allocated to its extension (not allocated: none).
    class(wave_drift_type), allocatable, intent(out) :: drift
    !> Set when `name` names no drift level.
    type(error_type), allocatable, intent(out) :: error
    select case (name)
    case ("none")
      return
    case ("mean")
      allocate (drift, source=drift_mean)
    case ("newman")
      allocate (drift, source=drift_newman)
    case default
      call fatal_error(error, "&ship drift = '"//name//"': no such drift level; allowed: "// &
                       join_text(drift_names, ", "))
    end select
  end subroutine new_wave_drift

end module davit_system_law_factory
