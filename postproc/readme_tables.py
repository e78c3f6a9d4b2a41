"""The documentation's deterministic tables, made from runs: `davit-post readme-tables [FOLDER]`.

Each table sits in its page of doc/ (PAGES) between `<!-- table:NAME -->` and
`<!-- /table:NAME -->` and is made here from the run files in FOLDER (default out/): the
launch loads of every III.A and III.B deck (doc/validation/launch.md), the regression
report's rows that the decks decide (doc/validation/index.md; the sweeps' rows need hours of
sweeps and stay by hand, with the command and the machine beside them), and the SOLAS decks
in calm water (doc/howto/operability.md). `--run` first runs the decks each table needs into
FOLDER (the davit of DAVIT_BIN, else `davit` on PATH), `--write` puts the tables into their
pages (or all into `--readme FILE`), `--check` compares (exit 1 naming each stale table).
test/python/test_readme_tables.py runs the decks afresh and checks the pages' copies, so
their numbers cannot go stale silently.
"""
import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys

import numpy as np

from . import launch_table, layout, regress

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ANGLES = ("000", "045", "090", "135", "180")
III_A = ("iiia_model_scale_1", "iiia_model_scale_2")
III_B = tuple(f"iiib_level{level}_{angle}{kind}" for level in (4, 5) for angle in ANGLES
              for kind in ("", "_irregular", "_nowind"))
# the launch table's rows: every III.A and III.B deck (doc/validation/launch.md)
LAUNCH_DECKS = tuple(sorted(III_A + III_B + ("iiib_level5_090_frozen",
                                             "iiib_level5_090_literal")))
# the regression report's deck facts (F2, F7 and F8 on the paper decks, F9)
REGRESS_DECKS = tuple(sorted(set(III_A + III_B) | {"fig13_tension", "iiib_level5_090_frozen"}))
SOLAS_DECKS = ("iiib_level5_090", "solas_list_p20", "solas_list_m20", "solas_trim_p10",
               "solas_trim_m10", "solas_headway")


def launch_loads(folder):
    """doc/validation/launch.md: one row per III.A/III.B run."""
    return launch_table.table([os.path.join(folder, f"{d}.h5") for d in LAUNCH_DECKS])


def regress_decks(folder):
    """The regression rows the decks decide: F2, F7 and F8 on the paper decks, F9."""
    verdicts = [v for v in regress.report(folder)
                if "(sweeps)" not in v.fact and not v.fact.startswith(("F10", "F11"))]
    lines = ["| fact | paper | davit | result |", "|---|---|---|---|"]
    lines += [f"| {v.fact} | {v.paper} | {v.davit or '-'} | {v.result} |" for v in verdicts]
    return "\n".join(lines)


def solas_calm(folder):
    """doc/howto/operability.md "SOLAS launch conditions": the calm-water decks' rule checks and peaks."""
    rows = ["| run | H (m) | lowering speed / limit (m/s) | impacts | fastest (m/s) | "
            "fall (kN) | sling (kN) | seat SRSS (m/s²) | DRI | released (s) | checks failed |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for deck in SOLAS_DECKS:
        run = layout.load(os.path.join(folder, f"{deck}.h5"))
        checks = {c.id: run.get(layout.assessment_dataset(c.id)) for c in layout.CHECKS}
        failed = [c.id for c in layout.CHECKS
                  if not np.isnan(checks[c.id][2]) and checks[c.id][2] < 0.0]
        speeds = run.get(layout.IMPACT_SPEED)
        speeds = np.zeros(0) if speeds is None else speeds
        release = float(run.get(layout.RELEASE_TIME)[0])
        height = float(run.group_attrs[layout.ASSESSMENT]["head_height"])
        rows.append(
            f"| {deck} | {height:.2f} | {checks['lowering_speed'][0]:.3f} / "
            f"{checks['lowering_speed'][1]:.3f} | {len(speeds)} | "
            f"{speeds.max() if len(speeds) else 0.0:.2f} | {checks['fall_swl'][0] / 1e3:.1f} | "
            f"{checks['sling_swl'][0] / 1e3:.1f} | {checks['seat_srss'][0]:.1f} | "
            f"{checks['seat_dri'][0]:.2f} | {release:.1f} | {', '.join(failed) or 'none'} |")
    return "\n".join(rows)


# name -> the page of doc/ that holds the table
PAGES = {"launch_loads": os.path.join("doc", "validation", "launch.md"),
         "regress_decks": os.path.join("doc", "validation", "index.md"),
         "solas_calm": os.path.join("doc", "howto", "operability.md")}


def page_path(name, readme=None):
    """The file that holds table `name`: `readme` when given, else its page of doc/."""
    return readme or os.path.join(ROOT, PAGES[name])


# name -> (decks it needs in the folder, maker)
TABLES = {"launch_loads": (LAUNCH_DECKS, launch_loads),
          "regress_decks": (REGRESS_DECKS, regress_decks),
          "solas_calm": (SOLAS_DECKS, solas_calm)}


def _markers(name):
    return f"<!-- table:{name} -->\n", f"\n<!-- /table:{name} -->"


def readme_copy(text, name):
    """The page's copy of table `name` (None if it has no such table)."""
    start, end = _markers(name)
    if start not in text or end not in text:
        return None
    return text.split(start, 1)[1].split(end, 1)[0]


def replace(text, name, table):
    """`text` with table `name` replaced by `table`."""
    start, end = _markers(name)
    head, rest = text.split(start, 1)
    return head + start + table + end + rest.split(end, 1)[1]


def davit_binary():
    """The davit to run: DAVIT_BIN, else `davit` on PATH."""
    binary = os.environ.get("DAVIT_BIN") or shutil.which("davit")
    if not binary:
        raise OSError("no davit: set DAVIT_BIN or put davit on PATH (bash make.sh install)")
    return binary


def run_decks(folder, decks, binary, jobs=2):
    """Run input/<deck>.nml -> FOLDER/<deck>.h5, `jobs` at a time; an error names the deck."""
    os.makedirs(folder, exist_ok=True)

    def one(deck):
        out = os.path.join(folder, f"{deck}.h5")
        result = subprocess.run([binary, "run", os.path.join(ROOT, "input", f"{deck}.nml"),
                                 "-o", out], capture_output=True, text=True,
                                env=dict(os.environ, OMP_NUM_THREADS="1"))
        if result.returncode != 0:
            raise OSError(f"davit run input/{deck}.nml failed: {result.stderr.strip()}")
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        list(pool.map(one, decks))


def make(folder, names):
    """{name: table} made from the run files in `folder`."""
    return {name: TABLES[name][1](folder) for name in names}


# Numbers in a table, with their printed decimals (a sign, digits, an optional fraction).
NUMBER = re.compile(r"(?<![\w.])[-+]?\d+(?:\.(\d+))?(?![\w.])")
# How far a number may move between CPUs and compilers (FMA or not, vector widths): the
# tables come from whole launches, where a last-bit difference in one step can move a
# located event by microseconds and a peak by a few parts in 10^4 (measured between
# -march=native and -march=x86-64-v2 builds: doc/validation/tests.md). A model change moves them
# by far more (a 10 % change of the strip drag coefficient moves most rows by > 1 %).
REL_TOL = 2e-3


def _split(line):
    """A table line as (text with numbers replaced by '#', [(value, decimals), ...])."""
    numbers = [(float(m.group(0)), len(m.group(1) or "")) for m in NUMBER.finditer(line)]
    return NUMBER.sub("#", line), numbers


def _close(old, new):
    """True when `new` equals the page's `old` at the precision `old` was printed with:
    one unit of its last decimal (a rounding that flips) plus REL_TOL of its size;
    integers (counts, whole newtons) only within REL_TOL."""
    (a, decimals), (b, _) = old, new
    unit = 10.0 ** -decimals if decimals else 0.0
    return abs(a - b) <= unit + REL_TOL * max(abs(a), abs(b))


def differences(copy, made):
    """Lines where the page's copy of a table and the made one differ: in their text, in
    how many numbers they hold, or in a number beyond its printed precision (_close)."""
    if copy is None:
        return ["(no table in the page)"]
    old_lines, new_lines = copy.split("\n"), made.split("\n")
    if len(old_lines) != len(new_lines):
        return [f"{len(old_lines)} lines in the page, {len(new_lines)} made"]
    found = []
    for old, new in zip(old_lines, new_lines):
        (old_text, old_numbers), (new_text, new_numbers) = _split(old), _split(new)
        if (old_text != new_text or len(old_numbers) != len(new_numbers)
                or not all(map(_close, old_numbers, new_numbers))):
            found.append(f"page: {old}\nmade:   {new}")
    return found


def stale(tables, text):
    """Names of the tables whose page copy differs (beyond the numbers' printed precision,
    see differences) from the made one, or that the page lacks."""
    return [name for name, table in tables.items()
            if differences(readme_copy(text, name), table)]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="davit-post readme-tables",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", nargs="?", default="out", help="run files (default out/)")
    parser.add_argument("--run", action="store_true", help="run the decks first")
    parser.add_argument("--write", action="store_true", help="put the tables into their pages")
    parser.add_argument("--check", action="store_true", help="exit 1 if a page's table is stale")
    parser.add_argument("--readme", default=None,
                        help="one file holding every table (default: each table's page of doc/)")
    parser.add_argument("--only", action="append", choices=sorted(TABLES),
                        help="this table only (repeatable)")
    args = parser.parse_args(argv)
    names = args.only or list(TABLES)
    try:
        if args.run:
            decks = sorted({d for n in names for d in TABLES[n][0]})
            run_decks(args.folder, decks, davit_binary())
        tables = make(args.folder, names)
        texts = {}
        for name in names:
            path = page_path(name, args.readme)
            if path not in texts:
                with open(path) as f:
                    texts[path] = f.read()
    except (OSError, ValueError, KeyError) as exc:
        print(f"davit-post readme-tables: {exc}", file=sys.stderr)
        return 1
    if args.write:
        for name, table in tables.items():
            path = page_path(name, args.readme)
            texts[path] = replace(texts[path], name, table)
        for path, text in texts.items():
            with open(path, "w") as f:
                f.write(text)
        print(f"readme-tables: wrote {', '.join(tables)} into {', '.join(texts)}")
    elif args.check:
        old = [name for name, table in tables.items()
               if stale({name: table}, texts[page_path(name, args.readme)])]
        for name in old:
            print(f"readme-tables: {page_path(name, args.readme)}: table '{name}' is stale "
                  f"(or missing): davit-post readme-tables {args.folder} --write", file=sys.stderr)
        return 1 if old else 0
    else:
        for name, table in tables.items():
            print(f"{name}:\n{table}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
