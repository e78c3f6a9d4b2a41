!> The real columns of a sweep summary, one table each for /cases and /results that the
!> writer (davit_sweep_summary), the reader (davit_sweep_summary_reader) and the row codec
!> (davit_sweep_row_codec) loop over: a result row's reals in declaration order
!> (`real_fields`, set back by `set_reals`), then the rule checks' values, limits and
!> margins; a case's reals (`case_fields`, set back by `set_case_fields`).
module davit_sweep_result_columns
  use davit_kinds, only: wp
  use davit_sweep_metrics, only: case_result
  use davit_sweep_cases, only: sweep_case
  use davit_assess_rules, only: n_checks
  implicit none
  private
  public :: column_doc, result_columns, n_result_columns, nreal_fields, real_fields, set_reals
  public :: case_columns, n_case_columns, case_fields, set_case_fields

  !> A real column of /results: its name, units and description.
  type :: column_doc
    !> Dataset name under /results.
    character(len=32) :: name
    !> Units of the column.
    character(len=8) :: units
    !> What the column holds (trailing blanks are not part of it).
    character(len=160) :: text
  end type column_doc

  !> The fields' note of the columns that only a run case defines.
  character(len=*), parameter :: defined = " (status 1 only; NaN otherwise)"

  !> The reals of a row before its rule checks.
  integer, parameter :: n_result_columns = 15
  !> All reals of a row: the columns, then the checks' values, limits and margins.
  integer, parameter :: nreal_fields = n_result_columns + 3*n_checks

  !> The columns in the declaration order of case_result.
  type(column_doc), parameter :: result_columns(n_result_columns) = [ &
    column_doc("min_clearance", "m", "Smallest fender-to-ship-side distance over the "// &
               "lowering; negative = indentation"//defined), &
    column_doc("peak_horizontal_acceleration", "m/s^2", "Largest horizontal CG "// &
               "acceleration |(a_x, a_y)|, mean over each step"//defined), &
    column_doc("peak_vertical_acceleration", "m/s^2", "Largest vertical CG acceleration "// &
               "|a_z| (gravity not subtracted: 0 hanging at rest), mean over each step"// &
               defined), &
    column_doc("peak_segment_tension", "N", "Largest tension of any cable or sling "// &
               "segment over the lowering"//defined), &
    column_doc("first_contact_time", "s", "Time of the first fender contact over the "// &
               "lowering; -1 = none"//defined), &
    column_doc("waterborne_time", "s", "Time the boat became waterborne; -1 = never"// &
               defined), &
    column_doc("end_time", "s", "End of the lowering window: hook release, or the end "// &
               "of the run"//defined), &
    column_doc("wall_time", "s", "Compute time of the case (one thread); NaN if not run"), &
    column_doc("peak_sling_tension", "N", "Largest sling tension over every step until "// &
               "release"//defined), &
    column_doc("peak_fall_tension", "N", "Largest cable-segment (fall) tension over "// &
               "every step until release"//defined), &
    column_doc("max_impact_speed", "m/s", "Fastest normal impact on the ship's side "// &
               "(0 = none)"//defined), &
    column_doc("peak_seat_acceleration", "m/s^2", "Largest filtered seat acceleration "// &
               "(&limits seat, seat_filter)"//defined), &
    column_doc("swl_exceeded_time", "s", "First time a wire tension exceeded the safe "// &
               "working load; -1 = never"//defined), &
    column_doc("mbl_exceeded_time", "s", "First time a wire tension exceeded the "// &
               "minimum breaking load; -1 = never"//defined), &
    column_doc("impact_speed_exceeded_time", "s", "First impact faster than &limits "// &
               "impact_speed; -1 = never"//defined)]

  !> The reals of a case.
  integer, parameter :: n_case_columns = 7

  !> The /cases columns of a case's reals, in the order of case_fields.
  type(column_doc), parameter :: case_columns(n_case_columns) = [ &
    column_doc("wind_speed", "m/s", "Wind speed"), &
    column_doc("wave_height", "m", "Wave height (regular: 2a; irregular: H of eq. 44)"), &
    column_doc("wave_period", "s", "Regular-wave period (irregular: sets only the ramp)"), &
    column_doc("angle_deg", "deg", "Encounter angle chi: wave direction from N1 towards "// &
               "N2, ship heading N1"), &
    column_doc("clearance_b", "-", "Initial fender-to-ship-side distance in boat widths"), &
    column_doc("dt", "s", "Time step"), &
    column_doc("phase_deg", "deg", "Regular-wave phase epsilon at the origin at t = 0 "// &
               "(irregular: unused, the seed sets the phases)")]

contains

  !> The case's reals in the order of case_columns.
  pure function case_fields(c) result(x)
    !> The case whose reals are listed.
    type(sweep_case), intent(in) :: c
    real(wp) :: x(n_case_columns)
    x = [c%wind_speed, c%wave_height, c%wave_period, c%angle_deg, c%clearance_b, c%dt, &
         c%phase_deg]
  end function case_fields

  !> The case's reals set from x, in the order of case_columns.
  pure subroutine set_case_fields(c, x)
    !> The case whose reals are set.
    type(sweep_case), intent(inout) :: c
    !> Its reals in the order of case_columns.
    real(wp), intent(in) :: x(n_case_columns)
    c%wind_speed = x(1)
    c%wave_height = x(2)
    c%wave_period = x(3)
    c%angle_deg = x(4)
    c%clearance_b = x(5)
    c%dt = x(6)
    c%phase_deg = x(7)
  end subroutine set_case_fields

  !> The row's reals: the columns in declaration order, then the checks' values, limits
  !> and margins.
  pure function real_fields(row) result(x)
    !> The summary row whose reals are listed.
    type(case_result), intent(in) :: row
    real(wp) :: x(nreal_fields)
    x = [row%min_clearance, row%peak_horizontal_acceleration, &
         row%peak_vertical_acceleration, row%peak_segment_tension, row%first_contact_time, &
         row%waterborne_time, row%end_time, row%wall_time, row%peak_sling_tension, &
         row%peak_fall_tension, row%max_impact_speed, row%peak_seat_acceleration, &
         row%swl_exceeded_time, row%mbl_exceeded_time, row%impact_speed_exceeded_time, &
         row%check_value, row%check_limit, row%check_margin]
  end function real_fields

  !> The row's reals set from x, in the order of real_fields.
  pure subroutine set_reals(row, x)
    !> The summary row whose reals are set.
    type(case_result), intent(inout) :: row
    !> The row's reals in declaration order, then the checks' values, limits and margins.
    real(wp), intent(in) :: x(nreal_fields)
    row%min_clearance = x(1)
    row%peak_horizontal_acceleration = x(2)
    row%peak_vertical_acceleration = x(3)
    row%peak_segment_tension = x(4)
    row%first_contact_time = x(5)
    row%waterborne_time = x(6)
    row%end_time = x(7)
    row%wall_time = x(8)
    row%peak_sling_tension = x(9)
    row%peak_fall_tension = x(10)
    row%max_impact_speed = x(11)
    row%peak_seat_acceleration = x(12)
    row%swl_exceeded_time = x(13)
    row%mbl_exceeded_time = x(14)
    row%impact_speed_exceeded_time = x(15)
    row%check_value = x(16:15 + n_checks)
    row%check_limit = x(16 + n_checks:15 + 2*n_checks)
    row%check_margin = x(16 + 2*n_checks:15 + 3*n_checks)
  end subroutine set_reals

end module davit_sweep_result_columns
