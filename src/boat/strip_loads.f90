!> Water loads on the lifeboat by strip theory (paper eqs. 18-25, review §1.3, §1.5, G25;
!> issue 18).
!>
!> Per strip k at (x_k, 0, 0): the wet part of its section (exact clipping, davit_boat_hull)
!> and quadratic drag on the velocity relative to the water particles at the wet centroid
!> (eqs. 21-22, review §1.5): D1 uses A_1max/n (the largest wet section area split evenly
!> over the strips, so the total surge drag is 1/2 rho A_max c |v| v), D2 the wet height and
!> D3 the wet width times t_s; drag acts at (x_k, 0, 0) (eq. 20). Two levels of detail,
!> `pressure` (default, issue 18: pressure integrated under the surface's tangent plane,
!> energy-conserving in calm water) and `paper` (eqs. 23-24 corrected), are extensions of
!> davit_boat_strip_level's strip_level_type, chosen once at build; the loads here call
!> their bindings once per evaluation and ask no question of the level.
!>
!> Roll stiffness (`&boat roll_restoring`): 'hull' (default) is the hull's own GM_T from
!> the plan shape and KG = keel (G25, 0.766 m); 'paper' is h_m (`metacentric_height`,
!> 2 m). With the pressure level, 'paper' adds the potential
!> Phi' = rho g (h_m - GM_T) (1 - cos phi) V to the hull's own, whose gradient is the
!> moment -rho g (h_m - GM_T) V sin phi (distributed over u1..u3 by d phi/dt) and a vertical
!> force -rho g (h_m - GM_T) (1 - cos phi) on the waterplane: a conservative roll-heave
!> coupling. Optional linear heave/roll/pitch damping (the paper's boat has no radiation
!> damping) scales with the wet fraction min(1, V / V_0), V_0 = m / rho; the heave part acts
!> vertically on the volume-weighted vertical velocity relative to the water.
module davit_boat_strip_loads
  use davit_kinds, only: wp, gravity, rho_water
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_kinematics
  use davit_boat_hull, only: boat_hull_type, section_immersion, section_wet_type, &
                             hull_metacentric_height, hull_waterplane_area
  use davit_boat_strip_waves, only: strip_wave_cache_type, strip_waves_cover, &
                                    cached_kinematics
  use davit_boat_strip_level, only: strip_data_type, strip_level_type, strip_level_pressure
  implicit none
  private
  public :: strip_model_type, new_strip_model, strip_loads, strip_partial_velocities
  public :: strip_velocity, strip_potential

  !> The strip model: the data both levels read, and its level of detail.
  type, extends(strip_data_type) :: strip_model_type
    !> Level of detail: strip_level_pressure (allocated by new_strip_model) or the paper's
    !> strips (davit_boat_strip_level).
    class(strip_level_type), allocatable :: level
  end type strip_model_type

contains

  !> The strip model at a level of detail (default pressure); roll stiffness from the hull
  !> (default) or h_m (paper_roll). Damping from fractions of critical zeta = (heave, roll,
  !> pitch) with the hydrostatic stiffnesses of the upright boat at its equilibrium
  !> draught: C33 = rho g A_wp, C44 = m g GM, C55 = rho g sum b_k t_s x_k^2;
  !> B = 2 zeta sqrt(C M).
  pure function new_strip_model(hull, cd, metacentric_height, zeta, mass, inertia, level, &
                                paper_roll) result(s)
    !> The hull's sections.
    type(boat_hull_type), intent(in) :: hull
    !> Drag coefficients along b1, b2, b3; metacentric height [m]; damping fractions; mass [kg];
    !> principal moments of inertia [kg m^2].
    real(wp), intent(in) :: cd(3), metacentric_height, zeta(3), mass, inertia(3)
    !> Level of detail (default: pressure-integrated strips, strip_level_pressure).
    class(strip_level_type), intent(in), optional :: level
    !> Roll from the paper's formula instead of the hull's breadth.
    logical, intent(in), optional :: paper_roll
    type(strip_model_type) :: s
    real(wp) :: c33, c44, c55
    logical :: paper
    s%hull = hull
    s%cd = cd
    if (present(level)) then
      allocate (s%level, source=level)
    else
      allocate (s%level, source=strip_level_pressure)
    end if
    s%volume0 = mass/rho_water
    s%draught0 = s%volume0/hull_waterplane_area(hull)
    s%gm_hull = hull_metacentric_height(hull, s%volume0)
    paper = .false.
    if (present(paper_roll)) paper = paper_roll
    s%metacentric_height = merge(metacentric_height, s%gm_hull, paper)
    c33 = rho_water*gravity*hull_waterplane_area(hull)
    c44 = mass*gravity*s%metacentric_height
    c55 = rho_water*gravity*sum(hull%breadth*hull%x**2)*hull%thickness
    s%damping = 2.0_wp*zeta*sqrt(max(0.0_wp, [c33*mass, c44*inertia(1), c55*inertia(2)]))
  end function new_strip_model

  !> Velocity of the strip centre (x, 0, 0) in b: (u4, u5 + x u3, u6 - x u2) (review §1.5).
  pure function strip_velocity(u, x) result(v)
    !> Boat speeds (Kane order) [rad/s, m/s]; strip position along b1 [m].
    real(wp), intent(in) :: u(6), x
    real(wp) :: v(3)
    ! eq. (20) written out (the partial-velocity matrix product made a heap temporary)
    v(1) = u(4)
    v(2) = u(5) + x*u(3)
    v(3) = u(6) - x*u(2)
  end function strip_velocity

  !> Partial velocities of the strip centre, eq. (20): column r is dv/du_r in b.
  pure function strip_partial_velocities(x) result(vr)
    !> Strip position along b1 [m].
    real(wp), intent(in) :: x
    real(wp) :: vr(3, 6)
    vr = 0.0_wp
    vr(3, 2) = -x
    vr(2, 3) = x
    vr(1, 4) = 1.0_wp
    vr(2, 5) = 1.0_wp
    vr(3, 6) = 1.0_wp
  end function strip_partial_velocities

  !> Hydrostatic potential energy [J] of the pressure level in calm water:
  !> rho g sum_k t_s A_k z_k (z_k the depth of the wet centroid; = rho g int z dV), plus
  !> rho g (h - GM_T) (1 - cos phi) V with the paper's roll stiffness. With -m g z_G and
  !> the kinetic energy, the undamped boat's energy.
  pure real(wp) function strip_potential(s, c, r) result(e)
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> Boat rotation b -> inertial and CG position (inertial) [m].
    real(wp), intent(in) :: c(3, 3), r(3)
    type(section_wet_type) :: wet
    real(wp) :: v, n3(3)
    integer :: k
    n3 = c(3, :)
    e = 0.0_wp
    v = 0.0_wp
    do k = 1, s%hull%n
      wet = section_immersion(s%hull, k, r(3) + n3(1)*s%hull%x(k), n3(2), n3(3))
      if (wet%area <= 0.0_wp) cycle
      v = v + wet%area*s%hull%thickness
      e = e + rho_water*gravity*wet%area*s%hull%thickness* &
          (r(3) + dot_product(n3, [s%hull%x(k), wet%centroid]))
    end do
    e = e + rho_water*gravity*(s%metacentric_height - s%gm_hull)* &
        (1.0_wp - n3(3)/hypot(n3(2), n3(3)))*v
  end function strip_potential

  !> Generalized force f (eqs. 18-25) of the water on the boat with rotation c (b -> N),
  !> CG r (inertial) and speeds u at time t; also the wet volume [m^3]. With a cache
  !> that covers t, the water comes from its slow clock (davit_boat_strip_waves).
  pure subroutine strip_loads(s, field, t, c, r, u, f, volume, cache)
    !> The strip model.
    type(strip_model_type), intent(in) :: s
    !> The sea at the strips.
    type(wave_field_type), intent(in) :: field
    !> Time [s], rotation b -> inertial, CG position (inertial) [m], speeds (Kane order).
    real(wp), intent(in) :: t, c(3, 3), r(3), u(6)
    !> Generalized forces (Kane order) [N m, N]; wet volume [m^3].
    real(wp), intent(out) :: f(6), volume
    !> The water at the strips on the slow clock (absent: evaluated directly).
    type(strip_wave_cache_type), intent(in), optional :: cache
    type(section_wet_type) :: wet(s%hull%n)
    real(wp) :: vrel(3, s%hull%n), grad_d(3, s%hull%n), p(3), a1max
    real(wp) :: heave_rel, d0(s%hull%n), n3(3), eta(s%hull%n), slope(2, s%hull%n)
    integer :: k
    logical :: window
    window = .false.
    if (present(cache)) window = strip_waves_cover(cache, t)
    f = 0.0_wp
    volume = 0.0_wp
    heave_rel = 0.0_wp
    a1max = 0.0_wp
    n3 = c(3, :)
    call s%level%surfaces(s%strip_data_type, field, t, c, r, window, cache, eta, slope)
    associate (h => s%hull)
      do k = 1, h%n
        p = r + c(:, 1)*h%x(k)
        d0(k) = p(3) + eta(k)
        ! depth below the tangent plane d = z + eta + slope . dx; its gradient in b
        grad_d(:, k) = n3 + slope(1, k)*c(1, :) + slope(2, k)*c(2, :)
        wet(k) = section_immersion(h, k, p(3) + eta(k), grad_d(2, k), grad_d(3, k))
        if (wet(k)%area <= 0.0_wp) cycle
        vrel(:, k) = strip_velocity(u, h%x(k)) - &
                     water_velocity(field, t, c, r, h%x(k), wet(k), k, eta(k), window, cache)
        volume = volume + wet(k)%area*h%thickness
        a1max = max(a1max, wet(k)%area)
        heave_rel = heave_rel + wet(k)%area*h%thickness*dot_product(n3, vrel(:, k))
      end do
      if (volume <= 0.0_wp) return
      call s%level%add_sections(s%strip_data_type, field, t, c, r, wet, vrel, a1max, d0, &
                                grad_d, volume, window, cache, f)
      associate (wet_fraction => min(1.0_wp, volume/s%volume0))
        f(4:6) = f(4:6) - s%damping(1)*wet_fraction*heave_rel/volume*n3
        f(1) = f(1) - s%damping(2)*wet_fraction*u(1)
        f(2) = f(2) - s%damping(3)*wet_fraction*u(2)
      end associate
    end associate
  end subroutine strip_loads

  !> Water-particle velocity (b components) at the wet centroid of strip k.
  pure function water_velocity(field, t, c, r, x, wet, k, eta, window, cache) result(vb)
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, c(3, 3), r(3), x, eta
    type(section_wet_type), intent(in) :: wet
    integer, intent(in) :: k
    logical, intent(in) :: window
    type(strip_wave_cache_type), intent(in), optional :: cache
    real(wp) :: vb(3), q(3), vw(3), aw(3), pw, e
    logical :: cached
    vb = 0.0_wp
    if (field%kind == wave_none) return
    cached = .false.
    if (window) cached = cache%sampled(k)
    ! wet centroid (x_k, y_c, z_c) in N, written out: an array constructor here costs
    ! a heap temporary per strip and stage
    q = r + c(:, 1)*x + c(:, 2)*wet%centroid(1) + c(:, 3)*wet%centroid(2)
    e = eta
    if (cached) then
      call cached_kinematics(cache, field, k, t, q, e, vw)
    else
      call wave_kinematics(field, t, q, e, vw, aw, pw)
    end if
    vb = matmul(vw, c)
  end function water_velocity

end module davit_boat_strip_loads
