"""The one place that knows davit's HDF5 layout.

Fortran writes time series as (components, time); h5py returns them as (time, components).
The inertial frame N has z down; the paper's plots use oxy1z1, N turned 180 deg about x, so
y1 = -y and z1 = -z (z1 up).
"""
from dataclasses import dataclass

import h5py
import numpy as np

TIME = "time"
BOAT_POSITION = "boat/position"
BOAT_EULER = "boat/euler"
BOAT_VELOCITY = "boat/velocity"
BOAT_ANGULAR_VELOCITY = "boat/angular_velocity"
BOAT_ACCELERATION = "boat/acceleration"
SLING_TENSION = "slings/tension"
ENERGY = "diagnostics/energy"

REQUIRED = (TIME, BOAT_POSITION, BOAT_EULER, BOAT_VELOCITY, BOAT_ANGULAR_VELOCITY,
            BOAT_ACCELERATION)
ROOT_ATTRIBUTES = ("davit_version", "input_namelist", "seed", "steps", "rhs_evaluations",
                   "wall_time", "complete", "status")


def _text(value):
    return value.decode() if isinstance(value, (bytes, np.bytes_)) else str(value)


@dataclass
class Run:
    """A davit run file, loaded into numpy arrays (time along the first axis)."""
    path: str
    attrs: dict
    datasets: dict

    @property
    def time(self):
        return self.datasets[TIME]

    def get(self, name):
        return self.datasets.get(name)

    @property
    def complete(self):
        return int(self.attrs.get("complete", 0)) == 1


def load(path):
    """Read every dataset and the root attributes of a davit output file."""
    datasets = {}
    with h5py.File(path, "r") as f:
        attrs = {k: (_text(v) if isinstance(v, (bytes, np.bytes_)) else v)
                 for k, v in f.attrs.items()}

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                datasets[name] = obj[()]
        f.visititems(visit)
    missing = [name for name in REQUIRED if name not in datasets]
    if missing:
        raise ValueError(f"{path}: not a davit run file (missing {', '.join(missing)})")
    return Run(path=path, attrs=attrs, datasets=datasets)


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
