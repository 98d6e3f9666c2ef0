"""`jdraw.plan` characters/s at batch 1, the paper's model against ours, by loop and order.

  python bench/plan_orders.py

Plans the first 32 held-out KanjiVG test characters one at a time (after a
warm-up call) with each checkpoint and option set, and prints chars/s: what
the planner itself costs (``order="model"``) and what the stroke ranker adds.
"""

import time

import numpy as np

import jdraw
from jdraw.data import demos as demo
from jdraw.data import kanji

OPTIONS = (
    dict(loop="vmap", order="model"),
    dict(loop="slots", order="model"),
    dict(loop="slots", order="model", batch_size=1, global_batch=1),
    dict(loop="vmap"),  # order="auto": the ranker where the checkpoint has one
)


def rate(targets, **kw) -> float:
    jdraw.plan(targets[:1], **kw)
    t = time.perf_counter()
    for x in targets:
        jdraw.plan(x[None], **kw)
    return len(targets) / (time.perf_counter() - t)


def main():
    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, "test")[:32]
    targets = np.stack([demo.sample(ks, int(i)).target for i in idx])
    for name, ck in (("paper", "jdraw/checkpoints/paper"), ("ours", None)):
        for kw in OPTIONS:
            print(f"{name:5s} {kw}: {rate(targets, checkpoint=ck, **kw):.2f} chars/s", flush=True)


if __name__ == "__main__":
    main()
