"""Training both models, resumable from Orbax checkpoints.

``train(cfg, workdir)`` builds the state (:func:`jdraw.train.step.create_state`),
restores the workdir's latest checkpoint if there is one, and runs the jitted
step (:mod:`jdraw.train.step`) on batches made ahead (:mod:`jdraw.train.feed`),
logging to ``metrics.jsonl`` and checkpointing (:mod:`jdraw.train.records`).
A finished run writes its bundle from the model it holds.
"""

from __future__ import annotations

import pathlib
import signal
import threading
import time

import jax
import numpy as np
from flax import nnx
from jax.sharding import NamedSharding
from jax.sharding import PartitionSpec as P

from jdraw import compile_cache
from jdraw.data import kanji, mix
from jdraw.model import checkpoints
from jdraw.train import distributed, feed, records
from jdraw.train.step import create_state, make_step, model_of
from jdraw.train.validation import validate


class _Rates:
    """Strokes and global samples per second since the last log."""

    def __init__(self, progress: dict):
        self.t, self.s, self.g = time.time(), progress["strokes_seen"], progress["global_seen"]

    def take(self, progress: dict) -> tuple[float, float]:
        now = time.time()
        dt = max(now - self.t, 1e-9)
        progress["wall_time_s"] += now - self.t
        rates = (progress["strokes_seen"] - self.s) / dt, (progress["global_seen"] - self.g) / dt
        self.t, self.s, self.g = now, progress["strokes_seen"], progress["global_seen"]
        return rates


def _on_sigterm(flag: dict):
    """Makes SIGTERM set ``flag["stop"]`` (main thread only); returns the old handler."""

    def handler(signum, frame):
        flag["stop"] = True

    if threading.current_thread() is threading.main_thread():
        return signal.signal(signal.SIGTERM, handler)
    return None


def _host_model(graphdef, state):
    """The model a (possibly multi-process) training state holds, on this process's arrays."""
    return model_of(
        graphdef,
        state._replace(
            params=distributed.local_copy(state.params), rest=distributed.local_copy(state.rest)
        ),
    )


def _replicate(state, mesh):
    """``state`` on every device of the mesh; the same values on every process."""
    rep = NamedSharding(mesh, P())
    if jax.process_count() > 1:
        return jax.tree.map(lambda a: distributed.global_array(np.asarray(a), rep), state)
    return jax.device_put(state, rep)


def train(
    cfg,
    workdir,
    *,
    progress: bool = True,
    stop_after: int | None = None,
    return_params: bool = False,
) -> dict:
    """Trains (or resumes) the run in ``workdir``; returns the final logs.

    Args:
      cfg: a config from ``configs/``; ``cfg.data.get("chars")``, if set,
        restricts training to those KanjiVG indices (tests).
      workdir: checkpoints, ``metrics.jsonl`` and the bundle go here.
      progress: show a progress bar.
      stop_after: stop (with a checkpoint) after this many steps of this call;
        for tests of resumption.
      return_params: also return this process's copy of the parameters
        (``"params"``, numpy) for tests.

    Run as several processes (:mod:`jdraw.train.distributed`), every process
    calls this; the batch is split over all their devices, Orbax saves each
    checkpoint once, and process 0 alone logs, validates and writes the bundle.
    The step is compiled through jdraw's persistent cache (:mod:`jdraw.compile_cache`),
    so a resumed run does not compile it again.
    """
    compile_cache.enable()
    workdir = pathlib.Path(workdir)
    lead = distributed.is_lead()
    progress = progress and lead
    workdir.mkdir(parents=True, exist_ok=True)
    if lead:
        (workdir / "config.json").write_text(cfg.to_json_best_effort(indent=2) + "\n")
    ks = kanji.load(progress=progress)
    pool = kanji.split_indices(ks, "train")
    if cfg.data.get("chars"):
        pool = [int(i) for i in cfg.data.chars]
    val_idx = kanji.split_indices(ks, "val")[: cfg.eval.val_chars]
    source = ks
    if cfg.data.get("extra"):  # other scripts beside KanjiVG (jdraw.data.mix)
        source = mix.mixture(ks, pool, cfg.data.extra, progress=progress)

    graphdef, tx, state = create_state(cfg)
    # Processes start together: Orbax's and the step's collectives wait 30 s at most.
    distributed.barrier(f"jdraw.train.loop start {workdir}")
    mesh = feed.data_mesh()
    mgr = records.manager(workdir)
    start, counts = 0, {"strokes_seen": 0, "global_seen": 0, "wall_time_s": 0.0}
    state = _replicate(state, mesh)
    if mgr.latest_step() is not None:  # restored into the state's (replicated) shardings
        state, counts = records.restore(mgr, mgr.latest_step(), state)
        start = int(counts.pop("step"))
    step_fn = make_step(graphdef, tx, float(cfg.train.global_weight))
    total = int(cfg.train.num_steps)
    end = total if stop_after is None else min(total, start + int(stop_after))
    log_path = workdir / "metrics.jsonl"
    if lead:
        records.drop_records_after(log_path, start)

    flag = {"stop": False}
    old_handler = _on_sigterm(flag)
    pf = feed.Prefetcher(lambda s: feed.make_batch(source, pool, cfg, s), start, end)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=total, initial=start, desc="train", unit="step", dynamic_ncols=True)
    logs, rates, step = {}, _Rates(counts), start
    try:
        while step < end and not flag["stop"]:
            s, batch, n_strokes = pf.get()
            assert s == step
            state, logs = step_fn(state, feed.shard_batch(batch, mesh))
            step += 1
            counts["strokes_seen"] += int(n_strokes)
            counts["global_seen"] += int(cfg.train.global_batch)
            if step % cfg.train.log_every == 0 or step == end:
                logs = {k: float(v) for k, v in distributed.local_copy(logs).items()}
                rate, grate = rates.take(counts)
                rec = {"step": step, **logs, "strokes_per_s": rate, "global_per_s": grate}
                if lead:
                    records.append(log_path, {**rec, **counts})
                if bar is not None:
                    shown = ("loss", "acc_move", "acc_start")
                    bar.set_postfix(
                        **{k: f"{logs[k]:.3f}" for k in shown if k in logs},
                        strokes_s=f"{rate:.1f}",
                    )
            if bar is not None:
                bar.update(1)
            due = cfg.eval.every and step % cfg.eval.every == 0 and step < end
            if lead and len(val_idx) and due:
                v = validate(_host_model(graphdef, state), ks, val_idx)
                records.append(log_path, {"step": step, "val": v})
                if bar is not None:
                    bar.write(
                        f"step {step}: val pixel {v['pixel_acc']:.4f} stroke {v['stroke_acc']:.4f}"
                    )
                rates.t = time.time()
            if due:
                distributed.barrier(f"jdraw.train.loop val {workdir} {step}")
            if step % cfg.train.checkpoint_every == 0 and step < end:
                records.save(mgr, step, state, counts, cfg)
    finally:
        pf.close()
        if bar is not None:
            bar.close()
        if step > start and mgr.latest_step() != step:
            records.save(mgr, step, state, counts, cfg)
        mgr.wait_until_finished()
        mgr.close()
        if old_handler is not None:
            signal.signal(signal.SIGTERM, old_handler)
    result = {"step": step, "done": step >= total, **counts, **logs}
    if return_params:
        result["params"] = distributed.local_copy(nnx.to_pure_dict(state.params))
    if step >= total and lead:
        model = _host_model(graphdef, state)
        prov = checkpoints.provenance(workdir, cfg, {"step": step, **counts})
        checkpoints.write_bundle(model, cfg, workdir / "bundle", prov)
        if len(val_idx):
            result["val"] = v = validate(model, ks, val_idx)
            records.append(log_path, {"step": step, "final_val": v})
    distributed.barrier(f"jdraw.train.loop {workdir} {step}")  # the bundle is there for all
    return result
