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

import os
from collections.abc import Callable, Iterable, Iterator, Sequence

import numpy as np
from tqdm.auto import tqdm

from jdraw.images.load import MAX_PIXELS
from jdraw.planner.plan import plan as default_planner
from jdraw.tiling.tiles import ImagePlan, Pipeline, _finish, _Job, _lay_out, _settings

Planner = Callable[..., object]


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
    retrace: bool = True,
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
        default_planner,
        retrace,
    )
    items = list(images) if not isinstance(images, Iterator) else images
    total = len(items) if isinstance(items, list) else None
    bar = tqdm(total=total, desc="planning", unit="image", disable=True if not progress else None)
    queue: list[_Job | Exception] = []  # in input order; jobs waiting for tiles
    pending: list[tuple[_Job, int]] = []  # laid-out tiles (job, index) not yet planned

    def ready():
        while queue and (isinstance(queue[0], Exception) or queue[0].done):
            head = queue.pop(0)
            bar.update(1)
            yield (
                head
                if isinstance(head, Exception)
                else _finish(head, cfg["simplify_tol"], join_lifts)
            )

    with Pipeline(cfg) as pipe:  # planner calls run beside the layout of the next images
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
            pending.extend((job, i) for i in range(len(job.tiles)))
            while len(pending) >= cfg["batch_size"]:
                pipe.submit(pending[: cfg["batch_size"]])
                del pending[: cfg["batch_size"]]
            yield from ready()
        if pending:
            pipe.submit(pending)
        while queue:
            if isinstance(queue[0], _Job):
                pipe.wait_for(queue[0])
                if not queue[0].done:  # every tile was submitted: cannot happen
                    raise RuntimeError("a job's tiles were never planned")
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
    retrace: bool = True,
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
      min_gap: canvas pixels kept between the centrelines of separate strokes
        (joined-up writing is drawn no larger than the planner learned it, and
        its lines may come closer: :func:`jdraw.tiling.layout.joined_scale`).
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
      retrace: in joined-up writing (a region much wider than its line's
        x-height: a cursive word, a joined Arabic piece;
        :func:`jdraw.tiling.layout.joined_pieces`) let the splitter's joins go
        back over a stroke's own line, as the writer goes back up a stem
        (``jdraw.plan``'s ``retrace=``, :data:`jdraw.planner.splits.JOINED_RETRACE`
        moves): fewer pen lifts, some lines drawn twice. ``False``: never there
        (for a pen that blots where it passes twice). Only with the default planner.

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
        retrace=retrace,
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
        default_planner,
        retrace,
    )
    job = _lay_out(image, cfg["polarity"], cfg["min_gap"], max_pixels, direction=cfg["direction"])
    batches = range(0, len(job.tiles), cfg["batch_size"])
    bar = tqdm(
        total=len(job.tiles),
        desc="planning",
        unit="tile",
        disable=True if not progress or len(batches) < 2 else None,
    )
    with Pipeline(cfg) as pipe:
        for start in batches:
            chunk = range(start, min(start + cfg["batch_size"], len(job.tiles)))
            pipe.submit([(job, i) for i in chunk])
            bar.n = len(job.tiles) - job._left
            bar.refresh()
    bar.n = len(job.tiles)
    bar.close()
    return _finish(job, cfg["simplify_tol"], join_lifts)
