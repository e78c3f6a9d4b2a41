!> The lifeboat's radiation and diffraction from a BEM database of its hull (issue 18),
!> added to the strips (davit_boat_strip_loads: nonlinear buoyancy and Froude-Krylov on
!> the instantaneous wetted hull, drag), Cummins' equation scaled with immersion s:
!>   (M + s A(inf)) u' = F_strips - s mu + s F_D - s B44 p - (1/2) s' A(inf) u + F_other,
!>   mu_i = sum_j C_ij x_ij,  x_ij' = A_ij x_ij + B_ij s u_j   (Perez & Fossen 2008),
!> mu the radiation memory of the database's state-space fits (driven by the wet hull's
!> motion s u), F_D the linear diffraction load X - X_FK of each wave component (the
!> strips carry the Froude-Krylov part), B44 a viscous roll damping (potential flow has
!> almost none in roll).
!>
!> Immersion: s = min(1, V_wet/(f V_0)), V_0 = m/rho, f = `&boat full_immersion`, so the
!> boat in the air feels none of it. s is a state, a first-order lag of that geometric
!> value with time constant immersion_lag, so that the mass matrix M + s A(inf) varies
!> continuously and its rate s' is known exactly. Then the force -(1/2) s' A(inf) u keeps
!> the kinetic energy T = 1/2 u^T (M + s A(inf)) u balanced: dT/dt = u^T F_other, the
!> changing added mass neither injects nor removes energy on entry or emergence (the
!> momentum form -s' A(inf) u of von Karman's slamming theory would remove
!> 1/2 s' u^T A u on entry and inject it on emergence).
!>
!> Frames (checked against the ship's database and its loads): the database is in davit's
!> body frame (x forward, y starboard, z down) about the CG, the boat's body frame; DOF order
!> (surge, sway, heave, roll, pitch, yaw), Kane order (omega, v) (eq. 4) by to_kane_order.
!> Wave loads: F = Re[X a exp(i (w t + eps - k (x_G cos g + y_G sin g)))] at the CG's
!> current horizontal position, relative heading beta = g - yaw, in the level heading
!> frame, turned into body axes (F_b = C^T Rz(yaw) F_h) as the ship's. The radiation memory
!> likewise: Cummins' equation is linear in that seakeeping frame h (level, yawed with the
!> boat), not in the rolling and pitching body axes, so mu is fed the speeds resolved in h,
!> m^T u (m = C^T Rz(yaw)), and its load is turned into body axes, m mu. Fed and applied in
!> body axes, the heave memory force of a heeled boat leaned with the heel: a sway force
!> -sin(phi) mu_3, whose mean over a roll in phase with the heave is a spurious second-order
!> drift (the ship's error of issue 20, item 1). A(inf) (the layout's modal block
!> M + s A(inf)) is still applied in body axes, without the turning and transport terms.
module davit_boat_bem_water
  use davit_kinds, only: wp, pi
  use davit_error, only: error_type, fatal_error
  use davit_core_rotation, only: rotation_matrix
  use davit_ship_bem_database, only: bem_database_type, bem_excitation, bracket
  use davit_ship_bem_loads, only: bem_memory, to_kane_order, bem_roll_damping
  use davit_sea_wave_field, only: wave_field_type, wave_none, wave_ramp, wave_chunk, &
                                  component_phases
  use davit_core_slow_clock, only: slow_clock_type
  implicit none
  private
  public :: boat_bem_type, new_boat_bem, boat_bem_loads, boat_bem_immersion, &
            boat_bem_kinetic_energy, diffraction_cache_type, diffraction_refresh

  !> Time constant of the immersion state [s]: short against the boat's periods (~2 s)
  !> and its entry (V_wet reaches f V_0 in ~0.15 s at 1 m/s).
  real(wp), parameter :: immersion_lag = 0.02_wp

  type :: boat_bem_type
    !> The boat's BEM database (added mass, damping, memory fits, diffraction; input/boat_bem.nc).
    type(bem_database_type) :: db
    !> A(inf) in Kane order (symmetrised) [kg, kg m, kg m^2].
    real(wp) :: a_inf(6, 6) = 0.0_wp
    !> Modal form of M + s A(inf): P = M^(-1/2) Q and the eigenvalues lambda of
    !> M^(-1/2) A(inf) M^(-1/2) = Q Lambda Q^T, so (M + s A)^-1 = P diag(1/(1 + s lambda)) P^T.
    real(wp) :: modes(6, 6) = 0.0_wp, lambda(6) = 0.0_wp
    !> Viscous roll damping at full immersion [N m s].
    real(wp) :: b44 = 0.0_wp
    !> V_0 = m/rho [m^3] and the fraction f of it at full immersion.
    real(wp) :: volume0 = 0.0_wp, full = 0.5_wp
    !> Diffraction load a (X - X_FK) of each sea component at each database heading,
    !> (6, heading, component), DOF order.
    complex(wp), allocatable :: diffraction(:, :, :)
  end type boat_bem_type

  !> The diffraction load on the strips' slow clock (issue 14: summed over every wave
  !> component it was half the cost of an irregular launch's water phase). At both ends
  !> t_j of the window, at the CG's horizontal position r0 and the yaw psi0 of the
  !> window's start: the unramped load (DOF order, heading frame), its time rate and its
  !> horizontal gradient, d(6, (value, d/dt, d/dx, d/dy), end). In between: the cubic
  !> Hermite in time plus the gradient (linear in time) times the CG's offset from r0.
  !> What it leaves out: the yaw's change within the window (the heading interpolation of
  !> X, ~d|X|/d(beta) x 0.005 rad) and second order in k |r - r0| (< 2e-3 of a component
  !> for k = 0.6 1/m and 0.1 m).
  type :: diffraction_cache_type
    !> The strips' slow clock at the sampling: the window [t1, t2] and whether it holds.
    type(slow_clock_type) :: clock
    !> The CG's horizontal position r0 (inertial) [m] and the yaw psi0 [rad] it was sampled
    !> at.
    real(wp) :: r0(2) = 0.0_wp, psi0 = 0.0_wp
    !> Load samples d(DOF, (value, d/dt, d/dx, d/dy), end) in the heading frame [N, N m and their
    !> rates].
    real(wp) :: d(6, 4, 2) = 0.0_wp
  end type diffraction_cache_type

  interface
    subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
      import :: wp
      character, intent(in) :: jobz, uplo
      integer, intent(in) :: n, lda, lwork
      real(wp), intent(inout) :: a(lda, *)
      real(wp), intent(out) :: w(*), work(*)
      integer, intent(out) :: info
    end subroutine dsyev
  end interface

contains

  !> The boat's BEM water model from database db for rigid-body mass diagonal m_kane
  !> (I1, I2, I3, m, m, m), in sea `sea`, with roll damping zeta_roll of critical at the
  !> roll stiffness c44 [N m/rad] of the strips, full immersion at f V_0.
  subroutine new_boat_bem(db, sea, m_kane, zeta_roll, c44, full, volume0, self, error)
    !> The boat's BEM database.
    type(bem_database_type), intent(in) :: db
    !> The sea whose waves excite the diffraction load.
    type(wave_field_type), intent(in) :: sea
    !> Rigid-body mass diagonal (I1, I2, I3, m, m, m) [kg m^2, kg]; roll damping fraction of
    !> critical; roll stiffness of the strips [N m/rad]; fraction f of V_0 at full immersion; V_0 =
    !> m/rho [m^3].
    real(wp), intent(in) :: m_kane(6), zeta_roll, c44, full, volume0
    !> The water model built.
    type(boat_bem_type), intent(out) :: self
    !> Set when the database does not fit the boat (sizes, a singular mass).
    type(error_type), allocatable, intent(out) :: error
    real(wp) :: s(6, 6), work(64)
    integer :: i, j, info
    self%db = db
    self%full = full
    self%volume0 = volume0
    self%a_inf = to_kane_order(0.5_wp*(db%added_mass_inf + transpose(db%added_mass_inf)))
    do j = 1, 6
      do i = 1, 6
        s(i, j) = self%a_inf(i, j)/sqrt(m_kane(i)*m_kane(j))
      end do
    end do
    call dsyev("V", "U", 6, s, 6, self%lambda, work, size(work), info)
    ! M + s A(inf) must stay positive definite for every s in [0, 1]
    if (info /= 0 .or. any(self%lambda <= -1.0_wp)) then
      call fatal_error(error, "BEM database '"//db%path//"': M + A(inf) of the boat is "// &
                       "not positive definite")
      return
    end if
    do j = 1, 6
      self%modes(:, j) = s(:, j)/sqrt(m_kane)
    end do
    self%b44 = bem_roll_damping(db, zeta_roll, c44, m_kane(1))
    call diffraction_table(self, sea)
  end subroutine new_boat_bem

  !> a (X - X_FK) of every component at every database heading.
  pure subroutine diffraction_table(self, sea)
    type(boat_bem_type), intent(inout) :: self
    type(wave_field_type), intent(in) :: sea
    integer :: i, k
    associate (h => self%db%heading)
      allocate (self%diffraction(6, size(h), sea%n))
      do i = 1, sea%n
        do k = 1, size(h)
          self%diffraction(:, k, i) = sea%amplitude(i)* &
                                      bem_excitation(self%db, sea%omega(i), h(k), .true.)
        end do
      end do
    end associate
  end subroutine diffraction_table

  !> The geometric immersion min(1, V_wet/(f V_0)) of wet volume `volume` [m^3].
  pure real(wp) function boat_bem_immersion(self, volume) result(s)
    !> The boat's BEM water model.
    type(boat_bem_type), intent(in) :: self
    !> Wet volume of the hull [m^3].
    real(wp), intent(in) :: volume
    s = min(1.0_wp, max(0.0_wp, volume/(self%full*self%volume0)))
  end function boat_bem_immersion

  !> Added kinetic energy 1/2 s u^T A(inf) u [J] at immersion s and speeds u (Kane order).
  pure real(wp) function boat_bem_kinetic_energy(self, s, u) result(e)
    !> The boat's BEM water model.
    type(boat_bem_type), intent(in) :: self
    !> Immersion s (0..1) and the boat's speeds u (Kane order) [rad/s, m/s].
    real(wp), intent(in) :: s, u(6)
    e = 0.5_wp*s*dot_product(u, matmul(self%a_inf, u))
  end function boat_bem_kinetic_energy

  !> Generalized forces f (Kane order) of the BEM terms on the boat at time t, rotation c,
  !> CG r (inertial), yaw psi, speeds u, geometric immersion s_geom, and its states x =
  !> (s, memory states) with their rates xdot; the modal masses v = 1 + s lambda of the
  !> boat's coupled mass block (davit_core_layout).
  pure subroutine boat_bem_loads(self, sea, t, c, r, psi, u, s_geom, x, cache, xdot, f, v)
    !> The boat's BEM water model.
    type(boat_bem_type), intent(in) :: self
    !> The sea (diffraction load and its ramp).
    type(wave_field_type), intent(in) :: sea
    !> Time [s], rotation b -> inertial, CG position (inertial) [m], yaw [rad], speeds (Kane
    !> order), geometric immersion (0..1), and the states (lagged immersion, memory states).
    real(wp), intent(in) :: t, c(3, 3), r(3), psi, u(6), s_geom, x(:)
    !> The diffraction load's slow-clock window (used when valid).
    type(diffraction_cache_type), intent(in) :: cache
    !> Rates of the states; generalized forces (Kane order) [N m, N]; modal masses 1 + s lambda.
    real(wp), intent(out) :: xdot(:), f(6), v(6)
    real(wp) :: mu(6), s, load(6), m(3, 3)
    s = x(1)
    xdot(1) = (s_geom - s)/immersion_lag
    if (s <= 0.0_wp .and. s_geom <= 0.0_wp .and. all(x(2:) == 0.0_wp)) then
      ! in the air before the first water contact the memory is at rest with no input
      ! and stays so: skip its state-space products (exact, and most of a launch)
      xdot(2:) = 0.0_wp
      f = 0.0_wp
      v = 1.0_wp
      return
    end if
    ! the memory of Cummins' equation in the seakeeping frame (level, yawed with the boat;
    ! m = C^T Rz(psi) turns its components into body axes): fed the speeds resolved
    ! there, its load turned back into body axes (as the ship's, davit_ship_ship_model)
    m = matmul(transpose(c), rotation_matrix([0.0_wp, 0.0_wp, psi]))
    call bem_memory(self%db, x(2:), s*[matmul(u(4:6), m), matmul(u(1:3), m)], xdot(2:), mu)
    f = -s*[matmul(m, mu(4:6)), matmul(m, mu(1:3))] - 0.5_wp*xdot(1)*matmul(self%a_inf, u)
    f(1) = f(1) - s*self%b44*u(1)
    v = 1.0_wp + s*self%lambda
    if (s <= 0.0_wp .or. sea%kind == wave_none) return
    if (cache%clock%covers(t)) then
      load = wave_ramp(sea, t)*cached_diffraction(cache, t, r)
    else
      load = wave_ramp(sea, t)*diffraction_load(self, sea, t, r, psi)
    end if
    f(1:3) = f(1:3) + s*matmul(m, load(4:6))
    f(4:6) = f(4:6) + s*matmul(m, load(1:3))
  end subroutine boat_bem_loads

  !> Sample the window of the slow clock `clock` (open: valid) at the CG's horizontal
  !> position r(1:2) and yaw psi.
  pure subroutine diffraction_refresh(self, sea, clock, r, psi, cache)
    !> The boat's BEM water model.
    type(boat_bem_type), intent(in) :: self
    !> The sea whose diffraction load is sampled.
    type(wave_field_type), intent(in) :: sea
    !> The strips' slow clock: the window [t1, t2] sampled.
    type(slow_clock_type), intent(in) :: clock
    !> CG position (inertial) [m], yaw [rad].
    real(wp), intent(in) :: r(3), psi
    !> The window sampled.
    type(diffraction_cache_type), intent(out) :: cache
    cache%clock = clock
    cache%r0 = r(1:2)
    cache%psi0 = psi
    call diffraction_sums(self, sea, cache%clock%window, r, psi, cache%d)
  end subroutine diffraction_refresh

  !> The unramped load at t and CG position r from the window.
  pure function cached_diffraction(cache, t, r) result(load)
    type(diffraction_cache_type), intent(in) :: cache
    real(wp), intent(in) :: t, r(3)
    real(wp) :: load(6), s, hw(4), dx(2)
    associate (w => cache%clock%window)
      s = (t - w(1))/(w(2) - w(1))
    end associate
    hw = cache%clock%weights(t)
    dx = r(1:2) - cache%r0
    associate (d => cache%d)
      load = hw(1)*d(:, 1, 1) + hw(2)*d(:, 2, 1) + hw(3)*d(:, 1, 2) + hw(4)*d(:, 2, 2) + &
             (1.0_wp - s)*(d(:, 3, 1)*dx(1) + d(:, 4, 1)*dx(2)) + &
             s*(d(:, 3, 2)*dx(1) + d(:, 4, 2)*dx(2))
    end associate
  end function cached_diffraction

  !> The unramped diffraction load at the times t (position r, yaw psi) with its time rate
  !> and horizontal gradient, d(DOF, (value, d/dt, d/dx, d/dy), time): with
  !> D e^(i Phi) = P + i Q per component (Phi = w t + eps - kx x - ky y), the load is
  !> sum P, d/dt = -sum w Q, d/dx = sum kx Q, d/dy = sum ky Q.
  pure subroutine diffraction_sums(self, sea, t, r, psi, d)
    type(boat_bem_type), intent(in) :: self
    type(wave_field_type), intent(in) :: sea
    real(wp), intent(in) :: t(:), r(3), psi
    real(wp), intent(out) :: d(6, 4, size(t))
    real(wp) :: sn(wave_chunk, size(t)), cs(wave_chunk, size(t)), beta, w, p(6), q(6)
    real(wp) :: dr(6), di(6)
    integer :: i, k, i0, m, j, l
    d = 0.0_wp
    associate (h => self%db%heading)
      do i0 = 1, sea%n, wave_chunk
        m = min(wave_chunk, sea%n - i0 + 1)
        do j = 1, size(t)
          call component_phases(sea, i0, m, t(j), r(1), r(2), sn(:, j), cs(:, j))
        end do
        do i = i0, i0 + m - 1
          ! the heading interpolation is the same at every time: once per component
          beta = modulo(sea%direction(i) - psi - h(1), 2.0_wp*pi) + h(1)
          call bracket(h, beta, k, w)
          dr = (1.0_wp - w)*real(self%diffraction(:, k, i), wp) + &
               w*real(self%diffraction(:, k + 1, i), wp)
          di = (1.0_wp - w)*aimag(self%diffraction(:, k, i)) + &
               w*aimag(self%diffraction(:, k + 1, i))
          l = i - i0 + 1
          do j = 1, size(t)
            p = dr*cs(l, j) - di*sn(l, j)
            q = dr*sn(l, j) + di*cs(l, j)
            d(:, 1, j) = d(:, 1, j) + p
            d(:, 2, j) = d(:, 2, j) - sea%omega(i)*q
            d(:, 3, j) = d(:, 3, j) + sea%kx(i)*q
            d(:, 4, j) = d(:, 4, j) + sea%ky(i)*q
          end do
        end do
      end do
    end associate
  end subroutine diffraction_sums

  !> Sum over the components of Re[a (X - X_FK) e^(i Phi)] (DOF order, heading frame),
  !> Phi = w t + eps - k . r_G, X at beta = g - psi, linear in beta: the exact load where
  !> the slow clock has no window (regular seas, or a step outside it).
  pure function diffraction_load(self, sea, t, r, psi) result(load)
    type(boat_bem_type), intent(in) :: self
    type(wave_field_type), intent(in) :: sea
    real(wp), intent(in) :: t, r(3), psi
    real(wp) :: load(6), d(6, 4, 1)
    call diffraction_sums(self, sea, [t], r, psi, d)
    load = d(:, 1, 1)
  end function diffraction_load

end module davit_boat_bem_water
