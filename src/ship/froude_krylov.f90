!> Froude-Krylov wave loads on the ship's equivalent box by the exact closed form of the
!> review (§1.8), which replaces the paper's garbled eq. (42): the incident-wave pressure
!> p = rho g zeta exp(-k z) cos(Phi - k x cos(chi) - k y sin(chi)) integrated over the two
!> ends, two sides and the bottom of the box -l/2 <= x <= l/2, -B/2 <= y <= B/2, 0 <= z <= d
!> (ship axes at O': midship, still waterline, centreline; x forward, y starboard, z down).
!> Moments are about O'; fk_transfer moves them to the CG.
module davit_ship_froude_krylov
  use davit_kinds, only: wp, gravity, rho_water
  implicit none
  private
  public :: box_type, fk_box_load, fk_transfer

  !> The ship's equivalent box for the Froude-Krylov loads.
  type :: box_type
    !> Length l = sqrt(C_b) L_wl (review §1.8, G15), beam B, draught d [m].
    real(wp) :: length = 0.0_wp, beam = 0.0_wp, draught = 0.0_wp
  end type box_type

contains

  !> Generalized load (X, Y, Z, K, M, N) about O' of one wave component of amplitude zeta,
  !> wave number k, direction chi relative to the box's x axis and phase Phi at O'.
  pure function fk_box_load(box, zeta, k, chi, phi) result(load)
    !> The equivalent box (length, beam, draught).
    type(box_type), intent(in) :: box
    !> Wave amplitude zeta [m], wave number k [rad/m], direction chi [rad] the wave travels
    !> in relative to the box's x axis (0: from astern) and the phase Phi [rad] at O'.
    real(wp), intent(in) :: zeta, k, chi, phi
    real(wp) :: load(6)
    real(wp) :: e, f, i0, i1, sl, sb, gl, gb, ekd, rgz, sfl, seb
    associate (l => box%length, b => box%beam, d => box%draught)
      e = 0.5_wp*k*sin(chi)
      f = 0.5_wp*k*cos(chi)
      ekd = exp(-k*d)
      i0 = -expm1_neg(k*d)/k
      i1 = (1.0_wp - (1.0_wp + k*d)*ekd)/k**2
      sfl = sin(f*l)
      seb = sin(e*b)
      sl = sinc_len(f, l)
      sb = sinc_len(e, b)
      gl = g_len(f, l)
      gb = g_len(e, b)
    end associate
    rgz = rho_water*gravity*zeta
    load(1) = -2.0_wp*rgz*i0*sb*sfl*sin(phi)
    load(2) = -2.0_wp*rgz*i0*sl*seb*sin(phi)
    load(3) = -rgz*ekd*sl*sb*cos(phi)
    load(4) = rgz*sl*(2.0_wp*i1*seb - ekd*gb)*sin(phi)
    load(5) = rgz*sb*(ekd*gl - 2.0_wp*i1*sfl)*sin(phi)
    load(6) = 2.0_wp*rgz*i0*(seb*gl - sfl*gb)*cos(phi)
  end function fk_box_load

  !> Moments about the CG at (x_g, 0, z_g) from O' (review §1.8):
  !> K_G = K + z_G Y, M_G = M - z_G X + x_G Z, N_G = N - x_G Y.
  pure function fk_transfer(load, x_g, z_g) result(out)
    !> Load (X, Y, Z [N], K, M, N [N m]) about O', and the CG's x (forward) and z (down)
    !> relative to O' [m].
    real(wp), intent(in) :: load(6), x_g, z_g
    real(wp) :: out(6)
    out(1:3) = load(1:3)
    out(4) = load(4) + z_g*load(2)
    out(5) = load(5) - z_g*load(1) + x_g*load(3)
    out(6) = load(6) - x_g*load(2)
  end function fk_transfer

  !> sin(a L)/a, -> L as a -> 0.
  pure real(wp) function sinc_len(a, len) result(s)
    real(wp), intent(in) :: a, len
    real(wp) :: x
    x = a*len
    if (abs(x) < 1.0e-4_wp) then
      s = len*(1.0_wp - x*x/6.0_wp)
    else
      s = sin(x)/a
    end if
  end function sinc_len

  !> (sin(a L) - a L cos(a L))/(2 a^2), -> a L^3/6 as a -> 0.
  pure real(wp) function g_len(a, len) result(g)
    real(wp), intent(in) :: a, len
    real(wp) :: x
    x = a*len
    if (abs(x) < 1.0e-3_wp) then
      g = len**2*(x/6.0_wp - x**3/60.0_wp)
    else
      g = (sin(x) - x*cos(x))/(2.0_wp*a*a)
    end if
  end function g_len

  !> exp(-x) - 1 without cancellation for small x.
  pure real(wp) function expm1_neg(x)
    real(wp), intent(in) :: x
    if (x < 1.0e-5_wp) then
      expm1_neg = -x + 0.5_wp*x*x
    else
      expm1_neg = exp(-x) - 1.0_wp
    end if
  end function expm1_neg

end module davit_ship_froude_krylov
