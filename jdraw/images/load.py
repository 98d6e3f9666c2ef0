"""Reading an image file and reducing it to luminance.

Accepts what people have: PNG, JPEG, GIF, BMP, TIFF, WebP, PBM/PGM/PPM; gray,
RGB or RGBA; 8 or 16 bits, floats or booleans. Errors say what is wrong with
the file in one line (:class:`ImageError`, a ``ValueError``).
"""

from __future__ import annotations

import os

import cv2
import numpy as np


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
