!> The rule checks a davit launch is judged by (../shared/spec/standards.md), as data: each
!> check's id, what it measures, its source and whether its limit bounds from below or
!> above; and one check's verdict from a measured value and its limit.
!>
!> The margin is relative and signed so that >= 0 passes: (limit - value)/limit for an
!> upper limit, (value - limit)/limit for a lower one. A check that does not apply to a run
!> (no emergency stop scripted, no hook release, the boat not on the davit) has NaN value,
!> limit and margin.
module davit_assess_rules
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
  use davit_kinds, only: wp
  implicit none
  private
  public :: n_checks, check_ids, check_units, check_sources, check_texts, check_lower
  public :: rule_check, new_check, not_applicable, check_passes
  public :: check_lowering_speed, check_impact_speed, check_fall_swl, check_fall_mbl
  public :: check_sling_swl, check_sling_mbl, check_brake_load, check_release_load
  public :: check_seat_srss, check_seat_dri

  integer, parameter :: n_checks = 10
  integer, parameter :: check_lowering_speed = 1, check_impact_speed = 2, check_fall_swl = 3
  integer, parameter :: check_fall_mbl = 4, check_sling_swl = 5, check_sling_mbl = 6
  integer, parameter :: check_brake_load = 7, check_release_load = 8, check_seat_srss = 9
  integer, parameter :: check_seat_dri = 10

  !> Ids (HDF5 names /assessment/<id>, sweep columns results/check_<id>_*; postproc/layout.py
  !> CHECKS holds the same list).
  character(len=*), parameter :: check_ids(n_checks) = [character(len=14) :: &
    "lowering_speed", "impact_speed", "fall_swl", "fall_mbl", "sling_swl", "sling_mbl", &
    "brake_load", "release_load", "seat_srss", "seat_dri"]
  character(len=*), parameter :: check_units(n_checks) = [character(len=5) :: &
    "m/s", "m/s", "N", "N", "N", "N", "N", "N", "m/s^2", "-"]
  !> .true.: the value must be at least the limit; .false.: at most.
  logical, parameter :: check_lower(n_checks) = [.true., .false., .false., .false., .false., &
                                                 .false., .false., .false., .false., .false.]
  character(len=*), parameter :: check_sources(n_checks) = [character(len=40) :: &
    "LSA Code 6.1.2 (0.4 + 0.02 H)", "LSA Code 4.4.1 (3.5 m/s)", "LSA Code 6.1.1.6 (6x)", &
    "EN 12385-4 MBL", "LSA Code 6.1.1.6 (6x)", "EN 12385-4 MBL", &
    "LSA Code 6.1.2.5.2 (1.1x)", "LSA Code 4.4.7.6 (1.1x)", &
    "MSC/Circ.616 6.8.3 (indicative)", "DRI 18 (indicative)"]
  character(len=*), parameter :: check_texts(n_checks) = [character(len=110) :: &
    "lowering speed after the initial acceleration >= 0.4 + 0.02 H (H: davit head height)", &
    "fastest normal impact on the ship's side <= the lateral impact speed withstood", &
    "peak fall (cable segment) tension <= safe working load MBL / safety_factor", &
    "peak fall (cable segment) tension <= minimum breaking load", &
    "peak sling tension <= safe working load MBL / safety_factor", &
    "peak sling tension <= minimum breaking load", &
    "peak fall tension in an emergency stop <= 1.1 x the fall load before it", &
    "hook load at release (both hooks together) <= 1.1 x the loaded boat's weight", &
    "peak filtered seat acceleration (SRSS of the boat axes) <= &limits srss_limit", &
    "dynamic response index up the spine <= &limits dri_limit"]

  type :: rule_check
    !> Measured value, its limit (same unit) and the margin 1 - value/limit (negative: failed).
    real(wp) :: value = 0.0_wp, limit = 0.0_wp, margin = 0.0_wp
  end type rule_check

contains

  !> Check k with the measured value and its limit (limit > 0).
  pure function new_check(k, value, limit) result(c)
    !> Index of the check in check_ids (1..n_checks).
    integer, intent(in) :: k
    !> Measured value and its limit (> 0), in the check's unit (check_units).
    real(wp), intent(in) :: value, limit
    type(rule_check) :: c
    c%value = value
    c%limit = limit
    if (check_lower(k)) then
      c%margin = (value - limit)/limit
    else
      c%margin = (limit - value)/limit
    end if
  end function new_check

  !> A check that does not apply to the run: NaN throughout.
  function not_applicable() result(c)
    type(rule_check) :: c
    c%value = ieee_value(c%value, ieee_quiet_nan)
    c%limit = c%value
    c%margin = c%value
  end function not_applicable

  !> Passed (margin >= 0); a check that does not apply passes.
  elemental logical function check_passes(c)
    !> The check.
    type(rule_check), intent(in) :: c
    check_passes = ieee_is_nan(c%margin) .or. c%margin >= 0.0_wp
  end function check_passes

end module davit_assess_rules
