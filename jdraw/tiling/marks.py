"""Marks (dots, accents) drawn right after the letter they belong to, in one canvas.

The tiler (:mod:`jdraw.tiling.tiles`) calls :func:`marks_after_bodies` on a
right-to-left drawing fitted to a single canvas (a word or two of Hebrew or
Arabic), whose strokes the ranker ordered as a whole.
"""

from __future__ import annotations

import cv2
import numpy as np

from jdraw.tiling.layout import mark_bodies, piece_of, tall_boxes

NEAR = 3  # px: a stroke's points this far off the ink still count for the piece beside them


def marks_after_bodies(image: np.ndarray, strokes) -> list[int]:
    """The order of a canvas's ``strokes`` with each mark drawn right after its letter body.

    A drawing laid out in tiles is planned region by region, a mark (an i's dot,
    an accent, Arabic dots: :func:`jdraw.tiling.layout.tall_boxes`) right after
    the letter body under or over it (:func:`jdraw.tiling.layout.layout`). One
    fitted to a single canvas is planned whole, in the ranker's order, which may
    draw a dot after the next piece. For right-to-left text this draws each mark
    right after the stroke of its body that passes nearest it (its letter), the
    marks after one stroke right to left, and keeps the planner's order
    otherwise. A stroke belongs to the piece of ink (8-connected, of ``image``)
    that most of its points lie on or beside (:data:`NEAR`); a mark's body is the
    letter body spanning its centre's x that lies nearest it in y.
    """
    n, labels, stats, _ = cv2.connectedComponentsWithStats(image.astype(np.uint8), connectivity=8)
    if n <= 2 or not strokes:
        return list(range(len(strokes)))
    grown = cv2.dilate(labels.astype(np.uint16), np.ones((3, 3), np.uint8), iterations=NEAR)
    near = np.where(labels > 0, labels, grown)
    piece = [piece_of(p, near) - 1 for p in strokes]  # -1: on no piece
    b = np.array([(x, y, x + w - 1, y + h - 1) for x, y, w, h, _ in stats[1:]], np.float64)
    cx, cy = (b[:, 0] + b[:, 2]) / 2, (b[:, 1] + b[:, 3]) / 2
    after: dict[int, list[int]] = {}  # stroke -> the marks that follow it
    for m, body in mark_bodies(b, tall_boxes(b)).items():
        own = [k for k, pc in enumerate(piece) if pc == body]
        if own:
            gap = [
                np.abs(np.reshape(strokes[k], (-1, 2)) - (cx[m], cy[m])).sum(1).min() for k in own
            ]
            after.setdefault(own[int(np.argmin(gap))], []).append(m)
    placed = {m for ms in after.values() for m in ms}
    order: list[int] = []
    for k, pc in enumerate(piece):
        if pc in placed:
            continue  # drawn after its letter
        order.append(k)
        for m in sorted(after.get(k, []), key=lambda m: (-cx[m], cy[m])):  # right to left
            order += [j for j, q in enumerate(piece) if q == m]
    return order
