"""What a redraw round draws: the target ink found missing, planned and cut to it.

The missing pieces (target pixels with no ink seen near their registered
place) are grown along the target so a redraw starts and ends on ink already
there, planned by ``jdraw.plan`` as a residual drawing, and cut to the
target's pixels so the pen is never down off the target.
"""

from __future__ import annotations

import cv2
import numpy as np

from jdraw import geometry
from jdraw.images.skeleton import skeleton_polylines
from jdraw.planner.plan import plan as default_planner
from jdraw.robot import look


def missing(
    target: np.ndarray, seen: np.ndarray, a: np.ndarray, tol_px: float, min_px: int
) -> np.ndarray:
    """``bool [100, 100]`` target pixels with no seen ink within ``tol_px`` of their place.

    Pieces of fewer than ``min_px`` pixels (8-connected) are dropped.
    """
    pts = np.argwhere(target)[:, ::-1]
    gone = look.sample(look.distance_to(seen), look.apply_affine(a, pts)) > tol_px
    out = np.zeros_like(target)
    out[pts[gone, 1], pts[gone, 0]] = True
    n, labels, stats, _ = cv2.connectedComponentsWithStats(out.astype(np.uint8), connectivity=8)
    small = np.flatnonzero(stats[:, cv2.CC_STAT_AREA] < min_px)
    small = small[small > 0]
    out[np.isin(labels, small)] = False
    return out


def grow_along(mask: np.ndarray, within: np.ndarray, steps: int) -> np.ndarray:
    """``mask`` grown ``steps`` pixels along ``within`` (geodesic dilation)."""
    kernel = np.ones((3, 3), np.uint8)
    out = mask.copy()
    for _ in range(steps):
        out = (cv2.dilate(out.astype(np.uint8), kernel) > 0) & within
    return out


def clip_to(strokes, allowed: np.ndarray) -> list[np.ndarray]:
    """Strokes cut to the runs of their pixel paths that lie on ``allowed`` pixels.

    Every returned stroke is a dense 8-connected pixel path of ``allowed``
    pixels, so the pen is never down over a pixel outside it.
    """
    out = []
    for s in strokes:
        s = np.asarray(s, np.float64).reshape(-1, 2)
        if not len(s):
            continue
        path = geometry.polyline_pixels(np.floor(s + 0.5))
        inside = np.all((path >= 0) & (path < geometry.CANVAS), axis=1)
        ok = np.zeros(len(path), bool)
        ok[inside] = allowed[path[inside, 1], path[inside, 0]]
        edges = np.flatnonzero(np.diff(np.concatenate([[0], ok.astype(int), [0]])))
        for start, stop in zip(edges[::2], edges[1::2]):
            out.append(path[start:stop].astype(np.float64))
    return out


def end_on_ink(strokes, covered: np.ndarray) -> list[np.ndarray]:
    """Turns strokes that start on ``covered`` pixels and end off them around.

    A pen that lifts early then loses the end of the stroke over ink that is
    already on the paper, not the piece the redraw is for.
    """
    out = []
    for s in strokes:
        a, b = (np.floor(s[k] + 0.5).astype(int) for k in (0, -1))
        if covered[a[1], a[0]] and not covered[b[1], b[0]]:
            s = s[::-1]
        out.append(s)
    return out


def residual_strokes(
    residual: np.ndarray, planner=None, checkpoint=None, covered: np.ndarray | None = None
) -> list[list[np.ndarray]]:
    """Plans ``residual`` ``bool [B, 100, 100]`` with ``jdraw.plan``; cut to it and completed.

    Pixels the plan leaves undrawn are traced along their skeleton, as
    ``jdraw.plan_image`` does for truncated tiles. With ``covered`` (``bool
    [B, 100, 100]``, target pixels already inked) strokes are oriented to end
    on ink (:func:`end_on_ink`).
    """
    if planner is None:
        planner = default_planner
    out: list[list[np.ndarray]] = [[] for _ in residual]
    todo = [i for i, r in enumerate(residual) if r.any()]
    if not todo:
        return out
    kwargs = {} if checkpoint is None else {"checkpoint": checkpoint}
    # the batch's own size (as a power of two), not the count left: one compile
    size = 1 << (len(residual) - 1).bit_length()
    batch = np.zeros((size, geometry.CANVAS, geometry.CANVAS), bool)
    batch[: len(todo)] = residual[todo]
    plan = planner(batch, **kwargs)
    for k, i in enumerate(todo):
        strokes = clip_to(plan.strokes[k], residual[i])
        left = residual[i] & ~geometry.render_strokes(strokes)
        if left.any():
            strokes += clip_to(skeleton_polylines(left), residual[i])
        out[i] = strokes if covered is None else end_on_ink(strokes, covered[i])
    return out
