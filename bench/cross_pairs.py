"""The join net's examples on cursive fragments with crosses: what it is taught and what it says.

  python bench/cross_pairs.py [--n 60] [--checkpoint BUNDLE]

Takes the first ``--n`` training fragments of :func:`jdraw.data.cursive.fragments`
that hold a t, traces them with the bundle's tracer and no splitter (``jdraw.plan(...,
split=False)``), and builds the splitter's join examples from them as its trainer does
(:func:`jdraw.train.splitter.join_examples`: cut at the true corners and at T's, every end
pair up to the default's reach and retrace). A pair is a *cross* pair when either end
lies on a writer's stroke shorter than a fifth of the fragment's longest (a t's cross;
:func:`jdraw.planner.joins.end_owner`). For cross pairs and the others it prints how
many there are, the share labelled "join" (the trainer's target) and the share the
bundle's join net scores above 0 (the planner joins those, as many as it can), and the
10th, 50th and 90th percentile of its logits. About a minute on the 2-core CPU.
"""

from __future__ import annotations

import argparse

import numpy as np

import jdraw
from jdraw.data import cursive
from jdraw.data import demos as D
from jdraw.planner import joins, splits
from jdraw.train.splitter import join_examples

SHORT = 0.2  # of the fragment's longest stroke: a shorter one is a mark


def has_t(name: str) -> bool:
    """Whether the fragment ``"word[a:b]"`` holds a t."""
    word, span = name.split("[")
    a, b = (int(v) for v in span.rstrip("]").split(":"))
    return "t" in word[a:b]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=60)
    ap.add_argument("--checkpoint", default="jdraw/checkpoints/default")
    a = ap.parse_args()
    sp = splits.load(a.checkpoint)
    reach, retrace = sp.reach, splits.JOINED_RETRACE
    ks = cursive.fragments("train")
    idx = [i for i, name in enumerate(ks.names) if has_t(name)][: a.n]
    demos = [D.sample(ks, i, None, keep_turns=True) for i in idx]
    traced = jdraw.plan(np.stack([d.target for d in demos]), checkpoint=a.checkpoint, split=False)
    rows = {"cross": [], "other": []}  # (label, logit)
    for d, s in zip(demos, traced.strokes):
        refs = [np.asarray(r, np.float64) for r in d.strokes]
        length = np.array([np.linalg.norm(np.diff(r, axis=0), axis=1).sum() for r in refs])
        marks = set(np.flatnonzero(length < SHORT * length.max()).tolist())
        _, _, _, cut, pairs, xj, yj = join_examples(
            s, refs, d.target, None, reach, retrace, sp.t_cuts
        )
        if not len(xj):
            continue
        z = splits._score(splits._join_logits, sp, splits.drawing_rows(xj, cut, sp.context))
        for (i, ie, j, je), y, zz in zip(pairs, yj, z):
            owners = {joins.end_owner(cut[i], ie, refs), joins.end_owner(cut[j], je, refs)}
            rows["cross" if owners & marks else "other"].append((float(y), float(zz)))
    print(
        f"join examples of {len(idx)} training fragments with a t "
        f"(reach {reach}, retrace {retrace})"
    )
    print("| pairs | n | labelled join | net > 0 | logit p10 / p50 / p90 |")
    print("| --- | ---: | ---: | ---: | --- |")
    for kind, v in rows.items():
        v = np.asarray(v).reshape(-1, 2)
        if len(v):
            p = np.percentile(v[:, 1], [10, 50, 90])
            print(
                f"| {kind} | {len(v)} | {v[:, 0].mean():.2f} | {(v[:, 1] > 0).mean():.2f} | "
                f"{p[0]:.2f} / {p[1]:.2f} / {p[2]:.2f} |"
            )


if __name__ == "__main__":
    main()
