"""The launch's hardware as points in the inertial frame N (z down), one frame per sample.

Shared by the ParaView scene (postproc.scene) and the animation (postproc.animate), so that
both draw the same ship, boat, falls and fenders. The run file holds the motion (boat and
ship poses, block positions, tensions); the fixed geometry comes from the deck the run was
made from (root attribute input_namelist). That text only holds the keys the deck states,
so the Fortran defaults of the keys drawn here are repeated in DEFAULTS (their sources:
src/io/ship_keys.f90, src/io/rigging_keys.f90, src/io/config.f90); a changed default there
must be changed here too (test_scene checks a few against a run).
"""
from dataclasses import dataclass

import numpy as np

from . import layout

# (group, key) -> the Fortran default
DEFAULTS = {
    ("ship", "length_waterline"): 130.55, ("ship", "beam"): 20.8,
    ("ship", "draught"): 4.4, ("ship", "depth"): 11.4,
    ("ship", "cg_x"): 0.0, ("ship", "cg_z"): 0.0,
    ("boat", "length"): 11.5, ("boat", "beam"): 2.8, ("boat", "height"): 3.1,
    ("boat", "keel"): 1.1, ("boat", "breadth_exponent"): 4.3,
    ("slings", "hook_fore"): (4.6, 0.0, -1.55), ("slings", "hook_aft"): (-4.6, 0.0, -1.55),
    ("slings", "anchor_fore"): (4.6, 13.3, -19.55),
    ("slings", "anchor_aft"): (-4.6, 13.3, -19.55),
    ("rigging", "reeving"): "a",
    ("rigging", "head_fore"): (4.6, 13.3, -20.55), ("rigging", "head_aft"): (-4.6, 13.3, -20.55),
    ("rigging", "head_spacing"): 0.32, ("rigging", "lead_sheave"): (0.0, 11.5, -21.0),
    ("rigging", "drum_position"): (0.0, 8.0, -16.5), ("rigging", "sheave_radius"): 0.16,
    ("contact", "fender_x"): (3.0, -3.0), ("contact", "fender_y"): -1.4,
    ("contact", "fender_z"): (-0.8, 0.2),
}
BOAT_STATIONS = 15       # sections along the boat's hull shape b(x) = B (1 - |2x/L|^p)
# node kinds of the rigging (the scene's point data "kind")
DRUM, SHEAVE, BLOCK, HOOK, DEAD_END, LUMP, ANCHOR = range(7)
KIND_NAMES = ("drum", "sheave", "block", "hook", "dead_end", "lump", "anchor")


def deck(run, group, key):
    """A deck key of the run as stated, else davit's default (DEFAULTS)."""
    value = run.deck(group, key, DEFAULTS[(group, key)])
    if isinstance(DEFAULTS[(group, key)], tuple) and not isinstance(value, tuple):
        value = (value,)
    return np.asarray(value, dtype=float) if not isinstance(value, str) else value.lower()


def rotations(euler):
    """C = Rz Ry Rx (src/core/rotation.f90) of each row of (roll, pitch, yaw): (n, 3, 3),
    body components to inertial ones."""
    s1, s2, s3 = (np.sin(euler[:, i]) for i in range(3))
    c1, c2, c3 = (np.cos(euler[:, i]) for i in range(3))
    c = np.empty((len(euler), 3, 3))
    c[:, 0] = np.stack([c2 * c3, s1 * s2 * c3 - s3 * c1, c1 * s2 * c3 + s3 * s1], axis=1)
    c[:, 1] = np.stack([c2 * s3, s1 * s2 * s3 + c1 * c3, c1 * s2 * s3 - c3 * s1], axis=1)
    c[:, 2] = np.stack([-s2, s1 * c2, c1 * c2], axis=1)
    return c


@dataclass
class Pose:
    """Origin r (n, 3) and rotation c (n, 3, 3) of a body over the frames."""
    r: np.ndarray
    c: np.ndarray

    def apply(self, local):
        """Inertial positions (n, m, 3) of body-frame points local (m, 3)."""
        return self.r[:, None, :] + np.einsum("nij,mj->nmi", self.c, np.asarray(local, float))


def ship_pose(run, frames):
    """The ship's pose: its recorded CG and attitude, or at rest at the origin (scenes
    without a ship body, where the ship frame is the inertial one)."""
    if run.has(*layout.SHIP):
        return Pose(run.get(layout.SHIP_POSITION)[frames],
                    rotations(run.get(layout.SHIP_EULER)[frames]))
    n = len(frames)
    return Pose(np.zeros((n, 3)), np.broadcast_to(np.eye(3), (n, 3, 3)).copy())


def boat_pose(run, frames):
    """The boat's recorded CG and attitude."""
    return Pose(run.get(layout.BOAT_POSITION)[frames],
                rotations(run.get(layout.BOAT_EULER)[frames]))


def ship_box(run):
    """The ship's hull as a box (8 corners, ship frame): waterline length x beam, keel at
    the draught below the still waterline, deck at the moulded depth above the keel; the
    CG (the frame's origin) cg_x forward of midship and cg_z below the waterline."""
    half_l = 0.5 * deck(run, "ship", "length_waterline")
    half_b = 0.5 * deck(run, "ship", "beam")
    x0, waterline = -deck(run, "ship", "cg_x"), -deck(run, "ship", "cg_z")
    keel = waterline + deck(run, "ship", "draught")
    top = keel - deck(run, "ship", "depth")
    return np.array([[x0 + sx * half_l, sy * half_b, z] for z in (keel, top)
                     for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))])


def side_plane(run):
    """The contact side plane (4 corners, ship frame): y = &contact side_y over the
    waterline length, from the still waterline up to the deck (its freeboard)."""
    box = ship_box(run)
    side_y = run.deck("contact", "side_y", 0.5 * deck(run, "ship", "beam") + 0.1)
    x_lo, x_hi = box[:, 0].min(), box[:, 0].max()
    waterline, top = -deck(run, "ship", "cg_z"), box[:, 2].min()
    return np.array([[x_lo, side_y, waterline], [x_hi, side_y, waterline],
                     [x_hi, side_y, top], [x_lo, side_y, top]])


def boat_hull(run):
    """The boat's hull (BOAT_STATIONS sections of 4 corners, boat frame): the strip
    model's plan shape b(x) = B (1 - |2x/L|^p), keel `keel` below the CG, `height` deep."""
    length, beam = deck(run, "boat", "length"), deck(run, "boat", "beam")
    keel, height = deck(run, "boat", "keel"), deck(run, "boat", "height")
    p = deck(run, "boat", "breadth_exponent")
    x = np.linspace(-0.5 * length, 0.5 * length, BOAT_STATIONS)
    half = 0.5 * beam * (1 - np.abs(2 * x / length) ** p)
    return np.array([[xi, sy * hi, z] for xi, hi in zip(x, half)
                     for sy, z in ((-1, keel), (1, keel), (1, keel - height),
                                   (-1, keel - height))])


def hooks(run, frames):
    """Inertial hook positions (n, 2, 3), fore then aft."""
    local = [deck(run, "slings", "hook_fore"), deck(run, "slings", "hook_aft")]
    return boat_pose(run, frames).apply(local)


def fenders(run, frames):
    """Inertial end points (n, nf, 2, 3) of each fender's vertical span, boat frame
    (fender_x, fender_y, fender_z)."""
    xs = np.atleast_1d(deck(run, "contact", "fender_x"))
    y, (z0, z1) = float(deck(run, "contact", "fender_y")), deck(run, "contact", "fender_z")
    local = [[x, y, z] for x in xs for z in (z0, z1)]
    return boat_pose(run, frames).apply(local).reshape(len(frames), len(xs), 2, 3)


@dataclass
class Falls:
    """The falls and slings over the frames as polylines: points (n, m, 3), each point's
    kind (m), the segments as point index pairs (s, 2), each segment's tension (n, s) and
    whether it is a sling (s)."""
    points: np.ndarray
    kind: np.ndarray
    segments: np.ndarray
    tension: np.ndarray
    sling: np.ndarray


def _cable_nodes(run):
    """Reeving A or B as in src/rigging/falls.f90 build_reeving: per cable, the ship-frame
    nodes (drum, lead sheave, head sheave(s)) with None at each block (its index)."""
    h = np.array([0.5 * float(deck(run, "rigging", "head_spacing")), 0.0, 0.0])
    heads = [deck(run, "rigging", "head_fore"), deck(run, "rigging", "head_aft")]
    drum, lead = deck(run, "rigging", "drum_position"), deck(run, "rigging", "lead_sheave")
    if deck(run, "rigging", "reeving") == "a":
        return [[(DRUM, drum), (SHEAVE, lead), (SHEAVE, heads[0] - h), (BLOCK, 0),
                 (SHEAVE, heads[0] + h), (SHEAVE, heads[1] + h), (BLOCK, 1),
                 (DEAD_END, heads[1] - h)]]
    cables = []
    for a, head in enumerate(heads):
        side = np.sign(head[0]) * h
        cables.append([(DRUM, np.r_[head[0], drum[1:]]), (SHEAVE, np.r_[head[0], lead[1:]]),
                       (SHEAVE, head - side), (BLOCK, a), (DEAD_END, head + side)])
    return cables


def _polyline(columns, kinds, segments, tensions, slings, nodes, tension, sling):
    """Append a polyline of node columns (n, 3) to the Falls accumulators."""
    start = len(columns)
    for kind, column in nodes:
        columns.append(column)
        kinds.append(kind)
    for i in range(len(nodes) - 1):
        segments.append((start + i, start + i + 1))
        tensions.append(tension[:, i] if np.ndim(tension) == 2 else tension)
        slings.append(sling)


def falls(run, frames):
    """The cables (davit rigging: /rigging/segment_tension, cable 1 then 2) and the slings
    from each block down its lumps to its hook (tension: the hook segment's, the only one
    recorded); without the davit rigging, the two slings from their fixed anchors."""
    n = len(frames)
    hook = _sling_ends(run, frames)
    sling_tension = run.get(layout.SLING_TENSION)[frames]
    columns, kinds, segments, tensions, slings = [], [], [], [], []
    seg = run.get(layout.RIGGING_SEGMENT_TENSION)
    if seg is None:
        anchors = [deck(run, "slings", "anchor_fore"), deck(run, "slings", "anchor_aft")]
        for s in range(2):
            _polyline(columns, kinds, segments, tensions, slings,
                      [(ANCHOR, np.broadcast_to(anchors[s], (n, 3))), (HOOK, hook[:, s])],
                      sling_tension[:, s], True)
        return _assemble(columns, kinds, segments, tensions, slings)
    ship = ship_pose(run, frames)
    blocks = _block_positions(run, frames, hook)
    first = 0
    for cable in _cable_nodes(run):
        nodes = [(kind, blocks[:, where] if kind == BLOCK else ship.apply([where])[:, 0])
                 for kind, where in cable]
        _polyline(columns, kinds, segments, tensions, slings, nodes,
                  seg[frames][:, first:first + len(nodes) - 1], False)
        first += len(nodes) - 1
    lumps = run.get(layout.SLING_LUMPS)
    per_sling = 0 if lumps is None else lumps.shape[1] // 2
    for s in range(2):
        chain = [(BLOCK, blocks[:, s])]
        chain += [(LUMP, lumps[frames][:, s * per_sling + j]) for j in reversed(range(per_sling))]
        chain += [(HOOK, hook[:, s])]
        _polyline(columns, kinds, segments, tensions, slings, chain, sling_tension[:, s], True)
    return _assemble(columns, kinds, segments, tensions, slings)


def _sling_ends(run, frames):
    """The slings' lower ends: the hooks, and once released (/events/release_time) where
    the hooks let go, as the Fortran freezes the falls there (src/system/observables.f90)."""
    ends = hooks(run, frames)
    release = run.event(layout.RELEASE_TIME)
    if release is None or release > run.time[-1]:
        return ends
    at = int(np.searchsorted(run.time, release))
    after = run.time[frames] >= release
    ends[after] = hooks(run, np.array([min(at, len(run.time) - 1)]))[0]
    return ends


def _block_positions(run, frames, hook):
    """Recorded block positions, or (files from before /rigging/block_position) each block
    drawn on its hook, so the falls still end at the boat."""
    blocks = run.get(layout.RIGGING_BLOCKS)
    return hook if blocks is None else blocks[frames]


def _assemble(columns, kinds, segments, tensions, slings):
    return Falls(points=np.stack(columns, axis=1), kind=np.array(kinds),
                 segments=np.array(segments), tension=np.stack(tensions, axis=1),
                 sling=np.array(slings))


def has_sea(run):
    """Whether the file records its waves (/sea/components: sea runs, and launches in waves)."""
    return run.has(layout.SEA_OMEGA, layout.SEA_K, layout.SEA_DIRECTION, layout.SEA_AMPLITUDE,
                   layout.SEA_PHASE)


def sea_elevation(run, t, x, y):
    """Surface elevation eta (up) at (x, y) and time t: the recorded wave components where
    the file has them, else the still water (0)."""
    if not has_sea(run):
        return np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)
    return layout.sea_elevation(run, t, x, y)


def frame_indices(run, every):
    """The sample indices drawn: every `every`-th, from the first."""
    if every < 1:
        raise ValueError(f"--every must be >= 1 (got {every})")
    return np.arange(0, len(run.time), every)
