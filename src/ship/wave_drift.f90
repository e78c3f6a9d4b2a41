!> Second-order mean and slowly varying wave drift loads on the BEM ship (surge, sway, yaw), from
!> the database's mean drift coefficients D(omega, beta) (far-field momentum flux, Maruo 1960,
!> per unit amplitude squared; postproc.bem_drift).
!>
!> Levels of detail (`&ship drift`), extensions of wave_drift_type chosen once at build
!> (davit_system_law_factory; 'none' builds none, and the ship adds no drift load):
!>  * 'mean': the mean load sum_i D_i a_i^2 (exact in a regular wave; in an irregular sea the
!>    mean of the slowly varying load).
!>  * 'newman': Newman's (1974) approximation of the difference-frequency load,
!>      F(t) = sum_i sum_j a_i a_j T_ij cos((w_i - w_j) t + eps_i - eps_j),
!>    T_ij = sign(D_i) sqrt(D_i D_j) where D_i and D_j share a sign and 0 where they do not,
!>    summed as the single sums F = |P+|^2 - |P-|^2, P+- = sum_{+-D_i > 0} a_i sqrt(|D_i|)
!>    exp(i Phi_i) (O(N), not O(N^2)); its mean is sum_i D_i a_i^2 and in a regular wave it
!>    is the constant mean load.
!> The phases Phi_i are those of the first-order loads (at the CG's initial position); the
!> loads act in the seakeeping frame (level, yawed with the ship) and grow with the square of
!> the sea's start-up ramp.
module davit_ship_wave_drift
  use davit_kinds, only: wp
  use davit_ship_bem_database, only: bem_database_type, bem_drift
  use davit_sea_wave_field, only: wave_field_type, wave_ramp, wave_chunk, component_phases
  implicit none
  private
  public :: wave_drift_type, mean_drift_type, newman_drift_type, drift_mean, drift_newman, &
            drift_names, drift_coefficients, drift_load

  !> The values of `&ship drift`: none, the mean load, Newman's slowly varying load.
  character(len=*), parameter :: drift_names(3) = [character(len=6) :: "none", "mean", &
                                                   "newman"]

  !> A level of the second-order drift load: (X, Y, N) from the signed coefficients.
  type, abstract :: wave_drift_type
  contains
    procedure(drift_force_i), deferred :: force
  end type wave_drift_type

  !> The mean load sum_i D_i a_i^2.
  type, extends(wave_drift_type) :: mean_drift_type
  contains
    procedure :: force => mean_force
  end type mean_drift_type

  !> Newman's (1974) slowly varying load |P+|^2 - |P-|^2.
  type, extends(wave_drift_type) :: newman_drift_type
  contains
    procedure :: force => newman_force
  end type newman_drift_type

  !> The two levels, as the values drift_load and the ship's set_drift take.
  type(mean_drift_type), parameter :: drift_mean = mean_drift_type()
  type(newman_drift_type), parameter :: drift_newman = newman_drift_type()

  abstract interface
    !> Surge, sway [N] and yaw [N m] of the drift load at time t without the start-up
    !> ramp, from the coefficients of drift_coefficients, the phases taken at (x, y).
    pure function drift_force_i(self, sea, coef, t, x, y) result(f)
      import :: wp, wave_drift_type, wave_field_type
      class(wave_drift_type), intent(in) :: self
      !> The sea (phases).
      type(wave_field_type), intent(in) :: sea
      !> The coefficients (3, number of components), time t [s] and the horizontal
      !> position x, y [m] (earth frame) the phases are taken at.
      real(wp), intent(in) :: coef(:, :), t, x, y
      real(wp) :: f(3)
    end function drift_force_i
  end interface

contains

  !> a_i sqrt(|D_i|) sign(D_i) of each component (surge, sway, yaw) for the ship at heading
  !> psi: the signed square roots that both levels sum.
  pure subroutine drift_coefficients(db, sea, psi, coef)
    !> The BEM database (with its drift coefficients).
    type(bem_database_type), intent(in) :: db
    !> The sea (component amplitudes [m], frequencies [rad/s], directions [rad]).
    type(wave_field_type), intent(in) :: sea
    !> The ship's heading psi [rad].
    real(wp), intent(in) :: psi
    !> a_i sqrt(|D_i|) sign(D_i), shape (3, number of components): surge, sway [N^(1/2)] and
    !> yaw [(N m)^(1/2)].
    real(wp), intent(out) :: coef(:, :)
    real(wp) :: d(3)
    integer :: i
    do i = 1, sea%n
      d = bem_drift(db, sea%omega(i), sea%direction(i) - psi)
      coef(:, i) = sign(sea%amplitude(i)*sqrt(abs(d)), d)
    end do
  end subroutine drift_coefficients

  !> The drift load (X, Y, Z, K, M, N; Z, K, M zero) in the seakeeping frame at time t of
  !> level `level` from the coefficients of drift_coefficients, the phases taken at (x, y),
  !> grown with the square of the sea's start-up ramp.
  pure function drift_load(level, sea, coef, t, x, y) result(load)
    !> drift_mean or drift_newman (or another extension of wave_drift_type).
    class(wave_drift_type), intent(in) :: level
    !> The sea (phases, start-up ramp).
    type(wave_field_type), intent(in) :: sea
    !> The coefficients of drift_coefficients (3, number of components), time t [s] and the
    !> horizontal position x, y [m] (earth frame) the phases are taken at.
    real(wp), intent(in) :: coef(:, :), t, x, y
    real(wp) :: load(6)
    load = 0.0_wp
    load([1, 2, 6]) = wave_ramp(sea, t)**2*level%force(sea, coef, t, x, y)
  end function drift_load

  !> The mean load sum_i D_i a_i^2 = sum_i sign(c_i) c_i^2 (exact in a regular wave).
  pure function mean_force(self, sea, coef, t, x, y) result(f)
    !> The level.
    class(mean_drift_type), intent(in) :: self
    !> The sea (phases).
    type(wave_field_type), intent(in) :: sea
    !> The coefficients (3, number of components), time t [s] and the horizontal
    !> position x, y [m] (earth frame) the phases are taken at.
    real(wp), intent(in) :: coef(:, :), t, x, y
    real(wp) :: f(3)
    f = sum(sign(coef**2, coef), dim=2)
  end function mean_force

  !> Newman's load as the single sums F = |P+|^2 - |P-|^2, P+- = sum_{+-c_i > 0} |c_i|
  !> exp(i Phi_i) (O(N), not O(N^2)).
  pure function newman_force(self, sea, coef, t, x, y) result(f)
    !> The level.
    class(newman_drift_type), intent(in) :: self
    !> The sea (phases).
    type(wave_field_type), intent(in) :: sea
    !> The coefficients (3, number of components), time t [s] and the horizontal
    !> position x, y [m] (earth frame) the phases are taken at.
    real(wp), intent(in) :: coef(:, :), t, x, y
    real(wp) :: f(3)
    real(wp) :: s(wave_chunk), c(wave_chunk), pc(3, 2), ps(3, 2)
    integer :: i0, i, m, j
    pc = 0.0_wp
    ps = 0.0_wp
    do i0 = 1, sea%n, wave_chunk
      m = min(wave_chunk, sea%n - i0 + 1)
      call component_phases(sea, i0, m, t, x, y, s, c)
      do i = 1, m
        do j = 1, 3
          ! column 1 the positive coefficients, column 2 the negative ones
          if (coef(j, i0 + i - 1) >= 0.0_wp) then
            pc(j, 1) = pc(j, 1) + coef(j, i0 + i - 1)*c(i)
            ps(j, 1) = ps(j, 1) + coef(j, i0 + i - 1)*s(i)
          else
            pc(j, 2) = pc(j, 2) - coef(j, i0 + i - 1)*c(i)
            ps(j, 2) = ps(j, 2) - coef(j, i0 + i - 1)*s(i)
          end if
        end do
      end do
    end do
    f = pc(:, 1)**2 + ps(:, 1)**2 - pc(:, 2)**2 - ps(:, 2)**2
  end function newman_force

end module davit_ship_wave_drift
