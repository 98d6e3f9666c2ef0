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


class TooLargeError(ImageError):
    """An image with more pixels than the limit (:func:`check_pixels`)."""


# ----------------------------------------------------------------------------- size

MAX_PIXELS = 100_000_000  # the default limit: 100 Mpx (a 600-dpi A4 scan is 35 Mpx)


def image_size(path: str | os.PathLike) -> tuple[int, int] | None:
    """``(width, height)`` of an image file from its header, without decoding the pixels.

    Returns ``None`` when Pillow cannot read the header (the file may still be
    one OpenCV decodes; :func:`load_image` says what is wrong with it).
    """
    from PIL import Image

    path = os.fspath(path)
    # Pillow refuses to open huge images (decompression-bomb check) before we can
    # read their size; only the header is read here, so lift it for this call.
    old, Image.MAX_IMAGE_PIXELS = Image.MAX_IMAGE_PIXELS, None
    try:
        with Image.open(path) as im:
            return int(im.width), int(im.height)
    except (OSError, ValueError, SyntaxError):
        return None
    finally:
        Image.MAX_IMAGE_PIXELS = old


def check_pixels(
    size: tuple[int, int],
    limit: float | None = MAX_PIXELS,
    name: str = "image",
    flag: str = "max_pixels=",
) -> None:
    """Raises :class:`TooLargeError` if a ``(width, height)`` image has more than ``limit`` pixels.

    The one-line message names the image, its size and ``flag``, the setting
    that raises the limit (``--max-mpx`` on the command line). ``limit=None``: no limit.
    """
    if limit is None:
        return
    w, h = size
    if w * h > limit:
        need = -(-w * h // 1_000_000)
        hint = f"{flag} {need}" if flag.startswith("--") else f"{flag}{need * 1_000_000}"
        raise TooLargeError(
            f"{name}: {w}x{h} pixels ({w * h / 1e6:.0f} Mpx) is over the limit of "
            f"{limit / 1e6:g} Mpx; to plan it anyway raise the limit ({hint}), it needs "
            f"about {30 * w * h / 1e9:.1f} GB of memory"
        )


# ----------------------------------------------------------------------------- loading


def load_image(
    path: str | os.PathLike, max_pixels: float | None = None, flag: str = "max_pixels="
) -> np.ndarray:
    """Reads an image file as it is stored.

    Args:
      path: the file.
      max_pixels: refuse an image with more pixels, judged from the file's header
        before decoding (:func:`check_pixels`; ``flag`` names the setting in the
        message); ``None``: no limit.

    Returns:
      ``uint8`` or ``uint16`` ``[H, W]``, ``[H, W, 3]`` (RGB) or ``[H, W, 4]`` (RGBA).

    Raises:
      ImageError: missing file, a format OpenCV cannot read, or undecodable data;
        TooLargeError: over ``max_pixels``.
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
    if max_pixels is not None:
        size = image_size(path)
        if size is not None:
            check_pixels(size, max_pixels, path, flag)
    img = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if img is None or img.size == 0:
        raise ImageError(f"cannot read {path!r}: the image data could not be decoded")
    if max_pixels is not None:  # a header Pillow could not read
        check_pixels((img.shape[1], img.shape[0]), max_pixels, path, flag)
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
        f = img.astype(np.float32)
        f /= float(np.iinfo(img.dtype).max)
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
