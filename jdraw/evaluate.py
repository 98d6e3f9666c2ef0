"""Evaluation as the paper's §IV-A: pixel and stroke accuracy on KanjiVG splits."""

from __future__ import annotations

import json
import pathlib
import time

import numpy as np

from jdraw import api, demo, figures, kanji, training


def plan_chars(ks, idx, checkpoint, batch: int = 32, progress: bool = True, max_steps=None):
    """Plans characters ``idx`` (no augmentation) in batches; returns ``(demos, plans)``."""
    from jdraw.types import Plan

    demos = [demo.sample(ks, int(i)) for i in idx]
    it = range(0, len(demos), batch)
    if progress:
        from tqdm import tqdm

        it = tqdm(it, desc="planning", unit="batch")
    parts = []
    for s in it:
        chunk = demos[s : s + batch]
        targets = np.stack([d.target for d in chunk])
        if len(chunk) < batch:  # pad to the compiled batch size
            targets = np.concatenate([targets, np.zeros((batch - len(chunk), 100, 100), bool)])
        p = api.plan(targets, checkpoint=checkpoint, max_steps=max_steps)
        n = len(chunk)
        parts.append(Plan(p.strokes[:n], p.actions[:n], p.lengths[:n], p.truncated[:n]))
    T = max(p.actions.shape[1] for p in parts)
    plan = Plan(
        strokes=[s for p in parts for s in p.strokes],
        actions=np.concatenate(
            [np.pad(p.actions, ((0, 0), (0, T - p.actions.shape[1]), (0, 0))) for p in parts]
        ),
        lengths=np.concatenate([p.lengths for p in parts]),
        truncated=np.concatenate([p.truncated for p in parts]),
    )
    return demos, plan


def evaluate(
    checkpoint=None,
    *,
    out_dir="results",
    name="eval",
    n_random: int = 100,
    seed: int = 0,
    full_test: bool = True,
    batch: int = 32,
    progress: bool = True,
    figure_chars: int = 6,
) -> dict:
    """Scores a checkpoint; writes ``{out_dir}/{name}.json`` and ``{name}_fig3.png``.

    Args:
      checkpoint: bundle folder, training workdir or ``None`` (bundled).
      n_random: characters drawn at random from each of train and test, as
        the paper's 100.
      full_test: also score the whole test split.
    """
    ks = kanji.load(progress=progress)
    rng = np.random.default_rng(seed)
    res: dict = {"checkpoint": str(checkpoint) if checkpoint is not None else "bundled default"}
    t0 = time.time()
    sets = {
        "train_random": rng.choice(kanji.split_indices(ks, "train"), n_random, replace=False),
        "test_random": rng.choice(kanji.split_indices(ks, "test"), n_random, replace=False),
    }
    if full_test:
        sets["test_full"] = kanji.split_indices(ks, "test")
    fig_rows = []
    for key, idx in sets.items():
        t = time.time()
        demos, plan = plan_chars(ks, idx, checkpoint, batch=batch, progress=progress)
        res[key] = {**training.score(demos, plan), "seconds": time.time() - t}
        if key == "test_random":
            for d, s in list(zip(demos, plan.strokes))[:figure_chars]:
                fig_rows.append(figures.fig3_row(d.target, s))
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
