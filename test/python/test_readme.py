"""The README stays true: its key tables are exactly what `davit keys` prints."""
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_key_tables_match_code(davit):
    result = davit("keys")
    assert result.returncode == 0
    readme = (ROOT / "README.md").read_text()
    assert result.stdout.strip() in readme


def test_readme_starts_with_the_two_commands():
    readme = (ROOT / "README.md").read_text()
    head = readme[: readme.index("## Status")]
    assert "bash make.sh demo" in head and "bash make.sh test" in head
    ci = (ROOT / ".ci" / "run").read_text()
    assert "make.sh test" in ci
