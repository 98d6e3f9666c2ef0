"""Synthetic inputs with known centrelines, and how close planned strokes lie to them.

Test fixtures (also used by ``examples/make_gallery.py`` and
``examples/tiling_check.py``): photo-like images drawn from known pen
centrelines, text set in a Hershey stroke font, and precision / recall of
strokes against the centrelines.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np
from scipy.spatial import cKDTree
from skimage import morphology

from jdraw.images.skeleton import skeleton_polylines


def photo_like(
    centrelines: Sequence[np.ndarray],
    shape: tuple[int, int],
    *,
    width: float = 6.0,
    light_ink: bool = False,
    gradient: float = 0.5,
    noise: float = 0.05,
    seed: int = 0,
) -> np.ndarray:
    """A photo-like image of pen strokes with known centrelines, for tests and demos.

    The strokes are drawn anti-aliased at sub-pixel precision with round caps,
    the page is lit by a linear gradient (brightness falls by ``gradient`` of
    its peak across the image) plus a soft blotch, and Gaussian noise is added.

    Args:
      centrelines: ``[n, 2]`` float (x, y) polylines in pixels.
      shape: ``(H, W)``.
      width: stroke width, pixels.
      light_ink: chalk on a board instead of ink on paper.
      gradient: fraction of the brightness lost across the image.
      noise: standard deviation of the added noise, in ``[0, 1]`` brightness.

    Returns:
      ``uint8 [H, W]``.
    """
    h, w = shape
    shift = 4
    cover = np.zeros(shape, np.uint8)
    for line in centrelines:
        p = np.round(np.asarray(line, np.float64) * (1 << shift)).astype(np.int32).reshape(-1, 1, 2)
        thickness = max(1, int(round(width)))
        cv2.polylines(cover, [p], False, 255, thickness, cv2.LINE_AA, shift)
    a = cover.astype(np.float32) / 255
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    angle = rng.uniform(0, 2 * np.pi)
    ramp = (np.cos(angle) * xx / w + np.sin(angle) * yy / h) + 1.0
    ramp = ramp / max(float(ramp.max()), 1e-6)
    cx, cy = rng.uniform(0, w), rng.uniform(0, h)
    blotch = np.exp(-((xx - cx) ** 2 + (yy - cy) ** 2) / (2 * (0.3 * max(h, w)) ** 2))
    light = 1.0 - gradient * (1.0 - ramp) - 0.1 * blotch
    if light_ink:
        ground, ink = 0.25 * light, 0.9 * light
    else:
        ground, ink = 0.95 * light, 0.15 * light
    img = ground * (1 - a) + ink * a + rng.normal(0.0, noise, shape).astype(np.float32)
    return (np.clip(img, 0, 1) * 255).round().astype(np.uint8)


def centreline_scores(
    strokes: Sequence[np.ndarray], reference: Sequence[np.ndarray], tol: float = 4.0
) -> tuple[float, float]:
    """Precision and recall of drawn strokes against reference centrelines.

    Both are sampled every 0.25 pixel; precision is the fraction of stroke
    samples within ``tol`` pixels of a reference sample, recall the fraction
    of reference samples within ``tol`` of a stroke sample.
    """
    a, b = _sample(strokes), _sample(reference)
    if len(a) == 0 or len(b) == 0:
        return 0.0, 0.0
    precision = float(np.mean(cKDTree(b).query(a, distance_upper_bound=tol)[0] <= tol))
    recall = float(np.mean(cKDTree(a).query(b, distance_upper_bound=tol)[0] <= tol))
    return precision, recall


def _sample(lines: Sequence[np.ndarray], step: float = 0.25) -> np.ndarray:
    out = []
    for line in lines:
        p = np.asarray(line, np.float64).reshape(-1, 2)
        out.append(p[:1])
        for a, b in zip(p[:-1], p[1:], strict=True):
            n = max(1, int(np.ceil(np.hypot(*(b - a)) / step)))
            t = np.arange(1, n + 1)[:, None] / n
            out.append(a + t * (b - a))
    return np.concatenate(out) if out else np.zeros((0, 2))


def text_centrelines(
    text: str, font_scale: float, *, script: bool = True, margin: float = 0.3
) -> tuple[list[np.ndarray], tuple[int, int]]:
    """Centrelines of ``text`` in an OpenCV Hershey stroke font, for tests and demos.

    Returns:
      ``(polylines [n, 2] float (x, y), (H, W))``: the text set on one line
      with a margin of ``margin`` times the text height.
    """
    font = cv2.FONT_HERSHEY_SCRIPT_SIMPLEX if script else cv2.FONT_HERSHEY_SIMPLEX
    (tw, th), base = cv2.getTextSize(text, font, font_scale, 1)
    m = int(margin * th) + 4
    shape = (th + base + 2 * m, tw + 2 * m)
    img = np.zeros(shape, np.uint8)
    cv2.putText(img, text, (m, m + th), font, font_scale, 255, 1, cv2.LINE_8)
    lines = skeleton_polylines(morphology.skeletonize(img > 0))
    return [p.astype(np.float64) for p in lines], shape
