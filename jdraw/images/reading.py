"""Reading direction read from the image: is this drawing right-to-left script?

Hebrew and Arabic are written right to left; Latin, Greek, Cyrillic,
Devanagari, Tamil, Hangul, CJK and sketches are planned left to right.
:func:`detect` decides from the ink alone, with no script flag:

1. the drawing's centrelines (:class:`jdraw.images.prepare.Prepared`) are
   grouped into text lines (:func:`jdraw.tiling.layout.text_lines`), each line
   drawn again as 1-pixel lines scaled to ``LINE`` px high
   (:func:`line_images`), so a font's weight, a marker's width and the text's
   size do not matter;
2. a small CNN (:class:`DirectionNet`) scores every window ``WINDOW`` px high
   and the net's ``width`` wide along each line (:func:`windows`);
3. the window logits, weighted by their ink, are pooled into the drawing's
   score (:func:`pool_scores`): their mean (``pool="logit"``), their mean
   probability as a logit (``"prob"``), or their mean times the square root
   of the number of windows (``"evidence"``: a long line of text says more
   than two letters do, as a mean of n noisy votes is sqrt(n) times surer);
   a score above the net's threshold is right to left.

The threshold is part of the trained detector (``direction.json``): the
trainer sets it on drawings in fonts it neither fits nor measures on
(:data:`jdraw.data.fonts.DETECTOR_VAL`), as the lowest mean logit at which
at most ``cfg.max_false_rtl`` of their left-to-right drawings would read right
to left, and never below 0. Reading a kanji or a sketch right to left would
reorder what the planner was built for, so left to right is the prior.
A detector saved without one uses ``THRESHOLD``.

The net is trained on random letters set in fonts of Debian packages
(:mod:`jdraw.train.reading`, ``configs/reading_direction.py``); its weights,
a few KB, are in ``jdraw/assets/reading``.
"""

from __future__ import annotations

import functools
import pathlib

import cv2
import jax
import jax.numpy as jnp
import numpy as np
from flax import nnx

from jdraw.images.prepare import Prepared

WINDOW = 32  # px, height of a window the net sees (and its width, unless the net says)
LINE = 28  # px, height a text line is scaled to (2 px blank above and below)
STRIDE = 16  # px between windows along a line
THRESHOLD = 1.5  # mean window logit above which a drawing reads right to left, if not stored
ASSET = pathlib.Path(__file__).resolve().parent.parent / "assets" / "reading"
DIRECTIONS = ("ltr", "rtl")
POOLS = ("logit", "prob", "evidence")  # how window logits become a drawing's score
SPANS = ("tall", "all")  # what a line image is scaled to fit (see line_images)


class DirectionNet(nnx.Module):
    """3x3 conv layers (one per entry of ``channels``) with 2x2 max pooling, a mean, one logit.

    ``x [B, WINDOW, width]`` float in [0, 1] (ink 1) -> ``[B]`` logits of right to left.
    """

    def __init__(
        self, channels: tuple[int, ...] = (8, 16, 24), threshold: float = THRESHOLD,
        width: int = WINDOW, pool: str = "logit", span: str = "tall", *, rngs: nnx.Rngs,
    ):  # fmt: skip
        if pool not in POOLS:
            raise ValueError(f"pool must be one of {POOLS}, not {pool!r}")
        if span not in SPANS:
            raise ValueError(f"span must be one of {SPANS}, not {span!r}")
        self.channels = tuple(channels)
        self.threshold = float(threshold)  # drawing score above which it is rtl
        self.width = int(width)  # px, width of the windows it reads
        self.pool = pool  # how window logits are pooled into the drawing's score
        self.span = span  # what its line images are scaled to fit (line_images)
        din = (1, *channels[:-1])
        self.convs = nnx.List(
            [nnx.Conv(a, b, (3, 3), padding="SAME", rngs=rngs) for a, b in zip(din, channels)]
        )
        self.out = nnx.Linear(channels[-1], 1, rngs=rngs)

    def __call__(self, x):
        h = x[..., None]
        for conv in self.convs:
            h = jax.nn.relu(conv(h))
            h = nnx.max_pool(h, (2, 2), strides=(2, 2))
        return self.out(jnp.mean(h, axis=(1, 2)))[..., 0]


def _components(prep: Prepared) -> tuple[np.ndarray, list[tuple[float, float, float, float]]]:
    """Ink components of the centrelines: ``labels [H, W]`` (0 background) and their boxes."""
    skel = prep.skeleton.astype(np.uint8)
    n, labels, stats, _ = cv2.connectedComponentsWithStats(skel, connectivity=8)
    boxes = [
        (float(x), float(y), float(x + w - 1), float(y + h - 1)) for x, y, w, h, _ in stats[1:]
    ]
    return labels, boxes


def line_images(prep: Prepared, span: str = "tall") -> list[np.ndarray]:
    """Each text line's centrelines, drawn again ``WINDOW`` px high.

    Args:
      prep: the drawing.
      span: what is scaled to ``LINE`` px: ``"tall"``, the line's letter bodies
        (its tall components' top to bottom; marks beyond it are clipped, as
        the detectors bundled until 2026-12-06 read), or ``"all"``, all its
        ink, so that Arabic dots over and under a word stay in the window
        (and a round dot, one point of centreline, is drawn as a pixel's line).

    Returns:
      ``float32 [WINDOW, w]`` images in [0, 1] (ink 1), one per text line, top
      to bottom, the width scaled as the height.
    """
    if span not in SPANS:
        raise ValueError(f"span must be one of {SPANS}, not {span!r}")
    from jdraw.tiling.layout import piece_of, text_lines

    labels, boxes = _components(prep)
    if not boxes:
        return []
    line_of, spans = text_lines(boxes)
    b = np.asarray(boxes)
    comp_of = [piece_of(p, labels) for p in prep.polylines]
    out = []
    for k, (y0, y1) in enumerate(spans):
        members = np.flatnonzero(line_of == k)
        if not len(members):  # its boxes went to an overlapping line
            continue
        x0, x1 = b[members, 0].min(), b[members, 2].max()
        if span == "all":
            y0, y1 = b[members, 1].min(), b[members, 3].max()
        s = LINE / max(y1 - y0 + 1.0, 1.0)
        # With span "tall", rows beyond the bodies (ascenders, marks) are clipped.
        img = np.zeros((WINDOW, max(int(np.ceil((x1 - x0 + 1) * s)) + 4, WINDOW)), np.uint8)
        shift = np.array([x0, y0]) - (WINDOW - LINE) / 2 / s
        member = set((members + 1).tolist())
        for p, c in zip(prep.polylines, comp_of):
            if c in member:
                q = np.round((p - shift) * s * 4).astype(np.int32)  # 2 fractional bits
                if span == "all" and len(q) == 1:  # a round dot's centreline is one point
                    q = np.concatenate([q, q + 4])
                cv2.polylines(img, [q], False, 255, 1, cv2.LINE_AA, shift=2)
        out.append(img.astype(np.float32) / 255.0)
    return out


def windows(line: np.ndarray, width: int = WINDOW) -> tuple[np.ndarray, np.ndarray]:
    """``width``-px-wide windows along a line image, every ``STRIDE`` px.

    Returns:
      ``(x [n, WINDOW, width] float32, ink [n] float32)``: the windows and the
      ink each holds (its weight in the vote); blank windows are left out.
    """
    if line.shape[1] < width:  # a short line: blank to the right
        line = np.pad(line, ((0, 0), (0, width - line.shape[1])))
    h, w = line.shape
    starts = list(range(0, w - width + 1, STRIDE))
    if starts[-1] + width < w:
        starts.append(w - width)
    x = np.stack([line[:WINDOW, s : s + width] for s in starts])
    ink = x.sum((1, 2))
    keep = ink > 0
    return x[keep], ink[keep]


def drawing_windows(
    prep: Prepared, width: int = WINDOW, span: str = "tall"
) -> tuple[np.ndarray, np.ndarray]:
    """All windows of a drawing's lines and their ink: ``([n, WINDOW, width], [n])``.

    ``span``: as :func:`line_images`.
    """
    parts = [windows(line, width) for line in line_images(prep, span)]
    parts = [p for p in parts if len(p[0])]
    if not parts:
        return np.zeros((0, WINDOW, width), np.float32), np.zeros(0, np.float32)
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


class DirectionEnsemble(nnx.Module):
    """Detectors fitted apart read as one: each window's logit is the mean of theirs.

    ``members``: :class:`DirectionNet` of the same window width and span; their own
    thresholds and poolings are not used. ``threshold`` and ``pool`` are the
    ensemble's, set on the validation fonts as one net's are
    (:func:`jdraw.train.reading.combine`).
    """

    def __init__(self, members, threshold: float = THRESHOLD, pool: str = "logit"):
        members = list(members)
        if not members:
            raise ValueError("an ensemble needs at least one detector")
        if len({(m.width, m.span) for m in members}) > 1:
            raise ValueError("the detectors read different windows (width or span)")
        if pool not in POOLS:
            raise ValueError(f"pool must be one of {POOLS}, not {pool!r}")
        self.members = nnx.List(members)
        self.threshold = float(threshold)
        self.width, self.span, self.pool = members[0].width, members[0].span, pool

    def __call__(self, x):
        return jnp.mean(jnp.stack([m(x) for m in self.members]), axis=0)


@jax.jit
def _logits(graphdef, st, x):
    return nnx.merge(graphdef, st)(x)


def window_logits(net: DirectionNet | DirectionEnsemble, x: np.ndarray) -> np.ndarray:
    """``[n]`` logits of ``x [n, WINDOW, net.width]``, padded to a power of two (few compiles)."""
    if len(x) == 0:
        return np.zeros(0, np.float32)
    g, st = nnx.split(net)
    size = 1 << (len(x) - 1).bit_length()
    pad = np.zeros((size, *x.shape[1:]), np.float32)
    pad[: len(x)] = x
    from jdraw.planner.ranker import net_call

    return np.asarray(net_call(_logits, g, st, pad))[: len(x)]


def pool_scores(logits: np.ndarray, ink: np.ndarray, pool: str = "logit") -> float:
    """A drawing's score from its windows' ``logits`` and ``ink``; ``-inf`` for no window.

    ``"logit"``: the ink-weighted mean logit. ``"prob"``: the ink-weighted mean
    probability, as a logit (clipped to +-20), so that each window's say is bounded.
    ``"evidence"``: the mean logit times ``sqrt(n)``, ``n`` the windows' number
    weighted by ink (``sum(ink)**2 / sum(ink**2)``, n for equal ink).
    """
    if len(logits) == 0:
        return -np.inf
    w = np.asarray(ink, np.float64) / np.sum(ink)
    z = np.asarray(logits, np.float64)
    if pool == "logit":
        return float(np.sum(z * w))
    if pool == "evidence":
        return float(np.sum(z * w) / np.sqrt(np.sum(w * w)))
    if pool == "prob":
        p = np.clip(np.sum(w / (1.0 + np.exp(-np.clip(z, -50, 50)))), 2e-9, 1 - 2e-9)
        return float(np.log(p) - np.log1p(-p))
    raise ValueError(f"pool must be one of {POOLS}, not {pool!r}")


def rtl_score(prep: Prepared, net: DirectionNet | DirectionEnsemble | None = None) -> float:
    """The drawing's score (:func:`pool_scores`): above ``net.threshold`` reads right to left."""
    net = net or load()
    x, ink = drawing_windows(prep, net.width, net.span)
    if len(x) == 0:
        return -np.inf
    return pool_scores(window_logits(net, x), ink, net.pool)


def detect(prep: Prepared, net: DirectionNet | DirectionEnsemble | None = None) -> str:
    """``"rtl"`` or ``"ltr"``: the reading direction of a prepared drawing (see the module doc)."""
    from jdraw import compile_cache

    compile_cache.enable()  # plan_image reads the direction before its first jdraw.plan
    net = net or load()
    return "rtl" if rtl_score(prep, net) > net.threshold else "ltr"


def save(net, out_dir=ASSET, provenance: dict | None = None) -> pathlib.Path:
    """Writes a :class:`DirectionNet` or :class:`DirectionEnsemble`: ``direction.npz``
    and ``direction.json`` (an ensemble's lists each member's ``channels``) in ``out_dir``."""
    from jdraw.model import bundle

    if isinstance(net, DirectionEnsemble):
        sizes = {"members": [list(m.channels) for m in net.members]}
    else:
        sizes = {"channels": list(net.channels)}
    meta = {
        **sizes,
        "threshold": net.threshold,
        "width": net.width,
        "pool": net.pool,
        "span": net.span,
        "provenance": provenance or {},
    }
    return bundle.save_net(net, out_dir, "direction", meta)


def load(folder=None) -> DirectionNet | DirectionEnsemble:
    """The detector stored in ``folder`` (default: the package's ``assets/reading``)."""
    return _load(str(pathlib.Path(folder or ASSET).resolve()))


@functools.lru_cache(maxsize=4)
def _load(folder: str) -> DirectionNet | DirectionEnsemble:
    from jdraw.model import bundle

    def build(meta):
        one = lambda ch: DirectionNet(  # noqa: E731
            ch, meta.get("threshold", THRESHOLD), meta.get("width", WINDOW),
            meta.get("pool", "logit"), meta.get("span", "tall"), rngs=nnx.Rngs(0),
        )  # fmt: skip
        if "members" in meta:
            return DirectionEnsemble([one(ch) for ch in meta["members"]], meta["threshold"],
                                     meta.get("pool", "logit"))  # fmt: skip
        return one(meta["channels"])

    net = bundle.load_net(folder, "direction", build)
    if net is None:
        raise FileNotFoundError(f"no reading-direction detector (direction.json) in {folder}")
    return net
