!> Eq. (2) rotation matrix and eq. (5) Euler kinematics.
module test_rotation
  use davit_kinds, only: wp
  use davit_core_rotation, only: rotation_matrix, euler_rates, skew, length3
  use harness, only: suite_type, case_state, new_case, check
  implicit none
  private
  public :: collect_rotation

  real(wp), parameter :: angles(3, 4) = reshape([0.3_wp, -0.2_wp, 1.1_wp, &
    -0.7_wp, 0.4_wp, -2.5_wp, 0.05_wp, 1.2_wp, 0.0_wp, 1.4_wp, -1.0_wp, 3.0_wp], [3, 4])

contains

  function collect_rotation() result(suite)
    type(suite_type) :: suite
    suite%name = "rotation"
    suite%cases = [new_case("orthonormal", orthonormal), &
                   new_case("elementary_axes", elementary_axes), &
                   new_case("euler_rates_vs_finite_difference", euler_rates_fd), &
                   new_case("length3_is_the_euclidean_length", length_cases)]
  end function collect_rotation

  !> C^T C = I and det C = +1 for several attitudes.
  subroutine orthonormal(state)
    type(case_state), intent(inout) :: state
    real(wp) :: c(3, 3), ctc(3, 3), det
    integer :: k, i, j
    do k = 1, size(angles, 2)
      c = rotation_matrix(angles(:, k))
      ctc = matmul(transpose(c), c)
      do j = 1, 3
        do i = 1, 3
          call check(state, ctc(i, j), merge(1.0_wp, 0.0_wp, i == j), "C^T C", abs_tol=1e-14_wp)
        end do
      end do
      det = c(1, 1)*(c(2, 2)*c(3, 3) - c(2, 3)*c(3, 2)) - c(1, 2)*(c(2, 1)*c(3, 3) - &
            c(2, 3)*c(3, 1)) + c(1, 3)*(c(2, 1)*c(3, 2) - c(2, 2)*c(3, 1))
      call check(state, det, 1.0_wp, "det C", abs_tol=1e-14_wp)
    end do
  end subroutine orthonormal

  !> A pure yaw of +90 deg maps body x (forward) to inertial y; a pure roll of +90 deg maps
  !> body y (starboard) to inertial z (down): right-handed ZYX with N3 down.
  subroutine elementary_axes(state)
    type(case_state), intent(inout) :: state
    real(wp) :: v(3)
    v = matmul(rotation_matrix([0.0_wp, 0.0_wp, acos(0.0_wp)]), [1.0_wp, 0.0_wp, 0.0_wp])
    call check(state, v(2), 1.0_wp, "yaw 90: x_b -> y_N", abs_tol=1e-15_wp)
    v = matmul(rotation_matrix([acos(0.0_wp), 0.0_wp, 0.0_wp]), [0.0_wp, 1.0_wp, 0.0_wp])
    call check(state, v(3), 1.0_wp, "roll 90: y_b -> z_N", abs_tol=1e-15_wp)
    v = matmul(rotation_matrix([0.0_wp, acos(0.0_wp), 0.0_wp]), [1.0_wp, 0.0_wp, 0.0_wp])
    call check(state, v(3), -1.0_wp, "pitch 90: x_b -> -z_N (bow up)", abs_tol=1e-15_wp)
  end subroutine elementary_axes

  !> dC/dt = C skew(omega): the Euler rates of eq. (5) advanced by a central difference of
  !> eq. (2) must reproduce the body angular velocity omega.
  subroutine euler_rates_fd(state)
    type(case_state), intent(inout) :: state
    real(wp), parameter :: h = 1.0e-5_wp
    real(wp) :: omega(3), rates(3), dc(3, 3), w(3, 3), s(3, 3)
    integer :: k, i, j
    omega = [0.4_wp, -1.3_wp, 0.8_wp]
    s = skew(omega)
    do k = 1, size(angles, 2)
      rates = euler_rates(angles(:, k), omega)
      dc = (rotation_matrix(angles(:, k) + h*rates) - rotation_matrix(angles(:, k) - h*rates)) &
           /(2.0_wp*h)
      w = matmul(transpose(rotation_matrix(angles(:, k))), dc)
      do j = 1, 3
        do i = 1, 3
          call check(state, w(i, j), s(i, j), "C^T dC/dt = skew(omega)", &
                     abs_tol=1e-8_wp)
        end do
      end do
    end do
  end subroutine euler_rates_fd

  !> length3 against Pythagoras by hand (3-4-12 -> 13, exact in binary) and against the
  !> intrinsic NORM2 within 4 ulp on 1000 random vectors from 1e-100 to 1e100 m.
  subroutine length_cases(state)
    type(case_state), intent(inout) :: state
    real(wp) :: a(3), worst, scale
    integer :: i
    call check(state, length3([3.0_wp, -4.0_wp, 12.0_wp]), 13.0_wp, "|(3, -4, 12)|", &
               abs_tol=0.0_wp)
    call check(state, length3([0.0_wp, 0.0_wp, 0.0_wp]), 0.0_wp, "|0|", abs_tol=0.0_wp)
    worst = 0.0_wp
    do i = 1, 1000
      call random_number(a)
      call random_number(scale)
      a = (a - 0.5_wp)*10.0_wp**(200.0_wp*scale - 100.0_wp)
      worst = max(worst, abs(length3(a) - norm2(a))/(spacing(norm2(a))))
    end do
    call check(state, worst, 0.0_wp, "largest difference from NORM2 (ulp)", abs_tol=4.0_wp)
  end subroutine length_cases

end module test_rotation
