"""Speed-versus-accuracy studies of the coupled launch (issue 7): work-precision of the
integrators and level-of-detail switches, and the stability map.

    python -m postproc.study input/study_work_precision.nml [-o out] [--davit PATH]
    python -m postproc.study input/study_stability.nml [-o out]
    python -m postproc.study input/study_damping.nml [-o out]

A study deck is a namelist with one `&study` group:
    kind = 'work_precision' | 'stability' | 'damping' | 'statistics'
    base = 'input/iiib_level5_090.nml'     (the scene every run starts from)
    t_end = 40.0                           (simulated span of each run, s)
    reference = 'rk4 dt=1e-4 dt_contact=2e-6'
    runs = 'rk4 dt=1e-3 dt_contact=1e-5', ...
Each run string is an integrator name followed by key=value overrides of the base deck
(the group of each key is looked up in KEY_GROUPS). The script runs `davit run` on each
variant, compares with the reference and writes out/<study>.h5 (layout.write_study) and a PNG
chart. Timings are the runs' own single-thread wall times (root attribute wall_time).

kind = 'damping' measures how much each method damps the boat's bounce on its slings: the
decay rate of the vertical CG velocity (a two-pole fit of its samples, bounce_decay), as an
apparent damping ratio zeta = sigma/omega, beside the value predicted from the method's stability function
R(h lambda) with the bounce's physical lambda (from the reference run).

kind = 'statistics' is for switches that change the sea itself (wave components): the runs
cannot be compared path by path, so each run spec is repeated over `seeds` (e.g. seeds = 4)
sea realisations and the study reports the mean and standard deviation over the seeds of
the boat's RMS heave, RMS roll and peak horizontal acceleration (sampled), and the cost.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

from . import layout, study_figures
from .deck_edit import KEY_GROUPS, STRING_KEYS, override, run_davit, variant  # noqa: F401
from .stability import stability_function  # noqa: F401

def parse_study(path):
    """Read the `&study` group: strings, numbers and comma-separated string lists."""
    text = open(path).read()
    body = re.search(r"&study(.*?)\n\s*/", text, re.S)
    if not body:
        raise ValueError(f"{path}: no &study group")
    lines = [ln.split("!")[0].rstrip() for ln in body.group(1).splitlines()]
    joined = " ".join(ln for ln in lines if ln.strip())
    study = {}
    for key, value in re.findall(r"(\w+)\s*=\s*((?:'[^']*'(?:\s*,\s*)?)+|[^\s,']+)", joined):
        strings = re.findall(r"'([^']*)'", value)
        if strings:
            study[key] = strings if key == "runs" else strings[0]
        else:
            study[key] = float(value.strip().rstrip(","))
    for need in ("kind", "base", "t_end", "runs"):
        if need not in study:
            raise ValueError(f"{path}: &study: missing key '{need}'")
    return study


def metrics(path):
    """Time, CG position, peak segment tension series, horizontal acceleration, first
    contact time, the launch log's resolved peaks (segment and sling tension, impact CG
    acceleration; 0 where the run has none) and cost of one run file."""
    def peak(f, name):
        return float(np.max(f[name][:])) if name in f and f[name].size else 0.0
    with h5py.File(path, "r") as f:
        time = f[layout.TIME][:]
        # a free boat (no rigging, no contact) has neither tensions nor contact events
        tension = (f[layout.RIGGING_SEGMENT_TENSION][:].max(axis=1)
                   if layout.RIGGING_SEGMENT_TENSION in f else np.zeros(len(time)))
        contact = (float(np.ravel(f[layout.FIRST_CONTACT_TIME])[0])
                   if layout.FIRST_CONTACT_TIME in f else -1.0)
        release = (float(np.ravel(f[layout.RELEASE_TIME])[0])
                   if layout.RELEASE_TIME in f else -1.0)
        out = {"time": time, "x": f[layout.BOAT_POSITION][:],
               "a": f[layout.BOAT_ACCELERATION][:], "tension": tension, "contact": contact,
               "release": release,
               "peak_segment": peak(f, layout.PEAK_SEGMENT_TENSION),
               "peak_sling": peak(f, layout.PEAK_SLING_TENSION),
               "peak_impact": peak(f, layout.IMPACT_PEAK_ACCELERATION),
               "wall": float(f.attrs[layout.WALL_TIME]),
               "rhs": int(f.attrs[layout.RHS_EVALUATIONS]),
               "steps": int(f.attrs[layout.STEPS]), "complete": int(f.attrs[layout.COMPLETE])}
    return out


def relative(a, b):
    """|a/b - 1|, 0 when both are 0 (a quantity neither run has)."""
    return abs(a / b - 1.0) if b > 0 else (0.0 if a == 0 else float("inf"))


def compare(run, ref):
    """Errors against the reference on the common samples (a run the launch monitor ends
    between samples has its last one off the grid: left out): max CG distance before the
    reference's first contact (smooth phase), after it and over the whole run; relative
    error of the peak segment tension (sampled) and of the launch log's resolved peaks
    (segment and sling tension, impact CG acceleration); the peak horizontal acceleration
    (sampled); and the max CG distance while the boat is on its falls (before the
    reference's hook release; the whole run where it has none)."""
    n = min(len(run["time"]), len(ref["time"]))
    while n > 1 and abs(run["time"][n - 1] - ref["time"][n - 1]) > 1e-9:
        n -= 1
    if n < 2 or not np.allclose(run["time"][:n], ref["time"][:n], atol=1e-9):
        raise ValueError("runs sampled at different times")
    dist = np.linalg.norm(run["x"][:n] - ref["x"][:n], axis=1)
    smooth = ref["time"][:n] < ref["contact"] if ref["contact"] > 0 else np.ones(n, bool)
    ah = np.hypot(run["a"][:n, 0], run["a"][:n, 1])
    on_falls = (ref["time"][:n] < ref["release"] if ref.get("release", -1.0) > 0
                else np.ones(n, bool))
    return {"err_smooth": dist[smooth].max(), "err_all": dist.max(),
            "err_falls": dist[on_falls].max(),
            "err_contact": dist[~smooth].max() if (~smooth).any() else 0.0,
            "tension_err": (abs(run["tension"][:n].max() / ref["tension"][:n].max() - 1)
                            if ref["tension"][:n].max() > 0 else 0.0),
            "segment_err": relative(run["peak_segment"], ref["peak_segment"]),
            "sling_err": relative(run["peak_sling"], ref["peak_sling"]),
            "impact_err": relative(run["peak_impact"], ref["peak_impact"]),
            "peak_ah": ah.max()}


def work_precision(study, davit, workdir):
    """Run the reference and every variant; rows of (label, cost, errors)."""
    base = open(study["base"]).read()
    t_end = study["t_end"]
    path, ok, msg = run_davit(davit, variant(base, study["reference"], t_end), workdir, "ref")
    if not ok:
        raise RuntimeError(f"reference run failed: {msg}")
    ref = metrics(path)
    rows = []
    for i, spec in enumerate(study["runs"]):
        path, ok, msg = run_davit(davit, variant(base, spec, t_end), workdir, f"run{i}")
        row = {"label": spec, "ok": ok, "message": msg}
        if ok:
            m = metrics(path)
            row.update(compare(m, ref), wall=m["wall"], rhs=m["rhs"], steps=m["steps"])
        rows.append(row)
        print(format_row(row), flush=True)
    return ref, rows


def format_row(row):
    if not row["ok"]:
        return f"{row['label']:<52s} FAILED: {row['message'][:80]}"
    return (f"{row['label']:<52s} {row['wall']:8.3f} s {row['rhs']:10d} rhs "
            f"{row['err_smooth']:10.2e} m {row['err_contact']:10.2e} m "
            f"{row['err_falls']:10.2e} m "
            f"{100 * row['segment_err']:8.3f} % {100 * row['sling_err']:8.3f} % "
            f"{100 * row['impact_err']:8.3f} %")


def largest_stable_step(davit, base, spec, t_end, workdir, lo, hi, iters=7):
    """Bisect (geometrically) the largest fixed step that completes t_end."""
    if run_ok(davit, base, spec, t_end, hi, workdir):
        return hi
    if not run_ok(davit, base, spec, t_end, lo, workdir):
        return float("nan")
    for _ in range(iters):
        mid = np.sqrt(lo * hi)
        if run_ok(davit, base, spec, t_end, mid, workdir):
            lo = mid
        else:
            hi = mid
    return lo


def run_ok(davit, base, spec, t_end, dt, workdir):
    deck = override(variant(base, spec, t_end), "simulation", "dt", f"{dt:.6e}")
    deck = override(deck, "simulation", "output_interval", f"{max(dt, t_end / 50):.6e}")
    _, ok, _ = run_davit(davit, deck, workdir, "probe")
    return ok


def modes_limit(davit, deck_text, workdir):
    """RK4 limit 2.83/|lambda|_max from `davit modes`."""
    deck = os.path.join(workdir, "modes.nml")
    with open(deck, "w") as f:
        f.write(deck_text)
    out = subprocess.run([davit, "modes", deck], capture_output=True, text=True, check=True)
    rate = float(re.search(r"rate_max =\s*(\S+)", out.stdout).group(1))
    return rate, 2.83 / rate


def stability(study, davit, workdir):
    """For each stiffness variant: the analytic RK4 limit, the largest RK4 step that runs,
    dopri5's mean accepted step (it settles at its stability boundary) and RODAS3's mean
    step at the same tolerance (set by accuracy)."""
    base = open(study["base"]).read()
    t_end = study["t_end"]
    rows = []
    for spec in study["runs"]:
        deck = variant(base, spec, t_end)
        rate, limit = modes_limit(davit, deck, workdir)
        rk4 = largest_stable_step(davit, base, spec, t_end, workdir, limit / 8, limit * 4)
        row = {"label": spec, "rate": rate, "rk4_limit": limit, "rk4_stable": rk4}
        for name in ("dopri5", "rosenbrock"):
            d = override(override(deck, "simulation", "integrator", name),
                         "simulation", "dt", "0.02")
            d = override(d, "simulation", "output_interval", "0.02")
            d = override(d, "simulation", "rtol", study.get("rtol", 1e-6))
            path, ok, msg = run_davit(davit, d, workdir, name)
            m = metrics(path) if os.path.exists(path) else None
            row[name + "_step"] = t_end / m["steps"] if ok and m["steps"] else float("nan")
            row[name + "_rhs"] = m["rhs"] if ok else -1
            row[name + "_wall"] = m["wall"] if ok else float("nan")
        rows.append(row)
        print(f"{spec:<40s} rate {rate:10.4g} 1/s  RK4 limit {limit:9.3e}  stable "
              f"{rk4:9.3e}  dopri5 h {row['dopri5_step']:9.3e} ({row['dopri5_rhs']} rhs)  "
              f"RODAS3 h {row['rosenbrock_step']:9.3e} ({row['rosenbrock_rhs']} rhs)",
              flush=True)
    return rows


def bounce_decay(path, t_max=1.0):
    """Bounce frequency [rad/s] and decay rate [1/s] from the vertical CG velocity samples:
    a two-pole linear prediction w[n+2] = p1 w[n+1] + p2 w[n] + c (c: a slow drift) fitted
    over the samples up to t_max, or until the bounce has decayed to 2 % of its first
    swing; the poles are R exp(+-i omega dt), so sigma = -ln|R|/dt, |R|^2 = -p2."""
    with h5py.File(path, "r") as f:
        t = f[layout.TIME][:]
        w = f[layout.BOAT_VELOCITY][:, 2]
    dt = t[1] - t[0]
    keep = (t > 0) & (t <= t_max)
    t, w = t[keep], w[keep]
    small = np.nonzero(np.abs(w) < 0.02 * np.abs(w).max())[0]
    n = max(small[0], 8) if len(small) and small[0] > 0 else len(w)
    w = w[:n]
    x = np.column_stack([w[1:-1], w[:-2], np.ones(len(w) - 2)])
    (p1, p2, _), *_ = np.linalg.lstsq(x, w[2:], rcond=None)
    if p2 >= 0:
        return np.nan, np.nan
    r = np.sqrt(-p2)
    omega = np.arccos(np.clip(p1 / (2 * r), -1, 1)) / dt
    return omega, -np.log(r) / dt


def damping(study, davit, workdir):
    """Apparent damping ratio of the bounce for each run, measured and predicted."""
    base = open(study["base"]).read()
    t_end = study["t_end"]
    ref_deck = override(variant(base, study["reference"], t_end), "simulation",
                        "output_interval", "1e-3")
    path, ok, msg = run_davit(davit, ref_deck, workdir, "ref")
    if not ok:
        raise RuntimeError(f"reference run failed: {msg}")
    omega, sigma = bounce_decay(path)
    zeta = sigma / omega
    lam = omega * complex(-zeta, np.sqrt(1 - zeta**2))
    print(f"reference {study['reference']}: omega {omega:.3f} rad/s, zeta {zeta:.5f}")
    rows = []
    for i, spec in enumerate(study["runs"]):
        method = spec.split()[0]
        dt = float(re.search(r"dt=(\S+)", spec).group(1))
        deck = override(variant(base, spec, t_end), "simulation", "output_interval",
                        f"{max(dt, 1e-3):.6e}")
        path, ok, msg = run_davit(davit, deck, workdir, f"run{i}")
        row = {"label": spec, "ok": ok, "message": msg, "dt": dt, "omega_h": omega * dt,
               "zeta_physical": zeta}
        r = abs(stability_function(method, dt * lam))
        row["zeta_predicted"] = -np.log(r) / (dt * omega) if r > 0 else np.inf
        if ok:
            row["zeta_measured"] = bounce_decay(path)[1] / omega
        rows.append(row)
        print(f"{spec:<48s} omega h {omega * dt:7.3f}  zeta measured "
              f"{row.get('zeta_measured', np.nan):9.5f}  predicted {row['zeta_predicted']:9.5f}"
              + ("" if ok else "  FAILED: " + msg[:60]), flush=True)
    return rows


def motion_statistics(path):
    """RMS heave [m] and roll [rad] about their means, and the peak horizontal CG
    acceleration [m/s^2] (sampled), of one run file."""
    with h5py.File(path, "r") as f:
        z = f[layout.BOAT_POSITION][:, 2]
        roll = f[layout.BOAT_EULER][:, 0]
        a = f[layout.BOAT_ACCELERATION][:]
        wall = float(f.attrs[layout.WALL_TIME])
    return {"rms_heave": np.std(z), "rms_roll": np.std(roll),
            "peak_ah": np.hypot(a[:, 0], a[:, 1]).max(), "wall": wall}


def statistics(study, davit, workdir):
    """Mean and standard deviation over seeds of each run's motion statistics."""
    base = open(study["base"]).read()
    t_end = study["t_end"]
    nseeds = int(study.get("seeds", 4))
    rows = []
    for i, spec in enumerate(study["runs"]):
        samples = []
        for seed in range(1, nseeds + 1):
            deck = override(variant(base, spec, t_end), "simulation", "seed", seed)
            path, ok, msg = run_davit(davit, deck, workdir, f"run{i}_{seed}")
            if not ok:
                raise RuntimeError(f"run '{spec}' seed {seed} failed: {msg}")
            samples.append(motion_statistics(path))
        row = {"label": spec, "ok": True, "seeds": nseeds}
        for key in ("rms_heave", "rms_roll", "peak_ah", "wall"):
            values = np.array([m[key] for m in samples])
            row[key + "_mean"] = values.mean()
            row[key + "_sd"] = values.std(ddof=1) if nseeds > 1 else 0.0
        rows.append(row)
        print(f"{spec:<44s} heave {row['rms_heave_mean']:.4f} +- {row['rms_heave_sd']:.4f} m  "
              f"roll {row['rms_roll_mean']:.4f} +- {row['rms_roll_sd']:.4f} rad  "
              f"a_h {row['peak_ah_mean']:.3f} +- {row['peak_ah_sd']:.3f}  "
              f"wall {row['wall_mean']:.2f} s", flush=True)
    return rows


def write_rows(path, study, rows, ref=None):
    """The study file (layout.write_study): one column per run metric, the study deck's
    settings as attributes."""
    attrs = {"kind": study["kind"], "base": study["base"], "t_end": study["t_end"]}
    if ref is not None:
        attrs["reference"] = study["reference"]
        attrs["reference_wall_time"] = ref["wall"]
        attrs["reference_first_contact"] = ref["contact"]
    keys = sorted({k for r in rows for k in r if k not in ("label", "message", "ok")})
    layout.write_study(path, attrs, [r["label"] for r in rows],
                       [int(r["ok"]) if "ok" in r else 1 for r in rows],
                       {k: [r.get(k, np.nan) for r in rows] for k in keys})


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m postproc.study", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("deck", help="study deck (&study group)")
    parser.add_argument("-o", "--outdir", default="out")
    parser.add_argument("--davit", default=os.environ.get("DAVIT", "davit"),
                        help="davit executable (default: $DAVIT or davit on PATH)")
    args = parser.parse_args(argv)
    try:
        study = parse_study(args.deck)
    except (OSError, ValueError) as exc:
        print(f"postproc.study: error: {exc}", file=sys.stderr)
        return 1
    os.makedirs(args.outdir, exist_ok=True)
    # the variants run from a temporary folder: their data files (BEM databases) are found
    # beside the base deck, through davit's DAVIT_PATH
    base_dir = os.path.dirname(os.path.abspath(study.get("base", args.deck)))
    os.environ["DAVIT_PATH"] = os.pathsep.join(
        p for p in (base_dir, os.environ.get("DAVIT_PATH", "")) if p)
    stem = os.path.splitext(os.path.basename(args.deck))[0]
    out = os.path.join(args.outdir, stem + ".h5")
    with tempfile.TemporaryDirectory() as workdir:
        if study["kind"] == "work_precision":
            ref, rows = work_precision(study, args.davit, workdir)
            write_rows(out, study, rows, ref)
        elif study["kind"] == "stability":
            write_rows(out, study, stability(study, args.davit, workdir))
        elif study["kind"] == "damping":
            write_rows(out, study, damping(study, args.davit, workdir))
        elif study["kind"] == "statistics":
            write_rows(out, study, statistics(study, args.davit, workdir))
        else:
            print(f"postproc.study: error: {args.deck}: &study: kind = '{study['kind']}' "
                  "must be 'work_precision', 'stability', 'damping' or 'statistics'", file=sys.stderr)
            return 1
    print(f"postproc.study: wrote {out}")
    for fn in study_figures.STUDY_FIGURES.values():
        png = fn(out, args.outdir)
        if png:
            print(f"postproc.study: wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
