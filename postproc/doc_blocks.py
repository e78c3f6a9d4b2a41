"""The documentation's blocks generated from the code, and the site: `davit-post doc-blocks`.

Each block sits in its page of doc/ between `<!-- NAME:start -->` and `<!-- NAME:end -->`:

  keys        doc/reference/deck_keys.md  `davit keys` (every deck key, Markdown tables)
  davit_help  doc/reference/cli.md        `davit --help` and each subcommand's --help
  post_help   doc/reference/cli.md        `davit-post --help` (its command list)
  modules     doc/reference/modules.md    every folder of src/ and its source files
  output_run  doc/reference/output.md     every dataset of a run file as davit writes it
                                          (a 2 s run of the default scene): dims, type,
                                          units, description
  output_sweep doc/reference/output.md    the same for a sweep summary (two 1 s cases)

  python -m postproc.doc_blocks [--write | --check] [--davit PATH]
      print the blocks made from the code; --write puts them into their pages, --check exits
      1 naming each page whose block differs (the davit of --davit, DAVIT_BIN, else `davit`
      on PATH)
  python -m postproc.doc_blocks --site [OUTDIR]
      build the site with FORD (settings in fpm.toml [extra.ford]; README.md is its front
      page, doc/ its pages) into build/doc/, then point the pages' links to other pages
      (`x.md`, `x.md#part`) at their HTML (`x.html`), so that the same Markdown reads on
      GitHub and on the site

test/python/test_docs.py checks that the pages hold what the code prints and that the site
builds with every internal link resolved; bash make.sh docs runs --write, then --site.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

from . import layout

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KEYS_PAGE = os.path.join("doc", "reference", "deck_keys.md")
CLI_PAGE = os.path.join("doc", "reference", "cli.md")
# name -> page of doc/ that holds it
MODULES_PAGE = os.path.join("doc", "reference", "modules.md")
OUTPUT_PAGE = os.path.join("doc", "reference", "output.md")
PAGES = {"keys": KEYS_PAGE, "davit_help": CLI_PAGE, "post_help": CLI_PAGE,
         "modules": MODULES_PAGE, "output_run": OUTPUT_PAGE, "output_sweep": OUTPUT_PAGE}
# the scene whose file the output reference lists, and the sweep over it
OUTPUT_DECK = os.path.join("input", "iiib_level5_090.nml")
SITE = os.path.join(ROOT, "build", "doc")


def davit_binary(given=None):
    """The davit to run: `given`, DAVIT_BIN, else `davit` on PATH."""
    binary = given or os.environ.get("DAVIT_BIN") or shutil.which("davit")
    if not binary:
        raise OSError("no davit: give --davit PATH, set DAVIT_BIN or put davit on PATH "
                      "(bash make.sh install)")
    return binary


def _run(argv):
    # the project's data files (BEM databases) after the user's DAVIT_PATH
    path = os.pathsep.join(p for p in (os.environ.get("DAVIT_PATH", ""),
                                       os.path.join(ROOT, "input")) if p)
    result = subprocess.run(argv, capture_output=True, text=True, cwd=ROOT,
                            env=dict(os.environ, COLUMNS="100", DAVIT_PATH=path))
    if result.returncode != 0:
        raise OSError(f"{' '.join(argv)} failed ({result.returncode}): {result.stderr.strip()}")
    return result.stdout


def post_help():
    """The command list of `davit-post --help` (its description, not argparse's option
    listing, whose layout changes with the Python version)."""
    text = _run([sys.executable, "-m", "postproc", "--help"])
    start = text.index("Command line:")
    end = text.index("\npositional arguments:")
    body = text[start:end].rstrip() + "\n"
    return body.replace("python -m postproc", "davit-post")


def modules():
    """A table of every folder of src/ and its Fortran (and C) sources."""
    src = os.path.join(ROOT, "src")
    rows = ["| folder | sources |", "|---|---|"]
    top = sorted(f for f in os.listdir(src) if os.path.isfile(os.path.join(src, f)))
    rows.append("| `src/` | " + ", ".join(f"`{f}`" for f in top) + " |")
    for folder in sorted(f for f in os.listdir(src) if os.path.isdir(os.path.join(src, f))):
        files = sorted(f for f in os.listdir(os.path.join(src, folder))
                       if f.endswith((".f90", ".F90", ".c")))
        rows.append(f"| `src/{folder}/` | " + ", ".join(f"`{f}`" for f in files) + " |")
    return "\n".join(rows) + "\n"


def _deck_with(text, group, key, value):
    """Deck text with `key = value` in `&group`: the key's line replaced where the deck has
    one, else added at the start of the group."""
    line = re.compile(rf"^(\s*{key}\s*=\s*)[^!\n]*", re.M | re.I)
    if line.search(text):
        return line.sub(rf"\g<1>{value} ", text, count=1)
    return re.sub(rf"(&{group}\b[^\n]*\n)", rf"\g<1>  {key} = {value}\n", text, count=1,
                  flags=re.I)


def _listing(path):
    """Markdown table of every dataset of an HDF5 file davit wrote: its path, dimension
    names (h5py's order), type, units and description (what the writer attached)."""
    import h5py
    rows = ["| dataset | dims (h5py order) | type | units | description |", "|---|---|---|---|---|"]

    def text(value):
        return value.decode() if isinstance(value, bytes) else str(value)

    def visit(name, obj):
        if not isinstance(obj, h5py.Dataset) or layout.UNITS not in obj.attrs:
            return
        # netCDF-4's dimension-only scales (a length, no data) are the dims, not datasets
        if text(obj.attrs.get(layout.SCALE_NAME, "")).startswith(layout.DIMENSION_ONLY):
            return
        dims = ", ".join(d[0].name.rsplit("/", 1)[-1] if len(d) else "-"
                         for d in obj.dims) or "scalar"
        kind = {"f": "real", "i": "int", "u": "int", "O": "text", "S": "text"}.get(
            obj.dtype.kind, str(obj.dtype))
        if h5py.check_string_dtype(obj.dtype) is not None:
            kind = "text"
        rows.append(f"| `/{name}` | {dims} | {kind} | {text(obj.attrs[layout.UNITS])} | "
                    f"{text(obj.attrs.get(layout.DESCRIPTION, '')).replace('|', '/')} |")
    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return "\n".join(rows) + "\n"


def output_blocks(binary):
    """The run file of a 2 s run of the default scene and the summary of a two-case sweep
    over it, listed (in a scratch folder)."""
    import tempfile
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(ROOT, OUTPUT_DECK)) as f:
            deck = _deck_with(f.read(), "simulation", "t_end", "2.0")
        base = os.path.join(work, "base.nml")
        with open(base, "w") as f:
            f.write(deck)
        run = os.path.join(work, "run.h5")
        _run([binary, "run", base, "-o", run])
        sweep_deck = os.path.join(work, "sweep.nml")
        with open(sweep_deck, "w") as f:
            f.write("&sweep\n  base_deck = 'base.nml'\n  levels = 4, 5\n"
                    "  realisations = 1\n/\n")
        summary = os.path.join(work, "sweep.h5")
        _run([binary, "sweep", sweep_deck, "-o", summary, "--quiet"])
        return {"output_run": _listing(run), "output_sweep": _listing(summary)}


SUBCOMMANDS = ("run", "rao", "sweep", "keys", "modes", "bench")


def davit_help(binary):
    """`davit --help`, then each subcommand's `--help`."""
    parts = ["```text\n" + _run([binary, "--help"]).rstrip() + "\n```\n"]
    for sub in SUBCOMMANDS:
        parts.append(f"\n`davit {sub} --help`:\n\n```text\n"
                     + _run([binary, sub, "--help"]).rstrip() + "\n```\n")
    return "".join(parts)


def make(binary):
    """{name: block text} from the code."""
    return {"keys": _run([binary, "keys"]),
            "davit_help": davit_help(binary),
            "post_help": "```text\n" + post_help() + "```\n",
            "modules": modules(), **output_blocks(binary)}


def _markers(name):
    return f"<!-- {name}:start -->\n", f"<!-- {name}:end -->"


def copy_of(text, name):
    """The page's copy of block `name` (None where the page has no such block)."""
    start, end = _markers(name)
    if start not in text or end not in text:
        return None
    return text.split(start, 1)[1].split(end, 1)[0]


def replace(text, name, block):
    start, end = _markers(name)
    head, rest = text.split(start, 1)
    return head + start + block + end + rest.split(end, 1)[1]


def page_text(name):
    with open(os.path.join(ROOT, PAGES[name])) as f:
        return f.read()


def stale(blocks):
    """Names of the blocks whose page copy differs from the code's."""
    return [name for name, block in blocks.items() if copy_of(page_text(name), name) != block]


def write(blocks):
    for name, block in blocks.items():
        path = os.path.join(ROOT, PAGES[name])
        with open(path) as f:
            text = f.read()
        new = replace(text, name, block)
        if new != text:
            with open(path, "w") as f:
                f.write(new)
            print(f"doc-blocks: updated '{name}' in {PAGES[name]}")


# href="x.md" or href="x.md#part" (relative, not a scheme): the page's own HTML
MD_LINK = re.compile(r'href="(?![a-z]+:|/|#)([^"#]*?)\.md(#[^"]*)?"')


def _html_links(path, front=False):
    with open(path) as f:
        text = f.read()
    if front:
        # the front page is README.md at the root: its links into doc/ go to page/
        text = re.sub(r'href="doc/([^"]*)"', r'href="page/\1"', text)
        text = text.replace('href="doc/"', 'href="page/index.html"')
    new = MD_LINK.sub(lambda m: f'href="{m.group(1)}.html{m.group(2) or ""}"', text)
    if new != text:
        with open(path, "w") as f:
            f.write(new)


def build_site(outdir=SITE):
    """FORD into `outdir` (README.md the front page, fpm.toml's [extra.ford] the settings),
    then the pages' .md links rewritten to .html. Returns FORD's output (warnings)."""
    ford = shutil.which("ford")
    if not ford:
        raise OSError("no ford: pip install ford (bash make.sh docs installs it)")
    result = subprocess.run([ford, "--output_dir", outdir, "README.md"], cwd=ROOT,
                            capture_output=True, text=True)
    if result.returncode != 0:
        raise OSError(f"ford failed ({result.returncode}):\n{result.stdout}\n{result.stderr}")
    _html_links(os.path.join(outdir, "index.html"), front=True)
    for folder, _, files in os.walk(os.path.join(outdir, "page")):
        for name in files:
            if name.endswith(".html"):
                _html_links(os.path.join(folder, name))
    return result.stdout + result.stderr


def main(argv=None):
    parser = argparse.ArgumentParser(prog="davit-post doc-blocks",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--write", action="store_true", help="put the blocks into their pages")
    parser.add_argument("--check", action="store_true", help="exit 1 if a page is stale")
    parser.add_argument("--davit", help="the davit binary (default DAVIT_BIN, else PATH)")
    parser.add_argument("--site", nargs="?", const=SITE, metavar="OUTDIR",
                        help="build the site with FORD (default build/doc)")
    args = parser.parse_args(argv)
    try:
        if args.site:
            log = build_site(os.path.abspath(args.site))
            warnings = [line for line in log.splitlines() if "warn" in line.lower()]
            for line in warnings:
                print(line, file=sys.stderr)
            print(f"doc-blocks: site in {os.path.join(os.path.abspath(args.site), 'index.html')}")
            return 0
        blocks = make(davit_binary(args.davit))
    except (OSError, ValueError) as exc:
        print(f"davit-post doc-blocks: {exc}", file=sys.stderr)
        return 1
    if args.write:
        write(blocks)
    elif args.check:
        old = stale(blocks)
        for name in old:
            print(f"doc-blocks: {PAGES[name]}: block '{name}' differs from the code: "
                  "davit-post doc-blocks --write (or .ci/update_docs.sh)", file=sys.stderr)
        return 1 if old else 0
    else:
        for name, block in blocks.items():
            print(f"<!-- {name} ({PAGES[name]}) -->\n{block}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
