"""Mesh convergence of a BEM database (`python -m postproc.bem compare FINE COARSE`): the
change of A(w), B(w), the excitation and the RAOs of heave, roll and pitch near their
natural frequencies between two databases on the same frequency and heading grids."""
import numpy as np

from . import bem_db as db
from . import bem_rao

WINDOW = 0.2          # [rad/s] either side of the undamped natural frequency
# the headings where each DOF is excited most: beam seas (heave, roll), head seas (pitch)
HEADINGS_DEG = {2: (90.0, 180.0), 3: (90.0, 45.0), 4: (180.0, 135.0)}


def _rel(fine, coarse):
    """max |coarse - fine| / max |fine| over the values given."""
    return float(np.max(np.abs(coarse - fine)) / np.max(np.abs(fine)))


def compare(fine, coarse, zeta=0.05):
    """Rows (dof name, w_n fine, w_n coarse, dA, dB, dX, dRAO peak) for heave, roll, pitch."""
    if fine.omega.shape != coarse.omega.shape or not np.allclose(fine.omega, coarse.omega):
        raise ValueError("the two databases have different frequency grids")
    w = fine.omega
    rows = []
    for dof in bem_rao.RESTORED:
        wn_f = bem_rao.natural_frequency(fine, dof)
        wn_c = bem_rao.natural_frequency(coarse, dof)
        m = np.abs(w - wn_f) <= WINDOW
        da = _rel(fine.added_mass[m, dof, dof], coarse.added_mass[m, dof, dof])
        dbb = _rel(fine.damping[m, dof, dof], coarse.damping[m, dof, dof])
        betas = np.radians(HEADINGS_DEG[dof])
        xf = bem_rao._interp_heading(fine.excitation[m], fine.heading, betas)[..., dof]
        xc = bem_rao._interp_heading(coarse.excitation[m], coarse.heading, betas)[..., dof]
        dx = _rel(xf, xc)
        rf, _ = bem_rao.raos(fine, w[m], betas[:1], zeta)
        rc, _ = bem_rao.raos(coarse, w[m], betas[:1], zeta)
        peak_f, peak_c = np.max(np.abs(rf[:, 0, dof])), np.max(np.abs(rc[:, 0, dof]))
        rows.append((db.DOFS[dof], wn_f, wn_c, da, dbb, dx, peak_c / peak_f - 1.0))
    return rows


def markdown(rows, fine_name, coarse_name):
    lines = [f"| DOF | w_n {fine_name} [rad/s] | w_n {coarse_name} [rad/s] | max dA | max dB | "
             "max dX | RAO peak change |",
             "|---|---|---|---|---|---|---|"]
    for name, wf, wc, da, dbb, dx, dp in rows:
        lines.append(f"| {name} | {wf:.4f} | {wc:.4f} | {da:.2%} | {dbb:.2%} | {dx:.2%} | "
                     f"{dp:+.2%} |")
    return "\n".join(lines)
