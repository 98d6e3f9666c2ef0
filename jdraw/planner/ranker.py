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
"""

from __future__ import annotations

import dataclasses
import json
import pathlib

import jax
import numpy as np
from flax import nnx

from jdraw import geometry
from jdraw.plans import actions_from_strokes

STROKE_FEATURES = 20
PAIR_FEATURES = 3 * STROKE_FEATURES + 9


def _pixels(points) -> np.ndarray:
    """``int64 [m, 2]`` 8-connected pixel path of a stroke's points."""
    p = np.rint(np.asarray(points, float)).astype(np.int64).reshape(-1, 2)
    d = np.diff(p, axis=0)
    if len(d) == 0 or np.abs(d).max() > 2:
        return geometry.polyline_pixels(p)
    # Local moves (|d| <= 2) skip at most one pixel: the line rule's midpoint.
    mid = p[:-1] + np.sign(d) * (np.abs(d) // 2)
    path = np.stack([mid, p[1:]], 1).reshape(-1, 2)
    path = np.concatenate([p[:1], path])
    keep = np.ones(len(path), bool)
    keep[1:] = np.any(path[1:] != path[:-1], axis=1)
    return path[keep]


def stroke_masks(strokes, shape=(geometry.CANVAS, geometry.CANVAS)) -> np.ndarray:
    """``bool [S, H, W]`` one image per stroke (as :func:`jdraw.geometry.render_strokes`)."""
    out = np.zeros((len(strokes), *shape), bool)
    for k, s in enumerate(strokes):
        p = _pixels(s)
        out[k, p[:, 1], p[:, 0]] = True
    return out


def stroke_features(path: np.ndarray, box: np.ndarray) -> np.ndarray:
    """``float32 [STROKE_FEATURES]`` of one stroke.

    Args:
      path: ``[m, 2]`` (x, y) pixel path in drawing order.
      box: ``[4]`` the character's ink box (x0, y0, x1, y1).
    """
    p = np.asarray(path, np.float64)
    s, e = p[0], p[-1]
    c = p.mean(0)
    lo, hi = p.min(0), p.max(0)
    n = len(p)
    k = min(3, n - 1)
    head = p[k] - p[0]
    tail = p[-1] - p[-1 - k]
    unit = lambda v: v / max(np.linalg.norm(v), 1e-6)
    size = np.maximum(box[2:] - box[:2], 1.0)
    rel = lambda q: (q - box[:2]) / size
    f = np.concatenate(
        [
            s / 100,
            e / 100,
            c / 100,
            lo / 100,
            hi / 100,
            unit(e - s),
            unit(head),
            unit(tail),
            [n / 100],
            rel(s),
            [np.linalg.norm(e - s) / max(n, 1)],
        ]
    )
    return f.astype(np.float32)


@dataclasses.dataclass
class Tokens:
    """A character's strokes as tokens.

    Attributes:
      paths: ``S`` pixel paths ``[m_i, 2]`` in their drawn direction.
      feats: ``float32 [S, STROKE_FEATURES]``.
      rfeats: ``float32 [S, STROKE_FEATURES]``, the same strokes reversed.
      rel: ``float32 [S, S, 9]`` relations of stroke pairs.
    """

    paths: list[np.ndarray]
    feats: np.ndarray
    rfeats: np.ndarray
    rel: np.ndarray


def _relations(paths: list[np.ndarray]) -> np.ndarray:
    """``float32 [S, S, 9]``: how stroke ``i`` relates to stroke ``j``."""
    n = len(paths)
    allp = np.concatenate(paths)
    h, w = int(allp[:, 1].max()) + 2, int(allp[:, 0].max()) + 2
    masks = np.zeros((n, h, w), bool)
    for k, p in enumerate(paths):
        masks[k, p[:, 1], p[:, 0]] = True
    near = masks.copy()  # 3x3 dilation
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near[:, max(dy, 0) : h + min(dy, 0), max(dx, 0) : w + min(dx, 0)] |= masks[
                :, max(-dy, 0) : h + min(-dy, 0), max(-dx, 0) : w + min(-dx, 0)
            ]
    inner = masks.copy()
    for k, p in enumerate(paths):
        inner[k, p[0, 1], p[0, 0]] = inner[k, p[-1, 1], p[-1, 0]] = False
    m = masks.reshape(n, -1).astype(np.float32)
    touch = (m @ near.reshape(n, -1).T.astype(np.float32)) > 0
    cross = (inner.reshape(n, -1).astype(np.float32) @ m.T) > 0
    s = np.array([p[0] for p in paths])
    e = np.array([p[-1] for p in paths])
    s_on = near[:, s[:, 1], s[:, 0]].T  # [i, j]: i's start near j
    e_on = near[:, e[:, 1], e[:, 0]].T
    lo = np.array([p.min(0) for p in paths], float)
    hi = np.array([p.max(0) for p in paths], float)
    ov = np.maximum(0, np.minimum(hi[:, None], hi[None]) - np.maximum(lo[:, None], lo[None]) + 1)
    span = np.maximum(1, np.minimum((hi - lo)[:, None], (hi - lo)[None]) + 1)
    holds = np.all(lo[:, None] <= lo[None], -1) & np.all(hi[:, None] >= hi[None], -1)
    rel = np.stack(
        [
            touch,
            s_on,
            e_on,
            s_on.T,
            e_on.T,
            cross,
            ov[..., 0] / span[..., 0],
            ov[..., 1] / span[..., 1],
            holds,
        ],
        -1,
    ).astype(np.float32)
    rel[np.arange(n), np.arange(n)] = 0
    return rel


def tokens(strokes) -> Tokens:
    """Tokens of strokes given as lists of ``[n, 2]`` points (a plan's or a demo's)."""
    paths = [_pixels(s) for s in strokes]
    if not paths:
        z = np.zeros((0, STROKE_FEATURES), np.float32)
        return Tokens([], z, z, np.zeros((0, 0, 9), np.float32))
    allp = np.concatenate(paths)
    box = np.concatenate([allp.min(0), allp.max(0)]).astype(np.float64)
    feats = np.stack([stroke_features(p, box) for p in paths])
    rfeats = np.stack([stroke_features(p[::-1], box) for p in paths])
    return Tokens(paths, feats, rfeats, _relations(paths))


def flipped(tk: Tokens, flip) -> Tokens:
    """The tokens of the same strokes with ``flip[i]`` ones drawn backwards.

    Equals :func:`tokens` of the reversed paths without recomputing it: a
    stroke's features and its reversed features trade places, and its
    "starts on" / "ends on" relations swap; the rest does not depend on
    direction.
    """
    f = np.asarray(flip, bool)
    rel = tk.rel.copy()
    rel[f, :, 1], rel[f, :, 2] = tk.rel[f, :, 2], tk.rel[f, :, 1]
    rel[:, f, 3], rel[:, f, 4] = tk.rel[:, f, 4], tk.rel[:, f, 3]
    return Tokens(
        [p[::-1] if fl else p for p, fl in zip(tk.paths, f)],
        np.where(f[:, None], tk.rfeats, tk.feats),
        np.where(f[:, None], tk.feats, tk.rfeats),
        rel,
    )


def pair_inputs(feats: np.ndarray, rel: np.ndarray, i, j) -> np.ndarray:
    """``float32 [K, PAIR_FEATURES]`` for index arrays ``i``, ``j`` of stroke pairs."""
    a, b = feats[i], feats[j]
    return np.concatenate([a, b, a - b, rel[i, j]], -1).astype(np.float32)


class _MLP(nnx.Module):
    def __init__(self, din: int, hidden: int, rngs: nnx.Rngs):
        self.l1 = nnx.Linear(din, hidden, rngs=rngs)
        self.l2 = nnx.Linear(hidden, hidden, rngs=rngs)
        self.out = nnx.Linear(hidden, 1, rngs=rngs)

    def __call__(self, x):
        return self.out(jax.nn.relu(self.l2(jax.nn.relu(self.l1(x)))))[..., 0]


class Ranker(nnx.Module):
    """Pairwise order and per-stroke heading scores (see the module docstring)."""

    def __init__(self, hidden: int = 64, *, rngs: nnx.Rngs):
        self.hidden = hidden
        self.pair_net = _MLP(PAIR_FEATURES, hidden, rngs)
        self.heading_net = _MLP(STROKE_FEATURES, hidden, rngs)

    def pair(self, x_ab, x_ba):
        """Log-odds that a precedes b, from both orders' inputs ``[..., PAIR_FEATURES]``."""
        return self.pair_net(x_ab) - self.pair_net(x_ba)

    def heading(self, f, rf):
        """Log-odds that strokes ``f [..., F]`` (reversed: ``rf``) run the right way."""
        return self.heading_net(f) - self.heading_net(rf)


# ----------------------------------------------------------------------------
# Inference.


@jax.jit
def _headings(graphdef, st, f, rf):
    return nnx.merge(graphdef, st).heading(f, rf)


@jax.jit
def _pair_net(graphdef, st, x):
    return nnx.merge(graphdef, st).pair_net(x)


def order_strokes(ranker: Ranker, strokes) -> tuple[list[int], list[bool]]:
    """The order and the flips the ranker chooses for one character's strokes.

    Returns:
      ``(order, flip)``: ``order`` lists stroke indices in drawing order;
      ``flip[i]`` says stroke ``i`` is to be drawn backwards.
    """
    n = len(strokes)
    if n == 0:
        return [], []
    tk = tokens(strokes)
    g, st = nnx.split(ranker)
    # Bucket the stroke count so a new count seldom recompiles.
    size = 1 << max(1, int(np.ceil(np.log2(max(n, 2)))))
    h = _headings(g, st, _pad(tk.feats, size), _pad(tk.rfeats, size))
    flip = [bool(v < 0) for v in np.asarray(h)[:n]]
    tk = flipped(tk, flip)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    net = np.asarray(
        _pair_net(g, st, _pad(pair_inputs(tk.feats, tk.rel, i.ravel(), j.ravel()), size * size))
    )[: n * n].reshape(n, n)
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
    return [int(k) for k in order], flip


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
        return _pixels(p)[::-1].astype(np.float64)
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

    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    np.savez(out / "ranker.npz", **bundle.state_arrays(ranker))
    meta = {"hidden": ranker.hidden, "provenance": provenance or {}}
    (out / "ranker.json").write_text(json.dumps(meta, indent=2) + "\n")
    return out


def load(bundle_dir) -> Ranker | None:
    """The ranker stored in a bundle folder, or ``None`` if it has none."""
    from jdraw.model import bundle

    d = pathlib.Path(bundle_dir)
    if not (d / "ranker.json").exists():
        return None
    meta = json.loads((d / "ranker.json").read_text())
    model = Ranker(int(meta.get("hidden", 64)), rngs=nnx.Rngs(0))
    try:
        with np.load(d / "ranker.npz") as z:
            arrays = {k: z[k] for k in z.files}
    except (OSError, ValueError) as e:
        raise bundle.BundleError(f"{d / 'ranker.npz'}: unreadable ({e})") from e
    try:
        bundle.fill(model, arrays)
    except bundle.BundleError as e:
        raise bundle.BundleError(f"{d / 'ranker.npz'}: {e}") from e
    return model


# ----------------------------------------------------------------------------
# Whole plans.

ORDERS = ("model", "ranker", "xy")


def reorder(plan, method: str, ranker: Ranker | None = None, max_rows: int | None = None):
    """A :class:`jdraw.Plan` with each image's strokes reordered (and maybe flipped).

    Args:
      method: ``"model"`` (as traced: returned unchanged), ``"ranker"`` (the
        learned order and directions; needs ``ranker``) or ``"xy"`` (the
        reference rule: sort by the start's x + y).
      max_rows: where flipping an image's strokes would need more action rows
        than this (a reversed knight move takes two rows), its strokes are
        reordered but not flipped, so a plan keeps within its step bound.
    """
    from jdraw.plans import Plan

    if method not in ORDERS:
        raise ValueError(f"order must be one of {ORDERS}, got {method!r}")
    if method == "model":
        return plan
    if method == "ranker" and ranker is None:
        raise ValueError("order='ranker' needs a ranker; this checkpoint has none")
    strokes = []
    for s in plan.strokes:
        if method == "xy":
            order = sorted(range(len(s)), key=lambda k: (s[k][0][0] + s[k][0][1], k))
            strokes.append([s[k] for k in order])
        else:
            order, flip = order_strokes(ranker, s)
            out = apply_order(s, order, flip)
            if max_rows is not None and len(actions_from_strokes(out)) > max_rows:
                out = apply_order(s, order, [False] * len(s))
            strokes.append(out)
    rows = [actions_from_strokes(s) for s in strokes]
    T = max([plan.actions.shape[1], *(len(r) for r in rows)])
    actions = np.zeros((len(rows), T, 3), np.int32)
    for b, r in enumerate(rows):
        actions[b, : len(r)] = r
    lengths = np.asarray([len(r) for r in rows], np.int32)
    return Plan(strokes=strokes, actions=actions, lengths=lengths, truncated=plan.truncated)
