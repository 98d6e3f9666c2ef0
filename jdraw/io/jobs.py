"""Drawing jobs: which images a command names, where their outputs go, one plan written.

Shared by ``jdraw draw`` and anything else that plans files and writes
their outputs (a web server, a script): :func:`image_files` expands folders,
:func:`out_dir_files` names each image's outputs in an output folder, and
:func:`write_plan` writes one plan's files and returns the summary line.
"""

from __future__ import annotations

import os
import pathlib
from collections.abc import Sequence
from typing import TYPE_CHECKING

from jdraw.io import outputs

if TYPE_CHECKING:
    from jdraw.tiling.plan_image import ImagePlan

FORMATS = ("svg", "gcode", "json", "png", "gif")
IMAGE_SUFFIXES = (
    ".png", ".jpg", ".jpeg", ".gif", ".bmp", ".tif", ".tiff", ".webp", ".pbm", ".pgm", ".ppm",
)  # fmt: skip


class OutputError(ValueError):
    """An output that cannot be written (bad G-code template or size, unwritable file)."""


def image_files(args: Sequence[str | os.PathLike]) -> list[pathlib.Path]:
    """The images ``args`` name: files as given, folders as their image files sorted by name.

    A folder contributes the files directly in it whose suffix is an image
    format's (:data:`IMAGE_SUFFIXES`, any case); other paths are kept as
    given, so a missing or unreadable file is reported when it is read.
    """
    out: list[pathlib.Path] = []
    for a in args:
        p = pathlib.Path(a)
        if p.is_dir():
            out.extend(
                sorted(f for f in p.iterdir() if f.suffix.lower() in IMAGE_SUFFIXES and f.is_file())
            )
        else:
            out.append(p)
    return out


def out_dir_files(
    images: Sequence[pathlib.Path], out_dir: str | os.PathLike, formats: Sequence[str]
) -> list[dict[str, pathlib.Path]]:
    """``{format: DIR/<image stem>.<format>}`` for each image.

    Raises:
      ValueError: two images with one stem (``a.png`` and ``a.jpg``) would write
        the same files.
    """
    d = pathlib.Path(out_dir)
    seen: dict[str, pathlib.Path] = {}
    for p in images:
        if p.stem in seen and seen[p.stem] != p:
            raise ValueError(f"{seen[p.stem]} and {p} would both write {d / p.stem}.*; rename one")
        seen[p.stem] = p
    return [{f: d / f"{p.stem}.{'gcode' if f == 'gcode' else f}" for f in formats} for p in images]


def write_plan(result: ImagePlan, files: dict, **options):
    """Writes ``result``'s outputs; ``files``: ``{format: path}`` (formats in :data:`FORMATS`).

    ``options`` are :func:`jdraw.io.outputs.write_outputs`'s (``width_mm``,
    ``preset``, ``feed``, ...). Returns its :class:`jdraw.io.outputs.Written`.

    Raises:
      OutputError: a bad G-code template or size, or a file that cannot be written.
    """
    try:
        return outputs.write_outputs(result, **{f: files.get(f) for f in FORMATS}, **options)
    except (KeyError, ValueError, IndexError) as e:
        raise OutputError(f"bad G-code template or size: {e}") from e
    except OSError as e:
        raise OutputError(f"cannot write output: {e}") from e


def summary(name: str, result: ImagePlan, stats, seconds: float) -> str:
    """One line about a planned image: size, tiles, strokes, lengths, plotting time, seconds."""
    h, w = result.shape
    msg = (
        f"{name}: {w}x{h} px, {len(result.tiles)} tile(s), {stats.summary()}"
        f"{'' if stats.units == 'mm' else ' (G-code 100 mm wide)'}, {seconds:.1f} s"
    )
    if result.direction == "rtl":
        msg += ", read right to left"
    if result.truncated:
        msg += f"; {result.truncated} tile(s) hit --max-steps ({result.completed_pixels} px traced)"
    return msg
