"""A picture of the arm and the sheet it drew (and optionally a video).

    MUJOCO_GL=egl python -m jdraw.robot.picture --out results/robot.png --video results/robot.mp4

Offscreen rendering uses MuJoCo's renderer (EGL or OSMesa); without one, only
the sheet panel is written.
"""

from __future__ import annotations

import argparse
import os

import cv2
import mujoco
import numpy as np

from jdraw import geometry
from jdraw.plans import Plan
from jdraw.robot import scene
from jdraw.robot.options import RobotOptions
from jdraw.robot.verifier import Report, verify


def demo_plan() -> Plan:
    """A hand-made plan: a square, its diagonal, a circle and a dot."""
    sq = geometry.polyline_pixels(
        np.array([[15, 15], [15, 55], [55, 55], [55, 15], [15, 15]])
    ).astype(float)
    th = np.linspace(0, 2 * np.pi, 64)
    circle = np.round(np.stack([70 + 18 * np.cos(th), 70 + 18 * np.sin(th)], -1))
    strokes = [sq, np.array([[15.0, 55.0], [55.0, 15.0]]), circle, np.array([[85.0, 15.0]])]
    return Plan(
        strokes=[strokes],
        actions=np.zeros((1, 1, 3), np.int32),
        lengths=np.zeros(1, np.int32),
        truncated=np.zeros(1, bool),
    )


def sheet_image(report: Report, index: int = 0, scale: int = 4) -> np.ndarray:
    """``uint8 [H, W, 3]`` BGR: planned pixels light blue, drawn pixels black."""
    img = np.full((*report.drawn.shape[1:], 3), 255, np.uint8)
    img[report.planned[index]] = (235, 200, 160)
    img[report.drawn[index]] = (20, 20, 20)
    img = cv2.resize(img, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST)
    cv2.putText(
        img,
        f"IoU {report.iou[index]:.3f}",
        (6, 18),
        cv2.FONT_HERSHEY_SIMPLEX,
        0.5,
        (0, 0, 200),
        1,
        cv2.LINE_AA,
    )
    return img


def _add_ink(view: mujoco.MjvScene, pixels: np.ndarray, options: RobotOptions) -> None:
    half = scene.pixel_size_m(options) / 2
    for x, y in pixels:
        if view.ngeom >= view.maxgeom:
            return
        pos = scene.canvas_to_world([[x, y]], 0.05, options)[0]
        c, s = np.cos(options.sheet_yaw), np.sin(options.sheet_yaw)
        mat = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], np.float64).reshape(-1)
        mujoco.mjv_initGeom(
            view.geoms[view.ngeom],
            mujoco.mjtGeom.mjGEOM_BOX,
            np.array([half[0], half[1], 2e-5]),
            pos,
            mat,
            np.array([0.05, 0.05, 0.05, 1], np.float32),
        )
        view.ngeom += 1


def render_frames(
    report: Report,
    index: int,
    options: RobotOptions,
    steps,
    width: int,
    height: int,
    camera: str = "overview",
) -> list[np.ndarray]:
    """BGR frames of the arm at control ``steps``, with the ink laid so far."""
    m = scene.load(options)
    m.vis.global_.offwidth, m.vis.global_.offheight = max(width, 640), max(height, 480)
    d = mujoco.MjData(m)
    frames = []
    with mujoco.Renderer(m, height, width) as r:
        for k in steps:
            d.qpos[: scene.N_ARM] = report.q_sim[index, k]
            mujoco.mj_forward(m, d)
            r.update_scene(d, camera=camera)
            # ink drawn so far: the planned pixels the nib has already passed
            done = report.touch[index, : k + 1]
            tip = scene.world_to_canvas(report.tip[index, : k + 1][done], options)
            ink = np.unique(np.floor(tip + 0.5).astype(int), axis=0) if len(tip) else tip
            ink = [
                p
                for p in ink
                if 0 <= p[0] < 100 and 0 <= p[1] < 100 and report.drawn[index, p[1], p[0]]
            ]
            _add_ink(r.scene, np.asarray(ink).reshape(-1, 2), options)
            frames.append(cv2.cvtColor(r.render(), cv2.COLOR_RGB2BGR))
    return frames


def picture(
    report: Report,
    path: str,
    index: int = 0,
    options: RobotOptions | None = None,
    video: str | None = None,
) -> str:
    """Writes a PNG: the arm after drawing (left) and the drawn sheet (right)."""
    options = options or RobotOptions()
    sheet = sheet_image(report, index)
    n = int(report.valid[index].sum())
    try:
        arm = render_frames(report, index, options, [n - 1], 640, 480)[0]
        pad = np.full((arm.shape[0], sheet.shape[1], 3), 255, np.uint8)
        top = (arm.shape[0] - sheet.shape[0]) // 2
        pad[top : top + sheet.shape[0]] = sheet
        out = np.concatenate([arm, pad], axis=1)
        if video:
            steps = np.linspace(0, n - 1, min(n, 120)).astype(int)
            frames = render_frames(report, index, options, steps, 640, 480)
            fps = len(steps) / max(n * (report.t[1] - report.t[0]), 1e-3)
            writer = cv2.VideoWriter(
                video, cv2.VideoWriter_fourcc(*"mp4v"), max(fps, 5.0), (640, 480)
            )
            for f in frames:
                writer.write(f)
            writer.release()
    except Exception as e:  # noqa: BLE001 - no OpenGL here: the sheet alone still helps
        print(f"offscreen rendering unavailable ({e}); writing the sheet only")
        out = sheet
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    cv2.imwrite(path, out)
    return path


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/robot.png")
    parser.add_argument("--video", default=None, help="optional .mp4 of the arm drawing")
    args = parser.parse_args(argv)
    options = RobotOptions()
    report = verify(demo_plan(), options)
    print(
        f"reachable={report.reachable[0]} iou={report.iou[0]:.3f} "
        f"max_ik_error_mm={report.max_ik_error_mm[0]:.4f} "
        f"drawing_time_s={report.drawing_time_s[0]:.1f}"
    )
    print("wrote", picture(report, args.out, options=options, video=args.video))


if __name__ == "__main__":
    main()
