"""The post-processing package's modules import each other without cycles (also imports
inside functions, which hide a cycle from Python until the function runs), and deck editing
lives in postproc.deck_edit, not in a study module."""
import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
PKG = ROOT / "postproc"


def graph():
    names = {p.stem for p in PKG.glob("*.py")}
    edges = {}
    for path in PKG.glob("*.py"):
        out = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                if node.level == 1 and node.module:
                    out.add(node.module.split(".")[0])
                elif node.level == 1:
                    out.update(a.name for a in node.names)
                elif node.module and node.module.startswith("postproc"):
                    parts = node.module.split(".")
                    out.update([parts[1]] if len(parts) > 1 else [a.name for a in node.names])
        edges[path.stem] = {n for n in out if n in names and n != path.stem}
    return edges


def cycles(edges):
    found, state = [], {}

    def visit(node, stack):
        state[node] = 1
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                found.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = 2

    for node in sorted(edges):
        if node not in state:
            visit(node, [node])
    return found


def test_no_import_cycles():
    assert cycles(graph()) == []


def test_the_cycle_finder_finds_one():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_deck_editing_is_its_own_module():
    edges = graph()
    users = sorted(m for m, out in edges.items() if "deck_edit" in out)
    assert "study" in users and "bench_reference" in users
    text = (PKG / "study.py").read_text()
    assert "def override(" not in text and "def variant(" not in text
