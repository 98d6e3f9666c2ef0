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

import time

import cv2
import jax
import jax.numpy as jnp
import numpy as np
import optax
from flax import nnx
from tqdm.auto import tqdm

from jdraw.data import fonts as F
from jdraw.images import reading
from jdraw.images.prepare import prepare


def sketch(rng: np.random.Generator) -> np.ndarray:
    """``uint8 [H, W]`` a random line drawing (lines, circles, boxes, zigzags), dark on white."""
    h, w = (int(v) for v in rng.integers(120, 360, 2))
    img = np.full((h, w), 255, np.uint8)
    t = int(rng.integers(1, 7))
    for _ in range(int(rng.integers(2, 9))):
        kind = int(rng.integers(0, 4))
        p = (rng.random(2) * (w, h)).astype(int)
        if kind == 0:
            q = (rng.random(2) * (w, h)).astype(int)
            cv2.line(img, tuple(map(int, p)), tuple(map(int, q)), 0, t, cv2.LINE_AA)
        elif kind == 1:
            r = int(rng.integers(8, max(9, min(h, w) // 3)))
            cv2.circle(img, tuple(map(int, p)), r, 0, t, cv2.LINE_AA)
        elif kind == 2:
            q = (rng.random(2) * (w, h)).astype(int)
            cv2.rectangle(img, tuple(map(int, p)), tuple(map(int, q)), 0, t, cv2.LINE_AA)
        else:
            pts = (rng.random((int(rng.integers(3, 8)), 2)) * (w, h)).astype(np.int32)
            cv2.polylines(img, [pts], bool(rng.random() < 0.3), 0, t, cv2.LINE_AA)
    return img


def _slant(img: np.ndarray, shear: float) -> np.ndarray:
    """``img`` sheared horizontally (a handwriting slant), white fill."""
    h, w = img.shape
    m = np.array([[1.0, -shear, max(0.0, shear) * h], [0.0, 1.0, 0.0]])
    return cv2.warpAffine(
        img, m, (w + int(abs(shear) * h) + 1, h), borderValue=255, flags=cv2.INTER_LINEAR
    )


def sample(script: str, font: str, rng: np.random.Generator, cfg) -> np.ndarray:
    """One random training drawing of ``script`` set in ``font``: ``uint8 [H, W]``."""
    words = [
        F.random_word(script, rng, font=font) for _ in range(1 + int(rng.random() < cfg.two_words))
    ]
    height = int(rng.integers(cfg.min_height, cfg.max_height + 1))
    pen = float(rng.uniform(0.01, 0.04)) if rng.random() < cfg.marker else 0.0
    direction = "rtl" if script in F.RTL_SCRIPTS else "ltr"
    img = F.render_word(" ".join(words), font, height, pen=pen, direction=direction)
    if rng.random() < cfg.slant:
        img = _slant(img, float(rng.uniform(-0.35, 0.35)))
    return img


def stretch(line: np.ndarray, factor: float) -> np.ndarray:
    """A line image (:func:`reading.line_images`) stretched ``factor`` times along x.

    Fonts and hands differ in how wide their letters are for their height; the
    detector should not learn a script from that alone.
    """
    h, w = line.shape
    out = cv2.resize(line, (max(int(round(w * factor)), 1), h), interpolation=cv2.INTER_AREA)
    return out


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
        img = sketch(rng) if script == "sketch" else sample(script, font, rng, cfg)
        try:
            lines = reading.line_images(prepare(img))
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


def fit(x, y, *, steps: int, batch: int, lr: float, channels, seed: int = 0):
    """Fits a :class:`reading.DirectionNet` on windows ``x [n, H, W] uint8`` and labels ``y [n]``.

    The two classes are sampled equally often. Returns the net and a log.
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

    rng = np.random.default_rng(seed)
    pos, neg = np.flatnonzero(y), np.flatnonzero(~y)
    logs = []
    for s in tqdm(range(steps), desc="fit", unit="step"):
        idx = np.concatenate(
            [rng.choice(pos, batch // 2), rng.choice(neg, batch - batch // 2)]
        )  # fmt: skip
        xb = x[idx].astype(np.float32) / 255.0
        if rng.random() < 0.5:  # ink of any weight: thicken some windows by a pixel
            xb = np.maximum(xb, np.roll(xb, 1, axis=1))
        xb = np.roll(xb, int(rng.integers(-2, 3)), axis=1)  # the line's height is not exact
        params, opt, loss, acc = step(params, opt, xb, y[idx].astype(np.float32))
        if s % 500 == 0 or s == steps - 1:
            logs.append({"step": s, "loss": float(loss), "window_acc": float(acc)})
    nnx.update(net, params)
    return net, logs


def accuracy(net, fonts_by_script: dict, words_per_font: int, cfg, seed: int = 1) -> dict:
    """Fraction of whole drawings :func:`reading.detect` reads right, per script.

    ``words_per_font`` random drawings per font; ``"sketch"``: random sketches.
    """
    rng = np.random.default_rng(seed)
    out = {}
    for script, names in fonts_by_script.items():
        right = total = 0
        for font in names:
            for _ in range(words_per_font):
                img = sketch(rng) if script == "sketch" else sample(script, font, rng, cfg)
                try:
                    got = reading.detect(prepare(img), net)
                except ValueError:  # too little ink left to read
                    continue
                right += got == ("rtl" if script in F.RTL_SCRIPTS else "ltr")
                total += 1
        out[script] = right / max(total, 1)
    return out


def scores(net, fonts_by_script: dict, words_per_font: int, cfg, seed: int) -> dict:
    """``{script: [rtl_score, ...]}`` of random drawings set in each script's fonts."""
    rng = np.random.default_rng(seed)
    out = {}
    for script, names in fonts_by_script.items():
        got = []
        for font in names:
            for _ in range(words_per_font):
                img = sketch(rng) if script == "sketch" else sample(script, font, rng, cfg)
                try:
                    got.append(reading.rtl_score(prepare(img), net))
                except ValueError:  # too little ink left to read
                    continue
        out[script] = got
    return out


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


def train(cfg, workdir) -> dict:
    """Makes examples, fits the detector, sets its threshold, measures it; writes it to ``cfg.out``.

    The threshold comes from drawings in :data:`jdraw.data.fonts.DETECTOR_VAL`
    (fonts neither fitted on nor measured on) and in the training fonts of the
    scripts that have no validation font, drawn with another seed.
    """
    t0 = time.perf_counter()
    per_script = {
        s: cfg.rtl_words_per_script if s in F.RTL_SCRIPTS else cfg.words_per_script
        for s in F.DETECTOR_TRAIN
    }
    x, y, _ = make_examples(F.DETECTOR_TRAIN, per_script, cfg.sketches, cfg, seed=cfg.seed)
    t1 = time.perf_counter()
    net, logs = fit(
        x, y, steps=cfg.steps, batch=cfg.batch, lr=cfg.learning_rate, channels=cfg.channels,
        seed=cfg.seed,
    )  # fmt: skip
    t2 = time.perf_counter()
    val_fonts = {s: F.DETECTOR_VAL.get(s, names) for s, names in F.DETECTOR_TRAIN.items()}
    val_fonts["sketch"] = [None]
    val = scores(net, val_fonts, cfg.val_words_per_font, cfg, seed=cfg.seed + 2)
    net.threshold = choose_threshold(val, cfg.max_false_rtl)
    val_acc = {
        s: float(np.mean((np.array(v) > net.threshold) == (s in F.RTL_SCRIPTS)))
        for s, v in val.items() if v
    }  # fmt: skip
    held = {**F.DETECTOR_EVAL, "sketch": [None]}
    acc = accuracy(net, held, cfg.eval_words_per_font, cfg, seed=cfg.seed + 1)
    t3 = time.perf_counter()
    provenance = {
        "command": f"python train.py --config configs/reading_direction.py --workdir {workdir}",
        "config": cfg.to_dict(),
        "train_fonts": F.DETECTOR_TRAIN,
        "val_fonts": F.DETECTOR_VAL,
        "eval_fonts": F.DETECTOR_EVAL,
        "windows": int(len(x)),
        "rtl_windows": int(y.sum()),
        "log": logs,
        "threshold": net.threshold,
        "val_accuracy": val_acc,
        "held_out_accuracy": acc,
        "seconds": {"examples": round(t1 - t0), "fit": round(t2 - t1), "measure": round(t3 - t2)},
    }
    reading.save(net, cfg.out, provenance)
    return {
        "out": str(cfg.out), "windows": len(x), "log": logs[-1], "threshold": net.threshold,
        "val_accuracy": val_acc, "held_out_accuracy": acc,
    }  # fmt: skip
