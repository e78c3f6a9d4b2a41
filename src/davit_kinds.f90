!> Working precision and physical constants (review G28).
module davit_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: wp, i8, pi, gravity, rho_water, rho_air, davit_version

  !> The one real kind of the project.
  integer, parameter :: wp = real64
  integer, parameter :: i8 = int64
  real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp
  !> Gravity [m/s^2], sea-water and air density [kg/m^3] (review G28).
  real(wp), parameter :: gravity = 9.81_wp
  real(wp), parameter :: rho_water = 1025.0_wp
  real(wp), parameter :: rho_air = 1.225_wp
  character(len=*), parameter :: davit_version = "0.1.0"
end module davit_kinds
