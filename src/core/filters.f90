!> Phaseless low-pass filtering of a uniformly sampled signal, as crash-test practice does
!> (SAE J211-1 / ISO 6487): a 2-pole Butterworth section by the bilinear transform, run
!> forward and then backward, so the result has no phase lag and a 4-pole magnitude
!> |H(f)| = 1/(1 + (f/f0)^4). Its -3 dB frequency fc is asked for; each pass's corner is then
!> f0 = fc/(sqrt(2) - 1)^(1/4) = 1.2465 fc (J211's 2.0775 CFC with fc = 1.6667 CFC).
module davit_core_filters
  use davit_kinds, only: wp, pi
  implicit none
  private
  public :: phaseless_lowpass, lowpass_in_place

contains

  !> x filtered with -3 dB at fc [Hz], sampled every dt [s]; the ends are padded with their
  !> first and last value so a signal at rest starts and ends without a transient.
  pure function phaseless_lowpass(x, dt, fc) result(y)
    !> Signal x sampled every dt [s]; fc the -3 dB frequency of the filter [Hz].
    real(wp), intent(in) :: x(:), dt, fc
    ! on the heap: the signal is as long as the run (a 1 kHz seat trace of t_end)
    real(wp), allocatable :: y(:)
    y = x
    call lowpass_in_place(y, dt, fc)
  end function phaseless_lowpass

  !> phaseless_lowpass of y in place: no copy of a signal as long as the run (y may be a
  !> strided row of a component table).
  pure subroutine lowpass_in_place(y, dt, fc)
    !> Signal, filtered in place.
    real(wp), intent(inout) :: y(:)
    !> Sampling interval dt [s] and -3 dB frequency fc [Hz].
    real(wp), intent(in) :: dt, fc
    real(wp) :: a(3), b(2)
    call butterworth2(dt, fc/(sqrt(2.0_wp) - 1.0_wp)**0.25_wp, a, b)
    call one_pass(y, a, b, .true.)
    call one_pass(y, a, b, .false.)
  end subroutine lowpass_in_place

  !> Coefficients of the 2-pole Butterworth low-pass with corner f0 (prewarped bilinear
  !> transform): y_n = a1 x_n + a2 x_n-1 + a3 x_n-2 + b1 y_n-1 + b2 y_n-2.
  pure subroutine butterworth2(dt, f0, a, b)
    !> Sampling interval dt [s] and the pass's corner frequency f0 [Hz].
    real(wp), intent(in) :: dt, f0
    !> Feed-forward a and feedback b coefficients of the recursion.
    real(wp), intent(out) :: a(3), b(2)
    real(wp) :: wa, den
    wa = tan(pi*f0*dt)
    den = 1.0_wp + sqrt(2.0_wp)*wa + wa**2
    a = [1.0_wp, 2.0_wp, 1.0_wp]*wa**2/den
    b = [-2.0_wp*(wa**2 - 1.0_wp), -1.0_wp + sqrt(2.0_wp)*wa - wa**2]/den
  end subroutine butterworth2

  !> One causal pass in place, forward (or backward in time: from the last value to the
  !> first), started at rest at the first value it meets.
  pure subroutine one_pass(y, a, b, forward)
    !> Signal, filtered in place.
    real(wp), intent(inout) :: y(:)
    !> Feed-forward a and feedback b coefficients (butterworth2).
    real(wp), intent(in) :: a(3), b(2)
    !> True for a pass forward in time, false for one backward.
    logical, intent(in) :: forward
    real(wp) :: x0, x1, x2, y1, y2
    integer :: n, first, last, stride
    if (size(y) == 0) return
    if (forward) then
      first = 1
      last = size(y)
      stride = 1
    else
      first = size(y)
      last = 1
      stride = -1
    end if
    x1 = y(first)
    x2 = y(first)
    y1 = y(first)
    y2 = y(first)
    do n = first, last, stride
      x0 = y(n)
      y(n) = a(1)*x0 + a(2)*x1 + a(3)*x2 + b(1)*y1 + b(2)*y2
      x2 = x1
      x1 = x0
      y2 = y1
      y1 = y(n)
    end do
  end subroutine one_pass

end module davit_core_filters
