"""Laying a drawing out for the planner: the scale, its regions in reading order, tiles.

A drawing whose ink fits a character's extent at a scale where its lines stay
separable is fitted to one ``100 x 100`` canvas, as for a character. Otherwise
its centrelines are drawn on one large canvas at that scale, split into
connected regions (a cursive word, a printed letter, a sketch), and every
region wider or taller than a canvas is laid out as a grid of canvas-sized tiles.
A region much wider than its text line is high is joined-up writing
(:func:`joined_pieces`), and its tiles say so; a drawing that is mostly such writing
is drawn no larger than the planner learned it (:func:`joined_scale`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import cv2
import numpy as np

from jdraw import geometry
from jdraw.images.canvas import (
    CHAR_EXTENT,
    CanvasTransform,
    fit_transform,
    ink_bbox,
    render_polylines,
)
from jdraw.images.prepare import Prepared

CANVAS = geometry.CANVAS
# A drawing that fits one canvas at this fraction of the separable scale is fitted, not tiled.
FIT_SLACK = 0.7
# A piece of ink at least this many times as wide as its text line's core is high (about
# its x-height; a printed m is under 2) runs through three or more letters: joined-up
# writing (a cursive word, a joined Arabic piece; :func:`joined_pieces`).
JOINED_WIDTH = 2.5
# Canvas pixels kept between separate lines unless asked otherwise (plan_image's min_gap).
MIN_GAP = 4.0
# Canvas pixels high that joined-up writing's x-height band is drawn at most (at MIN_GAP):
# the median x-height of the cursive fragments the planner learned joined-up writing from
# (jdraw.data.cursive.fragments: 16 to 41 px, 5th to 95th percentile, median 24.7).
JOINED_CORE = 25.0
# Canvas pixels that separate lines come at least when joined-up writing is drawn smaller
# (by the drawing's line gap): one blank pixel between two 1-pixel lines.
SEPARATE = 2.0


@dataclasses.dataclass(frozen=True)
class Tile:
    """One planner input.

    Attributes:
      region: index of the region it belongs to.
      transform: input pixels -> this tile's canvas pixels.
      image: ``bool [100, 100]`` what the planner is given.
      joined: its ink is joined-up writing (:func:`joined_pieces`), or a piece of a
        drawing that mostly is (the "er" of a cursive "river" lifted after its v):
        the planner may join its strokes back over their own line, as such a
        writer goes back up a stem (:data:`jdraw.planner.splits.JOINED_RETRACE`).
    """

    region: int
    transform: CanvasTransform
    image: np.ndarray
    joined: bool = False


def choose_scale(prep: Prepared, min_gap: float = MIN_GAP) -> tuple[float, bool]:
    """Canvas pixels per input pixel, and whether the drawing fits one canvas.

    Centrelines of strokes that do not touch are at least a stroke width
    apart; at ``min_gap / width`` canvas pixels per input pixel they stay
    ``min_gap`` pixels apart. A drawing whose ink fits the character extent at
    ``FIT_SLACK`` of that scale or larger is fitted to one canvas like a
    character (lines then stay at least ``FIT_SLACK * min_gap`` apart, as in
    KanjiVG's densest characters), so the model orders all its strokes.

    Otherwise it is tiled, and drawn as small as its lines allow: they come no
    closer than ``prep.gap`` (:func:`jdraw.images.gaps.line_gap`, one to four
    stroke widths), so at ``min_gap / gap`` they still stay ``min_gap`` apart,
    and a handwritten word's letters come out about as large as the planner's
    training characters and fragments (until 2026-12-04 a tiled drawing was
    drawn at ``min_gap / width``, its cursive letters most of a canvas high).
    Never enlarged, since thin lines are already separable.
    """
    x0, y0, x1, y1 = ink_bbox(prep.polylines)
    s_fit = CHAR_EXTENT / max(x1 - x0, y1 - y0, 1.0)
    if s_fit >= FIT_SLACK * min(1.0, min_gap / prep.width):
        return s_fit, True
    return min(1.0, min_gap / prep.gap), False


def tall_boxes(boxes: np.ndarray) -> np.ndarray:
    """``bool [n]``: which boxes ``(x0, y0, x1, y1)`` are letter bodies, not marks.

    A mark (a dot, an accent) is small both ways: its width and its height are
    under half the typical height, the median height with each box counted by
    its height. A word with more dots than letter bodies (an Arabic word with
    four dots over two joined pieces, a cursive "mini") measures its bodies,
    not its dots (a median over boxes would measure a dot, and the dots would
    make a text line of their own, drawn first). A long flat piece (a kana's
    top bar, an underline, a t's bar) is never a mark.
    """
    heights = boxes[:, 3] - boxes[:, 1] + 1
    widths = boxes[:, 2] - boxes[:, 0] + 1
    h = np.sort(heights)
    cum = np.cumsum(h)
    typical = h[np.searchsorted(cum, 0.5 * cum[-1])]
    return np.maximum(heights, widths) >= 0.5 * typical


def line_cores(labels: np.ndarray, stats: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each connected piece's text line and the height of that line's core, in pixels.

    ``labels`` and ``stats`` are ``cv2.connectedComponentsWithStats``' of the
    centrelines (piece ``k`` is label ``k + 1``). The core is the band of rows that
    cross at least half as many lines as the busiest tenth of rows: a line of
    letters' x-height band, which every letter crosses and only the tall ones rise
    above, and most of a line of kanji.

    Returns:
      ``(line_of [n] int, core [n] int)``: each piece's line (:func:`text_lines`) and
      its line's core height.
    """
    x, y, w, h = (stats[1:, k].astype(np.int64) for k in range(4))
    core = np.ones(len(x), np.int64)
    if not len(x):
        return np.zeros(0, int), core
    line_of, _ = text_lines(np.stack([x, y, x + w - 1, y + h - 1], 1))
    for k in np.unique(line_of):
        on = line_of == k
        y0, y1 = int(y[on].min()), int((y + h)[on].max())
        rows = np.isin(labels[y0:y1], np.flatnonzero(on) + 1)
        # A line starts where a row has ink and the 3 pixels before it none: separate
        # lines are further apart than that (min_gap). The busiest rows are the top
        # tenth, as the steps of a near-flat line make a row or two look busier.
        before = np.zeros_like(rows)
        for d in range(1, 4):
            before[:, d:] |= rows[:, :-d]
        crossings = np.count_nonzero(rows & ~before, axis=1)
        busy = np.percentile(crossings[crossings > 0], 90)
        core[on] = max(np.count_nonzero(crossings >= 0.5 * busy), 1)
    return line_of, core


def joined_pieces(labels: np.ndarray, stats: np.ndarray) -> np.ndarray:
    """``bool [n]``: which connected pieces of centrelines are joined-up writing.

    ``labels`` and ``stats`` are ``cv2.connectedComponentsWithStats``' of the
    centrelines (piece ``k`` is label ``k + 1``). A piece at least
    :data:`JOINED_WIDTH` times as wide as its text line's core (:func:`line_cores`)
    is high runs through several letters: a cursive word, a joined piece of Arabic,
    a Devanagari word under its headline. A printed letter, a kanji's part or a dot
    is narrower; a long flat piece (a dash, a kanji's one bar) may count, and being
    one straight line it has no strokes to join back over it.
    """
    return _wide(stats, line_cores(labels, stats)[1])


def _wide(stats: np.ndarray, core: np.ndarray) -> np.ndarray:
    """``bool [n]``: pieces at least :data:`JOINED_WIDTH` times as wide as ``core`` is high."""
    return stats[1:, cv2.CC_STAT_WIDTH].astype(np.int64) >= JOINED_WIDTH * core


def _most(stats: np.ndarray, joined: np.ndarray) -> bool:
    """Whether the ``joined`` pieces hold most of the centreline pixels."""
    area = stats[1:, cv2.CC_STAT_AREA]
    return bool(area[joined].sum() * 2 > area.sum())


def joined_scale(stats: np.ndarray, core: np.ndarray, min_gap: float = MIN_GAP) -> float:
    """How much smaller to draw mostly joined-up writing, so that its letters come out
    the size the planner learned them at (1.0: as they are).

    ``stats``: ``cv2.connectedComponentsWithStats``' of the centrelines; ``core``: each
    piece's line core (:func:`line_cores`). Where most centreline pixels are joined-up
    writing (:func:`joined_pieces`) and its lines' core (each joined piece's counted by
    its pixels, the median) is higher than :data:`JOINED_CORE` times
    ``min_gap / MIN_GAP``, the factor that makes it that high. A larger ``min_gap``
    draws everything larger, this too.
    :func:`layout` shrinks no further than keeps the drawing's separate lines
    :data:`SEPARATE` pixels apart (its line gap), so that a long line drawing taken for
    such writing (a skyline) keeps its detail.
    """
    joined = _wide(stats, core)
    if not _most(stats, joined):
        return 1.0
    order = np.argsort(core[joined], kind="stable")
    cum = np.cumsum(stats[1:, cv2.CC_STAT_AREA][joined][order])
    typical = core[joined][order][np.searchsorted(cum, 0.5 * cum[-1])]
    return min(1.0, JOINED_CORE * min_gap / MIN_GAP / typical)


def text_lines(
    boxes: Sequence[tuple[float, float, float, float]],
) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """Text lines of ``boxes`` ``(x0, y0, x1, y1)``: each box's line and the lines' spans.

    Tall boxes (:func:`tall_boxes`) define the lines; a small box (an i's dot,
    a comma) joins the line whose vertical span is nearest its centre.

    Returns:
      ``(line_of [n] int, spans)``: lines numbered top to bottom, ``spans[k] = (y0, y1)``.
    """
    b = np.asarray(boxes, np.float64).reshape(-1, 4)
    if not len(b):
        return np.zeros(0, int), []
    heights = b[:, 3] - b[:, 1] + 1
    tall = tall_boxes(b)
    lines: list[list[float]] = []  # [y0, y1]
    for i in np.argsort(b[:, 1]):
        if not tall[i]:
            continue
        for line in lines:
            overlap = min(line[1], b[i, 3]) - max(line[0], b[i, 1])
            if overlap > 0.5 * min(line[1] - line[0], heights[i]):
                line[0], line[1] = min(line[0], b[i, 1]), max(line[1], b[i, 3])
                break
        else:
            lines.append([b[i, 1], b[i, 3]])
    lines.sort(key=lambda ln: ln[0] + ln[1])
    centre_y = (b[:, 1] + b[:, 3]) / 2
    spans = np.asarray(lines)
    gap = np.maximum(spans[None, :, 0] - centre_y[:, None], centre_y[:, None] - spans[None, :, 1])
    return np.argmin(gap, axis=1), [(float(a), float(c)) for a, c in lines]


def piece_of(points: np.ndarray, labels: np.ndarray) -> int:
    """The label most of a polyline's vertices lie on in ``labels [H, W]`` (0: background,
    left out; its ends may lie off the ink); 0 if none lies on a piece."""
    h, w = labels.shape
    q = np.round(np.asarray(points, np.float64).reshape(-1, 2)).astype(int)
    got = labels[np.clip(q[:, 1], 0, h - 1), np.clip(q[:, 0], 0, w - 1)]
    got = got[got > 0]
    return int(np.bincount(got).argmax()) if len(got) else 0


def mark_bodies(b: np.ndarray, tall: np.ndarray, line_of=None) -> dict[int, int]:
    """``{mark: body}``: for each mark of boxes ``b [n, 4]`` (not ``tall``), the letter
    body of its text line (``line_of``; ``None``: one line) spanning its centre's x
    that lies nearest it in y; marks that no body spans are left out."""
    line_of = np.zeros(len(b), int) if line_of is None else np.asarray(line_of)
    cx, cy = (b[:, 0] + b[:, 2]) / 2, (b[:, 1] + b[:, 3]) / 2
    body_of: dict[int, int] = {}
    for i in np.flatnonzero(~tall):
        over = np.flatnonzero(
            tall & (line_of == line_of[i]) & (b[:, 0] <= cx[i]) & (cx[i] <= b[:, 2])
        )
        if len(over):
            dy = np.maximum(b[over, 1] - cy[i], cy[i] - b[over, 3])
            body_of[int(i)] = int(over[np.argmin(dy)])
    return body_of


def _reading_order(
    boxes: Sequence[tuple[float, float, float, float]], rtl: bool = False
) -> list[int]:
    """Indices of ``boxes`` in reading order: text lines top to bottom, along each line.

    Along a line boxes go left to right, or right to left if ``rtl``. A mark
    (a small box, as :func:`text_lines` says, whose centre lies over or under
    a tall box of its line: an i's dot, an accent, Arabic dots) comes right
    after that letter body, as people write; if several bodies span it, the
    nearest.
    """
    if not boxes:
        return []
    b = np.asarray(boxes, np.float64)
    line_of, _ = text_lines(boxes)
    tall = tall_boxes(b)
    centre_x = (b[:, 0] + b[:, 2]) / 2
    centre_y = (b[:, 1] + b[:, 3]) / 2
    sign = -1.0 if rtl else 1.0
    body_of = mark_bodies(b, tall, line_of)
    heads = [i for i in range(len(b)) if i not in body_of]
    heads.sort(key=lambda i: (line_of[i], sign * centre_x[i], centre_y[i]))
    order = []
    for h in heads:
        order.append(h)
        marks = [i for i, body in body_of.items() if body == h]
        order.extend(sorted(marks, key=lambda i: (sign * centre_x[i], centre_y[i])))
    return order


def layout(
    prep: Prepared, min_gap: float = MIN_GAP, rtl: bool = False
) -> tuple[float, list[Tile], list[tuple]]:
    """Splits a prepared image into planner inputs.

    Args:
      rtl: regions and a region's tiles go right to left along a line.

    Returns:
      ``(scale, tiles, regions)``: tiles in planning order (regions in reading
      order; a region's tiles column by column if it is wider than tall, else
      row by row) and each region's input-pixel box.
    """
    scale, single = choose_scale(prep, min_gap)
    if single:
        tf = fit_transform(ink_bbox(prep.polylines))
        canvas = render_polylines(prep.polylines, tf, (CANVAS, CANVAS))
        joined = mostly_joined(prep.skeleton)
        return scale, [Tile(0, tf, canvas, joined)], [ink_bbox(prep.polylines)]
    h, w = prep.shape

    def draw(scale):
        big = render_polylines(
            prep.polylines,
            CanvasTransform(scale),
            (int(np.ceil(scale * (h - 1))) + 1, int(np.ceil(scale * (w - 1))) + 1),
        )
        return cv2.connectedComponentsWithStats(big.astype(np.uint8), connectivity=8)

    n, labels, stats, _ = draw(scale)
    _, core = line_cores(labels, stats)
    smaller = joined_scale(stats, core, min_gap)
    if smaller < 1.0:  # but its separate lines keep a blank pixel between them
        scale = max(scale * smaller, min(scale, SEPARATE / prep.gap))
        n, labels, stats, _ = draw(scale)
        _, core = line_cores(labels, stats)
    whole = CanvasTransform(scale)
    boxes = []
    for k in range(1, n):
        x, y, bw, bh = stats[k, :4]
        boxes.append(tuple(whole.to_input([[x, y], [x + bw - 1, y + bh - 1]]).ravel()))
    joined = _wide(stats, core)
    if _most(stats, joined):  # a hand that joins its letters: its short pieces too
        joined[:] = True
    tiles: list[Tile] = []
    regions = []
    for r, i in enumerate(_reading_order(boxes, rtl)):
        k = i + 1
        x, y, bw, bh = (int(v) for v in stats[k, :4])
        regions.append(boxes[i])
        nx, ny = -(-bw // CANVAS), -(-bh // CANVAS)
        mask = labels == k
        gx = _grid_start(mask.sum(0), x, bw, nx)
        gy = _grid_start(mask.sum(1), y, bh, ny)
        cells = [(i, j) for i in range(nx) for j in range(ny)]
        if rtl:
            cells.sort(key=lambda c: (-c[0], c[1]))
        if bw <= bh:
            cells.sort(key=lambda c: (c[1], -c[0] if rtl else c[0]))
        for cx, cy in cells:
            ox, oy = gx + cx * CANVAS, gy + cy * CANVAS
            tile = _crop(mask, ox, oy)
            if tile.any():
                tiles.append(Tile(r, whole.shifted(ox, oy), tile, bool(joined[i])))
    return scale, tiles, regions


BORDER_BAND = 3  # pixels either side of a tile border whose lines count as cut by it


def _grid_start(profile: np.ndarray, start: int, size: int, n: int) -> int:
    """Where a region's grid of ``n`` canvases begins along one axis.

    The grid covers the region's ``size`` pixels from ``start`` with up to 99 to
    spare. Of the places it may begin, the one whose borders between canvases
    have the least ink within :data:`BORDER_BAND` pixels of them (``profile``: the
    region's centreline pixels per column or row): a border then runs through a
    gap between letters or across a plain stretch of line, seldom through a
    junction, a loop or the turn of a hump, which a tile's planner sees cut in
    two and the stitcher cannot mend. Nearest the centred grid on a tie.
    """
    slack = n * CANVAS - size
    centred = start - slack // 2
    if n < 2:
        return centred
    band = np.concatenate([[0], np.cumsum(profile)])
    end = len(profile)

    def ink_near(c: int) -> int:
        lo, hi = min(max(c - BORDER_BAND, 0), end), min(max(c + BORDER_BAND, 0), end)
        return int(band[hi] - band[lo])

    def cost(g: int) -> tuple[int, int]:
        return sum(ink_near(g + j * CANVAS) for j in range(1, n)), abs(g - centred)

    return min(range(start - slack, start + 1), key=cost)


def mostly_joined(lines: np.ndarray) -> bool:
    """Whether most centreline pixels of ``lines`` are joined-up writing (:func:`joined_pieces`)."""
    n, labels, stats, _ = cv2.connectedComponentsWithStats(
        np.asarray(lines, np.uint8), connectivity=8
    )
    return n >= 2 and _most(stats, joined_pieces(labels, stats))


def _crop(img: np.ndarray, ox: int, oy: int) -> np.ndarray:
    """``img[oy:oy + 100, ox:ox + 100]``, zero outside ``img``."""
    out = np.zeros((CANVAS, CANVAS), bool)
    h, w = img.shape
    x0, y0, x1, y1 = max(ox, 0), max(oy, 0), min(ox + CANVAS, w), min(oy + CANVAS, h)
    if x1 > x0 and y1 > y0:
        out[y0 - oy : y1 - oy, x0 - ox : x1 - ox] = img[y0:y1, x0:x1]
    return out
