"""Training batches, built on the host, deterministic in ``(seed, step)``.

A local batch packs whole strokes (a stroke basis, as the paper trains) into a
fixed number of encoder windows: ``windows`` slots, each naming a
``(stroke, step)``; padding costs only the cheap LSTM recurrence, never the
encoder. A global batch holds the state before a random stroke and that
stroke's start pixel. The state images themselves are made on the device by
:mod:`jdraw.state`, the functions the planner calls.
"""

from __future__ import annotations

import numpy as np

from jdraw import geometry
from jdraw import state as S
from jdraw.data import demos as D
from jdraw.data import variants
from jdraw.data.kanji import KanjiSet

CANVAS = geometry.CANVAS


def _sample(ks, pool, rng, strength: float, styles) -> D.Demo:
    """A random character of ``pool``: jdraw's own lines, or a style of ``styles``.

    ``ks`` may be a :class:`jdraw.data.mix.Mixture` (``pool`` unused): the
    character then comes from one of its sets.
    """
    if isinstance(ks, KanjiSet):
        i = int(rng.choice(pool))
    else:
        ks, i = ks.pick(rng)
    if not styles:
        return D.sample(ks, i, rng, strength)
    return variants.sample(ks, i, rng, strength, styles)


def _union(strokes) -> np.ndarray:
    return geometry.render_strokes(strokes) if strokes else np.zeros((CANVAS, CANVAS), bool)


def local_batch(
    ks: KanjiSet,
    pool: np.ndarray,
    rng: np.random.Generator,
    *,
    windows: int,
    strokes: int,
    max_len: int,
    per_char: int,
    strength: float,
    styles: dict | None = None,
) -> dict:
    """Packs random strokes of random characters into ``windows`` slots.

    Returns a dict of numpy arrays (``B = strokes``, ``T = max_len``):
      ``target`` bool [B, 100, 100], ``labels`` int32 [B, 100, 100],
      ``visited`` bool [B, 100, 100] (earlier strokes and this stroke's start),
      ``pts`` int32 [B, T + 1, 2] pen positions, ``n_moves`` int32 [B],
      ``move`` int32 [B, T] move labels, ``touch`` float32 [B, T],
      ``valid`` bool [B, T], ``slot_b``/``slot_t`` int32 [windows],
      ``slot_valid`` bool [windows], ``n_strokes`` int.

    ``styles`` (``{style: probability}``, :func:`jdraw.data.variants.sample`)
    draws characters other ways too; None keeps jdraw's own lines.
    """
    out = {
        "target": np.zeros((strokes, CANVAS, CANVAS), bool),
        "labels": np.zeros((strokes, CANVAS, CANVAS), np.int32),
        "visited": np.zeros((strokes, CANVAS, CANVAS), bool),
        "pts": np.zeros((strokes, max_len + 1, 2), np.int32),
        "n_moves": np.zeros(strokes, np.int32),
        "move": np.full((strokes, max_len), geometry.STAY, np.int32),
        "touch": np.zeros((strokes, max_len), np.float32),
        "valid": np.zeros((strokes, max_len), bool),
        "slot_b": np.zeros(windows, np.int32),
        "slot_t": np.zeros(windows, np.int32),
        "slot_valid": np.zeros(windows, bool),
    }
    b = used = 0
    full = False
    while not full:
        d = _sample(ks, pool, rng, strength, styles)
        labels = S.component_labels(d.target)
        picks = rng.permutation(len(d.strokes))[:per_char]
        for i in sorted(picks):
            s = d.strokes[i]
            moves = len(s) - 1
            steps = min(moves + 1, max_len)  # the last step says "lift" unless cut
            if b >= strokes or used + steps > windows:
                full = True
                break
            out["target"][b] = d.target
            out["labels"][b] = labels
            v = _union(d.strokes[:i])
            v[s[0, 1], s[0, 0]] = True
            out["visited"][b] = v
            n = min(moves, max_len)
            out["pts"][b, : n + 1] = s[: n + 1]
            out["pts"][b, n + 1 :] = s[n]
            out["n_moves"][b] = n
            mv = geometry.move_index(np.diff(s[: n + 1], axis=0))
            out["move"][b, :n] = mv
            out["touch"][b, :n] = 1.0
            out["valid"][b, :steps] = True
            out["slot_b"][used : used + steps] = b
            out["slot_t"][used : used + steps] = np.arange(steps)
            out["slot_valid"][used : used + steps] = True
            used += steps
            b += 1
    out["n_strokes"] = b
    return out


def global_state_arrays(size: int, **labels) -> dict:
    """Zeroed inputs of :func:`jdraw.state.global_state` for ``size`` samples, plus labels.

    ``labels`` maps a name to the dtype of a ``[size]`` label array.
    """
    out = {k: np.zeros((size, CANVAS, CANVAS), bool) for k in ("target", "visited", "last")}
    out.update(pen=np.zeros((size, 2), np.int32), has_pen=np.zeros(size, bool))
    out.update({k: np.zeros(size, t) for k, t in labels.items()})
    return out


def global_batch(
    ks: KanjiSet,
    pool: np.ndarray,
    rng: np.random.Generator,
    *,
    size: int,
    strength: float,
    per_char: int = 1,
    styles: dict | None = None,
) -> dict:
    """States before a random stroke and that stroke's start.

    ``per_char`` states (before distinct strokes) come from each sampled
    character: making the character is most of the host's cost. ``styles``
    as for :func:`local_batch`.

    Returns numpy arrays: ``target``, ``visited``, ``last`` bool [G, 100, 100],
    ``pen`` int32 [G, 2], ``has_pen`` bool [G], ``start`` int32 [G] (flat
    index ``y * 100 + x``).
    """
    out = global_state_arrays(size, start=np.int32)
    picks: list[tuple[D.Demo, int]] = []
    while len(picks) < size:
        d = _sample(ks, pool, rng, strength, styles)
        if per_char == 1:  # the paper config's exact data order
            picks.append((d, int(rng.integers(len(d.strokes)))))
        else:
            for i in rng.permutation(len(d.strokes))[:per_char]:
                picks.append((d, int(i)))
    for g, (d, i) in enumerate(picks[:size]):
        out["target"][g] = d.target
        out["visited"][g] = _union(d.strokes[:i])
        if i > 0:
            out["last"][g] = _union(d.strokes[i - 1 : i])
            out["pen"][g] = d.strokes[i - 1][-1]
            out["has_pen"][g] = True
        x, y = d.strokes[i][0]
        out["start"][g] = y * CANVAS + x
    return out
