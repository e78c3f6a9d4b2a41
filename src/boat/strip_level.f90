!> The strips' level of detail as a type (paper eqs. 18-25, review §1.5; issue 18): how a
!> strip sees the surface and what pressure acts on its wet section. One extension per
!> level, chosen once when the strip model is built (davit_system_law_factory); the strip
!> loads (davit_boat_strip_loads) call its two bindings once per evaluation, each looping
!> over the strips itself, so the per-strip loop holds no test of the level.
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
!> Drag (eqs. 21-22, review §1.5) is common to both: D1 uses A_1max/n (the largest wet
!> section area split evenly over the strips), D2 the wet height and D3 the wet width
!> times t_s, on the velocity relative to the water at the wet centroid, acting at
!> (x_k, 0, 0) (eq. 20).
module davit_boat_strip_level
  use davit_kinds, only: wp, gravity, rho_water
  use davit_core_rotation, only: cross
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_elevation, wave_ramp
  use davit_boat_hull, only: boat_hull_type, section_wet_type
  use davit_boat_strip_pressure, only: surface_plane, section_wave_load
  use davit_boat_strip_waves, only: strip_wave_cache_type, cached_surface, &
                                    cached_wave_load
  implicit none
  private
  public :: strip_data_type, strip_level_type, paper_strip_level_type, &
            pressure_strip_level_type, strip_level_paper, strip_level_pressure

  !> What both levels read of the strip model: hull, drag, roll stiffness, equilibrium.
  type :: strip_data_type
    !> The hull's sections.
    type(boat_hull_type) :: hull
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
  end type strip_data_type

  !> A level of detail of the strips: the surface each strip sees, and the drag, pressure
  !> and roll stiffness on the wet sections.
  type, abstract :: strip_level_type
  contains
    procedure(surfaces_i), deferred :: surfaces
    procedure(add_sections_i), deferred :: add_sections
  end type strip_level_type

  !> The paper's strips: level surface at each strip centre, buoyancy along N3 (eq. 23),
  !> metacentric roll moment (eq. 24).
  type, extends(strip_level_type) :: paper_strip_level_type
  contains
    procedure :: surfaces => paper_surfaces
    procedure :: add_sections => paper_sections
  end type paper_strip_level_type

  !> Pressure-integrated sections under the surface's tangent plane (issue 18).
  type, extends(strip_level_type) :: pressure_strip_level_type
  contains
    procedure :: surfaces => pressure_surfaces
    procedure :: add_sections => pressure_sections
  end type pressure_strip_level_type

  !> The two levels, as the values new_strip_model takes.
  type(paper_strip_level_type), parameter :: strip_level_paper = paper_strip_level_type()
  type(pressure_strip_level_type), parameter :: strip_level_pressure = &
    pressure_strip_level_type()

  abstract interface
    !> Elevation eta_k [m] at each strip centre p_k = r + x_k C b1 and the surface slope
    !> there (d eta/dx, d eta/dy), from the cache when `window` (it covers t).
    pure subroutine surfaces_i(self, s, field, t, c, r, window, cache, eta, slope)
      import :: wp, strip_level_type, strip_data_type, wave_field_type, strip_wave_cache_type
      class(strip_level_type), intent(in) :: self
      !> The strip model's data.
      type(strip_data_type), intent(in) :: s
      !> The sea at the strips.
      type(wave_field_type), intent(in) :: field
      !> Time [s], rotation b -> inertial, CG position (inertial) [m].
      real(wp), intent(in) :: t, c(3, 3), r(3)
      !> Whether the cache covers t.
      logical, intent(in) :: window
      !> The water at the strips on the slow clock.
      type(strip_wave_cache_type), intent(in), optional :: cache
      !> Elevation [m] and slope of the surface at each strip centre.
      real(wp), intent(out) :: eta(s%hull%n), slope(2, s%hull%n)
    end subroutine surfaces_i

    !> Adds to f (Kane order) the drag, hydrostatic and wave pressure on the wet sections
    !> and the roll stiffness beyond it; wet(k) the wet part of section k, vrel its velocity
    !> relative to the water (b), d0 the depth of its centre below the local surface and
    !> grad_d that depth's gradient (b); a1max the largest wet area, volume the wet volume.
    pure subroutine add_sections_i(self, s, field, t, c, r, wet, vrel, a1max, d0, grad_d, &
                                   volume, window, cache, f)
      import :: wp, strip_level_type, strip_data_type, wave_field_type, &
                strip_wave_cache_type, section_wet_type
      class(strip_level_type), intent(in) :: self
      !> The strip model's data.
      type(strip_data_type), intent(in) :: s
      !> The sea at the strips.
      type(wave_field_type), intent(in) :: field
      !> Time [s], rotation b -> inertial, CG position (inertial) [m].
      real(wp), intent(in) :: t, c(3, 3), r(3)
      !> The wet sections.
      type(section_wet_type), intent(in) :: wet(s%hull%n)
      !> Relative velocities [m/s], largest wet area [m^2], depths [m] and their gradients,
      !> wet volume [m^3].
      real(wp), intent(in) :: vrel(3, s%hull%n), a1max, d0(s%hull%n), grad_d(3, s%hull%n), &
                              volume
      !> Whether the cache covers t.
      logical, intent(in) :: window
      !> The water at the strips on the slow clock.
      type(strip_wave_cache_type), intent(in), optional :: cache
      !> Generalized forces (Kane order) [N m, N], added to.
      real(wp), intent(inout) :: f(6)
    end subroutine add_sections_i
  end interface

contains

  !> The paper's strips see a level surface: elevation only, zero slope.
  pure subroutine paper_surfaces(self, s, field, t, c, r, window, cache, eta, slope)
    !> The level.
    class(paper_strip_level_type), intent(in) :: self
    !> The strip model's data.
    type(strip_data_type), intent(in) :: s
    !> The sea at the strips.
    type(wave_field_type), intent(in) :: field
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> Whether the cache covers t.
    logical, intent(in) :: window
    !> The water at the strips on the slow clock.
    type(strip_wave_cache_type), intent(in), optional :: cache
    !> Elevation [m] and slope of the surface at each strip centre.
    real(wp), intent(out) :: eta(s%hull%n), slope(2, s%hull%n)
    real(wp) :: p(3), plane(2)
    integer :: k
    slope = 0.0_wp
    do k = 1, s%hull%n
      p = r + c(:, 1)*s%hull%x(k)
      if (window) then
        ! the cached surface's slope is not used: this level's surface is level
        call cached_surface(cache, field, k, t, p(1), p(2), eta(k), plane)
      else
        eta(k) = wave_elevation(field, t, p(1), p(2))
      end if
    end do
  end subroutine paper_surfaces

  !> The pressure level's strips see the surface's tangent plane at their centre.
  pure subroutine pressure_surfaces(self, s, field, t, c, r, window, cache, eta, slope)
    !> The level.
    class(pressure_strip_level_type), intent(in) :: self
    !> The strip model's data.
    type(strip_data_type), intent(in) :: s
    !> The sea at the strips.
    type(wave_field_type), intent(in) :: field
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> Whether the cache covers t.
    logical, intent(in) :: window
    !> The water at the strips on the slow clock.
    type(strip_wave_cache_type), intent(in), optional :: cache
    !> Elevation [m] and slope of the surface at each strip centre.
    real(wp), intent(out) :: eta(s%hull%n), slope(2, s%hull%n)
    real(wp) :: p(3)
    integer :: k
    do k = 1, s%hull%n
      p = r + c(:, 1)*s%hull%x(k)
      if (window) then
        call cached_surface(cache, field, k, t, p(1), p(2), eta(k), slope(:, k))
      else
        call surface_plane(field, t, p(1), p(2), eta(k), slope(:, k))
      end if
    end do
  end subroutine pressure_surfaces

  !> Drag and buoyancy -rho g V_k N3 at (x_k, 0, 0) (eq. 23, corrected sign) on each wet
  !> strip; then the metacentric roll moment T1 = -rho g h sin(phi) V (eq. 24 corrected).
  pure subroutine paper_sections(self, s, field, t, c, r, wet, vrel, a1max, d0, grad_d, &
                                 volume, window, cache, f)
    !> The level.
    class(paper_strip_level_type), intent(in) :: self
    !> The strip model's data.
    type(strip_data_type), intent(in) :: s
    !> The sea at the strips.
    type(wave_field_type), intent(in) :: field
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> The wet sections.
    type(section_wet_type), intent(in) :: wet(s%hull%n)
    !> Relative velocities [m/s], largest wet area [m^2], depths [m] and their gradients,
    !> wet volume [m^3].
    real(wp), intent(in) :: vrel(3, s%hull%n), a1max, d0(s%hull%n), grad_d(3, s%hull%n), &
                            volume
    !> Whether the cache covers t.
    logical, intent(in) :: window
    !> The water at the strips on the slow clock.
    type(strip_wave_cache_type), intent(in), optional :: cache
    !> Generalized forces (Kane order) [N m, N], added to.
    real(wp), intent(inout) :: f(6)
    real(wp) :: fk(3), n3(3), sn
    integer :: k
    n3 = c(3, :)
    associate (h => s%hull)
      do k = 1, h%n
        if (wet(k)%area <= 0.0_wp) cycle
        fk = strip_drag(s%cd, drag_areas(s, wet(k), a1max), vrel(:, k))
        fk = fk - rho_water*gravity*wet(k)%area*h%thickness*n3
        call add_strip_force(h%x(k), fk, f)
      end do
    end associate
    sn = max(n3(2)**2 + n3(3)**2, tiny(1.0_wp))
    f(1) = f(1) - rho_water*gravity*s%metacentric_height*n3(2)/sqrt(sn)*volume
  end subroutine paper_sections

  !> Drag, with the bottom's area growing over the first draught T_0 of immersion
  !> (continuous first contact), and the pressure on each wet section; then the roll
  !> stiffness of the paper's h_m beyond the hull's own (pressure_roll).
  pure subroutine pressure_sections(self, s, field, t, c, r, wet, vrel, a1max, d0, grad_d, &
                                    volume, window, cache, f)
    !> The level.
    class(pressure_strip_level_type), intent(in) :: self
    !> The strip model's data.
    type(strip_data_type), intent(in) :: s
    !> The sea at the strips.
    type(wave_field_type), intent(in) :: field
    !> Time [s], rotation b -> inertial, CG position (inertial) [m].
    real(wp), intent(in) :: t, c(3, 3), r(3)
    !> The wet sections.
    type(section_wet_type), intent(in) :: wet(s%hull%n)
    !> Relative velocities [m/s], largest wet area [m^2], depths [m] and their gradients,
    !> wet volume [m^3].
    real(wp), intent(in) :: vrel(3, s%hull%n), a1max, d0(s%hull%n), grad_d(3, s%hull%n), &
                            volume
    !> Whether the cache covers t.
    logical, intent(in) :: window
    !> The water at the strips on the slow clock.
    type(strip_wave_cache_type), intent(in), optional :: cache
    !> Generalized forces (Kane order) [N m, N], added to.
    real(wp), intent(inout) :: f(6)
    real(wp) :: fk(3), area(3), chord(4)
    integer :: k
    chord = 0.0_wp
    associate (h => s%hull)
      do k = 1, h%n
        if (wet(k)%area <= 0.0_wp) cycle
        area = drag_areas(s, wet(k), a1max)
        area(3) = area(3)*min(1.0_wp, wet(k)%height/s%draught0)
        fk = strip_drag(s%cd, area, vrel(:, k))
        call pressure_loads(s, field, t, c, r, k, wet(k), d0(k), grad_d(:, k), window, &
                            cache, f)
        if (s%metacentric_height /= s%gm_hull) call add_chord(wet(k), h%x(k), chord)
        call add_strip_force(h%x(k), fk, f)
      end do
    end associate
    call pressure_roll(s, c(3, :), volume, chord, f)
  end subroutine pressure_sections

  !> Drag areas of a wet section (review §1.5): A_1max / n, t_s x wet height, t_s x width.
  pure function drag_areas(s, wet, a1max) result(area)
    type(strip_data_type), intent(in) :: s
    type(section_wet_type), intent(in) :: wet
    real(wp), intent(in) :: a1max
    real(wp) :: area(3)
    area(1) = a1max/real(s%hull%n, wp)
    area(2) = s%hull%thickness*wet%height
    area(3) = s%hull%thickness*wet%width
  end function drag_areas

  !> Quadratic drag on a strip (eq. 22): -1/2 rho C A |v| v along b1, b2, b3.
  pure function strip_drag(cd, area, vrel) result(fk)
    real(wp), intent(in) :: cd(3), area(3), vrel(3)
    real(wp) :: fk(3)
    fk = -0.5_wp*rho_water*cd*area*abs(vrel)*vrel
  end function strip_drag

  !> f_r += fk . (dv/du_r) for a force fk (b) at (x, 0, 0), eq. (20): only u2, u3 (pitch,
  !> yaw) and u4..u6 enter.
  pure subroutine add_strip_force(x, fk, f)
    real(wp), intent(in) :: x, fk(3)
    real(wp), intent(inout) :: f(6)
    f(2) = f(2) - x*fk(3)
    f(3) = f(3) + x*fk(2)
    f(4:6) = f(4:6) + fk
  end subroutine add_strip_force

  !> Pressure on section k (pressure level): the tangent-plane part -rho g V_k grad(d) at
  !> the wet centroid (full 3-D moment about G) and the dynamic remainder p' on the wet
  !> hull edges (section-plane force at x_k and roll moment), added to f; d0 is the depth
  !> of the strip centre below the tangent plane.
  pure subroutine pressure_loads(s, field, t, c, r, k, wet, d0, grad_d, window, cache, f)
    type(strip_data_type), intent(in) :: s
    type(wave_field_type), intent(in) :: field
    real(wp), intent(in) :: t, c(3, 3), r(3), d0, grad_d(3)
    integer, intent(in) :: k
    type(section_wet_type), intent(in) :: wet
    logical, intent(in) :: window
    type(strip_wave_cache_type), intent(in), optional :: cache
    real(wp), intent(inout) :: f(6)
    real(wp) :: fb(3), load(3), rate(3), pc(3)
    logical :: found
    associate (h => s%hull)
      fb = -rho_water*gravity*wet%area*h%thickness*grad_d
      f(1:3) = f(1:3) + cross([h%x(k), wet%centroid], fb)
      f(4:6) = f(4:6) + fb
      if (field%kind == wave_none) return
      found = .false.
      pc = r + c(:, 1)*h%x(k)
      if (window) call cached_wave_load(cache, field, k, t, [d0, grad_d(2:3), c(1:2, 2), &
                                         c(1:2, 3)], pc(1:2), load, found)
      if (.not. found) then
        call section_wave_load(field, t, h, wet, c, pc, d0, grad_d(2), grad_d(3), load, rate)
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

  !> Roll stiffness of the pressure level beyond the hull's own, with the paper's h_m:
  !> the gradient of Phi' = rho g dh (1 - cos phi) V, dh = h_m - GM_T, in calm water: the
  !> moment M = -rho g dh V sin(phi) along d phi/du = (1, -n1 n2/s, -n1 n3/s),
  !> s = n2^2 + n3^2 (phi = atan2(n2, n3) of n3 = C^T N3), and the force
  !> -rho g dh (1 - cos phi) t_s l N3 on the waterline chords (the waterplane).
  pure subroutine pressure_roll(s, n3, volume, chord, f)
    type(strip_data_type), intent(in) :: s
    real(wp), intent(in) :: n3(3), volume, chord(4)
    real(wp), intent(inout) :: f(6)
    real(wp) :: sn, dh, moment, fw(3)
    sn = max(n3(2)**2 + n3(3)**2, tiny(1.0_wp))
    dh = s%metacentric_height - s%gm_hull
    if (dh == 0.0_wp) return
    moment = -rho_water*gravity*dh*volume*n3(2)/sqrt(sn)
    f(1:3) = f(1:3) + moment*[1.0_wp, -n3(1)*n3(2)/sn, -n3(1)*n3(3)/sn]
    if (chord(1) <= 0.0_wp) return
    fw = -rho_water*gravity*dh*(1.0_wp - n3(3)/sqrt(sn))*s%hull%thickness*chord(1)* &
         n3/hypot(n3(2), n3(3))
    f(1:3) = f(1:3) + cross(chord(2:4)/chord(1), fw)
    f(4:6) = f(4:6) + fw
  end subroutine pressure_roll

end module davit_boat_strip_level
