"""Splitting a drawn stroke where one person's stroke ends and the next begins.

Lines redrawn from a thick pen lose the small overshoot where two strokes
meet at a corner (the left side and the bottom of 口), so the local model
runs on round the corner and draws two strokes of a person as one, often a
whole box as one loop. A turn of the pen inside one stroke (the top-right
corner of 口, 乙) looks the same up close; which one a corner is depends on
the character around it. This stage learns it from KanjiVG: every sharp
corner of a drawn stroke (:func:`corners`) is described by its geometry and
its neighbourhood (:func:`corner_features`), and a small MLP
(:class:`Splitter`) gives the log-odds that the stroke should end there and
a new one begin. It is trained on the tracer's own strokes of training
characters drawn in several ways (:mod:`jdraw.train.splitter`), each corner
labelled by whether the reference strokes nearest the line on its two sides
differ (:func:`corner_labels`).

A split keeps every pixel: the two parts share the corner point, so the plan
inks exactly what it inked before; a join adds only the pixels between two
ends, and only where they are ink. Last, a crumb (a stroke of a few pixels
that touches another, most often what the local model left at a junction)
is drawn as part of the stroke it touches (:func:`jdraw.planner.joins.absorb_crumbs`).
"""

from __future__ import annotations

import pathlib

import jax
import numpy as np
from flax import nnx

from jdraw.planner.ranker import MLP

SPAN = 5.0  # pixels along the line on each side of a point that give its turn
MIN_TURN = 50.0  # degrees: a sharper turn is a corner candidate
MIN_ARM = 4.0  # pixels of line each side of a corner, at least
PATCH = 5  # pixels each side of a corner or a join the nets see of the ink and strokes
_SIDE = 2 * PATCH + 1
GEOMETRY_FEATURES = 23  # of a corner (corner_features)
CORNER_FEATURES = GEOMETRY_FEATURES + 3 * _SIDE * _SIDE  # with the patches (all_corners)


def _arclength(p: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-9)


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


def patch(img: np.ndarray, c) -> np.ndarray:
    """``float32 [(2 PATCH + 1)^2]``: the pixels of ``img`` around point ``c`` (x, y), 0 outside."""
    x, y = (int(v) for v in np.floor(np.asarray(c, np.float64) + 0.5))
    p = np.pad(np.asarray(img, np.float32), PATCH)
    return p[y : y + _SIDE, x : x + _SIDE].reshape(-1)


def corner_features(strokes, b: int, k: int, box=None, cs=None) -> np.ndarray:
    """``float32 [GEOMETRY_FEATURES]`` of corner ``k`` (a point index) of stroke ``b``.

    Its turn (signed, sharp over 2 pixels and wide over :data:`SPAN`), the
    headings in and out, where it is in the character's box, how much line
    runs before and after it and to the stroke's other corners, whether the
    stroke closes on itself, and how near other strokes and their ends come.
    """
    p = np.asarray(strokes[b], np.float64).reshape(-1, 2)
    if box is None:
        allp = np.concatenate([np.asarray(x, np.float64).reshape(-1, 2) for x in strokes])
        box = np.concatenate([allp.min(0), allp.max(0)])
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
    d = np.stack(
        [
            np.linalg.norm(p[:, None] - np.asarray(r, np.float64)[None], axis=-1).min(1)
            for r in refs
        ],
        1,
    )
    owner = d.argmin(1)

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


JOIN_GEOMETRY = 21  # of a pair of ends (join_features)
JOIN_FEATURES = JOIN_GEOMETRY + 3 * _SIDE * _SIDE
GAP = 3  # pixels (Chebyshev) between two stroke ends the join net looks at


def _end(p: np.ndarray, at_end: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The point of one end of a stroke, its outward heading and its turn there."""
    q = p if at_end else p[::-1]  # q runs towards the end
    s = _arclength(q)
    out = []
    for span in (SPAN, 2 * SPAN):
        k = max(int(np.searchsorted(s, s[-1] - span, side="right")) - 1, 0)
        out.append(_unit(q[-1] - q[k]))
    return q[-1], out[0], out[1]


def end_pairs(strokes, ink=None, gap: int = GAP) -> list[tuple[int, bool, int, bool]]:
    """Pairs of ends of different strokes at most ``gap`` pixels apart, joined on ink."""
    from jdraw.planner.joins import _link, _on_ink

    ends = [
        (i, e, (p[-1] if e else p[0]))
        for i, p in enumerate(np.asarray(x, np.float64).reshape(-1, 2) for x in strokes)
        if len(p) >= 2
        for e in (False, True)
    ]
    out = []
    for a in range(len(ends)):
        for b in range(a + 1, len(ends)):
            (i, ie, pa), (j, je, pb) = ends[a], ends[b]
            if i == j or np.abs(pa - pb).max() > gap:
                continue
            between = np.concatenate([pa[None], _link(pa, pb), pb[None]])
            if ink is not None and not _on_ink(between, ink):
                continue
            out.append((i, ie, j, je))
    return out


def join_features(strokes, pair, box=None) -> np.ndarray:
    """``float32 [JOIN_GEOMETRY]`` of joining two stroke ends (:func:`end_pairs`).

    How straight the line runs on through the two ends (near and further
    back), their headings, where they are, the gap, both strokes' lengths,
    whether each end is where its stroke began, and how crowded the place is
    (other ends and other lines near it).
    """
    S = [np.asarray(x, np.float64).reshape(-1, 2) for x in strokes]
    if box is None:
        allp = np.concatenate(S)
        box = np.concatenate([allp.min(0), allp.max(0)])
    size = np.maximum(box[2:] - box[:2], 1.0)
    i, ie, j, je = pair
    pa, ha, fa = _end(S[i], ie)
    pb, hb, fb = _end(S[j], je)
    c = (pa + pb) / 2
    la, lb = _arclength(S[i])[-1], _arclength(S[j])[-1]
    ends, lines = 0, 100.0
    for k, q in enumerate(S):
        for e in (q[0], q[-1]):
            if k not in (i, j) and np.abs(e - c).max() <= 2 * GAP:
                ends += 1
        if k not in (i, j):
            lines = min(lines, float(np.abs(q - c).max(-1).min()))
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
    d = np.stack(
        [
            np.linalg.norm(q[sel][:, None] - np.asarray(r, np.float64)[None], axis=-1).min(1)
            for r in refs
        ],
        1,
    )
    return int(np.bincount(d.argmin(1)).argmax())


def join_pairs(strokes, pairs) -> list[np.ndarray]:
    """Strokes with the chosen end pairs joined, each end used once, no loops.

    ``pairs`` are taken in the order given (best first); one that would
    reuse an end or close a ring of strokes is skipped. A chain is drawn from
    its first stroke's free end; a stroke turned round inks the same pixels
    (:func:`jdraw.planner.ranker.reverse`).
    """
    from jdraw.planner.joins import _link
    from jdraw.planner.ranker import reverse

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
                parts.append(_link(parts[-1][-1], p[0]))
            parts.append(p)
            nxt = link.get((cur, not enter))  # leave by the other end
            if nxt is None:
                break
            cur, enter = nxt
        out.append(np.concatenate(parts))
    return out


class Splitter(nnx.Module):
    """Log-odds that a drawn stroke should end at a corner (:func:`corner_features`)
    and that two stroke ends should be one line (:func:`join_features`)."""

    def __init__(self, hidden: int = 64, patches: bool = True, *, rngs: nnx.Rngs):
        self.hidden = hidden
        self.patches = patches  # whether the nets see the patches, or the geometry only
        self.split_net = MLP(CORNER_FEATURES if patches else GEOMETRY_FEATURES, hidden, rngs)
        self.join_net = MLP(JOIN_FEATURES if patches else JOIN_GEOMETRY, hidden, rngs)


@jax.jit
def _split_logits(graphdef, st, x):
    return nnx.merge(graphdef, st).split_net(x)


@jax.jit
def _join_logits(graphdef, st, x):
    return nnx.merge(graphdef, st).join_net(x)


def _score(fn, splitter, x: np.ndarray) -> np.ndarray:
    if not len(x):
        return np.zeros(0)
    g, st = nnx.split(splitter)
    rows = 1 << max(6, int(np.ceil(np.log2(len(x)))))  # few shapes, few compilations
    pad = np.zeros((rows, x.shape[1]), np.float32)
    pad[: len(x)] = x
    return np.asarray(fn(g, st, pad))[: len(x)]


def _box(strokes) -> np.ndarray:
    allp = np.concatenate([np.asarray(x, np.float64).reshape(-1, 2) for x in strokes])
    return np.concatenate([allp.min(0), allp.max(0)])


def _masks(strokes) -> np.ndarray:
    from jdraw.planner.stroke_tokens import stroke_masks

    return stroke_masks(strokes)


def all_corners(
    strokes, drawn=None, patches: bool = True
) -> tuple[list[tuple[int, int]], np.ndarray]:
    """Every corner of a character's strokes: ``[(stroke, point index)]`` and features.

    A corner's features are its geometry (:func:`corner_features`) and three
    patches around it (:func:`patch`): the ink as drawn (``drawn``, ``bool
    [H, W]``; a thick pen's outline tells a corner where two strokes meet from
    a turn), the stroke's own pixels and the other strokes' pixels;
    ``patches=False``: the geometry only.
    """
    keys, feats = [], []
    width = CORNER_FEATURES if patches else GEOMETRY_FEATURES
    found = [(b, p, corners(p)) for b, p in enumerate(strokes)]
    if any(len(cs) for _, _, cs in found):
        box = _box(strokes)
        if patches:
            masks = _masks(strokes)
            ink = masks.any(0) if drawn is None else np.asarray(drawn, bool)
        for b, p, cs in found:
            if patches and len(cs):
                others = masks[np.arange(len(masks)) != b].any(0)
            for k in cs:
                f = [corner_features(strokes, b, int(k), box, cs)]
                if patches:
                    c = np.asarray(p, np.float64).reshape(-1, 2)[k]
                    f += [patch(ink, c), patch(masks[b], c), patch(others, c)]
                keys.append((b, int(k)))
                feats.append(np.concatenate(f))
    return keys, np.asarray(feats, np.float32).reshape(-1, width)


def all_pairs(strokes, ink=None, drawn=None, patches: bool = True) -> tuple[list, np.ndarray]:
    """Every joinable pair of ends (:func:`end_pairs`, on ``ink``) and its features.

    Its geometry (:func:`join_features`) and three patches around the two
    ends' midpoint: the ink as drawn (``drawn``) and each stroke's pixels;
    ``patches=False``: the geometry only.
    """
    pairs = end_pairs(strokes, ink) if strokes else []
    feats = []
    if pairs:
        box = _box(strokes)
        if patches:
            masks = _masks(strokes)
            seen = masks.any(0) if drawn is None else np.asarray(drawn, bool)
        for q in pairs:
            f = [join_features(strokes, q, box)]
            if patches:
                i, ie, j, je = q
                pi = np.asarray(strokes[i], np.float64).reshape(-1, 2)
                pj = np.asarray(strokes[j], np.float64).reshape(-1, 2)
                c = ((pi[-1] if ie else pi[0]) + (pj[-1] if je else pj[0])) / 2
                f += [patch(seen, c), patch(masks[i], c), patch(masks[j], c)]
            feats.append(np.concatenate(f))
    width = JOIN_FEATURES if patches else JOIN_GEOMETRY
    return pairs, np.asarray(feats, np.float32).reshape(-1, width)


def split_many(
    splitter: Splitter, characters, drawn=None, threshold: float = 0.0
) -> list[list[np.ndarray]]:
    """Each character's strokes cut at the corners the splitter scores above ``threshold``.

    ``drawn``: each character's ink as drawn (:func:`all_corners`), or ``None``.
    """
    drawn = [None] * len(characters) if drawn is None else drawn
    found = [all_corners(s, d, splitter.patches) for s, d in zip(characters, drawn)]
    x = np.concatenate([f for _, f in found]) if found else np.zeros((0, 1))
    logit = _score(_split_logits, splitter, x)
    out, at = [], 0
    for strokes, (keys, _) in zip(characters, found):
        cut: dict[int, list[int]] = {}
        for (b, k), z in zip(keys, logit[at : at + len(keys)]):
            if z > threshold:
                cut.setdefault(b, []).append(k)
        at += len(keys)
        new = []
        for b, p in enumerate(strokes):
            new += split_at(p, cut[b]) if b in cut else [np.asarray(p, np.float64)]
        out.append(new)
    return out


def join_many(splitter: Splitter, characters, inks=None, drawn=None, threshold: float = 0.0):
    """Each character's strokes, the end pairs the join net scores above ``threshold`` joined.

    ``inks``: the ink planned (joins stay on it); ``drawn``: the ink as drawn.
    """
    inks = [None] * len(characters) if inks is None else inks
    drawn = [None] * len(characters) if drawn is None else drawn
    found = [all_pairs(s, ink, d, splitter.patches) for s, ink, d in zip(characters, inks, drawn)]
    x = np.concatenate([f for _, f in found]) if found else np.zeros((0, 1))
    logit = _score(_join_logits, splitter, x)
    out, at = [], 0
    for strokes, (pairs, _) in zip(characters, found):
        z = logit[at : at + len(pairs)]
        at += len(pairs)
        chosen = [pairs[k] for k in np.argsort(-z) if z[k] > threshold]
        out.append(join_pairs(strokes, chosen) if chosen else list(strokes))
    return out


def edit_plan(plan, splitter: Splitter, targets=None, max_rows: int | None = None, drawn=None):
    """A :class:`jdraw.Plan` with strokes cut at corners, joined where one line goes on.

    Strokes are cut (:func:`split_many`), then joined (:func:`join_many`;
    ``targets``, the ink planned, keeps joins on ink; ``drawn``, the images as
    given before they were canonicalised, shows the nets the pen's outline),
    then crumbs of a few
    pixels are drawn as part of the stroke they touch
    (:func:`jdraw.planner.joins.absorb_crumbs`). An image whose edited strokes
    would need more than ``max_rows`` action rows keeps its strokes.
    """
    from jdraw.planner.joins import absorb_crumbs
    from jdraw.plans import Plan, actions_from_strokes

    drawn = None if drawn is None else [np.asarray(d, bool) for d in drawn]
    cut = split_many(splitter, plan.strokes, drawn)
    inks = None if targets is None else [np.asarray(t, bool) for t in targets]
    new = join_many(splitter, cut, inks, drawn)
    strokes = []
    for old, s in zip(plan.strokes, new):
        s = absorb_crumbs(s)
        if max_rows is not None and len(actions_from_strokes(s)) > max_rows:
            s = old
        strokes.append(s)
    return Plan.from_strokes(strokes, plan.truncated, width=plan.actions.shape[1])


def save(splitter: Splitter, out_dir, provenance: dict | None = None) -> pathlib.Path:
    """Writes ``splitter.npz`` and ``splitter.json`` into a bundle folder."""
    from jdraw.model import bundle

    meta = {
        "hidden": splitter.hidden,
        "patches": splitter.patches,
        "corner_features": CORNER_FEATURES if splitter.patches else GEOMETRY_FEATURES,
        "join_features": JOIN_FEATURES if splitter.patches else JOIN_GEOMETRY,
        "provenance": provenance or {},
    }
    return bundle.save_net(splitter, out_dir, "splitter", meta)


def load(bundle_dir) -> Splitter | None:
    """The splitter stored in a bundle folder, or ``None`` if it has none."""
    from jdraw.model import bundle

    def build(meta):
        patches = bool(meta.get("patches", False))
        want = (CORNER_FEATURES, JOIN_FEATURES) if patches else (GEOMETRY_FEATURES, JOIN_GEOMETRY)
        sizes = (meta.get("corner_features", want[0]), meta.get("join_features", want[1]))
        if tuple(sizes) != want:
            raise bundle.BundleError(
                f"{pathlib.Path(bundle_dir) / 'splitter.json'}: made for {sizes} corner and "
                f"join features, this jdraw computes {want}; retrain it "
                "(configs/splitter_lean.py)"
            )
        return Splitter(int(meta.get("hidden", 64)), patches, rngs=nnx.Rngs(0))

    return bundle.load_net(bundle_dir, "splitter", build)
