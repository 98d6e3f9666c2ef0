"""Training both models, resumable from Orbax checkpoints.

The functional loop of the Flax NNX performance guide: ``nnx.split`` once, a
plain ``jax.jit`` step that merges inside and returns the new state, buffers
donated. Data are a pure function of ``(seed, step)``, so a resumed run sees
the same batches as an uninterrupted one. Batches are split over a
``jax.sharding`` mesh of all devices along the batch axes.
"""

from __future__ import annotations

import json
import pathlib
import queue
import signal
import threading
import time

import jax
import jax.numpy as jnp
import numpy as np
import optax
import orbax.checkpoint as ocp
from flax import nnx
from jax.sharding import Mesh, NamedSharding
from jax.sharding import PartitionSpec as P

from jdraw import state as S
from jdraw.data import batches, kanji
from jdraw.evaluation import metrics
from jdraw.model import network as M

# ----------------------------------------------------------------------------
# Losses.


def local_loss(model: M.DrawModel, b: dict):
    """Mean over valid steps of the move and touch cross-entropies (eqs. 5-7)."""
    W = model.window

    def stroke_windows(target, labels, visited, pts, n_moves):
        def body(visited, k):
            pen = pts[k]
            win, inside = S.local_window(target, labels, visited, pen, W)
            v2, _, _ = S.apply_move(visited, pen, pts[k + 1] - pen)
            return jnp.where(k < n_moves, v2, visited), (win, inside)

        _, (wins, inside) = jax.lax.scan(body, visited, jnp.arange(pts.shape[0] - 1))
        return wins, inside

    wins, inside = jax.vmap(stroke_windows)(
        b["target"], b["labels"], b["visited"], b["pts"], b["n_moves"]
    )
    sb, st = b["slot_b"], b["slot_t"]
    feat = model.local_features(wins[sb, st], inside[sb, st])  # [N, 1600]: only packed slots
    xp = model.core.project(feat) * b["slot_valid"][:, None]
    B, T = b["move"].shape
    seq = jnp.zeros((B, T, xp.shape[-1]), xp.dtype).at[sb, st].add(xp)

    def step(carry, x):
        return model.core.step(carry, x)

    _, hs = jax.lax.scan(step, model.core.init_carry((B,)), jnp.swapaxes(seq, 0, 1))
    move_logits, touch_logits = model.heads(jnp.swapaxes(hs, 0, 1))
    valid = b["valid"].astype(jnp.float32)
    ce_move = optax.softmax_cross_entropy_with_integer_labels(move_logits, b["move"])
    ce_touch = optax.sigmoid_binary_cross_entropy(touch_logits, b["touch"])
    n = jnp.maximum(valid.sum(), 1.0)
    acc_move = jnp.sum(
        (jnp.argmax(move_logits, -1) == b["move"]) * valid * b["touch"]
    ) / jnp.maximum(jnp.sum(valid * b["touch"]), 1.0)
    acc_touch = jnp.sum(((touch_logits > 0) == (b["touch"] > 0.5)) * valid) / n
    return jnp.sum((ce_move + ce_touch) * valid) / n, {"acc_move": acc_move, "acc_touch": acc_touch}


def global_loss(model: M.DrawModel, g: dict):
    """Cross-entropy of the next start (eq. 9) over the pixels a stroke may start on.

    The planner picks the start among :func:`jdraw.state.allowed_starts`, so
    the softmax is taken over those pixels (plus the true start).
    """
    x = jax.vmap(S.global_state)(g["target"], g["visited"], g["last"], g["pen"], g["has_pen"])
    logits = model.global_logits(x, restrict=False).reshape(x.shape[0], -1)
    allowed = jax.vmap(S.allowed_starts, in_axes=(0, 0, None))(g["target"], g["visited"], False)
    allowed = allowed.reshape(x.shape[0], -1) | jax.nn.one_hot(
        g["start"], logits.shape[1], dtype=bool
    )
    logits = jnp.where(allowed, logits, -1e9)
    ce = optax.softmax_cross_entropy_with_integer_labels(logits, g["start"])
    acc = jnp.mean(jnp.argmax(logits, -1) == g["start"])
    return jnp.mean(ce), {"acc_start": acc}


# ----------------------------------------------------------------------------
# The step.


def init_from_bundle(model: M.DrawModel, bundle_dir) -> int:
    """Copies every array of a bundle that ``model`` has (same path and shape).

    Used to train a new global model beside a trained local model
    (``configs/ours.py``). Returns the number of arrays copied.
    """
    from jdraw.model import bundle

    with np.load(pathlib.Path(bundle_dir) / "params.npz") as z:
        arrays = {k: z[k] for k in z.files}
    return bundle.fill(model, arrays, partial=True)


def make_step(graphdef, tx, global_weight: float):
    def loss_fn(model):
        b = batch_ref[0]
        if "global_only" in b:
            from jdraw.train import global_only

            loss, logs = global_only.loss(model, b["global_only"])
            return loss, {"loss": loss, **logs}
        gl, gm = global_loss(model, b["global"])
        if "local" not in b:  # only the global model trains (configs/ours.py)
            return gl, {"loss": gl, "global_loss": gl, **gm}
        ll, lm = local_loss(model, b["local"])
        loss = ll + global_weight * gl
        return loss, {"loss": loss, "local_loss": ll, "global_loss": gl, **lm, **gm}

    batch_ref = [None]

    def step(params, rest, opt_state, batch):
        batch_ref[0] = batch
        model = nnx.merge(graphdef, params, rest)
        grads, logs = nnx.grad(loss_fn, argnums=nnx.DiffState(0, nnx.Param), has_aux=True)(model)
        batch_ref[0] = None
        updates, opt_state = tx.update(grads, opt_state, params)
        params = optax.apply_updates(params, updates)
        rest = nnx.state(model, nnx.Not(nnx.Param))
        return params, rest, opt_state, logs

    return jax.jit(step, donate_argnums=(0, 1, 2))


def data_mesh() -> Mesh:
    return Mesh(np.asarray(jax.devices()), ("data",))


def shard_batch(batch: dict, mesh: Mesh) -> dict:
    """Places every array with its leading (batch) axis split over the mesh."""

    def put(x):
        x = np.asarray(x)
        spec = P("data") if x.ndim and x.shape[0] % mesh.size == 0 else P()
        return jax.device_put(x, NamedSharding(mesh, spec))

    return jax.tree.map(put, batch)


def make_batch(ks, pool, cfg, step: int) -> dict:
    """The batch of ``step``: a pure function of ``(cfg.seed, step)``."""
    rng = np.random.default_rng([int(cfg.seed), int(step)])
    t = cfg.train
    if cfg.model.get("kind", "two_scale") == "global_only":
        from jdraw.train import global_only

        g = global_only.batch(ks, pool, rng, size=t.global_batch, strength=cfg.data.augment)
        return {"global_only": g}, t.global_batch  # each sample is an action of one stroke
    gb = lambda: batches.global_batch(
        ks,
        pool,
        rng,
        size=t.global_batch,
        strength=cfg.data.augment,
        per_char=int(t.get("global_per_char", 1)),
    )
    if not t.get("train_local", True):
        return {"global": gb()}, 0
    lb = batches.local_batch(
        ks,
        pool,
        rng,
        windows=t.windows,
        strokes=t.strokes,
        max_len=t.max_len,
        per_char=t.strokes_per_char,
        strength=cfg.data.augment,
    )
    n = lb.pop("n_strokes")
    return {"local": lb, "global": gb()}, n


class Prefetcher:
    """Builds upcoming batches in a thread while the device works."""

    def __init__(self, fn, start: int, stop: int, depth: int = 2):
        self._q: queue.Queue = queue.Queue(maxsize=depth)
        self._fn, self._next, self._stop = fn, start, stop
        self._halt = threading.Event()
        self._t = threading.Thread(target=self._run, daemon=True)
        self._t.start()

    def _run(self):
        s = self._next
        while s < self._stop and not self._halt.is_set():
            try:
                item = (s, *self._fn(s))
            except Exception as e:  # handed to the training loop, which re-raises it
                item = (s, e, None)
            while not self._halt.is_set():
                try:
                    self._q.put(item, timeout=0.2)
                    break
                except queue.Full:
                    continue
            s += 1

    def get(self):
        item = self._q.get()
        if isinstance(item[1], Exception):
            raise RuntimeError(f"making the batch of step {item[0]} failed") from item[1]
        return item

    def close(self):
        self._halt.set()


# ----------------------------------------------------------------------------
# Checkpoints.


def checkpoint_manager(workdir, cfg) -> ocp.CheckpointManager:
    opts = ocp.CheckpointManagerOptions(max_to_keep=2, save_interval_steps=1)
    return ocp.CheckpointManager(
        pathlib.Path(workdir).resolve() / "checkpoints",
        options=opts,
        item_names=("model", "optimizer", "step", "config"),
    )


def save(mgr, step: int, model_state, opt_state, progress: dict, cfg):
    mgr.save(
        step,
        args=ocp.args.Composite(
            model=ocp.args.StandardSave(nnx.to_pure_dict(model_state)),
            optimizer=ocp.args.StandardSave(opt_state),
            step=ocp.args.JsonSave({"step": int(step), **progress}),
            config=ocp.args.JsonSave(json.loads(cfg.to_json())),
        ),
    )


def restore(mgr, step: int, model_state, opt_state):
    abstract = lambda t: jax.tree.map(ocp.utils.to_shape_dtype_struct, t)
    r = mgr.restore(
        step,
        args=ocp.args.Composite(
            model=ocp.args.StandardRestore(abstract(nnx.to_pure_dict(model_state))),
            optimizer=ocp.args.StandardRestore(abstract(opt_state)),
            step=ocp.args.JsonRestore(),
        ),
    )
    nnx.replace_by_pure_dict(model_state, r["model"])
    return model_state, r["optimizer"], r["step"]


# ----------------------------------------------------------------------------
# Validation.


def validate(model_state, graphdef, ks, idx, max_steps: int = 1024) -> dict:
    """Pixel and stroke accuracy of planning the characters ``idx`` (no augmentation)."""
    from jdraw.data import demos as demo
    from jdraw.planner import plan as api

    model = nnx.merge(graphdef, model_state)
    model.eval()
    demos = [demo.sample(ks, int(i)) for i in idx]
    plan = api.plan(np.stack([d.target for d in demos]), checkpoint=model, max_steps=max_steps)
    return score(demos, plan)


def score(demos, plan) -> dict:
    """Per-character metrics of a plan against demonstrations.

    See :func:`jdraw.evaluation.metrics.score`.
    """
    return metrics.score(demos, plan)


# ----------------------------------------------------------------------------
# The loop.


def _drop_records_after(log_path: pathlib.Path, step: int) -> None:
    """Rewrites ``metrics.jsonl`` without records past ``step`` (the restored one).

    A run killed after its last checkpoint logged steps it redoes on resume;
    without this they would appear twice. A half-written last line goes too.
    """
    if not log_path.exists():
        return
    kept = []
    for line in log_path.read_text().splitlines():
        try:
            rec = json.loads(line)
        except json.JSONDecodeError:
            continue
        # The final validation is logged again whenever a finished run is rerun.
        if isinstance(rec, dict) and int(rec.get("step", 0)) <= step and "final_val" not in rec:
            kept.append(line)
    tmp = log_path.with_suffix(".jsonl.tmp")
    tmp.write_text("".join(x + "\n" for x in kept))
    tmp.replace(log_path)


def train(cfg, workdir, *, progress: bool = True, stop_after: int | None = None) -> dict:
    """Trains (or resumes) the run in ``workdir``; returns the final logs.

    Args:
      cfg: a config from ``configs/``.
      workdir: checkpoints, ``metrics.jsonl`` and the exported bundle go here.
      stop_after: stop (with a checkpoint) after this many steps of this call;
        for tests of resumption.
    """
    workdir = pathlib.Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "config.json").write_text(cfg.to_json_best_effort(indent=2) + "\n")
    ks = kanji.load(progress=progress)
    pool = kanji.split_indices(ks, "train")
    val_idx = kanji.split_indices(ks, "val")[: cfg.eval.val_chars]

    model = M.build(cfg.model, seed=int(cfg.seed))
    if cfg.train.get("init_from"):
        init_from_bundle(model, cfg.train.init_from)
    model.train()
    graphdef, params, rest = nnx.split(model, nnx.Param, ...)
    tx = optax.adam(cfg.train.learning_rate)
    opt_state = tx.init(params)
    mesh = data_mesh()
    replicated = NamedSharding(mesh, P())
    mgr = checkpoint_manager(workdir, cfg)
    start, progress_state = 0, {"strokes_seen": 0, "global_seen": 0, "wall_time_s": 0.0}
    if mgr.latest_step() is not None:
        model_state = nnx.merge_state(params, rest)
        model_state, opt_state, progress_state = restore(
            mgr, mgr.latest_step(), model_state, opt_state
        )
        _, params, rest = nnx.split(nnx.merge(graphdef, model_state), nnx.Param, ...)
        start = int(progress_state.pop("step"))
    params, rest, opt_state = jax.device_put((params, rest, opt_state), replicated)
    step_fn = make_step(graphdef, tx, float(cfg.train.global_weight))
    total = int(cfg.train.num_steps)
    end = total if stop_after is None else min(total, start + int(stop_after))
    log_path = workdir / "metrics.jsonl"
    _drop_records_after(log_path, start)

    interrupted = {"flag": False}

    def on_signal(signum, frame):
        interrupted["flag"] = True

    old = (
        signal.signal(signal.SIGTERM, on_signal)
        if threading.current_thread() is threading.main_thread()
        else None
    )
    pf = Prefetcher(lambda s: make_batch(ks, pool, cfg, s), start, end)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=total, initial=start, desc="train", unit="step", dynamic_ncols=True)
    logs = {}
    t_last, s_last, g_last = (
        time.time(),
        progress_state["strokes_seen"],
        progress_state["global_seen"],
    )
    step = start
    try:
        while step < end and not interrupted["flag"]:
            s, batch, n_strokes = pf.get()
            assert s == step
            params, rest, opt_state, logs = step_fn(
                params, rest, opt_state, shard_batch(batch, mesh)
            )
            step += 1
            progress_state["strokes_seen"] += int(n_strokes)
            progress_state["global_seen"] += int(cfg.train.global_batch)
            if step % cfg.train.log_every == 0 or step == end:
                logs = {k: float(v) for k, v in logs.items()}
                now = time.time()
                progress_state["wall_time_s"] += now - t_last
                rate = (progress_state["strokes_seen"] - s_last) / max(now - t_last, 1e-9)
                grate = (progress_state["global_seen"] - g_last) / max(now - t_last, 1e-9)
                t_last, s_last, g_last = (
                    now,
                    progress_state["strokes_seen"],
                    progress_state["global_seen"],
                )
                rec = {
                    "step": step,
                    **logs,
                    "strokes_per_s": rate,
                    "global_per_s": grate,
                    **progress_state,
                }
                with open(log_path, "a") as f:
                    f.write(json.dumps(rec) + "\n")
                if bar is not None:
                    shown = {
                        k: f"{logs[k]:.3f}" for k in ("loss", "acc_move", "acc_start") if k in logs
                    }
                    bar.set_postfix(**shown, strokes_s=f"{rate:.1f}")
            if bar is not None:
                bar.update(1)
            if cfg.eval.every and step % cfg.eval.every == 0 and step < end:
                v = validate(nnx.merge_state(params, rest), graphdef, ks, val_idx)
                with open(log_path, "a") as f:
                    f.write(json.dumps({"step": step, "val": v}) + "\n")
                if bar is not None:
                    bar.write(
                        f"step {step}: val pixel {v['pixel_acc']:.4f} stroke {v['stroke_acc']:.4f}"
                    )
                t_last = time.time()
            if step % cfg.train.checkpoint_every == 0 and step < end:
                save(mgr, step, nnx.merge_state(params, rest), opt_state, progress_state, cfg)
    finally:
        pf.close()
        if bar is not None:
            bar.close()
        if step > start and mgr.latest_step() != step:
            save(mgr, step, nnx.merge_state(params, rest), opt_state, progress_state, cfg)
        mgr.wait_until_finished()
        mgr.close()
        if old is not None:
            signal.signal(signal.SIGTERM, old)
    result = {"step": step, "done": step >= total, **progress_state, **logs}
    if step >= total:
        from jdraw.model.checkpoints import export

        export(workdir, workdir / "bundle")
        v = validate(nnx.merge_state(params, rest), graphdef, ks, val_idx)
        result["val"] = v
        with open(log_path, "a") as f:
            f.write(json.dumps({"step": step, "final_val": v}) + "\n")
    return result
