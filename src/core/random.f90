!> Deterministic, thread-safe random numbers: L'Ecuyer's MRG32k3a (Oper. Res. 47, 1999),
!> whose state lives in the caller's rng_type (no global state, so a sweep gives the same
!> numbers for a case whatever the thread count). Integer arithmetic stays below 2^53, so
!> there is no reliance on integer overflow.
module davit_core_random
  use davit_kinds, only: wp, i8
  implicit none
  private
  public :: rng_type, new_rng, rng_uniform

  integer(i8), parameter :: m1 = 4294967087_i8, m2 = 4294944443_i8
  integer(i8), parameter :: a12 = 1403580_i8, a13n = 810728_i8
  integer(i8), parameter :: a21 = 527612_i8, a23n = 1370589_i8

  type :: rng_type
    integer(i8) :: s1(3) = [12345_i8, 12345_i8, 12345_i8]
    integer(i8) :: s2(3) = [12345_i8, 12345_i8, 12345_i8]
  end type rng_type

contains

  !> A generator seeded from `seed` and an optional `stream` index (e.g. a sweep case):
  !> the pair is mixed by a 32-bit LCG into the six state words, then 16 outputs are dropped.
  function new_rng(seed, stream) result(rng)
    integer, intent(in) :: seed
    integer, intent(in), optional :: stream
    type(rng_type) :: rng
    integer(i8) :: x
    real(wp) :: dummy
    integer :: i
    x = modulo(int(seed, i8), 4294967296_i8)
    if (present(stream)) x = modulo(x + 2654435761_i8*modulo(int(stream, i8), 65536_i8) + &
                                    int(stream, i8)/65536_i8, 4294967296_i8)
    do i = 1, 3
      x = lcg(x)
      rng%s1(i) = 1_i8 + modulo(x, m1 - 1_i8)
      x = lcg(x)
      rng%s2(i) = 1_i8 + modulo(x, m2 - 1_i8)
    end do
    do i = 1, 16
      call rng_uniform(rng, dummy)
    end do
  end function new_rng

  pure integer(i8) function lcg(x)
    integer(i8), intent(in) :: x
    lcg = modulo(69069_i8*x + 1234567_i8, 4294967296_i8)
  end function lcg

  !> Uniform in (0, 1).
  pure subroutine rng_uniform(rng, u)
    type(rng_type), intent(inout) :: rng
    real(wp), intent(out) :: u
    integer(i8) :: p1, p2
    p1 = modulo(a12*rng%s1(2) - a13n*rng%s1(1), m1)
    rng%s1 = [rng%s1(2), rng%s1(3), p1]
    p2 = modulo(a21*rng%s2(3) - a23n*rng%s2(1), m2)
    rng%s2 = [rng%s2(2), rng%s2(3), p2]
    if (p1 > p2) then
      u = real(p1 - p2, wp)/real(m1 + 1_i8, wp)
    else
      u = real(p1 - p2 + m1, wp)/real(m1 + 1_i8, wp)
    end if
  end subroutine rng_uniform

end module davit_core_random
