"""The skeleton as a graph: pixel chains between ends and junctions, spurs, simplification.

Coordinates are ``(x, y)``: ``x`` the column, ``y`` the row, pixel centres at
integers, as in :mod:`jdraw.geometry`.
"""

from __future__ import annotations

import math

import numpy as np

from jdraw.images import morph

_OFFSETS = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))  # (dy, dx)


def _neighbour_table(skel: np.ndarray):
    """Pixels of ``skel`` and their neighbours, without staircase shortcuts.

    A diagonal link whose corner pixel is also on the skeleton is dropped, so a
    staircase is a path and not a chain of triangles.
    """
    ys, xs = np.nonzero(skel)
    index = np.full(skel.shape, -1, np.int64)
    index[ys, xs] = np.arange(len(ys))
    pad = np.pad(skel, 1)
    nbrs: list[list[int]] = [[] for _ in range(len(ys))]
    h, w = skel.shape
    for dy, dx in _OFFSETS:
        ok = pad[ys + 1 + dy, xs + 1 + dx]
        if dy and dx:
            ok &= ~pad[ys + 1, xs + 1 + dx] & ~pad[ys + 1 + dy, xs + 1]
        sel = np.nonzero(ok)[0]
        for i, j in zip(sel.tolist(), index[ys[sel] + dy, xs[sel] + dx].tolist()):
            nbrs[i].append(j)
    return np.stack([xs, ys], 1), nbrs


def _trace(nbrs: list[list[int]]) -> list[list[int]]:
    """Splits a pixel graph into chains between nodes (degree != 2), then cycles."""
    deg = [len(n) for n in nbrs]
    seen_edges: set[tuple[int, int]] = set()
    chains = []

    def walk(a: int, b: int) -> list[int]:
        path = [a, b]
        seen_edges.add((a, b))
        seen_edges.add((b, a))
        prev, cur = a, b
        while deg[cur] == 2:
            nxt = nbrs[cur][0] if nbrs[cur][0] != prev else nbrs[cur][1]
            if (cur, nxt) in seen_edges:
                break
            seen_edges.add((cur, nxt))
            seen_edges.add((nxt, cur))
            path.append(nxt)
            prev, cur = cur, nxt
        return path

    for i, d in enumerate(deg):
        if d == 0:
            chains.append([i])
        elif d != 2:
            for j in nbrs[i]:
                if (i, j) not in seen_edges:
                    chains.append(walk(i, j))
    for i, d in enumerate(deg):
        if d == 2 and (i, nbrs[i][0]) not in seen_edges:
            chains.append(walk(i, nbrs[i][0]))
    return chains


def prune_spurs(skel: np.ndarray, dist: np.ndarray, width: float, rounds: int = 3) -> np.ndarray:
    """Removes noise spurs: end branches off a junction that run out to the ink's edge.

    A branch no longer than ``width`` whose free end is nearer the edge than
    half the stroke's radius comes from a bump in the outline; the true end
    of a stroke sits about a radius inside the outline (the centre of its
    round cap) and is kept.

    Args:
      skel: ``bool [H, W]`` skeleton.
      dist: ``float [H, W]`` distance of each ink pixel to the ground.
      width: typical stroke width, pixels.
    """
    skel = skel.copy()
    edge = 0.25 * width
    for _ in range(rounds):
        pts, nbrs = _neighbour_table(skel)
        deg = np.array([len(n) for n in nbrs])
        removed = False
        for chain in _trace(nbrs):
            a, b = deg[chain[0]], deg[chain[-1]]
            if len(chain) < 2 or len(chain) > width:
                continue
            if (a == 1 and b >= 3) or (b == 1 and a >= 3):
                tip = pts[chain[0]] if a == 1 else pts[chain[-1]]
                if dist[tip[1], tip[0]] >= edge:
                    continue
                body = chain[:-1] if b >= 3 else chain[1:]
                skel[pts[body, 1], pts[body, 0]] = False
                removed = True
        if not removed:
            break
    return morph.skeletonize(skel)


def extend_ends(
    polylines: list[np.ndarray], skel: np.ndarray, dist: np.ndarray, width: float
) -> list[np.ndarray]:
    """Carries each free end of the skeleton on to the centre of the stroke's cap.

    Thinning stops short of a stroke's end, most of all at a sharp turn where
    the outline is blunt. The end is moved along its direction while the ink
    there is still as thick as the stroke (distance to the ground at least
    the stroke's radius), at most one stroke width.
    """
    pts, nbrs = _neighbour_table(skel)
    ends = {(int(p[0]), int(p[1])) for p, n in zip(pts, nbrs, strict=True) if len(n) == 1}
    radius = width / 2.0
    h, w = dist.shape
    out = []
    for line in polylines:
        p = np.asarray(line, np.float64)
        if len(p) >= 3:
            for first in (True, False):
                q = p if not first else p[::-1]
                end = q[-1]
                if (int(end[0]), int(end[1])) not in ends:
                    continue
                back = q[max(0, len(q) - 1 - int(np.ceil(width)))]
                d = end - back
                n = np.hypot(*d)
                if n < 1e-6:
                    continue
                d /= n
                best = None
                for t in np.arange(0.5, width + 0.5, 0.5):
                    x, y = np.round(end + t * d).astype(int)
                    if not (0 <= x < w and 0 <= y < h) or dist[y, x] < radius - 0.5:
                        break
                    best = end + t * d
                if best is not None:
                    q = np.concatenate([q, best[None]])
                p = q if not first else q[::-1]
        out.append(p)
    return out


def skeleton_polylines(skel: np.ndarray) -> list[np.ndarray]:
    """Pixel chains of a 1-pixel skeleton: ``[n, 2]`` int (x, y) arrays.

    Chains run between end points and junctions; a closed loop is traced from
    an arbitrary pixel back to it (first point = last). A lone pixel is a
    one-point chain.
    """
    pts, nbrs = _neighbour_table(np.asarray(skel, bool))
    return [pts[c] for c in _trace(nbrs)]


def _farthest(r: list, c: list, a: int, b: int) -> tuple[int, float]:
    """``(index, distance)`` of the point of ``a+1 .. b-1`` farthest from the segment ``a -> b``.

    ``r`` and ``c`` are the polyline's coordinate columns as Python floats. The
    distance is the perpendicular where a point projects inside the segment,
    else the nearer end's. The perpendicular is ``|<q, n>| - <p[a], n>`` with
    the unit normal ``n`` from the segment's angle, as scikit-image's
    ``approximate_polygon`` measures it (the angle's cosine and sine from
    NumPy, as there), so both keep the same points. One point at a time on
    Python floats: most of Ramer-Douglas-Peucker's spans are a few points
    long, where NumPy's per-call overhead is most of the cost.
    """
    r0, c0, r1, c1 = r[a], c[a], r[b], c[b]
    dr, dc = r1 - r0, c1 - c0
    ang = -np.arctan2(dr, dc)
    cos, sin = float(np.cos(ang)), float(np.sin(ang))
    off = c0 * sin + r0 * cos
    best, at = -1.0, a + 1
    for i in range(a + 1, b):
        qr, qc = r[i], c[i]
        dr0, dc0, dr1, dc1 = qr - r0, qc - c0, qr - r1, qc - c1
        if dr0 * dr + dc0 * dc > 0 and -dr1 * dr - dc1 * dc > 0:
            d = abs(qr * cos + qc * sin - off)
        else:
            d = min(math.sqrt(dc0 * dc0 + dr0 * dr0), math.sqrt(dc1 * dc1 + dr1 * dr1))
        if d > best:
            best, at = d, i
    return at, best


def simplify(points: np.ndarray, tol: float) -> np.ndarray:
    """Ramer-Douglas-Peucker: drops points within ``tol`` of the kept polyline.

    Distances are to the kept *segments* (:func:`_farthest`), so a stroke that
    doubles back keeps its turning point. Written here rather than imported
    from scikit-image, whose polygon module loads SciPy's signal and stats
    packages (seconds at start-up).
    """
    pts = np.asarray(points, np.float64)
    if len(pts) < 3 or tol <= 0:
        return pts
    r, c = pts[:, 0].tolist(), pts[:, 1].tolist()
    keep = np.zeros(len(pts), bool)
    keep[[0, -1]] = True
    todo = [(0, len(pts) - 1)]
    while todo:
        a, b = todo.pop()
        if b - a < 2:
            continue
        m, dmax = _farthest(r, c, a, b)
        if dmax > tol:
            keep[m] = True
            todo += [(m, b), (a, m)]
    return pts[keep]


def join_straight(polys: dict, ends_at: dict, reach: int, straight: float = 35) -> list:
    """Polylines that meet at nodes, joined where a line goes straight through a node.

    At each node the two ends whose lines leave in the most nearly opposite
    directions (within ``straight`` degrees of a straight line) are joined,
    then the next two, so two lines crossing at a node become two polylines
    crossing there, and the bar of a T one polyline with the stem ending on it.

    Args:
      polys: ``{key: float [n, 2]}`` polylines; one that ends at a node starts
        or ends exactly at the node's point.
      ends_at: ``{node: [(key, first), ...]}``, the polyline ends at each node
        (``first``: its first point, else its last).
      reach: points along a polyline that give its direction from the node.

    Returns:
      A list of ``float [m, 2]`` polylines covering every input polyline once.
    """
    cos = np.cos(np.radians(straight))

    def away(key, first):
        p = polys[key] if first else polys[key][::-1]
        v = p[min(reach, len(p) - 1)] - p[0]
        n = np.linalg.norm(v)
        return v / n if n > 0 else v

    link: dict[tuple, tuple] = {}
    for es in ends_at.values():
        pairs = sorted(
            (float(away(*e) @ away(*f)), i, j)
            for i, e in enumerate(es)
            for j, f in enumerate(es)
            if i < j and e[0] != f[0]
        )
        for d, i, j in pairs:
            if d > -cos:
                break
            if es[i] not in link and es[j] not in link:
                link[es[i]] = es[j]
                link[es[j]] = es[i]
    out, seen = [], set()
    # Walks start at unjoined ends first, so that a cycle of joins is walked last.
    keys = sorted(polys, key=lambda k: ((k, True) in link and (k, False) in link, str(k)))
    for key in keys:
        if key in seen:
            continue
        first = (key, True) not in link  # walk away from an unjoined end
        parts, cur, f = [], key, first
        while cur not in seen:
            seen.add(cur)
            p = polys[cur] if f else polys[cur][::-1]
            parts.append(p if not parts else p[1:])  # the node's point once
            nxt = link.get((cur, not f))  # the end we arrive at
            if nxt is None:
                break
            cur, f = nxt
        out.append(np.concatenate(parts))
    return out
