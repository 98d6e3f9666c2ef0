"""The closed loop on held-out KanjiVG characters: IoU after one pass vs after the loop.

    MUJOCO_GL=egl nice -n 10 python examples/closed_loop_eval.py --chars 16 --rounds 2 \
        --picture docs/closed_loop.png

Plans test-split characters with ``jdraw.plan`` (bundled checkpoint) and draws
them with ``jdraw.robot.draw_closed_loop`` under each fault of the moderate
preset alone and all together; prints a Markdown table. One rollout compile
(several minutes on a loaded 2-core CPU), then about 1-3 min per row.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import jax
import numpy as np

import jdraw
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.robot import closed_loop, faults


def held_out_targets(n: int, seed: int = 0) -> np.ndarray:
    """``bool [n, 100, 100]`` test-split characters (the ones examples/robot_check.py draws)."""
    ks = kanji.load(progress=False)
    idx = np.random.default_rng(seed).choice(kanji.split_indices(ks, "test"), n, replace=False)
    return np.stack([demo.sample(ks, int(i)).target for i in idx])


def configs(seed: int) -> list[tuple[str, faults.Faults]]:
    base = faults.Faults(seed=seed)
    rows = [("none", base), ("all together", dataclasses.replace(faults.MODERATE, seed=seed))]
    return rows + [(name, faults.only(name, faults.MODERATE)) for name in faults.GROUPS]


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chars", type=int, default=16)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--only", default=None, help="comma-separated row names to run")
    ap.add_argument("--look", default="auto", choices=["auto", "render", "ink"])
    ap.add_argument("--picture", default=None, help="PNG of the 'all together' row's best gain")
    ap.add_argument("--cache", default="/tmp/jdraw_jax_cache", help="JAX compilation cache")
    args = ap.parse_args(argv)
    if args.cache:
        jax.config.update("jax_compilation_cache_dir", args.cache)
    plan = jdraw.plan(held_out_targets(args.chars, args.seed))
    rows = configs(args.seed)
    if args.only:
        keep = set(args.only.split(","))
        rows = [r for r in rows if r[0] in keep]
    print(
        "| faults | IoU one pass (mean / min) | IoU after loop (mean / min) | exact IoU one pass"
        " / after | chars redrawn | strokes redrawn | rounds | look + redraw s/char | wall s |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for name, f in rows:
        t = time.perf_counter()
        res = closed_loop.draw_closed_loop(plan, f, rounds=args.rounds, look_with=args.look)
        wall = time.perf_counter() - t
        first, last = res.iou[:, 0], res.iou[:, -1]
        redrawn = sum(1 for r in res.redrawn if any(len(s) for s in r[1:]))
        strokes = sum(len(s) for r in res.redrawn for s in r[1:])
        s = res.seconds
        # looking after every pass, planning and drawing the residuals
        extra = sum(s["look"]) + sum(s["plan"]) + sum(s["draw"][1:])
        lowered = int(np.sum(np.diff(res.iou, axis=1) < 0))
        print(
            f"| {name} | {first.mean():.3f} / {first.min():.3f} | {last.mean():.3f} /"
            f" {last.min():.3f} | {res.iou_exact[:, 0].mean():.3f} /"
            f" {res.iou_exact[:, -1].mean():.3f} | {redrawn}/{args.chars} | {strokes} |"
            f" {res.rounds} | {extra / args.chars:.2f} | {wall:.0f} |"
            + (f" LOWERED x{lowered}" if lowered else ""),
            flush=True,
        )
        if name == "all together":
            gain = res.iou[:, -1] - res.iou[:, 0]
            i = int(np.argmax(gain))
            off = res.offset_mm
            print(
                f"all together: looked with {res.source}; registered offset mean"
                f" ({off[:, 0].mean():.2f}, {off[:, 1].mean():.2f}) mm, rotation"
                f" {res.rotation_deg.mean():.2f} deg (simulated {f.sheet_offset_mm} mm,"
                f" {f.sheet_rotation_deg} deg)"
            )
            if args.picture:
                print("wrote", closed_loop.picture(res, args.picture, index=i), f"(char {i})")


if __name__ == "__main__":
    main()
