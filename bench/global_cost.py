"""The global (start) model's cost, and planning speed, paper's model against ours.

  python bench/global_cost.py [--chars 32] [--ours runs/ours/bundle]

Prints, for the paper's global model and the whole-canvas start model: ms per
call for one image (jitted, median of repeats), FLOPs per call from XLA's cost
analysis, and `jdraw.plan` characters/s at batch 1 on held-out KanjiVG test
characters with each checkpoint (stroke order as each plans by default).
"""

from __future__ import annotations

import argparse
import pathlib
import time

import jax
import jax.numpy as jnp
import numpy as np
from flax import nnx

import jdraw
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.planner import plan as api


def global_cost(model, repeats: int = 30) -> tuple[float, float]:
    """``(median ms, FLOPs)`` of one ``global_logits`` call on one image."""
    g, st = nnx.split(model)
    f = jax.jit(lambda st, x: nnx.merge(g, st).global_logits(x))
    x = jnp.asarray(np.random.default_rng(0).random((1, 100, 100, 4)) > 0.9, jnp.float32)
    f(st, x).block_until_ready()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f(st, x).block_until_ready()
        times.append(time.perf_counter() - t)
    ca = f.lower(st, x).compile().cost_analysis()
    ca = ca[0] if isinstance(ca, list) else ca
    return 1e3 * float(np.median(times)), float(ca.get("flops", float("nan")))


def plan_rate(checkpoint, targets) -> float:
    """Characters per second planning ``targets`` one at a time (after a warm-up)."""
    jdraw.plan(targets[:1], checkpoint=checkpoint)
    t = time.perf_counter()
    for x in targets:
        jdraw.plan(x[None], checkpoint=checkpoint)
    return len(targets) / (time.perf_counter() - t)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--paper", default=str(jdraw.model.bundle.PAPER_BUNDLE))
    p.add_argument("--ours", default=str(jdraw.model.bundle.DEFAULT_BUNDLE))
    p.add_argument("--chars", type=int, default=32)
    a = p.parse_args()
    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, "test")[: a.chars]
    targets = np.stack([demo.sample(ks, int(i)).target for i in idx])
    rows = []
    for name, ckpt in (("paper", a.paper), ("ours", a.ours)):
        model = api.load_model(pathlib.Path(ckpt))
        ms, flops = global_cost(model)
        rows.append((name, ms, flops, plan_rate(ckpt, targets)))
    print("| model | global ms / image | global GFLOP / image | plan chars/s, batch 1 |")
    print("| --- | --- | --- | --- |")
    for name, ms, flops, rate in rows:
        print(f"| {name} | {ms:.2f} | {flops / 1e9:.3f} | {rate:.2f} |")
    (_, ms0, f0, r0), (_, ms1, f1, r1) = rows
    ratios = f"global time {ms1 / ms0:.3f}, FLOPs {f1 / f0:.3f}, plan speed {r1 / r0:.2f}x"
    print(f"\nours / paper: {ratios}")


if __name__ == "__main__":
    main()
