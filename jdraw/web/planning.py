"""Plans for the server: one worker thread, a bounded queue, a time limit and a small cache.

The model is held once in memory and a CPU has few cores, so uploads are
planned one at a time, in arrival order, by a single worker thread; requests
wait for it in a queue of bounded length. The image is decoded in that worker
too, so one decoded picture at a time is in memory. A finished plan is kept
(its strokes only) under the image's hash and the planning options, so asking
for the SVG or the G-code of a plan just made, or for another size or preset,
writes files without planning again.
"""

from __future__ import annotations

import asyncio
import collections
import concurrent.futures
import dataclasses
import hashlib
import os
import tempfile
import threading
import time

from jdraw.io import outputs
from jdraw.tiling import plan_image as tiling
from jdraw.web import upload
from jdraw.web.options import OutputOptions, PlanOptions

FORMATS = ("json", "svg", "gcode")


# The time limit's clock (the tests move it forward instead of sleeping).
_clock = time.monotonic


class Busy(RuntimeError):
    """The queue is full."""


class PlanTimeout(RuntimeError):
    """Planning took longer than the time limit."""


def _timed(planner, deadline: float, limit_s: float):
    """``planner``, raising :class:`PlanTimeout` once the clock passes ``deadline``.

    ``jdraw.plan_image`` calls the planner once per batch of tiles; the
    deadline is checked before and after each call, so planning stops at the
    first batch boundary past the limit.
    """

    def timed(images, **kwargs):
        if _clock() > deadline:
            raise PlanTimeout(f"planning took longer than the limit of {limit_s:g} s")
        out = planner(images, **kwargs)
        if _clock() > deadline:
            raise PlanTimeout(f"planning took longer than the limit of {limit_s:g} s")
        return out

    return timed


class PlanQueue:
    """Plans uploads one at a time in a worker thread.

    Args:
      plan_timeout_s: seconds one plan may take, from when the worker starts it.
      max_queue: most requests planning or waiting at once; more get :class:`Busy`.
      cache_size: plans (their strokes) kept for later requests of the same image.
    """

    def __init__(self, *, plan_timeout_s: float, max_queue: int, cache_size: int = 16):
        self.plan_timeout_s = plan_timeout_s
        self.max_queue = max_queue
        self.cache_size = cache_size
        self._pool = concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="jdraw-plan")
        self._lock = threading.Lock()
        self._pending = 0
        self._cache: collections.OrderedDict = collections.OrderedDict()

    @property
    def pending(self) -> int:
        """Requests planning or waiting now."""
        return self._pending

    def close(self) -> None:
        """Stops the worker once the queued plans are done."""
        self._pool.shutdown(wait=False, cancel_futures=True)

    async def plan(self, data: bytes, name: str, options: PlanOptions) -> tiling.ImagePlan:
        """The plan of an uploaded image (from the cache, or queued for the worker).

        Raises:
          Busy: ``max_queue`` requests are already planning or waiting.
          PlanTimeout: the plan took longer than ``plan_timeout_s``.
          jdraw.images.load.ImageError, jdraw.validate.InputError: a bad image.
        """
        key = (hashlib.sha256(data).hexdigest(), options)
        hit = self._get(key)
        if hit is not None:
            return hit
        with self._lock:
            if self._pending >= self.max_queue:
                raise Busy(f"the server is busy: {self._pending} plans queued; try again")
            self._pending += 1
        try:
            future = self._pool.submit(self._job, key, data, name, options)
        except BaseException:
            self._done(None)
            raise
        # Counted until the worker is done with it, even if the client has gone.
        future.add_done_callback(self._done)
        return await asyncio.wrap_future(future)

    def warm_up(self) -> concurrent.futures.Future:
        """Queues a small plan so the model is loaded and compiled before the first request."""
        import numpy as np

        img = np.full((64, 64), 255, np.uint8)
        img[30:34, 8:56] = 0
        return self._pool.submit(
            tiling.plan_image, img, planner=tiling.default_planner, progress=False
        )

    def _done(self, _future) -> None:
        with self._lock:
            self._pending -= 1

    def _get(self, key):
        with self._lock:
            if key in self._cache:
                self._cache.move_to_end(key)
                return self._cache[key]
        return None

    def _job(self, key, data: bytes, name: str, options: PlanOptions) -> tiling.ImagePlan:
        hit = self._get(key)  # the same image may have been queued twice
        if hit is not None:
            return hit
        limit = self.plan_timeout_s
        deadline = _clock() + limit
        image = upload.decode(data, name)
        planner = _timed(tiling.default_planner, deadline, limit)
        result = tiling.plan_image(
            image,
            planner=planner,
            polarity=options.polarity,
            min_gap=options.min_gap,
            progress=False,
        )
        if _clock() > deadline:
            raise PlanTimeout(f"planning took longer than the limit of {limit:g} s")
        # The files need the strokes and the shape only; the pictures are dropped.
        slim = dataclasses.replace(result, prepared=None, tiles=[])
        with self._lock:
            self._cache[key] = slim
            while len(self._cache) > self.cache_size:
                self._cache.popitem(last=False)
        return slim


def render(plan: tiling.ImagePlan, fmt: str, options: OutputOptions) -> bytes:
    """The file ``jdraw draw --<fmt> OUT`` writes for this plan and these options, as bytes.

    It is written by :func:`jdraw.io.outputs.write_outputs`, as the command
    line writes it, into a temporary folder and read back.

    Raises:
      ValueError, KeyError, IndexError: a bad G-code template or size.
    """
    if fmt not in FORMATS:
        raise ValueError(f"format must be one of {', '.join(FORMATS)}; got {fmt!r}")
    with tempfile.TemporaryDirectory(prefix="jdraw-out-") as folder:
        path = os.path.join(folder, f"plan.{fmt}")
        outputs.write_outputs(plan, **{fmt: path}, **options.as_kwargs())
        with open(path, "rb") as f:
            return f.read()
