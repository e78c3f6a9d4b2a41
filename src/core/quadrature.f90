!> Fixed Gauss-Legendre rule shared by the panel integrals and the hull-length integrals.
module davit_core_quadrature
  use davit_kinds, only: wp
  implicit none
  private
  public :: gauss8_x, gauss8_w

  !> 8-point Gauss-Legendre nodes and weights on (-1, 1).
  real(wp), parameter :: gauss8_x(8) = [-0.9602898564975363_wp, -0.7966664774136267_wp, &
    -0.5255324099163290_wp, -0.1834346424956498_wp, 0.1834346424956498_wp, &
    0.5255324099163290_wp, 0.7966664774136267_wp, 0.9602898564975363_wp]
  real(wp), parameter :: gauss8_w(8) = [0.1012285362903763_wp, 0.2223810344533745_wp, &
    0.3137066458778873_wp, 0.3626837833783620_wp, 0.3626837833783620_wp, &
    0.3137066458778873_wp, 0.2223810344533745_wp, 0.1012285362903763_wp]
end module davit_core_quadrature
