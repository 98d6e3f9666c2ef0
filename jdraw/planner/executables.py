"""The slot planner's compiled program kept on disk whole, so a warm start skips tracing too.

JAX's persistent cache (:mod:`jdraw.compile_cache`) skips XLA's compilation,
but every process still traces and lowers the planner's loop to find the
cache key: seconds of Python on a 2-core CPU. Here the compiled executable
itself is stored (``jax.experimental.serialize_executable``) under a key made
of everything the program depends on that is known before tracing: the jax,
jaxlib and backend versions, the devices, ``XLA_FLAGS``, a hash of jdraw's
own source files, the model's graph (its structure and settings), the
planner's static settings and the shapes and dtypes of the arguments. A
file that cannot be read back (another version, corrupt) is ignored and
replaced; one that cannot be written is skipped.
"""

from __future__ import annotations

import functools
import hashlib
import os
import pathlib
import pickle
import re
import tempfile
import threading
import time

import jax
from jax import monitoring

from jdraw import compile_cache

LOAD_EVENT = "/jdraw/program_store/load_duration"
_PACKAGE = pathlib.Path(__file__).resolve().parents[1]


@functools.lru_cache(maxsize=1)
def source_hash() -> str:
    """sha256 of every ``.py`` file of the jdraw package (path and contents)."""
    h = hashlib.sha256()
    for f in sorted(_PACKAGE.rglob("*.py")):
        h.update(str(f.relative_to(_PACKAGE)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def _describe(tree) -> str:
    leaves, treedef = jax.tree_util.tree_flatten(tree)
    shapes = [(tuple(x.shape), str(x.dtype)) for x in leaves]
    return f"{treedef}|{shapes}"


def key(name: str, static: tuple, args: tuple, devices) -> str:
    """The file key of program ``name`` for ``static`` settings and ``args``' shapes."""
    import jaxlib

    backend = jax.extend.backend.get_backend()
    parts = [
        name,
        jax.__version__,
        jaxlib.__version__,
        backend.platform,
        backend.platform_version,
        repr([(d.platform, d.device_kind, d.id) for d in devices]),
        os.environ.get("XLA_FLAGS", ""),
        str(jax.config.jax_enable_x64),
        source_hash(),
        re.sub(r" at 0x[0-9a-f]+", "", repr(static)),  # object addresses change per process
        _describe(args),
    ]
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()[:32]


def path_of(name: str, static: tuple, args: tuple, devices) -> pathlib.Path | None:
    """Where program ``name`` for these settings and argument shapes is stored (cache on)."""
    folder = compile_cache.enable()
    if folder is None:
        return None
    return pathlib.Path(folder) / "jdraw-programs" / f"{name}-{key(name, static, args, devices)}"


def forget(name: str, static: tuple, args: tuple, devices) -> None:
    """Deletes a stored program that failed to run (it is compiled again next time)."""
    path = path_of(name, static, args, devices)
    if path is not None:
        path.unlink(missing_ok=True)


def compiled(name: str, fn, static: tuple, args: tuple, devices):
    """``fn`` (a ``jax.jit`` function) compiled for ``args``: from disk, or compiled and stored.

    Returns ``fn`` itself when the compilation cache is off.
    """
    path = path_of(name, static, args, devices)
    if path is None:
        return fn
    from jax.experimental import serialize_executable as se

    if path.exists():
        t0 = time.perf_counter()
        try:
            payload, in_tree, out_tree = pickle.loads(path.read_bytes())
            exe = se.deserialize_and_load(payload, in_tree, out_tree)
        except Exception:  # noqa: BLE001 - any unreadable entry is only a cache miss
            pass
        else:  # counted like JAX's own cache reads (bench/first_plan.py listens)
            monitoring.record_event_duration_secs(LOAD_EVENT, time.perf_counter() - t0)
            return exe
    with compile_cache.bypassed():
        exe = fn.lower(*args).compile()
    try:
        blob = pickle.dumps(se.serialize(exe))
        path.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path.parent, delete=False) as f:
            f.write(blob)
        os.replace(f.name, path)
    except Exception:  # noqa: BLE001 - not storable or not writable: plan without storing
        pass
    return exe


_MEMO: dict = {}  # (jitted function, key) -> its compiled program (or the function itself)
LOADING = threading.RLock()  # planner threads (jdraw.tiling.tiles.Pipeline) load each once


def run(name: str, fn, static, args, devices):
    """``fn(*args)`` by its compiled program: kept in memory, else from the store on disk.

    A stored program that does not run (a broken or foreign file) is dropped
    and the jitted function used from then on.
    """
    k = (fn, key(name, static, args, devices))
    if k not in _MEMO:
        with LOADING:
            if k not in _MEMO:
                _MEMO[k] = compiled(name, fn, static, args, devices)
    exe = _MEMO[k]
    try:
        return exe(*args)
    except jax.errors.JaxRuntimeError:
        if exe is fn:
            raise
        forget(name, static, args, devices)
        _MEMO[k] = fn
        return fn(*args)
