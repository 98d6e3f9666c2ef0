"""The training losses of both models (paper eqs. 5-7 and 9) and of ablation (c).

Each sample's inputs are built by one function written for one example
(:func:`stroke_windows`, :func:`global_inputs`) and batched with one
``jax.vmap``; they call :mod:`jdraw.state` as the planner does. The encoders
then run on the whole batch: their batch norms take the batch's statistics.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import optax

from jdraw import state as S
from jdraw.model import network as M


def stroke_windows(target, labels, visited, pts, n_moves, size: int):
    """The local windows the planner sees along one demonstrated stroke.

    Args:
      target: ``bool [100, 100]`` ink.
      labels: ``int32 [100, 100]`` its component labels.
      visited: ``bool [100, 100]`` before the first local move (earlier
        strokes and this stroke's start).
      pts: ``int32 [T + 1, 2]`` pen positions (x, y); past ``n_moves`` they repeat.
      n_moves: ``int32 []`` moves of the stroke.
      size: window side (``model.window``).

    Returns:
      ``(windows float32 [T, size, size, 3], inside bool [T, size, size])``:
      step ``k``'s window is taken before move ``k``.
    """

    def body(visited, k):
        pen = pts[k]
        win, inside = S.local_window(target, labels, visited, pen, size)
        v2, _, _ = S.apply_move(visited, pen, pts[k + 1] - pen)
        return jnp.where(k < n_moves, v2, visited), (win, inside)

    _, out = jax.lax.scan(body, visited, jnp.arange(pts.shape[0] - 1))
    return out


def local_loss(model: M.DrawModel, b: dict):
    """Mean over valid steps of the move and touch cross-entropies (eqs. 5-7).

    ``b`` is :func:`jdraw.data.batches.local_batch`'s dict; only its packed
    ``(slot_b, slot_t)`` windows are encoded.
    """
    windows = jax.vmap(stroke_windows, in_axes=(0, 0, 0, 0, 0, None))
    wins, inside = windows(
        b["target"], b["labels"], b["visited"], b["pts"], b["n_moves"], model.window
    )
    sb, st = b["slot_b"], b["slot_t"]
    feat = model.local_features(wins[sb, st], inside[sb, st])  # [N, 1600]
    xp = model.core.project(feat) * b["slot_valid"][:, None]
    B, T = b["move"].shape
    seq = jnp.zeros((B, T, xp.shape[-1]), xp.dtype).at[sb, st].add(xp)
    _, hs = jax.lax.scan(model.core.step, model.core.init_carry((B,)), jnp.swapaxes(seq, 0, 1))
    move_logits, touch_logits = model.heads(jnp.swapaxes(hs, 0, 1))  # [B, T, 25], [B, T]
    valid = b["valid"].astype(jnp.float32)
    ce_move = optax.softmax_cross_entropy_with_integer_labels(move_logits, b["move"])
    ce_touch = optax.sigmoid_binary_cross_entropy(touch_logits, b["touch"])
    n = jnp.maximum(valid.sum(), 1.0)
    drawn = valid * b["touch"]  # steps that move (the last says "lift")
    acc_move = jnp.sum((jnp.argmax(move_logits, -1) == b["move"]) * drawn) / jnp.maximum(
        drawn.sum(), 1.0
    )
    acc_touch = jnp.sum(((touch_logits > 0) == (b["touch"] > 0.5)) * valid) / n
    loss = jnp.sum((ce_move + ce_touch) * valid) / n
    return loss, {"acc_move": acc_move, "acc_touch": acc_touch}


def global_inputs(target, visited, last, pen, has_pen, label):
    """One sample's global state ``float32 [100, 100, 4]`` and where its label may be.

    Returns ``(state, allowed bool [10000])``: the pixels a stroke may start
    on (:func:`jdraw.state.allowed_starts`, as the planner decodes) plus the
    label ``label`` (flat index ``y * 100 + x``).
    """
    x = S.global_state(target, visited, last, pen, has_pen)
    allowed = S.allowed_starts(target, visited, False).reshape(-1)
    return x, allowed | jax.nn.one_hot(label, allowed.shape[0], dtype=bool)


def global_loss(model: M.DrawModel, g: dict):
    """Cross-entropy of the next start (eq. 9) over the pixels a stroke may start on.

    ``g`` is :func:`jdraw.data.batches.global_batch`'s dict.
    """
    x, allowed = jax.vmap(global_inputs)(
        g["target"], g["visited"], g["last"], g["pen"], g["has_pen"], g["start"]
    )
    logits = model.global_logits(x, restrict=False).reshape(allowed.shape)
    logits = jnp.where(allowed, logits, -1e9)
    ce = optax.softmax_cross_entropy_with_integer_labels(logits, g["start"])
    acc = jnp.mean(jnp.argmax(logits, -1) == g["start"])
    return jnp.mean(ce), {"acc_start": acc}


def global_only_loss(model: M.DrawModel, g: dict):
    """Ablation (c): next position (over ink pixels) plus touch cross-entropies.

    ``g`` is :func:`jdraw.train.global_only.batch`'s dict. The next position
    is chosen among ink pixels, as the planner chooses it.
    """
    x = jax.vmap(S.global_state)(g["target"], g["visited"], g["last"], g["pen"], g["has_pen"])
    pos, touch = model.position_and_touch(x)  # [G, 100, 100], [G]
    pos = pos.reshape(x.shape[0], -1)
    ink = g["target"].reshape(x.shape[0], -1) | jax.nn.one_hot(g["goal"], pos.shape[1], dtype=bool)
    pos = jnp.where(ink, pos, -1e9)
    ce = optax.softmax_cross_entropy_with_integer_labels(pos, g["goal"])
    bce = optax.sigmoid_binary_cross_entropy(touch, g["touch"])
    return jnp.mean(ce + bce), {
        "acc_goal": jnp.mean(jnp.argmax(pos, -1) == g["goal"]),
        "acc_touch": jnp.mean((touch > 0) == (g["touch"] > 0.5)),
    }


def total_loss(model: M.DrawModel, batch: dict, global_weight: float):
    """The loss of a :func:`jdraw.train.feed.make_batch` batch and its logs.

    A batch holds ``global_only`` (ablation c), or ``global`` alone (only the
    start model trains, stage ``start`` of ``configs/default.py``), or ``local`` and ``global``.
    """
    if "global_only" in batch:
        loss, logs = global_only_loss(model, batch["global_only"])
        return loss, {"loss": loss, **logs}
    gl, gm = global_loss(model, batch["global"])
    if "local" not in batch:
        return gl, {"loss": gl, "global_loss": gl, **gm}
    ll, lm = local_loss(model, batch["local"])
    loss = ll + global_weight * gl
    return loss, {"loss": loss, "local_loss": ll, "global_loss": gl, **lm, **gm}
