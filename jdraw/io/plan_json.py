"""A plan as JSON: the strokes and the pen-up moves between them."""

from __future__ import annotations

import numpy as np

from jdraw.io.frame import Strokes, as_strokes


def to_json(strokes: Strokes, shape: tuple[int, int]) -> dict:
    """Strokes and the pen-up moves between them, as a JSON-ready dict.

    ``{"width", "height", "units": "px", "strokes": [[[x, y], ...], ...],
    "moves": [{"pen": "up" | "down", ...}], "pen_down_length", "pen_up_length"}``;
    ``moves`` alternates a pen-up travel ``{"from", "to", "length"}`` (the
    first from the first stroke's start, length 0) with a pen-down stroke
    ``{"stroke": index, "length"}``.
    """
    h, w = shape
    ss = as_strokes(strokes)
    moves = []
    down = up = 0.0
    prev = ss[0][0] if ss else None
    for i, s in enumerate(ss):
        jump = float(np.hypot(*(s[0] - prev)))
        moves.append({"pen": "up", "from": _pt(prev), "to": _pt(s[0]), "length": round(jump, 3)})
        length = float(np.hypot(*np.diff(s, axis=0).T).sum()) if len(s) > 1 else 0.0
        moves.append({"pen": "down", "stroke": i, "length": round(length, 3)})
        down += length
        up += jump
        prev = s[-1]
    return {
        "width": w,
        "height": h,
        "units": "px",
        "strokes": [[_pt(p) for p in s] for s in ss],
        "moves": moves,
        "pen_down_length": round(down, 3),
        "pen_up_length": round(up, 3),
    }


def _pt(p) -> list[float]:
    return [round(float(p[0]), 3), round(float(p[1]), 3)]
