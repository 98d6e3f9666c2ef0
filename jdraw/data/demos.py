"""Demonstrations: a character's strokes as the planner's own actions.

Each stroke is rasterised to a 1-pixel, 8-connected pixel path and cut into
local moves with ``|dx|, |dy| <= 2`` that stay on that path: a two-pixel move
is taken only where :func:`jdraw.geometry.segment_pixels` inks exactly the path
pixel it skips. The target image is the union of the paths, so it is exactly
what replaying the demonstration draws.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from jdraw import geometry
from jdraw.data import kanji

CANVAS = geometry.CANVAS


def clean_path(pixels: np.ndarray, keep_turns: bool = False) -> np.ndarray:
    """Makes an integer point sequence a thin 8-connected path.

    Gaps are filled with :func:`geometry.polyline_pixels`; a pixel whose
    neighbours on the path already touch (the corner of a staircase) is
    dropped, as is a repeat.

    Args:
      pixels: ``[n, 2]`` int (x, y).
      keep_turns: keep a turn back onto the pixel the path came from, so a
        line drawn there and back (a cursive connector going back over the
        letter it landed on, :mod:`jdraw.data.cursive`) stays drawn twice.
        By default such a turn is a corner, and the way back erases the way
        there.

    Returns:
      ``[m, 2]`` int64 path, consecutive pixels 8-adjacent.
    """
    path = geometry.polyline_pixels(pixels)
    out: list[np.ndarray] = []
    for p in path:
        if out and np.array_equal(out[-1], p):
            continue
        if (
            len(out) >= 2
            and np.max(np.abs(out[-2] - p)) <= 1
            and not (keep_turns and np.array_equal(out[-2], p))
        ):
            out.pop()  # out[-1] was a corner: its neighbours touch directly
            if np.array_equal(out[-1], p):
                continue
        out.append(p)
    return np.asarray(out, np.int64).reshape(-1, 2)


def decompose(path: np.ndarray) -> np.ndarray:
    """Pen positions ``[M + 1, 2]`` whose local moves ink exactly ``path``."""
    pts = [path[0]]
    i, n = 0, len(path)
    while i < n - 1:
        if i + 2 < n:
            d = path[i + 2] - path[i]
            mid = path[i] + np.sign(d) * (np.abs(d) // 2)
            if np.max(np.abs(d)) == 2 and np.array_equal(mid, path[i + 1]):
                pts.append(path[i + 2])
                i += 2
                continue
        pts.append(path[i + 1])
        i += 1
    return np.asarray(pts, np.int64)


@dataclasses.dataclass
class Demo:
    """One character drawn as a demonstration.

    Attributes:
      strokes: list of ``[M_i + 1, 2]`` int64 pen positions (x, y), in order.
      target: ``bool [100, 100]``, the union of the strokes' pixels.
      drawn: ``bool [100, 100]`` the ink as drawn, before it was canonicalised,
        for a character drawn another way (:func:`jdraw.data.variants.sample`);
        ``None`` when it is the target.
    """

    strokes: list[np.ndarray]
    target: np.ndarray
    drawn: np.ndarray | None = None

    def actions(self, start=(0, 0)) -> np.ndarray:
        """``int32 [T, 3]`` (dx, dy, touch) as :class:`jdraw.Plan` stores them."""
        from jdraw.plans import actions_from_strokes

        return actions_from_strokes(self.strokes, start)

    def stroke_images(self) -> np.ndarray:
        """``bool [S, 100, 100]``, one image per stroke."""
        return np.stack([geometry.render_strokes([s]) for s in self.strokes])


def from_control_points(strokes_ctrl, affine=None, keep_turns: bool = False) -> Demo:
    """Builds the demonstration of one character.

    Args:
      strokes_ctrl: list of ``[K, 4, 2]`` cubic control points (canvas units).
      affine: optional ``(A [2, 2], t [2])`` applied to the control points.
      keep_turns: passed to :func:`clean_path` (True for strokes that go back
        over their own line, as cursive words' do).
    """
    strokes, target = [], np.zeros((CANVAS, CANVAS), bool)
    for c in strokes_ctrl:
        if affine is not None:
            c = c @ affine[0].T + affine[1]
        pts = np.floor(kanji.sample_cubics(c) + 0.5).astype(np.int64)
        pts = np.clip(pts, 0, CANVAS - 1)
        path = clean_path(pts, keep_turns)
        strokes.append(decompose(path))
        target[path[:, 1], path[:, 0]] = True
    return Demo(strokes=strokes, target=target)


def sample(
    ks: kanji.KanjiSet,
    i: int,
    rng: np.random.Generator | None = None,
    strength=1.0,
    keep_turns: bool | None = None,
) -> Demo:
    """Demonstration of character ``i``, augmented when ``rng`` is given.

    ``keep_turns``: see :func:`clean_path`; None takes the set's own
    (``ks.keep_turns``: True for cursive words and scribbles).
    """
    if keep_turns is None:
        keep_turns = bool(ks.keep_turns)
    strokes = ks.strokes(i)
    affine = None
    if rng is not None and strength > 0:
        affine = kanji.random_affine(rng, np.concatenate(strokes), strength)
    return from_control_points(strokes, affine, keep_turns)


def replay_arrays(demos: list[Demo], max_strokes: int, max_moves: int):
    """Pads demonstrations for :func:`jdraw.planner.loop.replay_policy`.

    Returns:
      ``(starts int32 [B, S, 2], moves int32 [B, S, L, 2], n_moves int32 [B, S])``.
    """
    b = len(demos)
    starts = np.zeros((b, max_strokes, 2), np.int32)
    moves = np.zeros((b, max_strokes, max_moves, 2), np.int32)
    n_moves = np.zeros((b, max_strokes), np.int32)
    for i, d in enumerate(demos):
        if len(d.strokes) > max_strokes:
            raise ValueError(f"demo {i} has {len(d.strokes)} strokes > max_strokes={max_strokes}")
        for j, s in enumerate(d.strokes):
            m = np.diff(s, axis=0)
            if len(m) > max_moves:
                raise ValueError(f"demo {i} stroke {j} has {len(m)} moves > max_moves={max_moves}")
            starts[i, j] = s[0]
            moves[i, j, : len(m)] = m
            n_moves[i, j] = len(m)
    return starts, moves, n_moves
