"""Mean wave drift forces from the far field (Maruo 1960; Newman 1967), deep water.

The Kochin function of a solved problem (Capytaine's convention, compute_kochin):
    H(theta) = 1/(4 pi) int sigma(x) exp(k z) exp(-i k ((x - x0) cos theta + (y - y0) sin theta)) dS
over hull and lid, sigma the source strength of the indirect method. The total far field of a
freely floating body in a unit-amplitude incident wave of direction beta is
    H_tot = i (H_diff + sum_j xi_j H_rad_j),
xi_j the motion RAO (radiation problems are solved for unit displacement amplitude:
boundary condition -i omega n.dof), and the mean horizontal loads per unit amplitude squared
are the momentum flux through a far control cylinder (Capytaine's
post_pro.mean_drift_force, its diagonal k = l):
    F_x = -2 pi rho omega cos(beta) Im H_tot(beta) - 2 pi rho k^2 int |H_tot|^2 cos(theta) dtheta
    F_y = -2 pi rho omega sin(beta) Im H_tot(beta) - 2 pi rho k^2 int |H_tot|^2 sin(theta) dtheta
    M_z = 2 pi rho omega / k Re H_tot'(beta) - 2 pi rho k int Im(conj(H_tot) H_tot') dtheta
(' = d/dtheta), about the vertical through x0. The first terms are the interference of the
scattered wave with the incident one, the second the scattered waves' own momentum. Energy
conservation of a body that absorbs nothing ties them: omega Im H_tot(beta) = -k^2 int |H_tot|^2
dtheta (energy_defect measures the departure; it checks the scale of the two terms against each
other).

Everything here is in Capytaine's frame (x forward, y port, z up; wave_direction from x
towards y); postproc.bem_build turns the result into davit's (sway and yaw change sign).
"""
import numpy as np

#: theta grid of the far-field integrals: uniform over [0, 2 pi), so the trapezoidal rule is
#: spectrally accurate for the periodic integrands; H varies like exp(i k L/2 cos theta)
#: (k L/2 = 22 for the 108 m ship at 2 rad/s), resolved with 720 points.
N_THETA = 720


def theta_grid(n=N_THETA):
    return np.arange(n) * (2.0 * np.pi / n)


def kochin_operators(body, k, theta, ref_point=(0.0, 0.0)):
    """Matrices Z, Z' (n_theta x n_faces, hull and lid) with H = Z sigma, H' = Z' sigma."""
    mesh = body.mesh_including_lid
    centres = mesh.faces_centers
    dx = centres[:, 0] - ref_point[0]
    dy = centres[:, 1] - ref_point[1]
    c, s = np.cos(theta), np.sin(theta)
    z = (np.exp(k * centres[:, 2]) * mesh.faces_areas / (4.0 * np.pi))[None, :] \
        * np.exp(-1j * k * (np.outer(c, dx) + np.outer(s, dy)))
    # d/dtheta of exp(-i k (dx cos + dy sin)) = -i k (-dx sin + dy cos) exp(...)
    zp = z * (-1j * k) * (np.outer(-s, dx) + np.outer(c, dy))
    return z, zp


def kochin(results, body, theta, ref_point=(0.0, 0.0)):
    """H and H' (n_results x n_theta) of solved problems of one frequency."""
    k = results[0].wavenumber
    z, zp = kochin_operators(body, k, theta, ref_point)
    sources = np.array([r.sources for r in results]).T
    return (z @ sources).T, (zp @ sources).T


def total_kochin(h_diff, hp_diff, h_rad, hp_rad, xi):
    """H_tot, H_tot' (n_beta x n_theta) from the diffraction functions (n_beta x n_theta),
    the radiation ones (n_dof x n_theta) and the RAOs xi (n_beta x n_dof)."""
    return 1j * (h_diff + xi @ h_rad), 1j * (hp_diff + xi @ hp_rad)


def incident_value(h, theta, beta):
    """h (n_beta x n_theta) at theta = beta of each row, by Fourier interpolation (exact for
    the band-limited Kochin function resolved by the grid)."""
    n = theta.size
    coef = np.fft.fft(h, axis=1) / n
    m = np.fft.fftfreq(n, 1.0 / n)
    return np.sum(coef * np.exp(1j * np.outer(beta, m)), axis=1)


def mean_drift(h, hp, theta, beta, omega, k, rho):
    """(F_x, F_y, M_z) per unit wave amplitude squared (n_beta x 3), Capytaine's frame, from
    the total Kochin function and its derivative on the uniform periodic grid theta."""
    dtheta = theta[1] - theta[0]
    hb = incident_value(h, theta, beta)
    hpb = incident_value(hp, theta, beta)
    a = 2.0 * np.pi * rho * omega
    b = 2.0 * np.pi * rho * k * k
    sq = np.abs(h) ** 2
    fx = -a * np.cos(beta) * hb.imag - b * dtheta * np.sum(sq * np.cos(theta), axis=1)
    fy = -a * np.sin(beta) * hb.imag - b * dtheta * np.sum(sq * np.sin(theta), axis=1)
    mz = a / k * hpb.real - b / k * dtheta * np.sum((np.conj(h) * hp).imag, axis=1)
    return np.stack([fx, fy, mz], axis=1)


def energy_defect(h, theta, beta, omega, k):
    """(omega Im H(beta) + k^2 int |H|^2) / (k^2 int |H|^2) for each heading: zero for a
    body that absorbs no energy (the scattered energy flux is drawn from the incident wave)."""
    dtheta = theta[1] - theta[0]
    scattered = k * k * dtheta * np.sum(np.abs(h) ** 2, axis=1)
    return (omega * incident_value(h, theta, beta).imag + scattered) / scattered


def shift_phase(h, hp, beta, k, ref_point):
    """Kochin functions about ref_point (from compute with ref_point) with the incident wave's
    phase taken there too: multiplied by exp(-i k (x0 cos beta + y0 sin beta)), so the
    formulas above hold about the vertical through ref_point."""
    phase = np.exp(-1j * k * (ref_point[0] * np.cos(beta) + ref_point[1] * np.sin(beta)))
    return h * phase[:, None], hp * phase[:, None]
