"""Training the reading-direction detector (:mod:`jdraw.images.reading`) on words set in fonts.

Random letter strings of each script are set in the fonts of
:data:`jdraw.data.fonts.DETECTOR_TRAIN` (Hebrew and Arabic: right to left;
Latin print and script, Greek, Cyrillic, Armenian, Georgian, Devanagari,
Bengali, Tamil, Thai, Ethiopic, Hangul, kana and han: left to right), at
random sizes, weights and slants, plus random line sketches (left to right:
a sketch keeps the planner's usual order). Each goes through
:func:`jdraw.images.prepare.prepare`, as ``plan_image`` sees it, and is cut
into line windows; the net learns the word's direction from every window.
:func:`accuracy` measures whole drawings in other fonts
(:data:`jdraw.data.fonts.DETECTOR_EVAL`).
"""

from __future__ import annotations

import hashlib
import json
import pathlib
import time

import jax
import jax.numpy as jnp
import numpy as np
import optax
from flax import nnx
from tqdm.auto import tqdm

from jdraw.data import cjk_faces
from jdraw.data import fonts as F
from jdraw.images import reading
from jdraw.images.prepare import prepare
from jdraw.train.reading_data import (  # noqa: F401 (the drawings; named here too)
    augment,
    cursive_sample,
    print_sample,
    sample,
    stretch,
)


def _jobs(fonts_by_script: dict, words_per_script, sketches: int) -> list:
    """``(script, font)`` per drawing; ``words_per_script``: an int or ``{script: int}``."""
    jobs = []
    for script, names in fonts_by_script.items():
        n = words_per_script if isinstance(words_per_script, int) else words_per_script[script]
        jobs += [(script, names[k % len(names)]) for k in range(n)]
    return jobs + [("sketch", None)] * sketches


def make_examples(fonts_by_script: dict, words_per_script, sketches: int, cfg, seed: int):
    """Windows of random drawings: ``(x [n, W, W] uint8, rtl [n] bool, drawing [n] int)``.

    ``words_per_script``: drawings per script, an int or ``{script: int}``. Each
    drawing's lines are cut into windows as they are and again stretched along
    x by a random factor in ``[1 / cfg.stretch, cfg.stretch]``.
    """
    rng = np.random.default_rng(seed)
    jobs = _jobs(fonts_by_script, words_per_script, sketches)
    xs, ys, gs = [], [], []
    for g, (script, font) in enumerate(tqdm(jobs, desc="drawings", unit="drawing")):
        img = sample(script, font, rng, cfg)
        try:
            lines = reading.line_images(prepare(img), cfg.get("span", "tall"))
        except ValueError:  # a word too small to keep any ink
            continue
        factor = float(np.exp(rng.uniform(-1.0, 1.0) * np.log(cfg.stretch)))
        for line in lines + [stretch(line, factor) for line in lines]:
            x, _ = reading.windows(line, cfg.get("width", reading.WINDOW))
            if not len(x):
                continue
            xs.append(np.round(x * 255).astype(np.uint8))
            ys.append(np.full(len(x), script in F.RTL_SCRIPTS))
            gs.append(np.full(len(x), g))
    return np.concatenate(xs), np.concatenate(ys), np.concatenate(gs)


def fit(
    x, y, *, steps: int, batch: int, lr: float, channels, seed: int = 0,
    augment_strength: float = 0.0, workdir=None, checkpoint_every: int = 500,
    stop_after: int | None = None, elastic: float = 0.0,
):  # fmt: skip
    """Fits a :class:`reading.DirectionNet` on windows ``x [n, H, W] uint8`` and labels ``y [n]``.

    The two classes are sampled equally often, and every batch is distorted
    (:func:`augment`). With ``workdir``, an Orbax checkpoint is written there
    (``fit/``) every ``checkpoint_every`` steps and at the end, and a fit that
    finds one goes on from it, as if it had not stopped (one that finds the last
    step's fits nothing: a rerun only measures). ``stop_after``: stop, with a
    checkpoint, after this many steps of this call. Returns the net and a log.
    """
    net = reading.DirectionNet(tuple(channels), width=x.shape[2], rngs=nnx.Rngs(seed))
    graphdef, params = nnx.split(net, nnx.Param)
    tx = optax.adam(optax.cosine_decay_schedule(lr, steps))
    opt = tx.init(params)

    def loss_fn(params, xb, yb):
        logits = nnx.merge(graphdef, params)(xb)
        loss = jnp.mean(optax.sigmoid_binary_cross_entropy(logits, yb))
        return loss, jnp.mean((logits > 0) == (yb > 0.5))

    @jax.jit
    def step(params, opt, xb, yb):
        (loss, acc), g = jax.value_and_grad(loss_fn, has_aux=True)(params, xb, yb)
        upd, opt = tx.update(g, opt, params)
        return optax.apply_updates(params, upd), opt, loss, acc

    mgr, start, logs = None, 0, []
    if workdir is not None:
        import orbax.checkpoint as ocp

        folder = pathlib.Path(workdir).resolve() / "fit"
        mgr = ocp.CheckpointManager(folder, options=ocp.CheckpointManagerOptions(max_to_keep=1))
        last = mgr.latest_step()
        if last is not None:
            got = mgr.restore(last, args=ocp.args.StandardRestore({"params": params, "opt": opt}))
            params, opt, start = got["params"], got["opt"], last
            logs = json.loads((folder / "log.json").read_text())
    pos, neg = np.flatnonzero(y), np.flatnonzero(~y)
    for s in tqdm(range(start, steps), desc="fit", unit="step", initial=start, total=steps):
        rng = np.random.default_rng([seed, s])  # each step's batch: the same after a resume
        idx = np.concatenate(
            [rng.choice(pos, batch // 2), rng.choice(neg, batch - batch // 2)]
        )  # fmt: skip
        xb = augment(x[idx].astype(np.float32) / 255.0, rng, augment_strength, elastic)
        params, opt, loss, acc = step(params, opt, xb, y[idx].astype(np.float32))
        if s % 500 == 0 or s == steps - 1:
            logs.append({"step": s, "loss": float(loss), "window_acc": float(acc)})
        done, stop = s + 1, stop_after is not None and s + 1 - start >= stop_after
        if mgr is not None and (done % checkpoint_every == 0 or done == steps or stop):
            import orbax.checkpoint as ocp

            mgr.save(done, args=ocp.args.StandardSave({"params": params, "opt": opt}))
            mgr.wait_until_finished()
            (folder / "log.json").write_text(json.dumps(logs))
        if stop:
            break
    nnx.update(net, params)
    return net, logs


def accuracy(net, fonts_by_script: dict, words_per_font: int, cfg, seed: int = 1) -> dict:
    """Fraction of whole drawings :func:`reading.detect` reads right, per script.

    ``words_per_font`` random drawings per font; ``"sketch"``: random sketches.
    The scores are :func:`scores`' in the net's pooling; a drawing with no
    window scores ``-inf`` and so reads left to right, as ``detect`` does.
    """
    by_script = scores(net, fonts_by_script, words_per_font, cfg, seed, (net.pool,))[net.pool]
    return {
        s: float(np.mean((np.array(v) > net.threshold) == (s in F.RTL_SCRIPTS))) if v else 0.0
        for s, v in by_script.items()
    }  # fmt: skip


def scores(net, fonts_by_script: dict, words_per_font: int, cfg, seed: int, pools) -> dict:
    """``{pool: {script: [rtl_score, ...]}}`` of random drawings set in each script's fonts.

    ``pools``: names from :data:`reading.POOLS`; every pooling scores the same
    drawings. A drawing too small to keep any ink is left out.
    """
    rng = np.random.default_rng(seed)
    out = {p: {} for p in pools}
    for script, names in fonts_by_script.items():
        got = {p: [] for p in pools}
        for font in names:
            for _ in range(words_per_font):
                img = sample(script, font, rng, cfg)
                try:
                    x, ink = reading.drawing_windows(prepare(img), net.width, net.span)
                except ValueError:  # too little ink left to read
                    continue
                z = reading.window_logits(net, x)
                for p in pools:
                    got[p].append(reading.pool_scores(z, ink, p))
        for p in pools:
            out[p][script] = got[p]
    return out


def _recall(by_script: dict, threshold: float) -> float:
    """Fraction of right-to-left drawings in ``by_script`` scoring above ``threshold``."""
    rtl = [v for s, got in by_script.items() if s in F.RTL_SCRIPTS for v in got]
    return float(np.mean(np.array(rtl) > threshold)) if rtl else 0.0


def _accuracy_at(by_script: dict, threshold: float) -> dict:
    """Each script's fraction of drawings read right (right to left above ``threshold``)."""
    return {
        s: float(np.mean((np.array(v) > threshold) == (s in F.RTL_SCRIPTS)))
        for s, v in by_script.items() if v
    }  # fmt: skip


def _summary(by_script: dict) -> dict:
    """Each script's score quantiles (min, 10%, median, 90%, max), rounded."""
    qs = [0.0, 0.1, 0.5, 0.9, 1.0]
    return {
        s: [round(float(q), 2) for q in np.quantile(np.array(v)[np.isfinite(v)], qs)]
        for s, v in by_script.items() if np.isfinite(v).any()
    }  # fmt: skip


def choose_threshold(by_script: dict, max_false_rtl: float) -> float:
    """The lowest mean logit at which at most ``max_false_rtl`` of left-to-right drawings read rtl.

    ``by_script``: :func:`scores` of validation drawings. Never below 0 (a
    mean window probability of one half).
    """
    ltr = np.sort([v for s, got in by_script.items() if s not in F.RTL_SCRIPTS for v in got])
    ltr = ltr[np.isfinite(ltr)]
    if not len(ltr):
        return reading.THRESHOLD
    allowed = int(np.floor(max_false_rtl * len(ltr)))  # drawings that may score above
    return float(max(ltr[len(ltr) - 1 - allowed], 0.0))


def _font_splits(cfg) -> tuple[dict, dict, dict]:
    """``{script: fonts}`` to fit on, to set the threshold on, and to measure on.

    With ``cfg.cursive_words``, ``"cursive"`` (:func:`cursive_sample`) joins
    each, its "fonts" the cursive word splits: train, val and test; with
    ``cfg.print_words``, ``"print"`` (:func:`print_sample`, the school glyphs of
    the planner's training split) joins the first; with ``cfg.more_cjk``, the CJK
    faces of :data:`jdraw.data.cjk_faces.DETECTOR_MORE_TRAIN` join the first too.
    """
    train = dict(F.DETECTOR_TRAIN)
    val = {s: F.DETECTOR_VAL.get(s, names) for s, names in F.DETECTOR_TRAIN.items()}
    if cfg.get("more_cjk", False):  # more CJK faces to fit on
        train.update({s: train[s] + more for s, more in cjk_faces.DETECTOR_MORE_TRAIN.items()})
    held = dict(F.DETECTOR_EVAL)
    if cfg.get("cursive_words", 0):
        train["cursive"], val["cursive"], held["cursive"] = ["train"], ["val"], ["test"]
    if cfg.get("print_words", 0):  # fitted on only: the validation fonts have a printing hand
        train["print"] = ["train"]
    val["sketch"] = held["sketch"] = [None]
    return train, val, held


def _cached_examples(cfg, workdir, per_script: dict, fonts_by_script=None):
    """:func:`make_examples` of the training fonts, kept in ``workdir/examples-<hash>.npz``.

    They take most of a run's making time; a rerun (an interrupted fit, another
    fit setting) with the same data settings (the hash) reads them back.
    """
    keys = (
        "seed", "words_per_script", "rtl_words_per_script", "sketches", "min_height",
        "max_height", "two_words", "marker", "slant", "stretch", "width",
    )  # fmt: skip
    fonts_by_script = fonts_by_script or F.DETECTOR_TRAIN
    want = {k: cfg.get(k) for k in keys} | {"fonts": fonts_by_script}
    if cfg.get("cursive_words", 0):
        want["cursive_words"] = cfg.cursive_words
    if cfg.get("print_words", 0):
        want["print_words"] = cfg.print_words
    if cfg.get("span", "tall") != "tall":  # older workdirs' examples keep their names
        want["span"] = cfg.span
    tag = hashlib.sha256(json.dumps(want, sort_keys=True).encode()).hexdigest()[:16]
    path = pathlib.Path(workdir) / f"examples-{tag}.npz"
    if path.exists():
        with np.load(path) as z:
            return z["x"], z["y"]
    x, y, _ = make_examples(fonts_by_script, per_script, cfg.sketches, cfg, seed=cfg.seed)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.npz")
    np.savez(tmp, x=x, y=y)
    tmp.replace(path)
    return x, y


def combine(cfg, folders, out) -> dict:
    """Detectors fitted apart (trainers' ``out`` folders) written to ``out`` as one.

    A :class:`reading.DirectionEnsemble` of them, pooled by mean logit; its
    threshold is set on the validation drawings as :func:`train` sets one
    detector's (``cfg.max_false_rtl``, the same seed), and it is measured on the
    held-out fonts. Returns the summary :func:`train` returns.
    """
    t0 = time.perf_counter()
    nets = [reading.load(f) for f in folders]
    net = reading.DirectionEnsemble(nets, pool="logit")
    _, val_fonts, held = _font_splits(cfg)
    val = scores(net, val_fonts, cfg.val_words_per_font, cfg, cfg.seed + 2, ("logit",))["logit"]
    net.threshold = choose_threshold(val, cfg.max_false_rtl)
    recall = _recall(val, net.threshold)
    val_acc = _accuracy_at(val, net.threshold)
    acc = accuracy(net, held, cfg.eval_words_per_font, cfg, seed=cfg.seed + 1)
    members = [json.loads((pathlib.Path(f) / "direction.json").read_text()) for f in folders]
    provenance = {
        "config": cfg.to_dict(),
        "members": [m.get("provenance", {}) for m in members],
        "threshold": net.threshold,
        "pool": net.pool,
        "val_rtl_recall": recall,
        "val_scores": _summary(val),
        "val_accuracy": val_acc,
        "held_out_accuracy": acc,
        "seconds": {"measure": round(time.perf_counter() - t0)},
    }
    reading.save(net, out, provenance)
    return {
        "out": str(out), "members": len(nets), "threshold": net.threshold, "pool": net.pool,
        "val_rtl_recall": recall, "val_accuracy": val_acc, "held_out_accuracy": acc,
    }  # fmt: skip


def train(cfg, workdir) -> dict:
    """Makes examples, fits the detector, sets its threshold, measures it; writes it to ``cfg.out``.

    With ``cfg.members`` (seeds), one detector is made per seed, each in its own
    ``workdir/seed<s>`` (so each resumes on its own), and they are written to
    ``cfg.out`` as one (:func:`combine`).

    The threshold and the pooling (:data:`reading.POOLS`; ``cfg.pool``, or
    ``"choose"``: the one that reads more right-to-left validation drawings
    right to left at its threshold) come from drawings in
    :data:`jdraw.data.fonts.DETECTOR_VAL` (fonts neither fitted on nor measured
    on) and in the training fonts of the scripts that have no validation font,
    drawn with another seed.
    """
    if cfg.get("members"):
        folders = []
        for seed in cfg.members:
            one = cfg.copy_and_resolve_references()
            one.seed, one.members = int(seed), ()
            one.out = str(pathlib.Path(workdir) / f"seed{seed}" / "out")
            if not (pathlib.Path(one.out) / "direction.json").exists():
                train(one, pathlib.Path(workdir) / f"seed{seed}")
            folders.append(one.out)
        return combine(cfg, folders, cfg.out)
    t0 = time.perf_counter()
    train_fonts, val_fonts, held = _font_splits(cfg)
    per_script = {
        s: cfg.rtl_words_per_script if s in F.RTL_SCRIPTS else cfg.words_per_script
        for s in train_fonts
    }
    if "cursive" in train_fonts:
        per_script["cursive"] = cfg.cursive_words
    if "print" in train_fonts:
        per_script["print"] = cfg.print_words
    x, y = _cached_examples(cfg, workdir, per_script, train_fonts)
    t1 = time.perf_counter()
    net, logs = fit(
        x, y, steps=cfg.steps, batch=cfg.batch, lr=cfg.learning_rate, channels=cfg.channels,
        seed=cfg.seed, augment_strength=cfg.get("augment", 0.0), workdir=workdir,
        elastic=cfg.get("elastic", 0.0),
    )  # fmt: skip
    t2 = time.perf_counter()
    net.span = cfg.get("span", "tall")
    pool = cfg.get("pool", "logit")
    by_pool = scores(net, val_fonts, cfg.val_words_per_font, cfg, cfg.seed + 2, reading.POOLS)
    cut = {p: choose_threshold(v, cfg.max_false_rtl) for p, v in by_pool.items()}
    recall = {p: _recall(by_pool[p], cut[p]) for p in by_pool}
    if pool == "choose":
        pool = max(reading.POOLS, key=lambda p: (recall[p], p == "logit"))
    net.pool, net.threshold = pool, cut[pool]
    val = by_pool[pool]
    val_acc = _accuracy_at(val, net.threshold)
    acc = accuracy(net, held, cfg.eval_words_per_font, cfg, seed=cfg.seed + 1)
    t3 = time.perf_counter()
    provenance = {
        "command": f"python train.py --config configs/reading_direction.py --workdir {workdir}",
        "config": cfg.to_dict(),
        "train_fonts": train_fonts,
        "val_fonts": val_fonts,
        "eval_fonts": held,
        "windows": int(len(x)),
        "rtl_windows": int(y.sum()),
        "log": logs,
        "threshold": net.threshold,
        "pool": net.pool,
        "val_thresholds": cut,
        "val_rtl_recall": recall,
        "val_scores": {p: _summary(v) for p, v in by_pool.items()},
        "val_accuracy": val_acc,
        "held_out_accuracy": acc,
        "seconds": {"examples": round(t1 - t0), "fit": round(t2 - t1), "measure": round(t3 - t2)},
    }
    reading.save(net, cfg.out, provenance)
    return {
        "out": str(cfg.out), "windows": len(x), "log": logs[-1], "threshold": net.threshold,
        "pool": net.pool, "val_rtl_recall": recall, "val_accuracy": val_acc,
        "held_out_accuracy": acc,
    }  # fmt: skip
