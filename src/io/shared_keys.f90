!> Key sequences that more than one deck group reads with the same shape, defaults and
!> ranges: a fore and aft pair of points, a wire's diameter and Young's modulus (the
!> foundation slings' and the davit rigging's wire), and the time integrator with its
!> multirate substeps (&simulation, and &sweep over the base deck's). One call serves each
!> group, so the groups' choices and ranges cannot drift apart.
module davit_io_shared_keys
  use davit_kinds, only: wp
  use davit_io_deck_reader, only: deck_reader_type
  use davit_solve_factory, only: integrator_names
  implicit none
  private
  public :: read_fore_aft, read_wire_rope, read_integrator

contains

  !> Keys <stem>_fore and <stem>_aft: two points [m], each component in [-limit, limit].
  subroutine read_fore_aft(r, g, stem, fore, aft, defaults, limit, fore_text, aft_text)
    !> The deck's reader, positioned at group g.
    type(deck_reader_type), intent(inout) :: r
    !> The group and the keys' common stem.
    character(len=*), intent(in) :: g, stem
    !> The fore and aft points read [m].
    real(wp), intent(inout) :: fore(3), aft(3)
    !> Their defaults, one column each (fore, aft) [m].
    real(wp), intent(in) :: defaults(3, 2)
    !> Bound of each component [m].
    real(wp), intent(in) :: limit
    !> The two keys' descriptions.
    character(len=*), intent(in) :: fore_text, aft_text
    call r%real_vec(g, stem//"_fore", fore, defaults(:, 1), -limit, limit, "m", fore_text)
    call r%real_vec(g, stem//"_aft", aft, defaults(:, 2), -limit, limit, "m", aft_text)
  end subroutine read_fore_aft

  !> A steel wire rope's diameter [m] (key diameter_key, 20 mm by default, paper III.B) and
  !> Young's modulus [Pa] (key youngs_modulus, 200 GPa by default), in that order.
  subroutine read_wire_rope(r, g, diameter_key, diameter, youngs, diameter_text, youngs_text)
    !> The deck's reader, positioned at group g.
    type(deck_reader_type), intent(inout) :: r
    !> The group and the diameter's key.
    character(len=*), intent(in) :: g, diameter_key
    !> The wire's diameter [m] and Young's modulus [Pa] read.
    real(wp), intent(out) :: diameter, youngs
    !> The two keys' descriptions.
    character(len=*), intent(in) :: diameter_text, youngs_text
    call r%real(g, diameter_key, diameter, 0.02_wp, 0.0_wp, 0.5_wp, "m", diameter_text, &
                lo_open=.true.)
    call r%real(g, "youngs_modulus", youngs, 200.0e9_wp, 1.0e6_wp, 1.0e12_wp, "Pa", &
                youngs_text)
  end subroutine read_wire_rope

  !> Keys integrator (one of the factory's names, 'rk4' by default) and substeps (RK4
  !> substeps of the multirate integrators' fast part, 1 to 10000, 10 by default).
  subroutine read_integrator(r, g, integrator, substeps, integrator_text, substeps_text, &
                             default_text)
    !> The deck's reader, positioned at group g.
    type(deck_reader_type), intent(inout) :: r
    !> The group.
    character(len=*), intent(in) :: g
    !> The integrator's name read.
    character(len=:), allocatable, intent(out) :: integrator
    !> The substeps read.
    integer, intent(out) :: substeps
    !> The two keys' descriptions.
    character(len=*), intent(in) :: integrator_text, substeps_text
    !> What the documentation gives as both defaults, where not the values above.
    character(len=*), intent(in), optional :: default_text
    call r%choice(g, "integrator", integrator, "rk4", integrator_names, integrator_text, &
                  default_text=default_text)
    call r%int(g, "substeps", substeps, 10, 1, 10000, "-", substeps_text, &
               default_text=default_text)
  end subroutine read_integrator

end module davit_io_shared_keys
