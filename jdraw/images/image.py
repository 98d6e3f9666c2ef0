"""Real images in: load, binarise, skeletonise and fit to the planner's canvas.

The planner sees 1-pixel, 8-connected lines on a ``100 x 100`` canvas (paper
§IV-C). A photo of handwriting has thick anti-aliased strokes, uneven light,
noise and either polarity, so :func:`prepare` turns it into an ink mask and a
centreline skeleton in *input* pixels, and :func:`skeleton_polylines` turns the
skeleton into polylines. Those polylines, not a resized bitmap, are what gets
drawn onto a canvas (with :func:`jdraw.geometry.render_strokes`, the one line
rule), so the scale can be chosen freely and every canvas point maps back to
input pixels through a kept :class:`CanvasTransform`.

Coordinates are ``(x, y)``: ``x`` the column, ``y`` the row, pixel centres at
integers, as in :mod:`jdraw.geometry`.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Sequence

import cv2
import numpy as np
from skimage import filters, measure, morphology

from jdraw import geometry as raster

CANVAS = raster.CANVAS
# A KanjiVG character spans about this many canvas pixels.
CHAR_EXTENT = 80

_OFFSETS = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))  # (dy, dx)


class ImageError(ValueError):
    """An input image that cannot be used: unreadable, unsupported or blank."""


class BlankImageError(ImageError):
    """No ink was found in the image."""


# ----------------------------------------------------------------------------- loading


def load_image(path: str | os.PathLike) -> np.ndarray:
    """Reads an image file as it is stored.

    Returns:
      ``uint8`` or ``uint16`` ``[H, W]``, ``[H, W, 3]`` (RGB) or ``[H, W, 4]`` (RGBA).

    Raises:
      ImageError: missing file, a format OpenCV cannot read, or undecodable data.
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ImageError(f"cannot read {path!r}: no such file")
    if os.path.isdir(path):
        raise ImageError(f"cannot read {path!r}: it is a directory")
    if os.path.getsize(path) == 0:
        raise ImageError(f"cannot read {path!r}: the file is empty")
    if not cv2.haveImageReader(path):
        raise ImageError(
            f"cannot read {path!r}: unsupported image format "
            "(use PNG, JPEG, GIF, BMP, TIFF, WebP or PBM/PGM/PPM)"
        )
    img = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if img is None or img.size == 0:
        raise ImageError(f"cannot read {path!r}: the image data could not be decoded")
    if img.ndim == 3 and img.shape[2] == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2RGB)
    elif img.ndim == 3 and img.shape[2] == 4:
        img = cv2.cvtColor(img, cv2.COLOR_BGRA2RGBA)
    return img


def to_gray(image: np.ndarray) -> np.ndarray:
    """Luminance in ``[0, 1]``: ``float32 [H, W]``.

    Accepts ``bool`` (true = ink, drawn dark on white), integer or float
    ``[H, W]``, ``[H, W, 1]``, RGB ``[H, W, 3]`` or RGBA ``[H, W, 4]``; transparent
    pixels are composited onto white.
    """
    img = np.asarray(image)
    if img.ndim == 3 and img.shape[2] == 1:
        img = img[..., 0]
    if img.ndim not in (2, 3) or (img.ndim == 3 and img.shape[2] not in (3, 4)):
        raise ImageError(f"expected a [H, W], [H, W, 3] or [H, W, 4] image, got shape {img.shape}")
    if min(img.shape[:2]) < 2:
        raise ImageError(f"image too small: {img.shape[1]} x {img.shape[0]} pixels")
    if img.dtype == bool:
        return np.where(img, 0.0, 1.0).astype(np.float32)
    if np.issubdtype(img.dtype, np.integer):
        f = img.astype(np.float32) / float(np.iinfo(img.dtype).max)
    else:
        f = np.nan_to_num(img.astype(np.float32))
        lo, hi = float(f.min()), float(f.max())
        if lo < 0.0 or hi > 1.0:
            f = (f - lo) / max(hi - lo, 1e-12)
    if f.ndim == 2:
        return f
    gray = f[..., 0] * 0.299 + f[..., 1] * 0.587 + f[..., 2] * 0.114
    if f.shape[2] == 4:
        gray = f[..., 3] * gray + (1.0 - f[..., 3])
    return gray.astype(np.float32)


# ----------------------------------------------------------------------------- binarising


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
    d = gray - _median_background(gray)
    d = d - d.mean()
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


def _poly_terms(x: np.ndarray, y: np.ndarray, powers: list[tuple[int, int]]) -> np.ndarray:
    return np.stack([x**i * y**j for i, j in powers], -1)


def background(gray: np.ndarray, polarity: str, degree: int = 3) -> np.ndarray:
    """The ground's brightness under the ink: ``float32 [H, W]``.

    A cubic in (x, y) fitted to a small copy of the image, refitted a few
    times without the pixels that lie on the ink side of it (a robust fit):
    lighting gradients, vignetting and soft shadows are smooth, ink is not.
    Unlike a blur, the fit does not bend towards the interior at the borders.
    """
    h, w = gray.shape
    # Each axis shrinks on its own: a long thin strip keeps its short side, so a
    # line along it is not averaged into the ground.
    sw, sh = max(2, min(w, 128)), max(2, min(h, 128))
    small = cv2.resize(gray, (sw, sh), interpolation=cv2.INTER_AREA).ravel().astype(np.float64)
    ys, xs = np.mgrid[0:sh, 0:sw]
    powers = _poly_powers(degree, w, h)
    terms = _poly_terms(xs.ravel() / (sw - 1) * 2 - 1, ys.ravel() / (sh - 1) * 2 - 1, powers)
    sign = 1.0 if polarity == "light" else -1.0
    keep = np.ones(small.shape, bool)
    for _ in range(5):
        coef = np.linalg.lstsq(terms[keep], small[keep], rcond=None)[0]
        r = small - terms @ coef
        spread = 1.4826 * np.median(np.abs(r[keep] - np.median(r[keep]))) + 1e-4
        ink = (sign * r > 2.0 * spread).reshape(sh, sw).astype(np.uint8)
        new_keep = ~cv2.dilate(ink, np.ones((3, 3), np.uint8)).astype(bool).ravel()
        if new_keep.sum() < terms.shape[1] * 4:
            break
        keep = new_keep
    # Evaluate on the full grid: pixel centres mapped to the small image's frame.
    gx = ((np.arange(w) + 0.5) * sw / w - 0.5) / (sw - 1) * 2 - 1
    gy = ((np.arange(h) + 0.5) * sh / h - 0.5) / (sh - 1) * 2 - 1
    out = np.zeros((h, w))
    for c, (i, j) in zip(coef, powers):
        out += c * np.outer(gy**j, gx**i)
    return out.astype(np.float32)


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
    g = cv2.GaussianBlur(gray.astype(np.float32), (0, 0), 1.0)
    bg = background(g, polarity)
    sign = -1.0 if polarity == "light" else 1.0
    contrast = sign * (1.0 - g / np.maximum(bg, 0.02))
    ink0 = contrast > filters.threshold_otsu(contrast)
    ground = (~cv2.dilate(ink0.astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)).astype(
        np.float32
    )
    if ground.mean() > 0.05:
        contrast = contrast - _masked_blur(contrast, ground, max(g.shape) / 10.0)
        ink0 = contrast > filters.threshold_otsu(contrast)
    background_px = contrast[~ink0]
    if not ink0.any() or background_px.size == 0:
        raise BlankImageError("no ink found (the image is blank)")
    level = float(np.median(contrast[ink0]))
    noise = 1.4826 * float(np.median(np.abs(background_px - np.median(background_px))))
    base = float(np.median(background_px))
    if level - base < max(0.06, 6.0 * noise):
        raise BlankImageError("no ink found (nothing stands out from the background)")
    return contrast > base + 0.5 * (level - base), polarity


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
        skeleton = morphology.skeletonize(ink)
    dist = ink_distance(ink)
    return max(1.0, 2.0 * float(np.median(dist[skeleton])) - 1.0)


def denoise(ink: np.ndarray, width: float) -> np.ndarray:
    """Drops specks and fills pinholes smaller than about half a stroke-width square."""
    area = max(6, int(0.6 * width * width))
    n, labels, stats, _ = cv2.connectedComponentsWithStats(ink.astype(np.uint8), connectivity=8)
    big = stats[:, cv2.CC_STAT_AREA] >= area
    big[0] = False
    ink = big[labels]
    return morphology.remove_small_holes(ink, max_size=area)


# ----------------------------------------------------------------------------- skeleton graph


def _neighbour_table(skel: np.ndarray):
    """Pixels of ``skel`` and their neighbours, without staircase shortcuts.

    A diagonal link whose corner pixel is also on the skeleton is dropped, so a
    staircase is a path and not a chain of triangles.
    """
    ys, xs = np.nonzero(skel)
    index = np.full(skel.shape, -1, np.int64)
    index[ys, xs] = np.arange(len(ys))
    pad = np.pad(skel, 1)
    nbrs: list[list[int]] = [[] for _ in range(len(ys))]
    h, w = skel.shape
    for dy, dx in _OFFSETS:
        ok = pad[ys + 1 + dy, xs + 1 + dx]
        if dy and dx:
            ok &= ~pad[ys + 1, xs + 1 + dx] & ~pad[ys + 1 + dy, xs + 1]
        for i in np.nonzero(ok)[0]:
            nbrs[i].append(int(index[ys[i] + dy, xs[i] + dx]))
    return np.stack([xs, ys], 1), nbrs


def _trace(nbrs: list[list[int]]) -> list[list[int]]:
    """Splits a pixel graph into chains between nodes (degree != 2), then cycles."""
    deg = [len(n) for n in nbrs]
    seen_edges: set[tuple[int, int]] = set()
    chains = []

    def walk(a: int, b: int) -> list[int]:
        path = [a, b]
        seen_edges.add((a, b))
        seen_edges.add((b, a))
        prev, cur = a, b
        while deg[cur] == 2:
            nxt = nbrs[cur][0] if nbrs[cur][0] != prev else nbrs[cur][1]
            if (cur, nxt) in seen_edges:
                break
            seen_edges.add((cur, nxt))
            seen_edges.add((nxt, cur))
            path.append(nxt)
            prev, cur = cur, nxt
        return path

    for i, d in enumerate(deg):
        if d == 0:
            chains.append([i])
        elif d != 2:
            for j in nbrs[i]:
                if (i, j) not in seen_edges:
                    chains.append(walk(i, j))
    for i, d in enumerate(deg):
        if d == 2 and (i, nbrs[i][0]) not in seen_edges:
            chains.append(walk(i, nbrs[i][0]))
    return chains


def prune_spurs(skel: np.ndarray, dist: np.ndarray, width: float, rounds: int = 3) -> np.ndarray:
    """Removes noise spurs: end branches off a junction that run out to the ink's edge.

    A branch no longer than ``width`` whose free end is nearer the edge than
    half the stroke's radius comes from a bump in the outline; the true end
    of a stroke sits about a radius inside the outline (the centre of its
    round cap) and is kept.

    Args:
      skel: ``bool [H, W]`` skeleton.
      dist: ``float [H, W]`` distance of each ink pixel to the ground.
      width: typical stroke width, pixels.
    """
    skel = skel.copy()
    edge = 0.25 * width
    for _ in range(rounds):
        pts, nbrs = _neighbour_table(skel)
        deg = np.array([len(n) for n in nbrs])
        removed = False
        for chain in _trace(nbrs):
            a, b = deg[chain[0]], deg[chain[-1]]
            if len(chain) < 2 or len(chain) > width:
                continue
            if (a == 1 and b >= 3) or (b == 1 and a >= 3):
                tip = pts[chain[0]] if a == 1 else pts[chain[-1]]
                if dist[tip[1], tip[0]] >= edge:
                    continue
                body = chain[:-1] if b >= 3 else chain[1:]
                skel[pts[body, 1], pts[body, 0]] = False
                removed = True
        if not removed:
            break
    return morphology.skeletonize(skel)


def extend_ends(
    polylines: list[np.ndarray], skel: np.ndarray, dist: np.ndarray, width: float
) -> list[np.ndarray]:
    """Carries each free end of the skeleton on to the centre of the stroke's cap.

    Thinning stops short of a stroke's end, most of all at a sharp turn where
    the outline is blunt. The end is moved along its direction while the ink
    there is still as thick as the stroke (distance to the ground at least
    the stroke's radius), at most one stroke width.
    """
    pts, nbrs = _neighbour_table(skel)
    ends = {(int(p[0]), int(p[1])) for p, n in zip(pts, nbrs, strict=True) if len(n) == 1}
    radius = width / 2.0
    h, w = dist.shape
    out = []
    for line in polylines:
        p = np.asarray(line, np.float64)
        if len(p) >= 3:
            for first in (True, False):
                q = p if not first else p[::-1]
                end = q[-1]
                if (int(end[0]), int(end[1])) not in ends:
                    continue
                back = q[max(0, len(q) - 1 - int(np.ceil(width)))]
                d = end - back
                n = np.hypot(*d)
                if n < 1e-6:
                    continue
                d /= n
                best = None
                for t in np.arange(0.5, width + 0.5, 0.5):
                    x, y = np.round(end + t * d).astype(int)
                    if not (0 <= x < w and 0 <= y < h) or dist[y, x] < radius - 0.5:
                        break
                    best = end + t * d
                if best is not None:
                    q = np.concatenate([q, best[None]])
                p = q if not first else q[::-1]
        out.append(p)
    return out


def skeleton_polylines(skel: np.ndarray) -> list[np.ndarray]:
    """Pixel chains of a 1-pixel skeleton: ``[n, 2]`` int (x, y) arrays.

    Chains run between end points and junctions; a closed loop is traced from
    an arbitrary pixel back to it (first point = last). A lone pixel is a
    one-point chain.
    """
    pts, nbrs = _neighbour_table(np.asarray(skel, bool))
    return [pts[c] for c in _trace(nbrs)]


def simplify(points: np.ndarray, tol: float) -> np.ndarray:
    """Ramer-Douglas-Peucker: drops points within ``tol`` of the kept polyline.

    Distances are to the kept *segments* (``skimage.measure.approximate_polygon``),
    so a stroke that doubles back keeps its turning point.
    """
    pts = np.asarray(points, np.float64)
    if len(pts) < 3 or tol <= 0:
        return pts
    return measure.approximate_polygon(pts, tol)


# ----------------------------------------------------------------------------- preparing


@dataclasses.dataclass
class Prepared:
    """A real image reduced to centrelines, in input pixels.

    Attributes:
      shape: ``(H, W)`` of the input.
      ink: ``bool [H, W]`` binarised, denoised ink.
      skeleton: ``bool [H, W]`` 1-pixel centrelines of ``ink``.
      polylines: skeleton chains, ``[n, 2]`` float (x, y), lightly simplified.
      width: typical stroke width, pixels.
      polarity: ``"dark"`` or ``"light"`` ink.
    """

    shape: tuple[int, int]
    ink: np.ndarray
    skeleton: np.ndarray
    polylines: list[np.ndarray]
    width: float
    polarity: str


def prepare(image: np.ndarray, *, polarity: str = "auto") -> Prepared:
    """Grayscale, binarise, denoise and skeletonise an image of any size.

    Args:
      image: anything :func:`to_gray` accepts.
      polarity: ``"auto"``, ``"dark"`` or ``"light"`` ink.

    Raises:
      ImageError: bad shape; BlankImageError: no ink.
    """
    gray = to_gray(image)
    ink, polarity = binarize(gray, polarity)
    width = stroke_width(ink)
    ink = denoise(ink, width)
    if not ink.any():
        raise BlankImageError("no ink found (only specks of noise)")
    skel = morphology.skeletonize(ink)
    width = stroke_width(ink, skel)
    polylines = skeleton_polylines(skel)
    if width > 2:
        dist = ink_distance(ink)
        skel = prune_spurs(skel, dist, width)
        polylines = extend_ends(skeleton_polylines(skel), skel, dist, width)
    polylines = [simplify(p, 0.5) for p in polylines]
    return Prepared(gray.shape, ink, skel, polylines, width, polarity)


@dataclasses.dataclass(frozen=True)
class CanvasTransform:
    """Uniform scale and shift from input pixels to canvas pixels: ``c = scale * p + offset``."""

    scale: float
    offset: tuple[float, float] = (0.0, 0.0)

    def to_canvas(self, points: np.ndarray) -> np.ndarray:
        """``[..., 2]`` (x, y) input pixels to canvas pixels."""
        return np.asarray(points, np.float64) * self.scale + np.asarray(self.offset)

    def to_input(self, points: np.ndarray) -> np.ndarray:
        """``[..., 2]`` (x, y) canvas pixels to input pixels."""
        return (np.asarray(points, np.float64) - np.asarray(self.offset)) / self.scale

    def shifted(self, dx: float, dy: float) -> CanvasTransform:
        """The same map followed by ``c -> c - (dx, dy)`` (a crop at ``(dx, dy)``)."""
        return CanvasTransform(self.scale, (self.offset[0] - dx, self.offset[1] - dy))

    @property
    def matrix(self) -> np.ndarray:
        """``[2, 3]`` affine matrix (input -> canvas), as ``cv2.warpAffine`` takes."""
        s = self.scale
        return np.array([[s, 0.0, self.offset[0]], [0.0, s, self.offset[1]]])


def render_polylines(
    polylines: Sequence[np.ndarray], transform: CanvasTransform, shape: tuple[int, int]
) -> np.ndarray:
    """Draws input-pixel polylines onto a canvas of ``shape`` as thin 8-connected lines.

    The lines are rasterised with :func:`jdraw.geometry.render_strokes` and the
    staircase corners this leaves are thinned away, so the result is what the
    planner is trained on. Returns ``bool [H, W]``.
    """
    tol = 0.35 / transform.scale
    canvas_lines = [transform.to_canvas(simplify(p, tol)) for p in polylines]
    img = raster.render_strokes(canvas_lines, shape)
    return morphology.skeletonize(img) if img.any() else img


def fit_transform(
    bbox: tuple[float, float, float, float], extent: float = CHAR_EXTENT, size: int = CANVAS
) -> CanvasTransform:
    """Scale and shift putting ``bbox = (x0, y0, x1, y1)`` centred in a ``size`` canvas,
    its longer side ``extent`` pixels long (aspect kept)."""
    x0, y0, x1, y1 = bbox
    s = extent / max(x1 - x0, y1 - y0, 1.0)
    c = (size - 1) / 2.0
    return CanvasTransform(s, (c - s * (x0 + x1) / 2.0, c - s * (y0 + y1) / 2.0))


def ink_bbox(polylines: Sequence[np.ndarray]) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)`` of all points."""
    allp = np.concatenate([np.asarray(p, np.float64).reshape(-1, 2) for p in polylines])
    return (*allp.min(0), *allp.max(0))


def to_canvas(
    image: np.ndarray, *, polarity: str = "auto", extent: float = CHAR_EXTENT
) -> tuple[np.ndarray, CanvasTransform, Prepared]:
    """A character-sized image as the planner's input, with the transform kept.

    Returns:
      ``(bool [100, 100] canvas, transform input -> canvas, Prepared)``.
    """
    prep = prepare(image, polarity=polarity)
    tf = fit_transform(ink_bbox(prep.polylines), extent)
    return render_polylines(prep.polylines, tf, (CANVAS, CANVAS)), tf, prep


# ----------------------------------------------------------------------------- synthetic photos


def photo_like(
    centrelines: Sequence[np.ndarray],
    shape: tuple[int, int],
    *,
    width: float = 6.0,
    light_ink: bool = False,
    gradient: float = 0.5,
    noise: float = 0.05,
    seed: int = 0,
) -> np.ndarray:
    """A photo-like image of pen strokes with known centrelines, for tests and demos.

    The strokes are drawn anti-aliased at sub-pixel precision with round caps,
    the page is lit by a linear gradient (brightness falls by ``gradient`` of
    its peak across the image) plus a soft blotch, and Gaussian noise is added.

    Args:
      centrelines: ``[n, 2]`` float (x, y) polylines in pixels.
      shape: ``(H, W)``.
      width: stroke width, pixels.
      light_ink: chalk on a board instead of ink on paper.
      gradient: fraction of the brightness lost across the image.
      noise: standard deviation of the added noise, in ``[0, 1]`` brightness.

    Returns:
      ``uint8 [H, W]``.
    """
    h, w = shape
    shift = 4
    cover = np.zeros(shape, np.uint8)
    for line in centrelines:
        p = np.round(np.asarray(line, np.float64) * (1 << shift)).astype(np.int32).reshape(-1, 1, 2)
        thickness = max(1, int(round(width)))
        cv2.polylines(cover, [p], False, 255, thickness, cv2.LINE_AA, shift)
    a = cover.astype(np.float32) / 255
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    angle = rng.uniform(0, 2 * np.pi)
    ramp = (np.cos(angle) * xx / w + np.sin(angle) * yy / h) + 1.0
    ramp = ramp / max(float(ramp.max()), 1e-6)
    cx, cy = rng.uniform(0, w), rng.uniform(0, h)
    blotch = np.exp(-((xx - cx) ** 2 + (yy - cy) ** 2) / (2 * (0.3 * max(h, w)) ** 2))
    light = 1.0 - gradient * (1.0 - ramp) - 0.1 * blotch
    if light_ink:
        ground, ink = 0.25 * light, 0.9 * light
    else:
        ground, ink = 0.95 * light, 0.15 * light
    img = ground * (1 - a) + ink * a + rng.normal(0.0, noise, shape).astype(np.float32)
    return (np.clip(img, 0, 1) * 255).round().astype(np.uint8)


def centreline_scores(
    strokes: Sequence[np.ndarray], reference: Sequence[np.ndarray], tol: float = 4.0
) -> tuple[float, float]:
    """Precision and recall of drawn strokes against reference centrelines.

    Both are sampled every 0.25 pixel; precision is the fraction of stroke
    samples within ``tol`` pixels of a reference sample, recall the fraction
    of reference samples within ``tol`` of a stroke sample.
    """
    from scipy.spatial import cKDTree

    a, b = _sample(strokes), _sample(reference)
    if len(a) == 0 or len(b) == 0:
        return 0.0, 0.0
    precision = float(np.mean(cKDTree(b).query(a, distance_upper_bound=tol)[0] <= tol))
    recall = float(np.mean(cKDTree(a).query(b, distance_upper_bound=tol)[0] <= tol))
    return precision, recall


def _sample(lines: Sequence[np.ndarray], step: float = 0.25) -> np.ndarray:
    out = []
    for line in lines:
        p = np.asarray(line, np.float64).reshape(-1, 2)
        out.append(p[:1])
        for a, b in zip(p[:-1], p[1:], strict=True):
            n = max(1, int(np.ceil(np.hypot(*(b - a)) / step)))
            t = np.arange(1, n + 1)[:, None] / n
            out.append(a + t * (b - a))
    return np.concatenate(out) if out else np.zeros((0, 2))


def text_centrelines(
    text: str, font_scale: float, *, script: bool = True, margin: float = 0.3
) -> tuple[list[np.ndarray], tuple[int, int]]:
    """Centrelines of ``text`` in an OpenCV Hershey stroke font, for tests and demos.

    Returns:
      ``(polylines [n, 2] float (x, y), (H, W))``: the text set on one line
      with a margin of ``margin`` times the text height.
    """
    font = cv2.FONT_HERSHEY_SCRIPT_SIMPLEX if script else cv2.FONT_HERSHEY_SIMPLEX
    (tw, th), base = cv2.getTextSize(text, font, font_scale, 1)
    m = int(margin * th) + 4
    shape = (th + base + 2 * m, tw + 2 * m)
    img = np.zeros(shape, np.uint8)
    cv2.putText(img, text, (m, m + th), font, font_scale, 255, 1, cv2.LINE_8)
    lines = skeleton_polylines(morphology.skeletonize(img > 0))
    return [p.astype(np.float64) for p in lines], shape
