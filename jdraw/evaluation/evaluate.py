"""Evaluation as the paper's §IV-A, plus stroke order and inputs drawn other ways.

Every split is planned once; the plan is then scored as traced and after each
reordering (:func:`jdraw.planner.ranker.reorder`): the learned ranker where the
checkpoint has one, and the x + y sort of the plan's own strokes as a
reference rule. Besides KanjiVG as our rasteriser draws it, the test split is
drawn by OpenCV (``cv2``: 1-pixel polylines through the curves, with the
staircase joints of a common rasteriser), with lines 3 pixels wide (``px3``)
and with OpenCV's ``thickness=3`` (``thick3``: lines 5 pixels wide), and
scored with a 1-pixel tolerance (:func:`jdraw.evaluation.metrics.score`).
"""

from __future__ import annotations

import json
import pathlib
import time

import numpy as np

from jdraw.data import demos as demo
from jdraw.data import kanji, variants
from jdraw.evaluation import metrics
from jdraw.evaluation.batched import plan_batched
from jdraw.io import figures
from jdraw.planner import plan as api
from jdraw.planner import ranker

VARIANTS = ("cv2", "px3", "thick3")


def rasterise(ks: kanji.KanjiSet, i: int, style: str) -> np.ndarray:
    """``bool [100, 100]`` character ``i`` drawn by OpenCV in ``style``.

    Styles (:data:`jdraw.data.variants.STYLES`): ``"cv2"`` 1-pixel
    8-connected polylines through points 1.5 px apart along the curves;
    ``"px3"`` / ``"px5"`` the same 3 and 5 pixels wide; ``"aa"`` anti-aliased
    1-pixel lines thresholded at half intensity. ``"thick3"`` is ``"px5"``
    under the name ``results/`` has used since it was added (OpenCV's
    ``thickness=3``, which draws lines 5 pixels across).
    """
    return variants.draw(ks.strokes(i), _ALIASES.get(style, style))


_ALIASES = {"thick3": "px5"}


def plan_chars(
    ks,
    idx,
    checkpoint,
    batch: int = 32,
    progress: bool = True,
    max_steps=None,
    style: str | None = None,
    canonicalise: bool = True,
    join: bool | None = None,
    split=None,
):
    """Plans characters ``idx`` (no augmentation) as traced (``order="model"``).

    Returns ``(demos, inputs bool [N, 100, 100], plan)``; ``inputs`` are the
    images planned: the demonstrations' targets, or ``style``'s drawing.
    """
    demos = [demo.sample(ks, int(i)) for i in idx]
    if style is None:
        inputs = np.stack([d.target for d in demos])
    else:
        inputs = np.stack([rasterise(ks, int(i), style) for i in idx])
    plan = plan_batched(
        inputs,
        checkpoint,
        batch=batch,
        progress=progress,
        desc=f"planning {style or 'kanjivg'}",
        max_steps=max_steps,
        canonicalise=canonicalise,
        join=join,
        split=split,
    )
    return demos, inputs, plan


def evaluate(
    checkpoint=None,
    *,
    out_dir="results",
    name="eval",
    n_random: int = 100,
    seed: int = 0,
    full_test: bool = True,
    variants=VARIANTS,
    variant_chars: int | None = None,
    batch: int = 32,
    progress: bool = True,
    figure_chars: int = 6,
    ranker_from=None,
    canonicalise: bool = True,
    join: bool | None = None,
    split=None,
    latin_copies: int = 0,
) -> dict:
    """Scores a checkpoint; writes ``{out_dir}/{name}.json`` and ``{name}_fig3.png``.

    Args:
      checkpoint: bundle folder, training workdir or ``None`` (bundled).
      n_random: characters drawn at random from each of train and test, as
        the paper's 100.
      full_test: also score the whole test split.
      variants: other drawings of the test split (see :func:`rasterise`).
      variant_chars: the first this many test characters for the variants
        (default: all).
      ranker_from: a folder holding a stroke ranker to use in place of the
        checkpoint's own (to score another planner's strokes with it).
      canonicalise: passed to ``jdraw.plan`` (False reproduces Table I as
        measured before canonical inputs existed).
      join: passed to ``jdraw.plan`` (``None``: as the checkpoint says).
      split: passed to ``jdraw.plan`` (``None``: the checkpoint's splitter if it
        has one; a folder: the splitter there).
      latin_copies: also score the Latin dev glyphs (:mod:`jdraw.evaluation.latin`),
        each drawn this many times in each style, under ``"latin_dev"``; 0 skips.

    Each split's entry holds the metrics of the order ``jdraw.plan`` uses by
    default for this checkpoint (the ranker's if it has one) and, under
    ``by_order``, those of every order.
    """
    ks = kanji.load(progress=progress)
    rng = np.random.default_rng(seed)
    own = api.load_ranker(checkpoint)
    rk = api.load_ranker(ranker_from) if ranker_from is not None else own
    orders = ["model", "xy"] + (["ranker"] if rk is not None else [])
    default = "ranker" if own is not None else "model"  # what jdraw.plan does with it
    res: dict = {
        "checkpoint": str(checkpoint) if checkpoint is not None else "bundled default",
        "default_order": default,
        "join": join,
        "split": split if split is None or isinstance(split, bool) else str(split),
    }
    t0 = time.time()
    test = kanji.split_indices(ks, "test")
    sets = {
        "train_random": (
            rng.choice(kanji.split_indices(ks, "train"), n_random, replace=False),
            None,
        ),
        "test_random": (rng.choice(test, n_random, replace=False), None),
    }
    if full_test:
        sets["test_full"] = (test, None)
    for v in variants:
        sets[f"test_{v}"] = (test[:variant_chars] if variant_chars else test, v)
    fig_rows = []
    for key, (idx, style) in sets.items():
        t = time.time()
        demos, inputs, plan = plan_chars(
            ks,
            idx,
            checkpoint,
            batch=batch,
            progress=progress,
            style=style,
            canonicalise=canonicalise,
            join=join,
            split=split,
        )
        plan_s = time.time() - t
        by = {}
        for o in orders:
            p = ranker.reorder(plan, o, rk)
            by[o] = metrics.score(demos, p, inputs, tol=1 if style else 0)
        res[key] = {**by[default], "seconds": plan_s, "by_order": by}
        if key == "test_random":
            p = ranker.reorder(plan, default, rk)
            for d, s in list(zip(demos, p.strokes))[:figure_chars]:
                fig_rows.append(figures.fig3_row(d.target, s))
    if latin_copies:
        from jdraw.evaluation.latin import evaluate_latin

        res["latin_dev"] = evaluate_latin(
            checkpoint,
            copies=latin_copies,
            batch=batch,
            progress=progress,
            canonicalise=canonicalise,
            join=join,
            split=split,
        )
    res["seconds"] = time.time() - t0
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{name}.json").write_text(json.dumps(res, indent=2) + "\n")
    if fig_rows:
        gap = np.full((6, fig_rows[0].shape[1], 3), 255, np.uint8)
        figures.save_png(
            out / f"{name}_fig3.png", np.concatenate([r for f in fig_rows for r in (f, gap)][:-1])
        )
    return res
