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
"""

from __future__ import annotations

import numpy as np

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


CRUMB = 5  # pixels: a stroke this short that touches another is drawn as part of it


def absorb_crumbs(strokes, crumb: int = CRUMB) -> list:
    """Strokes with each crumb drawn as part of a stroke it touches.

    A crumb is a stroke of at most ``crumb`` pixels, most often a pixel or two
    the local model left at a junction and came back for: a pen lift of its
    own for a dot of ink no person would lift for. When one of its ends
    touches (8-neighbour) another stroke, it is drawn there: on from that
    stroke's end if it touches an end, else as a detour out along it and back
    from the point it touches. No pixel is added or lost. Crumbs that touch
    nothing (a dot) stay strokes of their own.
    """
    from jdraw.planner.stroke_tokens import path_pixels

    S = [np.asarray(s, np.float64).reshape(-1, 2) for s in strokes]
    # A path inks at least as many pixels as its box is long: only short ones are counted.
    size = [
        len(path_pixels(s)) if np.ptp(s, axis=0).max() < crumb else crumb + 1 + len(s) for s in S
    ]
    k = 0
    while k < len(S):
        if size[k] > crumb or len(S) < 2:
            k += 1
            continue
        c = S[k]
        host = None
        for j, p in enumerate(S):
            if j == k:
                continue
            for from_start in (True, False):
                d = np.abs(p - (c[0] if from_start else c[-1])).max(-1)
                i = int(d.argmin())
                if d[i] <= 1 and (host is None or size[j] > size[host[0]]):
                    host = (j, i, from_start)
        if host is None:
            k += 1
            continue
        j, i, from_start = host
        out = c if from_start else reverse(c)  # the crumb from the end touching the host
        p = S[j]
        if i == len(p) - 1:
            S[j] = np.concatenate([p, out])
        elif i == 0:
            S[j] = np.concatenate([reverse(out), p])
        else:
            back = reverse(out)
            S[j] = np.concatenate([p[: i + 1], out, back[1:], p[i:]])
        size[j] += size[k]
        del S[k], size[k]
        k = 0  # a host may now touch another crumb
    return S
