"""Stitching planned strokes across tile borders, so one line is drawn in one motion."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.cluster.hierarchy import DisjointSet

from jdraw import geometry
from jdraw.planner.crumbs import absorb_crumbs, trim_to_new_ink


def _outward(path: np.ndarray, end: int, reach: int = 3) -> np.ndarray:
    """Unit direction in which a pixel path leaves through ``end`` (0 first, 1 last)."""
    if len(path) < 2:
        return np.zeros(2)
    k = min(reach, len(path) - 1)
    a, b = (path[k], path[0]) if end == 0 else (path[-1 - k], path[-1])
    d = (b - a).astype(np.float64)
    return d / max(np.hypot(*d), 1e-9)


def _codes(path: np.ndarray) -> np.ndarray:
    """One int64 per pixel of ``[n, 2]`` integer ``path``, equal for equal pixels."""
    p = np.asarray(path, np.int64)
    return (p[:, 0] << 32) + p[:, 1]


def _trim_retrace(path: np.ndarray, least: int = 2) -> np.ndarray:
    """Cuts a path's ends where it doubles back over its own pixels.

    A planner that overshoots and comes back ends its stroke in the middle of
    ink it already drew. Pixels drawn again at the end (or drawn first at the
    start and again later) are cut when there are at least ``least`` of them,
    so a closed loop that ends on its first pixel keeps it.
    """
    n = len(path)
    if n < 2:
        return path
    code = _codes(path)
    first = np.zeros(n, bool)
    first[np.unique(code, return_index=True)[1]] = True
    # From the end, a pixel drawn before is cut; the last pixel drawn first stays.
    hi = int(np.flatnonzero(first)[-1]) + 1
    if n - hi < least:
        hi = n
    last = np.zeros(hi, bool)  # the last time each pixel of path[:hi] is drawn
    last[hi - 1 - np.unique(code[:hi][::-1], return_index=True)[1]] = True
    # From the start, a pixel drawn again later is cut, up to the first one that is not.
    lo = min(int(np.argmax(last)), hi - 1)
    if lo < least:
        lo = 0
    return path[lo:hi]


def stitch(
    pieces: Sequence[tuple[int, np.ndarray]],
    report: dict | None = None,
    *,
    smooth_cos: float = -0.5,
    fragment: int = 5,
    reach: int = 2,
) -> list[np.ndarray]:
    """Joins strokes that meet end to end, so that one line is drawn in one motion.

    Args:
      pieces: ``(tile, [n, 2] int (x, y))`` strokes in one shared pixel frame
        (a region's big canvas), in drawing order; consecutive points may be
        up to the planner's move apart.
      report: when given, receives counts (added to what it holds):
        ``joins`` (links across tile borders), ``breaks`` (ends that had an
        8-neighbour across a border but stayed unjoined), ``lift_joins`` (pen
        lifts of one tile removed), ``fragments`` (pieces dropped because
        other strokes draw all their pixels) and ``crumbs`` (strokes of at most
        ``fragment`` pixels drawn as part of a stroke they touch).
      smooth_cos: two strokes of one tile are joined only where they continue
        each other: the cosine between their outward directions is at most this.
      reach: ends at most this many pixels apart (Chebyshev) may be joined;
        2 is the planner's longest move, and the gap is drawn as a straight step.
      fragment: a piece that adds at most this many pixels to what the others
        draw is a fragment; so is any piece this short. A joined stroke this
        short that touches another is a crumb (0: none are).

    Returns:
      The joined strokes as 8-connected pixel paths, ordered by their earliest
      piece; a joined stroke runs the way most of its pixels were planned
      (each tile's ranker heads its own piece), its earliest piece's way on a
      tie.

    Two ends are joined when they are at most ``reach`` pixels apart and

    * the pieces lie in different tiles (the tile border cut the stroke), or
    * they lie in one tile, no other stroke passes there (not a junction), and
      the two continue each other smoothly, or one of them is a fragment.
      The planner learned from KanjiVG to lift the pen where a character's
      stroke ends; a long line cut into tiles gets pen lifts at spots such as
      the tops of humps, where no character would end a stroke.

    Where a stroke doubles back over itself at an end, that end is cut back
    to the turn. Fragments (the planner retracing a stroke's end to reach a
    pixel or two beyond it) are then trimmed to the pixels nothing else draws
    (:func:`jdraw.planner.crumbs.trim_to_new_ink`; one adding nothing is dropped).
    Border joins are made first, then the closest, then the straightest
    continuations; every end is joined at most once. Last, a crumb left over
    (most often a pixel or two a tile drew on its border beside a stroke that
    crosses it, which no join can take, its end being joined already) is drawn
    as part of the stroke it touches, as the planner's own join stage draws the
    crumbs of a tile (:func:`jdraw.planner.crumbs.absorb_crumbs`), not as a pen
    lift of its own.
    """
    paths: list[np.ndarray | None] = [_trim_retrace(geometry.polyline_pixels(p)) for _, p in pieces]
    tile_of = [t for t, _ in pieces]
    paths = trim_to_new_ink(paths, fragment, drop=True, ends=True)
    dropped = sum(p is None for p in paths)
    live = [i for i, p in enumerate(paths) if p is not None and len(p)]
    size = {i: len(np.unique(_codes(paths[i]))) for i in live}

    ends: dict[tuple[int, int], list[tuple[int, int]]] = {}
    inner: dict[tuple[int, int], set[int]] = {}
    for s in live:
        p = paths[s]
        for e in (0, 1):
            q = p[0] if e == 0 else p[-1]
            ends.setdefault((int(q[0]), int(q[1])), []).append((s, e))
        for x, y in p[2 : len(p) - 2]:
            inner.setdefault((int(x), int(y)), set()).add(s)

    def junction(q: tuple[int, int], pair: tuple[int, int]) -> bool:
        x, y = q
        return any(
            inner.get((x + dx, y + dy), set()) - set(pair) for dx in (-1, 0, 1) for dy in (-1, 0, 1)
        )

    candidates = []
    for (x, y), here in ends.items():
        for dx in range(-reach, reach + 1):
            for dy in range(-reach, reach + 1):
                for s2, e2 in ends.get((x + dx, y + dy), ()):
                    for s1, e1 in here:
                        if s1 == s2 or (s1, e1) >= (s2, e2):
                            continue
                        o1, o2 = _outward(paths[s1], e1), _outward(paths[s2], e2)
                        across = tile_of[s1] != tile_of[s2]
                        if not across:
                            tiny = min(size[s1], size[s2]) <= fragment
                            if junction((x, y), (s1, s2)) or junction((x + dx, y + dy), (s1, s2)):
                                continue
                            if not tiny and float(o1 @ o2) > smooth_cos:
                                continue
                        step = np.array([dx, dy], np.float64) / max(np.hypot(dx, dy), 1e-9)
                        score = float(o1 @ step - o2 @ step - o1 @ o2)
                        gap = max(abs(dx), abs(dy))
                        candidates.append((not across, gap, -score, s1, e1, s2, e2))
    candidates.sort()
    link: dict[tuple[int, int], tuple[int, int]] = {}
    lift_joins = 0
    chains = DisjointSet(live)  # links never close a loop

    for same, _, _, s1, e1, s2, e2 in candidates:
        if (s1, e1) in link or (s2, e2) in link or chains.connected(s1, s2):
            continue
        chains.merge(s1, s2)
        link[(s1, e1)] = (s2, e2)
        link[(s2, e2)] = (s1, e1)
        lift_joins += same
    if report is not None:
        had = {(c[3], c[4]) for c in candidates if not c[0] and c[1] <= 1}
        had |= {(c[5], c[6]) for c in candidates if not c[0] and c[1] <= 1}
        report["joins"] = report.get("joins", 0) + len(link) // 2 - lift_joins
        report["breaks"] = report.get("breaks", 0) + len(had - link.keys())
        report["lift_joins"] = report.get("lift_joins", 0) + lift_joins
        report["fragments"] = report.get("fragments", 0) + dropped

    used = dict.fromkeys(live, False)

    def follow(seed: int, end: int) -> tuple[list[np.ndarray], int]:
        """Paths linked on from ``seed``'s ``end``, each turned to lead away from it,
        and how many of their pixels were planned the other way."""
        chain, at, against = [], (seed, end), 0
        while at in link:
            s, e = link[at]
            if used[s]:
                break
            used[s] = True
            turned = e == end
            chain.append(paths[s][::-1] if turned else paths[s])
            against += len(paths[s]) if turned else 0
            at = (s, 1 - e)
        return chain, against

    out = []
    for seed in live:
        if used[seed]:
            continue
        used[seed] = True
        ahead, against_ahead = follow(seed, 1)
        behind, against_behind = follow(seed, 0)
        parts = behind[::-1] + [paths[seed], *ahead]
        joined = geometry.polyline_pixels(np.concatenate(parts))
        # Each tile's ranker headed its own piece; the stroke runs the way most of
        # its pixels were planned, the earliest piece's way on a tie.
        against = against_ahead + against_behind
        if 2 * against > sum(len(p) for p in parts):
            joined = joined[::-1]
        out.append(joined)
    if fragment:
        n = len(out)
        out = [np.asarray(p, np.int64) for p in absorb_crumbs(out, crumb=fragment)]
        if report is not None:
            report["crumbs"] = report.get("crumbs", 0) + n - len(out)
    return out
