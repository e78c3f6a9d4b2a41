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
