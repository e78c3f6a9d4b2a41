!> Deck keys of the load and impact limits a run is checked against (group "limits"), and
!> of the occupant's acceleration (a seat position and the filter of crash-test practice).
!>
!> The wire's minimum breaking load follows EN 12385-4: MBL = K d^2 R_r, d the nominal
!> diameter, R_r the rope grade and K the minimum breaking force factor of the rope's
!> construction (0.356 for 6x36WS-IWRC). The falls' safe working load is MBL over the LSA
!> Code's factor of safety 6 (6.1.1: falls, links and blocks). 3.5 m/s is the lateral
!> impact speed a lifeboat must withstand against a rigid vertical surface (LSA Code 4.4.1,
!> MSC.81(70) 1.6). The seat filter follows MSC/Circ.616 5.4 (frequencies above 20 Hz do
!> not act on the body), applied as SAE J211's phaseless 4-pole Butterworth.
module davit_io_limits_keys
  use davit_kinds, only: wp
  use davit_io_deck_reader, only: deck_reader_type
  implicit none
  private
  public :: limits_config, read_limits, minimum_breaking_load

  type :: limits_config
    !> Rope grade [Pa], breaking force factor K [-], falls' factor of safety [-].
    real(wp) :: grade, breaking_factor, safety_factor
    !> Lateral impact speed limit [m/s].
    real(wp) :: impact_speed
    !> Seat position in the boat frame [m], the occupant filter's -3 dB frequency [Hz] and
    !> the interval its input is resampled at [s].
    real(wp) :: seat(3), seat_filter, seat_interval
    !> The occupant: SRSS limit of the filtered seat acceleration [m/s^2] (0 = none); the spine
    !> model's natural frequency [rad/s], damping ratio [-] and DRI limit [-].
    real(wp) :: srss_limit, dr_frequency, dr_damping, dri_limit
  end type limits_config

contains

  subroutine read_limits(r, s)
    !> The deck's reader, positioned at the &limits group.
    type(deck_reader_type), intent(inout) :: r
    !> The &limits values, defaults in, the deck's read over them.
    type(limits_config), intent(inout) :: s
    character(len=*), parameter :: g = "limits"
    call r%real(g, "grade", s%grade, 1960.0e6_wp, 1.0e8_wp, 3.0e9_wp, "Pa", &
                "Rope grade R_r of slings and cable (EN 12385-4: 1770, 1960 or 2160 "// &
                "N/mm^2).")
    call r%real(g, "breaking_factor", s%breaking_factor, 0.356_wp, 0.1_wp, 1.0_wp, "-", &
                "Minimum breaking force factor K, MBL = K d^2 R_r (EN 12385-4: 0.356 "// &
                "for 6x36WS-IWRC; 20 mm grade 1960 gives 279 kN).")
    call r%real(g, "safety_factor", s%safety_factor, 6.0_wp, 1.0_wp, 20.0_wp, "-", &
                "Safe working load = MBL / this (LSA Code 6.1.1: 6 for falls).")
    call r%real(g, "impact_speed", s%impact_speed, 3.5_wp, 0.0_wp, 20.0_wp, "m/s", &
                "Normal impact speed against the ship's side a lifeboat must withstand "// &
                "(LSA Code 4.4.1: 3.5 m/s, fenders fitted).", lo_open=.true.)
    call r%real_vec(g, "seat", s%seat, [3.0_wp, -1.0_wp, 0.0_wp], -50.0_wp, 50.0_wp, "m", &
                    "Occupant seat in the boat frame where the acceleration is reported "// &
                    "(MSC/Circ.616 5.1.3: the most forward seat by the side wall; here the "// &
                    "side facing the ship).")
    call r%real(g, "seat_filter", s%seat_filter, 20.0_wp, 1.0_wp, 1000.0_wp, "Hz", &
                "-3 dB frequency of the seat acceleration's phaseless 4-pole Butterworth "// &
                "low-pass (MSC/Circ.616 5.4: 20 Hz; SAE J211 form).")
    call r%real(g, "seat_interval", s%seat_interval, 1.0e-3_wp, 1.0e-5_wp, 0.01_wp, "s", &
                "Interval the seat velocity is resampled at before filtering (>= 10 "// &
                "samples per filter period).")
    call read_occupant(r, s)
  end subroutine read_limits

  !> The occupant's acceleration limits and dynamic response model, indicative for davit
  !> launches (MSC/Circ.616 was written for free-fall lifeboats).
  subroutine read_occupant(r, s)
    type(deck_reader_type), intent(inout) :: r
    type(limits_config), intent(inout) :: s
    character(len=*), parameter :: g = "limits"
    call r%real(g, "srss_limit", s%srss_limit, 0.0_wp, 0.0_wp, 1.0e4_wp, "m/s^2", &
                "Limit of the filtered seat acceleration's SRSS over the boat's axes "// &
                "(MSC/Circ.616 6.8.3 names the criterion; its number was not confirmed "// &
                "from a source, so 0 = reported without a limit).")
    call r%real(g, "dri_frequency", s%dr_frequency, 52.9_wp, 1.0_wp, 1.0e3_wp, "rad/s", &
                "Natural frequency of the spine's dynamic response model (52.9 rad/s: "// &
                "the seated occupant's vertical axis, MSC/Circ.616, STANAG 4569).")
    call r%real(g, "dri_damping", s%dr_damping, 0.224_wp, 0.0_wp, 2.0_wp, "-", &
                "Damping ratio of the spine model (0.224, same sources).")
    call r%real(g, "dri_limit", s%dri_limit, 18.0_wp, 0.0_wp, 1.0e3_wp, "-", &
                "Limit of the dynamic response index DRI = omega^2 delta_max / g up the "// &
                "spine (18: about 5 % probability of spinal injury, ejection-seat "// &
                "practice; STANAG 4569 gives 17.7 for 10 % serious injury).", lo_open=.true.)
  end subroutine read_occupant

  !> EN 12385-4 minimum breaking load [N] of a rope of diameter d [m].
  pure real(wp) function minimum_breaking_load(s, d)
    !> The &limits values (rope grade, breaking force factor).
    type(limits_config), intent(in) :: s
    !> Rope diameter [m].
    real(wp), intent(in) :: d
    minimum_breaking_load = s%breaking_factor*d**2*s%grade
  end function minimum_breaking_load

end module davit_io_limits_keys
