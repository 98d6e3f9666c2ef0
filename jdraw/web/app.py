"""The web app: the page, and ``POST /api/plan`` that plans an uploaded image.

::

    POST /api/plan                 multipart: image=<file>, and jdraw draw's options
                                   (width-mm=150, preset=servo, ...; jdraw.web.options)
      -> 200 application/json      what `jdraw draw IMAGE --json OUT` writes
    POST /api/plan?format=svg      -> 200 image/svg+xml, as `jdraw draw --svg`
    POST /api/plan?format=gcode    -> 200 text/plain, as `jdraw draw --gcode`
    GET  /api/options              -> the fields, presets and limits, for the page
    GET  /                         -> the page (static/, shipped in the package)

Errors are ``{"error": "one line"}`` with 400 (not an image, a bad option,
nothing to draw), 413 (over the byte or the pixel limit; the pixels are
counted from the header before anything is decoded), 503 (over the time
limit, or the queue is full) or 500 (a bug; the server stays up).
"""

from __future__ import annotations

import contextlib
import dataclasses
import importlib.resources
import logging

from anyio import to_thread
from starlette.applications import Starlette
from starlette.datastructures import UploadFile
from starlette.formparsers import MultiPartException
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from jdraw import validate
from jdraw.images import load
from jdraw.io.gcode import PRESETS
from jdraw.web import options as form_options
from jdraw.web import planning, upload

log = logging.getLogger("jdraw.web")

MEDIA_TYPES = {
    "json": "application/json",
    "svg": "image/svg+xml",
    "gcode": "text/plain; charset=utf-8",
}
# Room for the form's other fields and the multipart boundaries around the image.
_FORM_SLACK = 64 * 1024


@dataclasses.dataclass(frozen=True)
class Limits:
    """What one request may ask of the server.

    Attributes:
      max_bytes: largest image file, bytes (413 above).
      max_pixels: largest image, width x height read from its header (413 above).
      plan_timeout_s: seconds one plan may take once the worker starts it (503 above).
      max_queue: most requests planning or waiting at once (503 above).
    """

    max_bytes: int = 20 * 1000 * 1000
    max_pixels: int = 50 * 1000 * 1000
    plan_timeout_s: float = 120.0
    max_queue: int = 16


class HTTPError(Exception):
    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


def _error(status: int, message: object) -> JSONResponse:
    return JSONResponse({"error": validate.one_line(message)}, status_code=status)


def _static_dir() -> str:
    return str(importlib.resources.files("jdraw.web") / "static")


async def _read_body(request: Request, max_bytes: int) -> bytes:
    """The request body, refused with 413 as soon as it is clearly over ``max_bytes``.

    The body may exceed ``max_bytes`` by the room the form's other fields and the
    multipart boundaries take; the image itself is checked after parsing.
    """
    limit = max_bytes + _FORM_SLACK
    too_big = f"the upload is over the limit of {max_bytes} bytes"
    length = request.headers.get("content-length")
    if length is not None and length.isdigit() and int(length) > limit:
        raise HTTPError(413, f"the upload is {int(length)} bytes; the limit is {max_bytes} bytes")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise HTTPError(413, too_big)
        chunks.append(chunk)
    return b"".join(chunks)


async def _form(request: Request, limits: Limits) -> tuple[bytes, str, dict[str, str]]:
    """``(image bytes, file name, other fields)`` of a multipart request."""
    if not request.headers.get("content-type", "").startswith("multipart/form-data"):
        raise HTTPError(400, "send the image as multipart/form-data in a field named 'image'")
    body = await _read_body(request, limits.max_bytes)
    replay = [{"type": "http.request", "body": body, "more_body": False}]

    async def receive():
        return replay.pop() if replay else {"type": "http.disconnect"}

    try:
        form = await Request(request.scope, receive).form(max_files=1, max_fields=64)
    except MultiPartException as e:
        raise HTTPError(400, f"bad multipart form: {e}") from None
    try:
        fields: dict[str, str] = {}
        image = None
        for key, value in form.multi_items():
            if key == "image":
                if not isinstance(value, UploadFile):
                    raise HTTPError(400, "the 'image' field must be a file")
                image = value
            elif key in fields:
                raise HTTPError(400, f"field {key!r} given twice")
            else:
                fields[key] = value
        if image is None:
            raise HTTPError(400, "no image: send the picture in a file field named 'image'")
        data = await image.read()
        name = image.filename or "image"
    finally:
        await form.close()  # the spooled upload
    if len(data) > limits.max_bytes:
        raise HTTPError(413, f"the image is {len(data)} bytes; the limit is {limits.max_bytes}")
    if not data:
        raise HTTPError(400, "the image file is empty")
    return data, name, fields


def create_app(limits: Limits | None = None, *, warm_up: bool = False) -> Starlette:
    """The Starlette app serving the page and the API.

    Args:
      limits: the request limits (default :class:`Limits`).
      warm_up: load and compile the model when the app starts (the first
        plan then does not wait for it).
    """
    limits = limits or Limits()
    queue = planning.PlanQueue(plan_timeout_s=limits.plan_timeout_s, max_queue=limits.max_queue)

    async def plan(request: Request) -> Response:
        fmt = request.query_params.get("format", "json")
        try:
            if fmt not in planning.FORMATS:
                raise HTTPError(400, f"format must be json, svg or gcode; got {fmt!r}")
            data, name, fields = await _form(request, limits)
            try:
                plan_opts, out_opts = form_options.parse(fields)
                upload.header_size(data, limits.max_pixels)
            except validate.InputError as e:
                raise HTTPError(400, str(e)) from None
            except upload.NotAnImage as e:
                raise HTTPError(400, f"{name}: {e}") from None
            except upload.TooManyPixels as e:
                raise HTTPError(413, f"{name}: {e}") from None
            try:
                result = await queue.plan(data, name, plan_opts)
            except load.BlankImageError as e:
                raise HTTPError(400, f"{name}: {e}; nothing to draw") from None
            except (load.ImageError, validate.InputError) as e:
                raise HTTPError(400, str(e)) from None
            except (planning.PlanTimeout, planning.Busy) as e:
                raise HTTPError(503, str(e)) from None
            try:
                body = await to_thread.run_sync(planning.render, result, fmt, out_opts)
            except (KeyError, ValueError, IndexError) as e:
                raise HTTPError(400, f"bad G-code template or size: {e}") from None
        except HTTPError as e:
            return _error(e.status, e)
        except Exception as e:  # a bug: say so, log it, keep serving
            log.exception("internal error planning an upload")
            return _error(500, f"internal error: {type(e).__name__}: {e}")
        return Response(body, media_type=MEDIA_TYPES[fmt])

    async def api_options(request: Request) -> Response:
        return JSONResponse(
            {
                "fields": list(form_options.FIELDS),
                "presets": sorted(PRESETS),
                "polarities": list(form_options.POLARITIES),
                "limits": dataclasses.asdict(limits),
            }
        )

    async def index(request: Request) -> Response:
        return FileResponse(f"{_static_dir()}/index.html")

    @contextlib.asynccontextmanager
    async def lifespan(app):
        if warm_up:
            queue.warm_up()
        yield
        queue.close()

    app = Starlette(
        routes=[
            Route("/", index),
            Route("/api/plan", plan, methods=["POST"]),
            Route("/api/options", api_options),
            Mount("/static", StaticFiles(directory=_static_dir()), name="static"),
        ],
        lifespan=lifespan,
    )
    app.state.queue = queue
    app.state.limits = limits
    return app
