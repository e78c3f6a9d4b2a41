!> The boat's water terms on top of the strips (&boat water_model), chosen once at build:
!> none (the strips alone: 'pressure', 'paper') or the BEM terms ('bem',
!> davit_boat_bem_water: added mass M + s A(inf) as a modal coupled block, radiation
!> memory, diffraction and roll damping, with the lagged immersion s and the memory as
!> the states of part "boat_radiation"). The boat's loads, the after-step hook, the
!> energy and the initial state call these bindings and never ask which it is.
module davit_boat_water_terms
  use davit_kinds, only: wp
  use davit_core_layout, only: state_layout_type, state_part_type
  use davit_core_slow_clock, only: slow_clock_type
  use davit_sea_wave_field, only: wave_field_type
  use davit_boat_bem_water, only: boat_bem_type, boat_bem_loads, boat_bem_immersion, &
                                  boat_bem_kinetic_energy, diffraction_cache_type, &
                                  diffraction_refresh
  implicit none
  private
  public :: water_terms_type, strips_alone_type, bem_terms_type

  !> The water's terms beyond the strips.
  type, abstract :: water_terms_type
  contains
    procedure(add_states_i), deferred :: add_states
    procedure(start_i), deferred :: start_states
    procedure(modal_i), deferred :: modal_masses
    procedure(loads_i), deferred :: add_loads
    procedure(refresh_i), deferred :: refresh
    procedure(energy_i), deferred :: add_kinetic_energy
    procedure(immersion_i), deferred :: immersion
  end type water_terms_type

  !> The strips alone: no states, loads or mass of their own.
  type, extends(water_terms_type) :: strips_alone_type
  contains
    procedure :: add_states => none_states
    procedure :: start_states => none_start
    procedure :: modal_masses => none_modal
    procedure :: add_loads => none_loads
    procedure :: refresh => none_refresh
    procedure :: add_kinetic_energy => none_energy
    procedure :: immersion => none_immersion
  end type strips_alone_type

  !> The BEM terms of the hull's database.
  type, extends(water_terms_type) :: bem_terms_type
    !> The boat's BEM water model (database, modes, roll damping).
    type(boat_bem_type) :: bem
  contains
    procedure :: add_states => bem_states
    procedure :: start_states => bem_start
    procedure :: modal_masses => bem_modal
    procedure :: add_loads => bem_loads
    procedure :: refresh => bem_refresh
    procedure :: add_kinetic_energy => bem_energy
    procedure :: immersion => bem_immersion
  end type bem_terms_type

  abstract interface
    !> Register the terms' states (part "boat_radiation") after the boat's part and the
    !> boat's mass block they change.
    subroutine add_states_i(self, layout, boat, part)
      import :: water_terms_type, state_layout_type, state_part_type
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> The system's state layout, parts added.
      type(state_layout_type), intent(inout) :: layout
      !> The boat's rigid-body part.
      type(state_part_type), intent(in) :: boat
      !> The terms' own part (left empty without states).
      type(state_part_type), intent(inout) :: part
    end subroutine add_states_i

    !> The terms' states at the start, for the boat's initial wet volume.
    pure subroutine start_i(self, volume, x)
      import :: water_terms_type, wp
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> Wet volume of the hull in its initial pose [m^3].
      real(wp), intent(in) :: volume
      !> The terms' states.
      real(wp), intent(out) :: x(:)
    end subroutine start_i

    !> The boat's modal masses v at states x where the slow loads are not evaluated (the
    !> fast part of a multirate step); the terms' rates are then zero.
    pure subroutine modal_i(self, x, v)
      import :: water_terms_type, wp
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> The terms' states.
      real(wp), intent(in) :: x(:)
      !> Modal masses of the boat's coupled block (1: none).
      real(wp), intent(inout) :: v(6)
    end subroutine modal_i

    !> The terms' generalized forces added to f (Kane order), their states' rates and the
    !> boat's modal masses, at time t for the boat at c, r with yaw psi and speeds u.
    pure subroutine loads_i(self, sea, t, c, r, psi, u, volume, x, cache, xdot, f, v)
      import :: water_terms_type, wave_field_type, diffraction_cache_type, wp
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> The sea.
      type(wave_field_type), intent(in) :: sea
      !> Time [s], rotation b -> inertial, CG position (inertial) [m], yaw [rad], speeds
      !> (Kane order), the strips' wet volume [m^3] and the terms' states.
      real(wp), intent(in) :: t, c(3, 3), r(3), psi, u(6), volume, x(:)
      !> The diffraction load's slow-clock window.
      type(diffraction_cache_type), intent(in) :: cache
      !> The states' rates.
      real(wp), intent(out) :: xdot(:)
      !> Generalized forces [N m, N], the terms' added; modal masses.
      real(wp), intent(inout) :: f(6), v(6)
    end subroutine loads_i

    !> After a step: sample the diffraction load on the strips' window when the hull can
    !> be wet (`wet`), else close the window.
    pure subroutine refresh_i(self, sea, clock, r, psi, wet, cache)
      import :: water_terms_type, wave_field_type, slow_clock_type, &
                diffraction_cache_type, wp
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> The sea.
      type(wave_field_type), intent(in) :: sea
      !> The strips' slow clock (its window).
      type(slow_clock_type), intent(in) :: clock
      !> CG position (inertial) [m] and yaw [rad].
      real(wp), intent(in) :: r(3), psi
      !> Whether any strip may be wet or the boat is immersed.
      logical, intent(in) :: wet
      !> The diffraction window, sampled or closed.
      type(diffraction_cache_type), intent(inout) :: cache
    end subroutine refresh_i

    !> The terms' kinetic energy added to e [J].
    pure subroutine energy_i(self, x, u, e)
      import :: water_terms_type, wp
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> The terms' states and the boat's speeds (Kane order).
      real(wp), intent(in) :: x(:), u(6)
      !> The energy [J].
      real(wp), intent(inout) :: e
    end subroutine energy_i

    !> The lagged immersion s (0..1) in the terms' states (0 without one).
    pure real(wp) function immersion_i(self, x) result(s)
      import :: water_terms_type, wp
      !> The terms.
      class(water_terms_type), intent(in) :: self
      !> The terms' states.
      real(wp), intent(in) :: x(:)
    end function immersion_i
  end interface

contains

  subroutine none_states(self, layout, boat, part)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> The system's state layout, parts added.
    type(state_layout_type), intent(inout) :: layout
    !> The boat's rigid-body part.
    type(state_part_type), intent(in) :: boat
    !> The terms' own part (left empty without states).
    type(state_part_type), intent(inout) :: part
  end subroutine none_states

  pure subroutine none_start(self, volume, x)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> Wet volume of the hull in its initial pose [m^3].
    real(wp), intent(in) :: volume
    !> The terms' states.
    real(wp), intent(out) :: x(:)
  end subroutine none_start

  pure subroutine none_modal(self, x, v)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> The terms' states.
    real(wp), intent(in) :: x(:)
    !> Modal masses of the boat's coupled block (1: none).
    real(wp), intent(inout) :: v(6)
  end subroutine none_modal

  pure subroutine none_loads(self, sea, t, c, r, psi, u, volume, x, cache, xdot, f, v)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> Time [s], rotation b -> inertial, CG position (inertial) [m], yaw [rad], speeds
    !> (Kane order), the strips' wet volume [m^3] and the terms' states.
    real(wp), intent(in) :: t, c(3, 3), r(3), psi, u(6), volume, x(:)
    !> The diffraction load's slow-clock window.
    type(diffraction_cache_type), intent(in) :: cache
    !> The states' rates.
    real(wp), intent(out) :: xdot(:)
    !> Generalized forces [N m, N], the terms' added; modal masses.
    real(wp), intent(inout) :: f(6), v(6)
  end subroutine none_loads

  pure subroutine none_refresh(self, sea, clock, r, psi, wet, cache)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> The strips' slow clock (its window).
    type(slow_clock_type), intent(in) :: clock
    !> CG position (inertial) [m] and yaw [rad].
    real(wp), intent(in) :: r(3), psi
    !> Whether any strip may be wet or the boat is immersed.
    logical, intent(in) :: wet
    !> The diffraction window, sampled or closed.
    type(diffraction_cache_type), intent(inout) :: cache
    call cache%clock%invalidate()
  end subroutine none_refresh

  pure subroutine none_energy(self, x, u, e)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> The terms' states and the boat's speeds (Kane order).
    real(wp), intent(in) :: x(:), u(6)
    !> The energy [J].
    real(wp), intent(inout) :: e
  end subroutine none_energy

  pure real(wp) function none_immersion(self, x) result(s)
    !> The terms.
    class(strips_alone_type), intent(in) :: self
    !> The terms' states.
    real(wp), intent(in) :: x(:)
    s = 0.0_wp
  end function none_immersion

  !> The lagged immersion and the memory's states; the boat's speeds as a modal coupled
  !> block (M + s A(inf)).
  subroutine bem_states(self, layout, boat, part)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> The system's state layout, parts added.
    type(state_layout_type), intent(inout) :: layout
    !> The boat's rigid-body part.
    type(state_part_type), intent(in) :: boat
    !> The terms' own part (left empty without states).
    type(state_part_type), intent(inout) :: part
    call layout%add("boat_radiation", self%bem%db%nrad + 1, 0, part)
    call layout%couple(boat%u, self%bem%modes, modal=.true.)
  end subroutine bem_states

  !> A boat released afloat starts with its added mass (the geometric immersion of its
  !> initial pose) and no radiation memory yet.
  pure subroutine bem_start(self, volume, x)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> Wet volume of the hull in its initial pose [m^3].
    real(wp), intent(in) :: volume
    !> The terms' states.
    real(wp), intent(out) :: x(:)
    x = 0.0_wp
    x(1) = boat_bem_immersion(self%bem, volume)
  end subroutine bem_start

  !> v = 1 + s lambda at the lagged immersion s.
  pure subroutine bem_modal(self, x, v)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> The terms' states.
    real(wp), intent(in) :: x(:)
    !> Modal masses of the boat's coupled block (1: none).
    real(wp), intent(inout) :: v(6)
    v = 1.0_wp + x(1)*self%bem%lambda
  end subroutine bem_modal

  !> boat_bem_loads at the geometric immersion of the strips' wet volume.
  pure subroutine bem_loads(self, sea, t, c, r, psi, u, volume, x, cache, xdot, f, v)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> Time [s], rotation b -> inertial, CG position (inertial) [m], yaw [rad], speeds
    !> (Kane order), the strips' wet volume [m^3] and the terms' states.
    real(wp), intent(in) :: t, c(3, 3), r(3), psi, u(6), volume, x(:)
    !> The diffraction load's slow-clock window.
    type(diffraction_cache_type), intent(in) :: cache
    !> The states' rates.
    real(wp), intent(out) :: xdot(:)
    !> Generalized forces [N m, N], the terms' added; modal masses.
    real(wp), intent(inout) :: f(6), v(6)
    real(wp) :: fw(6)
    call boat_bem_loads(self%bem, sea, t, c, r, psi, u, boat_bem_immersion(self%bem, volume), &
                        x, cache, xdot, fw, v)
    f = f + fw
  end subroutine bem_loads

  !> The diffraction acts only on a wet hull (lagged immersion s > 0), on the strips'
  !> window.
  pure subroutine bem_refresh(self, sea, clock, r, psi, wet, cache)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> The sea.
    type(wave_field_type), intent(in) :: sea
    !> The strips' slow clock (its window).
    type(slow_clock_type), intent(in) :: clock
    !> CG position (inertial) [m] and yaw [rad].
    real(wp), intent(in) :: r(3), psi
    !> Whether any strip may be wet or the boat is immersed.
    logical, intent(in) :: wet
    !> The diffraction window, sampled or closed.
    type(diffraction_cache_type), intent(inout) :: cache
    if (wet) then
      call diffraction_refresh(self%bem, sea, clock, r, psi, cache)
    else
      call cache%clock%invalidate()
    end if
  end subroutine bem_refresh

  !> 1/2 s u^T A(inf) u.
  pure subroutine bem_energy(self, x, u, e)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> The terms' states and the boat's speeds (Kane order).
    real(wp), intent(in) :: x(:), u(6)
    !> The energy [J].
    real(wp), intent(inout) :: e
    e = e + boat_bem_kinetic_energy(self%bem, x(1), u)
  end subroutine bem_energy

  pure real(wp) function bem_immersion(self, x) result(s)
    !> The terms.
    class(bem_terms_type), intent(in) :: self
    !> The terms' states.
    real(wp), intent(in) :: x(:)
    s = x(1)
  end function bem_immersion

end module davit_boat_water_terms
