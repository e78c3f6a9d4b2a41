"""`davit sweep --shard K/N` and `--merge`: job arrays of one sweep. Three shards merged give
the single run's summary bit for bit (wall times aside); the merge refuses overlapping
shards, another deck and another N; a merge with a shard missing leaves its cases not run
for --resume to complete; bad --shard values are usage errors."""
import h5py
import numpy as np
import pytest

from postproc import layout
from test_sweep import BASE, SWEEP, _setup

# attributes that legitimately differ between the single run and the merge
VOLATILE = {"threads", *layout.SWEEP_SHARD_ATTRIBUTES}


def _ok(result):
    assert result.returncode == 0, result.stderr
    return result


def _contents(path):
    """{dataset name: (dtype, shape, raw bytes or text)} of every dataset but
    results/wall_time."""
    data = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and name != "results/wall_time":
            value = obj[()]
            # text (variable-length strings) by value, not by its pointers
            raw = tuple(value.tolist()) if value.dtype.kind == "O" else value.tobytes()
            data[name] = (value.dtype.str, value.shape, raw)
    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return data


def _attrs(path):
    with h5py.File(path, "r") as f:
        return {k: layout._text(v) for k, v in f.attrs.items()}


def _assert_bitwise(a, b):
    da, db = _contents(a), _contents(b)
    assert da.keys() == db.keys()
    assert any(name.startswith("results/") for name in da)
    assert any(name.startswith("cases/") for name in da)
    for name in da:
        assert da[name] == db[name], name


@pytest.fixture(scope="module")
def shards(davit, tmp_path_factory):
    """The 8-case sweep of test_sweep run whole (4 threads) and as shards 1/3, 2/3, 3/3."""
    folder = tmp_path_factory.mktemp("shards")
    deck = _setup(folder)
    whole = folder / "whole.h5"
    _ok(davit("sweep", deck, "-o", whole, "--threads", "4", "--quiet"))
    parts = []
    for k in (1, 2, 3):
        part = folder / f"shard_{k}.h5"
        _ok(davit("sweep", deck, "--shard", f"{k}/3", "-o", part, "--threads", "2"))
        parts.append(part)
    return deck, whole, parts


def test_shards_partition_the_cases(shards):
    """Each shard runs its own slice (3, 3 and 2 of the 8 cases, round-robin), the others
    stay status 0, and the summary records K and N."""
    _, _, parts = shards
    finished = []
    for k, part in enumerate(parts, start=1):
        s = layout.load_sweep(part)
        assert s.ncase == 8
        assert set(np.unique(s.status)) <= {layout.SWEEP_NOT_RUN, layout.SWEEP_OK}
        finished.append(s.status == layout.SWEEP_OK)
        attrs = _attrs(part)
        assert (attrs["shard_index"], attrs["shard_count"]) == (k, 3)
        assert attrs["complete"] == 0
        assert np.isnan(s.wall_time[~s.ok]).all()
        assert all(m == "" for m, ok in zip(s.message, s.ok) if not ok)
    assert [f.sum() for f in finished] == [3, 3, 2]
    assert (np.sum(finished, axis=0) == 1).all()          # every case in exactly one shard


def test_merge_equals_the_single_run_bitwise(davit, shards, tmp_path):
    deck, whole, parts = shards
    merged = tmp_path / "merged.h5"
    result = _ok(davit("sweep", "--merge", merged, *parts))
    assert "8 cases: 8 ok, 0 failed, 0 not run; from 3 of 3 shards" in result.stdout
    assert "missing" not in result.stderr
    _assert_bitwise(merged, whole)
    a, b = _attrs(merged), _attrs(whole)
    assert not set(layout.SWEEP_SHARD_ATTRIBUTES) & set(a)
    assert a["complete"] == 1
    for key in set(a) | set(b):
        if key not in VOLATILE:
            assert a[key] == b[key], key
    # merging in another order gives the same file contents
    again = tmp_path / "again.h5"
    _ok(davit("sweep", "--merge", again, parts[2], parts[0], parts[1]))
    _assert_bitwise(again, whole)


def test_merge_of_two_shards_then_resume(davit, shards, tmp_path):
    """Shard 2 missing: its 3 cases stay not run (stderr says so); --resume on the merged
    summary runs exactly those and gives the single run's summary."""
    deck, whole, parts = shards
    merged = tmp_path / "partial.h5"
    result = _ok(davit("sweep", "--merge", merged, parts[0], parts[2]))
    assert "shard(s) 2 of 3 missing" in result.stderr
    assert "5 ok, 0 failed, 3 not run" in result.stdout
    s, two = layout.load_sweep(merged), layout.load_sweep(parts[1])
    np.testing.assert_array_equal(s.status == layout.SWEEP_NOT_RUN, two.ok)
    assert _attrs(merged)["complete"] == 0
    resumed = _ok(davit("sweep", deck, "-o", merged, "--resume", "--threads", "2"))
    assert "3 of 8 cases to run" in resumed.stderr
    _assert_bitwise(merged, whole)


def test_resume_of_a_shard(davit, shards, tmp_path):
    """A shard stopped after 1 case resumes only its own 2 others; another shard's
    --resume, or a whole-sweep --resume, refuses it."""
    deck, _, parts = shards
    out = tmp_path / "shard_2.h5"
    first = _ok(davit("sweep", deck, "--shard", "2/3", "-o", out, "--max-cases", "1"))
    assert "1 ok, 0 failed, 7 not run" in first.stdout
    for other in (["--shard", "1/3"], ["--shard", "2/4"], []):
        result = davit("sweep", deck, "-o", out, "--resume", *other)
        assert result.returncode == 1, other
        assert "cannot resume" in result.stderr and "shard 2/3" in result.stderr
    second = _ok(davit("sweep", deck, "--shard", "2/3", "-o", out, "--resume"))
    assert "2 of 8 cases to run" in second.stderr
    _assert_bitwise(out, parts[1])
    whole = tmp_path / "whole.h5"
    _ok(davit("sweep", deck, "-o", whole, "--max-cases", "1"))
    result = davit("sweep", deck, "--shard", "1/3", "-o", whole, "--resume")
    assert result.returncode == 1 and "whole sweep" in result.stderr


def test_merge_refuses_overlapping_shards(davit, shards, tmp_path):
    deck, whole, parts = shards
    out = tmp_path / "bad.h5"
    result = davit("sweep", "--merge", out, parts[0], parts[1], parts[0])
    assert result.returncode == 1
    assert "shard 1/3 is given twice" in result.stderr and str(parts[0]) in result.stderr
    assert not out.exists()
    # a copy of shard 1 relabelled as shard 2: the cases themselves overlap
    fake = tmp_path / "fake.h5"
    fake.write_bytes(parts[0].read_bytes())
    with h5py.File(fake, "r+") as f:
        f.attrs["shard_index"] = np.int64(2)
    result = davit("sweep", "--merge", out, parts[0], fake)
    assert result.returncode == 1
    assert "was run in both" in result.stderr and str(fake) in result.stderr
    assert not out.exists()
    # a whole-sweep summary is not a shard
    result = davit("sweep", "--merge", out, parts[0], whole)
    assert result.returncode == 1 and "not a shard summary" in result.stderr
    assert not out.exists()
    # a crafted shard number, and the output among the inputs
    with h5py.File(fake, "r+") as f:
        f.attrs["shard_index"] = np.int64(5)
    result = davit("sweep", "--merge", out, parts[0], fake)
    assert result.returncode == 1 and "is not 1 <= K <= N" in result.stderr
    assert not out.exists()
    before = parts[1].read_bytes()
    result = davit("sweep", "--merge", parts[1], parts[0], parts[1])
    assert result.returncode == 1 and "is also an input" in result.stderr
    assert parts[1].read_bytes() == before


def test_merge_refuses_another_deck_or_n(davit, shards, tmp_path):
    deck, _, parts = shards
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    other_sweep = _setup(tmp_path / "a", SWEEP.replace("base_seed = 11", "base_seed = 12"))
    other_base = _setup(tmp_path / "b", SWEEP, BASE.replace("t_end = 1.0 ", "t_end = 0.9 "))
    out = tmp_path / "bad.h5"
    cases = [(other_sweep, "2/3", "different sweep deck"),
             (other_base, "2/3", "different base deck"),
             (deck, "2/4", "another number of shards")]
    for k, (d, shard, message) in enumerate(cases):
        part = tmp_path / f"other_{k}.h5"
        _ok(davit("sweep", d, "--shard", shard, "-o", part, "--max-cases", "1", "--quiet"))
        result = davit("sweep", "--merge", out, parts[0], part)
        assert result.returncode == 1, message
        assert message in result.stderr and str(part) in result.stderr, result.stderr
        assert not out.exists()


@pytest.mark.parametrize("args, message", [
    (["--shard", "0/3"], "1 <= K <= N"),
    (["--shard", "4/3"], "1 <= K <= N"),
    (["--shard", "x"], "needs K/N"),
    (["--shard", "1/0"], "N >= 1"),
    (["--shard", "-1/3"], "needs K/N"),
    (["--shard", "1/3/5"], "needs K/N"),
    (["--shard"], "needs a value"),
])
def test_bad_shard_is_a_usage_error(davit, shards, args, message):
    deck, _, _ = shards
    result = davit("sweep", deck, *args)
    assert result.returncode == 2
    assert message in result.stderr, result.stderr


@pytest.mark.parametrize("args", [["--merge", "out.h5"], ["--merge"], ["--merge", ""],
                                  ["--merge", "out.h5", "a.h5", "--threads", "2"]])
def test_bad_merge_is_a_usage_error(davit, tmp_path, args):
    result = davit("sweep", *args, cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert not (tmp_path / "out.h5").exists()
