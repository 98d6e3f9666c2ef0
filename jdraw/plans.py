"""The planner's output."""

from __future__ import annotations

import dataclasses

import numpy as np

from jdraw import geometry


@dataclasses.dataclass
class Plan:
    """Drawing plans for a batch of images.

    Attributes:
      strokes: one entry per image; each a list of ``[n, 2]`` float arrays of
        (x, y) canvas points the pen visits while down, in drawing order.
      actions: ``int32 [B, T, 3]`` (dx, dy, touch) as executed: ``touch=0`` is
        a pen-up jump (the global model's move to a stroke start), ``touch=1``
        a pen-down move that inks the segment (a lone ``(0, 0, 1)`` is a dot).
        Rows past ``lengths`` are zero.
      lengths: ``int32 [B]`` number of valid action rows.
      truncated: ``bool [B]`` true where the step bound cut the plan short.
    """

    strokes: list[list[np.ndarray]]
    actions: np.ndarray
    lengths: np.ndarray
    truncated: np.ndarray

    def __len__(self) -> int:
        return len(self.strokes)

    @classmethod
    def from_actions(cls, actions, lengths, truncated=None, targets=None) -> Plan:
        """The plan that ``actions [B, T, 3]`` (first ``lengths [B]`` rows) draw.

        ``truncated`` is given, or judged against ``targets [B, H, W]``: true
        exactly where ink the actions do not draw remains.
        """
        actions, lengths = np.asarray(actions), np.asarray(lengths)
        strokes = [strokes_from_actions(a, n) for a, n in zip(actions, lengths)]
        if truncated is None:
            truncated = [
                (t & ~geometry.render_strokes(s, t.shape)).any() for t, s in zip(targets, strokes)
            ]
        return cls(strokes, actions, lengths, np.asarray(truncated, bool).reshape(len(strokes)))

    @classmethod
    def from_strokes(cls, strokes, truncated, width: int = 0) -> Plan:
        """The plan that draws each image's ``strokes`` in order (:func:`actions_from_strokes`).

        ``width``: the fewest action rows of the result (a reordered plan keeps
        its input's width).
        """
        rows = [actions_from_strokes(s) for s in strokes]
        T = max([width, *(len(r) for r in rows)])
        actions = np.zeros((len(rows), T, 3), np.int32)
        for b, r in enumerate(rows):
            actions[b, : len(r)] = r
        lengths = np.asarray([len(r) for r in rows], np.int32)
        return cls(strokes, actions, lengths, np.asarray(truncated, bool))


def strokes_from_actions(actions: np.ndarray, length: int, start=(0, 0)) -> list[np.ndarray]:
    """Replays ``actions[:length]`` (``[T, 3]`` dx, dy, touch) into strokes.

    The pen starts at ``start``; a run of ``touch=1`` rows is one stroke whose
    points are the position before the run and after each of its moves.
    """
    a = np.asarray(actions[:length], np.int64).reshape(-1, 3)
    after = np.asarray(start, np.int64) + np.cumsum(a[:, :2], axis=0)  # pen after each row
    before = np.concatenate([np.asarray(start, np.int64)[None], after[:-1]])
    touch = a[:, 2] != 0
    edge = np.diff(np.concatenate([[0], touch.astype(np.int8), [0]]))
    moved = np.any(a[:, :2] != 0, axis=1)
    return [
        np.concatenate([before[s : s + 1], after[s:e][moved[s:e]]]).astype(np.float64)
        for s, e in zip(np.flatnonzero(edge == 1), np.flatnonzero(edge == -1))
    ]


def actions_from_strokes(strokes, start=(0, 0)) -> np.ndarray:
    """``int32 [T, 3]`` (dx, dy, touch) drawing ``strokes`` in order, as :class:`Plan` has them.

    A pen-up jump to each stroke's start, then its moves; a one-point stroke is a dot.
    The inverse of :func:`strokes_from_actions`.
    """
    parts = []
    pos = np.asarray(start, np.int64)
    for s in strokes:
        p = np.rint(np.asarray(s, float)).astype(np.int64)
        parts.append(np.array([[*(p[0] - pos), 0]], np.int64))
        if len(p) == 1:
            parts.append(np.array([[0, 0, 1]], np.int64))
        else:  # whole arrays, not a list per move: this runs for every stroke of every plan
            parts.append(
                np.concatenate([np.diff(p, axis=0), np.ones((len(p) - 1, 1), np.int64)], 1)
            )
        pos = p[-1]
    if not parts:
        return np.zeros((0, 3), np.int32)
    return np.concatenate(parts).astype(np.int32)


def render(plan: Plan, shape: tuple[int, int] = (geometry.CANVAS, geometry.CANVAS)) -> np.ndarray:
    """Draws each image's strokes: ``bool [B, H, W]``."""
    return (
        np.stack([geometry.render_strokes(s, shape) for s in plan.strokes])
        if len(plan)
        else (np.zeros((0, *shape), bool))
    )
