"""``jdraw.plan``: batched planning with the learned model."""

from __future__ import annotations

import functools
import os
import pathlib

import jax
import jax.numpy as jnp
import numpy as np
from flax import nnx

from jdraw import compile_cache, geometry, state, validate
from jdraw.model import bundle, checkpoints
from jdraw.planner import executables, global_only, slots
from jdraw.planner import loop as planner
from jdraw.plans import Plan

CANVAS = geometry.CANVAS
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


def _folder(checkpoint) -> pathlib.Path | None:
    """The bundle or workdir folder ``checkpoint`` names; ``None``: the default bundle."""
    return _default_bundle() if checkpoint is None else pathlib.Path(checkpoint)


@functools.lru_cache(maxsize=8)
def _load(path: str | None, mtime: float):
    del mtime  # part of the cache key only
    if path is None:
        from ml_collections import ConfigDict

        from jdraw.model import network as M

        mdl = M.build(ConfigDict(bundle.DEFAULT_MODEL), seed=0)
        mdl.eval()
        return mdl
    mdl, _ = bundle.load(path)
    return mdl


@functools.lru_cache(maxsize=4)
def _load_workdir(path: str, step: int):
    del step  # part of the cache key only: a newer checkpoint is read again
    return checkpoints.restore(path).model


def load_model(checkpoint=None):
    """The model ``plan`` uses: a bundle folder, a training workdir, the bundled default.

    A training workdir is read, not written: its latest Orbax checkpoint is
    restored in memory. With no argument and no bundled checkpoint, a seeded
    random model.
    """
    if isinstance(checkpoint, nnx.Module):
        return checkpoint
    path = _folder(checkpoint)
    if path is None:
        return _load(None, 0.0)
    meta = path / "bundle.json"
    if not meta.exists() and (path / "config.json").exists():
        step = checkpoints.latest_step(path)
        return _load_workdir(str(path.resolve()), -1 if step is None else step)
    return _load(str(path.resolve()), meta.stat().st_mtime if meta.exists() else 0.0)


def planner_settings(checkpoint=None) -> dict:
    """How ``plan`` uses a checkpoint: its bundle's ``planner`` section, or its run's config's.

    Keys: ``join`` (:mod:`jdraw.planner.joins`; default False). A model passed
    as a module has none.
    """
    if isinstance(checkpoint, nnx.Module):
        return {}
    path = _folder(checkpoint)
    if path is None:
        return {}
    for name in ("bundle.json", "config.json"):
        if (path / name).exists():  # read once per version of the file
            return dict(_settings(str((path / name).resolve()), (path / name).stat().st_mtime))
    return {}


@functools.lru_cache(maxsize=16)
def _settings(file: str, mtime: float) -> tuple:
    del mtime  # part of the cache key only
    path = pathlib.Path(file)
    if path.name == "bundle.json":
        section = bundle.read_meta(path.parent).get("planner") or {}
    else:
        section = checkpoints.read_config(path.parent).get("planner")
        section = section.to_dict() if section is not None else {}
    return tuple(sorted(section.items()))


@functools.lru_cache(maxsize=16)
def _planner(graphdef, limits: planner.Limits, local_encoding: str, kind: str = "two_scale"):
    policy = planner.model_policy(local_encoding)

    def one(st, target, labels):
        model = nnx.merge(graphdef, st)
        if kind == "global_only":
            return global_only.run(model, target, limits.max_steps)
        return planner.run(policy, model, (), target, labels, limits)

    def many(st, targets, labels):
        _TRACES["plan"] += 1
        return jax.vmap(one, in_axes=(None, 0, 0))(st, targets, labels)

    return jax.jit(many)


def load_ranker(checkpoint=None):
    """The stroke ranker stored beside a bundle's model, or ``None``."""
    if isinstance(checkpoint, nnx.Module):
        return None
    path = _folder(checkpoint)
    return _load_ranker(str(path.resolve())) if path is not None else None


@functools.lru_cache(maxsize=8)
def _load_ranker(path: str):
    from jdraw.planner import ranker

    return ranker.load(path)


def load_splitter(checkpoint=None):
    """The stroke splitter beside a bundle's model (:mod:`jdraw.planner.splits`), or ``None``."""
    if isinstance(checkpoint, nnx.Module):
        return None
    path = _folder(checkpoint)
    return _splitter_in(path) if path is not None else None


def splitter_for(checkpoint=None, split: bool | str | os.PathLike | None = None):
    """The splitter :func:`plan` runs with ``split=`` (a folder's, none, the checkpoint's)."""
    if isinstance(split, (str, os.PathLike)):
        sp = _splitter_in(split)
        if sp is None:
            raise ValueError(f"split={str(split)!r}: no splitter.json there")
        return sp
    sp = load_splitter(checkpoint) if split is not False else None
    if split is True and sp is None:
        raise ValueError("split=True needs a checkpoint with a stroke splitter; this one has none")
    return sp


def _splitter_in(folder) -> object | None:
    meta = pathlib.Path(folder) / "splitter.json"
    mtime = meta.stat().st_mtime if meta.exists() else 0.0
    return _load_splitter(str(pathlib.Path(folder).resolve()), mtime)


@functools.lru_cache(maxsize=8)
def _load_splitter(path: str, mtime: float):
    from jdraw.planner import splits

    del mtime  # part of the cache key only: a splitter written again is read again
    return splits.load(path)


def _bucket(n: int) -> int:
    """Queue length for ``n`` images: the next power of two, so few shapes compile."""
    return 1 << max(0, n - 1).bit_length()


@functools.lru_cache(maxsize=16)
def _streamer(graphdef, limits, local_encoding: str, width: int, global_batch: int, devices):
    """The jitted slot planner, each device streaming its own part of the queue."""
    policy = planner.model_policy(local_encoding)
    mesh = jax.sharding.Mesh(np.asarray(devices), ("d",))
    P = jax.sharding.PartitionSpec

    def per_device(st, targets, labels, count):
        model = nnx.merge(graphdef, st)
        out = slots.stream(
            policy, model, (), targets, labels, count[0], limits, width, global_batch
        )
        return out._replace(**{f: getattr(out, f)[None] for f in out._fields[3:]})

    def many(st, targets, labels, counts):
        _TRACES["plan"] += 1
        return jax.shard_map(
            per_device,
            mesh=mesh,
            in_specs=(P(), P("d"), P("d"), P("d")),
            out_specs=P("d"),
            check_vma=False,  # no collectives: each device runs alone
        )(st, targets, labels, counts)

    return jax.jit(many)


def stream_plan(
    model, targets, labels, limits, local_encoding="window", width=64, global_batch=4, devices=None
) -> slots.Stream:
    """The slot planner on ``targets [B, H, W]``: a :class:`slots.Stream`, one row per image.

    Each device takes a contiguous part of the images, padded to a
    power-of-two queue, and streams it through ``width`` slots.
    """
    devices = tuple(devices or jax.local_devices())  # this process's: plans are host-local
    d = len(devices)
    b = len(targets)
    per = -(-b // d)
    qd = _bucket(per)
    tq = np.zeros((d * qd, *targets.shape[1:]), bool)
    lq = np.zeros((d * qd, *targets.shape[1:]), np.int32)
    counts = np.zeros(d, np.int32)
    keep = []
    for j in range(d):
        part = slice(j * per, min(b, (j + 1) * per))
        m = max(0, part.stop - part.start)
        tq[j * qd : j * qd + m] = targets[part]
        lq[j * qd : j * qd + m] = labels[part]
        counts[j] = m
        keep.extend(range(j * qd, j * qd + m))
    graphdef, st = nnx.split(model)
    fn = _streamer(graphdef, limits, local_encoding, width, global_batch, devices)
    static = (graphdef, limits, local_encoding, width, global_batch)
    args = (st, tq, lq, counts)
    out = jax.device_get(executables.run("stream", fn, static, args, devices))
    keep = np.asarray(keep, int)
    return out._replace(
        actions=out.actions[keep], length=out.length[keep], truncated=out.truncated[keep]
    )


def plan(
    images,
    *,
    checkpoint=None,
    max_steps: int | None = None,
    local_encoding: str = "window",
    order: str = "auto",
    canonicalise: bool = True,
    batch_size: int = 64,
    global_batch: int = 4,
    loop: str = "slots",
    devices=None,
    join: bool | None = None,
    split: bool | str | os.PathLike | None = None,
    direction: str = "ltr",
    retrace: int | None = None,
) -> Plan:
    """Plans how to draw each image.

    Args:
      images: ``[B, 100, 100]`` or ``[100, 100]``; nonzero is ink: lines of
        any rasteriser, 1-4 pixels wide, with 1-pixel breaks allowed. bool,
        uint8 or float.
      checkpoint: a bundle folder (see :func:`jdraw.model.checkpoints`), a training
        workdir, a ``DrawModel``, or ``None`` for the bundled model.
      max_steps: action rows per image (default 1024); a plan cut by it is
        marked ``truncated``.
      local_encoding: ``"window"`` (default) or ``"full"``; same actions,
        ``"full"`` is the slow reference.
      order: ``"auto"`` (the checkpoint's stroke ranker if it has one, else
        as traced), ``"model"`` (as the planner traced them), ``"ranker"``
        (the learned order and directions, :mod:`jdraw.planner.ranker`) or ``"xy"``
        (sorted by the start's x + y, a reference rule).
      canonicalise: first map the ink to canonical 1-pixel lines
        (:func:`jdraw.images.canonical.canonicalise`: thin thick pens, drop
        staircase corners, fill 1-pixel breaks). The plan then inks pixels
        within 1 pixel of the input's ink; lines already canonical, like
        KanjiVG as jdraw draws it, are left as they are.
      batch_size: images in flight at once (per device); any number of
        images streams through them in one compiled loop.
      global_batch: slots that the global model starts together.
      loop: ``"slots"`` (default; see :mod:`jdraw.planner.slots`) or ``"vmap"`` (the
        old loop, every image waiting for the batch's longest stroke); same
        actions.
      devices: the JAX devices the slot batch is spread over (default all of this process's).
      join: join a stroke to the one that goes on from its end through a
        junction (:mod:`jdraw.planner.joins`); ``None``: as the checkpoint says
        (:func:`planner_settings`; the paper's model does not).
      split: cut strokes at corners where one person's stroke ends and the
        next begins, and join ends that are one line, as the checkpoint's
        learned splitter says (:mod:`jdraw.planner.splits`); ``None``: if the
        checkpoint has one; or a folder holding another splitter to use.
        ``True`` with a checkpoint that has none is an error.
      direction: ``"ltr"`` or ``"rtl"``: the reading direction the ranker
        orders strokes in (``"rtl"``: as for the mirrored image, see
        :func:`jdraw.planner.ranker.reorder`); the strokes traced are the same.
      retrace: moves back over a stroke's own line the splitter's joins may go, as a
        cursive writer goes back up a stem (``None``: the splitter's own, 0 for the
        default; joined where its join net says). :func:`jdraw.plan_image` asks for
        :data:`jdraw.planner.splits.JOINED_RETRACE` in joined-up writing.

    Returns:
      A :class:`jdraw.Plan` with one entry per image.
    """
    from jdraw.images import canonical
    from jdraw.planner import ranker

    compile_cache.enable()
    if order not in ("auto", *ranker.ORDERS):
        raise ValueError(f"order must be 'auto' or one of {ranker.ORDERS}, got {order!r}")
    targets = drawn = as_targets(images)
    if canonicalise:
        targets = np.stack([canonical.canonicalise(t) for t in targets])
    max_steps = validate.positive_int("max_steps", max_steps, optional=True)
    limits = planner.Limits(max_steps=max_steps or planner.Limits.max_steps)
    validate.choice("local_encoding", local_encoding, ("window", "full"))
    validate.choice("loop", loop, ("slots", "vmap"))
    validate.choice("direction", direction, ("ltr", "rtl"))
    batch_size = validate.positive_int("batch_size", batch_size)
    global_batch = validate.positive_int("global_batch", global_batch)
    retrace = validate.positive_int("retrace", retrace, optional=True, zero=True)
    model = load_model(validate.checkpoint(checkpoint))
    sp = splitter_for(checkpoint, split)
    if retrace and sp is None:
        raise ValueError("retrace= joins through the stroke splitter; this plan has none")
    labels = np.stack([state.component_labels(t) for t in targets])
    kind = getattr(model, "kind", "two_scale")
    if loop == "slots" and kind != "global_only":  # the global-only ablation keeps vmap
        out = stream_plan(
            model, targets, labels, limits, local_encoding, batch_size, global_batch, devices
        )
    else:
        graphdef, st = nnx.split(model)
        fn = _planner(graphdef, limits, local_encoding, kind)
        out = fn(st, jnp.asarray(targets), jnp.asarray(labels))
    # Truncated means exactly "ink the actions do not draw remains" (of the ink planned,
    # after canonicalising): judged from the rendered actions, not the planner's
    # `visited` (a jump marks its pixel visited before the dot is drawn).
    result = Plan.from_actions(out.actions, out.length, targets=targets)
    if join is None:
        join = bool(planner_settings(checkpoint).get("join", False))
    if join:
        from jdraw.planner import joins

        result = joins.join_plan(result, targets, max_rows=limits.max_steps)
    if sp is not None:
        from jdraw.planner import splits

        result = splits.edit_plan(
            result, sp, targets, max_rows=limits.max_steps, drawn=drawn, retrace=retrace
        )
    rk = load_ranker(checkpoint) if order in ("auto", "ranker") else None
    if order == "auto":
        order = "ranker" if rk is not None else "model"
    return ranker.reorder(result, order, rk, max_rows=limits.max_steps, mirror=direction == "rtl")


@functools.lru_cache(maxsize=4)
def _replayer(limits: planner.Limits):
    policy = planner.replay_policy()

    def one(starts, moves, n_moves, target, labels):
        pst = (starts, moves, n_moves, jnp.int32(0), jnp.int32(0))
        return planner.run(policy, None, pst, target, labels, limits)

    return jax.jit(jax.vmap(one))


def replay(demos, *, max_steps: int | None = None) -> Plan:
    """Runs demonstrations (:class:`jdraw.data.demos.Demo`) through the planner's state machine.

    The planner's own loop, masks and renderer, with the demonstration's
    moves in place of the model's: ``render(replay(d)) == target`` is the
    pipeline's losslessness check.
    """
    from jdraw.data import demos as D

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
    return Plan.from_actions(out.actions, out.length, truncated=out.truncated)
