"""Reading direction read from the image: is this drawing right-to-left script?

Hebrew and Arabic are written right to left; Latin, Greek, Cyrillic,
Devanagari, Tamil, Hangul, CJK and sketches are planned left to right.
:func:`detect` decides from the ink alone, with no script flag:

1. the drawing's centrelines (:class:`jdraw.images.prepare.Prepared`) are
   grouped into text lines (:func:`jdraw.tiling.layout.text_lines`), each line
   drawn again as 1-pixel lines scaled to ``LINE`` px high
   (:func:`line_images`), so a font's weight, a marker's width and the text's
   size do not matter;
2. a small CNN (:class:`DirectionNet`) scores every ``WINDOW x WINDOW`` window
   along each line (:func:`windows`);
3. the window logits, weighted by their ink, are averaged; a mean above
   ``THRESHOLD`` is right to left.

The threshold is a prior for left to right: reading a kanji or a sketch right
to left would reorder what the planner was built for, so the windows must
agree clearly (``THRESHOLD = 1.5``, a mean window probability of about 0.8).
It was set so that the four drawings of ``examples/images`` (a kanji, a
cursive word, a sentence, a sketch), which scored up to 1.18, stay left to
right; the right-to-left benchmark (``bench/rtl_words.py``) was not consulted.

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

WINDOW = 32  # px, side of a window the net sees
LINE = 28  # px, height a text line is scaled to (2 px blank above and below)
STRIDE = 16  # px between windows along a line
THRESHOLD = 1.5  # mean window logit above which a drawing reads right to left
ASSET = pathlib.Path(__file__).resolve().parent.parent / "assets" / "reading"
DIRECTIONS = ("ltr", "rtl")


class DirectionNet(nnx.Module):
    """Three 3x3 conv layers with 2x2 max pooling, a global mean and one logit.

    ``x [B, WINDOW, WINDOW]`` float in [0, 1] (ink 1) -> ``[B]`` logits of right to left.
    """

    def __init__(self, channels: tuple[int, ...] = (8, 16, 24), *, rngs: nnx.Rngs):
        self.channels = tuple(channels)
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


def _component_of(points: np.ndarray, labels: np.ndarray) -> int:
    """The component most of a polyline's vertices lie on (its ends may lie off the skeleton)."""
    h, w = labels.shape
    q = np.round(points).astype(int)
    got = labels[np.clip(q[:, 1], 0, h - 1), np.clip(q[:, 0], 0, w - 1)]
    got = got[got > 0]
    return int(np.bincount(got).argmax()) if len(got) else 0


def line_images(prep: Prepared) -> list[np.ndarray]:
    """Each text line's centrelines, drawn again ``WINDOW`` px high.

    Returns:
      ``float32 [WINDOW, w]`` images in [0, 1] (ink 1), one per text line, top
      to bottom; the line's span (its tall components' top to bottom) is
      scaled to ``LINE`` px, its width likewise.
    """
    from jdraw.tiling.layout import text_lines

    labels, boxes = _components(prep)
    if not boxes:
        return []
    line_of, spans = text_lines(boxes)
    b = np.asarray(boxes)
    comp_of = [_component_of(p, labels) for p in prep.polylines]
    out = []
    for k, (y0, y1) in enumerate(spans):
        members = np.flatnonzero(line_of == k)
        if not len(members):  # its boxes went to an overlapping line
            continue
        x0, x1 = b[members, 0].min(), b[members, 2].max()
        s = LINE / max(y1 - y0 + 1.0, 1.0)
        # Rows beyond the line's span (ascenders, marks) are clipped to the window.
        img = np.zeros((WINDOW, max(int(np.ceil((x1 - x0 + 1) * s)) + 4, WINDOW)), np.uint8)
        shift = np.array([x0, y0]) - (WINDOW - LINE) / 2 / s
        member = set((members + 1).tolist())
        for p, c in zip(prep.polylines, comp_of):
            if c in member:
                q = np.round((p - shift) * s * 4).astype(np.int32)  # 2 fractional bits
                cv2.polylines(img, [q], False, 255, 1, cv2.LINE_AA, shift=2)
        out.append(img.astype(np.float32) / 255.0)
    return out


def windows(line: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``WINDOW``-wide windows along a line image, every ``STRIDE`` px.

    Returns:
      ``(x [n, WINDOW, WINDOW] float32, ink [n] float32)``: the windows and the
      ink each holds (its weight in the vote); blank windows are left out.
    """
    h, w = line.shape
    starts = list(range(0, max(w - WINDOW, 0) + 1, STRIDE))
    if starts[-1] + WINDOW < w:
        starts.append(w - WINDOW)
    x = np.stack([line[:WINDOW, s : s + WINDOW] for s in starts])
    ink = x.sum((1, 2))
    keep = ink > 0
    return x[keep], ink[keep]


def drawing_windows(prep: Prepared) -> tuple[np.ndarray, np.ndarray]:
    """All windows of a drawing's lines and their ink: ``([n, WINDOW, WINDOW], [n])``."""
    parts = [windows(line) for line in line_images(prep)]
    parts = [p for p in parts if len(p[0])]
    if not parts:
        return np.zeros((0, WINDOW, WINDOW), np.float32), np.zeros(0, np.float32)
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


@jax.jit
def _logits(graphdef, st, x):
    return nnx.merge(graphdef, st)(x)


def window_logits(net: DirectionNet, x: np.ndarray) -> np.ndarray:
    """``[n]`` logits of ``x [n, WINDOW, WINDOW]``, padded to a power of two (few compiles)."""
    if len(x) == 0:
        return np.zeros(0, np.float32)
    g, st = nnx.split(net)
    size = 1 << (len(x) - 1).bit_length()
    pad = np.zeros((size, WINDOW, WINDOW), np.float32)
    pad[: len(x)] = x
    return np.asarray(_logits(g, st, pad))[: len(x)]


def rtl_score(prep: Prepared, net: DirectionNet | None = None) -> float:
    """Mean window logit, weighted by ink: above ``THRESHOLD`` reads right to left."""
    net = net or load()
    x, ink = drawing_windows(prep)
    if len(x) == 0:
        return -np.inf
    return float(np.sum(window_logits(net, x) * ink) / np.sum(ink))


def detect(prep: Prepared, net: DirectionNet | None = None) -> str:
    """``"rtl"`` or ``"ltr"``: the reading direction of a prepared drawing (see the module doc)."""
    from jdraw import compile_cache

    compile_cache.enable()  # plan_image reads the direction before its first jdraw.plan
    return "rtl" if rtl_score(prep, net) > THRESHOLD else "ltr"


def save(net: DirectionNet, out_dir=ASSET, provenance: dict | None = None) -> pathlib.Path:
    """Writes ``direction.npz`` and ``direction.json`` into ``out_dir``."""
    from jdraw.model import bundle

    meta = {"channels": list(net.channels), "provenance": provenance or {}}
    return bundle.save_net(net, out_dir, "direction", meta)


def load(folder=None) -> DirectionNet:
    """The detector stored in ``folder`` (default: the package's ``assets/reading``)."""
    return _load(str(pathlib.Path(folder or ASSET).resolve()))


@functools.lru_cache(maxsize=4)
def _load(folder: str) -> DirectionNet:
    from jdraw.model import bundle

    net = bundle.load_net(
        folder, "direction", lambda m: DirectionNet(tuple(m["channels"]), rngs=nnx.Rngs(0))
    )
    if net is None:
        raise FileNotFoundError(f"no reading-direction detector (direction.json) in {folder}")
    return net
