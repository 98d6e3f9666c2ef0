"""The ``jdraw`` command: ``jdraw draw IMAGE --svg out.svg --gcode out.gcode ...``."""

from __future__ import annotations

import contextlib
import os
import sys
import time
import traceback

from jdraw import validate
from jdraw.cli_options import parser

_parser = parser  # the ``jdraw`` parser (jdraw.cli_options)


def _fail(msg: str) -> int:
    print(f"jdraw: error: {validate.one_line(msg)}", file=sys.stderr)
    return 2


def _check(args, images) -> None:
    """Every option of ``draw``, checked before any work (raises ``InputError``)."""
    from jdraw.io import jobs

    formats = [f for f in jobs.FORMATS if getattr(args, f) is not None]
    if args.out_dir is not None:
        for f in formats:
            if getattr(args, f):
                raise validate.InputError(
                    f"with --out-dir, --{f} names a format only (it writes "
                    f"{args.out_dir}/<image name>.{f}); got --{f} {getattr(args, f)!r}; put the "
                    "images before the output flags"
                )
        for opt in ("trajectory", "robot"):
            if getattr(args, opt):
                raise validate.InputError(f"--{opt} takes one image, not --out-dir")
        if os.path.exists(args.out_dir) and not os.path.isdir(args.out_dir):
            raise validate.InputError(f"--out-dir {args.out_dir!r} is a file, not a folder")
        try:
            jobs.out_dir_files(images, args.out_dir, formats)
        except ValueError as e:
            raise validate.InputError(f"--out-dir: {e}") from e
    else:
        for f in formats:
            if not getattr(args, f):
                raise validate.InputError(f"--{f} needs a file name (or give --out-dir DIR)")
        if len(images) > 1 and (formats or args.trajectory or args.robot):
            raise validate.InputError(
                f"{len(images)} images: give --out-dir DIR and name formats only, "
                "e.g. --out-dir plans --svg --png"
            )
    if not images:
        raise validate.InputError(f"no image files in {' '.join(args.image)}")
    for opt in ("svg", "gcode", "json", "png", "gif", "trajectory"):
        if getattr(args, opt):
            validate.output_path(f"--{opt}", getattr(args, opt))
    validate.positive("--max-mpx", args.max_mpx)
    validate.positive_int("--max-steps", args.max_steps, optional=True)
    validate.positive("--min-gap", args.min_gap)
    validate.positive("--width-mm", args.width_mm, optional=True)
    validate.positive("--height-mm", args.height_mm, optional=True)
    validate.positive("--feed", args.feed, optional=True)
    validate.positive("--travel-feed", args.travel_feed, optional=True)
    validate.finite("--z-up", args.z_up, optional=True)
    validate.finite("--z-down", args.z_down, optional=True)
    for v in args.origin_mm:
        validate.finite("--origin-mm", v)
    for opt in ("pen_up", "pen_down"):
        if getattr(args, opt) is not None:
            validate.gcode_template("--" + opt.replace("_", "-"), getattr(args, opt))
    if not 0 < args.sheet_mm <= 1000:
        raise validate.InputError(f"--sheet-mm must be in (0, 1000], got {args.sheet_mm}")
    if args.checkpoint is not None:
        from jdraw.planner import plan as api

        api.load_model(validate.checkpoint(args.checkpoint))


def _robot():
    """``jdraw.robot``, imported with stray prints sent to stderr.

    Importing MJX prints a notice about its optional Warp backend to stdout,
    and the command's stdout is for results.
    """
    with contextlib.redirect_stdout(sys.stderr):
        from jdraw import robot
    return robot


def _output_options(args) -> dict:
    return dict(
        width_mm=args.width_mm,
        height_mm=args.height_mm,
        preset=args.preset,
        origin_mm=tuple(args.origin_mm),
        feed=args.feed,
        travel_feed=args.travel_feed,
        pen_up=args.pen_up,
        pen_down=args.pen_down,
        z_up=args.z_up,
        z_down=args.z_down,
    )


def _plan_options(args) -> dict:
    return dict(
        checkpoint=args.checkpoint,
        max_steps=args.max_steps,
        polarity=args.polarity,
        min_gap=args.min_gap,
        split=False if args.no_split else None,
        retrace=not args.no_retrace,
        max_pixels=args.max_mpx * 1e6,
        direction=None if args.direction == "auto" else args.direction,
    )


def _say(line: str, write=None) -> None:
    """A line on stdout. Once its reader has gone (``jdraw draw ... | head -3``), the
    rest are dropped and planning goes on: the output files are the job."""
    try:
        (write or print)(line, file=sys.stdout)
        sys.stdout.flush()
    except BrokenPipeError:
        # Point the descriptor at /dev/null, so no later write or flush fails again.
        try:
            null = os.open(os.devnull, os.O_WRONLY)
            os.dup2(null, sys.stdout.fileno())
            os.close(null)
        except (OSError, ValueError):  # no descriptor to point elsewhere
            sys.stdout = open(os.devnull, "w")  # lives as long as the process


def _draw_set(args, images) -> int:
    """Several images (or ``--out-dir``): one stream through the planner, a line per image."""
    from tqdm.auto import tqdm

    from jdraw.images import load
    from jdraw.io import jobs
    from jdraw.tiling import plan_image as tiling

    formats = [f for f in jobs.FORMATS if getattr(args, f) is not None]
    files = [{}] * len(images)
    if args.out_dir is not None:
        os.makedirs(args.out_dir, exist_ok=True)
        files = jobs.out_dir_files(images, args.out_dir, formats)
    failed = 0
    bar = tqdm(
        total=len(images), desc="planning", unit="image", disable=True if args.no_progress else None
    )
    results = tiling.plan_images(
        (str(p) for p in images), progress=False, pixel_flag="--max-mpx", **_plan_options(args)
    )
    t0 = time.perf_counter()
    for path, out, result in zip(images, files, results, strict=True):
        try:
            if isinstance(result, Exception):
                raise result
            stats = jobs.write_plan(result, out, **_output_options(args)).stats
            line = jobs.summary(str(path), result, stats, time.perf_counter() - t0)
            _say(line, tqdm.write)
        except (ValueError, OSError) as e:
            failed += 1
            msg = str(e)
            if isinstance(e, load.BlankImageError):
                msg = f"{path}: {e}; nothing to draw"
            elif str(path) not in msg:
                msg = f"{path}: {msg}"
            tqdm.write(f"jdraw: error: {validate.one_line(msg)}", file=sys.stderr)
        bar.update(1)
        t0 = time.perf_counter()
    bar.close()
    if failed:
        print(f"jdraw: {failed} of {len(images)} image(s) failed", file=sys.stderr)
    return 2 if failed else 0


def _draw(args) -> int:
    from jdraw.images import load
    from jdraw.io import jobs, outputs

    images = jobs.image_files(args.image)
    _check(args, images)
    if args.out_dir is not None or len(images) > 1:
        return _draw_set(args, images)
    files = {k: getattr(args, k) for k in jobs.FORMATS}
    image = str(images[0])
    faults = None
    if args.robot:
        try:
            faults = _robot().Faults.parse(args.faults)
        except ValueError as e:
            raise validate.InputError(str(e)) from e
    t0 = time.perf_counter()
    try:
        # Read (and size-checked) before the planner's imports: a refusal comes at once.
        pixels = load.load_image(image, args.max_mpx * 1e6, "--max-mpx")
        from jdraw.tiling import plan_image as tiling

        result = tiling.plan_image(
            pixels, progress=not args.no_progress, **{**_plan_options(args), "max_pixels": None}
        )
    except load.BlankImageError as e:
        return _fail(f"{image}: {e}; nothing to draw")
    except load.ImageError as e:
        return _fail(str(e))
    shape, strokes = result.shape, result.strokes
    try:
        plot = jobs.write_plan(result, files, **_output_options(args)).stats
    except jobs.OutputError as e:
        return _fail(str(e))
    arm_msg, status = "", 0
    if args.trajectory:
        _robot()
        try:
            report, traj = outputs.write_trajectory(result, args.trajectory, args.sheet_mm)
        except OSError as e:
            return _fail(f"cannot write output: {e}")
        ok = bool(report.reachable[0])
        arm_msg = (
            f"arm: {'reachable' if ok else 'NOT reachable'}, ink IoU vs plan "
            f"{float(report.iou[0]):.3f}, drawing time {float(report.drawing_time_s[0]):.1f} s, "
            f"{len(traj['points'])} trajectory points"
        )
        if not ok:
            status = 1
    if args.robot:
        robot = _robot()
        opts = robot.RobotOptions(sheet_size_mm=(args.sheet_mm, args.sheet_mm))
        res = robot.closed_loop.image_closed_loop(strokes, shape, faults, args.rounds, opts)
        arm_msg = "\n".join(filter(None, [arm_msg, res.summary()]))
    _say(jobs.summary(image, result, plot, time.perf_counter() - t0))
    if arm_msg:
        _say(arm_msg)
    if status:
        print(
            "jdraw: the arm cannot reach every waypoint of this sheet (see jdraw.robot.verify's "
            "`offending`); the trajectory was written but must not be run",
            file=sys.stderr,
        )
    if not any(files.values()) and not args.trajectory and not args.robot:
        print(
            "no output requested: add --svg, --gcode, --json, --png, --gif or --trajectory",
            file=sys.stderr,
        )
    return status


def main(argv: list[str] | None = None) -> int:
    """Runs the command line; returns the exit status (see the help's epilog)."""
    from jdraw.images import load

    args = _parser().parse_args(argv)
    debug = getattr(args, "debug", False)
    try:
        if args.command == "draw":
            return _draw(args)
        if args.command == "serve":
            from jdraw.web import server

            return server.main(args)
        return 2
    except (validate.InputError, load.ImageError) as e:
        if debug:
            traceback.print_exc()
        return _fail(str(e))
    except Exception as e:  # anything else is a bug, but for a bad checkpoint
        if debug:
            traceback.print_exc()
        # Not imported before it is needed (it loads Flax): an error from it means it was.
        bundle = sys.modules.get("jdraw.model.bundle")
        if bundle is not None and isinstance(e, bundle.BundleError):
            return _fail(str(e))
        print(
            f"jdraw: internal error: {type(e).__name__}: {validate.one_line(e)} "
            "(run again with --debug for the traceback)",
            file=sys.stderr,
        )
        return 3


def quick_exit(status: int) -> None:
    """Ends the process with ``status`` at once, once its streams and atexit handlers are done.

    Python's own shutdown then tears JAX's runtime down object by object:
    about 0.2 s on a 2-core CPU, a sixth of a warm ``jdraw draw`` (issue 25).
    Every output file is closed by the time a command returns, so nothing is lost.
    """
    import atexit
    import logging

    atexit._run_exitfuncs()  # what interpreter shutdown would run first (tqdm, logging, ...)
    logging.shutdown()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe: nothing more can be said
            pass
    os._exit(status)


def run() -> None:
    """The ``jdraw`` command: :func:`main`, then :func:`quick_exit` with its status."""
    quick_exit(main())


if __name__ == "__main__":
    run()
