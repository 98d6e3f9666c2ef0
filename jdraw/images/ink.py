"""Finding the ink: polarity, the ground's brightness, the threshold, stroke width, specks.

A photo of handwriting has thick anti-aliased strokes, uneven light, noise and
either polarity; :func:`binarize` turns its luminance into an ink mask that
holds up under all of them.
"""

from __future__ import annotations

import cv2
import numpy as np

from jdraw.images import morph
from jdraw.images.load import BlankImageError


def _odd(n: float) -> int:
    n = max(3, int(round(n)))
    return n if n % 2 else n + 1


def _median_background(gray: np.ndarray) -> np.ndarray:
    """Large-window median: the paper's (or board's) brightness under sparse ink."""
    h, w = gray.shape
    small = cv2.resize(gray, (min(w, 256), min(h, 256)), interpolation=cv2.INTER_AREA)
    k = min(
        _odd(max(small.shape) / 6), 2 * (min(small.shape) // 2) - 1 if min(small.shape) > 2 else 3
    )
    med = cv2.medianBlur((small * 255).round().astype(np.uint8), max(3, k)).astype(np.float32) / 255
    return cv2.resize(med, (w, h), interpolation=cv2.INTER_LINEAR)


def detect_polarity(gray: np.ndarray) -> str:
    """``"dark"`` for dark ink on a light ground, ``"light"`` for light on dark.

    Ink is the sparse, far-from-background tail of the brightness distribution
    once the slowly varying background is removed; its sign is the skew's.
    """
    d = _median_background(gray)
    np.subtract(gray, d, out=d)  # in place: big images hold fewer full-size copies
    d -= d.mean()
    skew = float(np.mean(d**3)) / max(float(np.mean(d**2)) ** 1.5, 1e-12)
    return "light" if skew > 0 else "dark"


def _masked_blur(values: np.ndarray, weights: np.ndarray, sigma: float) -> np.ndarray:
    """Gaussian average of ``values`` over pixels with ``weights``; wide blurs run on a
    small copy (what they keep is smooth anyway)."""
    h, w = values.shape
    f = min(1.0, 4.0 / sigma)
    size = (max(2, round(w * f)), max(2, round(h * f)))
    vw = values * weights
    if f < 1.0:
        vw = cv2.resize(vw, size, interpolation=cv2.INTER_AREA)
        weights = cv2.resize(weights, size, interpolation=cv2.INTER_AREA)
    num = cv2.GaussianBlur(vw, (0, 0), sigma * f)
    den = cv2.GaussianBlur(weights, (0, 0), sigma * f)
    out = num / np.maximum(den, 1e-6)
    return cv2.resize(out, (w, h), interpolation=cv2.INTER_LINEAR) if f < 1.0 else out


def _poly_powers(degree: int, w: int, h: int) -> list[tuple[int, int]]:
    """``(i, j)`` powers of ``x**i * y**j``: total degree ``<= degree``, and fewer
    across a long thin image's short side, over which lighting barely changes
    (else a cubic across 20 rows bends into a line along them)."""
    aspect = min(w, h) / max(w, h)
    short = min(degree, int(4 * degree * aspect))
    dx, dy = (degree, short) if w >= h else (short, degree)
    return [(i, j) for i in range(degree + 1) for j in range(degree + 1 - i) if i <= dx and j <= dy]


def _fit(t: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Least-squares coefficients of ``t @ coef ~ v`` for a few terms and many points.

    The normal equations, summed by einsum rather than BLAS: a system of at most
    10 x 10, where BLAS's threads would fight the planner's for the cores (a
    quarter of a second per image in a set instead of a few ms). Too few points,
    or points on which the terms are not independent (a 2 x 2 image), go to
    ``lstsq``'s minimum-norm solution.
    """
    if len(t) >= 4 * t.shape[1]:
        try:
            return np.linalg.solve(np.einsum("ni,nj->ij", t, t), np.einsum("ni,n->i", t, v))
        except np.linalg.LinAlgError:
            pass
    return np.linalg.lstsq(t, v, rcond=None)[0]


def _grid_fit(v: np.ndarray, keep: np.ndarray, xp: np.ndarray, yp: np.ndarray, powers):
    """:func:`_fit` of the terms ``x**i * y**j`` to ``v [sh, sw]`` at the grid points ``keep``.

    ``xp [sw, k]``, ``yp [sh, k]``: the powers 0..k-1 of each column's x and
    each row's y. On a grid, every sum of the normal equations is a sum of
    ``x**a * y**b`` over the kept points, and all of them come from two small
    products (``yp.T @ keep @ xp``), so no ``[points, terms]`` matrix is made.
    Too few kept points, or a singular system, go to :func:`_fit` on the terms.
    """
    k = keep.astype(np.float64)
    if k.sum() >= 4 * len(powers):
        m = np.einsum("yb,ya->ba", yp, np.einsum("yx,xa->ya", k, xp))
        r = np.einsum("yb,ya->ba", yp, np.einsum("yx,xa->ya", k * v, xp))
        i, j = np.array(powers).T
        try:
            return np.linalg.solve(m[j[:, None] + j, i[:, None] + i], r[j, i])
        except np.linalg.LinAlgError:
            pass
    t = np.stack([np.outer(yp[:, j], xp[:, i]).ravel() for i, j in powers], -1)
    return _fit(t[keep.ravel()], v.ravel()[keep.ravel()])


def _grid_eval(coef: np.ndarray, powers, xp: np.ndarray, yp: np.ndarray) -> np.ndarray:
    """``sum coef * x**i * y**j`` on the grid of ``xp [w, k]`` and ``yp [h, k]``: ``[h, w]``."""
    c = np.zeros((yp.shape[1], xp.shape[1]))
    for v, (i, j) in zip(coef, powers):
        c[j, i] = v
    return np.einsum("ya,xa->yx", np.einsum("yb,ba->ya", yp, c), xp)  # einsum: no BLAS threads


def background(gray: np.ndarray, polarity: str, degree: int = 3, heavy: bool = False) -> np.ndarray:
    """The ground's brightness under the ink: ``float32 [H, W]``.

    A cubic in (x, y) fitted to a small copy of the image, refitted a few
    times without the pixels that lie on the ink side of it (a robust fit):
    lighting gradients, vignetting and soft shadows are smooth, ink is not.
    Unlike a blur, the fit does not bend towards the interior at the borders.

    ``heavy``: the first fit leaves out the ink side of Otsu's threshold. Ink that
    covers much of the image (a bold font's word, 40% ink) pulls a first fit through
    every pixel so close that no ink stands clear of it, and no refit drops any.
    """
    h, w = gray.shape
    # Each axis shrinks on its own: a long thin strip keeps its short side, so a
    # line along it is not averaged into the ground.
    sw, sh = max(2, min(w, 128)), max(2, min(h, 128))
    small = cv2.resize(gray, (sw, sh), interpolation=cv2.INTER_AREA).astype(np.float64)
    powers = _poly_powers(degree, w, h)
    n = 2 * degree + 1  # the normal equations hold products of two terms
    xp = (np.arange(sw) / (sw - 1) * 2 - 1)[:, None] ** np.arange(n)
    yp = (np.arange(sh) / (sh - 1) * 2 - 1)[:, None] ** np.arange(n)
    sign = 1.0 if polarity == "light" else -1.0
    keep = np.ones(small.shape, bool)
    if heavy:
        ground = sign * small < sign * morph.otsu(small)
        keep = ground if ground.sum() >= len(powers) * 4 else keep
    for _ in range(5):
        coef = _grid_fit(small, keep, xp, yp, powers)
        r = small - _grid_eval(coef, powers, xp, yp)
        spread = 1.4826 * np.median(np.abs(r[keep] - np.median(r[keep]))) + 1e-4
        ink = (sign * r > 2.0 * spread).astype(np.uint8)
        new_keep = ~cv2.dilate(ink, np.ones((3, 3), np.uint8)).astype(bool)
        if new_keep.sum() < len(powers) * 4:
            break
        keep = new_keep
    # Evaluate on the full grid: pixel centres mapped to the small image's frame.
    gx = ((np.arange(w) + 0.5) * sw / w - 0.5) / (sw - 1) * 2 - 1
    gy = ((np.arange(h) + 0.5) * sh / h - 0.5) / (sh - 1) * 2 - 1
    gxp, gyp = gx[:, None] ** np.arange(n), gy[:, None] ** np.arange(n)
    out = np.empty((h, w), np.float32)
    rows = max(1, (1 << 22) // w)  # float64 sums over bands of ~32 MB, not the whole image
    for r0 in range(0, h, rows):
        out[r0 : r0 + rows] = _grid_eval(coef, powers, gxp, gyp[r0 : r0 + rows])
    return out


def binarize(gray: np.ndarray, polarity: str = "auto") -> tuple[np.ndarray, str]:
    """Ink mask robust to uneven lighting and noise.

    The image is divided by the ground's brightness (:func:`background`), so
    that a lighting gradient cancels (light falls on ink and ground alike:
    their ratio is constant), the remaining slow drift is removed with a blur
    over ground pixels, and the result is thresholded halfway between the
    ground and the typical ink contrast, which puts the mask's edge where an
    anti-aliased stroke's edge is.

    Args:
      gray: ``float32 [H, W]`` in ``[0, 1]``.
      polarity: ``"auto"``, ``"dark"`` (dark ink) or ``"light"`` (light ink).

    Returns:
      ``(bool [H, W] ink, polarity)``.

    Raises:
      BlankImageError: when no ink stands out from the background and noise.
    """
    if polarity not in ("auto", "dark", "light"):
        raise ValueError(f"polarity must be 'auto', 'dark' or 'light', got {polarity!r}")
    if polarity == "auto":
        polarity = detect_polarity(gray)
    try:
        return _mask(gray, polarity), polarity
    except BlankImageError:
        # Ink over much of the image can hide under the ground's first fit.
        return _mask(gray, polarity, heavy=True), polarity


def _mask(gray: np.ndarray, polarity: str, heavy: bool = False) -> np.ndarray:
    """:func:`binarize`'s mask for a known polarity (``heavy``: :func:`background`'s)."""
    g = cv2.GaussianBlur(np.asarray(gray, np.float32), (0, 0), 1.0)
    # contrast = sign * (1 - g / max(bg, 0.02)), computed in place: the same float32
    # values with one full-size array instead of four (a 100 Mpx scan is 400 MB each).
    contrast = background(g, polarity, heavy=heavy)
    np.maximum(contrast, 0.02, out=contrast)
    np.divide(g, contrast, out=contrast)
    np.subtract(1.0, contrast, out=contrast)
    if polarity == "light":
        np.negative(contrast, out=contrast)
    shape = g.shape
    del g
    ink0 = contrast > morph.otsu(contrast)
    ground = (~cv2.dilate(ink0.astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)).astype(
        np.float32
    )
    if ground.mean() > 0.05:
        contrast -= _masked_blur(contrast, ground, max(shape) / 10.0)
        ink0 = contrast > morph.otsu(contrast)
    del ground
    background_px = contrast[~ink0]
    if not ink0.any() or background_px.size == 0:
        raise BlankImageError("no ink found (the image is blank)")
    level = float(np.median(contrast[ink0]))
    # Medians reorder their (own, temporary) input in place rather than copy it.
    med = np.median(background_px, overwrite_input=True)
    base = float(med)
    np.abs(np.subtract(background_px, med, out=background_px), out=background_px)
    noise = 1.4826 * float(np.median(background_px, overwrite_input=True))
    del background_px
    if level - base < max(0.06, 6.0 * noise):
        raise BlankImageError("no ink found (nothing stands out from the background)")
    return contrast > base + 0.5 * (level - base)


def ink_distance(ink: np.ndarray) -> np.ndarray:
    """Distance from each ink pixel to the ground: ``float32 [H, W]``.

    Outside the frame counts as ground, so an image that is all ink has finite
    distances (OpenCV gives a huge sentinel where no ground pixel exists).
    """
    pad = np.pad(ink.astype(np.uint8), 1)
    return cv2.distanceTransform(pad, cv2.DIST_L2, 5)[1:-1, 1:-1]


def stroke_width(ink: np.ndarray, skeleton: np.ndarray | None = None) -> float:
    """Typical stroke width in pixels: twice the median distance to the ground on the skeleton."""
    if not ink.any():
        return 1.0
    if skeleton is None:
        skeleton = morph.skeletonize(ink)
    dist = ink_distance(ink)
    return max(1.0, 2.0 * float(np.median(dist[skeleton])) - 1.0)


def denoise(ink: np.ndarray, width: float) -> np.ndarray:
    """Drops specks and fills pinholes smaller than about half a stroke-width square."""
    area = max(6, int(0.6 * width * width))
    n, labels, stats, _ = cv2.connectedComponentsWithStats(ink.astype(np.uint8), connectivity=8)
    big = stats[:, cv2.CC_STAT_AREA] >= area
    big[0] = False
    ink = big[labels]
    return morph.fill_small_holes(ink, area)
