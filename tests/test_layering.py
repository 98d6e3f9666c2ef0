"""Inference never imports training (function-level imports included)."""

import ast
import pathlib

ROOT = pathlib.Path(__file__).parent.parent / "jdraw"


def _imports(path: pathlib.Path) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            out.add(node.module)
            out.update(f"{node.module}.{a.name}" for a in node.names)
    return out


def test_no_module_outside_train_imports_training():
    bad = {}
    for path in ROOT.rglob("*.py"):
        if path.relative_to(ROOT).parts[0] == "train":
            continue
        hits = {m for m in _imports(path) if m == "jdraw.train" or m.startswith("jdraw.train.")}
        if hits:
            bad[str(path.relative_to(ROOT))] = sorted(hits)
    assert not bad, bad


def test_checkpoint_reading_imports_only_the_model():
    mods = {m for m in _imports(ROOT / "model" / "checkpoints.py") if m.startswith("jdraw")}
    assert mods <= {"jdraw.model", "jdraw.model.bundle", "jdraw.model.network"}, mods
