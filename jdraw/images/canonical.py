"""One place where any binary line image becomes the kind of line the planner knows.

The planner learned from one rasteriser: 1-pixel, 8-connected lines with no
staircase corners, drawn through finely sampled curves. Other rasterisers
(OpenCV's polylines, anti-aliased lines thresholded), 2-5 pixel pens and
1-pixel breaks give it shapes it never saw, and it draws them as many short
strokes. :func:`canonicalise` maps them to canonical lines, and leaves
canonical lines (nearly) as they are:

1. thick ink (many full 2x2 blocks) and rough 1-pixel ink (lumps all along
   its lines, as anti-aliased lines thresholded leave: :func:`is_rough`)
   become centrelines (:func:`thick_centrelines`): skeleton chains, with
   junctions that thinning split merged, smoothed and redrawn with the
   demonstrations' curve rule, a line that goes on straight through a
   junction as one curve, so lines cross and meet as jdraw's strokes do;
2. lumps on a line (pixels with 3+ neighbours where only one line passes,
   like the triangle a polyline leaves at a joint) are thinned where there
   are two or more, while junctions of 3+ lines are kept as drawn, since
   jdraw's own crossings look like that; a lone lump of 5+ pixels is kept
   too, as jdraw draws one where a stroke overshoots the corner it meets
   (:func:`thin_lumps`);
3. staircase corners (a pixel whose only two neighbours touch diagonally) are
   dropped, since the line stays 8-connected without them;
4. a 1-pixel break between two line ends that point towards each other
   (along a line or round a corner) is filled.

Pixels a plan draws then lie within 1 pixel of the input's ink (of its
centreline, for thick ink), not on it: :func:`jdraw.evaluation.metrics.tolerant_pixel_accuracy`
scores plans of such inputs. ``bench/canonical_variants.py`` measures it all.
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


def bridge_gaps(ink: np.ndarray, min_cos: float = 0.3) -> np.ndarray:
    """Fills the pixel between two line ends 2 pixels apart that point at each other.

    Ends ``(2, 0)``, ``(2, 1)`` or ``(2, 2)`` pixels apart are joined by the
    middle pixel of jdraw's segment between them (:func:`jdraw.geometry.segment_pixels`).
    """
    from jdraw import geometry

    deg = _degree(ink)
    ends = list(zip(*np.nonzero(ink & (deg == 1))))
    out = ink.copy()
    for a in range(len(ends)):
        for b in range(a + 1, len(ends)):
            (y0, x0), (y1, x1) = ends[a], ends[b]
            dy, dx = y1 - y0, x1 - x0
            if max(abs(dy), abs(dx)) != 2:
                continue
            mx, my = geometry.segment_pixels((x0, y0), (x1, y1))[1]
            if ink[my, mx]:
                continue
            h0, h1 = _end_heading(ink, y0, x0), _end_heading(ink, y1, x1)
            if h0 is None or h1 is None:
                continue
            gap = np.array([dx, dy], float) / np.hypot(dx, dy)
            if h0 @ gap >= min_cos and h1 @ -gap >= min_cos:
                out[my, mx] = True
    return out


def _smooth(p: np.ndarray, sigma: float) -> np.ndarray:
    """``float [n, 2]`` chain ``p`` smoothed along its length, both ends pinned.

    A Gaussian of ``sigma`` samples, the chain continued past each end by its
    point reflection, so that straight chains stay straight up to the end.
    """
    n = len(p)
    r = min(int(np.ceil(2.5 * sigma)), n - 1)
    if r < 1:
        return p.astype(np.float64)
    k = np.exp(-0.5 * (np.arange(-r, r + 1) / sigma) ** 2)
    k /= k.sum()
    head = 2 * p[0] - p[r:0:-1]
    tail = 2 * p[-1] - p[-2 : -r - 2 : -1]
    q = np.concatenate([head, p, tail]).astype(np.float64)
    return np.stack([np.convolve(q[:, j], k, "valid") for j in range(2)], 1)


def _draw_curve(q: np.ndarray) -> np.ndarray:
    """``int64 [m, 2]`` pixels of a float polyline ``q [n, 2]`` (x, y) as jdraw draws a curve.

    Samples 0.25 px apart are rounded to the nearest pixel and made a thin
    path by :func:`jdraw.data.demos.clean_path`, as for demonstrations.
    """
    from jdraw.data import demos

    seg = np.diff(q, axis=0)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(seg[:, 0], seg[:, 1]))])
    t = np.append(np.arange(0.0, s[-1], 0.25), s[-1])
    xy = np.floor(np.stack([np.interp(t, s, q[:, 0]), np.interp(t, s, q[:, 1])], 1) + 0.5)
    return demos.clean_path(xy.astype(np.int64))


# The 8 neighbours in ring order (dy, dx); consecutive entries touch.
_RING = ((-1, -1), (-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1))


def _simple_table() -> np.ndarray:
    """``bool [256]``: whether a pixel with this ring of neighbours can go.

    It can when it has 2+ inked neighbours (it is no line end) that are
    8-connected among themselves without it, so removing it cuts nothing.
    """
    table = np.zeros(256, bool)
    for code in range(256):
        on = [k for k in range(8) if code >> k & 1]
        if len(on) < 2:
            continue
        seen, todo = {on[0]}, [on[0]]
        while todo:
            a = todo.pop()
            for b in on:
                da = np.subtract(_RING[a], _RING[b])
                if b not in seen and max(abs(da[0]), abs(da[1])) == 1:
                    seen.add(b)
                    todo.append(b)
        table[code] = len(seen) == len(on)
    return table


_SIMPLE = _simple_table()


def _lumps(ink: np.ndarray, max_ways: int | None = 2):
    """Clusters of crowded pixels (3+ neighbours) with at most ``max_ways`` ways out.

    Yields ``(y0, x0, mask)``: each cluster as a mask of the window at
    ``(y0, x0)``. Such a cluster with two ways out is a lump on one line (a
    staircase triangle, a doubled pixel); one with three or more is a
    junction. ``max_ways=None`` yields every cluster.
    """
    crowded = ink & (_degree(ink) >= 3)
    if not crowded.any():
        return
    n, lab, stats, _ = cv2.connectedComponentsWithStats(crowded.astype(np.uint8), connectivity=8)
    h, w = ink.shape
    for c in range(1, n):
        x, y, bw, bh, _ = stats[c]
        y0, y1, x0, x1 = max(0, y - 1), min(h, y + bh + 1), max(0, x - 1), min(w, x + bw + 1)
        cl = lab[y0:y1, x0:x1] == c
        near = cv2.dilate(cl.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
        ring = ink[y0:y1, x0:x1] & ~cl & near
        ways = cv2.connectedComponents(ring.astype(np.uint8), connectivity=8)[0] - 1
        if max_ways is None or ways <= max_ways:
            yield y0, x0, cl


def is_rough(ink: np.ndarray, per_100: float = 1.0) -> bool:
    """Whether 1-pixel ink has at least ``per_100`` lumps per 100 ink pixels.

    jdraw's rasteriser leaves at most one in a character, OpenCV's polylines a
    few; anti-aliased lines thresholded leave lumps all along (2-7 per 100 px).
    """
    n = np.count_nonzero(ink)
    return n > 0 and sum(1 for _ in _lumps(ink)) >= per_100 * n / 100


def thin_lumps(ink: np.ndarray) -> np.ndarray:
    """Thins lumps on a line (:func:`_lumps`); junctions are left as they are.

    A lump's pixels are removed one at a time, in raster order, while
    removing one cuts nothing, so the line keeps its course.
    """
    out = np.pad(ink, 1)
    for y0, x0, cl in _lumps(ink):
        for py, px in zip(*np.nonzero(cl)):
            py, px = py + y0 + 1, px + x0 + 1  # in the padded image
            code = sum(int(out[py + dy, px + dx]) << k for k, (dy, dx) in enumerate(_RING))
            if _SIMPLE[code]:
                out[py, px] = False
    return out[1:-1, 1:-1]


def thick_centrelines(
    ink: np.ndarray,
    merge: float = 1.0,
    sigma: float = 1.5,
    straight: float = 35.0,
) -> np.ndarray:
    """``bool [H, W]`` centrelines of thick ink, drawn as jdraw draws curves.

    The skeleton is cut into chains between ends and junctions. Two junctions
    joined by a chain no longer than ``merge`` pen widths are one junction
    that thinning split (a crossing, a stroke meeting a corner); the chain is
    dropped and the others meet at the junctions' mean. Each chain is then
    smoothed (``sigma`` pixels along it, ends pinned) and redrawn with the
    curve rule of the demonstrations (:func:`_draw_curve`), which takes the
    pen's wobble and the thinning's kinks out of the line; chains that go on
    straight through a junction (within ``straight`` degrees) are redrawn as
    one curve (:func:`jdraw.images.skeleton.join_straight`).

    Args:
      ink: ``bool [H, W]`` lines more than one pixel wide.
      merge: longest chain between two junctions merged away, pen widths.
      straight: most a line may turn at a junction and be drawn as one curve,
        degrees (0: every chain drawn alone).
      sigma: smoothing along chains, pixels.
    """
    from jdraw.images import ink as ink_rules
    from jdraw.images import skeleton
    from jdraw.images.morph import skeletonize

    sk = skeletonize(ink)
    width = ink_rules.stroke_width(ink, sk)
    sk = skeleton.prune_spurs(sk, ink_rules.ink_distance(ink), width)
    pts, nbrs = skeleton._neighbour_table(sk)
    chains = skeleton._trace(nbrs)
    deg = np.array([len(n) for n in nbrs])
    parent = list(range(len(pts)))

    def find(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    dropped = set()
    for k, ch in enumerate(chains):
        ends_are_junctions = deg[ch[0]] >= 3 and deg[ch[-1]] >= 3 and ch[0] != ch[-1]
        if len(ch) > 1 and ends_are_junctions and len(ch) - 1 <= merge * width:
            parent[find(ch[0])] = find(ch[-1])
            dropped.add(k)
    members: dict[int, list[int]] = {}
    for i in np.flatnonzero(deg >= 3):
        members.setdefault(find(int(i)), []).append(int(i))
    centre = {r: pts[m].mean(0) for r, m in members.items()}
    radius = max(1.0, width / 2)
    out = np.zeros_like(ink)
    h, w = ink.shape
    polys, ends_at = {}, {}
    for k, ch in enumerate(chains):
        if k in dropped:
            continue
        p = pts[ch].astype(np.float64)
        for first in (True, False):
            end = ch[0] if first else ch[-1]
            if deg[end] < 3:
                continue
            # Leave the junction's lump; run the chain on to the merged junction's centre.
            c = centre[find(end)]
            q = p if first else p[::-1]
            j = 0
            while j < len(q) - 2 and np.max(np.abs(q[j] - c)) < radius:
                j += 1
            q = np.concatenate([c[None], q[j:]])
            p = q if first else q[::-1]
            if straight:
                ends_at.setdefault(find(end), []).append((k, first))
        polys[k] = _smooth(p, sigma) if len(p) >= 4 else p
    # A line through a junction is drawn as one curve, as jdraw draws a stroke.
    lines = skeleton.join_straight(polys, ends_at, int(round(width)) + 3, straight)
    for p in lines:
        q = _draw_curve(p) if len(p) > 1 else np.floor(p + 0.5).astype(np.int64)
        out[np.clip(q[:, 1], 0, h - 1), np.clip(q[:, 0], 0, w - 1)] = True
    return out


def canonicalise(ink) -> np.ndarray:
    """``bool [H, W]`` canonical 1-pixel lines for any binary line image ``ink``."""
    ink = np.asarray(ink, bool)
    if not ink.any():
        return ink.copy()
    if is_thick(ink) or is_rough(ink):
        ink = thick_centrelines(ink)
    lumps = [cl for _, _, cl in _lumps(ink)]
    if len(lumps) >= 2 or (lumps and np.count_nonzero(lumps[0]) < 5):
        # A lone lump of 5+ pixels is most likely jdraw's own: a corner where a stroke
        # overshoots the one it meets by a pixel (the planner's cue that two meet there).
        ink = thin_lumps(ink)
    ink = drop_staircase_corners(ink)
    return bridge_gaps(ink)
