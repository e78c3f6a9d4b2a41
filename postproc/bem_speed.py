"""Forward-speed corrections of the zero-speed radiation coefficients, and their size on a
ship making way (the SOLAS headway launch): an estimate of what davit's BEM ship leaves out.

davit's ship making way meets the waves at their encounter frequencies w_e = w - k U cos
beta (beta the wave direction relative to the heading, 0 following, 180 deg head) and
feeds its zero-speed radiation memory the speeds about the steady forward motion (doc/
theory/ship.md, "MMG with BEM seakeeping"); the speed-dependent terms of the radiation
coefficients are in it with `&ship speed_terms = 'heave_pitch'` or 'stf' (written in the
time domain, src/ship/bem_loads.f90 bem_speed_load; test/test_ship_speed.f90 checks its
heave and pitch response against encounter_raos(..., stf=True)). Strip theory gives them (Salvesen, Tuck and Faltinsen, Ship
motions and sea loads, Trans. SNAME 78, 1970, Table 1 without the end terms; the zero-speed
coefficients here are the whole hull's): with x forward,

  A35 = A35' - U/w^2 B33    B35 = B35' + U A33     A53 = A53' + U/w^2 B33    B53 = B53' - U A33
  A55 = A55' + U^2/w^2 A33  B55 = B55' + U^2/w^2 B33
  A26 = A26' + U/w^2 B22    B26 = B26' - U A22     A62 = A62' - U/w^2 B22    B62 = B62' + U A22
  A46 = A46' + U/w^2 B24    B46 = B46' - U A24     A64 = A64' - U/w^2 B24    B64 = B64' + U A24
  A66 = A66' + U^2/w^2 A22  B66 = B66' + U^2/w^2 B22

(' the zero-speed value, all at w = w_e). They come from the pitch and yaw potentials of a
body making way, phi_5 = -x phi_3 + (U / (i w)) phi_3 and phi_6 = x phi_2 - (U / (i w)) phi_2,
and satisfy the Timman-Newman relations A_ij(U) = A_ji(-U), B_ij(U) = B_ji(-U). Written in
STF's frame (x forward, y to port, z up), they keep their form in davit's (x forward,
y starboard, z down: heave, pitch, sway and yaw change sign, surge and roll do not), since
each relation joins DOFs whose signs change alike (3 with 5, 2 with 6).
"""
import numpy as np

from . import bem_rao


def stf_coefficients(omega_e, added_mass, damping, speed):
    """(A(U), B(U)) (nw, 6, 6) from the zero-speed A, B (nw, 6, 6) at the encounter
    frequencies omega_e (nw,) and the forward speed U [m/s] (module doc)."""
    a0 = np.asarray(added_mass, float)
    b0 = np.asarray(damping, float)
    a, b = a0.copy(), b0.copy()
    u = float(speed)
    r = u / np.asarray(omega_e, float)**2
    # heave-pitch (3, 5 -> indices 2, 4): sign -1 on the 35 added mass; sway-yaw and
    # roll-yaw (2, 6 and 4, 6 -> 1, 5 and 3, 5): sign +1 on the i6 added mass
    for i, j, k, sign in ((2, 4, 2, -1.0), (1, 5, 1, 1.0), (3, 5, 1, 1.0)):
        # the force i from motion j: the potential of j gains sign (U / (i w)) phi_k
        a[:, i, j] += sign * r * b0[:, i, k]
        b[:, i, j] -= sign * u * a0[:, i, k]
        a[:, j, i] -= sign * r * b0[:, i, k]
        b[:, j, i] += sign * u * a0[:, i, k]
    for j, k in ((4, 2), (5, 1)):
        a[:, j, j] += u * r * a0[:, k, k]
        b[:, j, j] += u * r * b0[:, k, k]
    return a, b


def encounter_frequency(omega, heading, speed, g=9.81):
    """w_e = w - k U cos(beta), k = w^2 / g (deep water); beta davit's relative heading."""
    return omega - omega**2 / g * speed * np.cos(heading)


def encounter_raos(base, omega, heading, speed, zeta=0.05, stf=False):
    """(6,) complex response of the database's ship making way at U to a regular wave of
    frequency omega and relative heading beta: the zero-speed excitation X(omega, beta) and
    the radiation coefficients at w_e (zero-speed ones, as davit's memory gives them with
    speed_terms = 'none', or with stf_coefficients, as with 'stf'), the roll damping zeta
    of bem_rao."""
    we = float(encounter_frequency(omega, heading, speed))
    w = np.array([we])
    a = bem_rao._interp_omega(base.added_mass, base.omega, w)
    b = bem_rao._interp_omega(base.damping, base.omega, w)
    if stf:
        a, b = stf_coefficients(w, a, b, speed)
    x = bem_rao._interp_heading(bem_rao._interp_omega(base.excitation, base.omega,
                                                      np.array([omega])),
                                base.heading, np.array([heading]))[0, 0]
    bv = np.zeros((6, 6))
    bv[3, 3] = bem_rao.roll_damping(base, zeta) if zeta > 0 else 0.0
    z = -we**2 * (base.mass + a[0]) + 1j * we * (b[0] + bv) + base.stiffness
    return np.linalg.solve(z, x)
