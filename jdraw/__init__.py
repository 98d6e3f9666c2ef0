"""jdraw: look at a bitmap of a drawing and work out how to draw it.

The public surface, one name a line; everything else lives in the packages
named in the README's layout table.
"""

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
