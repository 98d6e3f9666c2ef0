"""Start-up: what ``import jdraw`` and the command line load before they need it."""

import json
import subprocess
import sys

import numpy as np
from skimage.measure import approximate_polygon

from jdraw.images.skeleton import simplify

HEAVY = ("jax", "flax", "scipy", "skimage", "mujoco", "orbax", "optax", "cv2")


def _loaded(code: str) -> list[str]:
    out = subprocess.run(
        [sys.executable, "-c", f"import sys, json\n{code}\nprint(json.dumps(sorted(sys.modules)))"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    mods = json.loads(out.stdout.strip().splitlines()[-1])
    return sorted({m.split(".")[0] for m in mods} & set(HEAVY))


def test_import_jdraw_loads_nothing_heavy():
    assert _loaded("import jdraw") == []
    # A public name loads what it needs, on first use.
    assert "jax" in _loaded("import jdraw\njdraw.plan")


def test_command_line_checks_options_without_jax():
    """``jdraw.cli`` and the image header check (the pixel limit) need no JAX or Flax."""
    loaded = _loaded("import jdraw.cli, jdraw.images.load, jdraw.io.jobs")
    assert "jax" not in loaded and "flax" not in loaded and "scipy" not in loaded


def test_simplify_keeps_the_points_scikit_image_keeps(rng):
    """Our Ramer-Douglas-Peucker against ``skimage.measure.approximate_polygon``: identical."""
    for _ in range(400):
        m = int(rng.integers(3, 50))
        pts = np.cumsum(rng.integers(-1, 2, (m, 2)), 0).astype(np.float64)
        if rng.random() < 0.3:
            pts += rng.random((m, 2))
        for tol in (0.5, 1.0, 2.0):
            np.testing.assert_array_equal(simplify(pts, tol), approximate_polygon(pts, tol))
