"""jdraw: look at a bitmap of a drawing and work out how to draw it."""

from jdraw.api import load_model as load_model
from jdraw.api import plan as plan
from jdraw.export import export as export
from jdraw.metrics import pixel_accuracy as pixel_accuracy
from jdraw.metrics import stroke_accuracy as stroke_accuracy
from jdraw.raster import render_strokes as render_strokes
from jdraw.tiling import ImagePlan as ImagePlan
from jdraw.tiling import plan_image as plan_image
from jdraw.types import Plan as Plan
from jdraw.types import render as render
