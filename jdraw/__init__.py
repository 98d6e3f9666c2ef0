"""jdraw: look at a bitmap of a drawing and work out how to draw it.

The public surface, one name a line; everything else lives in the packages
named in the README's layout table. Each name is imported on first use, so
``import jdraw`` is quick: JAX, Flax, SciPy and scikit-image load only when a
function that needs them is called.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

_PUBLIC = {
    "pixel_accuracy": "jdraw.evaluation.metrics",
    "stroke_accuracy": "jdraw.evaluation.metrics",
    "render_strokes": "jdraw.geometry",
    "to_gcode": "jdraw.io.gcode",
    "write_outputs": "jdraw.io.outputs",
    "to_svg": "jdraw.io.svg",
    "export": "jdraw.model.checkpoints",
    "load_model": "jdraw.planner.plan",
    "plan": "jdraw.planner.plan",
    "Plan": "jdraw.plans",
    "render": "jdraw.plans",
    "ImagePlan": "jdraw.tiling.plan_image",
    "plan_image": "jdraw.tiling.plan_image",
}

__all__ = sorted(_PUBLIC)


def __getattr__(name: str):
    if name not in _PUBLIC:
        raise AttributeError(f"module 'jdraw' has no attribute {name!r}")
    value = getattr(importlib.import_module(_PUBLIC[name]), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))


if TYPE_CHECKING:  # for type checkers and editors: the same names, imported eagerly
    from jdraw.evaluation.metrics import pixel_accuracy as pixel_accuracy
    from jdraw.evaluation.metrics import stroke_accuracy as stroke_accuracy
    from jdraw.geometry import render_strokes as render_strokes
    from jdraw.io.gcode import to_gcode as to_gcode
    from jdraw.io.outputs import write_outputs as write_outputs
    from jdraw.io.svg import to_svg as to_svg
    from jdraw.model.checkpoints import export as export
    from jdraw.planner.plan import load_model as load_model
    from jdraw.planner.plan import plan as plan
    from jdraw.plans import Plan as Plan
    from jdraw.plans import render as render
    from jdraw.tiling.plan_image import ImagePlan as ImagePlan
    from jdraw.tiling.plan_image import plan_image as plan_image
