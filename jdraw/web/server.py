"""``jdraw serve``: the page and the API on this machine (uvicorn, one process).

Its flags are added to the ``jdraw`` command by :func:`add_parser`; nothing
here imports the web stack until the command runs, so ``jdraw draw`` works
without the ``[web]`` extra.
"""

from __future__ import annotations

import argparse
import ipaddress
import sys

from jdraw import validate

_HELP = "serve a page to draw or drop an image, watch its plan and download it (needs [web])"
_DESCRIPTION = """\
Serve jdraw in a browser: draw with the mouse, a pen or a finger, or drop an
image; watch the plan drawn at pen speed; download the SVG, G-code and JSON
that `jdraw draw` writes for the same image and options. The API is
POST /api/plan (docs/web.md). Plans are made one at a time by the bundled
model; the first one waits for the model to compile (about 30 s on 2 cores).
Needs the web extra: pip install 'jdraw[web]'.
"""


def add_parser(sub) -> argparse.ArgumentParser:
    """Adds the ``serve`` command to the ``jdraw`` command's subparsers."""
    s = sub.add_parser(
        "serve",
        help=_HELP,
        description=_DESCRIPTION,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    s.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to listen on (default 127.0.0.1: this machine only; 0.0.0.0 opens it "
        "to the network, with no authentication)",
    )
    s.add_argument("--port", type=int, default=8765, help="port (default 8765)")
    s.add_argument(
        "--max-mb",
        type=float,
        default=20.0,
        metavar="MB",
        help="largest image file accepted, megabytes (default 20; 413 above)",
    )
    s.add_argument(
        "--max-mpx",
        type=float,
        default=50.0,
        metavar="MPX",
        help="largest image accepted, megapixels, read from the header before decoding "
        "(default 50, at most 178; 413 above)",
    )
    s.add_argument(
        "--plan-timeout",
        type=float,
        default=120.0,
        metavar="S",
        help="seconds one plan may take once started (default 120; 503 above)",
    )
    s.add_argument(
        "--max-queue",
        type=int,
        default=16,
        metavar="N",
        help="most requests planning or waiting at once (default 16; 503 above)",
    )
    s.add_argument(
        "--no-warm-up",
        action="store_true",
        help="do not compile the model at start (the first plan then takes ~30 s longer)",
    )
    s.add_argument("--debug", action="store_true", help="on an error, show the Python traceback")
    return s


def limits_from(args):
    """The :class:`jdraw.web.app.Limits` the flags ask for (checked)."""
    from jdraw.web.app import Limits

    if not 0 < args.port < 65536:
        raise validate.InputError(f"--port must be in 1..65535, got {args.port}")
    max_mb = validate.positive("--max-mb", args.max_mb)
    max_mpx = validate.positive("--max-mpx", args.max_mpx)
    from PIL import Image

    # Pillow refuses headers over twice its MAX_IMAGE_PIXELS (about 179 Mpx) outright.
    guard = 2 * Image.MAX_IMAGE_PIXELS / 1e6
    if max_mpx > guard:
        raise validate.InputError(f"--max-mpx must be at most {guard:.0f}, got {args.max_mpx}")
    return Limits(
        max_bytes=int(max_mb * 1e6),
        max_pixels=int(max_mpx * 1e6),
        plan_timeout_s=validate.positive("--plan-timeout", args.plan_timeout),
        max_queue=validate.positive_int("--max-queue", args.max_queue),
    )


def _loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def main(args) -> int:
    """Runs ``jdraw serve`` until interrupted; returns the exit status."""
    try:
        import uvicorn

        from jdraw.web.app import create_app
    except ImportError as e:
        print(
            f"jdraw: error: jdraw serve needs the web extra ({e.name} is missing): "
            "pip install 'jdraw[web]'",
            file=sys.stderr,
        )
        return 2
    limits = limits_from(args)
    if not _loopback(args.host):
        print(
            f"jdraw: warning: listening on {args.host}: anyone who can reach this machine "
            "can use the planner",
            file=sys.stderr,
        )
    app = create_app(limits, warm_up=not args.no_warm_up)
    shown = f"[{args.host}]" if ":" in args.host else args.host
    print(f"jdraw: serving http://{shown}:{args.port}/ (Ctrl-C stops)", file=sys.stderr)
    if not args.no_warm_up:
        print(
            "jdraw: the model compiles in the background (about 30 s); plans wait for it",
            file=sys.stderr,
        )
    uvicorn.run(app, host=args.host, port=args.port, workers=1, log_level="warning")
    return 0
