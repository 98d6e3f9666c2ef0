"""The streaming planner: one loop of steps over a fixed-width batch of slots.

Each slot holds one image and its state machine::

    NEEDS_START --start (global model)--> MOVING --move (local model)--> MOVING
         ^                                  |
         +------- stroke ends, ink left ----+---- stroke ends, no ink left --> DONE

The state machine is written once, for one image (:func:`load`, :func:`start`,
:func:`move`, with :func:`_settle` deciding when a stroke ends); it is the same
as :func:`jdraw.planner.loop.run`'s, so the actions are identical to planning each
image alone. Batching happens in one place, :func:`stream`'s ``step``:

* a finished slot takes the next image of the queue;
* the global model runs on a small fixed-size sub-batch (``global_batch``) of
  the slots that need a start, gathered and scattered back; the others wait.
  It runs only once the sub-batch can be filled (or every live slot waits),
  so the expensive whole-canvas encoder is rarely run on padding;
* the local model moves every moving slot once.

A step's cost is one global sub-batch (when due) and one local batch, not the
batch's longest stroke, and no image waits for another to finish.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import jax
import jax.numpy as jnp

from jdraw import geometry
from jdraw import state as S
from jdraw.planner.loop import Limits, Policy

NEEDS_START, MOVING, DONE = 0, 1, 2


class Image(NamedTuple):
    """One image's planning state; a slot batch stacks them as ``[S, ...]``."""

    target: jax.Array  # [H, W] bool
    labels: jax.Array  # [H, W] int32
    visited: jax.Array  # [H, W] bool
    last: jax.Array  # [H, W] bool, visited since the last global move
    pen: jax.Array  # [2] int32 (x, y)
    has_pen: jax.Array  # [] bool
    actions: jax.Array  # [T, 3] int32
    n: jax.Array  # [] int32, rows written
    stalled: jax.Array  # [] bool, the last stroke inked nothing new
    phase: jax.Array  # [] int32: NEEDS_START, MOVING or DONE
    k: jax.Array  # [] int32, local steps in this stroke
    moves: jax.Array  # [] int32, moves in this stroke
    idle: jax.Array  # [] int32, moves in a row that inked nothing new
    new: jax.Array  # [] int32, pixels this stroke inked
    lstate: Any  # the policy's per-stroke state
    pstate: Any  # the policy's carried state
    index: jax.Array  # [] int32, position in the queue; -1 for none


class Stream(NamedTuple):
    actions: jax.Array  # [Q, T, 3] int32
    length: jax.Array  # [Q] int32
    truncated: jax.Array  # [Q] bool
    global_calls: jax.Array  # [] int32, starts computed (one per stroke)
    global_batches: jax.Array  # [] int32, global sub-batches run
    local_steps: jax.Array  # [] int32, moving slots' local steps
    local_rows: jax.Array  # [] int32, slots the local model ran on (moving or padding)
    steps: jax.Array  # [] int32, loop steps


# ----------------------------------------------------------------------------
# One image.


def _write(actions, n, row, on=True):
    """Writes ``row`` at ``n`` when ``on`` and there is room; returns ``(actions, n)``."""
    i = jnp.minimum(n, actions.shape[0] - 1)
    ok = on & (n < actions.shape[0])
    return actions.at[i].set(jnp.where(ok, row, actions[i])), n + ok.astype(jnp.int32)


def _remaining(s: Image):
    return jnp.any(s.target & ~s.visited)


def _settle(s: Image, lifted, limits: Limits) -> Image:
    """Ends a stroke whose local loop stops here; the image then needs a start or is done."""
    going = (
        ~lifted
        & (s.k < limits.max_stroke_steps)
        & (s.n < s.actions.shape[0])
        & (s.idle < limits.max_idle_steps)
    )
    end = (s.phase == MOVING) & ~going
    # A stroke with no moves is drawn as a dot.
    actions, n = _write(s.actions, s.n, jnp.array([0, 0, 1], jnp.int32), end & (s.moves == 0))
    more = _remaining(s) & (n < s.actions.shape[0])
    return s._replace(
        actions=actions,
        n=n,
        stalled=jnp.where(end, s.new == 0, s.stalled),
        phase=jnp.where(end, jnp.where(more, NEEDS_START, DONE), s.phase),
    )


def load(policy: Policy, ctx, pstate, target, labels, index, max_steps: int) -> Image:
    """A fresh state for ``target`` (``bool [H, W]``); done at once when it has no ink."""
    z = jnp.int32(0)
    blank = jnp.zeros(target.shape, bool)
    return Image(
        target=target,
        labels=labels,
        visited=blank,
        last=blank,
        pen=jnp.zeros(2, jnp.int32),
        has_pen=jnp.bool_(False),
        actions=jnp.zeros((max_steps, 3), jnp.int32),
        n=z,
        stalled=jnp.bool_(False),
        phase=jnp.where(jnp.any(target), NEEDS_START, DONE).astype(jnp.int32),
        k=z,
        moves=z,
        idle=z,
        new=z,
        lstate=policy.begin(ctx, pstate),
        pstate=pstate,
        index=jnp.asarray(index, jnp.int32),
    )


def start(policy: Policy, ctx, s: Image, limits: Limits) -> Image:
    """The global move: jump to where the next stroke starts."""
    allowed = S.allowed_starts(s.target, s.visited, s.stalled)
    xy, pst = policy.start(ctx, s.pstate, s.target, s.visited, s.last, s.pen, s.has_pen, allowed)
    xy = xy.astype(jnp.int32)
    actions, n = _write(s.actions, s.n, jnp.stack([xy[0] - s.pen[0], xy[1] - s.pen[1], 0]))
    z = jnp.int32(0)
    s = s._replace(
        visited=s.visited.at[xy[1], xy[0]].set(True),
        last=jnp.zeros_like(s.last).at[xy[1], xy[0]].set(True),
        pen=xy,
        has_pen=jnp.bool_(True),
        actions=actions,
        n=n,
        phase=jnp.int32(MOVING),
        k=z,
        moves=z,
        idle=z,
        new=(~s.visited[xy[1], xy[0]]).astype(jnp.int32),
        lstate=policy.begin(ctx, pst),
        pstate=pst,
    )
    return _settle(s, jnp.bool_(False), limits)


def move(policy: Policy, ctx, s: Image, limits: Limits) -> Image:
    """One local step: a pen-down move, or lift (end the stroke)."""
    scores, lift, lst, pst = policy.local(
        ctx, s.pstate, s.lstate, s.target, s.labels, s.visited, s.pen
    )
    ok = S.allowed_moves(s.target, s.pen)
    lift = lift | ~jnp.any(ok)
    d = jnp.asarray(geometry.MOVES, jnp.int32)[jnp.argmax(jnp.where(ok, scores, -jnp.inf))]
    visited, pen, n_new = S.apply_move(s.visited, s.pen, d)
    last, _, _ = S.apply_move(s.last, s.pen, d)
    actions, n = _write(s.actions, s.n, jnp.stack([d[0], d[1], 1]), ~lift)
    keep = lambda old, nw: jnp.where(lift, old, nw)
    s = s._replace(
        visited=keep(s.visited, visited),
        last=keep(s.last, last),
        pen=keep(s.pen, pen),
        actions=actions,
        n=n,
        k=s.k + 1,
        moves=s.moves + (~lift).astype(jnp.int32),
        idle=jnp.where(lift, s.idle, jnp.where(n_new > 0, 0, s.idle + 1)),
        new=s.new + jnp.where(lift, 0, n_new),
        lstate=lst,
        pstate=pst,
    )
    return _settle(s, lift, limits)


# ----------------------------------------------------------------------------
# The slot batch: the one place where batching happens.


def stream(
    policy: Policy,
    ctx: Any,
    pstate: Any,
    targets,
    labels,
    count,
    limits: Limits,
    slots: int = 64,
    global_batch: int = 4,
) -> Stream:
    """Plans the first ``count`` images of a queue through ``slots`` slots.

    Args:
      policy: see :class:`jdraw.planner.loop.Policy`.
      ctx: passed through to the policy (e.g. the model, in eval mode: the
        global sub-batch must not change any image's numbers).
      pstate: the policy's initial carried state, the same for every image.
      targets: ``bool [Q, H, W]`` ink, a queue; entries from ``count`` on are
        padding and never planned.
      labels: ``int32 [Q, H, W]`` 8-connected component labels.
      count: ``int32 []`` images in the queue.
      limits: step bounds, per image as in :func:`jdraw.planner.loop.run`.
      slots: images in flight (the local model's batch), at most ``Q``.
      global_batch: the global model's sub-batch ``K``.

    Returns:
      A :class:`Stream`: per queue entry actions, lengths and truncation,
      and the work done.
    """
    q = targets.shape[0]
    width = max(1, min(slots, q))
    k_glob = max(1, min(global_batch, width))
    widths = sorted({max(1, width // 8), max(1, width // 2), width})
    each = lambda f: jax.vmap(lambda s: f(policy, ctx, s, limits))
    loads = jax.vmap(lambda t, lab, i: load(policy, ctx, pstate, t, lab, i, limits.max_steps))

    def fetch(i):
        ok = i < count
        j = jnp.minimum(i, q - 1)
        return loads(targets[j] & ok[:, None, None], labels[j], jnp.where(ok, i, -1))

    def save(out, s: Image, mask):
        dst = jnp.where(mask & (s.index >= 0), s.index, q)  # q: dropped
        acts, lens, trunc = out
        return (
            acts.at[dst].set(s.actions, mode="drop"),
            lens.at[dst].set(s.n, mode="drop"),
            trunc.at[dst].set(jax.vmap(_remaining)(s), mode="drop"),
        )

    def rows(mask, new, old):
        return jax.tree.map(
            lambda a, b: jnp.where(mask.reshape(mask.shape + (1,) * (a.ndim - 1)), a, b), new, old
        )

    def step(c):
        s, nxt, wait, out, stats = c
        # Finished slots hand their plan over and take the next images.
        free = s.phase == DONE
        i = nxt + jnp.cumsum(free) - 1
        take = free & (i < count)

        def refill(args):
            s, out = args
            return rows(take, fetch(i), s), save(out, s, take)

        s, out = jax.lax.cond(take.any(), refill, lambda a: a, (s, out))
        nxt = nxt + take.sum()

        # Global model: the longest-waiting slots that need a start, K at a time.
        need = s.phase == NEEDS_START
        live = (s.phase != DONE).sum()
        due = need.any() & (need.sum() >= jnp.minimum(k_glob, live))
        prio, pick = jax.lax.top_k(jnp.where(need, wait, -1), k_glob)
        dst = jnp.where(prio >= 0, pick, width)  # width: dropped

        def starts(s):
            done = each(start)(jax.tree.map(lambda a: a[pick], s))
            return jax.tree.map(lambda a, b: a.at[dst].set(b, mode="drop"), s, done)

        s = jax.lax.cond(due, starts, lambda s: s, s)
        wait = jnp.where(s.phase == NEEDS_START, wait + 1, 0)

        # Local model: every moving slot moves once, gathered into the smallest
        # of a few fixed widths that holds them (a batch's tail runs narrow).
        moving = s.phase == MOVING
        n_moving = moving.sum()
        size = jnp.searchsorted(jnp.asarray(widths), n_moving)

        def moves(w):
            def f(s):
                if w == width:
                    return rows(moving, each(move)(s), s)
                _, pick = jax.lax.top_k(moving.astype(jnp.int32), w)
                done = each(move)(jax.tree.map(lambda a: a[pick], s))
                dst = jnp.where(moving[pick], pick, width)  # width: dropped
                return jax.tree.map(lambda a, b: a.at[dst].set(b, mode="drop"), s, done)

            return f

        s = jax.lax.cond(
            n_moving > 0,
            lambda s: jax.lax.switch(size, [moves(w) for w in widths], s),
            lambda s: s,
            s,
        )

        n_starts = jnp.where(due, (prio >= 0).sum(), 0)
        rows_run = jnp.where(n_moving > 0, jnp.asarray(widths)[size], 0)
        work = [n_starts, due, n_moving, rows_run, 1]
        stats = stats + jnp.stack(work).astype(jnp.int32)
        return s, nxt, wait, out, stats

    def going(c):
        s, nxt, _, _, _ = c
        return jnp.any(s.phase != DONE) | (nxt < count)

    t = limits.max_steps
    out0 = (jnp.zeros((q, t, 3), jnp.int32), jnp.zeros(q, jnp.int32), jnp.zeros(q, bool))
    c0 = (
        fetch(jnp.arange(width)),
        jnp.int32(width),
        jnp.zeros(width, jnp.int32),
        out0,
        jnp.zeros(5, jnp.int32),
    )
    s, _, _, out, stats = jax.lax.while_loop(going, step, c0)
    acts, lens, trunc = save(out, s, jnp.ones(width, bool))
    return Stream(acts, lens, trunc, *stats)
