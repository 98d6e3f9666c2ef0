"""Training the stroke splitter (:mod:`jdraw.planner.splits`) on the tracer's own strokes.

The tracer (a planner bundle) plans augmented training characters drawn in
several ways, as for the ranker (:func:`jdraw.train.ranker.traced_chunk`).
Every sharp corner of a drawn stroke becomes a split example, labelled by
whether the reference strokes nearest the line on its two sides differ
(:func:`jdraw.planner.corners.corner_labels`). The strokes are then cut at the
true splits, and every pair of stroke ends close together on ink becomes a
join example, labelled by whether the line near both ends is one reference
stroke (ends a few pixels further apart count too when a short path
through the ink links them, :func:`jdraw.planner.joins.bridge`). Examples
are saved in the workdir a chunk at a time, so an interrupted run resumes
where it stopped; the nets train in seconds.
"""

from __future__ import annotations

import json
import pathlib
import time

import jax
import jax.numpy as jnp
import numpy as np
import optax
from flax import nnx

from jdraw.planner import corners, joins, splits
from jdraw.train.ranker import (
    chunk_jobs,
    made_chunks,
    read_chunks,
    seed_members,
    set_groups,
    shares_of,
)


def examples(
    traced,
    refs,
    ink,
    drawn=None,
    reach: int = joins.REACH,
    retrace: int = 0,
    t_cuts: bool = False,
) -> tuple[np.ndarray, ...]:
    """Split and join examples of one character: ``(xs, ys, xj, yj, cs, cj)``.

    ``cs`` and ``cj`` are the drawing's context (:func:`jdraw.planner.splits.drawing_rows`)
    for each corner (of the traced strokes) and each pair (of the strokes cut), which only
    a splitter with ``context`` reads.

    Args:
      traced: the tracer's strokes; refs: the reference strokes; ink: the ink
        planned (canonical); drawn: the ink as drawn before it was canonicalised;
        reach: pixels between ends joined through the ink (0: near ends only);
        retrace: further, up to this many, back over one of the two strokes' line.
        t_cuts: where ``retrace`` is not 0, also cut the strokes where another's end
          meets their line (:func:`jdraw.planner.corners.t_cuts`), as a splitter that
          learned them does in ``join_many``.
    """
    strokes, xs, ys, cut, pairs, xj, yj = join_examples(
        traced, refs, ink, drawn, reach, retrace, t_cuts
    )
    ctx = lambda rows, s: splits.drawing_rows(rows[:, :0], s)
    return xs, ys, xj, yj, ctx(xs, strokes), ctx(xj, cut)


def join_examples(
    traced,
    refs,
    ink,
    drawn=None,
    reach: int = joins.REACH,
    retrace: int = 0,
    t_cuts: bool = False,
):
    """:func:`examples` with the strokes and pairs they are of, not the context:
    ``(strokes, xs, ys, cut, pairs, xj, yj)``: the traced strokes, their corners'
    features and labels, the strokes cut at the true corners (and T's), their end
    pairs (``(i, i_at_end, j, j_at_end)`` into ``cut``), the pairs' features and labels.
    """
    strokes = [np.asarray(s, np.float64).reshape(-1, 2) for s in traced if len(s)]
    keys, xs = splits.all_corners(strokes, drawn)  # grouped by stroke, in stroke order
    by_stroke: dict[int, list[int]] = {}
    for b, k in keys:
        by_stroke.setdefault(b, []).append(k)
    cut, ys = [], []
    for b, p in enumerate(strokes):
        ks = np.asarray(by_stroke.get(b, []), np.int64)
        lab = corners.corner_labels(p, ks, refs) if len(ks) else np.zeros(0, bool)
        ys.append(lab)
        cut += corners.split_at(p, ks[lab]) if lab.any() else [p]
    ys = np.concatenate(ys) if ys else np.zeros(0)
    seams = set()
    if retrace and t_cuts:  # as jdraw.planner.splits.join_many cuts them
        cut, seam = corners.t_cuts(cut, with_seams=True)
        seams = set(seam)
    pairs, xj = splits.all_pairs(cut, ink, drawn, reach=reach, retrace=retrace)
    yj = [
        through(cut[i], cut[j], refs)
        if (i, ie, j, je) in seams
        else joins.end_owner(cut[i], ie, refs) == joins.end_owner(cut[j], je, refs)
        for i, ie, j, je in pairs
    ]
    return (
        strokes,
        xs,
        np.asarray(ys, np.float32),
        cut,
        pairs,
        xj,
        np.asarray(yj, np.float32),
    )


NEAR = 2.0  # pixels: a reference stroke this near a line follows it
ARM = 8.0  # pixels of line each side of a T's cut that the writer must run along


def _resampled(p: np.ndarray) -> np.ndarray:
    """``p`` with a point every half pixel along it."""
    s = corners._arclength(p)
    t = np.arange(0.0, s[-1] + 0.5, 0.5) if s[-1] > 0 else np.zeros(1)
    return np.stack([np.interp(t, s, p[:, 0]), np.interp(t, s, p[:, 1])], 1)


def _arm(p: np.ndarray) -> np.ndarray:
    """The points of ``p`` from 1 to ARM pixels along it from its first point."""
    s = corners._arclength(p)
    return p[(s >= 1.0) & (s <= ARM)]


def through(first: np.ndarray, second: np.ndarray, refs) -> bool:
    """Whether a reference stroke runs straight on from ``first``'s end into ``second``
    (two parts of a line cut apart at a T, sharing the point): the label of joining them
    again. A cursive writer who draws the branch on the way (an e's loop) comes to the
    point twice, from the first part into the branch and from the branch into the second,
    and never from one part straight into the other.
    """
    a = _arm(np.asarray(first, np.float64)[::-1])  # back along the first part
    b = _arm(np.asarray(second, np.float64))
    if not len(a) or not len(b):
        return False
    j = np.asarray(second, np.float64)[0]
    for r in refs:
        r = _resampled(np.asarray(r, np.float64).reshape(-1, 2))
        at = np.flatnonzero(np.hypot(*(r - j).T) <= NEAR + 1.0)
        runs = np.split(at, np.flatnonzero(np.diff(at) > 1) + 1) if len(at) else []
        for run in runs:
            m = int(2 * ARM) + 2  # points every half pixel
            c = int(run[np.argmin(np.hypot(*(r[run] - j).T))])  # the pass nearest the point
            before, after = r[max(c - m, 0) : c + 1], r[c : c + m + 1]
            if len(before) < 2 or len(after) < 2:
                continue
            near = lambda q, line: np.hypot(*(q[:, None] - line[None]).T).min(0).max() <= NEAR
            if (near(a, before) and near(b, after)) or (near(a, after) and near(b, before)):
                return True
    return False


def fit(
    data,
    *,
    steps: int = 3000,
    batch: int = 512,
    lr: float = 3e-3,
    seed: int = 0,
    patches: bool = True,
    hidden: int = 64,
    reach: int = joins.REACH,
    context: bool = False,
    retrace: int = 0,
    join_draw=None,
    join_weight=None,
):
    """Fits a :class:`jdraw.planner.splits.Splitter` on stacked :func:`examples`.

    ``patches=False`` fits nets that see the geometry only (the first
    features of each example); ``reach`` is the one the examples were made with;
    ``context``: the nets also see each drawing's context (``data``'s last two arrays);
    ``retrace``: the one the examples were made with (kept in the splitter);
    ``join_draw``: ``(groups [J] int, p [G] float)``, each end pair's set and each
    set's share of a batch's pairs (:func:`jdraw.train.ranker.shares_of`); ``None``:
    pairs drawn uniformly, as corners always are; ``join_weight``: ``[J]`` float, what
    each end pair weighs in the join loss (:func:`negative_weights`); ``None``: 1 each.
    """
    xs, ys, xj, yj = data[:4]
    if not patches:
        xs = xs[:, : corners.GEOMETRY_FEATURES]
        xj = xj[:, : splits.join_width(False, reach)]
    if context:
        xs, xj = np.concatenate([xs, data[4]], -1), np.concatenate([xj, data[5]], -1)
    model = splits.Splitter(
        hidden, patches, reach, context=context, retrace=retrace, rngs=nnx.Rngs(seed)
    )
    tx = optax.adam(lr)
    graphdef, params = nnx.split(model, nnx.Param)
    opt = tx.init(params)

    wj = (
        np.ones(len(xj), np.float32) if join_weight is None else np.asarray(join_weight, np.float32)
    )

    def loss_fn(params, a, la, b, lb, wb):
        m = nnx.merge(graphdef, params)
        za, zb = m.split_net(a), m.join_net(b)
        jl = optax.sigmoid_binary_cross_entropy(zb, lb)
        loss = jnp.mean(optax.sigmoid_binary_cross_entropy(za, la)) + jnp.sum(
            wb * jl
        ) / jnp.maximum(jnp.sum(wb), 1e-6)
        return loss, (jnp.mean((za > 0) == (la > 0.5)), jnp.mean((zb > 0) == (lb > 0.5)))

    @jax.jit
    def step(params, opt, a, la, b, lb, wb):
        (loss, accs), g = jax.value_and_grad(loss_fn, has_aux=True)(params, a, la, b, lb, wb)
        upd, opt = tx.update(g, opt, params)
        return optax.apply_updates(params, upd), opt, loss, accs

    rng = np.random.default_rng(seed)
    if join_draw is not None:
        members = [np.flatnonzero(join_draw[0] == g) for g in range(len(join_draw[1]))]
    logs = []
    for s in range(steps):
        i = rng.integers(len(xs), size=batch)
        if join_draw is None:
            j = rng.integers(len(xj), size=batch)
        else:
            counts = rng.multinomial(batch, join_draw[1])
            j = np.concatenate([m[rng.integers(len(m), size=c)] for m, c in zip(members, counts)])
        params, opt, loss, accs = step(params, opt, xs[i], ys[i], xj[j], yj[j], wj[j])
        if s % 500 == 0 or s == steps - 1:
            logs.append(
                {
                    "step": s,
                    "loss": float(loss),
                    "split_acc": float(accs[0]),
                    "join_acc": float(accs[1]),
                }
            )
    nnx.update(model, params)
    return model, logs


def negative_weights(groups: np.ndarray, labels: np.ndarray, weights) -> np.ndarray:
    """``float32 [J]``: what each end pair weighs in the join loss. A pair labelled "do
    not join" (``labels`` 0) from a set that ``weights`` names (``groups``: each pair's
    set) weighs that set's number; every other pair 1.

    In joined-up writing nearly every pair the trainer offers is "join", and the few that
    are not (a t's or an x's cross and the line it crosses) are what the net must learn
    not to take: weighing them more makes missing one cost as much as missing several joins.
    """
    w = np.ones(len(labels), np.float32)
    for name, v in dict(weights or {}).items():
        if float(v) <= 0:
            raise ValueError(f"join_negatives[{name!r}] = {v}: a weight must be > 0")
        w[(np.asarray(groups) == name) & (np.asarray(labels) < 0.5)] = float(v)
    return w


def fit_members(data, cfg, join_draw=None, join_weight=None):
    """``(splitter, logs)``: :func:`fit` with ``cfg``'s settings, ``cfg.members`` times.

    Member ``k`` is fitted with seed ``cfg.seed + k``; more than one are returned as
    their :func:`jdraw.planner.splits.ensemble`
    (:func:`jdraw.train.ranker.seed_members`, as the ranker's are).
    """

    def fit_one(seed):
        return fit(
            data,
            steps=int(cfg.steps),
            batch=int(cfg.batch),
            lr=float(cfg.learning_rate),
            seed=seed,
            patches=bool(cfg.get("patches", True)),
            hidden=int(cfg.get("hidden", 64)),
            reach=int(cfg.get("reach", joins.REACH)),
            context=bool(cfg.get("context", False)),
            retrace=int(cfg.get("retrace", 0)),
            join_draw=join_draw,
            join_weight=join_weight,
        )

    return seed_members(cfg, fit_one, splits.ensemble)


def retrace_for(target: np.ndarray, retrace: int, where: str = "everywhere") -> int:
    """How far back over a stroke's own line a drawing's join examples reach.

    ``retrace`` everywhere, or with ``where="joined"`` only in a drawing that
    ``plan_image`` would plan as joined-up writing
    (:func:`jdraw.tiling.layout.mostly_joined` of its 1-pixel lines ``target``), 0
    elsewhere.
    """
    from jdraw.tiling.layout import mostly_joined

    if not retrace or where == "everywhere":
        return int(retrace)
    return int(retrace) if mostly_joined(target) else 0


def make_examples(cfg, workdir, progress: bool = True) -> list[pathlib.Path]:
    """Examples in chunks of ``cfg.chunk`` traced characters, one npz each, whole or not at all.

    KanjiVG's training characters, and ``cfg.get("extra")``'s other sets
    (:mod:`jdraw.data.mix`), each planned by the tracer without a splitter. End pairs
    up to ``cfg.retrace`` apart back over a stroke's own line are candidates in every
    drawing, or with ``cfg.retrace_where = "joined"`` only in drawings that
    ``plan_image`` would plan as joined-up writing
    (:func:`jdraw.tiling.layout.mostly_joined`), as it asks for them there only. With
    ``cfg.t_cuts``, strokes there are also cut at T's (:func:`examples`).
    """
    reach = int(cfg.get("reach", joins.REACH))
    retrace = int(cfg.get("retrace", 0))
    where = cfg.get("retrace_where", "everywhere")
    r, cuts = retrace, bool(cfg.get("t_cuts", False))
    if where not in ("everywhere", "joined"):
        raise ValueError(f"retrace_where must be 'everywhere' or 'joined', got {where!r}")

    def label(demos, drawn):
        return [
            examples(s, d.strokes, d.target, d.drawn, reach, retrace_for(d.target, r, where), cuts)
            for d, s in zip(demos, drawn)
        ]

    return made_chunks(cfg, workdir, label, progress=progress)


def load_examples(paths, context: bool = False) -> tuple[np.ndarray, ...]:
    """Stacked :func:`examples` of every chunk; the context arrays too if ``context``."""
    try:
        data = read_chunks(paths, 6 if context else 4)
    except KeyError as e:
        raise ValueError(
            f"{pathlib.Path(paths[0]).parent}: examples made before they carried their "
            "drawing's context; delete them to remake them"
        ) from e
    made = (data[0].shape[1], data[2].shape[1])
    want = (splits.CORNER_FEATURES, splits.JOIN_FEATURES)
    if made != want:
        raise ValueError(
            f"{pathlib.Path(paths[0]).parent}: examples of {made} corner and join features, "
            f"this jdraw makes {want}; delete them to remake them"
        )
    return data


def train(cfg, workdir, progress: bool = True) -> dict:
    """Makes (or reuses) the examples, fits the splitter, writes it into ``cfg.out``.

    With ``cfg.members`` = k > 1, k splitters are fitted on the same examples (seeds
    ``cfg.seed`` to ``cfg.seed + k - 1``) and written as one, their mean
    (:func:`jdraw.planner.splits.ensemble`). ``cfg.join_negatives`` (``{set: weight}``):
    what a "do not join" end pair of each named set weighs in the join loss
    (:func:`negative_weights`).
    """
    workdir = pathlib.Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    negatives = dict(cfg.get("join_negatives", None) or {})
    unknown = set(negatives) - {name for name, _, _ in chunk_jobs(cfg)} if negatives else ()
    if unknown:  # before the tracing, not after it
        raise ValueError(f"join_negatives names sets not trained on: {sorted(unknown)}")
    (workdir / "config.json").write_text(cfg.to_json_best_effort(indent=2) + "\n")
    t0 = time.time()
    paths = make_examples(cfg, workdir, progress=progress)
    t1 = time.time()
    context = bool(cfg.get("context", False))
    data = load_examples(paths, context)
    draw = weight = None
    if cfg.get("join_shares", None) or negatives:
        names = [name for name, _, _ in chunk_jobs(cfg)]
        groups = set_groups(paths, names)[1]
        if cfg.get("join_shares", None):
            draw = shares_of(groups, dict(cfg.join_shares), known=names)
        if negatives:
            weight = negative_weights(groups, data[3], negatives)
    model, logs = fit_members(data, cfg, draw, weight)
    t2 = time.time()
    result = {
        "corners": int(len(data[0])),
        "corner_splits": int(data[1].sum()),
        "end_pairs": int(len(data[2])),
        "end_joins": int(data[3].sum()),
        "trace_s_this_call": t1 - t0,
        "fit_s": t2 - t1,
        "logs": logs,
    }
    model.t_cuts = bool(cfg.get("t_cuts", False))  # join_many cuts as the examples were
    if "bundle_retrace" in cfg:  # what jdraw.plan asks of it unless told (plan_image: more)
        model.retrace = int(cfg.bundle_retrace)
    out = splits.save(model, cfg.out, provenance={"config": json.loads(cfg.to_json()), **result})
    splits.save(model, workdir / "splitter")
    (workdir / "result.json").write_text(json.dumps(result, indent=2) + "\n")
    result["out"] = str(out)
    return result
