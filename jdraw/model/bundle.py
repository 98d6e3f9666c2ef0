"""Inference bundles: parameters, model config and a format version.

A bundle is a folder with ``bundle.json`` (format version, model config,
provenance) and ``params.npz`` (every array of the model's NNX state, keyed
by its path). It needs neither Orbax nor the training config to load.
"""

from __future__ import annotations

import json
import os
import pathlib
import zipfile

import numpy as np
from flax import nnx, traverse_util

FORMAT = "jdraw-bundle"
FORMAT_VERSION = 1
DEFAULT_BUNDLE = pathlib.Path(__file__).parent.parent / "checkpoints" / "default"  # ours
PAPER_BUNDLE = pathlib.Path(__file__).parent.parent / "checkpoints" / "paper"  # Table I, row 1
TRAINING_CONFIG = "training_config.json"
DEFAULT_MODEL = {"hidden": 256, "core": "lstm", "extraction": "late"}


class BundleError(ValueError):
    """A bundle that is missing, corrupt or does not fit this code."""


def _source_stamp() -> list:
    """Size and modification time of every ``.py`` file of the package: changes with the code."""
    root = pathlib.Path(__file__).resolve().parents[1]
    return sorted(
        (str(f.relative_to(root)), st.st_size, st.st_mtime_ns)
        for f in root.rglob("*.py")
        for st in [f.stat()]
    )


def shapes(build, key) -> nnx.Module:
    """``nnx.eval_shape(build)``: the module ``build()`` makes, its arrays as shapes only.

    Tracing a model's constructor takes a few tenths of a second, on every
    start (issue 25). The abstract module is therefore kept, pickled, in
    jdraw's cache folder (:func:`jdraw.compile_cache.cache_root`, the same
    trust as JAX's cache of executables beside it), under a name made of
    ``key`` (what ``build`` depends on, JSON), the flax and jax versions and
    the package's source files. Any failure to read or write it falls back to
    tracing; ``JDRAW_CACHE_DIR=off`` turns it off.
    """
    import hashlib
    import pickle

    from jdraw import compile_cache

    root = compile_cache.cache_root()
    if root is None:
        return nnx.eval_shape(build)
    import flax
    import jax

    tag = json.dumps(
        [key, flax.__version__, jax.__version__, _source_stamp()], sort_keys=True, default=str
    )
    path = root / "modules" / f"{hashlib.sha256(tag.encode()).hexdigest()[:32]}.pkl"
    try:
        with open(path, "rb") as f:
            return pickle.load(f)
    except Exception:  # noqa: BLE001 - missing, partial or from other code: trace it again
        pass
    mdl = nnx.eval_shape(build)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_bytes(pickle.dumps(mdl))
        tmp.replace(path)  # atomic: a reader never sees half a file
    except Exception:  # noqa: BLE001 - a cache that cannot be written only costs time
        pass
    return mdl


def state_arrays(model) -> dict[str, np.ndarray]:
    """Every array of ``model``'s state (params and batch stats), keyed by ``a/b/0/c`` path."""
    flat = traverse_util.flatten_dict(nnx.to_pure_dict(nnx.state(model)))
    return {"/".join(map(str, k)): np.asarray(v) for k, v in flat.items()}


def write(
    model,
    model_config: dict,
    out_dir,
    provenance: dict | None = None,
    training_config: dict | None = None,
    planner: dict | None = None,
) -> pathlib.Path:
    """Writes ``model`` as a bundle in ``out_dir``.

    ``training_config`` (the run's whole config) goes to ``training_config.json``
    beside it, for the record; loading does not need it. ``planner`` (settings
    of how ``jdraw.plan`` uses the model, e.g. ``{"join": True}``, see
    :func:`jdraw.planner.plan.planner_settings`) goes into ``bundle.json``.
    """
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    if training_config is not None:
        (out / TRAINING_CONFIG).write_text(json.dumps(training_config, indent=2) + "\n")
    np.savez(out / "params.npz", **state_arrays(model))
    meta = {
        "format": FORMAT,
        "format_version": FORMAT_VERSION,
        "model": dict(model_config),
        "provenance": provenance or {},
    }
    if planner:
        meta["planner"] = dict(planner)
    (out / "bundle.json").write_text(json.dumps(meta, indent=2) + "\n")
    return out


def read_meta(bundle_dir) -> dict:
    path = pathlib.Path(bundle_dir) / "bundle.json"
    if not path.exists():
        raise BundleError(
            f"{path}: no bundle.json here; is this a jdraw bundle (see jdraw.model.checkpoints)?"
        )
    try:
        meta = json.loads(path.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise BundleError(f"{path}: not valid JSON ({e})") from e
    if meta.get("format") != FORMAT:
        raise BundleError(f"{path}: format is {meta.get('format')!r}, expected {FORMAT!r}")
    if meta.get("format_version") != FORMAT_VERSION:
        raise BundleError(
            f"{path}: format_version {meta.get('format_version')!r}; "
            f"this jdraw reads {FORMAT_VERSION}"
        )
    if not isinstance(meta.get("model"), dict):
        raise BundleError(f"{path}: no 'model' config")
    return meta


def _checked_array(where, key: str, array: np.ndarray, like) -> np.ndarray:
    """A bundle's array ``key`` checked against the model variable ``like``.

    Raises:
      jdraw.model.bundle.BundleError: wrong shape or dtype, or NaN/inf values.
    """
    want_dtype = np.dtype(like.dtype)
    if array.shape != tuple(like.shape):
        raise BundleError(f"{where}: {key} has shape {array.shape}, the model needs {like.shape}")
    if array.dtype != want_dtype:
        raise BundleError(f"{where}: {key} has dtype {array.dtype}, the model needs {want_dtype}")
    if np.issubdtype(array.dtype, np.floating) and not np.all(np.isfinite(array)):
        raise BundleError(f"{where}: {key} contains NaN or inf; the weights are corrupt")
    return array


def load(bundle_dir):
    """Builds the model a bundle describes and fills in its arrays.

    Returns:
      ``(model in eval mode, model config dict)``.

    Raises:
      BundleError: naming the file, if the bundle is missing, corrupt, or its
        arrays do not match the model its config describes.
    """
    from ml_collections import ConfigDict

    from jdraw.model import network as M

    bundle_dir = pathlib.Path(bundle_dir)
    meta = read_meta(bundle_dir)
    try:
        # Shapes only: the weights come from the file, so no initialiser runs (each
        # would be one more small XLA compilation on a fresh machine).
        mdl = shapes(lambda: M.build(ConfigDict(meta["model"])), ["model", meta["model"]])
    except (ValueError, TypeError, KeyError) as e:
        raise BundleError(f"{bundle_dir / 'bundle.json'}: bad model config ({e})") from e
    path = bundle_dir / "params.npz"
    try:
        with np.load(path) as z:
            arrays = {k: z[k] for k in z.files}
    except FileNotFoundError as e:
        raise BundleError(f"{path}: missing") from e
    except (zipfile.BadZipFile, ValueError, OSError, EOFError) as e:
        raise BundleError(f"{path}: corrupt ({e})") from e
    flat = traverse_util.flatten_dict(nnx.to_pure_dict(nnx.state(mdl)))
    expected = {"/".join(map(str, k)): v for k, v in flat.items()}
    if set(arrays) != set(expected):
        miss, extra = sorted(set(expected) - set(arrays)), sorted(set(arrays) - set(expected))
        raise BundleError(
            f"{path}: arrays do not match the model (missing {miss[:3]}, unexpected {extra[:3]})"
        )
    for k, v in expected.items():
        arrays[k] = _checked_array(path, k, arrays[k], v)
    state = nnx.state(mdl)
    # Integer path entries (list indices) come back as strings; replace_by_pure_dict maps them.
    nnx.replace_by_pure_dict(
        state, traverse_util.unflatten_dict({tuple(k.split("/")): a for k, a in arrays.items()})
    )
    nnx.update(mdl, state)
    mdl.eval()
    return mdl, meta["model"]


def fill(model, arrays: dict[str, np.ndarray], *, partial: bool = False) -> int:
    """Sets ``model``'s state from arrays keyed as :func:`state_arrays` keys them.

    With ``partial``, only the arrays the model has with the same shape are
    set (others are skipped); otherwise every array must match. Returns the
    number of arrays set.

    Raises:
      BundleError: when not ``partial`` and the arrays do not fit the model.
    """
    flat = traverse_util.flatten_dict(nnx.to_pure_dict(nnx.state(model)))
    expected = {"/".join(map(str, k)): v for k, v in flat.items()}  # arrays or shapes only
    use = {k: a for k, a in arrays.items() if k in expected and a.shape == expected[k].shape}
    if not partial and len(use) != len(expected):
        bad = sorted(set(expected) - set(use))
        raise BundleError(f"arrays do not fit the model: {bad[:3]} missing or of the wrong shape")
    state = nnx.state(model)
    pure = traverse_util.flatten_dict(nnx.to_pure_dict(state))
    for k in pure:
        key = "/".join(map(str, k))
        if key in use:
            pure[k] = use[key]
    nnx.replace_by_pure_dict(state, traverse_util.unflatten_dict(pure))
    nnx.update(model, state)
    return len(use)


def save_net(net, out_dir, stem: str, meta: dict) -> pathlib.Path:
    """Writes a small net stored beside a bundle's model: ``{stem}.npz`` and ``{stem}.json``.

    ``meta`` is what :func:`load_net` needs to build the net again (its sizes)
    and its provenance.
    """
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(out / f"{stem}.npz", **state_arrays(net))  # an ensemble is mostly zeros
    (out / f"{stem}.json").write_text(json.dumps(meta, indent=2) + "\n")
    return out


def load_net(bundle_dir, stem: str, build):
    """The net ``{stem}.npz`` in a bundle folder, or ``None`` if it has no ``{stem}.json``.

    ``build(meta)`` makes the empty net from the json (and may raise
    :class:`BundleError`); its arrays are then filled from the npz.
    """
    d = pathlib.Path(bundle_dir)
    if not (d / f"{stem}.json").exists():
        return None
    meta = json.loads((d / f"{stem}.json").read_text())
    # Shapes only: the arrays come from the npz.
    model = shapes(lambda: build(meta), ["net", stem, build.__module__, build.__qualname__, meta])
    try:
        with np.load(d / f"{stem}.npz") as z:
            arrays = {k: z[k] for k in z.files}
    except (OSError, ValueError) as e:
        raise BundleError(f"{d / f'{stem}.npz'}: unreadable ({e})") from e
    try:
        fill(model, arrays)
    except BundleError as e:
        raise BundleError(f"{d / f'{stem}.npz'}: {e}") from e
    return model
