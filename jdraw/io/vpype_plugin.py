"""``vpype jdraw IMAGE``: jdraw's plan as a vpype layer, for plotter pipelines.

Registered through the ``vpype.plugins`` entry point (``pip install -e ".[vpype]"``)::

    vpype jdraw --width 150mm photo.jpg write out.svg
    vpype jdraw --size a6 photo.jpg gwrite --profile gcodemm out.gcode

The command is a vpype *generator*: it plans the image with
:func:`jdraw.plan_image` and adds one line path per stroke, in drawing order
and direction, to the target layer (vpype's own ``--layer`` option). Points
keep jdraw's SVG frame: input pixel ``(x, y)`` lands at ``(x, y) * k`` with
``k`` the CSS pixels (vpype's unit, 1/96 in) per input pixel; ``k = 1``
unless a size is given. When the document has no page size yet, it becomes
the image's frame (``W * k`` by ``H * k``), as in jdraw's own SVG, so
``write`` keeps the drawing where it lies on the picture and ``gwrite``
profiles that flip the Y axis (``gcode``, ``gcodemm``) work.
"""

from __future__ import annotations

from collections.abc import Sequence

import click
import numpy as np
import vpype as vp
import vpype_cli


def scale_for(
    shape: tuple[int, int],
    size: tuple[float, float] | None = None,
    width: float | None = None,
    height: float | None = None,
) -> float:
    """Output units per input pixel so the ``(H, W)`` frame fits every bound given.

    ``size`` is a ``(width, height)`` box; ``width`` and ``height`` bound one
    side each; with none, 1.
    """
    h, w = shape
    bounds = [b for b in (size[0] if size else None, width) if b is not None]
    k = [b / w for b in bounds]
    bounds = [b for b in (size[1] if size else None, height) if b is not None]
    k += [b / h for b in bounds]
    if not k:
        return 1.0
    if min(k) <= 0:
        raise click.BadParameter("the drawing size must be positive")
    return min(k)


def strokes_to_lines(strokes: Sequence[np.ndarray], scale: float = 1.0) -> vp.LineCollection:
    """A vpype layer of ``[n, 2]`` (x, y) polylines scaled by ``scale``, in order.

    A one-point stroke (a dot) becomes a zero-length segment, so plotters touch
    the paper there.
    """
    lc = vp.LineCollection()
    for s in strokes:
        p = np.asarray(s, np.float64).reshape(-1, 2)
        if not len(p):
            continue
        if len(p) == 1:
            p = np.concatenate([p, p])
        lc.append((p[:, 0] + 1j * p[:, 1]) * scale)
    return lc


@click.command(name="jdraw")
@click.argument("image", type=click.Path(exists=True, dir_okay=False))
@click.option(
    "-c",
    "--checkpoint",
    type=click.Path(exists=True),
    help="jdraw model bundle or training workdir (default: the bundled model).",
)
@click.option(
    "-s",
    "--size",
    type=vpype_cli.PageSizeType(),
    help="Fit the drawing inside this box, e.g. 150x100mm or a6 (aspect kept).",
)
@click.option("-w", "--width", type=vpype_cli.LengthType(), help="Drawing width, e.g. 150mm.")
@click.option("-H", "--height", type=vpype_cli.LengthType(), help="Drawing height, e.g. 4in.")
@click.option(
    "--polarity",
    type=click.Choice(["auto", "dark", "light"]),
    default="auto",
    show_default=True,
    help="Ink darker or lighter than the ground.",
)
@click.option(
    "--min-gap",
    type=float,
    default=4.0,
    show_default=True,
    help="Planner-canvas pixels kept between separate lines when scaling down.",
)
@click.option("--max-steps", type=int, help="Action limit per 100x100 tile (default 1024).")
@vpype_cli.generator
def jdraw(image, checkpoint, size, width, height, polarity, min_gap, max_steps):
    """Plan how to draw IMAGE with jdraw; one line per stroke, in drawing order.

    IMAGE is a photo, scan or bitmap of handwriting or a line drawing, any
    size. Without --size/--width/--height, one input pixel is one CSS pixel.
    Sets the page size to the image's frame when none is set.
    """
    from jdraw.images.load import ImageError, load_image
    from jdraw.tiling.plan_image import plan_image

    if max_steps is not None and max_steps < 1:
        raise click.BadParameter("must be positive", param_hint="--max-steps")
    try:
        result = plan_image(
            load_image(image),
            checkpoint=checkpoint,
            max_steps=max_steps,
            polarity=polarity,
            min_gap=min_gap,
            progress=False,
        )
    except ImageError as e:  # unreadable or blank: say so, no traceback
        raise click.ClickException(f"jdraw: {image}: {e}") from e
    k = scale_for(result.shape, size, width, height)
    document = vpype_cli.State.get_current().document
    if document.page_size is None:
        # The image's frame, as jdraw's own SVG; G-code profiles that flip Y need a page.
        h, w = result.shape
        document.page_size = (w * k, h * k)
    return strokes_to_lines(result.strokes, k)


jdraw.help_group = "Plugins"
