"""Hostile decks for the deck parser (issue 19, classes 4, 5, 7 and 8).

Every refused deck: exit status 1, exactly one `davit: error:` line naming file:line, the
group, the key and what is allowed; no file left beside the deck; a good file already at
the `-o` path left byte-identical. Every valid deck, however long, runs and stores its text.
The tables are generated: add a malformed form to a list and it is tried on every key kind.
"""
import re

import h5py
import pytest

ERROR_LINE = re.compile(r"^davit: error: ", re.M)

# Forms that list-directed READ accepts or misreads ('1-3' is 1e-3, '-15-1' is -1.5) and
# that are not numbers as a person writes them.
NOT_REAL = ["1-3", "-15-1", "1+3", "1e", "1e+", "1.0e-", "1..2", "1.0.0", "0x10", "--1",
            "+-1", "1e3.0", "1e-3e1", ".", "e3", "d-3", "1d", "2*0.5", "1.0_8", "nan",
            "NaN", "inf", "-Infinity", "T", ".true.", "'1.0'", "(1.0)", "1,5e", "\u00bd"]
NOT_INTEGER = ["1-3", "1e3", "1.0", "3.", "+-3", "--2", "0x10", "1_000", "T", "'7'", "7a",
               "1 2"]
NOT_LOGICAL = ["1", "0", "yes", "no", ".true.x", "tru", ".t", "'maybe'", ".false.."]

# Real forms that must be read exactly (dt = 1e-3 in each).
REAL_FORMS = ["1e-3", "1.0e-3", "1.0d-3", "1.0D-3", ".1e-2", "1.e-3", "+1E-3", "0.001",
              "1e-03", "1.0E-0003", "0.0010"]

PREAMBLE = "! hostile deck\n! line 2\n"          # keys below start on line 3


def _message(result):
    lines = ERROR_LINE.findall(result.stderr)
    assert len(lines) == 1, f"expected exactly one error line:\n{result.stderr}"
    return result.stderr.strip().splitlines()[-1]


@pytest.fixture
def good_output(short_run, tmp_path):
    """A complete output file already at the -o path of the deck under test."""
    target = tmp_path / "keep.h5"
    target.write_bytes(short_run[1].read_bytes())
    return target


def _refused(davit, tmp_path, text, pattern, good_output, command="run"):
    deck = tmp_path / "bad.nml"
    deck.write_text(text, encoding="utf-8")
    before = good_output.read_bytes()
    result = davit(command, deck, "-o", good_output)
    assert result.returncode == 1, result.stderr
    message = _message(result)
    assert re.search(pattern, message), message
    assert good_output.read_bytes() == before, "a refused deck changed the existing output"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.nml", "keep.h5"], \
        "a refused deck left a file"
    assert all(32 <= ord(c) < 127 for c in message), "message must be printable ASCII"
    return message


@pytest.mark.parametrize("value", NOT_REAL)
def test_malformed_real_scalar(davit, tmp_path, good_output, value):
    pattern = (rf"bad\.nml:4: &simulation: dt = .*: not a real number; "
               rf"allowed: 0 < dt <= 1 \[s\]$")
    if value == "1,5e":
        pattern = r"bad\.nml:4: &simulation: dt = 1,5e: expects 1 real value\(s\), got 2"
    _refused(davit, tmp_path, PREAMBLE + f"&simulation\n  dt = {value}\n/\n", pattern,
             good_output)


@pytest.mark.parametrize("value", [v for v in NOT_REAL if "," not in v])
def test_malformed_real_vector_item(davit, tmp_path, good_output, value):
    pattern = (r"bad\.nml:4: &boat: position = 0\.0, 13\.3, .*: item 3 \('.*'\) is not a "
               r"real number; allowed: -?[0-9.e]+ <= position <= [0-9.e]+ \(3 values\) \[m\]$")
    _refused(davit, tmp_path, PREAMBLE + f"&boat\n  position = 0.0, 13.3, {value}\n/\n",
             pattern, good_output)


@pytest.mark.parametrize("value", NOT_INTEGER)
def test_malformed_integer(davit, tmp_path, good_output, value):
    pattern = r"bad\.nml:3: &simulation: seed = .*: not an integer; allowed: .* <= seed <= "
    _refused(davit, tmp_path, PREAMBLE + f"&simulation seed = {value} /\n", pattern,
             good_output)


def test_integer_beyond_32_bits(davit, tmp_path, good_output):
    _refused(davit, tmp_path, PREAMBLE + "&simulation seed = 99999999999999999999 /\n",
             r"bad\.nml:3: &simulation: seed = 9+: out of range; allowed: .* <= seed <= ",
             good_output)


@pytest.mark.parametrize("value", NOT_LOGICAL)
def test_malformed_logical(davit, tmp_path, good_output, value):
    pattern = (r"bad\.nml:3: &simulation: fixed_step = .*: not a logical; "
               r"allowed: \.true\. or \.false\.$")
    _refused(davit, tmp_path, PREAMBLE + f"&simulation fixed_step = {value} /\n", pattern,
             good_output)


@pytest.mark.parametrize("form", REAL_FORMS)
def test_real_forms_are_read_exactly(davit, tmp_path, form):
    deck = tmp_path / "ok.nml"
    deck.write_text(f"&simulation t_end = 0.01, dt = {form}, output_interval = 0.01 /\n")
    out = tmp_path / "ok.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out) as f:
        assert f.attrs["dt"] == 1e-3


# Checks across keys: the line of (one of) the keys involved, else of the group.
CROSS_KEY = [
    ("&simulation\n  dt = 0.5\n/\n",
     r"bad\.nml:4: &simulation: output_interval = 0\.01 must be >= dt = 0\.5$"),
    ("&simulation\n  dt = 0.01,\n  output_interval = 0.001 /\n",
     r"bad\.nml:5: &simulation: output_interval = 0\.001 must be >= dt = 0\.01$"),
    ("&simulation\n  t_end = 0.001, dt = 0.002, output_interval = 0.01 /\n",
     r"bad\.nml:4: &simulation: t_end = 0\.001 must be >= dt = 0\.002$"),
    ("&sea\n\n  omega_max = 0.2\n/\n",
     r"bad\.nml:5: &sea: omega_min = 0\.3 must be < omega_max = 0\.2$"),
    ("&sea\n  probes_x = 1.0, 2.0,\n  probes_y = 3.0 /\n",
     r"bad\.nml:4: &sea: probes_x and probes_y must have the same number of values$"),
    ("&slings\n  hook_aft = 4.6, 0.0, -1.55 /\n",
     r"bad\.nml:4: &slings: hook_fore and hook_aft must differ$"),
]


@pytest.mark.parametrize("text,pattern", CROSS_KEY)
def test_cross_key_checks_name_a_line(davit, tmp_path, good_output, text, pattern):
    _refused(davit, tmp_path, PREAMBLE + text, pattern, good_output)


def test_sweep_cross_key_check_names_a_line(davit, tmp_path):
    (tmp_path / "base.nml").write_text("&simulation t_end = 0.05, output_interval = 0.01 /\n")
    deck = tmp_path / "sweep.nml"
    deck.write_text("&sweep\n  base_deck = 'base.nml'\n\n  dts = 0.5\n/\n")
    result = davit("sweep", deck, "-o", tmp_path / "s.h5")
    assert result.returncode == 1
    assert re.search(r"sweep\.nml:4: &sweep: dts = 0\.5 s must be <= the base deck's "
                     r"output_interval", _message(result))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["base.nml", "sweep.nml"]


# Broken structure, odd bytes, oversized names and values.
STRUCTURE = [
    ("&simulation dt = 'abc /\n", r"bad\.nml:3: &simulation: unterminated string$"),
    ("&simulation = 3 /\n", r"bad\.nml:3: &simulation: '=' without a key name before it$"),
    ("&" + "g" * 100 + " /\n", r"bad\.nml:3: group name '&g+' is longer than 64 characters$"),
    ("&simulation dt = 1e-3\n&boat mass = 1 /\n",
     r"bad\.nml:4: group &simulation \(opened at line 3\) is not closed before a new group$"),
    ("&simulation dt = 1/2\n", r"bad\.nml:3: text outside a namelist group: '2' "),
    ("&simulation dt = 1e-3 / &simulation seed = 1 /\n",
     r"bad\.nml:3: group &simulation appears twice \(first at line 3\)$"),
    ("\x00\x01\x02 binary\n", r"bad\.nml:3: text outside a namelist group: '\?\?\? binary'"),
    ("&simulation dt = " + "9" * 5000 + " /\n",
     r"bad\.nml:3: &simulation: dt = 9{72} \.\.\. : out of range; allowed: 0 < dt <= 1"),
    ("&sea probes_x = " + ", ".join(["1.0"] * 2000) + " /\n",
     r"bad\.nml:3: &sea: probes_x = .{77}: expects 1 to 1000 values, got 2000"),
    ("&simulation dt = 1e-3, dt = 2e-3 /\n",
     r"bad\.nml:3: &simulation: dt is given twice \(first at line 3\)$"),
]


@pytest.mark.parametrize("text,pattern", STRUCTURE)
def test_broken_structure(davit, tmp_path, good_output, text, pattern):
    _refused(davit, tmp_path, PREAMBLE + text, pattern, good_output)


def test_deck_that_is_a_directory(davit, tmp_path):
    (tmp_path / "dir.nml").mkdir()
    result = davit("run", tmp_path / "dir.nml", "-o", tmp_path / "x.h5")
    assert result.returncode == 1
    assert "cannot read input deck" in _message(result)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dir.nml"]


def test_crlf_tabs_and_byte_order_mark_are_accepted(davit, tmp_path):
    deck = tmp_path / "win.nml"
    deck.write_bytes(b"\xef\xbb\xbf! saved by a Windows editor\r\n&simulation\tt_end = 0.01,\r\n"
                     b"\tdt = 1.0d-3, output_interval = 0.01 /\r\n")
    out = tmp_path / "win.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out) as f:
        assert f.attrs["dt"] == 1e-3
        assert f.attrs["input_namelist"] == deck.read_bytes()


# Long but valid decks (class 7): the text over HDF5's 64 KiB compact attribute limit.
def _padding(kb):
    line = "! a long comment, as a study's provenance notes might be ...................\n"
    return line * (kb * 1024 // len(line) + 1)


@pytest.mark.parametrize("kb", [70, 1024])
def test_long_run_deck_runs_and_stores_its_text(davit, tmp_path, kb):
    deck = tmp_path / "long.nml"
    deck.write_text(_padding(kb) + "&simulation t_end = 0.01, output_interval = 0.01 /\n")
    out = tmp_path / "long.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out) as f:
        assert f.attrs["input_namelist"].decode() == deck.read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["long.h5", "long.nml"]


def test_long_sweep_deck_runs_resumes_and_stores_its_text(davit, tmp_path):
    base = "! base\n" + _padding(70) + "&simulation t_end = 0.05, output_interval = 0.01 /\n"
    (tmp_path / "base.nml").write_text(base)
    deck = tmp_path / "sweep.nml"
    deck.write_text(_padding(70) + "&sweep base_deck = 'base.nml', levels = 4, "
                    "angles_deg = 90.0, realisations = 1 /\n")
    out = tmp_path / "s.h5"
    for extra in ([], ["--resume"]):
        result = davit("sweep", deck, "-o", out, "--threads", "1", "--quiet", *extra)
        assert result.returncode == 0, result.stderr
    with h5py.File(out) as f:
        assert f.attrs["sweep_namelist"].decode() == deck.read_text()
        assert f.attrs["base_namelist"].decode() == base


# Size (class 4): a parser quadratic in the number of assignments takes hours on these;
# the linear one takes seconds. The timeout only catches quadratic behaviour, it is not a
# speed goal (README "Input errors" records the measured scaling).
def test_half_a_million_assignments_parse_in_linear_time(davit_bin, tmp_path):
    import subprocess
    deck = tmp_path / "huge.nml"
    deck.write_text("&simulation\n" + "".join(f" k{i} = 1.0\n" for i in range(500_000)) + "/\n")
    result = subprocess.run([davit_bin, "run", str(deck), "-o", str(tmp_path / "x.h5")],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert re.search(r"huge\.nml:2: &simulation: unknown key 'k0'; allowed keys: t_end",
                     _message(result))


def test_many_groups_parse_in_linear_time(davit_bin, tmp_path):
    import subprocess
    deck = tmp_path / "groups.nml"
    deck.write_text("".join(f"&g{i} /\n" for i in range(200_000)))
    result = subprocess.run([davit_bin, "run", str(deck), "-o", str(tmp_path / "x.h5")],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert re.search(r"groups\.nml:1: unknown namelist group &g0; allowed groups: &simulation",
                     _message(result))
