!> Water loads on the lifeboat by strip theory (paper eqs. 18-25, review §1.3, §1.5, G25).
!>
!> Per strip k at (x_k, 0, 0): the wet part of its section against the local wave elevation
!> (exact clipping, davit_boat_hull), buoyancy -rho g V_k N3 (eq. 23 with the corrected
!> sign) and quadratic drag on the velocity relative to the water particles at the wet
!> centroid (eqs. 21-22, review §1.5): D1 uses A_1max/n (the largest wet section area split
!> evenly over the strips, so the total surge drag is 1/2 rho A_max c |v| v), D2 the wet
!> height and D3 the wet width times t_s. Both act at (x_k, 0, 0), so they enter through the
!> partial velocities of eq. (20). Roll: the strips lie on the centreline, so the only
!> roll moment is the metacentric term T1 = -rho g h_m sin(phi) sum V_k (eq. 24 corrected:
!> restoring). Optional linear heave/roll/pitch damping (the paper's boat has no radiation
!> damping) scales with the wet fraction min(1, V / V_0), V_0 = m / rho; the heave part acts
!> vertically on the volume-weighted vertical velocity relative to the water.
module davit_boat_strip_loads
  use davit_kinds, only: wp, gravity, rho_water
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_elevation, wave_kinematics
  use davit_boat_hull, only: boat_hull_type, section_immersion, section_wet_type
  use davit_boat_strip_waves, only: strip_wave_cache_type, strip_waves_cover, &
                                    cached_elevation, cached_kinematics
  implicit none
  private
  public :: strip_model_type, new_strip_model, strip_loads, strip_partial_velocities
  public :: strip_velocity

  type :: strip_model_type
    type(boat_hull_type) :: hull
    !> Drag coefficients along b1, b2, b3 (paper: C_fluid = 1.2) and h_m [m].
    real(wp) :: cd(3) = 1.2_wp
    real(wp) :: metacentric_height = 2.0_wp
    !> Linear damping at full immersion: heave [N s/m], roll and pitch [N m s].
    real(wp) :: damping(3) = 0.0_wp
    !> Displaced volume at equilibrium, m / rho [m^3].
    real(wp) :: volume0 = 0.0_wp
  end type strip_model_type

contains

  !> Damping from fractions of critical zeta = (heave, roll, pitch) with the hydrostatic
  !> stiffnesses of the upright boat at its equilibrium draught: C33 = rho g A_wp,
  !> C44 = m g h_m, C55 = rho g sum b_k t_s x_k^2; B = 2 zeta sqrt(C M).
  pure function new_strip_model(hull, cd, metacentric_height, zeta, mass, inertia) result(s)
    type(boat_hull_type), intent(in) :: hull
    real(wp), intent(in) :: cd(3), metacentric_height, zeta(3), mass, inertia(3)
    type(strip_model_type) :: s
    real(wp) :: c33, c44, c55
    s%hull = hull
    s%cd = cd
    s%metacentric_height = metacentric_height
    s%volume0 = mass/rho_water
    c33 = rho_water*gravity*sum(hull%breadth)*hull%thickness
    c44 = mass*gravity*metacentric_height
    c55 = rho_water*gravity*sum(hull%breadth*hull%x**2)*hull%thickness
    s%damping = 2.0_wp*zeta*sqrt([c33*mass, c44*inertia(1), c55*inertia(2)])
  end function new_strip_model

  !> Velocity of the strip centre (x, 0, 0) in b: (u4, u5 + x u3, u6 - x u2) (review §1.5).
  pure function strip_velocity(u, x) result(v)
    real(wp), intent(in) :: u(6), x
    real(wp) :: v(3)
    ! eq. (20) written out (the partial-velocity matrix product made a heap temporary)
    v(1) = u(4)
    v(2) = u(5) + x*u(3)
    v(3) = u(6) - x*u(2)
  end function strip_velocity

  !> Partial velocities of the strip centre, eq. (20): column r is dv/du_r in b.
  pure function strip_partial_velocities(x) result(vr)
    real(wp), intent(in) :: x
    real(wp) :: vr(3, 6)
    vr = 0.0_wp
    vr(3, 2) = -x
    vr(2, 3) = x
    vr(1, 4) = 1.0_wp
    vr(2, 5) = 1.0_wp
    vr(3, 6) = 1.0_wp
  end function strip_partial_velocities

  !> Generalized force f (eqs. 18-25) of the water on the boat with rotation c (b -> N),
  !> CG r (inertial) and speeds u at time t; also the wet volume [m^3]. With a cache
  !> that covers t, the water comes from its slow clock (davit_boat_strip_waves).
  pure subroutine strip_loads(s, field, t, c, r, u, f, volume, cache)
    type(strip_model_type), intent(in) :: s
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, c(3, 3), r(3), u(6)
    real(wp), intent(out) :: f(6), volume
    type(strip_wave_cache_type), intent(in), optional :: cache
    type(section_wet_type) :: wet(s%hull%n)
    real(wp) :: vrel(3, s%hull%n), fk(3), p(3), q(3), area(3), eta, vw(3), aw(3), pw, a1max
    real(wp) :: heave_rel
    real(wp) :: sin_roll
    integer :: k
    logical :: window, cached
    window = .false.
    if (present(cache)) window = strip_waves_cover(cache, t)
    f = 0.0_wp
    volume = 0.0_wp
    heave_rel = 0.0_wp
    a1max = 0.0_wp
    associate (h => s%hull, n3 => c(3, :))
      do k = 1, h%n
        p = r + c(:, 1)*h%x(k)
        if (window) then
          eta = cached_elevation(cache, field, k, t, p(1), p(2))
        else
          eta = wave_elevation(field, t, p(1), p(2))
        end if
        wet(k) = section_immersion(h, k, p(3) + eta, n3(2), n3(3))
        if (wet(k)%area <= 0.0_wp) cycle
        vw = 0.0_wp
        cached = .false.
        if (window) cached = cache%sampled(k)
        ! wet centroid (x_k, y_c, z_c) in N, written out: an array constructor here costs
        ! a heap temporary per strip and stage
        q = r + c(:, 1)*h%x(k) + c(:, 2)*wet(k)%centroid(1) + c(:, 3)*wet(k)%centroid(2)
        if (cached) then
          call cached_kinematics(cache, field, k, t, q, eta, vw)
        else if (field%kind /= wave_none) then
          call wave_kinematics(field, t, q, eta, vw, aw, pw)
        end if
        vrel(:, k) = strip_velocity(u, h%x(k)) - matmul(vw, c)
        volume = volume + wet(k)%area*h%thickness
        a1max = max(a1max, wet(k)%area)
        heave_rel = heave_rel + wet(k)%area*h%thickness*dot_product(n3, vrel(:, k))
      end do
      if (volume <= 0.0_wp) return
      do k = 1, h%n
        if (wet(k)%area <= 0.0_wp) cycle
        ! Eq. (22) with the review's areas, plus buoyancy (eq. 23 corrected).
        area(1) = a1max/real(h%n, wp)
        area(2) = h%thickness*wet(k)%height
        area(3) = h%thickness*wet(k)%width
        fk = -0.5_wp*rho_water*s%cd*area*abs(vrel(:, k))*vrel(:, k)
        fk = fk - rho_water*gravity*wet(k)%area*h%thickness*n3
        ! f_r += fk . (dv/du_r), eq. (20): only u2, u3 (pitch, yaw) and u4..u6 enter
        f(2) = f(2) - h%x(k)*fk(3)
        f(3) = f(3) + h%x(k)*fk(2)
        f(4:6) = f(4:6) + fk
      end do
      sin_roll = n3(2)/max(hypot(n3(2), n3(3)), tiny(1.0_wp))
      f(1) = f(1) - rho_water*gravity*s%metacentric_height*sin_roll*volume
      associate (wet_fraction => min(1.0_wp, volume/s%volume0))
        f(4:6) = f(4:6) - s%damping(1)*wet_fraction*heave_rel/volume*n3
        f(1) = f(1) - s%damping(2)*wet_fraction*u(1)
        f(2) = f(2) - s%damping(3)*wet_fraction*u(2)
      end associate
    end associate
  end subroutine strip_loads

end module davit_boat_strip_loads
