"""Closing the loop: draw, look at the sheet, redraw what is missing.

Round 0 draws the plan under the robot's :class:`~jdraw.robot.faults.Faults`.
Each later round photographs the sheet (:mod:`jdraw.robot.look`), finds the
ink, registers it against the target (where on the paper the drawing
landed), and takes the target ink with no ink within ``tol_mm`` of its
registered place as missing. The missing pieces (grown ``overlap_mm`` along the
target so a redraw starts and ends on ink already there) are planned by
``jdraw.plan`` as a residual drawing, cut to the target's pixels
(:mod:`jdraw.robot.redraw`), and drawn.

The residual is found in the registered frame, so it is drawn with the same
commands that put the rest of the drawing where it is: its ink continues the
lines already on the paper. Moving the commands by the registered offset
instead would draw the missing piece at the target's nominal place, beside the
drawing it belongs to.
"""

from __future__ import annotations

import dataclasses
import os
import time

import cv2
import numpy as np

from jdraw import geometry
from jdraw import plans as types
from jdraw.images.canvas import to_canvas
from jdraw.images.load import load_image
from jdraw.planner.plan import plan as default_planner
from jdraw.robot import look
from jdraw.robot.faults import Faults, true_options
from jdraw.robot.options import RobotOptions
from jdraw.robot.redraw import grow_along, missing, residual_strokes
from jdraw.robot.sheet import to_sheet
from jdraw.robot.verifier import Report, verify


@dataclasses.dataclass
class LoopResult:
    """Every round of drawing one batch of images under faults.

    Attributes:
      target: ``bool [B, 100, 100]`` what should be drawn.
      sheets: ``bool [B, R, 100, 100]`` ink on the paper (its own canvas frame)
        after each round; ``R - 1`` rounds of redraw ran (fewer than asked when
        nothing was missing).
      seen: ``bool [B, R, 100, 100]`` the ink the arm found in its picture.
      iou: ``[B, R]`` tolerant IoU with the target after each round (see
        :func:`tolerant_iou`), measured with the last round's registration.
      iou_exact: ``[B, R]`` pixel IoU of the sheet with the target moved by the
        last registration (rounded to whole pixels).
      redrawn: per image, per round ``r >= 1``, the strokes drawn (target
        canvas coordinates); ``redrawn[b][0]`` is the plan.
      missing: ``bool [B, R, 100, 100]`` target pixels found missing after each
        round (what the next round was asked to draw, before the overlap).
      transform: ``[B, R, 2, 3]`` registration after each round (target canvas
        -> paper canvas).
      offset_mm: ``[B, 2]`` sheet offset estimated from the last registration
        (table frame), and ``rotation_deg`` ``[B]``.
      source: how the arm looked: ``"render"`` (MuJoCo camera) or ``"ink"``
        (contact-ink picture, where OpenGL is missing).
      faults: what was simulated; ``reports``: the :class:`Report` of each round.
      seconds: ``{"draw": [R], "look": [R], "plan": [R]}`` wall seconds per round.
    """

    target: np.ndarray
    sheets: np.ndarray
    seen: np.ndarray
    iou: np.ndarray
    iou_exact: np.ndarray
    redrawn: list
    missing: np.ndarray
    transform: np.ndarray
    offset_mm: np.ndarray
    rotation_deg: np.ndarray
    source: str
    faults: Faults
    reports: list[Report]
    seconds: dict

    @property
    def rounds(self) -> int:
        """Drawing passes that ran (1 = the plan only, no redraw)."""
        return self.sheets.shape[1]

    def summary(self, index: int = 0) -> str:
        """Lines for a terminal: faults, IoU per round, what was redrawn."""
        act = self.faults.active()
        lines = [
            "faults: " + (", ".join(f"{k}={v}" for k, v in act.items()) if act else "none"),
            f"looked with: {self.source}",
        ]
        for r in range(self.rounds):
            what = (
                f"drew the plan, {len(self.redrawn[index][0])} strokes"
                if r == 0
                else (
                    f"redrew {len(self.redrawn[index][r])} strokes, "
                    f"{int(self.missing[index, r - 1].sum())} missing px"
                )
            )
            lines.append(
                f"round {r}: {what}; IoU {self.iou[index, r]:.3f} "
                f"(exact {self.iou_exact[index, r]:.3f})"
            )
        off = self.offset_mm[index]
        lines.append(
            f"registered sheet offset ({off[0]:.1f}, {off[1]:.1f}) mm, "
            f"rotation {self.rotation_deg[index]:.1f} deg"
        )
        return "\n".join(lines)


def tolerant_iou(target: np.ndarray, sheet: np.ndarray, a: np.ndarray, tol_px: float) -> float:
    """IoU with a tolerance: ``hits / (|target| + strays)``.

    ``hits``: target pixels with sheet ink within ``tol_px`` of their place on
    the paper (``a @ p``); ``strays``: sheet pixels farther than ``tol_px`` from
    every registered target pixel. Ink added within ``tol_px`` of the target
    never lowers it. 1 when both are empty.
    """
    n = int(target.sum())
    if n == 0 and not sheet.any():
        return 1.0
    pts = np.argwhere(target)[:, ::-1]
    hits = int(np.sum(look.sample(look.distance_to(sheet), look.apply_affine(a, pts)) <= tol_px))
    inv = cv2.invertAffineTransform(a)
    ink = np.argwhere(sheet)[:, ::-1]
    far = look.sample(look.distance_to(target), look.apply_affine(inv, ink)) > tol_px
    return hits / (n + int(far.sum()))


def exact_iou(target: np.ndarray, sheet: np.ndarray, a: np.ndarray) -> float:
    """Pixel IoU of ``sheet`` with the target's pixels moved by ``a`` and rounded."""
    pts = np.floor(look.apply_affine(a, np.argwhere(target)[:, ::-1]) + 0.5).astype(int)
    moved = np.zeros_like(target)
    ok = np.all((pts >= 0) & (pts < geometry.CANVAS), axis=1)
    moved[pts[ok, 1], pts[ok, 0]] = True
    union = int((moved | sheet).sum())
    return (moved & sheet).sum() / union if union else 1.0


def _as_plan(image_or_plan, checkpoint) -> types.Plan:
    if isinstance(image_or_plan, types.Plan):
        return image_or_plan

    x = image_or_plan
    if isinstance(x, str | os.PathLike):
        x = load_image(x)
    x = np.asarray(x)
    if x.shape[-2:] == (geometry.CANVAS, geometry.CANVAS) and x.ndim in (2, 3) and x.dtype == bool:
        targets = x.reshape(-1, geometry.CANVAS, geometry.CANVAS)
    else:
        targets = to_canvas(x)[0][None]
    kwargs = {} if checkpoint is None else {"checkpoint": checkpoint}
    return default_planner(targets, **kwargs)


def draw_closed_loop(
    image_or_plan,
    faults: Faults | None = None,
    rounds: int = 2,
    *,
    options: RobotOptions | None = None,
    tol_mm: float = 1.2,
    overlap_mm: float = 2.0,
    min_missing_px: int = 2,
    look_with: str = "auto",
    press_step_mm: float = 1.25,
    max_press_mm: float = 4.0,
    checkpoint=None,
    planner=None,
) -> LoopResult:
    """Draws with the simulated arm under ``faults``, then looks and redraws up to ``rounds`` times.

    Args:
      image_or_plan: a :class:`jdraw.Plan` (its render is the target), a
        ``bool [B, 100, 100]`` / ``[100, 100]`` target of thin lines, or any
        image or image path (fitted to the canvas like ``jdraw.plan_image``).
      faults: what goes wrong (default: nothing).
      rounds: most redraw rounds after the first pass.
      options: where the planner believes the sheet is, speeds, ...
      tol_mm: target ink with drawn ink this close to its registered place
        counts as drawn (also the IoU's tolerance).
      overlap_mm: a redraw runs this far along the target into ink already there.
      min_missing_px: missing pieces smaller than this are left alone.
      look_with: ``"auto"``, ``"render"`` or ``"ink"`` (see :func:`look.photograph`).
      press_step_mm: each redraw round presses the pen this much deeper (the
        spring-loaded tip takes it up), up to ``max_press_mm``: where a sheet
        sags away from the pen, the redraw still reaches it.
      checkpoint, planner: for the residual plans (default: ``jdraw.plan``).

    Returns:
      A :class:`LoopResult`.
    """
    if rounds < 0:
        raise ValueError(f"rounds must be >= 0, got {rounds}")
    options = options or RobotOptions()
    faults = faults or Faults()
    plan = _as_plan(image_or_plan, checkpoint)
    target = types.render(plan)
    b = len(target)
    real = true_options(options, faults)
    tol_px = tol_mm / (float(np.mean(options.sheet_size_mm)) / geometry.CANVAS)
    grow = int(round(overlap_mm / (float(np.mean(options.sheet_size_mm)) / geometry.CANVAS)))

    sheet = np.zeros_like(target)
    sheets, seens, misses, transforms, reports = [], [], [], [], []
    redrawn = [[list(s)] for s in plan.strokes]
    secs = {"draw": [], "look": [], "plan": []}
    todo = plan
    source = "ink"
    pass_options = options
    for r in range(rounds + 1):
        t0 = time.perf_counter()
        rep = verify(todo, pass_options, faults=faults, pass_index=r)
        # Redraws are shorter than the plan: padding them to its length reuses
        # the compiled rollout (a new length compiles for minutes on a CPU).
        press = min(options.press_mm + (r + 1) * press_step_mm, max_press_mm)
        press = max(press, options.press_mm)
        pass_options = dataclasses.replace(options, pad_steps=int(rep.t.size), press_mm=press)
        sheet = sheet | rep.drawn
        reports.append(rep)
        t1 = time.perf_counter()
        seen = np.zeros_like(target)
        a = np.tile(np.eye(2, 3), (b, 1, 1))
        for i in range(b):
            photo, source = look.photograph(sheet[i], real, options, look_with)
            seen[i] = look.see(photo)
            a[i] = look.register(target[i], seen[i])
        miss = np.stack(
            [missing(target[i], seen[i], a[i], tol_px, min_missing_px) for i in range(b)]
        )
        t2 = time.perf_counter()
        sheets.append(sheet.copy())
        seens.append(seen)
        misses.append(miss)
        transforms.append(a)
        secs["draw"].append(t1 - t0)
        secs["look"].append(t2 - t1)
        if r == rounds or not miss.any():
            secs["plan"].append(0.0)
            break
        want = np.stack([grow_along(miss[i], target[i], grow) for i in range(b)])
        strokes = residual_strokes(want, planner, checkpoint, target & ~miss)
        secs["plan"].append(time.perf_counter() - t2)
        for i in range(b):
            redrawn[i].append(strokes[i])
        todo = types.Plan(
            strokes=strokes,
            actions=np.zeros((b, 1, 3), np.int32),
            lengths=np.zeros(b, np.int32),
            truncated=np.zeros(b, bool),
        )

    n = len(sheets)
    last = transforms[-1]
    iou = np.array(
        [
            [tolerant_iou(target[i], sheets[r][i], last[i], tol_px) for r in range(n)]
            for i in range(b)
        ]
    )
    iou_exact = np.array(
        [[exact_iou(target[i], sheets[r][i], last[i]) for r in range(n)] for i in range(b)]
    )
    poses = [look.sheet_pose(last[i], options) for i in range(b)]
    return LoopResult(
        target=target,
        sheets=np.stack(sheets, 1),
        seen=np.stack(seens, 1),
        iou=iou,
        iou_exact=iou_exact,
        redrawn=redrawn,
        missing=np.stack(misses, 1),
        transform=np.stack(transforms, 1),
        offset_mm=np.array([p[0] for p in poses]),
        rotation_deg=np.array([p[1] for p in poses]),
        source=source,
        faults=faults,
        reports=reports,
        seconds=secs,
    )


def image_closed_loop(
    strokes,
    shape: tuple[int, int],
    faults: Faults | None = None,
    rounds: int = 2,
    options: RobotOptions | None = None,
    fill: float = 0.9,
) -> LoopResult:
    """The loop for ``jdraw.plan_image`` strokes (input pixels of an ``(H, W)`` image).

    The strokes are fitted onto the sheet as ``jdraw draw --trajectory`` does
    (:func:`jdraw.robot.to_sheet`); their render on the canvas is the target.
    """
    sheet = to_sheet(strokes, shape, fill)
    plan = types.Plan(
        [sheet], np.zeros((1, 0, 3), np.int32), np.zeros(1, np.int32), np.zeros(1, bool)
    )
    return draw_closed_loop(plan, faults, rounds, options=options)


def picture(result: LoopResult, path: str | os.PathLike, index: int = 0, scale: int = 4) -> str:
    """Writes a PNG: target | sheet after round 0 | sheet after the last round.

    The sheets are the paper's own frame; light blue is the target at its
    registered place, black the first pass's ink, red the redrawn ink.
    """
    a = result.transform[index, -1]
    pts = np.floor(look.apply_affine(a, np.argwhere(result.target[index])[:, ::-1]) + 0.5)
    pts = pts.astype(int)
    ok = np.all((pts >= 0) & (pts < geometry.CANVAS), axis=1)
    placed = np.zeros_like(result.target[index])
    placed[pts[ok, 1], pts[ok, 0]] = True
    first = result.sheets[index, 0]
    panels = []
    for k, sheet in enumerate([None, first, result.sheets[index, -1]]):
        img = np.full((geometry.CANVAS, geometry.CANVAS, 3), 255, np.uint8)
        if sheet is None:
            img[result.target[index]] = (20, 20, 20)
            label = "target"
        else:
            img[placed] = (235, 200, 160)
            img[sheet] = (40, 40, 220)
            img[first] = (20, 20, 20)
            r = 0 if k == 1 else result.rounds - 1
            label = f"round {r}: IoU {result.iou[index, r]:.2f}"
        img = cv2.resize(img, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST)
        cv2.putText(img, label, (6, 18), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (0, 0, 0), 1, cv2.LINE_AA)
        panels.append(img)
        panels.append(np.full((img.shape[0], 6, 3), 200, np.uint8))
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    cv2.imwrite(os.fspath(path), np.concatenate(panels[:-1], axis=1))
    return os.fspath(path)
