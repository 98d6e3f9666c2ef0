"""The package layout's rules, read from the source (issue 12).

Imports are read from every module's AST, function-level imports included:
no cycles, no subpackage importing the top-level ``jdraw`` package, and
nothing outside ``jdraw.train`` importing training code (so planning never
does). Modules stay under 400 lines, and every function or class
the library defines is used outside ``tests/`` (test doubles live in tests).
"""

from __future__ import annotations

import ast
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
PKG = ROOT / "jdraw"
MAX_LINES = 400
TRAINING = ("jdraw.train",)


def _modules() -> dict[str, pathlib.Path]:
    out = {}
    for p in sorted(PKG.rglob("*.py")):
        name = ".".join(p.relative_to(ROOT).with_suffix("").parts)
        out[name.removesuffix(".__init__")] = p
    return out


def _imports(mods: dict[str, pathlib.Path]) -> dict[str, set[str]]:
    """Module -> the ``jdraw`` modules it imports anywhere in its body."""

    def resolve(name: str) -> str:
        while name and name not in mods:
            name = name.rpartition(".")[0]
        return name

    edges: dict[str, set[str]] = {m: set() for m in mods}
    for m, p in mods.items():
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [f"{node.module}.{a.name}" for a in node.names]
            else:
                continue
            edges[m] |= {resolve(n) for n in names if n.split(".")[0] == "jdraw"}
        edges[m].discard(m)
    return edges


def _within(name: str, prefixes) -> bool:
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in edges:
        if v not in index:
            visit(v)
    return found


def test_cycle_finder_finds_a_cycle():
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(edges) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_import_cycles():
    assert _cycles(_imports(_modules())) == []


def test_subpackages_do_not_import_the_top_level_package():
    edges = _imports(_modules())
    bad = sorted(m for m, deps in edges.items() if "jdraw" in deps and m != "jdraw")
    assert bad == []


def test_only_training_imports_training():
    """Nothing outside ``jdraw.train`` reaches it, directly or through another module."""
    edges = _imports(_modules())
    bad = []
    for m in edges:
        if _within(m, TRAINING):
            continue
        seen, todo = set(), [m]
        while todo:  # everything m reaches, transitively
            for d in edges[todo.pop()] - seen:
                seen.add(d)
                todo.append(d)
        bad += [f"{m} -> {d}" for d in sorted(seen) if _within(d, TRAINING)]
    assert bad == []


def test_checkpoint_reading_imports_only_the_model():
    deps = _imports(_modules())["jdraw.model.checkpoints"]
    assert deps <= {"jdraw.model", "jdraw.model.bundle", "jdraw.model.network"}, deps


def test_modules_are_small():
    long = {
        m: n for m, p in _modules().items() if (n := len(p.read_text().splitlines())) > MAX_LINES
    }
    assert long == {}


def test_library_holds_no_test_doubles():
    """Every top-level function and class in ``jdraw/`` is named outside ``tests/``."""
    outside = [
        p
        for pattern in (
            "jdraw/**/*.py",
            "bench/*.py",
            "examples/*.py",
            "configs/*.py",
            "*.py",
            "*.md",
            "docs/*.md",
            "pyproject.toml",
        )  # fmt: skip
        for p in ROOT.glob(pattern)
    ]
    text = {p: p.read_text() for p in outside}
    unused = []
    for m, p in _modules().items():
        for node in ast.parse(text[p]).body:
            if not isinstance(node, (ast.FunctionDef, ast.ClassDef)) or node.name.startswith("__"):
                continue
            word = re.compile(rf"\b{re.escape(node.name)}\b")
            own = len(word.findall(text[p]))
            others = sum(len(word.findall(t)) for q, t in text.items() if q != p)
            if own < 2 and others == 0:
                unused.append(f"{m}.{node.name}")
    assert unused == []
