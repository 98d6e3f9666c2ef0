"""The planning loop: global move, then local moves until touch says lift.

Written for one image and batched with one ``jax.vmap``; the whole loop runs
inside ``jit`` as two nested ``lax.while_loop``s (strokes, then the moves of a
stroke), each bounded, so a plan always ends. Under ``vmap`` the global model
runs once per stroke for the whole batch and the local model once per local
step, never both per step.

The policy is passed in (``policy``), so the same state machine replays a
demonstration (:func:`replay_policy`) or runs the model (:func:`model_policy`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, NamedTuple

import jax
import jax.numpy as jnp

from jdraw import geometry
from jdraw import state as S


@dataclasses.dataclass(frozen=True)
class Limits:
    """Bounds that make every plan finite.

    Attributes:
      max_steps: action rows ``T`` (global jumps and local moves together).
      max_stroke_steps: local steps in one stroke.
      max_idle_steps: local steps in a row that ink nothing new before the
        stroke is ended (a loop over drawn ink never finishes otherwise).
    """

    max_steps: int = 1024
    max_stroke_steps: int = 256
    max_idle_steps: int = 8


class Policy(NamedTuple):
    """How moves are chosen; all functions are for one image.

    ``start(ctx, pstate, target, visited, last, pen, has_pen, allowed) -> (xy [2], pstate)``
    (``last``: pixels visited since the previous global move; ``allowed``:
    where a stroke may start)
    ``begin(ctx, pstate) -> lstate`` (per-stroke local state, e.g. LSTM carry)
    ``observe(ctx, pstate, target, labels, visited, pen) -> obs`` (what the
    local step looks at: for the model, a small window around the pen)
    ``decide(ctx, pstate, lstate, obs) -> (move scores [25], lift bool, lstate, pstate)``

    A local step is ``decide(observe(...))`` (:meth:`local`); the two halves
    are apart so the slot planner can batch ``decide`` over small
    observations instead of whole canvases.
    """

    start: Callable
    begin: Callable
    observe: Callable
    decide: Callable

    def local(self, ctx, pstate, lstate, target, labels, visited, pen):
        obs = self.observe(ctx, pstate, target, labels, visited, pen)
        return self.decide(ctx, pstate, lstate, obs)


class Out(NamedTuple):
    actions: jax.Array  # [T, 3] int32
    length: jax.Array  # [] int32
    truncated: jax.Array  # [] bool
    visited: jax.Array  # [H, W] bool


def run(policy: Policy, ctx: Any, pstate: Any, target, labels, limits: Limits) -> Out:
    """Plans one image.

    Args:
      policy: see :class:`Policy`.
      ctx: passed through to the policy (e.g. the model).
      pstate: the policy's own carried state (e.g. a replay cursor).
      target: ``bool [H, W]`` ink.
      labels: ``int32 [H, W]`` 8-connected component labels of ``target``.
      limits: step bounds.
    """
    T = limits.max_steps
    h, w = target.shape

    def remaining(visited):
        return jnp.any(target & ~visited)

    def write(actions, n, row):
        ok = n < T
        actions = jnp.where(ok, actions.at[jnp.minimum(n, T - 1)].set(row), actions)
        return actions, n + ok.astype(jnp.int32)

    def stroke_body(c):
        visited, last, pen, has_pen, actions, n, stalled, pst = c
        allowed = S.allowed_starts(target, visited, stalled)
        start, pst = policy.start(ctx, pst, target, visited, last, pen, has_pen, allowed)
        start = start.astype(jnp.int32)
        actions, n = write(
            actions, n, jnp.array([start[0] - pen[0], start[1] - pen[1], 0], jnp.int32)
        )
        new0 = (~visited[start[1], start[0]]).astype(jnp.int32)
        visited = visited.at[start[1], start[0]].set(True)
        last = jnp.zeros_like(last).at[start[1], start[0]].set(True)
        lst = policy.begin(ctx, pst)

        def local_cond(lc):
            visited, last, pen, actions, n, k, moves, idle, new, lifted, lst, pst = lc
            return (
                ~lifted & (k < limits.max_stroke_steps) & (n < T) & (idle < limits.max_idle_steps)
            )

        def local_body(lc):
            visited, last, pen, actions, n, k, moves, idle, new, lifted, lst, pst = lc
            scores, lift, lst, pst = policy.local(ctx, pst, lst, target, labels, visited, pen)
            ok = S.allowed_moves(target, pen)
            lift = lift | ~jnp.any(ok)
            idx = jnp.argmax(jnp.where(ok, scores, -jnp.inf))
            d = jnp.asarray(geometry.MOVES, jnp.int32)[idx]
            v2, pen2, n_new = S.apply_move(visited, pen, d)
            l2, _, _ = S.apply_move(last, pen, d)
            a2, n2 = write(actions, n, jnp.array([d[0], d[1], 1], jnp.int32))
            keep = lambda old, nw: jnp.where(lift, old, nw)
            return (
                keep(visited, v2),
                keep(last, l2),
                keep(pen, pen2),
                keep(actions, a2),
                keep(n, n2),
                k + 1,
                moves + (~lift).astype(jnp.int32),
                jnp.where(lift, idle, jnp.where(n_new > 0, 0, idle + 1)),
                new + jnp.where(lift, 0, n_new),
                lift,
                lst,
                pst,
            )

        z = jnp.int32(0)
        lc = (visited, last, start, actions, n, z, z, z, new0, jnp.bool_(False), lst, pst)
        visited, last, pen, actions, n, _, moves, _, new, _, _, pst = jax.lax.while_loop(
            local_cond, local_body, lc
        )
        a_dot, n_dot = write(actions, n, jnp.array([0, 0, 1], jnp.int32))
        actions = jnp.where(moves > 0, actions, a_dot)
        n = jnp.where(moves > 0, n, n_dot)
        return visited, last, pen, jnp.bool_(True), actions, n, new == 0, pst

    def stroke_cond(c):
        visited, last, pen, has_pen, actions, n, stalled, pst = c
        return remaining(visited) & (n < T)

    c0 = (
        jnp.zeros((h, w), bool),
        jnp.zeros((h, w), bool),
        jnp.zeros(2, jnp.int32),
        jnp.bool_(False),
        jnp.zeros((T, 3), jnp.int32),
        jnp.int32(0),
        jnp.bool_(False),
        pstate,
    )
    visited, _, _, _, actions, n, _, _ = jax.lax.while_loop(stroke_cond, stroke_body, c0)
    return Out(actions=actions, length=n, truncated=remaining(visited), visited=visited)


# ----------------------------------------------------------------------------
# Policies.


def replay_policy() -> Policy:
    """Replays a demonstration.

    ``pstate = (starts [S, 2], moves [S, L, 2], n_moves [S], stroke, k)``.

    The replayed strokes go through the same ``run`` as the model's, so
    ``render(plan) == target`` checks the state machine and the renderer.
    """

    def start(ctx, pst, *unused):
        starts, moves, nm, s, k = pst
        return starts[s], (starts, moves, nm, s, jnp.int32(0))

    def begin(ctx, pst):
        return ()

    def observe(ctx, pst, *unused):
        return ()

    def decide(ctx, pst, lst, obs):
        starts, moves, nm, s, k = pst
        lift = k >= nm[s]
        d = moves[s, jnp.minimum(k, moves.shape[1] - 1)]
        scores = jax.nn.one_hot(geometry.move_index(d), 25)
        nxt = (starts, moves, nm, jnp.where(lift, s + 1, s), jnp.where(lift, 0, k + 1))
        return scores, lift, lst, nxt

    return Policy(start, begin, observe, decide)


def model_policy(local_encoding: str = "window") -> Policy:
    """The learned policy; ``ctx`` is a :class:`jdraw.model.network.DrawModel` in eval mode.

    Args:
      local_encoding: ``"window"`` (exact, cheap) or ``"full"`` (encode the
        whole canvas at every local step; for benchmarks and tests).
    """
    if local_encoding not in ("window", "full"):
        raise ValueError(f"local_encoding must be 'window' or 'full', got {local_encoding!r}")

    def start(model, pst, target, visited, last, pen, has_pen, allowed):
        x = S.global_state(target, visited, last, pen, has_pen)
        logits = model.global_logits(x[None])[0]
        idx = jnp.argmax(jnp.where(allowed, logits, -jnp.inf).reshape(-1))
        xy = jnp.stack([idx % target.shape[1], idx // target.shape[1]]).astype(jnp.int32)
        return xy, pst

    def begin(model, pst):
        return model.core.init_carry()

    def observe(model, pst, target, labels, visited, pen):
        if local_encoding == "window":
            return S.local_window(target, labels, visited, pen, model.window)
        return S.local_state(target, labels, visited, pen), pen

    def decide(model, pst, carry, obs):
        if local_encoding == "window":
            win, inside = obs
            feat = model.local_features(win[None], inside[None])[0]
        else:
            x, pen = obs
            feat = model.local_features_full(x[None], pen[None])[0]
        carry, h = model.core.step(carry, model.core.project(feat))
        move, touch = model.heads(h)
        return move, touch < 0.0, carry, pst

    return Policy(start, begin, observe, decide)
