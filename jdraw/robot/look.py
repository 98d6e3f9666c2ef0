"""The arm looks at its sheet: a camera image, the ink found in it, and registration.

:func:`photograph` renders the table from a camera above the sheet with
MuJoCo's renderer (EGL, OSMesa or GLFW, whichever ``MUJOCO_GL`` selects) and
cuts the paper out of the picture; where no OpenGL context can be made it
falls back to a picture of the contact ink (:func:`ink_photo`). :func:`see`
runs the image pipeline ``jdraw.plan_image`` uses (binarise, skeletonise,
polylines, thin lines on the canvas) on it, and :func:`register` estimates
where the drawing landed on the paper relative to the target (phase
correlation, refined by OpenCV's ECC as a rotation plus shift).

Canvas coordinates are ``(x, y)`` pixels of the 100 x 100 sheet canvas, pixel
centres at integers; a paper-frame image is one whose canvas is the real paper.
"""

from __future__ import annotations

import dataclasses
import functools

import cv2
import mujoco
import numpy as np

from jdraw import geometry
from jdraw.images.canvas import CanvasTransform, render_polylines
from jdraw.images.load import BlankImageError
from jdraw.images.prepare import prepare
from jdraw.robot import scene
from jdraw.robot.options import RobotOptions

SCALE = 4  # photo pixels per canvas pixel
# The arm swung aside (joint 1 a quarter turn) so the camera sees the whole sheet.
PARK = scene.SEED + np.array([np.pi / 2, -0.6, 0, 0.6, 0, 0, 0], np.float32)


def ink_photo(drawn: np.ndarray, nib_px: float = 1.0) -> np.ndarray:
    """A paper-frame picture of the contact ink: ``uint8 [400, 400]``, dark ink on white.

    Args:
      drawn: ``bool [100, 100]`` inked canvas pixels.
      nib_px: canvas pixels, width of the painted line.
    """
    big = cv2.resize(
        drawn.astype(np.uint8), None, fx=SCALE, fy=SCALE, interpolation=cv2.INTER_NEAREST
    )
    k = max(1, int(round(nib_px * SCALE / 2)))
    big = cv2.GaussianBlur(big.astype(np.float32), (2 * k + 1, 2 * k + 1), k / 2) > 0.25
    return np.where(big, 30, 245).astype(np.uint8)


@functools.lru_cache(maxsize=1)
def can_render() -> bool:
    """Whether MuJoCo can open an offscreen OpenGL context in this process."""
    try:
        m = mujoco.MjModel.from_xml_string("<mujoco><worldbody/></mujoco>")
        with mujoco.Renderer(m, 8, 8) as r:
            r.render()
        return True
    except Exception:  # noqa: BLE001 - any GL failure means: use the contact ink
        return False


def _camera(options: RobotOptions, size: int) -> tuple[mujoco.MjvCamera, float]:
    """A free camera straight above the believed sheet centre and its distance (m)."""
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = (*options.sheet_center, 0.0)
    cam.elevation = -90.0
    cam.azimuth = 90.0 + np.degrees(options.sheet_yaw)
    # the view spans 1.4 sheets so a misplaced sheet still lies inside it
    half = 0.7 * max(options.sheet_size_mm) / 1000
    cam.distance = half / np.tan(np.radians(45.0 / 2))
    return cam, cam.distance


def _project(view: mujoco.MjvScene, points: np.ndarray, h: int, w: int) -> np.ndarray:
    """World points ``[N, 3]`` to image ``(col, row)`` with the view's GL camera."""
    c = view.camera[0]
    # a mono picture is taken from between the two stereo eyes
    pos = (np.array(view.camera[0].pos) + np.array(view.camera[1].pos)) / 2
    fwd, up = np.array(c.forward), np.array(c.up)
    right = np.cross(fwd, up)
    rel = points - pos
    z = rel @ fwd
    x = (rel @ right) * c.frustum_near / z
    y = (rel @ up) * c.frustum_near / z
    # a zero width means the renderer derives it from the viewport's aspect
    width = c.frustum_width or (c.frustum_top - c.frustum_bottom) / 2 * w / h
    nx = (x - c.frustum_center) / width
    ny = (y - (c.frustum_top + c.frustum_bottom) / 2) / ((c.frustum_top - c.frustum_bottom) / 2)
    return np.stack([(nx + 1) / 2 * w - 0.5, (1 - ny) / 2 * h - 0.5], -1)


def render_table(drawn: np.ndarray, real: RobotOptions, believed: RobotOptions, size: int = 560):
    """Renders the table from above the believed sheet with ``drawn`` inked on the real one.

    Returns:
      ``(rgb uint8 [size, size, 3], corners [4, 2])``: the picture and where the
      *believed* sheet's corners (canvas ``(-0.5, -0.5)``, ``(99.5, -0.5)``,
      ``(99.5, 99.5)``, ``(-0.5, 99.5)``) project in it.
    """
    from jdraw.robot.picture import _add_ink

    m = scene.load(real)
    m.vis.global_.offwidth = max(m.vis.global_.offwidth, size)
    m.vis.global_.offheight = max(m.vis.global_.offheight, size)
    d = mujoco.MjData(m)
    d.qpos[: scene.N_ARM] = PARK
    mujoco.mj_forward(m, d)
    cam, _ = _camera(believed, size)
    n = int(drawn.sum())
    with mujoco.Renderer(m, size, size, max_geom=n + 200) as r:
        r.update_scene(d, camera=cam)
        _add_ink(r.scene, np.argwhere(drawn)[:, ::-1], real)
        rgb = r.render().copy()
        edge = np.array([[-0.5, -0.5], [99.5, -0.5], [99.5, 99.5], [-0.5, 99.5]])
        corners = _project(r.scene, scene.canvas_to_world(edge, 0.0, believed), size, size)
    return rgb, corners


def find_paper(rgb: np.ndarray, guess: np.ndarray) -> np.ndarray | None:
    """The paper's corners ``[4, 2]`` (col, row) in a picture, ordered like ``guess``.

    The paper is the largest bright quadrilateral; ink inside it is filled over.
    """
    gray = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    _, bright = cv2.threshold(gray, 0, 255, cv2.THRESH_BINARY + cv2.THRESH_OTSU)
    contours, _ = cv2.findContours(bright, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    if not contours:
        return None
    big = max(contours, key=cv2.contourArea)
    if cv2.contourArea(big) < 0.25 * cv2.contourArea(guess.astype(np.float32)):
        return None
    box = cv2.boxPoints(cv2.minAreaRect(big))
    # the cyclic order of the box's corners that best matches the believed sheet
    best = min(
        (np.roll(b, k, axis=0) for b in (box, box[::-1]) for k in range(4)),
        key=lambda c: float(np.sum((c - guess) ** 2)),
    )
    return best


def photograph(
    drawn: np.ndarray, real: RobotOptions, believed: RobotOptions, method: str = "auto"
) -> tuple[np.ndarray, str]:
    """What the arm's camera sees of the paper, warped to a paper-frame picture.

    Args:
      drawn: ``bool [100, 100]`` ink on the real sheet (its own canvas frame).
      real: where the sheet really is; believed: where the planner thinks it is.
      method: ``"render"`` (fail without OpenGL), ``"ink"`` (contact-ink
        picture) or ``"auto"`` (render where possible, else ink).

    Returns:
      ``(gray uint8 [400, 400], source)`` with ``source`` ``"render"`` or ``"ink"``.
    """
    if method not in ("auto", "render", "ink"):
        raise ValueError(f"method must be auto, render or ink, got {method!r}")
    if method == "ink" or (method == "auto" and not can_render()):
        return ink_photo(drawn), "ink"
    rgb, guess = render_table(drawn, real, believed)
    corners = find_paper(rgb, guess)
    if corners is None:
        if method == "render":
            raise RuntimeError("the paper was not found in the camera picture")
        return ink_photo(drawn), "ink"
    side = geometry.CANVAS * SCALE
    dst = np.array([[0, 0], [side, 0], [side, side], [0, side]], np.float32) - 0.5
    h = cv2.getPerspectiveTransform(corners.astype(np.float32), dst)
    gray = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    warped = cv2.warpPerspective(gray, h, (side, side), flags=cv2.INTER_LINEAR, borderValue=255)
    return warped, "render"


def see(photo: np.ndarray) -> np.ndarray:
    """The ink in a paper-frame picture as 1-pixel lines on the canvas: ``bool [100, 100]``.

    The steps of ``jdraw.plan_image``: :func:`jdraw.images.prepare.prepare` (binarise,
    denoise, skeletonise, polylines) and :func:`jdraw.images.canvas.render_polylines`
    with the picture's known scale (no refitting: the canvas is the paper).
    """
    try:
        prep = prepare(photo, polarity="dark")
    except BlankImageError:
        return np.zeros((geometry.CANVAS, geometry.CANVAS), bool)
    s = photo.shape[1] / geometry.CANVAS
    tf = CanvasTransform(1 / s, (0.5 / s - 0.5, 0.5 / s - 0.5))
    return render_polylines(prep.polylines, tf, (geometry.CANVAS, geometry.CANVAS))


def register(target: np.ndarray, seen: np.ndarray, sigma: float = 1.5) -> np.ndarray:
    """Where the target landed on the paper: ``[2, 3]`` affine (rotation + shift).

    ``A @ (x, y, 1)`` takes a target canvas point to the paper canvas point the
    drawing put it at. Phase correlation of the blurred images gives the
    shift; ECC (``MOTION_EUCLIDEAN``) refines it with a rotation. Identity when
    either image is empty.
    """
    a = np.eye(2, 3, dtype=np.float32)
    if not target.any() or not seen.any():
        return a
    k = int(4 * sigma) | 1
    t = cv2.GaussianBlur(target.astype(np.float32), (k, k), sigma)
    s = cv2.GaussianBlur(seen.astype(np.float32), (k, k), sigma)
    win = cv2.createHanningWindow(t.shape[::-1], cv2.CV_32F)
    (dx, dy), _ = cv2.phaseCorrelate(t, s, win)
    a[:, 2] = (dx, dy)
    crit = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 200, 1e-6)
    try:
        _, a = cv2.findTransformECC(t, s, a.copy(), cv2.MOTION_EUCLIDEAN, crit, None, 1)
    except cv2.error:
        pass  # ECC did not converge: keep the phase-correlation shift
    return a.astype(np.float64)


def apply_affine(a: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``[N, 2]`` points through a ``[2, 3]`` affine."""
    p = np.asarray(points, np.float64).reshape(-1, 2)
    return p @ a[:, :2].T + a[:, 2]


def sheet_pose(a: np.ndarray, believed: RobotOptions) -> tuple[np.ndarray, float]:
    """The real sheet placement implied by a registration: ``(offset mm [2], rotation deg)``.

    The arm put target point ``p`` at the believed world position ``w(p)``;
    the paper shows it at ``A p``, so the real sheet has canvas point ``A p`` at
    ``w(p)``. A canvas rotation by ``phi`` is a sheet yaw of ``phi`` (the
    canvas's y axis points down).
    """
    phi = float(np.arctan2(a[1, 0], a[0, 0]))
    yaw = believed.sheet_yaw + phi
    c = np.array([[49.5, 49.5]])
    w = scene.canvas_to_world(c, 0.0, believed)[0, :2]
    at_zero = dataclasses.replace(believed, sheet_center=(0.0, 0.0), sheet_yaw=yaw)
    rel = scene.canvas_to_world(apply_affine(a, c), 0.0, at_zero)[0, :2]
    center = w - rel
    return (center - np.asarray(believed.sheet_center)) * 1000, float(np.degrees(phi))


def distance_to(ink: np.ndarray) -> np.ndarray:
    """``float32 [100, 100]`` canvas pixels from each pixel to the nearest ink pixel."""
    if not ink.any():
        return np.full(ink.shape, np.inf, np.float32)
    return cv2.distanceTransform((~ink).astype(np.uint8), cv2.DIST_L2, cv2.DIST_MASK_PRECISE)


def sample(field: np.ndarray, points: np.ndarray, outside: float = np.inf) -> np.ndarray:
    """Bilinear samples ``[N]`` of ``field [H, W]`` at ``(x, y)`` points (``outside`` off it)."""
    p = np.asarray(points, np.float64).reshape(-1, 2)
    h, w = field.shape
    ok = (p[:, 0] >= 0) & (p[:, 0] <= w - 1) & (p[:, 1] >= 0) & (p[:, 1] <= h - 1)
    x0 = np.clip(np.floor(p[:, 0]).astype(int), 0, w - 2)
    y0 = np.clip(np.floor(p[:, 1]).astype(int), 0, h - 2)
    fx, fy = p[:, 0] - x0, p[:, 1] - y0
    f = np.where(np.isfinite(field), field, 1e6)
    v = (
        f[y0, x0] * (1 - fx) * (1 - fy)
        + f[y0, x0 + 1] * fx * (1 - fy)
        + f[y0 + 1, x0] * (1 - fx) * fy
        + f[y0 + 1, x0 + 1] * fx * fy
    )
    return np.where(ok, v, outside)
