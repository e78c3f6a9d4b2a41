"""The documentation: the blocks generated from the code (deck keys, the command line) are
what the code prints, the FORD site builds (bash make.sh docs runs the same build) with
every page and every internal link resolved, and the user pages speak of the software, not
of its development history. The site build takes ~30 s, once for the module."""
import html.parser
import pathlib
import re
import shutil
import urllib.parse

import pytest

from postproc import doc_blocks

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = sorted((ROOT / "doc").rglob("*.md"))


@pytest.fixture(scope="module")
def blocks(davit_bin):
    """The blocks made from the code once (the output listings run davit twice)."""
    return doc_blocks.make(davit_bin)


@pytest.mark.parametrize("name", sorted(doc_blocks.PAGES))
def test_generated_block_is_what_the_code_prints(blocks, name):
    made = blocks[name]
    copy = doc_blocks.copy_of(doc_blocks.page_text(name), name)
    assert copy is not None, f"{doc_blocks.PAGES[name]} has no block '{name}'"
    assert copy == made, (f"{doc_blocks.PAGES[name]}: block '{name}' differs from the code "
                          "(davit-post doc-blocks --write)")


def test_block_check_fails_on_a_changed_page(blocks, monkeypatch):
    """--check notices a page whose block is not what the code prints: a deck key renamed,
    a dataset's units changed."""
    real = doc_blocks.page_text
    monkeypatch.setattr(doc_blocks, "page_text",
                        lambda name: real(name).replace("| `dt` |", "| `dt_old` |")
                        .replace("| `/time` | - | real | s |", "| `/time` | - | real | ms |"))
    assert doc_blocks.stale(blocks) == ["keys", "output_run"]


def test_every_key_of_the_code_is_in_the_reference(davit_bin):
    keys = re.findall(r"^\| `(\w+)` \|", doc_blocks.make(davit_bin)["keys"], re.M)
    page = (ROOT / doc_blocks.KEYS_PAGE).read_text()
    assert len(keys) > 100
    assert all(f"| `{k}` |" in page for k in keys)


class _Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("name"):
            self.ids.add(attrs["name"])
        for key in ("href", "src"):
            if attrs.get(key) and (tag, key) in (("a", "href"), ("img", "src")):
                self.links.append(attrs[key])


def _parse(path):
    parser = _Links()
    parser.feed(path.read_text(errors="replace"))
    return parser


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    if not shutil.which("ford"):
        pytest.fail("no ford on PATH: bash make.sh test installs it (pip install ford)")
    out = tmp_path_factory.mktemp("site")
    log = doc_blocks.build_site(str(out))
    return out, log


def test_site_builds_without_warnings(site):
    out, log = site
    assert (out / "index.html").is_file()
    problems = [line for line in log.splitlines()
                if re.search(r"warn|error", line, re.I) and "Undocumented" not in line]
    assert not problems, "\n".join(problems)


def test_every_page_is_in_the_site(site):
    out, _ = site
    for page in PAGES:
        rel = page.relative_to(ROOT / "doc").with_suffix(".html")
        assert (out / "page" / rel).is_file(), f"{page} is not in the site (a 'title:' line?)"
    assert (out / "page" / "figures" / "launch_frame.png").is_file()
    # the API pages: one per module of src/
    assert (out / "module" / "davit_sea.html").is_file() or list((out / "module").glob("*.html"))


def test_internal_links_resolve(site):
    """Every relative link of the front page and the user pages names a file of the site,
    and its #part an id in that file."""
    out, _ = site
    broken, ids = [], {}
    files = [out / "index.html", *sorted((out / "page").rglob("*.html"))]
    for path in files:
        for link in _parse(path).links:
            url = urllib.parse.urlsplit(link)
            if url.scheme or link.startswith(("//", "mailto:", "javascript:")):
                continue
            target = (path.parent / urllib.parse.unquote(url.path)).resolve() if url.path \
                else path
            if not target.exists() or target.is_dir() and not (target / "index.html").exists():
                broken.append(f"{path.relative_to(out)}: {link}")
                continue
            if url.fragment and target.suffix == ".html":
                if target not in ids:
                    ids[target] = _parse(target).ids
                if url.fragment not in ids[target]:
                    broken.append(f"{path.relative_to(out)}: {link} (no id)")
    assert not broken, "\n".join(broken)


def _prose(page):
    """A page's text outside the blocks generated from the code."""
    text = page.read_text()
    for name in doc_blocks.PAGES:
        start, end = doc_blocks._markers(name)
        if start in text:
            head, rest = text.split(start, 1)
            text = head + rest.split(end, 1)[1]
    return text


@pytest.mark.parametrize("page", [ROOT / "README.md", *PAGES],
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_pages_speak_of_the_software(page):
    """No internal labels without their meaning: no issue numbers, no review sections or
    gap labels, no paths outside the repository; generated blocks (the deck keys' texts
    from the code) included."""
    text = page.read_text()
    found = [m.group(0) for m in re.finditer(
        r"shared/spec|\bissues? \d+|\breview (?:§|G\d|A\d|F\d)|\(G\d+[),]|\bG\d+\b", text)]
    assert not found, f"{page.relative_to(ROOT)}: {sorted(set(found))}"


def test_readme_is_short_and_maps_the_docs():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 250
    for page in ("doc/tutorial.md", "doc/howto/index.md", "doc/reference/index.md",
                 "doc/theory/index.md", "doc/validation/index.md", "doc/benchmarks/index.md"):
        assert f"]({page})" in readme, page
        assert (ROOT / page).is_file(), page


def test_module_map_describes_every_folder():
    """The source layout's hand-written map names every folder of src/ (the generated
    table beside it lists their files)."""
    page = _prose(ROOT / doc_blocks.MODULES_PAGE)
    folders = sorted(p.name for p in (ROOT / "src").iterdir() if p.is_dir())
    missing = [f for f in folders if f"\nsrc/{f}/ " not in page]
    assert not missing, missing
    for module in ("bem_database", "bem_loads", "bem_water", "rosenbrock_w", "event_location",
                   "adaptive", "files", "scenario"):
        assert module in page, module
