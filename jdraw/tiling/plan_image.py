"""Drawings of any size: regions, tiles, planning each and stitching the strokes.

:func:`plan_image` reduces an image to centrelines (:mod:`jdraw.images.image`), picks
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
from scipy.cluster.hierarchy import DisjointSet

from jdraw import geometry as raster
from jdraw.images import image as im

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
      lift_joins: pen lifts inside a tile removed by joining strokes that
        continue each other (``join_lifts``).
      fragments: planned pieces dropped because other strokes draw all their pixels.
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
    lift_joins: int = 0
    fragments: int = 0

    def pen_down_length(self) -> float:
        """Total length drawn, input pixels."""
        return float(sum(np.hypot(*np.diff(s, axis=0).T).sum() for s in self.strokes if len(s) > 1))


# ----------------------------------------------------------------------------- layout


def choose_scale(prep: im.Prepared, min_gap: float = 4.0) -> tuple[float, bool]:
    """Canvas pixels per input pixel, and whether the drawing fits one canvas.

    Centrelines of strokes that do not touch are at least a stroke width
    apart; at ``min_gap / width`` canvas pixels per input pixel they stay
    ``min_gap`` pixels apart, so they do not merge on the canvas. A drawing
    whose ink fits the character extent at ``FIT_SLACK`` of that scale or
    larger is fitted to one canvas like a character (lines then stay at least
    ``FIT_SLACK * min_gap`` apart, as in KanjiVG's densest characters), so the
    model orders all its strokes; otherwise it is tiled at that scale (never
    enlarged, since thin lines are already separable).
    """
    s_min = min(1.0, min_gap / prep.width)
    x0, y0, x1, y1 = im.ink_bbox(prep.polylines)
    s_fit = im.CHAR_EXTENT / max(x1 - x0, y1 - y0, 1.0)
    return (s_fit, True) if s_fit >= FIT_SLACK * s_min else (s_min, False)


FIT_SLACK = 0.7


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


def _outward(path: np.ndarray, end: int, reach: int = 3) -> np.ndarray:
    """Unit direction in which a pixel path leaves through ``end`` (0 first, 1 last)."""
    if len(path) < 2:
        return np.zeros(2)
    k = min(reach, len(path) - 1)
    a, b = (path[k], path[0]) if end == 0 else (path[-1 - k], path[-1])
    d = (b - a).astype(np.float64)
    return d / max(np.hypot(*d), 1e-9)


def _trim_retrace(path: np.ndarray, least: int = 2) -> np.ndarray:
    """Cuts a path's ends where it doubles back over its own pixels.

    A planner that overshoots and comes back ends its stroke in the middle of
    ink it already drew. Pixels drawn again at the end (or drawn first at the
    start and again later) are cut when there are at least ``least`` of them,
    so a closed loop that ends on its first pixel keeps it.
    """
    pix = [(int(x), int(y)) for x, y in path]
    count: dict[tuple[int, int], int] = {}
    for q in pix:
        count[q] = count.get(q, 0) + 1
    hi = len(pix)
    left = dict(count)
    while hi > 1 and left[pix[hi - 1]] > 1:
        left[pix[hi - 1]] -= 1
        hi -= 1
    if len(pix) - hi < least:
        hi = len(pix)
    lo = 0
    left = {q: 0 for q in count}
    for q in pix[:hi]:
        left[q] += 1
    while lo < hi - 1 and left[pix[lo]] > 1:
        left[pix[lo]] -= 1
        lo += 1
    if lo < least:
        lo = 0
    return path[lo:hi]


def _trim_fragments(paths: list[np.ndarray | None], fragment: int) -> int:
    """Trims fragments to the pixels no other path draws.

    A fragment is a path that adds at most ``fragment`` pixels to what the
    other paths draw (a retrace with a pixel or two beyond a stroke's end).
    It is cut to its new pixels in the order first drawn when they form one
    8-connected run, else covered pixels are removed from its ends only, so it
    stays one connected path; a fragment adding nothing is dropped (set to
    ``None``). Fragments adding least go first. Returns the number dropped.
    """
    own = [set(map(tuple, p.tolist())) if p is not None else set() for p in paths]
    count: dict[tuple, int] = {}  # how many paths draw each pixel
    for px in own:
        for q in px:
            count[q] = count.get(q, 0) + 1

    def fresh(i: int) -> list[tuple]:
        """Pixels only path ``i`` draws, in the order it first draws them."""
        return [q for q in dict.fromkeys(map(tuple, paths[i].tolist())) if count[q] == 1]

    adds = {i: len(fresh(i)) for i in range(len(paths)) if paths[i] is not None}
    small = {i: n for i, n in adds.items() if n <= fragment}
    dropped = 0
    for i in sorted(small, key=small.get):
        new = fresh(i)  # others may have been trimmed since
        p = paths[i]
        if not new:
            paths[i] = None
            dropped += 1
        elif np.all(np.abs(np.diff(np.asarray(new), axis=0)) <= 1):
            paths[i] = np.asarray(new, np.int64)  # one 8-connected run of new pixels
        else:
            lo, hi = 0, len(p)
            while count[tuple(p[lo].tolist())] > 1:
                lo += 1
            while count[tuple(p[hi - 1].tolist())] > 1:
                hi -= 1
            paths[i] = p[lo:hi]
        kept = set(map(tuple, paths[i].tolist())) if paths[i] is not None else set()
        for q in own[i] - kept:
            count[q] -= 1
        own[i] = kept
    return dropped


def stitch(
    pieces: Sequence[tuple[int, np.ndarray]],
    report: dict | None = None,
    *,
    smooth_cos: float = -0.5,
    fragment: int = 5,
    reach: int = 2,
) -> list[np.ndarray]:
    """Joins strokes that meet end to end, so that one line is drawn in one motion.

    Args:
      pieces: ``(tile, [n, 2] int (x, y))`` strokes in one shared pixel frame
        (a region's big canvas), in drawing order; consecutive points may be
        up to the planner's move apart.
      report: when given, receives counts (added to what it holds):
        ``joins`` (links across tile borders), ``breaks`` (ends that had an
        8-neighbour across a border but stayed unjoined), ``lift_joins`` (pen
        lifts of one tile removed) and ``fragments`` (pieces dropped because
        other strokes draw all their pixels).
      smooth_cos: two strokes of one tile are joined only where they continue
        each other: the cosine between their outward directions is at most this.
      reach: ends at most this many pixels apart (Chebyshev) may be joined;
        2 is the planner's longest move, and the gap is drawn as a straight step.
      fragment: a piece that adds at most this many pixels to what the others
        draw is a fragment; so is any piece this short.

    Returns:
      The joined strokes as 8-connected pixel paths, ordered by their earliest
      piece; a joined stroke runs in the direction of its earliest piece.

    Two ends are joined when they are at most ``reach`` pixels apart and

    * the pieces lie in different tiles (the tile border cut the stroke), or
    * they lie in one tile, no other stroke passes there (not a junction), and
      the two continue each other smoothly, or one of them is a fragment.
      The planner learned from KanjiVG to lift the pen where a character's
      stroke ends; a long line cut into tiles gets pen lifts at spots such as
      the tops of humps, where no character would end a stroke.

    Where a stroke doubles back over itself at an end, that end is cut back
    to the turn. Fragments (the planner retracing a stroke's end to reach a
    pixel or two beyond it) are then trimmed to the pixels nothing else draws.
    Border joins are made first, then the closest, then the straightest
    continuations; every end is joined at most once.
    """
    paths: list[np.ndarray | None] = [_trim_retrace(raster.polyline_pixels(p)) for _, p in pieces]
    tile_of = [t for t, _ in pieces]
    dropped = _trim_fragments(paths, fragment)
    live = [i for i, p in enumerate(paths) if p is not None and len(p)]
    size = {i: len({(int(x), int(y)) for x, y in paths[i]}) for i in live}

    ends: dict[tuple[int, int], list[tuple[int, int]]] = {}
    inner: dict[tuple[int, int], set[int]] = {}
    for s in live:
        p = paths[s]
        for e in (0, 1):
            q = p[0] if e == 0 else p[-1]
            ends.setdefault((int(q[0]), int(q[1])), []).append((s, e))
        for x, y in p[2 : len(p) - 2]:
            inner.setdefault((int(x), int(y)), set()).add(s)

    def junction(q: tuple[int, int], pair: tuple[int, int]) -> bool:
        x, y = q
        return any(
            inner.get((x + dx, y + dy), set()) - set(pair) for dx in (-1, 0, 1) for dy in (-1, 0, 1)
        )

    candidates = []
    for (x, y), here in ends.items():
        for dx in range(-reach, reach + 1):
            for dy in range(-reach, reach + 1):
                for s2, e2 in ends.get((x + dx, y + dy), ()):
                    for s1, e1 in here:
                        if s1 == s2 or (s1, e1) >= (s2, e2):
                            continue
                        o1, o2 = _outward(paths[s1], e1), _outward(paths[s2], e2)
                        across = tile_of[s1] != tile_of[s2]
                        if not across:
                            tiny = min(size[s1], size[s2]) <= fragment
                            if junction((x, y), (s1, s2)) or junction((x + dx, y + dy), (s1, s2)):
                                continue
                            if not tiny and float(o1 @ o2) > smooth_cos:
                                continue
                        step = np.array([dx, dy], np.float64) / max(np.hypot(dx, dy), 1e-9)
                        score = float(o1 @ step - o2 @ step - o1 @ o2)
                        gap = max(abs(dx), abs(dy))
                        candidates.append((not across, gap, -score, s1, e1, s2, e2))
    candidates.sort()
    link: dict[tuple[int, int], tuple[int, int]] = {}
    lift_joins = 0
    chains = DisjointSet(live)  # links never close a loop

    for same, _, _, s1, e1, s2, e2 in candidates:
        if (s1, e1) in link or (s2, e2) in link or chains.connected(s1, s2):
            continue
        chains.merge(s1, s2)
        link[(s1, e1)] = (s2, e2)
        link[(s2, e2)] = (s1, e1)
        lift_joins += same
    if report is not None:
        had = {(c[3], c[4]) for c in candidates if not c[0] and c[1] <= 1}
        had |= {(c[5], c[6]) for c in candidates if not c[0] and c[1] <= 1}
        report["joins"] = report.get("joins", 0) + len(link) // 2 - lift_joins
        report["breaks"] = report.get("breaks", 0) + len(had - link.keys())
        report["lift_joins"] = report.get("lift_joins", 0) + lift_joins
        report["fragments"] = report.get("fragments", 0) + dropped

    used = dict.fromkeys(live, False)
    out = []
    for seed in live:
        if used[seed]:
            continue
        used[seed] = True
        forward = [paths[seed]]
        at = (seed, 1)
        while at in link:
            s, e = link[at]
            if used[s]:
                break
            used[s] = True
            forward.append(paths[s] if e == 0 else paths[s][::-1])
            at = (s, 1 - e)
        backward = []
        at = (seed, 0)
        while at in link:
            s, e = link[at]
            if used[s]:
                break
            used[s] = True
            backward.append(paths[s] if e == 1 else paths[s][::-1])
            at = (s, 1 - e)
        out.append(raster.polyline_pixels(np.concatenate(backward[::-1] + forward)))
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
    join_lifts: bool = True,
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
      join_lifts: on tiled drawings, also join strokes of one tile that meet
        end to end and continue each other (see :func:`stitch`); strokes that
        meet across a tile border are always joined. A drawing fitted to one
        canvas is drawn exactly as planned.
      progress: show a progress bar (on a terminal) when there are several batches.

    Raises:
      jdraw.images.image.ImageError: unreadable or blank image; jdraw.validate.InputError
        (both ``ValueError``): any other bad argument, named.
    """
    from scipy.spatial import cKDTree
    from tqdm.auto import tqdm

    from jdraw import validate

    if planner is None:
        planner = _default_planner()
        checkpoint = validate.checkpoint(checkpoint)
    max_steps = validate.positive_int("max_steps", max_steps, optional=True)
    validate.choice("polarity", polarity, ("auto", "dark", "light"))
    min_gap = validate.positive("min_gap", min_gap)
    batch_size = validate.positive_int("batch_size", batch_size)
    simplify_tol = validate.positive("simplify_tol", simplify_tol, zero=True)
    if isinstance(image, str | os.PathLike):
        image = im.load_image(image)
    image = validate.any_image(image)
    prep = im.prepare(image, polarity=polarity)
    scale, tiles, regions = layout(prep, min_gap)
    single = choose_scale(prep, min_gap)[1]
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
        if single:
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
            knobs = {} if join_lifts else {"smooth_cos": -2.0, "fragment": 0}
            region_strokes = [base.to_input(p) for p in stitch(pieces, report, **knobs)]
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
        report.get("lift_joins", 0),
        report.get("fragments", 0),
    )


def trace_planner(images, *, checkpoint=None, max_steps=None):
    """A stand-in planner without a model: every skeleton chain is one stroke.

    Same signature and output type as :func:`jdraw.plan`; useful for tests
    and as a baseline.
    """
    from jdraw.plans import Plan

    imgs = np.asarray(images)
    if imgs.ndim == 2:
        imgs = imgs[None]
    if imgs.ndim != 3 or imgs.shape[1:] != (CANVAS, CANVAS):
        raise ValueError(f"expected [B, {CANVAS}, {CANVAS}] images, got {imgs.shape}")
    strokes = [[p.astype(np.float64) for p in im.skeleton_polylines(x != 0)] for x in imgs]
    b = len(imgs)
    return Plan(strokes, np.zeros((b, 0, 3), np.int32), np.zeros(b, np.int32), np.zeros(b, bool))
