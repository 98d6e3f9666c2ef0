"""How close a drawing's separate lines and the sides of its loops come: what sets its scale.

``jdraw.plan_image`` shrinks a drawing onto the planner's canvas as far as its
lines stay ``min_gap`` canvas pixels apart. Lines that do not touch are at
least a stroke width apart, so a scale of ``min_gap / width`` is always safe;
but handwriting's lines are mostly much farther apart than its pen is wide,
and at that scale a word's letters come out several times larger than the
planner's training characters, cut into tiles. :func:`line_gap` measures the
distance the drawing's lines do keep, in input pixels:

* **necks**: two centreline points closer than ``most`` widths whose way along
  the ink is more than ``ratio`` times longer than the straight line between
  them (two letters that nearly touch, a loop's sides near where it closes).
  The arms of a junction meet at an angle and are not counted (at their
  apex the way along the ink is short), unless the angle is under about
  ``2 * asin(1 / ratio)`` (19 degrees for 6): arms that close are near-parallel
  lines and merge on a canvas as two separate ones would;
* **holes**: a round loop's inside (background not reachable from the
  border, of at most ``ROUND`` times the area of its largest inscribed
  circle) is as wide as that circle, so its sides' centrelines are that plus
  a stroke width apart. Longer holes are slivers between lines that nearly
  meet, or long loops, whose sides are necks; holes narrower than the pen
  are where two passes of it nearly closed (the tip of a cusp), not loops.

The gap is a low percentile of the necks (a few odd pixels do not set it) or
the narrowest hole, whichever is smaller, clipped to ``[width, most * width]``:
never closer than the safe bound, never shrinking a drawing more than
``most`` times below it.
"""

from __future__ import annotations

import cv2
import numpy as np
from scipy import sparse
from scipy.sparse.csgraph import dijkstra
from scipy.spatial import cKDTree

RATIO = 6.0  # way along the ink / straight distance above which two points are separate lines
MOST = 4.0  # stroke widths: the largest gap looked for
SOURCES = 800  # centreline pixels measured (a fixed random sample of larger skeletons)
PERCENTILE = 5.0  # of the necks measured: the gap
ROUND = 4.0  # a hole is a loop's inside if its area is at most this many inscribed circles


def line_gap(
    ink: np.ndarray,
    skeleton: np.ndarray,
    width: float,
    *,
    ratio: float = RATIO,
    most: float = MOST,
    sources: int = SOURCES,
    percentile: float = PERCENTILE,
) -> float:
    """Centreline distance, input pixels, that the drawing's separate lines keep.

    Args:
      ink: ``bool [H, W]`` the ink mask.
      skeleton: ``bool [H, W]`` its 1-pixel centrelines.
      width: typical stroke width, pixels (:func:`jdraw.images.ink.stroke_width`).

    Returns:
      a distance in ``[width, most * width]`` (module docstring).
    """
    width = max(float(width), 1.0)
    hi = most * width
    gap = min(hi, _necks(skeleton, width, hi, ratio, sources, percentile), _holes(ink, width))
    return float(max(gap, width))


def _necks(skel, width, hi, ratio, sources, percentile) -> float:
    ys, xs = np.nonzero(skel)
    pts = np.stack([xs, ys], 1).astype(np.float64)
    n = len(pts)
    if n < 3:
        return np.inf
    tree = cKDTree(pts)
    pairs = tree.query_pairs(1.5, output_type="ndarray")
    if not len(pairs):
        return np.inf
    step = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    graph = sparse.coo_matrix((step, (pairs[:, 0], pairs[:, 1])), shape=(n, n)).tocsr()
    rng = np.random.default_rng(0)
    src = rng.choice(n, sources, replace=False) if n > sources else np.arange(n)
    near = tree.query_ball_point(pts[src], hi)
    chunk = int(max(1, min(64, 2e7 // n)))  # rows of the [chunk, n] distance array
    best = np.full(len(src), np.inf)
    for a in range(0, len(src), chunk):
        way = dijkstra(graph, directed=False, indices=src[a : a + chunk], limit=ratio * hi)
        for k, row in enumerate(way):
            i = a + k
            nb = np.asarray(near[i], np.int64)
            d = np.linalg.norm(pts[nb] - pts[src[i]], axis=1)
            ok = (d >= width) & (row[nb] > ratio * d)
            if ok.any():
                best[i] = d[ok].min()
    found = best[np.isfinite(best)]
    return float(np.percentile(found, percentile)) if len(found) else np.inf


def _holes(ink, width) -> float:
    ground = (~np.asarray(ink, bool)).astype(np.uint8)
    count, labels, stats, _ = cv2.connectedComponentsWithStats(ground, connectivity=4)
    h, w = ground.shape
    x, y, bw, bh = (stats[:, k] for k in range(4))
    inside = (x > 0) & (y > 0) & (x + bw < w) & (y + bh < h)
    inside[0] = False  # OpenCV's label 0 is the ink
    if not inside.any():
        return np.inf
    dist = cv2.distanceTransform(ground, cv2.DIST_L2, 5)
    mask = inside[labels]
    radius = np.zeros(count, np.float32)
    np.maximum.at(radius, labels[mask], dist[mask])
    area = stats[inside, cv2.CC_STAT_AREA]
    radius = radius[inside]
    # Round holes only: a sliver between two lines that nearly meet is long for its width,
    # and a long loop's sides are necks. A hole narrower than the pen is where its two
    # passes nearly closed (a cusp's tip, a retrace), not a loop drawn to be seen.
    keep = (2 * radius >= max(width, 2.0)) & (area <= ROUND * np.pi * radius**2)
    radius = radius[keep]
    return float(2 * radius.min() + width) if len(radius) else np.inf
