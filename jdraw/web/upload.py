"""An uploaded image: its size read from the header, then decoded as ``jdraw draw`` does.

The pixel count is read from the file's header (Pillow opens lazily: it
parses the header and decodes nothing), so an image too big to plan, or a
decompression bomb (a small file that claims a huge picture), is refused for
the cost of reading a few bytes. Only then is the image decoded, by the same
function the command line uses (:func:`jdraw.images.load.load_image`), so a
request and ``jdraw draw`` on the same file see the same pixels.
"""

from __future__ import annotations

import io
import os
import re
import tempfile
import warnings

import numpy as np

from jdraw.images import load

# The formats the command line reads (jdraw.images.load), as Pillow names them;
# PPM is Pillow's reader of PBM, PGM and PPM.
FORMATS = ("PNG", "JPEG", "GIF", "BMP", "TIFF", "WEBP", "PPM")
FORMATS_TEXT = "PNG, JPEG, GIF, BMP, TIFF, WebP or PBM/PGM/PPM"


class NotAnImage(ValueError):
    """The bytes are not an image of a readable format."""


class TooManyPixels(ValueError):
    """The image is bigger than the pixel limit."""


def header_size(data: bytes, max_pixels: int) -> tuple[int, int]:
    """``(width, height)`` from the image's header, checked against ``max_pixels``.

    Raises:
      NotAnImage: not a PNG, JPEG, GIF, BMP, TIFF, WebP or PBM/PGM/PPM file.
      TooManyPixels: ``width * height > max_pixels`` (also when Pillow's own
        decompression-bomb guard, about 179 Mpx, refuses the header).
    """
    from PIL import Image

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            with Image.open(io.BytesIO(data), formats=FORMATS) as im:
                w, h = im.size
    except Image.DecompressionBombError as e:
        # Pillow's own guard (about 179 Mpx) refused the header; its message has the count.
        m = re.search(r"\((\d+) pixels\)", str(e))
        size = f"{int(m.group(1))} pixels" if m else "too many pixels"
        raise TooManyPixels(f"the image is {size}; the limit is {max_pixels} pixels") from None
    except Exception:  # Pillow raises UnidentifiedImageError, or anything on a mangled header
        raise NotAnImage(f"not an image: use {FORMATS_TEXT}") from None
    if w * h > max_pixels:
        raise TooManyPixels(
            f"the image is {w} x {h} = {w * h} pixels; the limit is {max_pixels} pixels"
        )
    return w, h


def decode(data: bytes, name: str = "image") -> np.ndarray:
    """The image as :func:`jdraw.images.load.load_image` reads it from a file.

    Args:
      data: the file's bytes.
      name: what to call it in an error message (the upload's file name).

    Raises:
      jdraw.images.load.ImageError: undecodable data, named after ``name``.
    """
    fd, path = tempfile.mkstemp(prefix="jdraw-upload-")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        try:
            return load.load_image(path)
        except load.ImageError as e:
            raise load.ImageError(str(e).replace(repr(path), repr(name))) from None
    finally:
        os.unlink(path)
