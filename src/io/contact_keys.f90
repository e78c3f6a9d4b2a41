!> Deck keys of the fender contact with the ship's side (group "contact"; eqs. 27-34,
!> review §1.7, G16, G17): the contact law, its material and fender data, and where the
!> fenders sit on the boat and the side plane on the ship.
module davit_io_contact_keys
  use davit_kinds, only: wp
  use davit_io_deck_reader, only: deck_reader_type
  use davit_boat_contact_law, only: contact_law_names
  implicit none
  private
  public :: contact_config, read_contact

  !> Fender contact with the ship's side (eqs. 27-34, review §1.7, G16, G17).
  type :: contact_config
    !> Whether fender contact with the ship's side is on.
    logical :: enabled
    !> The contact law: 'rubber_fender', 'hertz_elastoplastic' or 'lankarani_nikravesh'.
    character(len=:), allocatable :: law
    !> Hertz laws: Young's moduli [Pa] and Poisson ratios of the fender and of the ship's side.
    real(wp) :: youngs_boat, poisson_boat, youngs_ship, poisson_ship
    !> Hertz laws: radii of curvature of the fender and of the side [m] (0: flat side); the
    !> coefficient of restitution of every law.
    real(wp) :: radius_boat, radius_ship, restitution
    !> Rubber fender: diameter [m] and rated reaction at 60 % deflection [N].
    real(wp) :: fender_diameter, fender_reaction
    !> Boat-frame x of each fender [m].
    real(wp), allocatable :: fender_x(:)
    !> Boat-frame y of the fenders [m], their z span (z down) [m], and the ship-frame y of the side
    !> plane [m].
    real(wp) :: fender_y, fender_z(2), side_y
    !> Contact points per fender.
    integer :: fender_points
  end type contact_config

contains

  !> The &contact group's keys, checked and documented (deck_reader_type).
  subroutine read_contact(r, s, ship_beam)
    !> The deck's reader, positioned at the &contact group.
    type(deck_reader_type), intent(inout) :: r
    !> The &contact values, defaults in, the deck's read over them.
    type(contact_config), intent(inout) :: s
    !> The ship's beam [m] (&ship beam): the side plane's default is half of it plus 0.1 m.
    real(wp), intent(in) :: ship_beam
    character(len=*), parameter :: g = "contact"
    call r%logical(g, "enabled", s%enabled, .true., &
                   "Fender contact with the ship's side plane (eqs. 27-34).")
    call r%choice(g, "law", s%law, "rubber_fender", contact_law_names, "A rubber fender's "// &
                  "published reaction-deflection curve with hysteresis returning e_r^2 of the "// &
                  "work (README Fenders); or the paper's Hertz compression with the corrected "// &
                  "elastoplastic restitution (eqs. 27-28); or the smooth "// &
                  "Lankarani-Nikravesh Hertz law (accurate for e_r near 1).")
    call r%real(g, "fender_diameter", s%fender_diameter, 1.0_wp, 0.01_wp, 10.0_wp, "m", &
                "rubber_fender: diameter D; the curve's deflections are fractions of it "// &
                "(ISO 17357-1 1000 x 1500 pneumatic fender).")
    call r%real(g, "fender_reaction", s%fender_reaction, 182.0e3_wp, 1.0e2_wp, 1.0e8_wp, "N", &
                "rubber_fender: rated reaction R_r at the rated 60 % deflection (ISO "// &
                "17357-1, 1000 x 1500 at 50 kPa: 182 kN, 32 kJ).")
    call read_material(r, "boat", s%youngs_boat, s%poisson_boat, [55.0e9_wp, 0.45_wp], &
                       "Hertz laws: Young's modulus E_b of the fender (the paper's value; "// &
                       "55 GPa gives 100+ g impacts).", &
                       "Poisson's ratio nu_b of the fender (paper).")
    call read_material(r, "ship", s%youngs_ship, s%poisson_ship, [200.0e9_wp, 0.3_wp], &
                       "Young's modulus E_s of the ship's side (steel).", &
                       "Poisson's ratio nu_s of the ship's side (0.3; the paper's 0.6 is "// &
                       "impossible).")
    call r%real(g, "radius_boat", s%radius_boat, 0.15_wp, 0.0_wp, 10.0_wp, "m", &
                "Fender radius of curvature R_b.", lo_open=.true.)
    call r%real(g, "radius_ship", s%radius_ship, 0.0_wp, 0.0_wp, 1.0e3_wp, "m", &
                "Radius of curvature R_s of the side; 0 = flat plate (R = R_b).")
    call r%real(g, "restitution", s%restitution, 0.8_wp, 0.0_wp, 1.0_wp, "-", &
                "Coefficient of restitution e_r (paper).", lo_open=.true.)
    call r%real_list(g, "fender_x", s%fender_x, [3.0_wp, -3.0_wp], -50.0_wp, 50.0_wp, "m", &
                     "Boat-frame x of each fender (two fenders at +-3 m; the paper gives "// &
                     "none).", 1, 8)
    call r%real(g, "fender_y", s%fender_y, -1.4_wp, -50.0_wp, 50.0_wp, "m", &
                "Boat-frame y of the fenders: the port side, facing the ship.")
    call r%real_vec(g, "fender_z", s%fender_z, [-0.8_wp, 0.2_wp], -50.0_wp, 50.0_wp, "m", &
                    "Boat-frame z span of each fender (z down).")
    call r%int(g, "fender_points", s%fender_points, 5, 1, 100, "-", &
               "Points n_d per fender; one contact per fender at its deepest point.")
    call r%real(g, "side_y", s%side_y, 0.5_wp*ship_beam + 0.1_wp, -100.0_wp, 100.0_wp, &
                "m", "Ship-frame y of the side plane (normal +s2, towards the boat); default "// &
                "the paper's y1 = 10.5 m (III.B; starboard, so +): half the "// &
                "&ship beam plus 0.1 m.", default_text="&ship beam/2 + 0.1 (10.5)")
  end subroutine read_contact

  !> One body's elastic material in the Hertz laws (eq. 28's E and nu): keys youngs_<body> and
  !> poisson_<body>, with the same ranges for the fender and the ship's side.
  subroutine read_material(r, body, youngs, poisson, defaults, youngs_text, poisson_text)
    !> The deck's reader, positioned at the &contact group.
    type(deck_reader_type), intent(inout) :: r
    !> The body's suffix of the keys: 'boat' or 'ship'.
    character(len=*), intent(in) :: body
    !> Young's modulus [Pa] and Poisson's ratio [-] read.
    real(wp), intent(out) :: youngs, poisson
    !> Their defaults.
    real(wp), intent(in) :: defaults(2)
    !> The two keys' descriptions.
    character(len=*), intent(in) :: youngs_text, poisson_text
    call r%real("contact", "youngs_"//body, youngs, defaults(1), 1.0e5_wp, 1.0e12_wp, "Pa", &
                youngs_text)
    call r%real("contact", "poisson_"//body, poisson, defaults(2), 0.0_wp, 0.5_wp, "-", &
                poisson_text)
  end subroutine read_material

end module davit_io_contact_keys
