"""Verifies the bundled model's plans of held-out KanjiVG characters on the simulated arm.

  python examples/robot_check.py [--chars 16]

Plans test-split characters with ``jdraw.plan`` (bundled checkpoint), runs them
through ``jdraw.robot.verify`` and prints reachability, IK error and IoU
(drawn vs planned) per batch.
"""

import argparse
import time

import numpy as np

import jdraw
from jdraw import robot
from jdraw.data import demos as demo
from jdraw.data import kanji


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chars", type=int, default=16)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    ks = kanji.load()
    rng = np.random.default_rng(args.seed)
    idx = rng.choice(kanji.split_indices(ks, "test"), args.chars, replace=False)
    plan = jdraw.plan(np.stack([demo.sample(ks, int(i)).target for i in idx]))
    t = time.perf_counter()
    rep = robot.verify(plan)
    dt = time.perf_counter() - t
    print(f"{args.chars} held-out characters planned by the bundled model, verified in {dt:.1f} s")
    print(f"reachable: {int(rep.reachable.sum())}/{len(rep.reachable)}")
    print(f"max IK error mm: {float(rep.max_ik_error_mm.max()):.4f}")
    print(f"IoU drawn vs planned: min {float(rep.iou.min()):.3f} mean {float(rep.iou.mean()):.3f}")
    print(
        f"pen lifts (measured == planned): {bool(np.all(rep.pen_lifts == rep.planned_pen_lifts))}"
    )
    print(f"drawing time s: mean {float(np.mean(rep.drawing_time_s)):.1f}")


if __name__ == "__main__":
    main()
