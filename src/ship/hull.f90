!> Ship parameters derived from Table 1 and the review's gaps (G9-G15); every number the
!> ship's equations use is computed here once, with its source in a comment.
module davit_ship_hull
  use davit_kinds, only: wp, pi, gravity, rho_water
  use davit_error, only: error_type
  use davit_io_config, only: ship_config
  use davit_ship_froude_krylov, only: box_type
  use davit_ship_wind_load, only: ship_wind_type
  use davit_ship_section_added_mass, only: section_added_mass, rectangle_contour
  implicit none
  private
  public :: hull_type, new_hull, hull_natural_periods

  !> The ship's hull: masses, restoring, damping and empirical coefficients derived once.
  type :: hull_type
    !> The equivalent box of the Froude-Krylov loads (l = sqrt(C_b) L_wl, beam, draught).
    type(box_type) :: box
    !> Windage (areas, length overall, height of the centre of effort) of the wind load.
    type(ship_wind_type) :: wind
    !> Displacement mass [kg] (Table 1).
    real(wp) :: mass = 0.0_wp
    !> Rigid-body principal inertia about G [kg m^2].
    real(wp) :: inertia(3) = 0.0_wp
    !> Added mass (surge, sway, heave) [kg] and added inertia (roll, pitch, yaw) [kg m^2].
    real(wp) :: added_mass(3) = 0.0_wp, added_inertia(3) = 0.0_wp
    !> Sway-yaw added-mass coupling about G [kg m] (MMG: the sway added mass acts at
    !> midship, -x_G m_y about G; 0 for the box).
    real(wp) :: added_sway_yaw = 0.0_wp
    !> Linear restoring: heave [N/m], roll and pitch [N m/rad].
    real(wp) :: c33 = 0.0_wp, c44 = 0.0_wp, c55 = 0.0_wp
    !> Linear damping: heave [N s/m], roll, pitch [N m s]; quadratic roll [N m s^2].
    real(wp) :: b33 = 0.0_wp, b44 = 0.0_wp, b55 = 0.0_wp, b44q = 0.0_wp
    !> Cross-flow drag: length, draught, coefficient.
    real(wp) :: lpp = 0.0_wp, draught = 0.0_wp, cd = 0.0_wp
    !> CG relative to O' (midship, waterline, centreline) [m].
    real(wp) :: cg_x = 0.0_wp, cg_z = 0.0_wp
    !> Equilibrium roll and pitch (static list and trim) [rad].
    real(wp) :: list = 0.0_wp, trim = 0.0_wp
    !> Linear MMG hull derivatives (Kijima et al. 1990, review G13), non-dimensional on
    !> 1/2 rho L_pp d U^2 (forces) and 1/2 rho L_pp^2 d U^2 (moments); v' = v/U, r' = r L/U.
    real(wp) :: yv = 0.0_wp, yr = 0.0_wp, nv = 0.0_wp, nr = 0.0_wp
    !> The empirical loads (cross-flow drag, surge resistance, manoeuvring, windage) act.
    logical :: empirical = .true.
    !> Restrained DOFs (surge, sway, heave, roll, pitch, yaw).
    logical :: restrained(6) = .false.
    !> The BEM ship's forward-speed radiation terms (&ship speed_terms): the heave-pitch
    !> ones ('heave_pitch' or 'stf'), and the sway-yaw ones too ('stf').
    logical :: speed_terms = .false., speed_sway_yaw = .false.
  end type hull_type

contains

  !> Derive the hull from the deck's &ship group: box, masses and inertias, strip-theory
  !> added masses, hydrostatics, damping, Kijima derivatives (and the MMG added masses).
  subroutine new_hull(hull, s, error)
    !> The hull derived.
    type(hull_type), intent(out) :: hull
    !> The deck's &ship group (Table 1 and the review's gaps).
    type(ship_config), intent(in) :: s
    !> Set when the section added-mass solve of the box's cross-section fails.
    type(error_type), allocatable, intent(out) :: error
    real(wp), allocatable :: y(:), z(:)
    real(wp) :: a(4), l, a44_g
    ! equivalent box: l = sqrt(C_b) L_wl, full beam and draught (review §1.8, G15)
    l = sqrt(s%cb)*s%lwl
    hull%box = box_type(l, s%beam, s%draught)
    hull%mass = s%displacement
    ! radii of gyration 0.38 B and 0.25 L_pp (review G9)
    hull%inertia = s%displacement*[(0.38_wp*s%beam)**2, (0.25_wp*s%lpp)**2, &
                                   (0.25_wp*s%lpp)**2]
    ! strip theory on the box's rectangular section at infinite frequency
    call rectangle_contour(s%beam, s%draught, 40, 120, y, z)
    call section_added_mass(y, z, a, error)
    if (allocated(error)) return
    ! roll about G at depth cg_z: roll_G = roll_O' + z_G sway
    a44_g = a(3) + 2.0_wp*s%cg_z*a(4) + s%cg_z**2*a(1)
    hull%added_mass = [0.05_wp*s%displacement, a(1)*l, a(2)*l]
    hull%added_inertia = [a44_g*l, a(2)*(l**3/12.0_wp + s%cg_x**2*l), &
                          a(1)*(l**3/12.0_wp + s%cg_x**2*l)]
    ! hydrostatics of the same box (review G11): waterplane l B, C44 from the table's GM
    hull%c33 = rho_water*gravity*l*s%beam
    hull%c44 = s%displacement*gravity*s%gm
    hull%c55 = rho_water*gravity*s%beam*l**3/12.0_wp
    ! damping as fractions of critical (review G12)
    hull%b33 = 2.0_wp*s%zeta_heave*sqrt(hull%c33*(hull%mass + hull%added_mass(3)))
    hull%b44 = 2.0_wp*s%zeta_roll*sqrt(hull%c44*(hull%inertia(1) + hull%added_inertia(1)))
    hull%b55 = 2.0_wp*s%zeta_pitch*sqrt(hull%c55*(hull%inertia(2) + hull%added_inertia(2)))
    hull%b44q = s%roll_quadratic
    hull%lpp = s%lpp
    hull%draught = s%draught
    hull%cd = s%crossflow_cd
    hull%cg_x = s%cg_x
    hull%cg_z = s%cg_z
    hull%list = s%list
    hull%trim = s%trim
    hull%wind = ship_wind_type(s%area_front, s%area_lateral, s%loa, s%wind_height)
    call kijima(hull, s)
    hull%empirical = s%empirical_loads == "deck"
    hull%restrained = s%restrained
    hull%speed_terms = s%speed_terms /= "none"
    hull%speed_sway_yaw = s%speed_terms == "stf"
    if (s%manoeuvring == "mmg") call mmg_added_masses(hull, s)
  end subroutine new_hull

  !> The MMG ship's horizontal added masses (Yasukawa & Yoshimura 2015 eq. 4) in place of
  !> the box's: m_x, and m_y and J_z about midship moved to G (x_G forward of midship):
  !> kinetic energy 1/2 m_y (v_G - x_G r)^2 + 1/2 J_z r^2.
  pure subroutine mmg_added_masses(hull, s)
    type(hull_type), intent(inout) :: hull
    type(ship_config), intent(in) :: s
    real(wp) :: q, my
    q = 0.5_wp*rho_water*s%lpp**2*s%draught
    my = s%mmg%my*q
    hull%added_mass(1:2) = [s%mmg%mx*q, my]
    hull%added_inertia(3) = s%mmg%jz*q*s%lpp**2 + s%cg_x**2*my
    hull%added_sway_yaw = -s%cg_x*my
  end subroutine mmg_added_masses

  !> Kijima's linear derivatives with k = 2d/L: Y'_beta = (pi/2) k + 1.4 C_b B/L,
  !> (m' + m'_x) - Y'_r = 1.5 C_b B/L, N'_beta = k, N'_r = -0.54 k + k^2. With the drift
  !> angle beta = -v', Y'_v = -Y'_beta and N'_v = -N'_beta.
  pure subroutine kijima(hull, s)
    type(hull_type), intent(inout) :: hull
    type(ship_config), intent(in) :: s
    real(wp) :: k, mp, mxp
    k = 2.0_wp*s%draught/s%lpp
    mp = hull%mass/(0.5_wp*rho_water*s%lpp**2*s%draught)
    mxp = hull%added_mass(1)/(0.5_wp*rho_water*s%lpp**2*s%draught)
    hull%yv = -(0.5_wp*pi*k + 1.4_wp*s%cb*s%beam/s%lpp)
    hull%yr = mp + mxp - 1.5_wp*s%cb*s%beam/s%lpp
    hull%nv = -k
    hull%nr = -0.54_wp*k + k*k
  end subroutine kijima

  !> Undamped natural periods (heave, roll, pitch) of the model's own mass, added mass and
  !> restoring [s].
  pure function hull_natural_periods(hull) result(t)
    !> The hull (its masses, added masses and restoring).
    type(hull_type), intent(in) :: hull
    real(wp) :: t(3)
    t(1) = 2.0_wp*pi*sqrt((hull%mass + hull%added_mass(3))/hull%c33)
    t(2) = 2.0_wp*pi*sqrt((hull%inertia(1) + hull%added_inertia(1))/hull%c44)
    t(3) = 2.0_wp*pi*sqrt((hull%inertia(2) + hull%added_inertia(2))/hull%c55)
  end function hull_natural_periods

end module davit_ship_hull
