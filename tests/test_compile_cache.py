"""The persistent compilation cache: where it lives, when it is off; plans do not change."""

import json
import os
import pathlib
import subprocess
import sys

from jdraw import compile_cache

ROOT = pathlib.Path(__file__).resolve().parents[1]

# Plans the README's kanji (one tile) and prints its strokes, the cache folder and the
# compilation-cache hits JAX reported.
_PLAN = """
import json, warnings
from jax import monitoring
hits, stored, compiled = [], [], []
monitoring.register_event_listener(
    lambda e, **k: hits.append(e) if e == "/jax/compilation_cache/cache_hits" else None)
monitoring.register_event_duration_secs_listener(
    lambda e, s, **k: stored.append(e) if e == "/jdraw/program_store/load_duration" else None)
monitoring.register_event_duration_secs_listener(
    lambda e, s, **k: compiled.append(e) if e == "/jax/core/compile/backend_compile_duration"
    else None)
import jdraw
from jdraw import compile_cache
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    r = jdraw.plan_image("examples/images/kanji.png", progress=False)
    folder = compile_cache.enable()
print(json.dumps({"dir": folder and str(folder), "hits": len(hits), "stored": len(stored),
                  "compiled": len(compiled),
                  "warnings": [str(x.message) for x in w],
                  "strokes": [s.tolist() for s in r.strokes]}))
"""


def _run(code: str, cache) -> dict:
    env = dict(os.environ, JDRAW_CACHE_DIR=str(cache), PYTHONPATH=str(ROOT))
    env.pop("JAX_COMPILATION_CACHE_DIR", None)
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=ROOT, capture_output=True, text=True, timeout=600
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_cache_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.delenv(compile_cache.ENV, raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert compile_cache.cache_root() == tmp_path / "xdg" / "jdraw"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert compile_cache.cache_root() == tmp_path / "home" / ".cache" / "jdraw"
    monkeypatch.setenv(compile_cache.ENV, str(tmp_path / "mine"))
    assert compile_cache.cache_root() == tmp_path / "mine"
    for off in ("off", "OFF", "0", "none", "false", ""):
        monkeypatch.setenv(compile_cache.ENV, off)
        assert compile_cache.cache_root() is None


def test_cache_is_per_jax_version():
    import jax
    import jaxlib

    d = compile_cache.versioned_dir(pathlib.Path("/c"))
    assert d.parent == pathlib.Path("/c")
    assert f"jax{jax.__version__}" in d.name and f"jaxlib{jaxlib.__version__}" in d.name


def test_plans_identical_with_and_without_the_cache(tmp_path):
    """Cold (compiles, writes), warm (reads the programs back) and off: the same strokes."""
    cache = tmp_path / "cache"
    # Another version's cache beside ours, with junk in it: never read.
    (cache / "xla-jax0.0.1-jaxlib0.0.1").mkdir(parents=True)
    (cache / "xla-jax0.0.1-jaxlib0.0.1" / "jit_many-0000-cache").write_bytes(b"junk")
    cold = _run(_PLAN, cache)
    folder = pathlib.Path(cold["dir"])
    assert folder.parent == cache and folder.name != "xla-jax0.0.1-jaxlib0.0.1"
    assert cold["hits"] == 0 and cold["stored"] == 0 and cold["compiled"] > 0
    # The slot planner, whole, and the five small nets: direction, splits, joins, ranker x2.
    stored = sorted(p.name.rsplit("-", 1)[0] for p in (folder / "jdraw-programs").iterdir())
    assert stored == [
        "net-_headings", "net-_join_logits", "net-_logits", "net-_pair_net", "net-_split_logits",
        "stream",
    ]  # fmt: skip
    # The model, the ranker, the splitter and the reading-direction net, shapes only.
    assert len(list((cache / "modules").glob("*.pkl"))) == 4
    warm = _run(_PLAN, cache)
    assert warm["stored"] == 6 and warm["compiled"] == 0 and warm["dir"] == cold["dir"]
    off = _run(_PLAN, "off")
    assert off["dir"] is None and off["hits"] == 0 and off["stored"] == 0
    assert cold["strokes"] == warm["strokes"] == off["strokes"]
    assert not cold["warnings"] and not warm["warnings"]


def test_unwritable_cache_warns_once_and_plans(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("a file where the cache folder would go")
    code = """
import json, warnings
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    from jdraw import compile_cache
    first, second = compile_cache.enable(), compile_cache.enable()
    import jax, jax.numpy as jnp
    y = int(jax.jit(lambda x: x * 2 + 1)(jnp.int32(20)))
print(json.dumps({"dir": first or second, "y": y, "warnings": [str(x.message) for x in w
      if "compilation cache" in str(x.message)]}))
"""
    out = _run(code, blocker / "cache")
    assert out["dir"] is None and out["y"] == 41
    assert len(out["warnings"]) == 1 and "JDRAW_CACHE_DIR" in out["warnings"][0]


def test_module_shapes_are_kept_and_checked(monkeypatch, tmp_path):
    """bundle.shapes: traced once, then read back; a bad file or another key traces again."""
    from flax import nnx

    from jdraw.model import bundle

    monkeypatch.setenv(compile_cache.ENV, str(tmp_path))
    calls = []

    def build(width=3):
        calls.append(width)
        return nnx.Linear(2, width, rngs=nnx.Rngs(0))

    first = bundle.shapes(build, ["test", 3])
    again = bundle.shapes(build, ["test", 3])
    assert calls == [3] and again.kernel.shape == first.kernel.shape == (2, 3)
    (kept,) = (tmp_path / "modules").glob("*.pkl")
    kept.write_bytes(b"not a pickle")
    assert bundle.shapes(build, ["test", 3]).kernel.shape == (2, 3) and calls == [3, 3]
    assert bundle.shapes(lambda: build(4), ["test", 4]).kernel.shape == (2, 4)
    assert len(list((tmp_path / "modules").glob("*.pkl"))) == 2
    monkeypatch.setenv(compile_cache.ENV, "off")
    bundle.shapes(build, ["test", 3])
    assert calls == [3, 3, 4, 3]
