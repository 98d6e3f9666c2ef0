"""The errors real drawing robots make, injected into the simulated arm.

Every fault is a field of :class:`Faults` with a physical unit; all are off by
default. :func:`apply` turns them into what the MJX rollout consumes: the real
(unknown to the planner) sheet placement, joint-target offsets, tip targets
moved by the sheet's height, and a per-step gate that keeps the pen from inking.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from jdraw.robot import scene
from jdraw.robot.options import RobotOptions


@dataclasses.dataclass(frozen=True)
class Faults:
    """Errors of the robot and its workcell; zero means the fault is off.

    Attributes:
      sheet_offset_mm: ``(x, y)`` mm, where the paper really lies relative to
        where the planner believes (table frame: x forward, y left).
      sheet_rotation_deg: deg, the paper's real yaw minus the believed one.
      joint_bias_rad: rad, standard deviation of a constant per-joint offset of
        the joint angles (encoder calibration); drawn once from ``seed``.
      joint_noise_rad: rad, standard deviation of white noise added to each
        joint target every control step (10 ms), new for every drawing pass.
      pen_skip_per_mm: probability per mm of pen-down travel that the pen stops
        inking for ``skip_length_mm`` (a dry or skipping nib).
      skip_length_mm: mm of travel a skip lasts.
      early_lift_mm: mm, the pen leaves the paper this long before the end of
        each stroke (strokes shorter than this leave no ink; dots are kept).
      sheet_wobble_mm: mm, amplitude of the paper's height error: the surface is
        ``A sin(2 pi x / L + a) sin(2 pi y / L + b)`` above the believed plane,
        ``L = wobble_wavelength_mm``; where it sinks deeper than ``press_mm``
        the pen does not touch.
      wobble_wavelength_mm: mm.
      seed: draws the bias, the wobble's phases, and (with the pass index) the
        noise and the skips.
    """

    sheet_offset_mm: tuple[float, float] = (0.0, 0.0)
    sheet_rotation_deg: float = 0.0
    joint_bias_rad: float = 0.0
    joint_noise_rad: float = 0.0
    pen_skip_per_mm: float = 0.0
    skip_length_mm: float = 4.0
    early_lift_mm: float = 0.0
    sheet_wobble_mm: float = 0.0
    wobble_wavelength_mm: float = 60.0
    seed: int = 0

    @property
    def any(self) -> bool:
        """Whether any fault is on."""
        return bool(
            np.any(self.sheet_offset_mm)
            or self.sheet_rotation_deg
            or self.joint_bias_rad
            or self.joint_noise_rad
            or self.pen_skip_per_mm
            or self.early_lift_mm
            or self.sheet_wobble_mm
        )

    def active(self) -> dict:
        """The fields that differ from the defaults (what a report should print)."""
        base = Faults()
        return {
            f.name: getattr(self, f.name)
            for f in dataclasses.fields(self)
            if getattr(self, f.name) != getattr(base, f.name)
        }

    @classmethod
    def parse(cls, text: str | None) -> Faults:
        """``"moderate"``, ``"none"`` or ``name=value,...`` (tuples as ``x:y``).

        A preset may be followed by overrides: ``"moderate,seed=3"``.
        """
        out = cls()
        for part in (text or "").split(","):
            part = part.strip()
            if not part:
                continue
            if "=" not in part:
                if part not in PRESETS:
                    raise ValueError(f"unknown fault preset {part!r}; use {sorted(PRESETS)}")
                out = dataclasses.replace(out, **PRESETS[part].active())
                continue
            name, value = (s.strip() for s in part.split("=", 1))
            fields = {f.name: f for f in dataclasses.fields(cls)}
            if name not in fields:
                raise ValueError(f"unknown fault {name!r}; use {sorted(fields)}")
            default = getattr(cls(), name)
            try:
                if isinstance(default, tuple):
                    parsed = tuple(float(v) for v in value.split(":"))
                    if len(parsed) != len(default):
                        raise ValueError
                elif isinstance(default, int):
                    parsed = int(value)
                else:
                    parsed = float(value)
            except ValueError:
                raise ValueError(f"bad value for {name}: {value!r}") from None
            out = dataclasses.replace(out, **{name: parsed})
        return out


# Moderate settings: each is a few mm (or ~1 mm of tip motion) on a 100 mm sheet.
MODERATE = Faults(
    sheet_offset_mm=(3.0, -2.0),
    sheet_rotation_deg=2.0,
    joint_bias_rad=0.002,
    joint_noise_rad=0.001,
    pen_skip_per_mm=0.01,
    early_lift_mm=3.0,
    sheet_wobble_mm=2.5,
)
PRESETS = {"none": Faults(), "moderate": MODERATE}


def only(name: str, faults: Faults = MODERATE) -> Faults:
    """``faults`` with every fault but ``name`` (a group, see :data:`GROUPS`) switched off."""
    keep = {f: getattr(faults, f) for f in GROUPS[name]}
    return dataclasses.replace(Faults(seed=faults.seed), **keep)


GROUPS = {
    "sheet offset": ("sheet_offset_mm",),
    "sheet rotation": ("sheet_rotation_deg",),
    "joint bias": ("joint_bias_rad",),
    "joint noise": ("joint_noise_rad",),
    "pen skips": ("pen_skip_per_mm", "skip_length_mm"),
    "early lift": ("early_lift_mm",),
    "wobbly sheet": ("sheet_wobble_mm", "wobble_wavelength_mm"),
}


def true_options(options: RobotOptions, faults: Faults) -> RobotOptions:
    """Where the sheet really lies: ``options`` moved by the sheet offset and rotation."""
    center = np.asarray(options.sheet_center) + np.asarray(faults.sheet_offset_mm) / 1000
    return dataclasses.replace(
        options,
        sheet_center=(float(center[0]), float(center[1])),
        sheet_yaw=options.sheet_yaw + float(np.radians(faults.sheet_rotation_deg)),
    )


def sheet_height_mm(canvas_xy: np.ndarray, options: RobotOptions, faults: Faults) -> np.ndarray:
    """``[N]`` mm height of the real paper surface above the believed plane at canvas points."""
    if not faults.sheet_wobble_mm:
        return np.zeros(len(canvas_xy))
    a, b = np.random.default_rng([faults.seed, 7]).uniform(0, 2 * np.pi, 2)
    mm = np.asarray(canvas_xy, np.float64) * np.asarray(options.sheet_size_mm) / 100
    k = 2 * np.pi / faults.wobble_wavelength_mm
    return faults.sheet_wobble_mm * np.sin(k * mm[:, 0] + a) * np.sin(k * mm[:, 1] + b)


def pen_gate(canvas: np.ndarray, down: np.ndarray, mm_per_px, faults: Faults, rng) -> np.ndarray:
    """``bool [T]``: steps where the pen may ink (False inside skips and early lifts).

    Args:
      canvas: ``[T, 2]`` canvas targets of one tip path.
      down: ``[T]`` bool, pen-down steps.
      mm_per_px: ``[2]`` mm per canvas pixel.
      rng: a numpy Generator for the skips.
    """
    ok = np.ones(len(down), bool)
    step = np.zeros(len(down))
    step[1:] = np.linalg.norm(np.diff(canvas, axis=0) * np.asarray(mm_per_px), axis=1)
    idx = np.flatnonzero(down)
    if not len(idx):
        return ok
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    for run in runs:
        travel = step[run] * (np.arange(len(run)) > 0)
        if faults.early_lift_mm > 0:
            left = np.cumsum(travel[::-1])[::-1] - travel  # mm still to go after each step
            if travel.sum() > 0:
                ok[run[left < faults.early_lift_mm]] = False
        if faults.pen_skip_per_mm > 0:
            dry = 0.0
            for k, s in zip(run, travel):
                if dry > 0:
                    ok[k] = False
                    dry -= s
                elif rng.random() < 1 - np.exp(-faults.pen_skip_per_mm * s):
                    ok[k] = False
                    dry = faults.skip_length_mm - s
    return ok


def apply(paths, targets: np.ndarray, options: RobotOptions, faults: Faults, pass_index: int = 0):
    """Turns ``faults`` into rollout inputs for a batch of tip paths.

    Args:
      paths: the :class:`jdraw.robot.trajectory.TipPath` of each image.
      targets: ``[B, T, 3]`` m padded tip targets the planner asks for.
      options: the planner's (believed) sheet placement.
      faults: what is really wrong.
      pass_index: which drawing pass on this sheet (new noise and skips).

    Returns:
      ``(real_options, targets [B, T, 3], ctrl_offset [B, T, 7] rad,
      pen_ok [B, T] bool, log)``; ``log`` is one dict per image of what was
      drawn: the joint bias (rad), mm of pen-down travel lost to skips and to
      early lifts.
    """
    b, t, _ = targets.shape
    targets = targets.copy()
    bias = np.random.default_rng([faults.seed, 1]).normal(0, 1, scene.N_ARM)
    bias = (faults.joint_bias_rad * bias).astype(np.float32)
    ctrl_offset = np.broadcast_to(bias, (b, t, scene.N_ARM)).copy()
    pen_ok = np.ones((b, t), bool)
    mm_per_px = np.asarray(options.sheet_size_mm, np.float64) / 100
    logs = []
    for i, p in enumerate(paths):
        rng = np.random.default_rng([faults.seed, 2, pass_index, i])
        n = p.n_steps
        if faults.joint_noise_rad:
            ctrl_offset[i, :n] += rng.normal(0, faults.joint_noise_rad, (n, scene.N_ARM))
        if faults.sheet_wobble_mm:
            # A surface h higher is the same as the tip target h lower on a flat sheet.
            h = sheet_height_mm(p.canvas, options, faults)
            targets[i, :n, 2] -= (h / 1000).astype(np.float32)
            targets[i, n:, 2] = targets[i, n - 1, 2]
        pen_ok[i, :n] = pen_gate(p.canvas, p.down, mm_per_px, faults, rng)
        step = np.zeros(n)
        step[1:] = np.linalg.norm(np.diff(p.canvas, axis=0) * mm_per_px, axis=1)
        lost = float(np.sum(step * (p.down & ~pen_ok[i, :n])))
        logs.append({"joint_bias_rad": bias.tolist(), "dry_mm": lost})
    return true_options(options, faults), targets, ctrl_offset, pen_ok, logs
