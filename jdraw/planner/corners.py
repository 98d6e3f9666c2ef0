"""Corners of drawn strokes: where a stroke turns sharply, what it looks like there.

The geometry the stroke splitter (:mod:`jdraw.planner.splits`) reads: a
corner is a point where a drawn stroke turns at least :data:`MIN_TURN`
degrees over :data:`SPAN` pixels of line each side (:func:`corners`);
:func:`corner_features` describes one; :func:`corner_labels` says, from the
reference strokes, whether two strokes of a person meet there; and
:func:`split_at` cuts a stroke at corners, the parts sharing the cut point.
"""

from __future__ import annotations

import numpy as np

SPAN = 5.0  # pixels along the line on each side of a point that give its turn
MIN_TURN = 50.0  # degrees: a sharper turn is a corner candidate
MIN_ARM = 4.0  # pixels of line each side of a corner, at least
GEOMETRY_FEATURES = 23  # of a corner (corner_features)


def _arclength(p: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-9)


def _box(strokes) -> np.ndarray:
    """``[4]`` the box (x0, y0, x1, y1) of a character's strokes."""
    allp = np.concatenate([np.asarray(x, np.float64).reshape(-1, 2) for x in strokes])
    return np.concatenate([allp.min(0), allp.max(0)])


def _owners(points: np.ndarray, refs) -> np.ndarray:
    """``int [n]``: for each point, the index of the reference stroke nearest it."""
    d = np.stack(
        [
            np.linalg.norm(points[:, None] - np.asarray(r, np.float64)[None], axis=-1).min(1)
            for r in refs
        ],
        1,
    )
    return d.argmin(1)


def _headings(p: np.ndarray, s: np.ndarray, span: float) -> tuple[np.ndarray, np.ndarray]:
    """Unit headings into and out of every point, over ``span`` pixels of line."""
    back = np.searchsorted(s, s - span, side="right") - 1
    fwd = np.searchsorted(s, s + span, side="left")
    back = np.clip(back, 0, len(p) - 1)
    fwd = np.clip(fwd, 0, len(p) - 1)
    return _unit(p - p[back]), _unit(p[fwd] - p)


def corners(points) -> np.ndarray:
    """Indices of the sharp corners of one stroke (``[n, 2]`` points, drawing order).

    A corner is a point where the line turns at least :data:`MIN_TURN`
    degrees over :data:`SPAN` pixels each side, the sharpest within ``SPAN``,
    with at least :data:`MIN_ARM` pixels of line before and after it.
    """
    p = np.asarray(points, np.float64).reshape(-1, 2)
    if len(p) < 3:
        return np.zeros(0, np.int64)
    s = _arclength(p)
    hin, hout = _headings(p, s, SPAN)
    turn = np.degrees(np.arccos(np.clip(np.sum(hin * hout, -1), -1, 1)))
    ok = (turn >= MIN_TURN) & (s >= MIN_ARM) & (s <= s[-1] - MIN_ARM)
    out: list[int] = []
    for k in np.argsort(-turn, kind="stable"):
        if turn[k] < MIN_TURN:
            break
        if ok[k] and all(abs(s[k] - s[j]) > SPAN for j in out):
            out.append(int(k))
    return np.asarray(sorted(out), np.int64)


def corner_features(strokes, b: int, k: int, box=None, cs=None) -> np.ndarray:
    """``float32 [GEOMETRY_FEATURES]`` of corner ``k`` (a point index) of stroke ``b``.

    Its turn (signed, sharp over 2 pixels and wide over :data:`SPAN`), the
    headings in and out, where it is in the character's box, how much line
    runs before and after it and to the stroke's other corners, whether the
    stroke closes on itself, and how near other strokes and their ends come.
    """
    p = np.asarray(strokes[b], np.float64).reshape(-1, 2)
    box = _box(strokes) if box is None else box
    size = np.maximum(box[2:] - box[:2], 1.0)
    s = _arclength(p)
    c = p[k]
    feats = []
    for span in (2.0, SPAN, 2 * SPAN):
        hin, hout = _headings(p, s, span)
        a, o = hin[k], hout[k]
        feats += [float(a @ o), float(a[0] * o[1] - a[1] * o[0])]
    hin, hout = _headings(p, s, SPAN)
    feats += [*hin[k], *hout[k]]
    feats += [*((c - box[:2]) / size)]
    total = max(s[-1], 1e-6)
    feats += [s[k] / 100, (total - s[k]) / 100, s[k] / total]
    cs = corners(p) if cs is None else cs  # the stroke's corners
    before = s[k] - max([s[j] for j in cs if j < k], default=0.0)
    after = min([s[j] for j in cs if j > k], default=total) - s[k]
    feats += [before / 100, after / 100, len(cs) / 4]
    feats += [np.linalg.norm(p[0] - p[-1]) / 100]
    others = [np.asarray(x, np.float64).reshape(-1, 2) for i, x in enumerate(strokes) if i != b]
    if others:
        near = min(float(np.abs(o - c).max(-1).min()) for o in others)
        ends = np.concatenate([o[[0, -1]] for o in others])
        end = float(np.abs(ends - c).max(-1).min())
    else:
        near = end = 100.0
    # The stroke's own line passing close by, away from the corner (a loop closing there).
    far = np.abs(s - s[k]) > 3 * SPAN
    own = float(np.abs(p[far] - c).max(-1).min()) if far.any() else 100.0
    feats += [min(near, 20) / 20, min(end, 20) / 20, min(own, 20) / 20, len(strokes) / 20]
    return np.asarray(feats, np.float32)


def corner_labels(points, ks, refs, reach: float = 8.0, skip: float = 2.0) -> np.ndarray:
    """Whether each corner ``ks`` of a drawn stroke is where two reference strokes meet.

    Each point of the stroke takes the reference stroke nearest it; a corner
    is a split when the most common reference over ``skip``..``reach`` pixels
    of line before it differs from the one after it.

    Args:
      points: ``[n, 2]`` the drawn stroke.
      ks: its corners' point indices.
      refs: the reference strokes, ``[m_i, 2]`` points each.
    """
    p = np.asarray(points, np.float64).reshape(-1, 2)
    s = _arclength(p)
    owner = _owners(p, refs)

    def mode(sel):
        v = owner[sel]
        return np.bincount(v).argmax() if len(v) else -1

    out = []
    for k in ks:
        before = mode((s < s[k] - skip) & (s >= s[k] - reach))
        after = mode((s > s[k] + skip) & (s <= s[k] + reach))
        out.append(before != after and before >= 0 and after >= 0)
    return np.asarray(out, bool)


def split_at(points, ks) -> list[np.ndarray]:
    """One stroke cut at point indices ``ks``; neighbouring parts share the cut point."""
    p = np.asarray(points, np.float64).reshape(-1, 2)
    cuts = [0, *sorted(int(k) for k in ks), len(p) - 1]
    return [p[a : b + 1] for a, b in zip(cuts[:-1], cuts[1:]) if b > a]


T_TOUCH = 2.5  # pixels: a stroke end this near another stroke's line meets it there
T_AWAY = 4.0  # pixels along the line from that stroke's ends, at least (nearer: an end pair)


def t_cuts(strokes, with_seams: bool = False):
    """Strokes cut where another stroke's end meets their line (a T), the parts sharing the point.

    The tracer may run on through a junction and draw the branch later, from
    the junction: the e of a cursive word, whose loop a writer draws on the way
    through and goes back over. Cut there, the junction has three stroke ends,
    and the join stage can draw the branch on the way through (two end pairs,
    one of them back over the branch's line) or join the two parts again.
    An end meets a line within :data:`T_TOUCH` pixels of it and at least
    :data:`T_AWAY` along it from its ends. ``with_seams``: also the end pairs
    ``(i, True, i + 1, False)`` of the parts cut apart, so a cut no join uses can be
    joined again.
    """
    S = [np.asarray(s, np.float64).reshape(-1, 2) for s in strokes]
    along = [_arclength(r) for r in S]
    cuts: dict[int, set[int]] = {}
    for b, p in enumerate(S):
        if len(p) < 2:
            continue
        for q in (p[0], p[-1]):
            for a, r in enumerate(S):
                if a == b or len(r) < 3:
                    continue
                d = np.hypot(*(r - q).T)
                k = int(d.argmin())
                s = along[a]
                if d[k] <= T_TOUCH and T_AWAY <= s[k] <= s[-1] - T_AWAY:
                    cuts.setdefault(a, set()).add(k)
    out, seams = [], []
    for a, p in enumerate(S):
        parts = split_at(p, sorted(cuts[a])) if a in cuts else [p]
        seams += [(len(out) + k, True, len(out) + k + 1, False) for k in range(len(parts) - 1)]
        out += parts
    return (out, seams) if with_seams else out
