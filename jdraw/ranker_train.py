"""Training the stroke ranker (:mod:`jdraw.ranker`) on the tracer's own strokes.

The tracer (a planner bundle) plans augmented training characters; each drawn
stroke is labelled with the KanjiVG stroke it matches, and the ranker learns
KanjiVG's order and direction from those noisy strokes. The labelled examples
are saved in the workdir as they are made, so an interrupted run resumes
where it stopped; the ranker itself trains in seconds.
"""

from __future__ import annotations

import json
import pathlib
import time

import numpy as np

from jdraw import demo, kanji, ranker


def _chunk_path(workdir: pathlib.Path, kind: str, k: int) -> pathlib.Path:
    return workdir / "examples" / f"{kind}_{k:04d}.npz"


def make_examples(cfg, workdir, progress: bool = True) -> list[pathlib.Path]:
    """Labelled examples in chunks of ``cfg.chunk`` augmented training characters.

    ``cfg.chars`` characters are planned by the tracer (its own noisy
    strokes); ``cfg.get("demo_chars", 0)`` more contribute KanjiVG's strokes
    as they are. One npz per chunk, written whole or not at all.
    """
    from jdraw import api

    workdir = pathlib.Path(workdir)
    (workdir / "examples").mkdir(parents=True, exist_ok=True)
    ks = kanji.load(progress=progress)
    pool = kanji.split_indices(ks, "train")
    jobs = [("demo", k) for k in range(int(np.ceil(cfg.get("demo_chars", 0) / cfg.chunk)))]
    jobs += [("traced", k) for k in range(int(np.ceil(cfg.chars / cfg.chunk)))]
    it = jobs
    if progress:
        from tqdm import tqdm

        it = tqdm(jobs, desc="examples", unit="chunk")
    paths = []
    for kind, k in it:
        path = _chunk_path(workdir, kind, k)
        paths.append(path)
        if path.exists():
            continue
        rng = np.random.default_rng([int(cfg.seed), k, int(kind == "demo")])
        demos = [
            demo.sample(ks, int(rng.choice(pool)), rng, float(cfg.augment))
            for _ in range(cfg.chunk)
        ]
        if kind == "traced":
            targets = np.stack([d.target for d in demos])
            drawn = api.plan(targets, checkpoint=cfg.tracer, order="model").strokes
        else:
            drawn = [d.strokes for d in demos]
        parts = [
            ranker.examples(s, ranker.stroke_masks(d.strokes), d.strokes)
            for d, s in zip(demos, drawn)
        ]
        parts = [p for p in parts if p is not None]
        arrays = [np.concatenate([p[i] for p in parts]) for i in range(5)]
        tmp = path.with_suffix(".tmp.npz")
        np.savez(tmp, *arrays)
        tmp.rename(path)  # a chunk is there whole or not at all
    return paths


def load_examples(paths) -> tuple[np.ndarray, ...]:
    parts = []
    for p in paths:
        with np.load(p) as z:
            parts.append([z[f"arr_{i}"] for i in range(5)])
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(5))


def train(cfg, workdir, progress: bool = True) -> dict:
    """Makes (or reuses) the examples, fits the ranker, writes it into ``cfg.out``."""
    workdir = pathlib.Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "config.json").write_text(cfg.to_json_best_effort(indent=2) + "\n")
    t0 = time.time()
    paths = make_examples(cfg, workdir, progress=progress)
    t1 = time.time()
    data = load_examples(paths)
    model, logs = ranker.train_ranker(
        data,
        steps=int(cfg.steps),
        batch=int(cfg.batch),
        lr=float(cfg.learning_rate),
        seed=int(cfg.seed),
    )
    t2 = time.time()
    result = {
        "pairs": int(len(data[0])),
        "headings": int(len(data[2])),
        "trace_s_this_call": t1 - t0,
        "fit_s": t2 - t1,
        "logs": logs,
    }
    out = ranker.save(model, cfg.out, provenance={"config": json.loads(cfg.to_json()), **result})
    ranker.save(model, workdir / "ranker")
    (workdir / "result.json").write_text(json.dumps(result, indent=2) + "\n")
    result["out"] = str(out)
    return result
