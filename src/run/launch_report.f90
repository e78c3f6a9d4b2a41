!> The launch log's findings in the output file: /events/impacts (one row per impact),
!> /peaks (step-resolved peak tensions and accelerations), /limits (the wire's and the
!> impact's limits, when first exceeded and for how long) and /seat (the occupant's
!> filtered acceleration).
module davit_run_launch_report
  use davit_kinds, only: wp, i8
  use davit_io_hdf5_writer, only: h5_writer_type
  use davit_run_impact_events, only: impact_tracker
  use davit_run_load_peaks, only: load_peaks, limit_watch
  use davit_run_seat_trace, only: seat_trace
  use davit_assess_rules, only: n_checks, rule_check, check_ids, check_units, check_sources, &
                                check_texts, check_lower, check_passes
  use davit_io_namelist, only: int_to_str
  use davit_io_text, only: fmt_fixed
  implicit none
  private
  public :: write_impacts, write_loads, write_seat, write_assessment, launch_text

contains

  subroutine write_impacts(w, tr)
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The impacts of the run.
    type(impact_tracker), intent(in) :: tr
    integer :: n
    n = tr%n
    call w%group("events/impacts")
    associate (e => tr%events(1:n))
      call w%write_1d("events/impacts/time", e%time, "s", "Onset of each impact (first "// &
                      "step with a contact force; resolved at every step, not sampled)", &
                      dims="impact")
      call w%write_1d_int("events/impacts/fender", int(e%fender, i8), "-", &
                          "Fender index (order of &contact fender_x)", dims="impact")
      call w%write_1d("events/impacts/speed", e%speed, "m/s", "Normal impact speed: "// &
                      "approach rate of the fender on the ship's side at onset (eq. 33)", &
                      dims="impact")
      call w%write_1d("events/impacts/peak_force", e%peak_force, "N", &
                      "Largest normal force of the fender during the impact", dims="impact")
      call w%write_1d("events/impacts/duration", e%duration, "s", "Contact duration "// &
                      "(to the first step without force; up to the end of the run if open)", &
                      dims="impact")
      call w%write_1d("events/impacts/peak_acceleration", e%peak_acceleration, "m/s^2", &
                      "Largest CG acceleration |Delta v/Delta t| over a step during it", &
                      dims="impact")
      call w%write_1d("events/impacts/peak_seat_acceleration_raw", e%peak_seat_raw, &
                      "m/s^2", "Largest step-mean seat acceleration during it", dims="impact")
      call w%write_1d("events/impacts/peak_seat_acceleration", e%peak_seat, "m/s^2", &
                      "Largest filtered seat acceleration from its onset to 0.2 s after "// &
                      "its end (/seat)", dims="impact")
    end associate
  end subroutine write_impacts

  subroutine write_loads(w, p)
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    !> Peak loads and limit exceedances.
    type(load_peaks), intent(in) :: p
    call w%group("peaks")
    call w%write_1d("peaks/sling_tension", p%sling, "N", "Largest tension of each sling "// &
                    "(fore, aft) over every step until release", dims="sling")
    call w%write_1d("peaks/sling_tension_time", p%sling_time, "s", "When", dims="sling")
    call w%write_1d("peaks/segment_tension", p%segment, "N", "Largest tension of each "// &
                    "cable segment (the falls) over every step until release", dims="segment")
    call w%write_1d("peaks/segment_tension_time", p%segment_time, "s", "When", dims="segment")
    call w%group("limits")
    call w%attr_real("limits", "minimum_breaking_load", p%mbl%value)
    call w%attr_real("limits", "safe_working_load", p%swl%value)
    call w%attr_real("limits", "impact_speed", p%impact%value)
    call w%attr_real("limits", "max_impact_speed", p%max_impact_speed)
    call write_limit(w, "limits/safe_working_load", p%swl, "Largest wire tension above "// &
                     "the safe working load (MBL / &limits safety_factor)")
    call write_limit(w, "limits/minimum_breaking_load", p%mbl, "Largest wire tension "// &
                     "above the minimum breaking load (EN 12385-4)")
    call write_limit(w, "limits/impact_speed", p%impact, "Impacts faster than the "// &
                     "LSA Code's lateral impact speed")
  end subroutine write_loads

  !> [first time, time beyond, excursions] of one limit (first = -1: never exceeded).
  subroutine write_limit(w, name, lw, text)
    type(h5_writer_type), intent(inout) :: w
    character(len=*), intent(in) :: name, text
    type(limit_watch), intent(in) :: lw
    call w%write_1d(name, [lw%first, lw%duration, real(lw%count, wp)], "s, s, -", &
                    text//": first time exceeded (-1 = never), time beyond (0 for "// &
                    "impacts), number of excursions", dims="first_beyond_count")
  end subroutine write_limit

  subroutine write_seat(w, s, a, point)
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The seat trace.
    type(seat_trace), intent(in) :: s
    !> The seat's filtered acceleration (3, n) [m/s^2]; the seat's point in the boat frame [m].
    real(wp), intent(in) :: a(:, :), point(3)
    call w%group("seat")
    call w%attr_real("seat", "interval", s%dt)
    call w%attr_real("seat", "filter_hz", s%cutoff)
    call w%write_1d("seat/point", point, "m", "Seat position in the boat frame (&limits seat)", &
                    dims="component")
    call w%write_2d("seat/acceleration", a, "m/s^2", "Seat acceleration (inertial, "// &
                    "gravity not subtracted) at t = (k - 1/2) interval, phaseless 4-pole "// &
                    "Butterworth low-pass, -3 dB at filter_hz (MSC/Circ.616 5.4, SAE J211)", &
                    dims="component seat_sample")
    call w%write_1d("seat/raw_peak", [s%raw_peak, s%raw_time], "m/s^2, s", "Largest "// &
                    "step-mean seat acceleration |Delta v/Delta t| and when", dims="value_time")
  end subroutine write_seat

  !> /assessment: one dataset per rule check, [value, limit, margin] (NaN: does not apply),
  !> with what it checks, its source and whether it passed; the davit head height H and the
  !> occupant's dynamic response indices.
  subroutine write_assessment(w, c, head_height, dr)
    !> The run's open output file.
    type(h5_writer_type), intent(inout) :: w
    !> The rule checks.
    type(rule_check), intent(in) :: c(n_checks)
    !> Davit head height H above the still water [m]; the occupant's dynamic response indices
    !> (positive, negative).
    real(wp), intent(in) :: head_height, dr(2)
    character(len=:), allocatable :: name
    integer :: k
    call w%group("assessment")
    call w%attr_real("assessment", "head_height", head_height)
    call w%attr_int("assessment", "failed", int(count(.not. check_passes(c)), i8))
    do k = 1, n_checks
      name = "assessment/"//trim(check_ids(k))
      call w%write_1d(name, [c(k)%value, c(k)%limit, c(k)%margin], &
                      trim(check_units(k))//", "//trim(check_units(k))//", -", &
                      trim(check_texts(k))//": value, limit, relative margin (>= 0 "// &
                      "passes; NaN: does not apply to this run)", dims="value_limit_margin")
      call w%attr_str(name, "source", trim(check_sources(k)))
      call w%attr_str(name, "verdict", verdict(c(k)))
    end do
    call w%write_1d("assessment/dynamic_response", dr, "-", "Peak dynamic response index "// &
                    "up the spine (seat pushed up) and down, the spine model on the "// &
                    "filtered seat acceleration along the boat's vertical axis", dims="up_down")
  end subroutine write_assessment

  elemental function verdict(c) result(text)
    type(rule_check), intent(in) :: c
    character(len=14) :: text
    if (c%margin /= c%margin .and. c%value == c%value) then
      text = "reported only"
    else if (c%margin /= c%margin) then
      text = "not applicable"
    else if (check_passes(c)) then
      text = "pass"
    else
      text = "FAIL"
    end if
  end function verdict

  !> The end-of-run summary: outcome, impacts, peaks and the rule checks, one per line.
  function launch_text(outcome, impacts, loads, seat_peak, c) result(text)
    !> How the launch ended, in words.
    character(len=*), intent(in) :: outcome
    !> The impacts of the run.
    type(impact_tracker), intent(in) :: impacts
    !> Peak loads and limit exceedances.
    type(load_peaks), intent(in) :: loads
    !> Largest filtered seat acceleration [m/s^2].
    real(wp), intent(in) :: seat_peak
    !> The rule checks.
    type(rule_check), intent(in) :: c(n_checks)
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = new_line("a")
    integer :: k
    text = ""
    if (len(outcome) > 0) text = "launch: "//outcome//nl
    text = text//"impacts: "//int_to_str(impacts%n)//", fastest "// &
           num(loads%max_impact_speed)//" m/s; peak fall tension "// &
           num(max(0.0_wp, maxval(loads%segment))/1.0e3_wp)//" kN, peak sling tension "// &
           num(max(0.0_wp, maxval(loads%sling))/1.0e3_wp)//" kN; peak seat acceleration "// &
           num(seat_peak)//" m/s^2 (filtered)"//nl
    text = text//"rule checks (value vs limit, margin; /assessment):"
    do k = 1, n_checks
      text = text//nl//"  "//pad(check_ids(k), 15)//pad(verdict(c(k)), 15)
      if (c(k)%margin == c(k)%margin) then
        text = text//pad(shown(c(k)%value, k)//merge(" >= ", " <= ", check_lower(k))// &
                         shown(c(k)%limit, k), 30)//pad(num(100.0_wp*c(k)%margin)//" %", 10)
      else if (c(k)%value == c(k)%value) then
        text = text//pad(shown(c(k)%value, k), 40)
      end if
      text = text//trim(check_sources(k))
    end do
  end function launch_text

  !> A value of check k in its display unit (kN for forces).
  function shown(x, k) result(s)
    real(wp), intent(in) :: x
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    if (trim(check_units(k)) == "N") then
      s = num(x/1.0e3_wp)//" kN"
    else
      s = num(x)//" "//trim(check_units(k))
    end if
  end function shown

  !> x to about 3-4 significant digits.
  function num(x) result(s)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=24) :: buf
    if ((abs(x) < 1.0e-3_wp .and. x /= 0.0_wp) .or. abs(x) >= 1.0e4_wp) then
      write (buf, "(es10.3)") x
      s = trim(adjustl(buf))
    else
      s = fmt_fixed(x, merge(3, 1, abs(x) < 10.0_wp))
    end if
  end function num

  function pad(s, n) result(t)
    character(len=*), intent(in) :: s
    integer, intent(in) :: n
    character(len=max(n, len_trim(s) + 1)) :: t
    t = trim(s)
  end function pad

end module davit_run_launch_report
