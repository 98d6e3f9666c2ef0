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
:func:`jdraw.metrics.tolerant_pixel_accuracy` scores plans of such inputs.
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


# ----------------------------------------------------------------------------- experimental


def _smooth(p: np.ndarray, sigma: float) -> np.ndarray:
    """Gaussian-smoothed chain ``[n, 2]`` with its two ends pinned (point reflection)."""
    r = int(np.ceil(2.5 * sigma))
    if len(p) < 3 or r < 1:
        return p.astype(np.float64)
    k = np.exp(-0.5 * (np.arange(-r, r + 1) / sigma) ** 2)
    k /= k.sum()
    n = len(p)
    r = min(r, n - 1)
    k = np.exp(-0.5 * (np.arange(-r, r + 1) / sigma) ** 2)
    k /= k.sum()
    head = 2 * p[0] - p[r:0:-1]
    tail = 2 * p[-1] - p[-2 : -r - 2 : -1]
    q = np.concatenate([head, p, tail]).astype(np.float64)
    out = np.stack([np.convolve(q[:, j], k, "valid") for j in range(2)], 1)
    return out


def _draw_curve(q: np.ndarray) -> np.ndarray:
    """Pixels of a float polyline as jdraw's rasteriser draws a curve (fine samples, rounded)."""
    from jdraw import demo

    seg = np.diff(q, axis=0)
    ln = np.hypot(seg[:, 0], seg[:, 1])
    s = np.concatenate([[0], np.cumsum(ln)])
    t = np.arange(0, s[-1] + 1e-9, 0.25) if s[-1] > 0 else np.zeros(1)
    t = np.append(t, s[-1])
    x = np.interp(t, s, q[:, 0])
    y = np.interp(t, s, q[:, 1])
    pts = np.floor(np.stack([x, y], 1) + 0.5).astype(np.int64)
    return demo.clean_path(pts)


def redraw(ink: np.ndarray, sigma: float = 1.5) -> np.ndarray:
    """Skeleton chains smoothed and redrawn with jdraw's curve rasteriser."""
    from jdraw import image

    pts, nbrs = image._neighbour_table(ink)
    out = np.zeros_like(ink)
    h, w = ink.shape
    for chain in image._trace(nbrs):
        p = pts[chain]
        if len(p) < 4:
            out[p[:, 1], p[:, 0]] = True
            continue
        q = _draw_curve(_smooth(p, sigma))
        q[:, 0] = np.clip(q[:, 0], 0, w - 1)
        q[:, 1] = np.clip(q[:, 1], 0, h - 1)
        out[q[:, 1], q[:, 0]] = True
    return out


def canonicalise_v2(ink, sigma: float = 1.5) -> np.ndarray:
    from skimage.morphology import skeletonize

    ink = np.asarray(ink, bool)
    if not ink.any():
        return ink.copy()
    sk = skeletonize(ink)
    out = redraw(sk, sigma)
    out = drop_staircase_corners(out)
    return bridge_gaps(out)


def canonicalise_sk(ink) -> np.ndarray:
    from skimage.morphology import skeletonize

    ink = np.asarray(ink, bool)
    if not ink.any():
        return ink.copy()
    return bridge_gaps(drop_staircase_corners(skeletonize(ink)))


def thin_lines(ink: np.ndarray, near: int = 2) -> np.ndarray:
    """Skeletonises, then puts back what it removed within ``near`` px of a junction."""
    from skimage.morphology import skeletonize

    sk = skeletonize(ink)
    junction = sk & (_degree(sk) >= 3)
    k = np.ones((2 * near + 1, 2 * near + 1), np.uint8)
    zone = cv2.dilate(junction.astype(np.uint8), k).astype(bool)
    return sk | (ink & ~sk & zone)


def canonicalise_t(ink) -> np.ndarray:
    from skimage.morphology import skeletonize

    ink = np.asarray(ink, bool)
    if not ink.any():
        return ink.copy()
    if is_thick(ink):
        ink = skeletonize(ink)
    ink = thin_lines(ink)
    ink = drop_staircase_corners(ink)
    return bridge_gaps(ink)


def thin_glitches(ink: np.ndarray) -> np.ndarray:
    """Thins clusters of crowded pixels (3+ neighbours) that only a line passes through.

    A cluster with two ways out is a lump on one line (a staircase triangle, a
    doubled pixel); one with three or more is a junction and is kept as drawn.
    """
    from skimage.morphology import skeletonize

    crowded = ink & (_degree(ink) >= 3)
    if not crowded.any():
        return ink
    n, lab, stats, _ = cv2.connectedComponentsWithStats(crowded.astype(np.uint8), connectivity=8)
    h, w = ink.shape
    lumps = np.zeros_like(ink)
    for c in range(1, n):
        x, y, bw, bh, _ = stats[c]
        y0, y1, x0, x1 = max(0, y - 1), min(h, y + bh + 1), max(0, x - 1), min(w, x + bw + 1)
        cl = lab[y0:y1, x0:x1] == c
        ring = ink[y0:y1, x0:x1] & ~cl & cv2.dilate(cl.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
        exits = cv2.connectedComponents(ring.astype(np.uint8), connectivity=8)[0] - 1
        if exits <= 2:
            lumps[y0:y1, x0:x1] |= cl
    if not lumps.any():
        return ink
    sk = skeletonize(ink)
    return ink & ~(lumps & ~sk)


def canonicalise_g(ink) -> np.ndarray:
    from skimage.morphology import skeletonize

    ink = np.asarray(ink, bool)
    if not ink.any():
        return ink.copy()
    if is_thick(ink):
        ink = skeletonize(ink)
    ink = thin_glitches(ink)
    ink = drop_staircase_corners(ink)
    return bridge_gaps(ink)
