"""Regular-wave RAOs of the floating lifeboat in davit's time domain (issue 18), against
the frequency-domain solution of its BEM database (postproc.bem_rao).

  python -m postproc.boat_rao [--database input/boat_bem.nc] [--omegas W ...]
                              [--headings-deg 90 180] [--roll-damping 0.1]

Each (omega, heading) is one davit run of a free boat on a small regular Airy wave
(a = 0.02 m): &boat water_model = 'bem', no drag (the reference is potential flow plus the
viscous roll damping), GM_T the hull's (the database's C44 / (m g)); the wave travels at
`heading` relative to the boat's bow (boat heading 0, sea direction = heading). The
response is fitted over whole periods after the transient as m + R cos(w t + phi):
heave (z down, m/m), roll and pitch (rad/m); compared by amplitude with |xi| of the 6x6
frequency-domain system [-w^2 (M + A) + i w (B + B_visc) + C] xi = X.
"""
import argparse
import pathlib
import subprocess
import tempfile

import numpy as np

from . import bem_db, bem_rao, layout
from .build_flags import fpm_release

AMPLITUDE = 0.02
DOFS = {"heave": 2, "roll": 3, "pitch": 4}
DECK = """&simulation t_end = {t_end:.4f}, dt = {dt:.5f}, output_interval = {out:.5f} /
&boat position = 0.0, 0.0, {z0:.5f}, drag_coefficients = 0.0, 0.0, 0.0,
      metacentric_height = {gm:.5f}, roll_damping = {zeta}, water_model = 'bem',
      database = '{database}' /
&slings attached = .false. /
&wind speed = 0.0 /
&contact enabled = .false. /
&sea wave_type = 'airy', height = {height}, period = {period:.6f}, direction_deg = {heading},
     ramp_periods = 2.0 /
"""


def settle_time(omega):
    """Ramp (2 periods) plus the transient's decay: 8 periods, at least 30 s (roll at 10 %
    of critical decays as exp(-0.14 t))."""
    return max(10.0 * 2 * np.pi / omega, 32.0)


def run_case(davit_bin, database, omega, heading_deg, zeta, gm, z0, folder):
    """Amplitudes per unit wave amplitude of heave, roll, pitch from one davit run."""
    period = 2 * np.pi / omega
    measure = 4 * period
    t_end = settle_time(omega) + measure
    dt = min(period / 100.0, 0.01)
    deck = pathlib.Path(folder) / f"rao_{omega:.3f}_{heading_deg:.0f}.nml"
    deck.write_text(DECK.format(t_end=t_end, dt=dt, out=dt, z0=z0, gm=gm, zeta=zeta,
                                database=database, height=2 * AMPLITUDE, period=period,
                                heading=heading_deg))
    out = deck.with_suffix(".h5")
    result = subprocess.run([str(davit_bin), "run", str(deck), "-o", str(out)],
                            capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        raise RuntimeError(result.stderr)
    run = layout.load(out)
    t = run.time
    keep = t >= t_end - measure - 1e-9
    series = {"heave": run.get(layout.BOAT_POSITION)[:, 2],
              "roll": run.get(layout.BOAT_EULER)[:, 0],
              "pitch": run.get(layout.BOAT_EULER)[:, 1]}
    basis = np.stack([np.ones(keep.sum()), np.cos(omega * t[keep]), np.sin(omega * t[keep])], 1)
    amp = {}
    for name, x in series.items():
        c, *_ = np.linalg.lstsq(basis, x[keep], rcond=None)
        amp[name] = float(np.hypot(c[1], c[2])) / AMPLITUDE
    return amp


def reference(database, omegas, headings_deg, zeta):
    base = bem_db.Database(database)
    xi, _ = bem_rao.raos(base, omegas, np.radians(headings_deg), zeta)
    return {name: np.abs(xi[:, :, i]) for name, i in DOFS.items()}


def floating_depth(database):
    """CG depth of the floating boat: keel 1.1 m below the CG, draught m/(rho A_wp) of
    the 20 strips (what davit's strips float at)."""
    x = -5.75 + (np.arange(20) + 0.5) * 11.5 / 20
    a_wp = np.sum(2.8 * (1 - np.abs(2 * x / 11.5) ** 4.3)) * 11.5 / 20
    return -(1.1 - 8500.0 / (1025.0 * a_wp))


def compare(davit_bin, database, omegas, headings_deg, zeta=0.1, folder=None):
    """(time-domain amplitudes, references) as {dof: (nw, nb)} arrays."""
    base = bem_db.Database(database)
    gm = base.stiffness[3, 3] / (base.mass[0, 0] * 9.81)
    z0 = floating_depth(database)
    ref = reference(database, omegas, headings_deg, zeta)
    td = {name: np.zeros((len(omegas), len(headings_deg))) for name in DOFS}
    with tempfile.TemporaryDirectory() as tmp:
        for n, w in enumerate(omegas):
            for m, h in enumerate(headings_deg):
                amp = run_case(davit_bin, pathlib.Path(database).resolve(), w, h, zeta, gm, z0,
                               folder or tmp)
                for name in DOFS:
                    td[name][n, m] = amp[name]
    return td, ref


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m postproc.boat_rao", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--database", default="input/boat_bem.nc")
    p.add_argument("--davit", default=None, help="davit binary (default: found by fpm)")
    p.add_argument("--omegas", type=float, nargs="+",
                   default=[0.5, 1.0, 1.4, 2.0, 2.5, 2.9, 3.2, 4.0, 5.0, 6.0])
    p.add_argument("--headings-deg", type=float, nargs="+", default=[90.0, 180.0])
    p.add_argument("--roll-damping", type=float, default=0.1)
    a = p.parse_args(argv)
    davit_bin = a.davit
    if davit_bin is None:
        out = subprocess.run(["fpm", "run", *fpm_release(), "--runner", "echo"],
                             capture_output=True, text=True, check=True)
        davit_bin = out.stdout.strip().splitlines()[-1]
    td, ref = compare(davit_bin, a.database, a.omegas, a.headings_deg, a.roll_damping)
    print("| omega | heading | DOF | davit | BEM | error |")
    print("|---|---|---|---|---|---|")
    for m, h in enumerate(a.headings_deg):
        for name in DOFS:
            for n, w in enumerate(a.omegas):
                r, d = ref[name][n, m], td[name][n, m]
                err = (d - r) / r if r > 1e-6 else float("nan")
                print(f"| {w:g} | {h:g} | {name} | {d:.4g} | {r:.4g} | {100 * err:+.1f} % |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
