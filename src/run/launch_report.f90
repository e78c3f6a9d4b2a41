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
  implicit none
  private
  public :: write_impacts, write_loads, write_seat

contains

  subroutine write_impacts(w, tr)
    type(h5_writer_type), intent(inout) :: w
    type(impact_tracker), intent(in) :: tr
    integer :: n
    n = tr%n
    call w%group("events/impacts")
    associate (e => tr%events(1:n))
      call w%write_1d("events/impacts/time", e%time, "s", "Onset of each impact (first "// &
                      "step with a contact force; resolved at every step, not sampled)")
      call w%write_1d_int("events/impacts/fender", int(e%fender, i8), "-", &
                          "Fender index (order of &contact fender_x)")
      call w%write_1d("events/impacts/speed", e%speed, "m/s", "Normal impact speed: "// &
                      "approach rate of the fender on the ship's side at onset (eq. 33)")
      call w%write_1d("events/impacts/peak_force", e%peak_force, "N", &
                      "Largest normal force of the fender during the impact")
      call w%write_1d("events/impacts/duration", e%duration, "s", "Contact duration "// &
                      "(to the first step without force; up to the end of the run if open)")
      call w%write_1d("events/impacts/peak_acceleration", e%peak_acceleration, "m/s^2", &
                      "Largest CG acceleration |Delta v/Delta t| over a step during it")
      call w%write_1d("events/impacts/peak_seat_acceleration_raw", e%peak_seat_raw, &
                      "m/s^2", "Largest step-mean seat acceleration during it")
      call w%write_1d("events/impacts/peak_seat_acceleration", e%peak_seat, "m/s^2", &
                      "Largest filtered seat acceleration from its onset to 0.2 s after "// &
                      "its end (/seat)")
    end associate
  end subroutine write_impacts

  subroutine write_loads(w, p)
    type(h5_writer_type), intent(inout) :: w
    type(load_peaks), intent(in) :: p
    call w%group("peaks")
    call w%write_1d("peaks/sling_tension", p%sling, "N", "Largest tension of each sling "// &
                    "(fore, aft) over every step until release")
    call w%write_1d("peaks/sling_tension_time", p%sling_time, "s", "When")
    call w%write_1d("peaks/segment_tension", p%segment, "N", "Largest tension of each "// &
                    "cable segment (the falls) over every step until release")
    call w%write_1d("peaks/segment_tension_time", p%segment_time, "s", "When")
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
                    "impacts), number of excursions")
  end subroutine write_limit

  subroutine write_seat(w, s, a, point)
    type(h5_writer_type), intent(inout) :: w
    type(seat_trace), intent(in) :: s
    real(wp), intent(in) :: a(:, :), point(3)
    call w%group("seat")
    call w%attr_real("seat", "interval", s%dt)
    call w%attr_real("seat", "filter_hz", s%cutoff)
    call w%write_1d("seat/point", point, "m", "Seat position in the boat frame (&limits seat)")
    call w%write_2d("seat/acceleration", a, "m/s^2", "Seat acceleration (inertial, "// &
                    "gravity not subtracted) at t = (k - 1/2) interval, phaseless 4-pole "// &
                    "Butterworth low-pass, -3 dB at filter_hz (MSC/Circ.616 5.4, SAE J211)")
    call w%write_1d("seat/raw_peak", [s%raw_peak, s%raw_time], "m/s^2, s", "Largest "// &
                    "step-mean seat acceleration |Delta v/Delta t| and when")
  end subroutine write_seat

end module davit_run_launch_report
