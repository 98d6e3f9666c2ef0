"""One image's way through the tiler: laid out, its tiles planned, stitched back.

:func:`jdraw.tiling.plan_image.plan_image` and ``plan_images`` drive these steps;
a :class:`_Job` carries an image between them.
"""

from __future__ import annotations

import collections
import dataclasses
import os
import threading
from collections.abc import Callable

import numpy as np
from scipy.spatial import cKDTree

from jdraw import geometry, validate
from jdraw.images.canvas import CanvasTransform
from jdraw.images.load import check_pixels, load_image
from jdraw.images.prepare import Prepared, prepare
from jdraw.images.skeleton import simplify, skeleton_polylines
from jdraw.tiling.layout import Tile, choose_scale, layout
from jdraw.tiling.marks import marks_after_bodies
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
      crumbs: strokes of a few pixels left by the stitching (most often a tile's
        pixel or two on its border) drawn as part of the stroke they touch.
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
    crumbs: int = 0

    def pen_down_length(self) -> float:
        """Total length drawn, input pixels."""
        return float(sum(np.hypot(*np.diff(s, axis=0).T).sum() for s in self.strokes if len(s) > 1))


def _run_planner(
    planner, images, checkpoint, max_steps, split=None, batch_size=16, direction=None, retrace=None
):
    kwargs = {} if split is None else {"split": split}
    if direction is not None:
        kwargs["direction"] = direction
    if retrace is not None:
        kwargs["retrace"] = retrace
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
    planned: list = dataclasses.field(default_factory=list)  # per tile; None until planned
    truncated: int = 0
    completed: int = 0

    def __post_init__(self):
        self.planned = [None] * len(self.tiles)
        self._left = len(self.tiles)

    @property
    def done(self) -> bool:
        return self._left == 0


def _settings(
    planner,
    checkpoint,
    split,
    max_steps,
    polarity,
    min_gap,
    batch_size,
    simplify_tol,
    direction,
    default,
    retrace=True,
):
    """Checked settings; ``default`` is the planner used when ``planner`` is None."""
    if direction is not None:
        validate.choice("direction", direction, ("ltr", "rtl"))
    if not isinstance(retrace, bool):
        raise validate.InputError(f"retrace must be True or False, got {retrace!r}")
    own = planner is None
    joined_retrace = None
    if own:
        planner = default
        checkpoint = validate.checkpoint(checkpoint)
        joined_retrace = _joined_retrace(checkpoint, split) if retrace else None
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
        own=own,
        retrace=joined_retrace,
    )


def _joined_retrace(checkpoint, split) -> int | None:
    """The ``retrace`` the default planner is asked for in joined-up writing's tiles.

    :data:`jdraw.planner.splits.JOINED_RETRACE` when the plan runs a splitter whose
    own reach back over a line is shorter, else ``None`` (no splitter, none asked for,
    or one that already goes that far).
    """
    from jdraw.planner.plan import splitter_for
    from jdraw.planner.splits import JOINED_RETRACE

    sp = splitter_for(checkpoint, split)
    return JOINED_RETRACE if sp is not None and sp.retrace < JOINED_RETRACE else None


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


_FILL = threading.Lock()  # planner calls may run in threads (:class:`Pipeline`)


def _plan_tiles(pending: list[tuple[_Job, int]], cfg: dict) -> None:
    """Plans ``pending`` tiles (job, tile index; of one or more images) in one planner call.

    Fills each tile's strokes into its job. Tiles of images read right to left
    go in a call of their own, whose ranker orders right to left, and tiles of
    joined-up writing (:attr:`Tile.joined`) in one whose joins may go back over a
    stroke's own line (``cfg["retrace"]``); the default planner only, a custom
    one is called as is.
    """
    own = cfg["own"]
    pending = [(job, i, job.tiles[i]) for job, i in pending]
    retrace = cfg.get("retrace")
    kinds = [(d, j) for d in ("ltr", "rtl") for j in (False, True)]
    groups = [
        [p for p in pending if p[0].direction == d and (p[2].joined and retrace is not None) == j]
        for d, j in kinds
    ]
    results = {}
    for (d, j), group in zip(kinds, groups):
        if not group:
            continue
        strokes, trunc = _run_planner(
            cfg["planner"],
            [t.image for _, _, t in group],
            cfg["checkpoint"],
            cfg["max_steps"],
            cfg["split"],
            cfg["batch_size"],
            "rtl" if d == "rtl" and own else None,
            retrace if j else None,
        )
        for p, s, tr in zip(group, strokes, trunc, strict=True):
            results[id(p[2])] = (s, tr)
    for job, i, t in pending:
        s, tr = results[id(t)]
        s, n = _complete(t.image, [np.asarray(p, np.float64).reshape(-1, 2) for p in s])
        with _FILL:
            job.completed += n
            job.truncated += int(tr)
            job.planned[i] = s
            job._left -= 1


class Pipeline:
    """Planner calls run in worker threads while the caller lays out and stitches images.

    JAX runs a planner call's compiled loop without holding Python's lock, so
    reading and laying out the next images, and stitching finished ones, go
    on beside it; with two workers one call's host-side stages (splitter,
    ranker) also run beside the next call's loop. Calls of a custom planner
    run one at a time. At most ``workers`` calls are in flight: :meth:`submit`
    waits for the oldest beyond that, so memory holds only a few batches.
    The batches and their contents are the caller's, so plans do not depend
    on the threads.
    """

    def __init__(self, cfg: dict, workers: int | None = None):
        from concurrent.futures import ThreadPoolExecutor

        self.cfg = cfg
        self.workers = workers or (2 if cfg["own"] else 1)
        self.pool = ThreadPoolExecutor(self.workers, thread_name_prefix="jdraw-plan")
        self.inflight: collections.deque = collections.deque()
        self.calls = 0

    def submit(self, batch: list[tuple[_Job, int]]) -> None:
        if self.calls == 1:  # the first call loads the models and programs; the rest share them
            self.wait_all()
        self.calls += 1
        self.inflight.append(self.pool.submit(_plan_tiles, batch, self.cfg))
        while len(self.inflight) > self.workers:
            self.inflight.popleft().result()

    def wait_all(self) -> None:
        while self.inflight:
            self.inflight.popleft().result()

    def wait_for(self, job: _Job) -> None:
        """Waits until ``job``'s tiles are planned (each call's error is raised here)."""
        while not job.done and self.inflight:
            self.inflight.popleft().result()

    def close(self) -> None:
        try:
            self.wait_all()
        finally:
            for f in self.inflight:
                f.cancel()
            self.pool.shutdown(wait=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


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
            drawn = planned[idx[0]]
            if job.direction == "rtl":
                drawn = [drawn[k] for k in marks_after_bodies(t.image, drawn)]
            region_strokes = [t.transform.to_input(np.floor(p + 0.5)) for p in drawn]
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
        report.get("crumbs", 0),
    )
