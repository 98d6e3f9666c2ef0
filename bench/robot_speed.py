"""Robot verification speed on held-out KanjiVG characters; prints a table.

    python bench/robot_speed.py            # batch 1 and 16, ~3-6 min on a busy 2-core CPU

"sim s / wall s" is simulated seconds (all images, padded horizon) per wall
second. Plans are the test split's stroke-order demonstrations (the same form as
``jdraw.plan`` output). Each batch size is run twice; the second, compiled run
is timed. Also reports the acceptance figures (reachability, IoU, IK error).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import jdraw
from jdraw import robot
from jdraw.data import demos as demo
from jdraw.data import kanji


def held_out_plans(n: int, seed: int = 0) -> jdraw.Plan:
    ks = kanji.load(progress=False)
    idx = np.random.default_rng(seed).choice(kanji.split_indices(ks, "test"), n, replace=False)
    strokes = [[s.astype(np.float64) for s in demo.sample(ks, int(i)).strokes] for i in idx]
    return jdraw.Plan(
        strokes=strokes,
        actions=np.zeros((n, 1, 3), np.int32),
        lengths=np.zeros(n, np.int32),
        truncated=np.zeros(n, bool),
    )


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--batches", default="1,16")
    args = parser.parse_args(argv)
    rows = []
    for b in (int(x) for x in args.batches.split(",")):
        plan = held_out_plans(b, seed=b)
        t0 = time.perf_counter()
        robot.verify(plan)
        first = time.perf_counter() - t0
        report = robot.verify(plan)
        wall = report.wall_time_s
        # every image is simulated over the padded horizon
        sim = b * report.t.size * (report.t[1] - report.t[0])
        rows.append((b, first, wall, b / wall, sim / wall, report))
    print(
        "| batch | first call s | compiled call s | verified chars/s | sim s / wall s |"
        " reachable | IoU min / mean | max IK err mm | max track err mm |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for b, first, wall, cps, ratio, r in rows:
        print(
            f"| {b} | {first:.1f} | {wall:.2f} | {cps:.2f} | {ratio:.2f} |"
            f" {int(r.reachable.sum())}/{b} | {r.iou.min():.3f} / {r.iou.mean():.3f} |"
            f" {r.max_ik_error_mm.max():.4f} | {r.max_track_error_mm.max():.2f} |"
        )


if __name__ == "__main__":
    main()
