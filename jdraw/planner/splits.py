"""Cutting a drawn stroke where one person's stroke ends, joining two that are one.

Lines redrawn from a thick pen lose the small overshoot where two strokes
meet at a corner (the left side and the bottom of 口), so the local model
runs on round the corner and draws two strokes of a person as one, often a
whole box as one loop; at crossings it still leaves one line in pieces. A
turn of the pen inside one stroke (the top-right corner of 口, 乙) looks the
same up close; which one a corner is depends on the character around it.
This stage learns it from KanjiVG: every sharp corner of a drawn stroke
(:func:`jdraw.planner.corners.corners`) and every pair of stroke ends close
together on ink (:func:`jdraw.planner.joins.end_pairs`) is described by its
geometry and neighbourhood (:func:`all_corners`, :func:`all_pairs`), and two
small MLPs (:class:`Splitter`) give the log-odds that the stroke should end
there and that the two ends are one line. They are trained on the tracer's
own strokes of training characters drawn in several ways
(:mod:`jdraw.train.splitter`), each corner labelled by whether the reference
strokes nearest the line on its two sides differ
(:func:`jdraw.planner.corners.corner_labels`).

A split keeps every pixel: the two parts share the corner point, so the plan
inks exactly what it inked before; a join adds only the pixels between two
ends, and only where they are ink: straight across a gap of a few pixels, or
along the ink over a crossing the line was broken at. A stroke all of whose
pixels others draw is then dropped. Last, a crumb (a stroke of a few pixels
that touches another, most often what the local model left at a junction)
is drawn as part of the stroke it touches (:func:`jdraw.planner.crumbs.absorb_crumbs`).
"""

from __future__ import annotations

import pathlib

import jax
import numpy as np
from flax import nnx

from jdraw.planner.corners import (
    GEOMETRY_FEATURES,
    _box,
    corner_features,
    corners,
    split_at,
    t_cuts,
)
from jdraw.planner.joins import (
    JOIN_GEOMETRY,
    REACH,
    crowd,
    end_links,
    join_features,
    join_pairs,
)
from jdraw.planner.more_joins import most_joins
from jdraw.planner.ranker import MLP, chunked, stack_mlps, with_context
from jdraw.planner.stroke_tokens import CONTEXT_FEATURES, context, stroke_masks, tokens

PATCH = 5  # pixels each side of a corner or a join the nets see of the ink and strokes
_SIDE = 2 * PATCH + 1
CORNER_FEATURES = GEOMETRY_FEATURES + 3 * _SIDE * _SIDE  # with the patches (all_corners)
JOIN_FEATURES = JOIN_GEOMETRY + 3 * _SIDE * _SIDE
NEAR_GEOMETRY = JOIN_GEOMETRY - 2  # a joiner of near ends only (reach 0) lacks the bridge's two
# Moves back over a stroke's own line a join may go in joined-up writing (jdraw.plan's
# ``retrace``, asked by jdraw.plan_image for such tiles): the reach that own-line joins
# were first trained and measured with (docs/scripts.md, 2026-12-05).
JOINED_RETRACE = 40


def join_width(patches: bool, reach: int) -> int:
    """How many features a splitter's join net reads (:class:`Splitter`)."""
    if patches:
        return JOIN_FEATURES
    return JOIN_GEOMETRY if reach else NEAR_GEOMETRY


def patch(img: np.ndarray, c) -> np.ndarray:
    """``float32 [(2 PATCH + 1)^2]``: the pixels of ``img`` around point ``c`` (x, y), 0 outside."""
    x, y = (int(v) for v in np.floor(np.asarray(c, np.float64) + 0.5))
    p = np.pad(np.asarray(img, np.float32), PATCH)
    return p[y : y + _SIDE, x : x + _SIDE].reshape(-1)


class Splitter(nnx.Module):
    """Log-odds that a drawn stroke should end at a corner (:func:`corner_features`)
    and that two stroke ends should be one line (:func:`join_features`).

    ``reach``: how far apart two ends linked through the ink may be to be
    joined (:func:`jdraw.planner.joins.bridge`); 0, only ends a few pixels
    apart, as the first splitters did (their nets lack the bridge's features).
    ``context``: every corner and pair also carries its drawing's
    :func:`~jdraw.planner.stroke_tokens.context` (:func:`drawing_rows`), so a
    corner of a kanji and one of a cursive word may be judged differently.
    """

    def __init__(
        self,
        hidden: int = 64,
        patches: bool = True,
        reach: int = REACH,
        *,
        context: bool = False,
        retrace: int = 0,
        rngs: nnx.Rngs,
    ):
        self.hidden = hidden
        self.patches = patches  # whether the nets see the patches, or the geometry only
        self.reach = reach
        self.retrace = int(retrace)  # further, back over one of the two strokes' own line
        self.context = bool(context)
        self.t_cuts = False  # whether its join net learned t_cuts' ends (where it retraces)
        c = CONTEXT_FEATURES if context else 0
        self.split_net = MLP((CORNER_FEATURES if patches else GEOMETRY_FEATURES) + c, hidden, rngs)
        self.join_net = MLP(join_width(patches, reach) + c, hidden, rngs)


def ensemble(splitters) -> Splitter:
    """One :class:`Splitter` whose every logit is the mean of ``splitters``' logits.

    Its two nets stack the members' side by side
    (:func:`jdraw.planner.ranker.stack_mlps`), so it is ``len(splitters)`` times as
    wide, and it is stored and loaded as any splitter of that width.
    """
    splitters = list(splitters)
    if not splitters:
        raise ValueError("an ensemble needs at least one splitter")
    first = splitters[0]
    kind = (first.hidden, first.patches, first.reach, first.context, first.retrace)
    if any((s.hidden, s.patches, s.reach, s.context, s.retrace) != kind for s in splitters):
        raise ValueError("the splitters of an ensemble must have the same width and inputs")
    out = Splitter(
        first.hidden * len(splitters), first.patches, first.reach, context=first.context,
        retrace=first.retrace, rngs=nnx.Rngs(0),
    )  # fmt: skip
    out.t_cuts = first.t_cuts
    for name in ("split_net", "join_net"):
        stack_mlps(getattr(out, name), [getattr(s, name) for s in splitters], first.hidden)
    return out


@jax.jit
def _split_logits(graphdef, st, x):
    return nnx.merge(graphdef, st).split_net(x)


@jax.jit
def _join_logits(graphdef, st, x):
    return nnx.merge(graphdef, st).join_net(x)


def _score(fn, splitter, x: np.ndarray) -> np.ndarray:
    """One logit per row of ``x``, in calls of one shape (:func:`jdraw.planner.ranker.chunked`)."""
    g, st = nnx.split(splitter)
    return chunked(fn, g, st, x) if len(x) else np.zeros(0)


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
            masks = stroke_masks(strokes)
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


def all_pairs(
    strokes, ink=None, drawn=None, patches: bool = True, reach: int = REACH, retrace: int = 0
) -> tuple[list, np.ndarray]:
    """Every joinable pair of ends (:func:`end_links`, on ``ink``, up to ``reach``
    apart through it) and its features.

    Its geometry (:func:`join_features`) and three patches around the two
    ends' midpoint: the ink as drawn (``drawn``) and each stroke's pixels;
    ``patches=False``: the geometry only.
    """
    found = end_links(strokes, ink, reach=reach, retrace=retrace) if strokes else []
    pairs = [q for q, _ in found]
    feats = []
    if pairs:
        box, near = _box(strokes), crowd(strokes)
        if patches:
            masks = stroke_masks(strokes)
            seen = masks.any(0) if drawn is None else np.asarray(drawn, bool)
        for q, link in found:
            g = join_features(strokes, q, box, link, near)
            f = [g if patches or reach else g[:NEAR_GEOMETRY]]
            if patches:
                i, ie, j, je = q
                pi = np.asarray(strokes[i], np.float64).reshape(-1, 2)
                pj = np.asarray(strokes[j], np.float64).reshape(-1, 2)
                c = ((pi[-1] if ie else pi[0]) + (pj[-1] if je else pj[0])) / 2
                f += [patch(seen, c), patch(masks[i], c), patch(masks[j], c)]
            feats.append(np.concatenate(f))
    width = join_width(patches, reach)
    return pairs, np.asarray(feats, np.float32).reshape(-1, width)


def drawing_rows(rows: np.ndarray, strokes, on: bool = True) -> np.ndarray:
    """``rows [K, F]`` of one drawing's corners or pairs, its context appended if ``on``."""
    if not on:
        return rows
    return with_context(rows, context(tokens(strokes)) if len(rows) else np.zeros(CONTEXT_FEATURES))


def split_many(
    splitter: Splitter, characters, drawn=None, threshold: float = 0.0
) -> list[list[np.ndarray]]:
    """Each character's strokes cut at the corners the splitter scores above ``threshold``.

    ``drawn``: each character's ink as drawn (:func:`all_corners`), or ``None``.
    """
    drawn = [None] * len(characters) if drawn is None else drawn
    found = [all_corners(s, d, splitter.patches) for s, d in zip(characters, drawn)]
    on = splitter.context
    rows = [drawing_rows(f, s, on) for (_, f), s in zip(found, characters)]
    x = np.concatenate(rows) if rows else np.zeros((0, 1))
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


def join_many(
    splitter: Splitter,
    characters,
    inks=None,
    drawn=None,
    threshold: float = 0.0,
    retrace: int | None = None,
):
    """Each character's strokes, the end pairs the join net scores above ``threshold`` joined.

    ``inks``: the ink planned (joins stay on it); ``drawn``: the ink as drawn;
    ``retrace``: how far back over a stroke's own line a join may go (``None``: the
    splitter's own); where it is not 0 and the splitter learned it (``t_cuts``), strokes
    are first cut where another's end meets their line
    (:func:`jdraw.planner.corners.t_cuts`), and a cut whose two ends no chosen join
    takes is joined again. Where ``retrace`` is not 0, as many of the chosen pairs are
    joined as can be (:func:`jdraw.planner.more_joins.most_joins`).
    """
    inks = [None] * len(characters) if inks is None else inks
    drawn = [None] * len(characters) if drawn is None else drawn
    retrace = splitter.retrace if retrace is None else int(retrace)
    seams = [[] for _ in characters]
    if retrace and splitter.t_cuts:  # a branch may be drawn on the way through
        cut = [t_cuts(s, with_seams=True) for s in characters]
        characters, seams = [c for c, _ in cut], [m for _, m in cut]
    found = [
        all_pairs(s, ink, d, splitter.patches, splitter.reach, retrace)
        for s, ink, d in zip(characters, inks, drawn)
    ]
    on = splitter.context
    rows = [drawing_rows(f, s, on) for (_, f), s in zip(found, characters)]
    x = np.concatenate(rows) if rows else np.zeros((0, 1))
    logit = _score(_join_logits, splitter, x)
    out, at = [], 0
    for strokes, ink, (pairs, _), seam in zip(characters, inks, found, seams):
        z = logit[at : at + len(pairs)]
        at += len(pairs)
        chosen = [pairs[k] for k in np.argsort(-z) if z[k] > threshold]
        chosen += seam  # a T's cut that no join took is joined again, last
        if retrace:  # joined-up writing: one join given up for two where that can be
            chosen = most_joins(chosen, len(strokes))
        reach = max(splitter.reach, retrace)
        out.append(join_pairs(strokes, chosen, ink, reach) if chosen else list(strokes))
    return out


def drop_covered(strokes) -> list:
    """Strokes without those whose every pixel another stroke inks, smallest first.

    A join through the ink (:func:`jdraw.planner.joins.bridge`) draws again a
    crossing that the local model may have drawn as a piece of its own; that
    piece is then drawn twice. The plan inks the same pixels without it.
    """
    if len(strokes) < 2:
        return list(strokes)
    masks = stroke_masks(strokes)
    count = masks.sum(0)
    keep = np.ones(len(strokes), bool)
    for k in np.argsort(masks.sum((1, 2)), kind="stable"):
        if masks[k].any() and (count[masks[k]] >= 2).all():
            keep[k] = False
            count -= masks[k]
    return [s for s, kept in zip(strokes, keep) if kept]


def edit_plan(
    plan,
    splitter: Splitter,
    targets=None,
    max_rows: int | None = None,
    drawn=None,
    retrace: int | None = None,
):
    """A :class:`jdraw.Plan` with strokes cut at corners, joined where one line goes on.

    Strokes are cut (:func:`split_many`), then joined (:func:`join_many`;
    ``targets``, the ink planned, keeps joins on ink; ``drawn``, the images as
    given before they were canonicalised, shows the nets the pen's outline;
    ``retrace``, how far back over a stroke's own line a join may go),
    then strokes drawn over by others are dropped (:func:`drop_covered`) and
    crumbs of a few pixels are drawn as part of the stroke they touch
    (:func:`jdraw.planner.crumbs.absorb_crumbs`). An image whose edited strokes
    would need more than ``max_rows`` action rows keeps its strokes.
    """
    from jdraw.planner.crumbs import absorb_crumbs
    from jdraw.plans import Plan, actions_from_strokes

    drawn = None if drawn is None else [np.asarray(d, bool) for d in drawn]
    cut = split_many(splitter, plan.strokes, drawn)
    inks = None if targets is None else [np.asarray(t, bool) for t in targets]
    new = join_many(splitter, cut, inks, drawn, retrace=retrace)
    strokes = []
    for old, s in zip(plan.strokes, new):
        s = absorb_crumbs(drop_covered(s))
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
        "reach": splitter.reach,
        "context": splitter.context,
        "retrace": splitter.retrace,
        "t_cuts": splitter.t_cuts,
        "corner_features": CORNER_FEATURES if splitter.patches else GEOMETRY_FEATURES,
        "join_features": join_width(splitter.patches, splitter.reach),
        "provenance": provenance or {},
    }
    return bundle.save_net(splitter, out_dir, "splitter", meta)


def load(bundle_dir) -> Splitter | None:
    """The splitter stored in a bundle folder, or ``None`` if it has none."""
    from jdraw.model import bundle

    def build(meta):
        patches = bool(meta.get("patches", False))
        reach = int(meta.get("reach", 0))  # the first splitters joined near ends only
        want = (CORNER_FEATURES if patches else GEOMETRY_FEATURES, join_width(patches, reach))
        sizes = (meta.get("corner_features", want[0]), meta.get("join_features", want[1]))
        if tuple(sizes) != want:
            raise bundle.BundleError(
                f"{pathlib.Path(bundle_dir) / 'splitter.json'}: made for {sizes} corner and "
                f"join features, this jdraw computes {want}; retrain it "
                "(configs/default.py, stage splitter)"
            )
        ctx = bool(meta.get("context", False))
        sp = Splitter(
            int(meta.get("hidden", 64)),
            patches,
            reach,
            context=ctx,
            retrace=int(meta.get("retrace", 0)),
            rngs=nnx.Rngs(0),
        )
        sp.t_cuts = bool(meta.get("t_cuts", False))
        return sp

    return bundle.load_net(bundle_dir, "splitter", build)
