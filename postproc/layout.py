"""The one place that knows davit's HDF5 layout.

Fortran writes time series as (components, time); h5py returns them as (time, components).
The inertial frame N has z down; the paper's plots use oxy1z1, N turned 180 deg about x, so
y1 = -y and z1 = -z (z1 up).
"""
from dataclasses import dataclass

import h5py
import numpy as np

GRAVITY = 9.81

TIME = "time"
BOAT_POSITION = "boat/position"
BOAT_EULER = "boat/euler"
BOAT_VELOCITY = "boat/velocity"
BOAT_ANGULAR_VELOCITY = "boat/angular_velocity"
BOAT_ACCELERATION = "boat/acceleration"
SLING_TENSION = "slings/tension"
ENERGY = "diagnostics/energy"
CONTACT_CLEARANCE = "contact/clearance"
CONTACT_FORCE = "contact/force"
FIRST_CONTACT_TIME = "events/first_contact_time"
LOWERING_START_TIME = "events/lowering_start_time"
WATERBORNE_TIME = "events/waterborne_time"
RELEASE_TIME = "events/release_time"
END_TIME = "events/end_time"
CONTACT = (CONTACT_CLEARANCE, CONTACT_FORCE)
# The launch log (src/run/launch_log.f90), resolved at every step: one row per impact, peak
# tensions per sling and cable segment with their times, [value, time] pairs of the CG and
# seat peaks, limits as [first time (-1 never), time beyond, excursions] with the limit
# values in the group's attributes, and the seat's filtered acceleration (3, n) at
# t = (k - 1/2) interval (attributes of group "seat").
IMPACT_TIME = "events/impacts/time"
IMPACT_FENDER = "events/impacts/fender"
IMPACT_SPEED = "events/impacts/speed"
IMPACT_PEAK_FORCE = "events/impacts/peak_force"
IMPACT_DURATION = "events/impacts/duration"
IMPACT_PEAK_ACCELERATION = "events/impacts/peak_acceleration"
IMPACT_PEAK_SEAT = "events/impacts/peak_seat_acceleration"
IMPACTS = (IMPACT_TIME, IMPACT_FENDER, IMPACT_SPEED, IMPACT_PEAK_FORCE, IMPACT_DURATION,
           IMPACT_PEAK_ACCELERATION, IMPACT_PEAK_SEAT)
PEAK_SLING_TENSION = "peaks/sling_tension"
PEAK_SLING_TENSION_TIME = "peaks/sling_tension_time"
PEAK_SEGMENT_TENSION = "peaks/segment_tension"
PEAK_SEGMENT_TENSION_TIME = "peaks/segment_tension_time"
PEAK_CG_ACCELERATION = "peaks/cg_acceleration"
PEAK_SEAT_ACCELERATION = "peaks/seat_acceleration"
PEAK_TILT = "peaks/tilt"                          # [largest tilt of b3 from vertical (rad), t]
SEAT_ACCELERATION = "seat/acceleration"
SEAT_GROUP = "seat"
LIMITS_GROUP = "limits"
LIMIT_SWL = "limits/safe_working_load"
LIMIT_MBL = "limits/minimum_breaking_load"
LIMIT_IMPACT = "limits/impact_speed"
OUTCOME = "outcome"
INPUT_FILE = "input_file"          # root attribute of a run: the deck it ran
SWEEP_NAMELIST = "sweep_namelist"  # root attribute of a summary: the sweep deck's text
RIGGING_SEGMENT_TENSION = "rigging/segment_tension"
RIGGING_PAID_OUT = "rigging/paid_out"
RIGGING_PULLEY_ANGLE = "rigging/pulley_angle"
SLING_LUMPS = "slings/lump_position"
# the movable blocks (nt, 2, 3): fore, aft, inertial N (the state's copy for quasi-static
# blocks); files written before it was recorded have none (postproc.scene then draws none)
RIGGING_BLOCKS = "rigging/block_position"
SEA_ELEVATION = "sea/elevation"
SEA_PROBES = "sea/probe_position"
SEA_OMEGA = "sea/components/omega"
SEA_K = "sea/components/wavenumber"
SEA_DIRECTION = "sea/components/direction"
SEA_AMPLITUDE = "sea/components/amplitude"
SEA_PHASE = "sea/components/phase"

RAO_OMEGA = "rao/omega"
RAO_HEADING = "rao/heading"
RAO_AMPLITUDE = "rao/amplitude"
RAO_PHASE = "rao/phase"
RAO = (RAO_OMEGA, RAO_HEADING, RAO_AMPLITUDE, RAO_PHASE)
RAO_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
# `python -m postproc.bem rao` (postproc.bem_rao): frequency-domain RAOs from the BEM
# database, davit's body frame (z down); root datasets, numpy shapes: omega (nw) [rad/s],
# heading (nb) [rad], rao_re, rao_im, amplitude (nw, nb, 6), phase (nw, nb, 6) [rad],
# natural_period (6) [s], radiation_damping_ratio (6); root attributes: the database's
# path, the roll damping ratio, B44_visc [N m s], C44 [N m] and its GM [m]. (The BEM database itself is Capytaine's format: postproc.bem_db.)
BEM_RAO_OMEGA = "omega"
BEM_RAO_HEADING = "heading"
BEM_RAO_RE = "rao_re"
BEM_RAO_IM = "rao_im"
BEM_RAO_AMPLITUDE = "amplitude"
BEM_RAO_PHASE = "phase"
BEM_RAO_NATURAL_PERIOD = "natural_period"
BEM_RAO_DATABASE = "database"
BEM_RAO_ROLL_DAMPING_RATIO = "roll_damping_ratio"
BEM_RAO_ROLL_DAMPING_VISC = "roll_damping_visc"
# radiation damping ratio at each undamped natural frequency (6) [-], and the roll
# stiffness C44 [N m] and the GM_T [m] it implies (root attributes)
BEM_RAO_DAMPING_RATIO = "radiation_damping_ratio"
BEM_RAO_ROLL_STIFFNESS = "roll_stiffness"
BEM_RAO_ROLL_GM = "roll_gm"
# the attributes of every dataset
UNITS = "units"
DESCRIPTION = "description"
SHIP_POSITION = "ship/position"
SHIP_EULER = "ship/euler"
SHIP_RUDDER = "ship/rudder"        # the MMG ship's rudder angle (&ship manoeuvring = 'mmg')
SHIP = (SHIP_POSITION, SHIP_EULER)

BOAT = (BOAT_POSITION, BOAT_EULER, BOAT_VELOCITY, BOAT_ANGULAR_VELOCITY, BOAT_ACCELERATION)
SEA = (SEA_ELEVATION, SEA_PROBES, SEA_OMEGA, SEA_K, SEA_DIRECTION, SEA_AMPLITUDE, SEA_PHASE)
ROOT_ATTRIBUTES = ("davit_version", "input_namelist", "seed", "steps", "rhs_evaluations",
                   "wall_time", "complete", "status")
# root attributes read one by one (postproc.study's run metrics)
WALL_TIME = "wall_time"
RHS_EVALUATIONS = "rhs_evaluations"
STEPS = "steps"
COMPLETE = "complete"
# group of the sea's attributes (ramp_time, wave_type) in Run.group_attrs
SEA_GROUP = "sea"


def _text(value):
    return value.decode() if isinstance(value, (bytes, np.bytes_)) else value


@dataclass
class Run:
    """A davit output file loaded into numpy arrays (time along the first axis)."""
    path: str
    attrs: dict
    datasets: dict
    group_attrs: dict

    @property
    def time(self):
        return self.datasets[TIME]

    def get(self, name):
        return self.datasets.get(name)

    def has(self, *names):
        return all(name in self.datasets for name in names)

    def require(self, names, what):
        missing = [name for name in names if name not in self.datasets]
        if missing:
            raise ValueError(f"{self.path}: no {what} in this file "
                             f"(missing {', '.join(missing)})")

    @property
    def complete(self):
        return int(self.attrs.get(COMPLETE, 0)) == 1

    @property
    def scene(self):
        return self.attrs.get("scene", "")

    def event(self, name):
        """An /events time [s], or None where the file has none or it never happened (-1):
        callers then fall back to the whole record instead of a sentinel time."""
        value = self.get(name)
        if value is None:
            return None
        value = float(np.ravel(value)[0])
        return value if value >= 0 else None

    def limit(self, name):
        """A limit's value from /limits' attributes (minimum_breaking_load,
        safe_working_load, impact_speed), or None where the file has none."""
        value = self.group_attrs.get(LIMITS_GROUP, {}).get(name)
        return None if value is None else float(np.ravel(value)[0])

    def seat_time(self):
        """Times of the seat's filtered acceleration samples, or None."""
        a = self.get(SEAT_ACCELERATION)
        if a is None:
            return None
        dt = float(np.ravel(self.group_attrs[SEAT_GROUP]["interval"])[0])
        return (np.arange(a.shape[0]) + 0.5) * dt

    def deck(self, group, key, default=None):
        """A key of the deck this file was run from (root attribute input_namelist)."""
        return deck_value(self.attrs.get("input_namelist", ""), group, key, default)


def _open(path):
    """h5py.File for reading; h5py's own errors do not name the file, so this one does."""
    try:
        return h5py.File(path, "r")
    except OSError as exc:
        raise OSError(f"{path}: cannot read as HDF5 ({exc})") from exc


def load(path):
    """Read every dataset and the attributes of a davit output file."""
    datasets, group_attrs = {}, {}
    with _open(path) as f:
        attrs = {k: _text(v) for k, v in f.attrs.items()}

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                datasets[name] = obj[()]
            else:
                group_attrs[name] = {k: _text(v) for k, v in obj.attrs.items()}
        f.visititems(visit)
    if "davit_version" not in attrs or (TIME not in datasets and RAO_OMEGA not in datasets):
        raise ValueError(f"{path}: not a davit output file")
    return Run(path=path, attrs=attrs, datasets=datasets, group_attrs=group_attrs)


RAO_GROUP = "rao"
SWEEP_GROUP = "cases"
STUDY_GROUP = "study"
KINDS = ("run", "sea", "rao", "sweep", "study")


def file_kind(path):
    """What a davit HDF5 file holds, so that `python -m postproc all` can dispatch it:
    'rao' (davit rao), 'sweep' (davit sweep summary), 'study' (study charts), 'sea' (the
    'sea' scene) or 'run' (a time-domain run with a boat); None for anything else."""
    with _open(path) as f:
        if RAO_GROUP in f:
            return "rao"
        if SWEEP_GROUP in f:
            return "sweep"
        if STUDY_GROUP in f:
            return "study"
        if TIME not in f:
            return None
        return "sea" if _text(f.attrs.get("scene", "")) == "sea" else "run"


def deck_value(text, group, key, default=None):
    """The value of `key` in namelist group `&group` of a deck's text, as a float, a tuple
    of floats, a bool or a string; `default` where the deck does not set it. Only keys the
    deck states are known here: davit's own defaults live in the Fortran deck reader."""
    import re
    body = None
    clean = "\n".join(line.split("!", 1)[0] for line in text.splitlines())
    for match in re.finditer(r"&(\w+)(.*?)(?:^\s*/|/\s*$)", clean, re.S | re.M):
        if match.group(1).lower() == group.lower():
            body = match.group(2)
    if body is None:
        return default
    found = re.search(rf"(?:^|[\s,]){re.escape(key)}\s*=\s*(.*?)(?=[\s,]\w+\s*=|\Z)",
                      body, re.S | re.I)
    if not found:
        return default
    raw = found.group(1).strip().rstrip(",").strip()
    if raw[:1] in "'\"":
        return raw.strip("'\"")
    if raw.lower() in (".true.", ".false."):
        return raw.lower() == ".true."
    values = [float(v.lower().replace("d", "e")) for v in re.split(r"[\s,]+", raw) if v]
    return values[0] if len(values) == 1 else tuple(values)


def dataset_metadata(path):
    """{dataset name: (units, description)} for every dataset in the file."""
    meta = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                meta[name] = (_text(obj.attrs.get("units", "")),
                              _text(obj.attrs.get("description", "")))
        f.visititems(visit)
    return meta


def to_plot_frame(xyz):
    """Inertial N (z down) to the paper's oxy1z1 (y1 = -y, z1 = -z)."""
    out = np.array(xyz, dtype=float, copy=True)
    out[..., 1] *= -1.0
    out[..., 2] *= -1.0
    return out


def sea_ramp_time(run):
    """The recorded sea's ramp time T [s] (attribute of /sea; 0 where it has none)."""
    return float(run.group_attrs.get(SEA_GROUP, {}).get("ramp_time", 0.0))


def sea_ramp(run, t):
    """The smooth-start factor (1 - cos(pi t/T))/2 of the recorded sea."""
    ramp_time = sea_ramp_time(run)
    t = np.asarray(t, dtype=float)
    if ramp_time <= 0:
        return np.ones_like(t)
    return np.where(t < ramp_time, 0.5 * (1 - np.cos(np.pi * np.clip(t, 0, None) / ramp_time)),
                    1.0)


def sea_elevation(run, t, x, y):
    """Rebuild eta(x, y, t) from the recorded component table (eq. 43; Stokes-2 adds
    k a^2/2 cos 2 theta). x and y broadcast together."""
    w, k = run.get(SEA_OMEGA), run.get(SEA_K)
    g, a, eps = run.get(SEA_DIRECTION), run.get(SEA_AMPLITUDE), run.get(SEA_PHASE)
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    theta = (w * t + eps - k * (x[..., None] * np.cos(g) + y[..., None] * np.sin(g)))
    eta1 = np.sum(a * np.cos(theta), axis=-1)
    r = sea_ramp(run, t)
    eta = r * eta1
    if run.group_attrs.get(SEA_GROUP, {}).get("wave_type") == "stokes2":
        eta = eta + 0.5 * k[0] * (r * a[0]) ** 2 * np.cos(2 * theta[..., 0])
    return eta


# ---------------------------------------------------------------------------------------
# davit sweep summary, as read by the regression report (postproc/regress.py): one row per
# case, 1-D arrays of length ncase. /cases holds the inputs, /results the outcomes.
SUMMARY_LEVEL = "cases/level"
SUMMARY_REALISATION = "cases/realisation"
SUMMARY_WIND = "cases/wind"
SUMMARY_WAVE_TYPE = "cases/wave_type"          # 1 airy, 2 stokes2, 3 irregular
SUMMARY_ANGLE = "cases/angle_deg"
SUMMARY_CLEARANCE = "cases/clearance_b"        # initial clearance in boat widths B
SUMMARY_STATUS = "results/status"              # 0 not run, 1 ok, 2 failed, 3 not needed
SUMMARY_MIN_CLEARANCE = "results/min_clearance"
SUMMARY_PEAK_HORIZONTAL_ACCELERATION = "results/peak_horizontal_acceleration"
SUMMARY_COLLIDED = "results/collided"
SUMMARY_FIELDS = {"level": SUMMARY_LEVEL, "realisation": SUMMARY_REALISATION,
                  "wind": SUMMARY_WIND, "wave_type": SUMMARY_WAVE_TYPE,
                  "angle_deg": SUMMARY_ANGLE, "clearance_b": SUMMARY_CLEARANCE,
                  "status": SUMMARY_STATUS, "min_clearance": SUMMARY_MIN_CLEARANCE,
                  "peak_horizontal_acceleration": SUMMARY_PEAK_HORIZONTAL_ACCELERATION,
                  "collided": SUMMARY_COLLIDED}
SUMMARY_STATUS_OK = 1
SUMMARY_WAVE_IRREGULAR = 3


def load_summary_fields(path):
    """{field: 1-D array} of the SUMMARY_FIELDS of a sweep summary; a missing dataset is an
    error naming the file and the dataset (a half-written or foreign file must not pass as
    'no collisions')."""
    return load_sweep_columns(path, SUMMARY_FIELDS)


def chinese_spectrum(omega, height):
    """Eq. 44: S = 0.74 w^-5 exp(-g^2/(U^2 w^2)), U = 6.28 sqrt(H) [m^2 s]."""
    u = 6.28 * np.sqrt(height)
    omega = np.asarray(omega, dtype=float)
    return 0.74 / omega ** 5 * np.exp(-(GRAVITY / u) ** 2 / omega ** 2)


# --- Sweep summaries (`davit sweep`) ---------------------------------------------------------
# One row per case: 1-D datasets of length ncase. Every dataset has `units` and
# `description`. Results are defined for status 1 (ok) only: otherwise the real results are
# NaN and collided/impacts -1. Event times are -1 when the event did not happen.
import os  # noqa: E402  (here, not at the top: only the sweep section needs it)

SWEEP_CASE_INDEX = "cases/index"
SWEEP_CASE_LEVEL = "cases/level"
SWEEP_CASE_REALISATION = "cases/realisation"
SWEEP_CASE_SEED = "cases/seed"
SWEEP_CASE_WIND = "cases/wind"                      # 1 on (along the waves), 0 off
SWEEP_CASE_WAVE_TYPE = "cases/wave_type"            # code, see SWEEP_WAVE_TYPES
SWEEP_CASE_WAVE_HEIGHT = "cases/wave_height"
SWEEP_CASE_WAVE_PERIOD = "cases/wave_period"
SWEEP_CASE_ANGLE = "cases/angle_deg"
SWEEP_CASE_CLEARANCE = "cases/clearance_b"          # initial clearance in boat widths
SWEEP_CASE_WIND_SPEED = "cases/wind_speed"
SWEEP_CASE_DT = "cases/dt"
SWEEP_CASE_PHASE = "cases/phase_deg"
SWEEP_STATUS = "results/status"                     # 0 not run, 1 ok, 2 failed, 3 not needed
SWEEP_MESSAGE = "results/message"
SWEEP_MIN_CLEARANCE = "results/min_clearance"
SWEEP_COLLIDED = "results/collided"
SWEEP_IMPACTS = "results/impacts"
SWEEP_PEAK_HORIZONTAL = "results/peak_horizontal_acceleration"
SWEEP_PEAK_VERTICAL = "results/peak_vertical_acceleration"
SWEEP_PEAK_TENSION = "results/peak_segment_tension"
SWEEP_FIRST_CONTACT = "results/first_contact_time"
SWEEP_WATERBORNE = "results/waterborne_time"
SWEEP_END_TIME = "results/end_time"
SWEEP_WALL_TIME = "results/wall_time"
SWEEP_STEPS = "results/steps"
SWEEP_RHS = "results/rhs_evaluations"

SWEEP_WAVE_TYPES = {0: "calm", 1: "airy", 2: "stokes2", 3: "irregular"}
SWEEP_NOT_RUN, SWEEP_OK, SWEEP_FAILED = 0, 1, 2
# adaptive realisations (&sweep target_halfwidth > 0): the case's cell converged before
# reaching it; the message says why. Done, unlike SWEEP_NOT_RUN (an interrupted sweep).
SWEEP_NOT_NEEDED = 3
SWEEP_ROOT_ATTRIBUTES = ("davit_version", "sweep_file", "sweep_namelist", "base_deck",
                         "base_namelist", "ncase", "threads", "complete", "series_dir",
                         "target_halfwidth", "max_realisations", "realisation_batch")
# root attributes of a shard's summary only (`davit sweep --shard K/N`): K and N
SWEEP_SHARD_ATTRIBUTES = ("shard_index", "shard_count")

# field of Sweep -> dataset; every summary holds these
SWEEP_FIELDS = {
    "index": SWEEP_CASE_INDEX, "level": SWEEP_CASE_LEVEL,
    "realisation": SWEEP_CASE_REALISATION, "seed": SWEEP_CASE_SEED, "wind": SWEEP_CASE_WIND,
    "wave_type": SWEEP_CASE_WAVE_TYPE, "wave_height": SWEEP_CASE_WAVE_HEIGHT,
    "wave_period": SWEEP_CASE_WAVE_PERIOD, "angle_deg": SWEEP_CASE_ANGLE,
    "clearance_b": SWEEP_CASE_CLEARANCE, "wind_speed": SWEEP_CASE_WIND_SPEED,
    "dt": SWEEP_CASE_DT, "phase_deg": SWEEP_CASE_PHASE, "status": SWEEP_STATUS,
    "message": SWEEP_MESSAGE, "min_clearance": SWEEP_MIN_CLEARANCE,
    "collided": SWEEP_COLLIDED, "impacts": SWEEP_IMPACTS,
    "peak_horizontal_acceleration": SWEEP_PEAK_HORIZONTAL,
    "peak_vertical_acceleration": SWEEP_PEAK_VERTICAL,
    "peak_segment_tension": SWEEP_PEAK_TENSION, "first_contact_time": SWEEP_FIRST_CONTACT,
    "waterborne_time": SWEEP_WATERBORNE, "end_time": SWEEP_END_TIME,
    "wall_time": SWEEP_WALL_TIME, "steps": SWEEP_STEPS, "rhs_evaluations": SWEEP_RHS,
}


@dataclass
class Sweep:
    """A sweep summary as numpy arrays of length ncase (message: list of str)."""
    path: str
    attrs: dict
    index: np.ndarray
    level: np.ndarray
    realisation: np.ndarray
    seed: np.ndarray
    wind: np.ndarray
    wave_type: np.ndarray
    wave_height: np.ndarray
    wave_period: np.ndarray
    angle_deg: np.ndarray
    clearance_b: np.ndarray
    wind_speed: np.ndarray
    dt: np.ndarray
    phase_deg: np.ndarray
    status: np.ndarray
    message: list
    min_clearance: np.ndarray
    collided: np.ndarray
    impacts: np.ndarray
    peak_horizontal_acceleration: np.ndarray
    peak_vertical_acceleration: np.ndarray
    peak_segment_tension: np.ndarray
    first_contact_time: np.ndarray
    waterborne_time: np.ndarray
    end_time: np.ndarray
    wall_time: np.ndarray
    steps: np.ndarray
    rhs_evaluations: np.ndarray

    @property
    def ncase(self):
        return self.index.size

    @property
    def ok(self):
        return self.status == SWEEP_OK

    def series_file(self, index):
        """Path of case `index`'s time-series file (`davit sweep --series DIR`), or None."""
        folder = self.attrs.get("series_dir", "").strip()
        if not folder:
            return None
        if not os.path.isabs(folder) and not os.path.isdir(folder):
            folder = os.path.join(os.path.dirname(os.path.abspath(self.path)), folder)
        path = os.path.join(folder, f"case_{int(index):06d}.h5")
        return path if os.path.exists(path) else None


def load_sweep(path):
    """Read a `davit sweep` summary; ValueError naming what is missing if it is not one."""
    with h5py.File(path, "r") as f:
        attrs = {k: _text(v) for k, v in f.attrs.items()}
        missing = [name for name in SWEEP_FIELDS.values() if name not in f]
        if missing:
            raise ValueError(f"{path}: not a davit sweep summary "
                             f"(missing {', '.join(missing)})")
        data = {field: f[name][()] for field, name in SWEEP_FIELDS.items()}
    data["message"] = [_text(m).strip() for m in data["message"]]
    return Sweep(path=str(path), attrs=attrs, **data)


# --- Study charts (`python -m postproc.study`) ----------------------------------------------
# /study (STUDY_GROUP) holds one 1-D dataset per column, one entry per run: the run labels
# (variable-length UTF-8 text), ok (1 where the run completed) and the numeric metrics; the study's settings
# (kind, base, t_end, ...) are attributes of /study.
STUDY_LABEL = "label"
STUDY_OK = "ok"


# The study's one dimension (a dimension-only scale at the root, so that /study holds only
# the columns load_study returns).
STUDY_RUN = "run"


def write_study(path, attrs, labels, ok, columns):
    """Write a study file: /study with `attrs` as its attributes, the run labels, the ok
    flags and one float dataset per entry of `columns` ({name: values}, in that order),
    each along the named dimension `run` (xarray.open_dataset(path, group="study"))."""
    with h5py.File(path, "w") as f:
        g = f.create_group(STUDY_GROUP)
        for key, value in attrs.items():
            g.attrs[key] = value
        # variable-length UTF-8: netCDF-C (ncdump) misreads a fixed-length string array
        written = [g.create_dataset(STUDY_LABEL, data=[str(s) for s in labels],
                                    dtype=h5py.string_dtype()),
                   g.create_dataset(STUDY_OK, data=np.array(ok))]
        for key, values in columns.items():
            written.append(g.create_dataset(key, data=np.array(values, dtype=float)))
        for dataset in written:
            name_dimensions(dataset, (STUDY_RUN,), where=f)


def load_study(path, kind=None):
    """{column: array} of a study file's /study datasets (label: list of str) plus
    "attrs": the attributes of /study; None if the file has no /study, or (given `kind`)
    if its kind is another."""
    with h5py.File(path, "r") as f:
        if STUDY_GROUP not in f:
            return None
        g = f[STUDY_GROUP]
        if kind is not None and g.attrs.get("kind") != kind:
            return None
        data = {k: g[k][:] for k in g}
        data[STUDY_LABEL] = [_text(s) for s in data[STUDY_LABEL]]
        data["attrs"] = dict(g.attrs)
    return data


SENSITIVITY_FIELDS = {"wave_height": SWEEP_CASE_WAVE_HEIGHT,
                      "wave_period": SWEEP_CASE_WAVE_PERIOD, "angle_deg": SWEEP_CASE_ANGLE,
                      "status": SWEEP_STATUS, "collided": SWEEP_COLLIDED,
                      "min_clearance": SWEEP_MIN_CLEARANCE}


def load_sweep_columns(path, fields):
    """{field: 1-D array} of a sweep summary's datasets `fields` (field -> dataset name);
    a missing one is an error naming the file and the dataset."""
    with _open(path) as f:
        missing = [name for name in fields.values() if name not in f]
        if missing:
            raise ValueError(f"{path}: not a complete davit sweep summary "
                             f"(missing dataset {', '.join('/' + m for m in missing)})")
        return {field: np.ravel(f[name][()]) for field, name in fields.items()}


# --- Named dimensions (xarray, netCDF-4), as src/io/hdf5_writer.f90 writes them ---------
# Each axis of a dataset is attached to an HDF5 dimension scale: a 1-D dataset named like
# its dimension (/time) is that dimension's coordinate; any other dimension is a netCDF-4
# dimension-only scale (a float dataset of the dimension's length, never written, whose
# NAME starts with the sentence below: netCDF-4, h5netcdf and xarray hide it as a variable).
DIMENSION_ONLY = "This is a netCDF dimension but not a netCDF variable."
SCALE_NAME = "NAME"                 # a dimension scale's name attribute (HDF5 DS)
UNITS = "units"
DESCRIPTION = "description"
LONG_NAME = "long_name"


def dimension_scale(where, name, length):
    """The dimension-only scale `name` of h5py group `where`, created on first use."""
    if name in where:
        return where[name]
    scale = where.create_dataset(name, shape=(length,), dtype="f4")
    scale.make_scale(f"{DIMENSION_ONLY}{length:10d}")
    return scale


def name_dimensions(dataset, dims, where=None):
    """Attach axis k of h5py `dataset` (in the order h5py shows it) to dimension dims[k]:
    the dataset itself if it is 1-D and named like it (a coordinate), else the scale of
    that name in group `where` (default: the dataset's group), created if missing."""
    where = dataset.parent if where is None else where
    for axis, name in enumerate(dims):
        if dataset.ndim == 1 and dataset.name.rsplit("/", 1)[-1] == name:
            dataset.make_scale(name)
        else:
            dataset.dims[axis].attach_scale(dimension_scale(where, name, dataset.shape[axis]))


# The converged references of davit bench's scenes (postproc.bench_reference, read by
# src/bench/accuracy.f90): one group per scene with these datasets and attributes.
BENCH_REFERENCE_DATASETS = ("time", "position", "first_contact_time", "peak_sling_tension",
                            "peak_segment_tension")
BENCH_REFERENCE_ATTRS = {"description": "description", "deck": "deck",
                         "settings": "settings", "wall_time": "wall_time"}
# their dimensions (as h5py shows them; BENCH_REFERENCE_DATASETS' order)
BENCH_REFERENCE_DIMS = (("time",), ("time", "component"), ("scalar",), ("sling",),
                        ("segment",))


# --- Rule checks and the operability table (issue 16; postproc.operability) ---------------
# `davit sweep` writes, for each rule check below, three float columns per case:
# results/check_<id>_value, results/check_<id>_limit and results/check_<id>_margin. The
# margin is relative: >= 0 passes, < 0 fails, NaN = the rule does not apply to that case
# (e.g. no emergency stop scripted). A summary without a check's columns simply has no such
# check (older summaries have none).
@dataclass(frozen=True)
class Check:
    """One rule check: its id, which side of the limit passes ('lower': value >= limit,
    'upper': value <= limit), what it means and where the rule comes from."""
    id: str
    bound: str
    meaning: str
    source: str


CHECKS = (
    Check("lowering_speed", "lower", "lowering speed >= 0.4 + 0.02 H m/s (H: davit head above the water)",
          "S1 LSA Code 6.1.2"),
    Check("impact_speed", "upper", "lateral impact speed on the ship's side <= 3.5 m/s",
          "S5 LSA Code 4.4.1"),
    Check("fall_swl", "upper", "fall tension <= safe working load (MBL/6)",
          "S8 LSA Code 6.1.1 (breaking strength >= 6 x load)"),
    Check("fall_mbl", "upper", "fall tension <= minimum breaking load",
          "S8 LSA Code 6.1.1"),
    Check("sling_swl", "upper", "sling tension <= safe working load (MBL/6)",
          "S8 LSA Code 6.1.1 (breaking strength >= 6 x load)"),
    Check("sling_mbl", "upper", "sling tension <= minimum breaking load",
          "S8 LSA Code 6.1.1"),
    Check("brake_load", "upper", "dynamic brake load <= 1.1 x working load",
          "S6 LSA Code 6.1.2 / MSC.81(70)"),
    Check("release_load", "upper", "on-load release load <= 1.1 x loaded mass weight",
          "S9 LSA Code 4.4.7.6"),
    Check("seat_srss", "upper", "seat acceleration SRSS <= limit (indicative for davit "
          "launches)", "S12 MSC/Circ.616 / MSC.81(70)"),
    Check("seat_dri", "upper", "spine dynamic response index <= 18 (indicative for davit "
          "launches)", "S12 DRI (52.9 rad/s, 0.224)"),
)
# A run's file holds the same checks in /assessment/<id> = [value, limit, margin] (NaN: does
# not apply) with attributes `source` and `verdict`; the group's attributes `head_height`
# (H [m]) and `failed` (count); /assessment/dynamic_response = [up, down] peaks of the DRI.
ASSESSMENT = "assessment"
ASSESSMENT_DRI = "assessment/dynamic_response"


def assessment_dataset(check_id):
    """The run file's dataset of rule check `check_id`."""
    return f"{ASSESSMENT}/{check_id}"
CHECK_PARTS = ("value", "limit", "margin")


def check_columns(check_id):
    """{part: dataset} of rule check `check_id`: its value, limit and relative margin."""
    return {part: f"results/check_{check_id}_{part}" for part in CHECK_PARTS}


# what the operability table needs of every summary ...
OPERABILITY_FIELDS = {
    "level": SWEEP_CASE_LEVEL, "wave_height": SWEEP_CASE_WAVE_HEIGHT,
    "wave_period": SWEEP_CASE_WAVE_PERIOD, "angle_deg": SWEEP_CASE_ANGLE,
    "clearance_b": SWEEP_CASE_CLEARANCE, "status": SWEEP_STATUS, "collided": SWEEP_COLLIDED,
}
# ... and the per-launch maxima it fits when the summary has them (the launch log's columns)
OPERABILITY_MAXIMA = {
    "peak_horizontal_acceleration": SWEEP_PEAK_HORIZONTAL,
    "peak_fall_tension": "results/peak_fall_tension",
    "peak_sling_tension": "results/peak_sling_tension",
}


def load_sweep_optional(path, fields):
    """{field: 1-D float array} of those datasets of `fields` (field -> dataset name) that
    the summary holds; the absent ones are left out, not an error."""
    with _open(path) as f:
        return {field: np.ravel(f[name][()]).astype(float)
                for field, name in fields.items() if name in f}


def load_checks(path):
    """{check id: {part: 1-D float array}} of the rule checks whose three columns the
    summary holds, in the order of CHECKS; a check with any column missing is absent."""
    out = {}
    for check in CHECKS:
        columns = load_sweep_optional(path, check_columns(check.id))
        if len(columns) == len(CHECK_PARTS):
            out[check.id] = columns
    return out
