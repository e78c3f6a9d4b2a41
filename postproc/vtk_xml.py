"""VTK XML files written with numpy alone: unstructured grids (.vtu) and the ParaView
collection (.pvd) that makes a time series of them, so that the scene needs no VTK.

Arrays are inline base64 binary (format="binary", a UInt64 byte count before the raw
little-endian values, uncompressed): about a third larger than the raw bytes and four
times smaller than ASCII, and every VTK reader (ParaView, meshio, pyvista) opens it.
"""
import base64
import os
from xml.sax.saxutils import quoteattr

import numpy as np

# VTK cell type ids (vtkCellType.h) and how many points each has
VERTEX, LINE, POLYGON, QUAD = 1, 3, 7, 9
_TYPES = {np.dtype("float64"): "Float64", np.dtype("float32"): "Float32",
          np.dtype("int64"): "Int64", np.dtype("int32"): "Int32", np.dtype("uint8"): "UInt8"}


def _data_array(name, values, components=1):
    """One <DataArray> element: header (bytes as UInt64) and values, base64 together."""
    values = np.ascontiguousarray(values)
    if values.dtype not in _TYPES:
        values = values.astype(np.float64)
    raw = values.astype(values.dtype.newbyteorder("<"), copy=False).tobytes()
    payload = base64.b64encode(np.uint64(len(raw)).tobytes() + raw).decode("ascii")
    # scalars state no NumberOfComponents (1 by default), so readers give them 1-D
    count = f'NumberOfComponents="{components}" ' if components > 1 else ""
    return (f'<DataArray type="{_TYPES[values.dtype]}" Name={quoteattr(name)} {count}'
            f'format="binary">{payload}</DataArray>')


def _field(tag, data):
    """<PointData> or <CellData> with one array per entry of data ({name: array})."""
    arrays = [_data_array(name, v, 1 if np.ndim(v) == 1 else np.shape(v)[1])
              for name, v in data.items()]
    return f"<{tag}>" + "".join(arrays) + f"</{tag}>"


def write_vtu(path, points, cells, point_data=None, cell_data=None):
    """Write an unstructured grid: points (n, 3; stored as Float32, 1e-5 m at 100 m, which
    halves the sea patch's files), cells [(vtk type, connectivity (m, k))]
    in order, point_data {name: (n,) or (n, c)} and cell_data {name: one value per cell
    over all blocks, in the order of `cells`}."""
    points = np.asarray(points, dtype=np.float32).reshape(-1, 3)
    conn = [np.asarray(c, dtype=np.int32).reshape(len(c), -1) for _, c in cells]
    connectivity = np.concatenate([c.ravel() for c in conn]) if conn else np.zeros(0, np.int32)
    sizes = np.concatenate([np.full(len(c), c.shape[1]) for c in conn]) if conn else []
    offsets = np.cumsum(sizes).astype(np.int32)
    types = np.concatenate([np.full(len(c), t, np.uint8) for (t, _), c in zip(cells, conn)])
    body = ("<?xml version=\"1.0\"?>\n"
            '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
            'header_type="UInt64">\n<UnstructuredGrid>\n'
            f'<Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(types)}">\n'
            + _field("PointData", point_data or {}) + "\n"
            + _field("CellData", cell_data or {}) + "\n"
            + "<Points>" + _data_array("Points", points, 3) + "</Points>\n"
            + "<Cells>" + _data_array("connectivity", connectivity)
            + _data_array("offsets", offsets) + _data_array("types", types) + "</Cells>\n"
            "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")
    with open(path, "w") as f:
        f.write(body)
    return path


def write_pvd(path, entries):
    """A ParaView collection: entries [(time, part index, part name, file)], the files
    relative to the .pvd's folder so that the set can be moved."""
    folder = os.path.dirname(os.path.abspath(path))
    rows = [f'<DataSet timestep="{float(t)!r}" group="" part="{part}" name={quoteattr(name)} '
            f'file={quoteattr(os.path.relpath(os.path.abspath(file), folder))}/>'
            for t, part, name, file in entries]
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" '
                'byte_order="LittleEndian">\n<Collection>\n' + "\n".join(rows)
                + "\n</Collection>\n</VTKFile>\n")
    return path
