"""Ablation (c), Table I row 5: the global model looped on itself, no local model.

At every step the global network sees (pen, visited, visited since the pen
went down, unvisited target), picks the next pen position among all pixels
and, through an extra fully connected head, whether the pen is down on the
way there. It is trained on raw actions (points along each stroke, not the
+-2 local moves), as the paper did. Pen-down moves ink straight segments with
the line rule of :mod:`jdraw.geometry`.

For a fair comparison with row 1 the next position is chosen among ink
pixels, as row 1's masks keep its pen on ink.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import optax

from jdraw import geometry as raster
from jdraw import state as S
from jdraw.data import demos as D
from jdraw.data.batches import global_state_arrays

CANVAS = raster.CANVAS
RAW_SPACING = (3, 5)  # raw points every 3-4 pen positions (about 5-8 pixels)


def raw_points(stroke: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Points along a stroke's pen positions ``[M + 1, 2]``: its start, end, and some between."""
    idx = [0]
    while idx[-1] < len(stroke) - 1:
        idx.append(min(idx[-1] + int(rng.integers(*RAW_SPACING)), len(stroke) - 1))
    return stroke[idx]


def raw_actions(d: D.Demo, rng: np.random.Generator) -> list[tuple[np.ndarray, int, int]]:
    """``(point, touch, stroke)`` per raw action: a pen-up move to each start, pen-down after."""
    out = []
    for s, st in enumerate(d.strokes):
        r = raw_points(st, rng)
        out.append((r[0], 0, s))
        if len(r) == 1:
            out.append((r[0], 1, s))
        out.extend((p, 1, s) for p in r[1:])
    return out


def batch(ks, pool, rng, *, size: int, strength: float) -> dict:
    """States before random raw actions and the actions.

    Returns numpy arrays: ``target``, ``visited``, ``last`` bool [G, 100, 100],
    ``pen`` int32 [G, 2], ``has_pen`` bool [G], ``goal`` int32 [G] (flat
    index ``y * 100 + x``), ``touch`` float32 [G].
    """
    out = global_state_arrays(size, goal=np.int32, touch=np.float32)
    for g in range(size):
        d = D.sample(ks, int(rng.choice(pool)), rng, strength)
        acts = raw_actions(d, rng)
        j = int(rng.integers(len(acts)))
        drawn: list[list[np.ndarray]] = []
        for p, touch, _ in acts[:j]:
            if touch:
                drawn[-1].append(p)
            else:
                drawn.append([p])
        out["target"][g] = d.target
        if drawn:
            out["visited"][g] = raster.render_strokes([np.asarray(s) for s in drawn if len(s) > 1])
            out["pen"][g] = acts[j - 1][0]
            out["has_pen"][g] = True
            cur = drawn[-1]
            if len(cur) > 1:
                out["last"][g] = raster.render_strokes([np.asarray(cur)])
        p, touch, _ = acts[j]
        out["goal"][g] = p[1] * CANVAS + p[0]
        out["touch"][g] = touch
    return out


def heads(model, states):
    """``[N, 100, 100, 4]`` -> (position logits ``[N, 100, 100]``, touch logit ``[N]``)."""
    from jdraw.model.network import _conv, encode

    f = encode(states, model.global_first, model.trunk, model.global_norms)
    pos = _conv(f, model.global_head.w[...], model.global_head.b[...], "VALID")[..., 0]
    pooled = jnp.concatenate([f.mean((1, 2)), f.max((1, 2))], -1)
    return pos, model.global_touch(pooled)[..., 0]


def loss(model, g: dict):
    """Cross-entropy of the next position (over ink pixels) plus the touch cross-entropy."""
    x = jax.vmap(S.global_state)(g["target"], g["visited"], g["last"], g["pen"], g["has_pen"])
    pos, touch = heads(model, x)
    pos = pos.reshape(x.shape[0], -1)
    ink = g["target"].reshape(x.shape[0], -1) | jax.nn.one_hot(g["goal"], pos.shape[1], dtype=bool)
    pos = jnp.where(ink, pos, -1e9)
    ce = optax.softmax_cross_entropy_with_integer_labels(pos, g["goal"])
    bce = optax.sigmoid_binary_cross_entropy(touch, g["touch"])
    acc = jnp.mean(jnp.argmax(pos, -1) == g["goal"])
    return jnp.mean(ce + bce), {
        "acc_goal": acc,
        "acc_touch": jnp.mean((touch > 0) == (g["touch"] > 0.5)),
    }


def draw_segment(img: jax.Array, a: jax.Array, b: jax.Array) -> jax.Array:
    """``img`` with the pixels of :func:`jdraw.geometry.segment_pixels` ``(a, b)`` set."""
    d = b - a
    n = jnp.maximum(jnp.max(jnp.abs(d)), 1)
    k = jnp.arange(CANVAS + 1)[:, None]
    m = k * d[None]  # the offset is m / n rounded half toward zero, done in integers
    p = a[None] + jnp.sign(m) * ((2 * jnp.abs(m) + n - 1) // (2 * n))
    on = k[:, 0] <= jnp.max(jnp.abs(d))
    p = jnp.where(on[:, None], p, a[None])
    return img.at[p[:, 1], p[:, 0]].set(True)


def run(model, target, max_steps: int, max_idle: int = 16):
    """Plans one image with the looped global model; returns ``planner.Out``-like fields."""
    from jdraw.planner.loop import Out

    def cond(c):
        visited, last, pen, has_pen, actions, n, idle = c
        return jnp.any(target & ~visited) & (n < max_steps) & (idle < max_idle)

    def body(c):
        visited, last, pen, has_pen, actions, n, idle = c
        x = S.global_state(target, visited, last, pen, has_pen)
        pos, touch = heads(model, x[None])
        idx = jnp.argmax(jnp.where(target, pos[0], -jnp.inf).reshape(-1))
        p = jnp.stack([idx % CANVAS, idx // CANVAS]).astype(jnp.int32)
        down = (touch[0] > 0) & has_pen  # the pen is first put somewhere, lifted
        v2 = jnp.where(down, draw_segment(visited, pen, p), visited)
        new = jnp.sum(v2 & ~visited)
        last = jnp.where(down, draw_segment(last, pen, p), jnp.zeros_like(last))
        actions = actions.at[n].set(
            jnp.array([p[0] - pen[0], p[1] - pen[1], down.astype(jnp.int32)])
        )
        return v2, last, p, jnp.bool_(True), actions, n + 1, jnp.where(new > 0, 0, idle + 1)

    z = jnp.zeros(target.shape, bool)
    c0 = (
        z,
        z,
        jnp.zeros(2, jnp.int32),
        jnp.bool_(False),
        jnp.zeros((max_steps, 3), jnp.int32),
        jnp.int32(0),
        jnp.int32(0),
    )
    visited, _, _, _, actions, n, _ = jax.lax.while_loop(cond, body, c0)
    return Out(actions=actions, length=n, truncated=jnp.any(target & ~visited), visited=visited)
