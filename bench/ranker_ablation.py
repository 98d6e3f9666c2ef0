"""What each change to the stroke ranker buys: width, the drawing's context, other scripts.

  PYTHONPATH=. python bench/ranker_ablation.py [--workdir runs/ranker_ablation]
      [--fits kanji64,mix64,mix128,ctx128] [--seeds 0,1] [--splits val] [--arabic 8]

Traces the default ranker config's examples once (``configs/default.py``'s
``ranker`` stage, the bundled default as tracer: KanjiVG's 600 traced and 2,500
demonstrated characters, 2,000 Latin letters, 400 cursive fragments, 1,000 printed
words; chunks are
saved in the workdir, so a second run reuses them), fits one ranker per fit and
seed, and scores each by reordering the same plans: the bundled default's
strokes (its tracer and splitter, ``order="model"``) of the KanjiVG ``--splits``
(1,000 characters each) and of the Latin dev glyphs drawn four times (clean lines),
planned once and kept in the workdir. This is what ``eval.py`` does after
planning, so a ranker's figures here equal its ``eval.py`` figures for the same
strokes. Choose by the KanjiVG val split; the Latin dev split is only reported.

Fits: ``kanji64`` (KanjiVG only, 64 wide, no context: the ranker before
2026-12-04), ``kanji128``, ``mix64`` and ``mix128`` (KanjiVG, Latin letters and
cursive, no context), ``ctx64`` and ``ctx128`` (the same sets, with the drawing's
context: the default); ``words128`` adds 1,000 printed Latin words
(:func:`jdraw.data.latin.words`), ``heads128`` gives cursive 15% and Latin letters
10% of every batch's headings (``heading_shares``), ``wheads128`` both (the
default); ``wcur30`` gives cursive 30%, ``wcur30w`` printed words 10% more;
``pfx`` adds 400 cursive fragments stopped part-way through their writing
(:func:`jdraw.data.cursive.prefixes`) with 15% of the headings, ``pfxh`` splits
cursive's 15% between them. ``--ensembles 2,3`` also scores each fit's first 2 and 3
seeds' rankers as one (:func:`jdraw.planner.ranker.ensemble`, as the default's
``members``).

``--arabic N``: also plan our Arabic words (``bench/rtl_words.py``, N words a
font, the right-to-left hint) with each ranker in a copy of the default bundle,
and report the share whose first stroke starts in the rightmost letter and the
rank correlation of stroke order with x; in the held-out fonts, or in the
detector's validation fonts with ``--arabic-fonts val``.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import pickle
import shutil
import sys

import numpy as np

from configs import default
from jdraw.data import demos as D
from jdraw.data import kanji, latin
from jdraw.evaluation import evaluate, metrics
from jdraw.evaluation import latin as latin_eval
from jdraw.evaluation.batched import plan_batched
from jdraw.model import bundle
from jdraw.planner import ranker
from jdraw.train import ranker as ranker_train

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import rtl_words  # noqa: E402 (bench/rtl_words.py, beside this script)

MIX = ("kanji", "latin", "cursive")
HEADS = {"cursive": 0.15, "latin": 0.1}  # heads128's shares of a batch's headings
CUR30 = {"cursive": 0.3, "latin": 0.1}
FITS = {  # name: (sets, hidden, context, heading shares)
    "kanji64": (("kanji",), 64, False, None),
    "kanji128": (("kanji",), 128, False, None),
    "mix64": (MIX, 64, False, None),
    "mix128": (MIX, 128, False, None),
    "ctx64": (MIX, 64, True, None),
    "ctx128": (MIX, 128, True, None),
    "words128": ((*MIX, "latin_words"), 128, True, None),
    "heads128": (MIX, 128, True, HEADS),
    "wheads128": ((*MIX, "latin_words"), 128, True, HEADS),
    "wcur30": ((*MIX, "latin_words"), 128, True, CUR30),
    "wcur30w": ((*MIX, "latin_words"), 128, True, {**CUR30, "latin_words": 0.1}),
    "pfx": ((*MIX, "latin_words", "cursive_prefix"), 128, True, {**HEADS, "cursive_prefix": 0.15}),
    "pfxh": (
        (*MIX, "latin_words", "cursive_prefix"),
        128,
        True,
        {"cursive": 0.075, "cursive_prefix": 0.075, "latin": 0.1},
    ),
}
PREFIX_CHARS = 400  # fragments stopped part-way (jdraw.data.cursive.prefixes), where a fit asks


def arabic(model, work: pathlib.Path, words: int, tag: str, fonts: str = "eval") -> list:
    """``[first, rho]`` of Arabic words planned right to left with ``model`` as the ranker
    (in a copy of the default bundle, ``work/bundle_<tag>``: bundles are cached by folder)."""
    b = work / f"bundle_{tag}"
    shutil.rmtree(b, ignore_errors=True)
    shutil.copytree(bundle.DEFAULT_BUNDLE, b)
    ranker.save(model, b)
    table = rtl_words.F.DETECTOR_VAL if fonts == "val" else rtl_words.F.DETECTOR_EVAL
    r = rtl_words.measure("arabic", words, np.random.default_rng(0), "rtl", str(b), table)
    return [round(r["first"], 3), round(r["rho"], 3)]


def plans(work: pathlib.Path, splits) -> dict:
    """``{name: (demos, inputs or None, plan)}`` of the default's strokes, made once."""
    ks, out = kanji.load(progress=False), {}
    for split in splits:
        f = work / f"plans_kanji_{split}.pkl"
        if not f.exists():
            idx = kanji.split_indices(ks, split)
            f.write_bytes(pickle.dumps(evaluate.plan_chars(ks, idx, None, progress=True)[2]))
        idx = kanji.split_indices(ks, split)
        out[f"kanji {split}"] = (
            [D.sample(ks, int(i)) for i in idx],
            None,
            pickle.loads(f.read_bytes()),
        )
    demos, inputs = latin_eval.drawings(latin.load("dev"), 4, "clean")
    f = work / "plans_latin_dev.pkl"
    if not f.exists():
        f.write_bytes(pickle.dumps(plan_batched(inputs, None, batch=32, progress=True)))
    out["latin dev"] = (demos, inputs, pickle.loads(f.read_bytes()))
    return out


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--workdir", default="runs/ranker_ablation")
    p.add_argument("--fits", default=",".join(FITS))
    p.add_argument("--seeds", default="0,1")
    p.add_argument("--splits", default="val", help="KanjiVG splits to score (val, test)")
    p.add_argument("--arabic", type=int, default=0, help="Arabic words per font (0: none)")
    p.add_argument("--arabic-fonts", default="eval", choices=("eval", "val"))
    p.add_argument(
        "--ensembles", default="", help="also score the first k seeds' rankers as one, e.g. 2,3"
    )
    a = p.parse_args(argv)
    work = pathlib.Path(a.workdir)
    cfg = default.ranker()
    cfg.tracer, cfg.out = str(bundle.DEFAULT_BUNDLE), str(work / "out")
    if any("cursive_prefix" in FITS[f][0] for f in a.fits.split(",")):
        cfg.extra = {**cfg.extra.to_dict(), "cursive_prefix": PREFIX_CHARS}
    paths = ranker_train.make_examples(cfg, work)
    names = [j[0] for j in ranker_train.chunk_jobs(cfg)]
    groups = ranker_train.set_groups(paths, names)[0]
    print({n: int((groups == n).sum()) for n in sorted(set(names))}, "pairs")
    sets = plans(work, a.splits.split(","))
    rows = {}
    for fit in a.fits.split(","):
        kinds, hidden, context, heads = FITS[fit]
        keep = [i for i, n in enumerate(names) if n in kinds]
        kept = [paths[i] for i in keep]
        sub = ranker_train.load_examples(kept, context=True)
        draw = None
        if heads:
            draw = ranker_train.heading_shares(kept, [names[i] for i in keep], heads)
        fitted = []
        for seed in (int(s) for s in a.seeds.split(",")):
            model, _ = ranker_train.train_ranker(
                sub,
                steps=int(cfg.steps),
                batch=int(cfg.batch),
                lr=float(cfg.learning_rate),
                seed=seed,
                context=context,
                hidden=hidden,
                heading_draw=draw,
            )
            fitted.append(model)
            rows[f"{fit} seed {seed}"] = score(model, sets, a, work, f"{fit}_{seed}")
        for k in (int(v) for v in a.ensembles.split(",") if v):
            if k <= len(fitted):  # the first k seeds' rankers as one (their mean scores)
                rows[f"{fit} seeds 1st {k}"] = score(
                    ranker.ensemble(fitted[:k]), sets, a, work, f"{fit}_first{k}"
                )
    (work / "results.json").write_text(json.dumps(rows, indent=1) + "\n")


def score(model, sets: dict, a, work: pathlib.Path, tag: str) -> dict:
    """Order over all pairs and direction of every set reordered by ``model``; Arabic words."""
    row = {}
    for name, (demos, inputs, plan) in sets.items():
        r = metrics.score(demos, ranker.reorder(plan, "ranker", model), inputs)
        row[name] = [round(r["order_all_pairs"], 4), round(r["direction_agreement"], 4)]
    if a.arabic:
        row["arabic rtl: first, rho"] = arabic(model, work, a.arabic, tag, a.arabic_fonts)
    print(f"{tag}: order over all pairs, direction:", json.dumps(row), flush=True)
    return row


if __name__ == "__main__":
    main()
