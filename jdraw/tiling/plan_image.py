"""Drawings of any size: regions, tiles, planning each and stitching the strokes.

:func:`plan_image` reduces an image to centrelines (:mod:`jdraw.images.prepare`), picks
the canvas scale (canvas pixels per input pixel) at which lines stay
separable, and then either

* fits the whole drawing to one ``100 x 100`` canvas, as for a character, or
* draws the centrelines on one large canvas at that scale, splits it into
  connected regions (a cursive word, a printed letter, a sketch), lays every
  region that is wider or taller than a canvas out as a grid of canvas-sized
  tiles (:mod:`jdraw.tiling.layout`), plans every region or tile, and joins
  strokes that leave one tile where a stroke of the next tile starts
  (:mod:`jdraw.tiling.stitch`), so one stroke stays one motion.

Regions are drawn in reading order: lines of text top to bottom, and along a
line left to right, or right to left where the image reads so
(:mod:`jdraw.images.reading`); a dot or mark comes right after the letter
body it sits over or under. Planned points are mapped back to input pixels and
snapped onto the skeleton, so strokes lie on the ink's centreline.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterable, Iterator, Sequence

import numpy as np
from scipy.spatial import cKDTree
from tqdm.auto import tqdm

from jdraw import geometry, validate
from jdraw.images.canvas import CanvasTransform
from jdraw.images.load import MAX_PIXELS, check_pixels, load_image
from jdraw.images.prepare import Prepared, prepare
from jdraw.images.skeleton import simplify, skeleton_polylines
from jdraw.planner.plan import plan as default_planner
from jdraw.tiling.layout import Tile, choose_scale, layout
from jdraw.tiling.stitch import stitch

CANVAS = geometry.CANVAS
Planner = Callable[..., object]


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
      direction: ``"ltr"`` or ``"rtl"``, the reading direction planned in.
    """

    strokes: list[np.ndarray]
    shape: tuple[int, int]
    prepared: Prepared
    scale: float
    tiles: list[Tile]
    regions: list[tuple[float, float, float, float]]
    truncated: int = 0
    completed_pixels: int = 0
    border_joins: int = 0
    border_breaks: int = 0
    lift_joins: int = 0
    fragments: int = 0
    direction: str = "ltr"

    def pen_down_length(self) -> float:
        """Total length drawn, input pixels."""
        return float(sum(np.hypot(*np.diff(s, axis=0).T).sum() for s in self.strokes if len(s) > 1))


def _run_planner(planner, images, checkpoint, max_steps, split=None, batch_size=16, direction=None):
    kwargs = {} if split is None else {"split": split}
    if direction is not None:
        kwargs["direction"] = direction
    if checkpoint is not None:
        kwargs["checkpoint"] = checkpoint
    if max_steps is not None:
        kwargs["max_steps"] = max_steps
    n = len(images)
    # Two batch shapes only, so a jitted planner compiles at most two programs for any
    # mix of drawings: one tile (a character, the small one-slot program) or a full batch
    # (every tiled drawing and every set of images share it).
    size = 1 if n == 1 else max(n, 1 << (batch_size - 1).bit_length())
    batch = np.zeros((size, CANVAS, CANVAS), bool)
    batch[:n] = np.stack(images)
    plan = planner(batch, **kwargs)
    return plan.strokes[:n], np.asarray(plan.truncated, bool).reshape(-1)[:n]


def _complete(tile: np.ndarray, strokes: list[np.ndarray]) -> tuple[list[np.ndarray], int]:
    """Appends skeleton-traced strokes for ink a (truncated) plan left undrawn."""
    left = tile & ~geometry.render_strokes(strokes, tile.shape)
    if not left.any():
        return strokes, 0
    return strokes + [p.astype(np.float64) for p in skeleton_polylines(left)], int(left.sum())


def _snap(points: np.ndarray, tree, skel_pts: np.ndarray, radius: float) -> np.ndarray:
    d, i = tree.query(points, distance_upper_bound=radius)
    ok = np.isfinite(d)
    out = points.copy()
    out[ok] = skel_pts[i[ok]]
    keep = np.ones(len(out), bool)
    keep[1:] = np.any(out[1:] != out[:-1], axis=1)
    return out[keep]


@dataclasses.dataclass
class _Job:
    """One image between layout and stitching: its tiles and, once planned, their strokes."""

    prep: Prepared
    scale: float
    tiles: list[Tile]
    regions: list
    single: bool
    direction: str = "ltr"
    planned: list = dataclasses.field(default_factory=list)
    truncated: int = 0
    completed: int = 0

    @property
    def done(self) -> bool:
        return len(self.planned) == len(self.tiles)


def _settings(
    planner, checkpoint, split, max_steps, polarity, min_gap, batch_size, simplify_tol, direction
):
    if direction is not None:
        validate.choice("direction", direction, ("ltr", "rtl"))
    if planner is None:
        planner = default_planner
        checkpoint = validate.checkpoint(checkpoint)
    elif split is not None:
        raise validate.InputError("split= is jdraw.plan's option; give it to your planner")
    return dict(
        planner=planner,
        checkpoint=checkpoint,
        split=split,
        max_steps=validate.positive_int("max_steps", max_steps, optional=True),
        polarity=validate.choice("polarity", polarity, ("auto", "dark", "light")),
        min_gap=validate.positive("min_gap", min_gap),
        batch_size=validate.positive_int("batch_size", batch_size),
        simplify_tol=validate.positive("simplify_tol", simplify_tol, zero=True),
        direction=direction,
    )


def _lay_out(
    image, polarity: str, min_gap: float, max_pixels, flag="max_pixels=", direction=None
) -> _Job:
    if isinstance(image, str | os.PathLike):
        image = validate.any_image(load_image(image, max_pixels, flag))
    else:
        image = validate.any_image(image)
        h, w = image.shape[:2]
        check_pixels((w, h), max_pixels, f"image of shape {image.shape}")
    prep = prepare(image, polarity=polarity)
    if direction is None:
        from jdraw.images import reading

        direction = reading.detect(prep)
    scale, tiles, regions = layout(prep, min_gap, rtl=direction == "rtl")
    return _Job(prep, scale, tiles, regions, choose_scale(prep, min_gap)[1], direction)


def _plan_tiles(pending: list[tuple[_Job, Tile]], cfg: dict) -> None:
    """Plans ``pending`` tiles (of one or more images) in one planner call; fills their jobs.

    Tiles of images read right to left go in a call of their own, whose ranker
    orders right to left (the default planner only; a custom one is left as is).
    """
    own = cfg["planner"] is default_planner
    groups = [[p for p in pending if p[0].direction == d] for d in ("ltr", "rtl")]
    results = {}
    for d, group in zip(("ltr", "rtl"), groups):
        if not group:
            continue
        strokes, trunc = _run_planner(
            cfg["planner"],
            [t.image for _, t in group],
            cfg["checkpoint"],
            cfg["max_steps"],
            cfg["split"],
            cfg["batch_size"],
            "rtl" if d == "rtl" and own else None,
        )
        for p, s, tr in zip(group, strokes, trunc, strict=True):
            results[id(p[1])] = (s, tr)
    for job, t in pending:
        s, tr = results[id(t)]
        s, n = _complete(t.image, [np.asarray(p, np.float64).reshape(-1, 2) for p in s])
        job.completed += n
        job.truncated += int(tr)
        job.planned.append(s)


def _finish(job: _Job, simplify_tol: float, join_lifts: bool) -> ImagePlan:
    """Stitches a planned job's tiles and maps the strokes back onto the input's centrelines."""
    prep, scale, tiles, regions, planned = job.prep, job.scale, job.tiles, job.regions, job.planned
    skel_pts = np.argwhere(prep.skeleton)[:, ::-1].astype(np.float64)
    tree = cKDTree(skel_pts)
    radius = 0.75 / scale + 1.0
    out: list[np.ndarray] = []
    report: dict = {}
    for r in range(len(regions)):
        idx = [i for i, t in enumerate(tiles) if t.region == r]
        if job.single:
            t = tiles[idx[0]]
            region_strokes = [t.transform.to_input(np.floor(p + 0.5)) for p in planned[idx[0]]]
        else:
            # Pieces in the frame of the whole-drawing canvas, where tiles abut.
            base = CanvasTransform(scale)
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
            out.append(simplify(p, simplify_tol) if len(p) > 2 else p)
    return ImagePlan(
        out,
        prep.shape,
        prep,
        scale,
        tiles,
        regions,
        job.truncated,
        job.completed,
        report.get("joins", 0),
        report.get("breaks", 0),
        report.get("lift_joins", 0),
        report.get("fragments", 0),
        job.direction,
    )


def plan_images(
    images: Iterable,
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
    split: bool | None = None,
    max_pixels: float | None = MAX_PIXELS,
    pixel_flag: str = "max_pixels=",
    direction: str | None = None,
) -> Iterator[ImagePlan | Exception]:
    """Plans many images in one stream: each image's plan (or its error), in input order.

    The tiles of consecutive images share planner batches, so a folder of
    small drawings costs a few planner calls, not one per image. Images are
    read and laid out one by one as the batches need them, and each plan is
    yielded as soon as its last tile is planned, so memory holds only the
    images in flight. An image that cannot be used (:class:`jdraw.images.load.ImageError`,
    a ``ValueError``) is yielded as that exception and the others go on.

    Args:
      images: an iterable of what :func:`plan_image` takes (arrays or paths).
      progress: one progress bar over the images (on a terminal).
      pixel_flag: how a too-large image's message names the limit's setting
        (``"--max-mpx"`` on the command line).
      others: as :func:`plan_image`.

    Yields:
      :class:`ImagePlan` or the ``ImageError``/``ValueError`` of each image, in order.
    """
    cfg = _settings(
        planner,
        checkpoint,
        split,
        max_steps,
        polarity,
        min_gap,
        batch_size,
        simplify_tol,
        direction,
    )
    items = list(images) if not isinstance(images, Iterator) else images
    total = len(items) if isinstance(items, list) else None
    bar = tqdm(total=total, desc="planning", unit="image", disable=True if not progress else None)
    queue: list[_Job | Exception] = []  # in input order; jobs waiting for tiles
    pending: list[tuple[_Job, Tile]] = []  # laid-out tiles not yet planned

    def ready():
        while queue and (isinstance(queue[0], Exception) or queue[0].done):
            head = queue.pop(0)
            bar.update(1)
            yield (
                head
                if isinstance(head, Exception)
                else _finish(head, cfg["simplify_tol"], join_lifts)
            )

    for image in items:
        try:
            job = _lay_out(
                image, cfg["polarity"], cfg["min_gap"], max_pixels, pixel_flag, cfg["direction"]
            )
        except ValueError as e:  # ImageError, InputError: this image only
            queue.append(e)
            yield from ready()
            continue
        queue.append(job)
        pending.extend((job, t) for t in job.tiles)
        while len(pending) >= cfg["batch_size"]:
            _plan_tiles(pending[: cfg["batch_size"]], cfg)
            del pending[: cfg["batch_size"]]
            yield from ready()
        yield from ready()
    if pending:
        _plan_tiles(pending, cfg)
    yield from ready()
    bar.close()


def plan_image(
    image: np.ndarray | str | os.PathLike | Sequence,
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
    split: bool | None = None,
    max_pixels: float | None = MAX_PIXELS,
    direction: str | None = None,
) -> ImagePlan | list[ImagePlan]:
    """Plans how to draw an image of any size; strokes in input pixel coordinates.

    Args:
      image: ``[H, W]``, ``[H, W, 3]`` (RGB) or ``[H, W, 4]`` of any dtype, or
        an image file's path; a photo, a scan or a clean bitmap, either ink
        polarity. Or a list (tuple) of those: their tiles are planned together
        (:func:`plan_images`) and a list of plans is returned, the same plans
        as planning each alone.
      planner: ``planner(images [B, 100, 100] bool, *, checkpoint, max_steps)
        -> jdraw.Plan``; default :func:`jdraw.plan`.
      checkpoint, max_steps: passed to the planner when given.
      polarity: ``"auto"``, ``"dark"`` or ``"light"`` ink.
      min_gap: canvas pixels kept between the centrelines of separate strokes.
      batch_size: most tiles per planner call; a call of several tiles is padded
        to this (rounded up to a power of two), so a jitted planner compiles for
        two shapes only: one tile and a full batch.
      simplify_tol: input pixels a simplified stroke may stray from the plan.
      join_lifts: on tiled drawings, also join strokes of one tile that meet
        end to end and continue each other (see :func:`stitch`); strokes that
        meet across a tile border are always joined. A drawing fitted to one
        canvas is drawn exactly as planned.
      progress: show a progress bar (on a terminal) when there are several batches
        (for a list: one bar over its images).
      split: passed to :func:`jdraw.plan` (``False``: no learned cutting and
        joining of strokes; ``None``: as the checkpoint says). Only with the
        default planner.
      max_pixels: refuse an image with more pixels (for a file, read from its
        header before decoding); ``None``: no limit. Planning needs about 30
        bytes of memory per input pixel.
      direction: ``"ltr"``, ``"rtl"`` (right-to-left script: regions along a
        line and the strokes of a tile ordered right to left, the latter only
        with the default planner) or ``None``: read from each image
        (:func:`jdraw.images.reading.detect`).

    Raises:
      jdraw.images.load.ImageError: unreadable, blank or too big
        (``TooLargeError``) image; jdraw.validate.InputError (both ``ValueError``):
        any other bad argument, named. For a list, the first image's error.
    """
    kwargs = dict(
        planner=planner,
        checkpoint=checkpoint,
        max_steps=max_steps,
        polarity=polarity,
        min_gap=min_gap,
        batch_size=batch_size,
        simplify_tol=simplify_tol,
        join_lifts=join_lifts,
        split=split,
        max_pixels=max_pixels,
        direction=direction,
    )
    if isinstance(image, list | tuple):
        plans = []
        for r in plan_images(image, progress=progress, **kwargs):
            if isinstance(r, Exception):
                raise r
            plans.append(r)
        return plans
    cfg = _settings(
        planner,
        checkpoint,
        split,
        max_steps,
        polarity,
        min_gap,
        batch_size,
        simplify_tol,
        direction,
    )
    job = _lay_out(image, cfg["polarity"], cfg["min_gap"], max_pixels, direction=cfg["direction"])
    batches = range(0, len(job.tiles), cfg["batch_size"])
    bar = tqdm(
        total=len(job.tiles),
        desc="planning",
        unit="tile",
        disable=True if not progress or len(batches) < 2 else None,
    )
    for start in batches:
        chunk = job.tiles[start : start + cfg["batch_size"]]
        _plan_tiles([(job, t) for t in chunk], cfg)
        bar.update(len(chunk))
    bar.close()
    return _finish(job, cfg["simplify_tol"], join_lifts)
