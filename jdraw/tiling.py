"""Drawings of any size: regions, tiles, planning each and stitching the strokes.

:func:`plan_image` reduces an image to centrelines (:mod:`jdraw.image`), picks
the canvas scale (canvas pixels per input pixel) at which lines stay
separable, and then either

* fits the whole drawing to one ``100 x 100`` canvas, as for a character, or
* draws the centrelines on one large canvas at that scale, splits it into
  connected regions (a cursive word, a printed letter, a sketch), lays every
  region that is wider or taller than a canvas out as a grid of canvas-sized
  tiles, plans every region or tile, and joins strokes that leave one tile
  where a stroke of the next tile starts, so one stroke stays one motion.

Regions are drawn in reading order (lines of text top to bottom, left to
right within a line). Planned points are mapped back to input pixels and
snapped onto the skeleton, so strokes lie on the ink's centreline.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Sequence

import cv2
import numpy as np

from jdraw import image as im
from jdraw import raster

CANVAS = raster.CANVAS
Planner = Callable[..., object]


@dataclasses.dataclass(frozen=True)
class Tile:
    """One planner input.

    Attributes:
      region: index of the region it belongs to.
      transform: input pixels -> this tile's canvas pixels.
      image: ``bool [100, 100]`` what the planner is given.
    """

    region: int
    transform: im.CanvasTransform
    image: np.ndarray


@dataclasses.dataclass
class ImagePlan:
    """A plan for one image of any size, in input pixel coordinates.

    Attributes:
      strokes: ``[n, 2]`` float (x, y) input-pixel polylines drawn with the pen
        down, in drawing order.
      shape: ``(H, W)`` of the input image.
      prepared: the binarised image and its centrelines.
      scale: canvas pixels per input pixel used for planning.
      tiles: every planner input, in planning order.
      regions: ``(x0, y0, x1, y1)`` input-pixel box of each region, in drawing order.
      truncated: number of tiles whose plan hit the step bound.
      completed_pixels: canvas pixels a truncated plan left undrawn and that
        were traced along the skeleton instead.
      border_joins: strokes joined across a tile border.
      border_breaks: stroke ends next to ink across a tile border that were
        left unjoined (a pen lift at the border).
    """

    strokes: list[np.ndarray]
    shape: tuple[int, int]
    prepared: im.Prepared
    scale: float
    tiles: list[Tile]
    regions: list[tuple[float, float, float, float]]
    truncated: int = 0
    completed_pixels: int = 0
    border_joins: int = 0
    border_breaks: int = 0

    def pen_down_length(self) -> float:
        """Total length drawn, input pixels."""
        return float(sum(np.hypot(*np.diff(s, axis=0).T).sum() for s in self.strokes if len(s) > 1))


# ----------------------------------------------------------------------------- layout


def choose_scale(prep: im.Prepared, min_gap: float = 4.0) -> tuple[float, bool]:
    """Canvas pixels per input pixel, and whether the drawing fits one canvas.

    Centrelines of strokes that do not touch are at least a stroke width
    apart; at ``min_gap / width`` canvas pixels per input pixel they stay
    ``min_gap`` pixels apart, so they do not merge on the canvas. A drawing
    that still fits the character extent at that scale or larger is fitted
    to one canvas like a character; otherwise it is tiled at that scale (never
    enlarged, since thin lines are already separable).
    """
    s_min = min(1.0, min_gap / prep.width)
    x0, y0, x1, y1 = im.ink_bbox(prep.polylines)
    s_fit = im.CHAR_EXTENT / max(x1 - x0, y1 - y0, 1.0)
    return (s_fit, True) if s_fit >= s_min else (s_min, False)


def _reading_order(boxes: Sequence[tuple[float, float, float, float]]) -> list[int]:
    """Indices of ``boxes`` in reading order: text lines top to bottom, left to right.

    Tall boxes define the lines; a small box (an i's dot, a comma) joins the
    line whose vertical span is nearest its centre.
    """
    if not boxes:
        return []
    b = np.asarray(boxes, np.float64)
    heights = b[:, 3] - b[:, 1] + 1
    tall = heights >= 0.5 * np.median(heights)
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
    line_of = np.argmin(gap, axis=1)
    centre_x = (b[:, 0] + b[:, 2]) / 2
    return sorted(range(len(b)), key=lambda i: (line_of[i], centre_x[i]))


def layout(prep: im.Prepared, min_gap: float = 4.0) -> tuple[float, list[Tile], list[tuple]]:
    """Splits a prepared image into planner inputs.

    Returns:
      ``(scale, tiles, regions)``: tiles in planning order (regions in reading
      order; a region's tiles column by column if it is wider than tall, else
      row by row) and each region's input-pixel box.
    """
    scale, single = choose_scale(prep, min_gap)
    if single:
        tf = im.fit_transform(im.ink_bbox(prep.polylines))
        canvas = im.render_polylines(prep.polylines, tf, (CANVAS, CANVAS))
        return scale, [Tile(0, tf, canvas)], [im.ink_bbox(prep.polylines)]
    h, w = prep.shape
    whole = im.CanvasTransform(scale)
    big = im.render_polylines(
        prep.polylines,
        whole,
        (int(np.ceil(scale * (h - 1))) + 1, int(np.ceil(scale * (w - 1))) + 1),
    )
    n, labels, stats, _ = cv2.connectedComponentsWithStats(big.astype(np.uint8), connectivity=8)
    boxes = []
    for k in range(1, n):
        x, y, bw, bh = stats[k, :4]
        boxes.append(tuple(whole.to_input([[x, y], [x + bw - 1, y + bh - 1]]).ravel()))
    tiles: list[Tile] = []
    regions = []
    for r, i in enumerate(_reading_order(boxes)):
        k = i + 1
        x, y, bw, bh = (int(v) for v in stats[k, :4])
        regions.append(boxes[i])
        nx, ny = -(-bw // CANVAS), -(-bh // CANVAS)
        gx, gy = x - (nx * CANVAS - bw) // 2, y - (ny * CANVAS - bh) // 2
        cells = [(i, j) for i in range(nx) for j in range(ny)]
        if bw <= bh:
            cells.sort(key=lambda c: (c[1], c[0]))
        mask = labels == k
        for cx, cy in cells:
            ox, oy = gx + cx * CANVAS, gy + cy * CANVAS
            tile = _crop(mask, ox, oy)
            if tile.any():
                tiles.append(Tile(r, whole.shifted(ox, oy), tile))
    return scale, tiles, regions


def _crop(img: np.ndarray, ox: int, oy: int) -> np.ndarray:
    """``img[oy:oy + 100, ox:ox + 100]``, zero outside ``img``."""
    out = np.zeros((CANVAS, CANVAS), bool)
    h, w = img.shape
    x0, y0, x1, y1 = max(ox, 0), max(oy, 0), min(ox + CANVAS, w), min(oy + CANVAS, h)
    if x1 > x0 and y1 > y0:
        out[y0 - oy : y1 - oy, x0 - ox : x1 - ox] = img[y0:y1, x0:x1]
    return out


# ----------------------------------------------------------------------------- stitching


def stitch(
    pieces: Sequence[tuple[int, np.ndarray]], report: dict | None = None
) -> list[np.ndarray]:
    """Joins strokes of different tiles that meet across a tile border.

    Args:
      pieces: ``(tile, [n, 2] int (x, y))`` strokes in one shared pixel frame
        (a region's big canvas), in drawing order. Strokes of one tile are
        never joined to each other: the planner lifted the pen there.

    Returns:
      The joined strokes, ordered by their earliest piece; a joined stroke
      runs in the direction of its earliest piece.

    An end of one piece is joined to an end of a piece of another tile when
    the two points are 8-neighbours; where an end has several candidates the
    straightest continuation wins, and every end is joined at most once.
    ``report``, when given, receives ``joins`` (links made) and ``breaks``
    (ends that had a neighbour across a border but stayed unjoined).
    """
    ends: dict[tuple[int, int], list[tuple[int, int]]] = {}
    for s, (_, pts) in enumerate(pieces):
        for e in (0, 1):
            p = pts[0] if e == 0 else pts[-1]
            ends.setdefault((int(p[0]), int(p[1])), []).append((s, e))

    def outward(s: int, e: int) -> np.ndarray:
        pts = pieces[s][1].astype(np.float64)
        if len(pts) < 2:
            return np.zeros(2)
        a, b = (pts[min(3, len(pts) - 1)], pts[0]) if e == 0 else (pts[-min(4, len(pts))], pts[-1])
        d = b - a
        return d / max(np.hypot(*d), 1e-9)

    candidates = []
    for (x, y), here in ends.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for s2, e2 in ends.get((x + dx, y + dy), ()):
                    for s1, e1 in here:
                        if pieces[s1][0] == pieces[s2][0] or (s1, e1) >= (s2, e2):
                            continue
                        step = np.array([dx, dy], np.float64) / max(np.hypot(dx, dy), 1e-9)
                        score = float(outward(s1, e1) @ step - outward(s2, e2) @ step)
                        candidates.append((-score, s1, e1, s2, e2))
    candidates.sort()
    link: dict[tuple[int, int], tuple[int, int]] = {}
    for _, s1, e1, s2, e2 in candidates:
        if (s1, e1) in link or (s2, e2) in link:
            continue
        link[(s1, e1)] = (s2, e2)
        link[(s2, e2)] = (s1, e1)
    if report is not None:
        had = {(s1, e1) for _, s1, e1, _, _ in candidates} | {(s2, e2) for *_, s2, e2 in candidates}
        report["joins"] = report.get("joins", 0) + len(link) // 2
        report["breaks"] = report.get("breaks", 0) + len(had - link.keys())

    used = [False] * len(pieces)
    out = []
    for seed in range(len(pieces)):
        if used[seed]:
            continue
        used[seed] = True
        forward = [pieces[seed][1]]
        at = (seed, 1)
        while at in link:
            s, e = link[at]
            if used[s]:
                break
            used[s] = True
            forward.append(pieces[s][1] if e == 0 else pieces[s][1][::-1])
            at = (s, 1 - e)
        backward = []
        at = (seed, 0)
        while at in link:
            s, e = link[at]
            if used[s]:
                break
            used[s] = True
            backward.append(pieces[s][1] if e == 1 else pieces[s][1][::-1])
            at = (s, 1 - e)
        out.append(np.concatenate(backward[::-1] + forward))
    return out


# ----------------------------------------------------------------------------- planning


def _default_planner() -> Planner:
    import jdraw

    return jdraw.plan


def _run_planner(planner, images, checkpoint, max_steps):
    kwargs = {}
    if checkpoint is not None:
        kwargs["checkpoint"] = checkpoint
    if max_steps is not None:
        kwargs["max_steps"] = max_steps
    n = len(images)
    # Batches come in a few fixed sizes so a jitted planner compiles once per size.
    size = 1 << (n - 1).bit_length()
    batch = np.zeros((size, CANVAS, CANVAS), bool)
    batch[:n] = np.stack(images)
    plan = planner(batch, **kwargs)
    return plan.strokes[:n], np.asarray(plan.truncated, bool).reshape(-1)[:n]


def _complete(tile: np.ndarray, strokes: list[np.ndarray]) -> tuple[list[np.ndarray], int]:
    """Appends skeleton-traced strokes for ink a (truncated) plan left undrawn."""
    left = tile & ~raster.render_strokes(strokes, tile.shape)
    if not left.any():
        return strokes, 0
    return strokes + [p.astype(np.float64) for p in im.skeleton_polylines(left)], int(left.sum())


def _snap(points: np.ndarray, tree, skel_pts: np.ndarray, radius: float) -> np.ndarray:
    d, i = tree.query(points, distance_upper_bound=radius)
    ok = np.isfinite(d)
    out = points.copy()
    out[ok] = skel_pts[i[ok]]
    keep = np.ones(len(out), bool)
    keep[1:] = np.any(out[1:] != out[:-1], axis=1)
    return out[keep]


def plan_image(
    image: np.ndarray | str | os.PathLike,
    *,
    planner: Planner | None = None,
    checkpoint=None,
    max_steps: int | None = None,
    polarity: str = "auto",
    min_gap: float = 4.0,
    batch_size: int = 16,
    simplify_tol: float = 0.5,
    progress: bool = True,
) -> ImagePlan:
    """Plans how to draw an image of any size; strokes in input pixel coordinates.

    Args:
      image: ``[H, W]``, ``[H, W, 3]`` (RGB) or ``[H, W, 4]`` of any dtype, or
        an image file's path; a photo, a scan or a clean bitmap, either ink polarity.
      planner: ``planner(images [B, 100, 100] bool, *, checkpoint, max_steps)
        -> jdraw.Plan``; default :func:`jdraw.plan`.
      checkpoint, max_steps: passed to the planner when given.
      polarity: ``"auto"``, ``"dark"`` or ``"light"`` ink.
      min_gap: canvas pixels kept between the centrelines of separate strokes.
      batch_size: most tiles per planner call; a call's batch is padded to a
        power of two so a jitted planner compiles for few shapes.
      simplify_tol: input pixels a simplified stroke may stray from the plan.
      progress: show a progress bar (on a terminal) when there are several batches.

    Raises:
      jdraw.image.ImageError: bad shape; jdraw.image.BlankImageError: no ink.
    """
    from scipy.spatial import cKDTree
    from tqdm.auto import tqdm

    planner = planner or _default_planner()
    if isinstance(image, str | os.PathLike):
        image = im.load_image(image)
    prep = im.prepare(image, polarity=polarity)
    scale, tiles, regions = layout(prep, min_gap)
    skel_pts = np.argwhere(prep.skeleton)[:, ::-1].astype(np.float64)
    tree = cKDTree(skel_pts)
    radius = 0.75 / scale + 1.0

    planned: list[list[np.ndarray]] = []
    truncated = completed = 0
    batches = range(0, len(tiles), batch_size)
    bar = tqdm(
        total=len(tiles),
        desc="planning",
        unit="tile",
        disable=True if not progress or len(batches) < 2 else None,
    )
    for start in batches:
        chunk = tiles[start : start + batch_size]
        strokes, trunc = _run_planner(planner, [t.image for t in chunk], checkpoint, max_steps)
        truncated += int(trunc.sum())
        for t, s in zip(chunk, strokes, strict=True):
            s, n = _complete(t.image, [np.asarray(p, np.float64).reshape(-1, 2) for p in s])
            completed += n
            planned.append(s)
        bar.update(len(chunk))
    bar.close()

    out: list[np.ndarray] = []
    report: dict = {}
    for r in range(len(regions)):
        idx = [i for i, t in enumerate(tiles) if t.region == r]
        if len(idx) == 1:
            t = tiles[idx[0]]
            region_strokes = [t.transform.to_input(np.floor(p + 0.5)) for p in planned[idx[0]]]
        else:
            # Pieces in the frame of the whole-drawing canvas, where tiles abut.
            base = im.CanvasTransform(scale)
            pieces = []
            for i in idx:
                dx = base.offset[0] - tiles[i].transform.offset[0]
                dy = base.offset[1] - tiles[i].transform.offset[1]
                for p in planned[i]:
                    if len(p):
                        pieces.append((i, (np.floor(p + 0.5) + (dx, dy)).astype(np.int64)))
            region_strokes = [base.to_input(p) for p in stitch(pieces, report)]
        for p in region_strokes:
            if len(p) == 0:
                continue
            p = _snap(p, tree, skel_pts, radius)
            out.append(im.simplify(p, simplify_tol) if len(p) > 2 else p)
    return ImagePlan(
        out,
        prep.shape,
        prep,
        scale,
        tiles,
        regions,
        truncated,
        completed,
        report.get("joins", 0),
        report.get("breaks", 0),
    )


def trace_planner(images, *, checkpoint=None, max_steps=None):
    """A stand-in planner without a model: every skeleton chain is one stroke.

    Same signature and output type as :func:`jdraw.plan`; useful for tests
    and as a baseline.
    """
    from jdraw.types import Plan

    imgs = np.asarray(images)
    if imgs.ndim == 2:
        imgs = imgs[None]
    if imgs.ndim != 3 or imgs.shape[1:] != (CANVAS, CANVAS):
        raise ValueError(f"expected [B, {CANVAS}, {CANVAS}] images, got {imgs.shape}")
    strokes = [[p.astype(np.float64) for p in im.skeleton_polylines(x != 0)] for x in imgs]
    b = len(imgs)
    return Plan(strokes, np.zeros((b, 0, 3), np.int32), np.zeros(b, np.int32), np.zeros(b, bool))
