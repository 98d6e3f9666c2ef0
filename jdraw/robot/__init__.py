"""Robot in the loop: an MJX arm draws each plan and reports what came out.

``verify(plan)`` maps the plan's strokes onto a sheet on the table, solves IK
for the pen tip along the timed path, simulates the arm tracking it with MJX
and rasterises where the nib touched the paper.

Importing MJX prints a notice to stdout when its optional Warp backend is not
installed (jdraw uses the JAX backend); the ``jdraw`` command sends it to stderr.
"""

import warnings

from jdraw.robot.closed_loop import LoopResult as LoopResult
from jdraw.robot.closed_loop import draw_closed_loop as draw_closed_loop
from jdraw.robot.faults import Faults as Faults
from jdraw.robot.options import RobotOptions as RobotOptions
from jdraw.robot.ros import joint_trajectory as joint_trajectory
from jdraw.robot.scene import canvas_to_world as canvas_to_world
from jdraw.robot.scene import load as load_scene
from jdraw.robot.scene import world_to_canvas as world_to_canvas
from jdraw.robot.sheet import image_trajectory as image_trajectory
from jdraw.robot.sheet import to_sheet as to_sheet
from jdraw.robot.trajectory import tip_path as tip_path
from jdraw.robot.verifier import Report as Report
from jdraw.robot.verifier import arm as arm
from jdraw.robot.verifier import verify as verify


def load_model(options: RobotOptions | None = None):
    """Deprecated name of :func:`load_scene` (it clashed with :func:`jdraw.load_model`)."""
    warnings.warn(
        "jdraw.robot.load_model is deprecated; use jdraw.robot.load_scene",
        DeprecationWarning,
        stacklevel=2,
    )
    return load_scene(options)
