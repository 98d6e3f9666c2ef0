"""``jdraw.plan``: batched planning with the learned model."""

from __future__ import annotations

import functools
import os
import pathlib

import jax
import jax.numpy as jnp
import numpy as np
from flax import nnx

from jdraw import bundle, planner, raster, state, validate
from jdraw.types import Plan, strokes_from_actions

CANVAS = state.CANVAS
_TRACES = {"plan": 0}  # counts traces of the planning function (tests check it)


def as_targets(images) -> np.ndarray:
    """Validates ``images`` and returns ``bool [B, 100, 100]`` ink masks.

    Accepts ``[B, 100, 100]``, ``[100, 100]`` or a trailing channel axis of
    size 1; bool, integer or float; nonzero is ink.

    Raises:
      ValueError: naming the problem (rank, shape, channels, NaN/inf, dtype).
    """
    return validate.canvas_images(images)


def _default_bundle() -> pathlib.Path | None:
    env = os.environ.get("JDRAW_CHECKPOINT")
    if env:
        return pathlib.Path(env)
    return bundle.DEFAULT_BUNDLE if (bundle.DEFAULT_BUNDLE / "bundle.json").exists() else None


@functools.lru_cache(maxsize=8)
def _load(path: str | None, mtime: float):
    del mtime  # part of the cache key only
    if path is None:
        from ml_collections import ConfigDict

        from jdraw import model as M

        mdl = M.build(ConfigDict(bundle.DEFAULT_MODEL), seed=0)
        mdl.eval()
        return mdl
    mdl, _ = bundle.load(path)
    return mdl


def load_model(checkpoint=None):
    """The model ``plan`` uses: a bundle folder, a training workdir, the bundled default.

    With no argument and no bundled checkpoint, a seeded random model.
    """
    if checkpoint is None:
        path = _default_bundle()
    elif isinstance(checkpoint, nnx.Module):
        return checkpoint
    else:
        path = pathlib.Path(checkpoint)
        if not (path / "bundle.json").exists() and path.exists():
            from jdraw.export import bundle_for_workdir

            path = bundle_for_workdir(path)
    if path is None:
        return _load(None, 0.0)
    meta = pathlib.Path(path) / "bundle.json"
    return _load(str(pathlib.Path(path).resolve()), meta.stat().st_mtime if meta.exists() else 0.0)


@functools.lru_cache(maxsize=16)
def _planner(graphdef, limits: planner.Limits, local_encoding: str, kind: str = "two_scale"):
    policy = planner.model_policy(local_encoding)

    def one(st, target, labels):
        model = nnx.merge(graphdef, st)
        if kind == "global_only":
            from jdraw import global_only

            return global_only.run(model, target, limits.max_steps)
        return planner.run(policy, model, (), target, labels, limits)

    def many(st, targets, labels):
        _TRACES["plan"] += 1
        return jax.vmap(one, in_axes=(None, 0, 0))(st, targets, labels)

    return jax.jit(many)


def plan(
    images, *, checkpoint=None, max_steps: int | None = None, local_encoding: str = "window"
) -> Plan:
    """Plans how to draw each image.

    Args:
      images: ``[B, 100, 100]`` or ``[100, 100]``; nonzero is ink (1-pixel
        lines, like a skeleton). bool, uint8 or float.
      checkpoint: a bundle folder (see :func:`jdraw.export`), a training
        workdir, a ``DrawModel``, or ``None`` for the bundled model.
      max_steps: action rows per image (default 1024); a plan cut by it is
        marked ``truncated``.
      local_encoding: ``"window"`` (default) or ``"full"``; same actions,
        ``"full"`` is the slow reference.

    Returns:
      A :class:`jdraw.Plan` with one entry per image.
    """
    targets = as_targets(images)
    max_steps = validate.positive_int("max_steps", max_steps, optional=True)
    limits = planner.Limits(max_steps=max_steps or planner.Limits.max_steps)
    validate.choice("local_encoding", local_encoding, ("window", "full"))
    model = load_model(validate.checkpoint(checkpoint))
    graphdef, st = nnx.split(model)
    labels = np.stack([state.component_labels(t) for t in targets])
    fn = _planner(graphdef, limits, local_encoding, getattr(model, "kind", "two_scale"))
    out = fn(st, jnp.asarray(targets), jnp.asarray(labels))
    actions = np.asarray(out.actions)
    lengths = np.asarray(out.length)
    strokes = [strokes_from_actions(a, n) for a, n in zip(actions, lengths)]
    # Truncated means exactly "ink the actions do not draw remains": judged from the
    # rendered actions, not the planner's `visited` (a jump marks its pixel visited
    # before the dot is drawn).
    truncated = np.array(
        [(t & ~raster.render_strokes(s, t.shape)).any() for t, s in zip(targets, strokes)], bool
    )
    return Plan(strokes=strokes, actions=actions, lengths=lengths, truncated=truncated)


@functools.lru_cache(maxsize=4)
def _replayer(limits: planner.Limits):
    policy = planner.replay_policy()

    def one(starts, moves, n_moves, target, labels):
        pst = (starts, moves, n_moves, jnp.int32(0), jnp.int32(0))
        return planner.run(policy, None, pst, target, labels, limits)

    return jax.jit(jax.vmap(one))


def replay(demos, *, max_steps: int | None = None) -> Plan:
    """Runs demonstrations (:class:`jdraw.demo.Demo`) through the planner's state machine.

    The planner's own loop, masks and renderer, with the demonstration's
    moves in place of the model's: ``render(replay(d)) == target`` is the
    pipeline's losslessness check.
    """
    from jdraw import demo as D

    demos = list(demos)
    limits = planner.Limits(
        max_steps=int(max_steps or 2048), max_stroke_steps=512, max_idle_steps=512
    )
    s_max = max(len(d.strokes) for d in demos)
    m_max = max(max(len(s) for s in d.strokes) for d in demos)
    starts, moves, n_moves = D.replay_arrays(demos, s_max, m_max)
    targets = np.stack([d.target for d in demos])
    labels = np.stack([state.component_labels(t) for t in targets])
    out = _replayer(limits)(starts, moves, n_moves, targets, labels)
    actions, lengths = np.asarray(out.actions), np.asarray(out.length)
    strokes = [strokes_from_actions(a, n) for a, n in zip(actions, lengths)]
    return Plan(
        strokes=strokes, actions=actions, lengths=lengths, truncated=np.asarray(out.truncated)
    )
