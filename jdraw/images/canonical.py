"""One place where any binary line image becomes the kind of line the planner knows.

The planner learned from one rasteriser: 1-pixel, 8-connected lines with no
staircase corners. Other rasterisers (Bresenham joints, anti-aliased lines
thresholded), 2-4 pixel pens and 1-pixel breaks give it shapes it never saw,
and it draws them as many short strokes. :func:`canonicalise` maps them to
canonical lines, and leaves canonical lines as they are:

1. thick ink (many full 2x2 blocks) is thinned to its centreline;
2. staircase corners (a pixel whose only two neighbours touch diagonally) are
   dropped, since the line stays 8-connected without them;
3. a 1-pixel break between two line ends that point at each other is filled.

Pixels a plan draws then lie within 1 pixel of the input's ink, not on it:
:func:`jdraw.evaluation.metrics.tolerant_pixel_accuracy` scores plans of such inputs.
"""

from __future__ import annotations

import cv2
import numpy as np

_N8 = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.float32)


def _degree(ink: np.ndarray) -> np.ndarray:
    """``int [H, W]``: inked 8-neighbours of every pixel."""
    d = cv2.filter2D(ink.astype(np.float32), -1, _N8, borderType=cv2.BORDER_CONSTANT)
    return np.rint(d).astype(np.int32)


def _blocks(ink: np.ndarray) -> np.ndarray:
    """``bool [H-1, W-1]``: 2x2 blocks fully inked."""
    return ink[:-1, :-1] & ink[1:, :-1] & ink[:-1, 1:] & ink[1:, 1:]


def is_thick(ink: np.ndarray, fraction: float = 0.25) -> bool:
    """Whether at least ``fraction`` of the ink lies in fully inked 2x2 blocks."""
    n = np.count_nonzero(ink)
    if n == 0 or min(ink.shape) < 2:
        return False
    b = _blocks(ink)
    covered = np.zeros_like(ink)
    covered[:-1, :-1] |= b
    covered[1:, :-1] |= b
    covered[:-1, 1:] |= b
    covered[1:, 1:] |= b
    return np.count_nonzero(covered) >= fraction * n


def drop_staircase_corners(ink: np.ndarray) -> np.ndarray:
    """Removes pixels whose only two 8-neighbours are 4-neighbours touching diagonally."""
    ink = ink.copy()
    for _ in range(2):  # a removal can expose a neighbour; two passes settle it
        p = np.pad(ink, 1)
        up, down = p[:-2, 1:-1], p[2:, 1:-1]
        left, right = p[1:-1, :-2], p[1:-1, 2:]
        deg = _degree(ink)
        l_shape = (up | down) & (left | right) & ~(up & down) & ~(left & right)
        corner = ink & (deg == 2) & l_shape
        # Remove only one of two adjacent corner candidates (keep the path connected).
        keep = np.zeros_like(corner)
        ys, xs = np.nonzero(corner)
        taken = np.zeros_like(corner)
        for y, x in zip(ys, xs):
            if taken[max(0, y - 1) : y + 2, max(0, x - 1) : x + 2].any():
                keep[y, x] = True
                continue
            taken[y, x] = True
        removed = corner & ~keep
        if not removed.any():
            break
        ink &= ~removed
    return ink


def _end_heading(ink: np.ndarray, y: int, x: int, reach: int = 3) -> np.ndarray | None:
    """Direction ``(dx, dy)`` pointing out of the line end at ``(y, x)``, or None."""
    path = [(y, x)]
    seen = {(y, x)}
    cy, cx = y, x
    for _ in range(reach):
        nxt = [
            (cy + dy, cx + dx)
            for dy in (-1, 0, 1)
            for dx in (-1, 0, 1)
            if (dy or dx)
            and 0 <= cy + dy < ink.shape[0]
            and 0 <= cx + dx < ink.shape[1]
            and ink[cy + dy, cx + dx]
            and (cy + dy, cx + dx) not in seen
        ]
        if len(nxt) != 1:
            break
        cy, cx = nxt[0]
        seen.add((cy, cx))
        path.append((cy, cx))
    if len(path) < 2:
        return None
    v = np.array([x - path[-1][1], y - path[-1][0]], float)
    return v / np.linalg.norm(v)


def bridge_gaps(ink: np.ndarray, min_cos: float = 0.7) -> np.ndarray:
    """Fills the pixel between two line ends 2 pixels apart that point at each other."""
    deg = _degree(ink)
    ends = list(zip(*np.nonzero(ink & (deg == 1))))
    out = ink.copy()
    for a in range(len(ends)):
        for b in range(a + 1, len(ends)):
            (y0, x0), (y1, x1) = ends[a], ends[b]
            dy, dx = y1 - y0, x1 - x0
            if max(abs(dy), abs(dx)) != 2 or (dy % 2) or (dx % 2):
                continue
            my, mx = y0 + dy // 2, x0 + dx // 2
            if ink[my, mx]:
                continue
            h0, h1 = _end_heading(ink, y0, x0), _end_heading(ink, y1, x1)
            if h0 is None or h1 is None:
                continue
            gap = np.array([dx, dy], float) / np.hypot(dx, dy)
            if h0 @ gap >= min_cos and h1 @ -gap >= min_cos:
                out[my, mx] = True
    return out


def canonicalise(ink) -> np.ndarray:
    """``bool [H, W]`` canonical 1-pixel lines for any binary line image ``ink``."""
    from skimage.morphology import skeletonize

    ink = np.asarray(ink, bool)
    if not ink.any():
        return ink.copy()
    if is_thick(ink):
        ink = skeletonize(ink)
    ink = drop_staircase_corners(ink)
    return bridge_gaps(ink)
