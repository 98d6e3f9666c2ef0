"""Ablation (c), Table I row 5: planning with the global model looped on itself.

At every step the global network sees (pen, visited, visited since the pen
went down, unvisited target), picks the next pen position among the ink
pixels (as row 1's masks keep its pen on ink, for a fair comparison) and,
through an extra fully connected head, whether the pen is down on the way
there (:meth:`jdraw.model.network.DrawModel.position_and_touch`). Pen-down
moves ink straight segments with the line rule of :mod:`jdraw.geometry`.
Its training data and loss: :mod:`jdraw.train.global_only`.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp

from jdraw import geometry
from jdraw import state as S
from jdraw.planner.loop import Out

CANVAS = geometry.CANVAS


def run(model, target, max_steps: int, max_idle: int = 16):
    """Plans one image ``target bool [100, 100]``; at most ``max_steps`` actions.

    Stops when no ink is left or after ``max_idle`` actions in a row that
    ink nothing new. Returns a :class:`jdraw.planner.loop.Out`.
    """

    def cond(c):
        visited, last, pen, has_pen, actions, n, idle = c
        return jnp.any(target & ~visited) & (n < max_steps) & (idle < max_idle)

    def body(c):
        visited, last, pen, has_pen, actions, n, idle = c
        x = S.global_state(target, visited, last, pen, has_pen)
        pos, touch = model.position_and_touch(x[None])
        idx = jnp.argmax(jnp.where(target, pos[0], -jnp.inf).reshape(-1))
        p = jnp.stack([idx % CANVAS, idx // CANVAS]).astype(jnp.int32)
        down = (touch[0] > 0) & has_pen  # the pen is first put somewhere, lifted
        v2 = jnp.where(down, geometry.paint_segment(visited, pen, p), visited)
        new = jnp.sum(v2 & ~visited)
        last = jnp.where(down, geometry.paint_segment(last, pen, p), jnp.zeros_like(last))
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
