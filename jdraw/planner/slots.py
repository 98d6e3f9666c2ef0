"""The streaming planner: one loop of steps over a fixed-width batch of slots.

Each slot holds one image and its state machine::

    NEEDS_START --start (global model)--> MOVING --move (local model)--> MOVING
         ^                                  |
         +------- stroke ends, ink left ----+---- stroke ends, no ink left --> DONE

The state machine is written once, for one image (:func:`load`, :func:`start`,
:func:`observe` and :func:`move`, with :func:`_settle` deciding when a stroke
ends); it is the same as :func:`jdraw.planner.loop.run`'s, so the actions are
identical to planning each image alone. Batching happens in one place,
:func:`stream`'s ``step``:

* the global model runs on a small fixed-size sub-batch (``global_batch``) of
  the slots that need a start, gathered and scattered back; the others wait.
  It runs only once the sub-batch can be filled (or every live slot waits),
  so the expensive whole-canvas encoder is rarely run on padding;
* the local model decides for the moving slots only: each slot's observation
  (a small window at the pen) is cut out, the moving ones gathered into the
  narrowest of a few fixed widths that holds them, decided together and
  scattered back; each slot then applies its decision;
* a finished slot hands its plan over and takes the next image of the queue.

A step's cost is one global sub-batch (when due) and one local batch about
as wide as the slots that move, not the batch's longest stroke, and no image
waits for another to finish. Each part touches a few rows or pixels of the
big per-slot arrays, which XLA then updates in place: a step never copies
the whole slot batch.
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
    left: jax.Array  # [] int32, ink pixels not yet visited
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
    return s.left > 0


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
        left=target.sum(dtype=jnp.int32),
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
    new = (~s.visited[xy[1], xy[0]]).astype(jnp.int32)
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
        new=new,
        left=s.left - new * s.target[xy[1], xy[0]],
        lstate=policy.begin(ctx, pst),
        pstate=pst,
    )
    return _settle(s, jnp.bool_(False), limits)


def observe(policy: Policy, ctx, s: Image):
    """What the local step looks at (for the model, a small window at the pen)."""
    return policy.observe(ctx, s.pstate, s.target, s.labels, s.visited, s.pen)


def move(s: Image, decision, limits: Limits) -> Image:
    """One local step from the policy's ``decision``: a pen-down move, or lift (end the stroke).

    ``decision`` is ``policy.decide``'s ``(move scores [25], lift, lstate, pstate)``.
    An image that is not moving is left as it is; the updates are a few
    pixels and one action row, so a batch of slots changes in place.
    """
    scores, lift, lst, pst = decision
    on = s.phase == MOVING
    ok = S.allowed_moves(s.target, s.pen)
    lift = lift | ~jnp.any(ok)
    d = jnp.asarray(geometry.MOVES, jnp.int32)[jnp.argmax(jnp.where(ok, scores, -jnp.inf))]
    down = on & ~lift
    visited, pen, n_new = S.apply_move(s.visited, s.pen, d, down)
    last, _, _ = S.apply_move(s.last, s.pen, d, down)
    actions, n = _write(s.actions, s.n, jnp.stack([d[0], d[1], 1]), down)
    keep = lambda old, nw: jax.tree.map(lambda a, b: jnp.where(on, b, a), old, nw)
    s = s._replace(
        visited=visited,
        last=last,
        pen=pen,
        actions=actions,
        n=n,
        k=s.k + on.astype(jnp.int32),
        moves=s.moves + down.astype(jnp.int32),
        idle=jnp.where(down, jnp.where(n_new > 0, 0, s.idle + 1), s.idle),
        new=s.new + n_new,
        left=s.left - n_new,  # a move goes along ink only (`allowed_moves`)
        lstate=keep(s.lstate, lst),
        pstate=keep(s.pstate, pst),
    )
    return _settle(s, lift, limits)


# ----------------------------------------------------------------------------
# The slot batch: the one place where batching happens.


def _when(pred, f, x):
    """``f(x)`` if ``pred`` else ``x``, updating ``x``'s buffers in place.

    A loop run once or not at all: unlike ``lax.cond``, XLA carries a loop's
    buffers through without copying the untouched branch's whole state.
    """
    return jax.lax.while_loop(lambda c: c[0], lambda c: (False, f(c[1])), (pred, x))[1]


def local_widths(width: int) -> list[int]:
    """The local model's batch widths for ``width`` slots: 2, 4, then steps of ``width / 8``.

    A step runs the narrowest that holds its moving slots, so little work is
    padding (1 only when there is one slot: a one-row tail step pads a row
    rather than compile one more width).
    """
    step = max(1, width // 8)
    return sorted({min(w, width) for w in (2, 4, *range(step, width + 1, step))})


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
    widths = local_widths(width)
    refills = max(1, width // 8)
    each = lambda f: jax.vmap(lambda s: f(policy, ctx, s, limits))
    loads = jax.vmap(lambda t, lab, i: load(policy, ctx, pstate, t, lab, i, limits.max_steps))

    def fetch(i):
        ok = i < count
        j = jnp.minimum(i, q - 1)
        return loads(targets[j] & ok[:, None, None], labels[j], jnp.where(ok, i, -1))

    def save(out, s: Image, mask):
        dst = jnp.where(mask & (s.index >= 0), s.index, q)  # q: dropped
        acts, lens, trunc = out
        # A refilled slot's rows past ``n`` still hold its earlier image's.
        written = jnp.arange(limits.max_steps)[None, :, None] < s.n[:, None, None]
        return (
            acts.at[dst].set(jnp.where(written, s.actions, 0), mode="drop"),
            lens.at[dst].set(s.n, mode="drop"),
            trunc.at[dst].set(jax.vmap(_remaining)(s), mode="drop"),
        )

    def gather(s, pick):
        return jax.tree.map(lambda a: a[pick], s)

    def scatter(s, dst, new, keep=()):  # rows at ``dst``; ``width`` drops the row
        put = lambda a, b: a.at[dst].set(b, mode="drop")
        fields = [f for f in s._fields if f not in keep]
        return s._replace(**{f: jax.tree.map(put, getattr(s, f), getattr(new, f)) for f in fields})

    # Each part of a step touches a few rows of the slot batch: gathered,
    # changed and scattered back, so the big per-slot arrays are updated in
    # place and never copied whole.
    def step(c):
        s, nxt, wait, out, stats = c
        # Global model: the longest-waiting slots that need a start, K at a time.
        need = s.phase == NEEDS_START
        live = (s.phase != DONE).sum()
        due = need.any() & (need.sum() >= jnp.minimum(k_glob, live))
        prio, pick = jax.lax.top_k(jnp.where(need, wait, -1), k_glob)
        dst = jnp.where(prio >= 0, pick, width)
        s = _when(due, lambda s: scatter(s, dst, each(start)(gather(s, pick))), s)
        wait = jnp.where(s.phase == NEEDS_START, wait + 1, 0)

        # Local model: every moving slot moves once. Each slot's observation
        # (a small window) is cut out; the moving slots' observations are
        # gathered into the smallest of a few fixed widths that holds them
        # (a batch's tail runs narrow), decided together and scattered back.
        moving = s.phase == MOVING
        n_moving = moving.sum()
        size = jnp.searchsorted(jnp.asarray(widths), n_moving)
        decide = jax.vmap(lambda pst, lst, obs: policy.decide(ctx, pst, lst, obs))

        def decided(w):
            def f(inputs):
                if w == width:
                    return decide(*inputs)
                _, pick = jax.lax.top_k(moving.astype(jnp.int32), w)
                out = decide(*gather(inputs, pick))
                # Rows of slots that are not moving are never read (`move` skips them).
                return jax.tree.map(
                    lambda a: jnp.zeros((width, *a.shape[1:]), a.dtype).at[pick].set(a), out
                )

            return f

        inputs = (s.pstate, s.lstate, jax.vmap(lambda s: observe(policy, ctx, s))(s))
        decision = jax.lax.switch(size, [decided(w) for w in widths], inputs)
        s = jax.vmap(lambda s, d: move(s, d, limits))(s, decision)

        # Finished slots hand their plan over and take the next images, a few a step.
        free = s.phase == DONE
        _, pick = jax.lax.top_k(free.astype(jnp.int32), refills)
        i = nxt + jnp.cumsum(free[pick]) - 1
        take = free[pick] & (i < count)

        def refill(args):
            s, out = args
            out = save(out, gather(s, pick), take)
            # A new image's action rows are not cleared: ``save`` reads only ``n`` of them.
            return scatter(s, jnp.where(take, pick, width), fetch(i), keep=("actions",)), out

        s, out = _when(take.any(), refill, (s, out))
        nxt = nxt + take.sum()

        n_starts = jnp.where(due, (prio >= 0).sum(), 0)
        rows_run = jnp.asarray(widths)[size]
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
