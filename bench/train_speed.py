"""Training throughput of a config: strokes/s and global samples/s per step.

  python bench/train_speed.py [--config configs/paper.py] [--steps 20]

Times jitted training steps on prepared batches (data making excluded, it
runs in a background thread during training) and, separately, the host-side
batch making. Prints a table.
"""

import argparse
import importlib.util
import time

import jax
import numpy as np

from jdraw.data import kanji
from jdraw.train import feed
from jdraw.train.step import create_state, make_step


def load_config(path):
    spec = importlib.util.spec_from_file_location("cfg", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.get_config()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", default="configs/paper.py")
    ap.add_argument("--steps", type=int, default=20)
    args = ap.parse_args()
    cfg = load_config(args.config)
    ks = kanji.load()
    pool = kanji.split_indices(ks, "train")
    t = time.perf_counter()
    made = [feed.make_batch(ks, pool, cfg, s) for s in range(args.steps)]
    t_data = (time.perf_counter() - t) / args.steps
    g, tx, state = create_state(cfg)
    step = make_step(g, tx, float(cfg.train.global_weight))
    mesh = feed.data_mesh()
    batches = [feed.shard_batch(b, mesh) for b, _ in made]
    state, logs = step(state, batches[0])  # compile
    jax.block_until_ready(logs)
    t = time.perf_counter()
    for b in batches:
        state, logs = step(state, b)
    jax.block_until_ready(logs)
    dt = (time.perf_counter() - t) / args.steps
    strokes = np.mean([n for _, n in made])
    glob = cfg.train.global_batch
    print(f"config {args.config}: {jax.device_count()} device(s), {args.steps} steps")
    cols = ["step s", "strokes/step", "strokes/s", "global/s", "data s/step"]
    vals = [dt, strokes, strokes / dt, glob / dt, t_data]
    print(" | ".join(f"{c:>12}" for c in cols))
    print("-" * (15 * len(cols)))
    print(" | ".join(f"{v:>12.3f}" for v in vals))


if __name__ == "__main__":
    main()
