"""Feeding the step: each step's batch, made ahead in a thread, split over the devices.

A batch is a pure function of ``(cfg.seed, step)``, so a resumed run sees
the same batches as an uninterrupted one. Batches are split over a
``jax.sharding`` mesh of all devices along their leading (batch) axis.
"""

from __future__ import annotations

import queue
import threading

import jax
import numpy as np
from jax.sharding import Mesh, NamedSharding
from jax.sharding import PartitionSpec as P

from jdraw.data import batches, variants
from jdraw.train import distributed, global_only


def make_batch(ks, pool, cfg, step: int) -> tuple[dict, int]:
    """The batch of ``step`` and the strokes it feeds the local model.

    Returns ``({"local": ..., "global": ...}, n_strokes)`` (see
    :mod:`jdraw.data.batches`); ``{"global": ...}`` alone when the local
    model does not train; ``{"global_only": ...}`` for ablation (c), whose
    samples each count as one stroke.
    """
    rng = np.random.default_rng([int(cfg.seed), int(step)])
    t = cfg.train
    styles = variants.weights(cfg.data.get("styles", None))
    if cfg.model.get("kind", "two_scale") == "global_only":
        g = global_only.batch(ks, pool, rng, size=t.global_batch, strength=cfg.data.augment)
        return {"global_only": g}, t.global_batch

    def global_part():
        return batches.global_batch(
            ks,
            pool,
            rng,
            size=t.global_batch,
            strength=cfg.data.augment,
            per_char=int(t.get("global_per_char", 1)),
            styles=styles,
        )

    if not t.get("train_local", True):
        return {"global": global_part()}, 0
    lb = batches.local_batch(
        ks,
        pool,
        rng,
        windows=t.windows,
        strokes=t.strokes,
        max_len=t.max_len,
        per_char=t.strokes_per_char,
        strength=cfg.data.augment,
        styles=styles,
    )
    n = lb.pop("n_strokes")
    return {"local": lb, "global": global_part()}, n


def data_mesh() -> Mesh:
    return Mesh(np.asarray(jax.devices()), ("data",))


def shard_batch(batch: dict, mesh: Mesh) -> dict:
    """Places every array with its leading (batch) axis split over all processes' devices."""

    def put(x):
        x = np.asarray(x)
        spec = P("data") if x.ndim and x.shape[0] % mesh.size == 0 else P()
        if jax.process_count() > 1:  # every process holds the whole batch and places its part
            return distributed.global_array(x, NamedSharding(mesh, spec))
        return jax.device_put(x, NamedSharding(mesh, spec))

    return jax.tree.map(put, batch)


class Prefetcher:
    """Builds upcoming batches ``fn(step)`` in a thread while the device works."""

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
        """``(step, *fn(step))`` for the next step."""
        item = self._q.get()
        if isinstance(item[1], Exception):
            raise RuntimeError(f"making the batch of step {item[0]} failed") from item[1]
        return item

    def close(self):
        self._halt.set()
