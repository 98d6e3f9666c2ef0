"""The ``jdraw`` command's options: ``jdraw draw`` and ``jdraw serve``, with their help."""

from __future__ import annotations

import argparse

from jdraw.io.gcode import PRESETS

_DESCRIPTION = """\
Plan how to draw a picture with a pen: a photo or scan of handwriting, a
word, a sentence or a line drawing of any size. The image is binarised
(either ink polarity, uneven lighting), thinned to centrelines, split into
character-sized regions or tiles, planned stroke by stroke with the learned
model, and written out in the image's own pixel coordinates. The model plans
on 100x100-pixel canvases, "tiles": a small drawing is fitted to one tile;
a bigger one is scaled so its lines stay apart (joined-up writing no larger
than the model learned it), each connected piece of ink
gets a tile, pieces bigger than a tile are cut into a grid of 100x100 tiles,
and strokes crossing a tile border are joined again.
"""

_EPILOG = """\
examples:
  jdraw draw hello.jpg --svg hello.svg --png hello_strokes.png
  jdraw draw sketch.png --gcode sketch.gcode --preset servo --width-mm 150 --feed 2000
  jdraw draw board.jpg --polarity light --json board.json
  jdraw draw word.png --trajectory word_arm.json --sheet-mm 120

  jdraw draw scans/ --out-dir plans --svg --gcode    # every image in scans/, one run

exit status:
  0  success
  1  --trajectory finds the sheet out of the arm's reach (the file is written)
  2  user error: a bad option, an unusable image (missing, unreadable,
     unsupported, blank, too many pixels) or checkpoint; one line on stderr
     (--debug: traceback). With several images, each bad one gets its own
     line, the others are planned, and the status is 2 if any failed.
  3  internal error (a bug: please report it with the --debug traceback)
All options are checked before planning starts.

compilation cache: the first run on a machine compiles the planner (tens of
seconds); compiled programs are kept in $XDG_CACHE_HOME/jdraw (default
~/.cache/jdraw) so later runs start in seconds. JDRAW_CACHE_DIR=DIR moves it,
JDRAW_CACHE_DIR=off turns it off.
"""


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="jdraw",
        description=_DESCRIPTION,
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    d = sub.add_parser(
        "draw",
        help="plan the strokes for an image; write SVG, G-code, JSON, PNG or an arm trajectory",
        description=_DESCRIPTION,
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    d.add_argument(
        "image",
        metavar="IMAGE",
        nargs="+",
        help="input image: PNG, JPEG, GIF (first frame), BMP, TIFF, WebP, PBM/PGM/PPM; or "
        "several, or folders of them, planned in one run (outputs need --out-dir)",
    )
    out = d.add_argument_group(
        "outputs (any combination; with none, only a summary is printed). With --out-dir "
        "each flag names only a format: --svg --png writes DIR/<image name>.svg and .png"
    )
    out.add_argument(
        "--out-dir",
        metavar="DIR",
        help="write each image's outputs to DIR/<image name>.<format> (made if missing); "
        "needed for several images",
    )
    out.add_argument(
        "--svg",
        metavar="OUT",
        nargs="?",
        const="",
        help="SVG, one polyline per stroke in drawing order, viewBox = image pixels",
    )
    out.add_argument(
        "--gcode",
        metavar="OUT",
        nargs="?",
        const="",
        help="G-code for a pen plotter, millimetres (see --preset)",
    )
    out.add_argument(
        "--json",
        metavar="OUT",
        nargs="?",
        const="",
        help="JSON with the strokes and the pen-up moves between them",
    )
    out.add_argument(
        "--png",
        metavar="OUT",
        nargs="?",
        const="",
        help="PNG of the strokes coloured by order (blue first, red last), starts dotted; "
        "cropped to the ink",
    )
    out.add_argument(
        "--gif",
        metavar="OUT",
        nargs="?",
        const="",
        help="animated GIF of the plan being drawn at pen speed: the current stroke black, "
        "pen-up moves faint, the input light grey behind; cropped to the ink",
    )
    out.add_argument(
        "--trajectory",
        metavar="OUT",
        help="JSON joint trajectory (shaped like ROS trajectory_msgs/JointTrajectory) of "
        "the simulated 7-DoF arm drawing the strokes on a --sheet-mm sheet; the arm is "
        "rolled out in MuJoCo MJX to check reach and ink (adds ~30 s of compiling; one image)",
    )

    im = d.add_argument_group("image")
    im.add_argument(
        "--polarity",
        choices=("auto", "dark", "light"),
        default="auto",
        help="ink darker (dark) or lighter (light, e.g. chalk) than the ground; default: detect",
    )
    im.add_argument(
        "--min-gap",
        type=float,
        default=4.0,
        metavar="PX",
        help="planner-canvas pixels kept between separate lines when scaling down (default: 4)",
    )
    im.add_argument(
        "--max-mpx",
        type=float,
        default=100.0,
        metavar="MPX",
        help="refuse images of more megapixels, read from the file header before decoding "
        "(default: 100; planning needs about 30 bytes of memory per pixel)",
    )

    pl = d.add_argument_group("planner")
    pl.add_argument(
        "--checkpoint",
        metavar="PATH",
        help="model bundle or training workdir (default: the bundled model)",
    )
    pl.add_argument(
        "--max-steps",
        type=int,
        metavar="N",
        help="action limit (pen moves and lifts) per 100x100 tile; a tile that hits it is "
        "finished by tracing its skeleton (default: 1024)",
    )
    pl.add_argument(
        "--no-split",
        action="store_true",
        help="keep the strokes as the local model traced them: no learned cutting at corners "
        "and joining of ends (trained on kanji, it may cut a Latin e at its bar)",
    )
    pl.add_argument(
        "--no-retrace",
        action="store_true",
        help="in joined-up writing (a cursive word, a joined Arabic piece) never go back over "
        "a drawn line to save a pen lift, as the writer would (for a pen that blots where it "
        "passes twice)",
    )
    pl.add_argument(
        "--direction",
        choices=("auto", "ltr", "rtl"),
        default="auto",
        help="reading direction: rtl (Hebrew, Arabic script) orders letters and strokes right "
        "to left; default: read from the image",
    )
    pl.add_argument("--no-progress", action="store_true", help="no progress bar")
    pl.add_argument("--debug", action="store_true", help="on an error, show the Python traceback")

    sz = d.add_argument_group("physical size (SVG and G-code)")
    sz.add_argument(
        "--width-mm",
        type=float,
        metavar="MM",
        help="drawing width in mm (SVG: default pixels; G-code: default 100)",
    )
    sz.add_argument(
        "--height-mm",
        type=float,
        metavar="MM",
        help="drawing height in mm; with --width-mm the drawing fits inside both",
    )

    rb = d.add_argument_group("robot (--trajectory, --robot)")
    rb.add_argument(
        "--sheet-mm",
        type=float,
        default=100.0,
        metavar="MM",
        help="side of the square sheet in front of the arm; the drawing spans 90%% of it "
        "(default 100, the arm's comfortable reach; 1 mm per canvas pixel)",
    )
    rb.add_argument(
        "--robot",
        action="store_true",
        help="draw with the simulated arm, look at the sheet and redraw what is missing; "
        "prints the IoU with the target after each round",
    )
    rb.add_argument(
        "--faults",
        metavar="SPEC",
        help="robot errors for --robot: 'moderate' and/or name=value,... e.g. "
        "'pen_skip_per_mm=0.02,sheet_offset_mm=3:-2' (jdraw.robot.Faults; default none)",
    )
    rb.add_argument("--rounds", type=int, default=2, help="most redraw rounds (default 2)")

    gc = d.add_argument_group("G-code")
    gc.add_argument(
        "--preset",
        choices=sorted(PRESETS),
        default="zaxis",
        help="pen lift: zaxis (G0 Z5 / G1 Z0), servo (M3 S90 down, M5 up, with a dwell), "
        "servo-s (M3 S90 down, M3 S30 up); default: zaxis",
    )
    gc.add_argument(
        "--feed", type=float, metavar="MM/MIN", help="drawing feed rate (default: 1500)"
    )
    gc.add_argument(
        "--travel-feed",
        type=float,
        metavar="MM/MIN",
        help="pen-up moves as G1 at this feed (default: G0 rapid moves)",
    )
    gc.add_argument(
        "--pen-up",
        metavar="GCODE",
        help=r"pen-up template replacing the preset's, lines separated by \n; fields like {z_up}",
    )
    gc.add_argument(
        "--pen-down",
        metavar="GCODE",
        help=r"pen-down template replacing the preset's, e.g. 'M3 S40\nG4 P0.2'",
    )
    gc.add_argument(
        "--z-up", type=float, metavar="MM", help="zaxis preset: pen-up height (default: 5)"
    )
    gc.add_argument(
        "--z-down", type=float, metavar="MM", help="zaxis preset: pen-down height (default: 0)"
    )
    gc.add_argument(
        "--origin-mm",
        type=float,
        nargs=2,
        default=(0.0, 0.0),
        metavar=("X", "Y"),
        help="machine position of the drawing's bottom-left corner (default: 0 0)",
    )
    from jdraw.web import server  # `jdraw serve`; imports the web stack only when it runs

    server.add_parser(sub)
    return p
