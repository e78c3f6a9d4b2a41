!> Water loads on the lifeboat by strip theory (paper eqs. 18-25, review §1.3, §1.5, G25;
!> issue 18).
!>
!> Per strip k at (x_k, 0, 0): the wet part of its section (exact clipping, davit_boat_hull)
!> and quadratic drag on the velocity relative to the water particles at the wet centroid
!> (eqs. 21-22, review §1.5): D1 uses A_1max/n (the largest wet section area split evenly
!> over the strips, so the total surge drag is 1/2 rho A_max c |v| v), D2 the wet height and
!> D3 the wet width times t_s; drag acts at (x_k, 0, 0) (eq. 20). Two levels of detail:
!>
!> * `pressure` (default, issue 18): the section is clipped by the tangent plane of the
!>   surface at the strip centre, and the pressure is integrated over it
!>   (davit_boat_strip_pressure): the tangent-plane part is -rho g V_k grad(d) at the wet
!>   centroid (buoyancy normal to the local surface, its moment about G included: the roll
!>   restoring GM_T = KB + BM - KG comes out of the geometry), the rest is the dynamic
!>   pressure's decay with depth and its phase across the breadth, integrated exactly on
!>   the wet bottom and sides (vertical and horizontal force and roll moment). In calm water
!>   the load is the exact gradient of rho g sum_k t_s int_A_k z dA: energy is conserved.
!>   The bottom's drag area builds up over the first equilibrium draught T_0 (t_s x wet
!>   width x min(1, wet height / T_0)), so first contact is continuous.
!> * `paper`: buoyancy -rho g V_k N3 at (x_k, 0, 0) against the level surface at the strip
!>   centre (eq. 23, corrected sign) and the metacentric roll moment
!>   T1 = -rho g h sin(phi) sum V_k (eq. 24 corrected: restoring); not conservative (the
!>   moment depends on heave through V, the heave force not on roll).
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
  use davit_core_rotation, only: cross
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_elevation, wave_kinematics, &
                                  wave_ramp
  use davit_boat_hull, only: boat_hull_type, section_immersion, section_wet_type, &
                             hull_metacentric_height, hull_waterplane_area
  use davit_boat_strip_pressure, only: surface_plane, section_wave_load
  use davit_boat_strip_waves, only: strip_wave_cache_type, strip_waves_cover, &
                                    cached_elevation, cached_kinematics, cached_slope, &
                                    cached_wave_load
  implicit none
  private
  public :: strip_model_type, new_strip_model, strip_loads, strip_partial_velocities
  public :: strip_velocity, strip_potential
  public :: strip_level_pressure, strip_level_paper

  !> Levels of detail: pressure-integrated sections (issue 18), the paper's strips.
  integer, parameter :: strip_level_pressure = 1, strip_level_paper = 2

  type :: strip_model_type
    !> The hull's sections.
    type(boat_hull_type) :: hull
    !> Level of detail: strip_level_pressure or the paper's strips.
    integer :: level = strip_level_pressure
    !> Drag coefficients along b1, b2, b3 (paper: C_fluid = 1.2).
    real(wp) :: cd(3) = 1.2_wp
    !> Roll stiffness height [m]: GM_T of the hull or h_m; the paper level's metacentric
    !> term uses it, the pressure level adds (metacentric_height - gm_hull) to its own.
    real(wp) :: metacentric_height = 2.0_wp
    !> GM_T = KB + BM - KG of the upright hull at its equilibrium draught [m].
    real(wp) :: gm_hull = 0.0_wp
    !> Linear damping at full immersion: heave [N s/m], roll and pitch [N m s].
    real(wp) :: damping(3) = 0.0_wp
    !> Displaced volume at equilibrium, m / rho [m^3], and its draught V_0 / A_wp [m].
    real(wp) :: volume0 = 0.0_wp, draught0 = 0.0_wp
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
    !> Level of detail (default: pressure-integrated strips).
    integer, intent(in), optional :: level
    !> Roll from the paper's formula instead of the hull's breadth.
    logical, intent(in), optional :: paper_roll
    type(strip_model_type) :: s
    real(wp) :: c33, c44, c55
    logical :: paper
    s%hull = hull
    s%cd = cd
    if (present(level)) s%level = level
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
    real(wp) :: vrel(3, s%hull%n), grad_d(3, s%hull%n), fk(3), p(3), eta, slope(2), a1max
    real(wp) :: heave_rel, chord(4), d0(s%hull%n), n3(3)
    integer :: k
    logical :: window
    window = .false.
    if (present(cache)) window = strip_waves_cover(cache, t)
    f = 0.0_wp
    volume = 0.0_wp
    heave_rel = 0.0_wp
    a1max = 0.0_wp
    chord = 0.0_wp
    n3 = c(3, :)
    associate (h => s%hull)
      do k = 1, h%n
        p = r + c(:, 1)*h%x(k)
        call local_surface(s, field, t, k, p, window, cache, eta, slope)
        d0(k) = p(3) + eta
        ! depth below the tangent plane d = z + eta + slope . dx; its gradient in b
        grad_d(:, k) = n3 + slope(1)*c(1, :) + slope(2)*c(2, :)
        wet(k) = section_immersion(h, k, p(3) + eta, grad_d(2, k), grad_d(3, k))
        if (wet(k)%area <= 0.0_wp) cycle
        vrel(:, k) = strip_velocity(u, h%x(k)) - &
                     water_velocity(field, t, c, r, h%x(k), wet(k), k, eta, window, cache)
        volume = volume + wet(k)%area*h%thickness
        a1max = max(a1max, wet(k)%area)
        heave_rel = heave_rel + wet(k)%area*h%thickness*dot_product(n3, vrel(:, k))
      end do
      if (volume <= 0.0_wp) return
      do k = 1, h%n
        if (wet(k)%area <= 0.0_wp) cycle
        fk = strip_drag(s, wet(k), a1max, vrel(:, k))
        if (s%level == strip_level_paper) then
          fk = fk - rho_water*gravity*wet(k)%area*h%thickness*n3
        else
          call pressure_loads(s, field, t, c, r, k, wet(k), d0(k), grad_d(:, k), window, &
                              cache, f)
          if (s%metacentric_height /= s%gm_hull) call add_chord(wet(k), h%x(k), chord)
        end if
        ! f_r += fk . (dv/du_r), eq. (20): only u2, u3 (pitch, yaw) and u4..u6 enter
        f(2) = f(2) - h%x(k)*fk(3)
        f(3) = f(3) + h%x(k)*fk(2)
        f(4:6) = f(4:6) + fk
      end do
      call roll_restoring(s, n3, volume, chord, f)
      associate (wet_fraction => min(1.0_wp, volume/s%volume0))
        f(4:6) = f(4:6) - s%damping(1)*wet_fraction*heave_rel/volume*n3
        f(1) = f(1) - s%damping(2)*wet_fraction*u(1)
        f(2) = f(2) - s%damping(3)*wet_fraction*u(2)
      end associate
    end associate
  end subroutine strip_loads

  !> Elevation at the strip centre p and, for the pressure level, the surface slope there
  !> (the paper's strips see a level surface).
  pure subroutine local_surface(s, field, t, k, p, window, cache, eta, slope)
    type(strip_model_type), intent(in) :: s
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, p(3)
    integer, intent(in) :: k
    logical, intent(in) :: window
    type(strip_wave_cache_type), intent(in), optional :: cache
    real(wp), intent(out) :: eta, slope(2)
    slope = 0.0_wp
    if (window) then
      eta = cached_elevation(cache, field, k, t, p(1), p(2))
      if (s%level == strip_level_pressure) slope = cached_slope(cache, field, k, t)
    else if (s%level == strip_level_pressure) then
      call surface_plane(field, t, p(1), p(2), eta, slope)
    else
      eta = wave_elevation(field, t, p(1), p(2))
    end if
  end subroutine local_surface

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

  !> Drag on strip k (eq. 22 with the review's areas). The pressure level lets the bottom's
  !> area grow over the first draught T_0 of immersion (continuous first contact).
  pure function strip_drag(s, wet, a1max, vrel) result(fk)
    type(strip_model_type), intent(in) :: s
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: a1max, vrel(3)
    real(wp) :: fk(3), area(3)
    area(1) = a1max/real(s%hull%n, wp)
    area(2) = s%hull%thickness*wet%height
    area(3) = s%hull%thickness*wet%width
    if (s%level == strip_level_pressure) area(3) = area(3)*min(1.0_wp, wet%height/s%draught0)
    fk = -0.5_wp*rho_water*s%cd*area*abs(vrel)*vrel
  end function strip_drag

  !> Pressure on section k (pressure level): the tangent-plane part -rho g V_k grad(d) at
  !> the wet centroid (full 3-D moment about G) and the dynamic remainder p' on the wet
  !> hull edges (section-plane force at x_k and roll moment), added to f; d0 is the depth
  !> of the strip centre below the tangent plane.
  pure subroutine pressure_loads(s, field, t, c, r, k, wet, d0, grad_d, window, cache, f)
    type(strip_model_type), intent(in) :: s
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, c(3, 3), r(3), d0, grad_d(3)
    integer, intent(in) :: k
    type(section_wet_type), intent(in) :: wet
    logical, intent(in) :: window
    type(strip_wave_cache_type), intent(in), optional :: cache
    real(wp), intent(inout) :: f(6)
    real(wp) :: fb(3), load(3), rate(3)
    logical :: found
    associate (h => s%hull)
      fb = -rho_water*gravity*wet%area*h%thickness*grad_d
      f(1:3) = f(1:3) + cross([h%x(k), wet%centroid], fb)
      f(4:6) = f(4:6) + fb
      if (field%kind == wave_none) return
      found = .false.
      if (window) call cached_wave_load(cache, field, k, t, load, found)
      if (.not. found) then
        call section_wave_load(field, t, h, wet, c, r + c(:, 1)*h%x(k), d0, grad_d(2), &
                               grad_d(3), load, rate)
        load = wave_ramp(field, t)*load
      end if
      f(5:6) = f(5:6) + load(1:2)
      f(1) = f(1) + load(3)
      f(2) = f(2) - h%x(k)*load(2)
      f(3) = f(3) + h%x(k)*load(1)
    end associate
  end subroutine pressure_loads

  !> Waterline chord of a wet section (both ends on the surface line): accumulates its
  !> length l and l times its midpoint (x, y, z) in b, for the paper roll stiffness's
  !> heave coupling (d V / d(depth) = sum t_s l / |grad d|).
  pure subroutine add_chord(wet, x, chord)
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: x
    real(wp), intent(inout) :: chord(4)
    real(wp) :: len
    integer :: v, e
    do v = 1, wet%m
      e = merge(1, v + 1, v == wet%m)
      if (.not. (wet%cut(v) .and. wet%cut(e))) cycle
      len = norm2(wet%poly(:, e) - wet%poly(:, v))
      chord = chord + len*[1.0_wp, x, 0.5_wp*(wet%poly(:, v) + wet%poly(:, e))]
    end do
  end subroutine add_chord

  !> Roll stiffness beyond the pressure: the paper level's metacentric moment
  !> T1 = -rho g h sin(phi) V about b1 (eq. 24 corrected); the pressure level with the
  !> paper's h_m the gradient of Phi' = rho g dh (1 - cos phi) V, dh = h_m - GM_T, in calm
  !> water: the moment M = -rho g dh V sin(phi) along d phi/du = (1, -n1 n2/s, -n1 n3/s),
  !> s = n2^2 + n3^2 (phi = atan2(n2, n3) of n3 = C^T N3), and the force
  !> -rho g dh (1 - cos phi) t_s l N3 on the waterline chords (the waterplane).
  pure subroutine roll_restoring(s, n3, volume, chord, f)
    type(strip_model_type), intent(in) :: s
    real(wp), intent(in) :: n3(3), volume, chord(4)
    real(wp), intent(inout) :: f(6)
    real(wp) :: sn, dh, moment, fw(3)
    sn = max(n3(2)**2 + n3(3)**2, tiny(1.0_wp))
    if (s%level == strip_level_paper) then
      f(1) = f(1) - rho_water*gravity*s%metacentric_height*n3(2)/sqrt(sn)*volume
      return
    end if
    dh = s%metacentric_height - s%gm_hull
    if (dh == 0.0_wp) return
    moment = -rho_water*gravity*dh*volume*n3(2)/sqrt(sn)
    f(1:3) = f(1:3) + moment*[1.0_wp, -n3(1)*n3(2)/sn, -n3(1)*n3(3)/sn]
    if (chord(1) <= 0.0_wp) return
    fw = -rho_water*gravity*dh*(1.0_wp - n3(3)/sqrt(sn))*s%hull%thickness*chord(1)* &
         n3/hypot(n3(2), n3(3))
    f(1:3) = f(1:3) + cross(chord(2:4)/chord(1), fw)
    f(4:6) = f(4:6) + fw
  end subroutine roll_restoring

end module davit_boat_strip_loads
