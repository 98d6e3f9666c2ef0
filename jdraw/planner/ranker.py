"""A learned ordering stage: which of the traced strokes comes first, and which way.

The two-scale planner traces strokes well, but a start model that sees a
neighbourhood cannot order them like a person. This stage looks at the strokes
the planner drew as tokens of geometry (start, end, centre, box, heading,
length, and how two strokes touch or cross) and learns from KanjiVG's order,
on the tracer's own strokes, two small functions:

* ``pair(a, b)``: the log-odds that stroke ``a`` is written before ``b``
  (antisymmetric by construction, RankNet loss);
* ``heading(s)``: the log-odds that ``s`` is drawn in the right direction
  (``h(s) - h(reversed s)``, so flipping a stroke flips the sign).

Strokes are flipped where ``heading < 0`` and ranked by their summed pairwise
probabilities, then adjacent swaps that raise the pairwise log-likelihood are
made until none does. Flipping walks a stroke's pixel path backwards, so the
plan inks exactly the same pixels.

Several rankers fitted with different seeds are one ranker with their mean
scores (:func:`ensemble`): each net of the result is as wide as theirs
together, its second layer block-diagonal, so a bundle stores and runs it as
any other ranker.
"""

from __future__ import annotations

import functools
import pathlib

import jax
import jax.numpy as jnp
import numpy as np
from flax import nnx

from jdraw.geometry import CANVAS
from jdraw.planner.stroke_tokens import (  # noqa: F401 (the ranker's inputs, named here too)
    CONTEXT_FEATURES,
    PAIR_FEATURES,
    STROKE_FEATURES,
    Tokens,
    flipped,
    pair_inputs,
    path_pixels,
    stroke_features,
    stroke_masks,
    tokens,
)
from jdraw.planner.stroke_tokens import context as drawing_context
from jdraw.plans import actions_from_strokes


class MLP(nnx.Module):
    """Two hidden ReLU layers and one output: the ranker's and the splitter's small nets."""

    def __init__(self, din: int, hidden: int, rngs: nnx.Rngs):
        self.l1 = nnx.Linear(din, hidden, rngs=rngs)
        self.l2 = nnx.Linear(hidden, hidden, rngs=rngs)
        self.out = nnx.Linear(hidden, 1, rngs=rngs)

    def __call__(self, x):
        return self.out(jax.nn.relu(self.l2(jax.nn.relu(self.l1(x)))))[..., 0]


class Ranker(nnx.Module):
    """Pairwise order and per-stroke heading scores (see the module docstring).

    ``context``: with ``True``, every pair's and stroke's inputs also carry the
    drawing's :func:`~jdraw.planner.stroke_tokens.context` (``CONTEXT_FEATURES``
    numbers), so one ranker can learn different rules for different kinds of
    drawing; ``False`` is the ranker the bundles before it hold.
    """

    def __init__(self, hidden: int = 64, *, context: bool = False, rngs: nnx.Rngs):
        self.hidden = hidden
        self.context = bool(context)
        c = CONTEXT_FEATURES if context else 0
        self.pair_net = MLP(PAIR_FEATURES + c, hidden, rngs)
        self.heading_net = MLP(STROKE_FEATURES + c, hidden, rngs)

    def pair(self, x_ab, x_ba):
        """Log-odds that a precedes b, from both orders' inputs ``[..., PAIR_FEATURES]``."""
        return self.pair_net(x_ab) - self.pair_net(x_ba)

    def heading(self, f, rf):
        """Log-odds that strokes ``f [..., F]`` (reversed: ``rf``) run the right way."""
        return self.heading_net(f) - self.heading_net(rf)


def stack_mlps(dst: MLP, src, hidden: int) -> None:
    """Sets ``dst`` (``len(src) * hidden`` wide) to the mean of the :class:`MLP` s ``src``.

    The first layers' units are concatenated, the second layer is block-diagonal
    (no unit sees another member's), and the output averages the members' outputs.
    """
    k = len(src)
    dst.l1.kernel[...] = jnp.concatenate([m.l1.kernel[...] for m in src], 1)
    dst.l1.bias[...] = jnp.concatenate([m.l1.bias[...] for m in src])
    w2 = jnp.zeros((hidden * k, hidden * k), dst.l2.kernel[...].dtype)
    for i, m in enumerate(src):
        w2 = w2.at[i * hidden : (i + 1) * hidden, i * hidden : (i + 1) * hidden].set(
            m.l2.kernel[...]
        )
    dst.l2.kernel[...] = w2
    dst.l2.bias[...] = jnp.concatenate([m.l2.bias[...] for m in src])
    dst.out.kernel[...] = jnp.concatenate([m.out.kernel[...] for m in src], 0) / k
    dst.out.bias[...] = sum(m.out.bias[...] for m in src) / k


def ensemble(rankers) -> Ranker:
    """One :class:`Ranker` whose every score is the mean of ``rankers``' scores.

    Each of its two nets stacks the members' nets side by side (:func:`stack_mlps`),
    so ``pair`` and ``heading`` are exactly the members' mean, and the result is
    ``len(rankers)`` times as wide as they are.
    """
    rankers = list(rankers)
    if not rankers:
        raise ValueError("an ensemble needs at least one ranker")
    h, ctx = rankers[0].hidden, rankers[0].context
    if any(r.hidden != h or r.context != ctx for r in rankers):
        raise ValueError("the rankers of an ensemble must have the same width and inputs")
    out = Ranker(h * len(rankers), context=ctx, rngs=nnx.Rngs(0))
    for name in ("pair_net", "heading_net"):
        stack_mlps(getattr(out, name), [getattr(r, name) for r in rankers], h)
    return out


# ----------------------------------------------------------------------------
# Inference.


@jax.jit
def _headings(graphdef, st, f, rf):
    return nnx.merge(graphdef, st).heading(f, rf)


@jax.jit
def _pair_net(graphdef, st, x):
    return nnx.merge(graphdef, st).pair_net(x)


CHUNK = 256  # rows per network call: one shape, compiled once, whatever the strokes


def net_call(fn, g, st, *xs):
    """``fn(g, st, *xs)``, a small jitted net, by its compiled program.

    The program comes from jdraw's program store (:mod:`jdraw.planner.executables`),
    so a warm start neither traces nor lowers it to find JAX's cache key; within a
    process it is looked up by the net's graph and the rows' shapes alone.
    """
    from jdraw.planner import executables

    k = (fn, g, tuple((x.shape, x.dtype) for x in xs))  # equal graphs, one program
    exe = _PROGRAMS.get(k)
    if exe is None:
        with executables.LOADING:  # planner threads load each program once
            exe = _PROGRAMS.get(k)
            if exe is None:
                args, devices = (st, *xs), jax.local_devices()[:1]
                exe = executables.compiled(f"net-{fn.__name__}", _bound(fn, g), (g,), args, devices)
                _PROGRAMS[k] = exe
    try:
        return exe(st, *xs)
    except jax.errors.JaxRuntimeError:  # a stored program that does not run here
        bound = _bound(fn, g)
        if exe is bound:
            raise
        executables.forget(f"net-{fn.__name__}", (g,), (st, *xs), jax.local_devices()[:1])
        _PROGRAMS[k] = bound
        return bound(st, *xs)


_PROGRAMS: dict = {}  # (net function, its graph, row shapes) -> its compiled program


@functools.lru_cache(maxsize=64)
def _bound(fn, g):
    """``fn`` with its graph fixed: the program store keys the graph as a setting, by its repr."""
    return jax.jit(lambda st, *xs: fn(g, st, *xs))


def chunked(fn, g, st, *xs) -> np.ndarray:
    """``fn(g, st, *rows)`` over the rows of ``xs``, ``CHUNK`` rows a call."""
    n = len(xs[0])
    out = [
        np.asarray(net_call(fn, g, st, *(_pad(x[k : k + CHUNK], CHUNK) for x in xs)))
        for k in range(0, n, CHUNK)
    ]
    return np.concatenate(out)[:n] if out else np.zeros(0, np.float32)


def order_strokes(ranker: Ranker, strokes) -> tuple[list[int], list[bool]]:
    """The order and the flips the ranker chooses for one character's strokes.

    Returns:
      ``(order, flip)``: ``order`` lists stroke indices in drawing order;
      ``flip[i]`` says stroke ``i`` is to be drawn backwards.
    """
    return order_many(ranker, [strokes])[0]


def mirrored(strokes) -> list[np.ndarray]:
    """Strokes mirrored left to right on the canvas (x -> 99 - x): how right-to-left script
    looks to a ranker that learned left-to-right order."""
    out = []
    for s in strokes:
        p = np.array(s, np.float64).reshape(-1, 2)
        p[:, 0] = CANVAS - 1 - p[:, 0]
        out.append(p)
    return out


def order_many(
    ranker: Ranker, characters, mirror: bool = False
) -> list[tuple[list[int], list[bool]]]:
    """:func:`order_strokes` for many characters, their strokes scored together.

    Every stroke and stroke pair is scored in calls of ``CHUNK`` rows, so a
    character's scores do not depend on the others it is batched with.
    ``mirror``: rank the mirrored strokes (:func:`mirrored`), so the order
    and directions run right to left; the result indexes the strokes given.
    """
    if mirror:
        characters = [mirrored(s) for s in characters]
    g, st = nnx.split(ranker)
    tks = [tokens(s) for s in characters]
    counts = [len(s) for s in characters]
    c = CONTEXT_FEATURES if ranker.context else 0
    ctx = [drawing_context(tk) if c else np.zeros(0, np.float32) for tk in tks]
    cat = lambda xs, width: np.concatenate(xs) if xs else np.zeros((0, width), np.float32)
    h = chunked(
        _headings,
        g,
        st,
        cat([with_context(tk.feats, x) for tk, x in zip(tks, ctx)], STROKE_FEATURES + c),
        cat([with_context(tk.rfeats, x) for tk, x in zip(tks, ctx)], STROKE_FEATURES + c),
    )
    flips = np.split(h < 0, np.cumsum(counts)[:-1])
    tks = [flipped(tk, f) for tk, f in zip(tks, flips)]
    pairs = []
    for tk, n, x in zip(tks, counts, ctx):
        i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
        pairs.append(with_context(pair_inputs(tk.feats, tk.rel, i.ravel(), j.ravel()), x))
    net = chunked(_pair_net, g, st, cat(pairs, PAIR_FEATURES + c))
    nets = np.split(net, np.cumsum([n * n for n in counts])[:-1])
    return [(_order(v.reshape(n, n)), [bool(x) for x in f]) for v, n, f in zip(nets, counts, flips)]


def with_context(rows: np.ndarray, ctx: np.ndarray) -> np.ndarray:
    """``rows [K, F]`` with the drawing's context ``ctx [C]`` appended to each (``C`` may be 0)."""
    rows = np.asarray(rows, np.float32)
    return np.concatenate([rows, np.broadcast_to(ctx, (len(rows), len(ctx)))], -1)


def _order(net: np.ndarray) -> list[int]:
    """Stroke order from the pair network's scores ``net [n, n]``."""
    n = len(net)
    logit = net - net.T  # Ranker.pair: the score of (a, b) minus that of (b, a)
    np.fill_diagonal(logit, 0.0)
    prob = 1.0 / (1.0 + np.exp(-logit))
    np.fill_diagonal(prob, 0.0)
    order = list(np.argsort(-prob.sum(1), kind="stable"))
    # Adjacent swaps while the pairwise log-likelihood rises.
    for _ in range(n):
        changed = False
        for k in range(n - 1):
            a, b = order[k], order[k + 1]
            if logit[b, a] > logit[a, b]:
                order[k], order[k + 1] = b, a
                changed = True
        if not changed:
            break
    return [int(k) for k in order]


def _pad(x: np.ndarray, rows: int) -> np.ndarray:
    out = np.zeros((rows, *x.shape[1:]), np.float32)
    out[: len(x)] = x[:rows]
    return out


def reverse(points) -> np.ndarray:
    """A stroke drawn backwards, inking exactly the same pixels.

    A local move's skipped pixel follows the line rule from the move's start,
    so a knight move (|d| = (2, 1)) reversed would skip another pixel; there
    the original skipped pixel becomes a point of its own. Other moves reverse
    as they are.
    """
    p = np.rint(np.asarray(points, float)).astype(np.int64).reshape(-1, 2)
    d = np.diff(p, axis=0)
    if len(d) and np.abs(d).max() > 2:
        return path_pixels(p)[::-1].astype(np.float64)
    out = [p[-1]]
    for k in range(len(p) - 1, 0, -1):
        a, b = p[k - 1], p[k]  # drawn a -> b; now b -> a
        fwd = a + np.sign(b - a) * (np.abs(b - a) // 2)
        back = b + np.sign(a - b) * (np.abs(a - b) // 2)
        if np.abs(b - a).max() == 2 and np.any(fwd != back):
            out.append(fwd)
        out.append(a)
    return np.asarray(out, np.float64)


def apply_order(strokes, order, flip) -> list[np.ndarray]:
    """Strokes reordered, flipped ones drawn backwards (:func:`reverse`)."""
    return [reverse(strokes[k]) if flip[k] else np.asarray(strokes[k], np.float64) for k in order]


def save(ranker: Ranker, out_dir, provenance: dict | None = None) -> pathlib.Path:
    """Writes ``ranker.npz`` and ``ranker.json`` into a bundle folder."""
    from jdraw.model import bundle

    meta = {"hidden": ranker.hidden, "context": ranker.context, "provenance": provenance or {}}
    return bundle.save_net(ranker, out_dir, "ranker", meta)


def load(bundle_dir) -> Ranker | None:
    """The ranker stored in a bundle folder, or ``None`` if it has none."""
    from jdraw.model import bundle

    return bundle.load_net(
        bundle_dir,
        "ranker",
        lambda meta: Ranker(
            int(meta.get("hidden", 64)), context=bool(meta.get("context", False)), rngs=nnx.Rngs(0)
        ),
    )


# ----------------------------------------------------------------------------
# Whole plans.

ORDERS = ("model", "ranker", "xy")


def reorder(
    plan,
    method: str,
    ranker: Ranker | None = None,
    max_rows: int | None = None,
    mirror: bool = False,
):
    """A :class:`jdraw.Plan` with each image's strokes reordered (and maybe flipped).

    Args:
      method: ``"model"`` (as traced: returned unchanged), ``"ranker"`` (the
        learned order and directions; needs ``ranker``) or ``"xy"`` (the
        reference rule: sort by the start's x + y).
      max_rows: where flipping an image's strokes would need more action rows
        than this (a reversed knight move takes two rows), its strokes are
        reordered but not flipped, so a plan keeps within its step bound.
      mirror: order as for the image mirrored left to right (right-to-left
        script): the ranker sees :func:`mirrored` strokes, ``"xy"`` sorts by
        ``(99 - x) + y``.
    """
    from jdraw.plans import Plan

    if method not in ORDERS:
        raise ValueError(f"order must be one of {ORDERS}, got {method!r}")
    if method == "model":
        return plan
    if method == "ranker" and ranker is None:
        raise ValueError("order='ranker' needs a ranker; this checkpoint has none")
    strokes = []
    chosen = order_many(ranker, plan.strokes, mirror) if method == "ranker" else None
    for b, s in enumerate(plan.strokes):
        if method == "xy":
            x = [CANVAS - 1 - p[0][0] if mirror else p[0][0] for p in s]
            order = sorted(range(len(s)), key=lambda k: (x[k] + s[k][0][1], k))
            strokes.append([s[k] for k in order])
        else:
            order, flip = chosen[b]
            out = apply_order(s, order, flip)
            if max_rows is not None and len(actions_from_strokes(out)) > max_rows:
                out = apply_order(s, order, [False] * len(s))
            strokes.append(out)
    return Plan.from_strokes(strokes, plan.truncated, width=plan.actions.shape[1])
