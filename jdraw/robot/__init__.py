"""Robot in the loop: an MJX arm draws each plan and reports what came out.

``verify(plan)`` maps the plan's strokes onto a sheet on the table, solves IK
for the pen tip along the timed path, simulates the arm tracking it with MJX
and rasterises where the nib touched the paper.
"""

import contextlib
import io

# mujoco.mjx prints a notice to stdout when its optional Warp backend is not
# installed; jdraw uses the JAX backend, and the CLI's stdout is for results.
with contextlib.redirect_stdout(io.StringIO()):
    import mujoco.mjx  # noqa: F401

from jdraw.robot.closed_loop import LoopResult as LoopResult
from jdraw.robot.closed_loop import draw_closed_loop as draw_closed_loop
from jdraw.robot.faults import Faults as Faults
from jdraw.robot.image import image_trajectory as image_trajectory
from jdraw.robot.image import to_sheet as to_sheet
from jdraw.robot.model import canvas_to_world as canvas_to_world
from jdraw.robot.model import load as load_model  # noqa: F401
from jdraw.robot.model import world_to_canvas as world_to_canvas
from jdraw.robot.options import RobotOptions as RobotOptions
from jdraw.robot.trajectory import tip_path as tip_path
from jdraw.robot.verifier import Report as Report
from jdraw.robot.verifier import arm as arm
from jdraw.robot.verifier import verify as verify
