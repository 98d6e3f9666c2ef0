"""Ablation (c), Table I row 5: training data of the global model looped on itself.

It is trained on raw actions (points along each stroke, not the +-2 local
moves), as the paper did: the state before a random raw action and that
action (the next pen position and whether the pen is down on the way). The
loss is :func:`jdraw.train.losses.global_only_loss`; planning,
:mod:`jdraw.planner.global_only`.
"""

from __future__ import annotations

import numpy as np

from jdraw import geometry
from jdraw.data import demos as D
from jdraw.data.batches import global_state_arrays

CANVAS = geometry.CANVAS
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
            out["visited"][g] = geometry.render_strokes(
                [np.asarray(s) for s in drawn if len(s) > 1]
            )
            out["pen"][g] = acts[j - 1][0]
            out["has_pen"][g] = True
            cur = drawn[-1]
            if len(cur) > 1:
                out["last"][g] = geometry.render_strokes([np.asarray(cur)])
        p, touch, _ = acts[j]
        out["goal"][g] = p[1] * CANVAS + p[0]
        out["touch"][g] = touch
    return out
