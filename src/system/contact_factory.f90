!> The one place a fender contact law is chosen by its name: the &contact group's `law`
!> becomes an extension of contact_law_type, once, at build; everything after calls its
!> bindings (force, update, next_phase) without asking which law it is.
module davit_system_contact_factory
  use davit_kinds, only: wp
  use davit_error, only: error_type, fatal_error
  use davit_io_config, only: contact_config
  use davit_boat_contact_law, only: contact_law_type, contact_law_names
  use davit_boat_contact, only: hertz_elastoplastic_law_type, lankarani_nikravesh_law_type, &
                                hertz_stiffness
  use davit_boat_rubber_fender_law, only: new_rubber_fender_law
  implicit none
  private
  public :: new_contact_law

contains

  !> The &contact law: the rubber fender's curve, or a Hertz law from the two materials
  !> (eq. 27's K); an unknown name is an error naming the key and the allowed values.
  subroutine new_contact_law(k, law, error)
    !> The &contact group as read from the deck.
    type(contact_config), intent(in) :: k
    !> The law, allocated to its extension.
    class(contact_law_type), allocatable, intent(out) :: law
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
                       allowed())
    end select
  end subroutine new_contact_law

  pure real(wp) function stiffness(k)
    type(contact_config), intent(in) :: k
    stiffness = hertz_stiffness(k%youngs_boat, k%poisson_boat, k%youngs_ship, k%poisson_ship, &
                                k%radius_boat, k%radius_ship)
  end function stiffness

  !> "rubber_fender, hertz_elastoplastic, lankarani_nikravesh".
  pure function allowed() result(list)
    character(len=:), allocatable :: list
    integer :: i
    list = trim(contact_law_names(1))
    do i = 2, size(contact_law_names)
      list = list//", "//trim(contact_law_names(i))
    end do
  end function allowed

end module davit_system_contact_factory
