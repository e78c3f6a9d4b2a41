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
  integer(i8), parameter :: two32 = 4294967296_i8
  integer(i8), parameter :: a12 = 1403580_i8, a13n = 810728_i8
  integer(i8), parameter :: a21 = 527612_i8, a23n = 1370589_i8

  type :: rng_type
    !> State words of the first MRG32k3a component (modulus m1).
    integer(i8) :: s1(3) = [12345_i8, 12345_i8, 12345_i8]
    !> State words of the second MRG32k3a component (modulus m2).
    integer(i8) :: s2(3) = [12345_i8, 12345_i8, 12345_i8]
  end type rng_type

contains

  !> A generator seeded from `seed` and an optional `stream` index (e.g. a sweep case). The
  !> six state words are independent 32-bit hashes of (seed, stream, word), so nearby seeds
  !> and streams give unrelated sequences (a plain LCG fill left measurable correlations
  !> between the phase vectors of neighbouring seeds).
  function new_rng(seed, stream) result(rng)
    !> Seed of the generator.
    integer, intent(in) :: seed
    !> Stream index (e.g. a sweep case); none gives the seed's own stream.
    integer, intent(in), optional :: stream
    type(rng_type) :: rng
    integer(i8) :: key
    real(wp) :: dummy
    integer :: i
    key = hash32(modulo(int(seed, i8), two32))
    if (present(stream)) key = hash32(ieor(key, hash32(modulo(int(stream, i8) + 1_i8, two32))))
    do i = 1, 3
      rng%s1(i) = 1_i8 + modulo(hash32(ieor(key, hash32(int(2*i - 1, i8)))), m1 - 1_i8)
      rng%s2(i) = 1_i8 + modulo(hash32(ieor(key, hash32(int(2*i, i8) + 1000_i8))), m2 - 1_i8)
    end do
    do i = 1, 16
      call rng_uniform(rng, dummy)
    end do
  end function new_rng

  !> A 32-bit integer hash (xor-shift-multiply, multiplier 0x45d9f3b); all products stay
  !> below 2^59, so int64 arithmetic never overflows.
  pure integer(i8) function hash32(x) result(h)
    !> Value hashed (its low 32 bits are used).
    integer(i8), intent(in) :: x
    h = modulo(x, two32)
    h = modulo(ieor(ishft(h, -16), h)*73244475_i8, two32)
    h = modulo(ieor(ishft(h, -16), h)*73244475_i8, two32)
    h = ieor(ishft(h, -16), h)
  end function hash32

  !> Uniform in (0, 1).
  pure subroutine rng_uniform(rng, u)
    !> The generator, advanced by one draw.
    type(rng_type), intent(inout) :: rng
    !> The uniform deviate in (0, 1).
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
