"""Joining a stroke to the stroke that goes on from its end.

The local model sometimes lifts the pen where a line meets or crosses another
and draws the rest of the line later, from the junction on: one stroke of a
person becomes two of the plan, end to end and heading the same way. This is
most common on lines redrawn from a thick pen, whose junctions are not quite
the shape of jdraw's own. :func:`join_strokes` joins such pairs: two stroke
ends at most ``gap`` pixels apart, the line running on through them within
``max_turn`` degrees, the pixels between them ink. The joined stroke is drawn
in the first one's direction (the ranker may flip it later); a stroke turned
round to be joined inks the same pixels (:func:`jdraw.planner.ranker.reverse`).

Whether ``jdraw.plan`` joins is a setting of the checkpoint (its bundle's
``planner.join``), so the paper's model plans as it always has.

Also here: the candidates of the learned joiner of
:mod:`jdraw.planner.splits`: pairs of stroke ends close together on ink
(:func:`end_pairs`), their features (:func:`join_features`), their label
from the reference strokes (:func:`end_owner`) and the strokes with chosen
pairs joined (:func:`join_pairs`). Ends a little further apart count too
when a short path through the ink links them (:func:`bridge`): where a line
crosses another, the local model may stop a few pixels short of the crossing
and go on from a few pixels past it, and the join then draws the crossing
again.
"""

from __future__ import annotations

import numpy as np

from jdraw.planner.corners import SPAN as CORNER_SPAN
from jdraw.planner.corners import _arclength, _box, _owners, _unit, corners
from jdraw.planner.ink_paths import between, ink_tree, own_line
from jdraw.planner.ranker import reverse

GAP = 3  # pixels (Chebyshev) between the ends joined
MAX_TURN = 45.0  # degrees the line may turn where two strokes are joined
SPAN = 6  # pixels back along a stroke that give its heading at an end


def _outward(p: np.ndarray, at_end: bool) -> np.ndarray | None:
    """Unit heading out of a stroke at one end (travel direction there, continued)."""
    q = p if at_end else p[::-1]
    e = q[-1]
    k = len(q) - 1
    while k > 0 and np.abs(q[k] - e).max() < SPAN:
        k -= 1
    v = e - q[k]
    n = float(np.hypot(*v))
    return v / n if n > 0 else None


def _link(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Points strictly between ``a`` and ``b`` so that no move is longer than 2 pixels."""
    d = b - a
    m = int(np.ceil(np.abs(d).max() / 2))
    return np.rint(a + d * (np.arange(1, m)[:, None] / m)) if m > 1 else np.zeros((0, 2))


def _on_ink(points: np.ndarray, ink: np.ndarray | None) -> bool:
    if ink is None:
        return True
    from jdraw import geometry

    line = geometry.render_strokes([points], shape=ink.shape)
    return bool(ink[line].all())


def join_strokes(strokes, ink=None, gap: int = GAP, max_turn: float = MAX_TURN) -> list:
    """Strokes with each pair that continues one line joined into one stroke.

    Args:
      strokes: list of ``[n, 2]`` (x, y) points, in drawing order.
      ink: optional ``bool [H, W]``; a join is made only where the pixels
        between the two ends are ink.
      gap: most pixels (Chebyshev) between the two ends.
      max_turn: most degrees the line turns from one stroke to the other.

    Returns:
      The strokes, joined pairs replaced by one stroke at the first one's place.
      The best-aligned pair is joined first, then the next, until none is left.
    """
    S = [np.asarray(s, np.float64) for s in strokes]
    cos = np.cos(np.radians(max_turn))
    while len(S) > 1:
        ends = []  # (stroke, at_end, point, outward heading)
        for i, p in enumerate(S):
            if len(p) < 2:
                continue
            for at_end in (False, True):
                h = _outward(p, at_end)
                if h is not None:
                    ends.append((i, at_end, p[-1] if at_end else p[0], h))
        if not ends:
            break
        pos = np.array([e[2] for e in ends])
        head = np.array([e[3] for e in ends])
        owner = np.array([e[0] for e in ends])
        near = np.abs(pos[:, None] - pos[None]).max(-1) <= gap
        straight = head @ head.T <= -cos  # the two ends point at each other
        ok = near & straight & (owner[:, None] != owner[None])
        joined = False
        for a, b in sorted(zip(*np.nonzero(ok)), key=lambda ab: head[ab[0]] @ head[ab[1]]):
            (i, i_end, pa, _), (j, j_end, pb, _) = ends[a], ends[b]
            first = S[i] if i_end else reverse(S[i])  # ends at pa
            second = reverse(S[j]) if j_end else S[j]  # starts at pb
            link = _link(pa, pb)
            if not _on_ink(np.concatenate([pa[None], link, pb[None]]), ink):
                continue
            S[min(i, j)] = np.concatenate([first, link, second])
            del S[max(i, j)]
            joined = True
            break
        if not joined:
            break
    return S


def join_plan(plan, targets=None, max_rows: int | None = None):
    """A :class:`jdraw.Plan` with :func:`join_strokes` applied to each image.

    ``targets`` (``bool [B, H, W]``, the ink planned) keeps joins on ink; an
    image whose joined strokes would need more than ``max_rows`` action rows
    keeps its strokes as they were.
    """
    from jdraw.plans import Plan, actions_from_strokes

    strokes = []
    for b, s in enumerate(plan.strokes):
        out = join_strokes(s, None if targets is None else np.asarray(targets[b], bool))
        if max_rows is not None and len(actions_from_strokes(out)) > max_rows:
            out = s
        strokes.append(out)
    return Plan.from_strokes(strokes, plan.truncated, width=plan.actions.shape[1])


# ----------------------------------------------------------------------------
# Pairs of stroke ends: the learned joiner's candidates (jdraw.planner.splits).

JOIN_GEOMETRY = 23  # of a pair of ends (join_features)
REACH = 8  # pixels (Chebyshev, and moves along the ink) between ends linked through ink


def bridge(a, b, ink=None, gap: int = GAP, reach: int = REACH) -> np.ndarray | None:
    """Points strictly between two ends that a join draws, or ``None`` if they cannot join.

    Ends at most ``gap`` pixels apart (Chebyshev) are linked straight, if the pixels
    between are ink (any, without ``ink``); ends up to ``reach`` apart by the shortest
    path through ``ink`` of at most ``reach`` moves, often over a line drawn already.
    So are near ends whose straight link would leave the ink: the two sides of a
    narrow cusp (the top of a cursive m's hump, an r's spike), where the tracer
    lifts at the turn and starts again beside it, are linked round the tip
    (until 2026-12-07 such a pair was never a candidate).
    """
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    far = np.abs(a - b).max()
    if far <= gap:
        link = _link(a, b)
        if _on_ink(np.concatenate([a[None], link, b[None]]), ink):
            return link
    if ink is None or far > reach:
        return None
    return between(ink_tree(np.asarray(ink, bool), a, reach), a, b)


def _end(p: np.ndarray, at_end: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The point of one end of a stroke, its outward heading and its turn there."""
    q = p if at_end else p[::-1]  # q runs towards the end
    s = _arclength(q)
    out = []
    for span in (CORNER_SPAN, 2 * CORNER_SPAN):
        k = max(int(np.searchsorted(s, s[-1] - span, side="right")) - 1, 0)
        out.append(_unit(q[-1] - q[k]))
    return q[-1], out[0], out[1]


def end_pairs(
    strokes, ink=None, gap: int = GAP, reach: int = REACH
) -> list[tuple[int, bool, int, bool]]:
    """Pairs of ends of different strokes that :func:`bridge` can link: at most
    ``gap`` pixels apart on ink, or up to ``reach`` along a path through ``ink``."""
    return [pair for pair, _ in end_links(strokes, ink, gap, reach)]


def end_links(strokes, ink=None, gap: int = GAP, reach: int = REACH, retrace: int = 0) -> list:
    """:func:`end_pairs` with each pair's :func:`bridge`: ``[((i, ie, j, je), points)]``.

    ``retrace``: ends further apart than ``reach``, up to ``retrace`` moves, are
    linked too when their path goes back over the line of one of the two
    strokes (:func:`own_line`): a writer runs back down the stem just drawn
    up, never across another stroke's line to a far one.
    """
    far_reach = max(reach, retrace)
    ends = [
        (i, e, (p[-1] if e else p[0]))
        for i, p in enumerate(np.asarray(x, np.float64).reshape(-1, 2) for x in strokes)
        if len(p) >= 2
        for e in (False, True)
    ]
    ink = None if ink is None else np.asarray(ink, bool)
    out = []
    for a in range(len(ends)):
        tree = None  # one breadth-first search from this end serves every pair of it
        for b in range(a + 1, len(ends)):
            (i, ie, pa), (j, je, pb) = ends[a], ends[b]
            far = np.abs(pa - pb).max()
            if i == j or far > max(gap, far_reach if ink is not None else 0):
                continue
            if far <= gap:
                link = bridge(pa, pb, ink, gap, reach)
            else:  # as bridge(): the shortest path through the ink of at most reach moves
                tree = ink_tree(ink, pa, far_reach) if tree is None else tree
                link = between(tree, pa, pb)
                if link is not None and len(link) >= reach:
                    link = link if own_line(link, strokes[i], strokes[j]) else None
            if link is not None:
                out.append(((i, ie, j, je), link))
    return out


def crowd(strokes) -> tuple[np.ndarray, ...]:
    """Every point of ``strokes`` and every stroke's two ends, each with its stroke's index:
    what :func:`join_features` counts near a pair, gathered once for all of a drawing's pairs."""
    S = [np.asarray(x, np.float64).reshape(-1, 2) for x in strokes]
    owner = np.repeat(np.arange(len(S)), [len(q) for q in S])
    ends = np.asarray([e for q in S for e in (q[0], q[-1])]).reshape(-1, 2)
    return np.concatenate(S) if S else np.zeros((0, 2)), owner, ends, np.arange(len(ends)) // 2


def join_features(strokes, pair, box=None, link=None, near=None) -> np.ndarray:
    """``float32 [JOIN_GEOMETRY]`` of joining two stroke ends (:func:`end_links`).

    How straight the line runs on through the two ends (near and further
    back), their headings, where they are, the gap and the moves of their
    :func:`bridge` (``link``, the points between), both strokes' lengths, whether each end is
    where its stroke began, and how crowded the place is (other ends and
    other lines near it; ``near``: the drawing's :func:`crowd`, else computed here).
    """
    S = [np.asarray(x, np.float64).reshape(-1, 2) for x in strokes]
    box = _box(S) if box is None else box
    size = np.maximum(box[2:] - box[:2], 1.0)
    i, ie, j, je = pair
    pa, ha, fa = _end(S[i], ie)
    pb, hb, fb = _end(S[j], je)
    c = (pa + pb) / 2
    la, lb = _arclength(S[i])[-1], _arclength(S[j])[-1]
    points, owner, tips, tip_owner = crowd(S) if near is None else near
    other = (tip_owner != i) & (tip_owner != j)
    ends = int(np.count_nonzero(other & (np.abs(tips - c).max(-1) <= 2 * GAP)))
    other = (owner != i) & (owner != j)
    lines = min(100.0, float(np.abs(points[other] - c).max(-1).min())) if other.any() else 100.0
    f = [
        float(ha @ hb),
        float(fa @ fb),
        float(ha[0] * hb[1] - ha[1] * hb[0]),
        *ha,
        *hb,
        *((c - box[:2]) / size),
        float(np.abs(pa - pb).max()) / GAP,
        min(la, lb) / 100,
        max(la, lb) / 100,
        float(not ie),
        float(not je),
        ends / 4,
        min(lines, 10) / 10,
        len(S) / 20,
        float(np.linalg.norm(S[i][0] - S[i][-1])) / 100,
        float(np.linalg.norm(S[j][0] - S[j][-1])) / 100,
        float(len(corners(S[i])) + len(corners(S[j]))) / 4,
        float(abs(ha @ fa) + abs(hb @ fb)) / 2,
        float(np.abs(pa - pb).max() > GAP),
        (len(link) + 1) / REACH if link is not None else 0.0,
    ]
    return np.asarray(f, np.float32)


def end_owner(points, at_end: bool, refs, reach: float = 8.0, skip: float = 1.0) -> int:
    """The reference stroke nearest most of the line within ``reach`` pixels of an end."""
    p = np.asarray(points, np.float64).reshape(-1, 2)
    q = p[::-1] if at_end else p
    s = _arclength(q)
    sel = (s >= skip) & (s <= reach)
    if not sel.any():
        sel = s <= reach
    return int(np.bincount(_owners(q[sel], refs)).argmax())


def join_pairs(strokes, pairs, ink=None, reach: int = REACH) -> list[np.ndarray]:
    """Strokes with the chosen end pairs joined, each end used once, no loops.

    ``pairs`` are taken in the order given (best first); one that would
    reuse an end or close a ring of strokes is skipped. A chain is drawn from
    its first stroke's free end; a stroke turned round inks the same pixels
    (:func:`jdraw.planner.ranker.reverse`). Two ends are linked by their
    :func:`bridge` over ``ink`` (straight if there is none), up to ``reach``.
    """
    S = [np.asarray(x, np.float64).reshape(-1, 2) for x in strokes]
    parent = list(range(len(S)))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    link: dict[tuple[int, bool], tuple[int, bool]] = {}
    for i, ie, j, je in pairs:
        if (i, ie) in link or (j, je) in link or find(i) == find(j):
            continue
        parent[find(i)] = find(j)
        link[(i, ie)] = (j, je)
        link[(j, je)] = (i, ie)
    out, seen = [], set()
    # Every chain has two free ends (no rings); walk each from the free end met first.
    for k, free in ((k, e) for k in range(len(S)) for e in (False, True)):
        if k in seen or (k, free) in link:
            continue
        parts, cur, enter = [], k, free
        while True:
            seen.add(cur)
            p = S[cur] if not enter else reverse(S[cur])  # from the end entered
            if parts:
                between = bridge(parts[-1][-1], p[0], ink, reach=reach)
                parts.append(_link(parts[-1][-1], p[0]) if between is None else between)
            parts.append(p)
            nxt = link.get((cur, not enter))  # leave by the other end
            if nxt is None:
                break
            cur, enter = nxt
        out.append(np.concatenate(parts))
    return out
