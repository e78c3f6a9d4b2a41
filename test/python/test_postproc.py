"""postproc on a file written by the Fortran code."""
import struct

from postproc import __main__ as cli
from postproc import layout


def png_size(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def test_all_run_figures(short_run, tmp_path):
    _, out = short_run
    assert cli.main(["run", str(out), "-o", str(tmp_path)]) == 0
    names = sorted(p.name for p in tmp_path.glob("*.png"))
    assert names == ["short_acceleration.png", "short_contact.png", "short_sling_tension.png",
                     "short_trajectory.png"]
    for name in names:
        width, height = png_size(tmp_path / name)
        assert width > 400 and height > 300


def test_plot_frame_flips_y_and_z():
    assert layout.to_plot_frame([[1.0, 2.0, -15.0]]).tolist() == [[1.0, -2.0, 15.0]]


def test_non_davit_file_is_refused(tmp_path, capsys):
    bogus = tmp_path / "bogus.h5"
    bogus.write_bytes(b"not hdf5")
    assert cli.main(["trajectory", str(bogus), "-o", str(tmp_path)]) == 1
    assert "postproc: error" in capsys.readouterr().err


# --- layout.py is the one module that knows the HDF5 layout ---------------------------------
import ast  # noqa: E402
import pathlib  # noqa: E402
import re  # noqa: E402

POSTPROC = pathlib.Path(layout.__file__).parent
# top-level groups of davit's files: those of layout's paths, and the ones named directly
HDF5_GROUPS = ({value.split("/")[0] for name, value in vars(layout).items()
                if name.isupper() and isinstance(value, str) and "/" in value}
               | {layout.STUDY_GROUP, layout.RAO_GROUP, layout.SWEEP_GROUP, layout.SEA_GROUP}
               | {"boat", "study", "rigging", "sweep", "bench", "ship", "sea", "time", "events",
                  "diagnostics", "contact", "slings", "cases", "results", "rao"})
_ABSOLUTE = re.compile(rf"^/({'|'.join(sorted(HDF5_GROUPS | {'input'}))})(/|$)")
_RELATIVE = re.compile(rf"^({'|'.join(sorted(HDF5_GROUPS))})/\w")
_H5_WRITERS = {"create_group", "create_dataset", "require_group", "require_dataset"}
_ATTRIBUTE_HOLDERS = {"attrs", "group_attrs"}


def _docstrings(tree):
    nodes = [tree] + [n for n in ast.walk(tree)
                      if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))]
    return {id(n.body[0].value) for n in nodes
            if n.body and isinstance(n.body[0], ast.Expr)
            and isinstance(n.body[0].value, ast.Constant)}


def _layout_literals(tree):
    """(line, text) of every literal in `tree` that names an HDF5 path, group or attribute:
    a string like "/boat/..." or "boat/position", the name given to create_group and the
    like, and a literal key of an `.attrs` or `.group_attrs` lookup."""
    skip = _docstrings(tree)
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skip:
            if _ABSOLUTE.match(node.value) or _RELATIVE.match(node.value):
                found.append((node.lineno, node.value))
        key = None
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.args
                and (node.func.attr in _H5_WRITERS
                     or (node.func.attr == "get" and isinstance(node.func.value, ast.Attribute)
                         and node.func.value.attr in _ATTRIBUTE_HOLDERS))):
            key = node.args[0]
        elif (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Attribute)
              and node.value.attr in _ATTRIBUTE_HOLDERS):
            key = node.slice
        if isinstance(key, ast.Constant) and isinstance(key.value, str):
            found.append((key.lineno, key.value))
    return sorted(set(found))


def test_only_layout_names_hdf5_paths():
    offenders = [f"{path.name}:{line}: {text!r}"
                 for path in sorted(POSTPROC.glob("*.py")) if path.name != "layout.py"
                 for line, text in _layout_literals(ast.parse(path.read_text()))]
    assert not offenders, "HDF5 names outside postproc/layout.py:\n" + "\n".join(offenders)


def test_the_check_sees_raw_paths():
    code = ('f["/boat/position"]; f["study"].attrs.get("kind"); f.create_group("study")\n'
            'run.group_attrs.get("sea", {}); x = "results/status"\n'
            'def g():\n    """Reads /study and boat/position."""\n    return run.deck("sea", "h")\n')
    assert sorted(text for _, text in _layout_literals(ast.parse(code))) == \
        ["/boat/position", "kind", "results/status", "sea", "study"]


def test_one_figure_writer():
    saves = [f"{path.name}:{node.lineno}" for path in sorted(POSTPROC.glob("*.py"))
             for node in ast.walk(ast.parse(path.read_text()))
             if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name == "_save"]
    assert len(saves) == 1, f"def _save in postproc/: {saves}"


def test_sensitivity_counts_collisions_per_sea_state_and_angle(tmp_path):
    """postproc.sensitivity: a made-up summary of 2 sea states x 2 angles x 3 launches, one
    of them failed (status 2, not counted), gives the collided/finished counts by hand."""
    import h5py
    from postproc import layout, sensitivity
    h = [2.5] * 6 + [4.0] * 6
    t = [10.0] * 6 + [12.7] * 6
    a = [45.0, 45.0, 45.0, 90.0, 90.0, 90.0] * 2
    status = [1] * 12
    status[5] = 2
    collided = [1, 0, 1, 0, 0, 1, 0, 0, 0, 1, 1, 1]
    path = tmp_path / "s.h5"
    with h5py.File(path, "w") as f:
        for name, values in ((layout.SWEEP_CASE_WAVE_HEIGHT, h), (layout.SWEEP_CASE_WAVE_PERIOD, t),
                             (layout.SWEEP_CASE_ANGLE, a), (layout.SWEEP_STATUS, status),
                             (layout.SWEEP_COLLIDED, collided),
                             (layout.SWEEP_MIN_CLEARANCE, [0.0] * 12)):
            f[name] = values
    p = sensitivity.pattern(path)
    assert p == {(2.5, 10.0, 45.0): (2, 3), (2.5, 10.0, 90.0): (0, 2),
                 (4.0, 12.7, 45.0): (0, 3), (4.0, 12.7, 90.0): (3, 3)}
    assert "| s | 2/3 | 0/2 | 0/3 | 3/3 |" in sensitivity.table([path])


# --- bem_db.py is the one module that knows the BEM database's variables -------------------
_DATABASE_NAME = re.compile(r"^davit_[a-z0-9_]+$")


def _database_literals(tree):
    """(line, text) of every literal in `tree` (docstrings aside) that names a variable or
    attribute of the BEM database: a string of the form davit_<name>."""
    skip = _docstrings(tree)
    return sorted({(node.lineno, node.value) for node in ast.walk(tree)
                   if isinstance(node, ast.Constant) and isinstance(node.value, str)
                   and id(node) not in skip and _DATABASE_NAME.match(node.value)})


def test_only_bem_db_names_database_variables():
    """The database's schema is postproc/bem_db.py's (its names, shapes and units); davit's
    output files are layout.py's, whose root attribute davit_version is the one davit_ name it
    holds; doc_blocks.py's page keys (davit_help) name no variable."""
    allowed = {"layout.py": {"davit_version"}, "doc_blocks.py": {"davit_help"}}
    offenders = [f"{path.name}:{line}: {text!r}"
                 for path in sorted(POSTPROC.glob("*.py")) if path.name != "bem_db.py"
                 for line, text in _database_literals(ast.parse(path.read_text()))
                 if text not in allowed.get(path.name, set())]
    assert not offenders, "BEM database names outside postproc/bem_db.py:\n" + \
        "\n".join(offenders)


def test_the_database_check_sees_raw_names():
    found = _database_literals(ast.parse('"""davit_docstring"""\nx = f["davit_omega"]\n'
                                         'y = "davit omega"\n'))
    assert found == [(2, "davit_omega")]
