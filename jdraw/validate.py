"""One validation layer for the public entry points.

``jdraw.plan``, ``jdraw.plan_image``, the ``jdraw`` command and bundle loading
check what they are given here, before any work starts, and fail with an
:class:`InputError` (a ``ValueError``) whose message is one line naming the
argument and the problem. Anything else that escapes is a bug, which is how
the command line tells a user error (exit 2) from an internal one (exit 3).
"""

from __future__ import annotations

import math
import numbers
import os
import pathlib
import string

import numpy as np

# Fields a G-code pen template may name (see jdraw.io.gcode.PlotterPreset).
TEMPLATE_FIELDS = (
    "z_up",
    "z_down",
    "z_feed",
    "servo_up",
    "servo_down",
    "dwell_s",
    "feed",
    "travel_feed",
)


class InputError(ValueError):
    """A bad argument or input, described in one line."""


def one_line(message: object) -> str:
    """``message`` as a single line (multi-line exception texts joined with '; ')."""
    return "; ".join(ln.strip() for ln in str(message).splitlines() if ln.strip())


# ----------------------------------------------------------------------------- scalars


def positive_int(name: str, value, *, optional: bool = False, zero: bool = False) -> int | None:
    """``value`` as an ``int >= 1`` (``>= 0`` with ``zero``); ``None`` passes when ``optional``."""
    if value is None and optional:
        return None
    what = "a non-negative" if zero else "a positive"
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{name} must be {what} integer, got {value!r}")
    if value < (0 if zero else 1):
        raise InputError(f"{name} must be {what} integer, got {value}")
    return int(value)


def finite(name: str, value, *, optional: bool = False) -> float | None:
    """``value`` as a finite ``float``; ``None`` passes when ``optional``."""
    if value is None and optional:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{name} must be a number, got {value!r}")
    if not math.isfinite(value):
        raise InputError(f"{name} must be finite, got {value}")
    return float(value)


def positive(name: str, value, *, optional: bool = False, zero: bool = False) -> float | None:
    """``value`` as a finite ``float > 0`` (``>= 0`` with ``zero``)."""
    v = finite(name, value, optional=optional)
    if v is not None and (v < 0 or (v == 0 and not zero)):
        raise InputError(f"{name} must be {'>= 0' if zero else 'positive'}, got {value}")
    return v


def choice(name: str, value, options) -> str:
    if value not in options:
        raise InputError(f"{name} must be one of {', '.join(map(repr, options))}; got {value!r}")
    return value


# ----------------------------------------------------------------------------- arrays


def _as_array(x, name: str) -> np.ndarray:
    try:
        a = np.asarray(x)
    except ValueError as e:
        # numpy's "inhomogeneous shape" for a ragged nested list.
        raise InputError(
            f"{name} is a ragged nested list (rows of different lengths); pass an array"
        ) from e
    if a.dtype == object:
        raise InputError(
            f"{name} is an object array (a ragged list or mixed types?); pass a numeric array"
        )
    if a.dtype == bool:
        return a
    if np.issubdtype(a.dtype, np.complexfloating):
        raise InputError(f"{name} is complex ({a.dtype}); pass real numbers")
    if not np.issubdtype(a.dtype, np.number):
        raise InputError(f"{name} must be a numeric or bool array, got dtype {a.dtype}")
    if np.issubdtype(a.dtype, np.floating) and not np.all(np.isfinite(a)):
        raise InputError(f"{name} contains NaN or inf")
    return a


def canvas_images(images) -> np.ndarray:
    """``images`` for :func:`jdraw.plan` as ``bool [B, 100, 100]`` ink masks.

    Accepts ``[B, 100, 100]``, ``[100, 100]``, or either with a trailing
    channel axis of size 1; bool, integer or real float; nonzero is ink.
    """
    from jdraw.geometry import CANVAS  # here: the command line checks options without JAX

    x = _as_array(images, "images")
    shape = x.shape
    if x.ndim in (3, 4) and x.shape[-1] == 1 and x.shape[-3:-1] == (CANVAS, CANVAS):
        x = x[..., 0]
    if x.ndim == 2:
        x = x[None]
    if x.ndim != 3 or x.shape[1:] != (CANVAS, CANVAS):
        c = shape[-1] if shape else 0
        if len(shape) in (3, 4) and shape[-3:-1] == (CANVAS, CANVAS):
            hint = f"; it has {c} channels: convert to one, or use jdraw.plan_image"
        elif len(shape) == 4 and shape[-2:] == (CANVAS, CANVAS):
            hint = f"; channels first? it has {shape[1]} channels along axis 1: pass one, last"
        elif len(shape) in (2, 3):
            hint = "; use jdraw.plan_image for sizes other than 100x100"
        else:
            hint = ""
        raise InputError(
            f"images must have shape [B, 100, 100] or [100, 100] (a trailing channel axis of "
            f"size 1 is allowed), got rank {len(shape)} shape {shape}{hint}"
        )
    if len(x) == 0:
        raise InputError(f"images is an empty batch (shape {shape}); pass at least one image")
    return x != 0


def any_image(image) -> np.ndarray:
    """An image array for :func:`jdraw.plan_image`: real, finite, 2-D or with 1/3/4 channels."""
    x = _as_array(image, "image")
    ok = x.ndim == 2 or (x.ndim == 3 and x.shape[2] in (1, 3, 4))
    if not ok:
        raise InputError(f"image must have shape [H, W], [H, W, 3] or [H, W, 4], got {x.shape}")
    if min(x.shape[:2]) < 2:
        raise InputError(f"image too small: {x.shape[1]} x {x.shape[0]} pixels (need 2 x 2)")
    return x


# ----------------------------------------------------------------------------- models


def checkpoint(value):
    """A checkpoint argument: ``None``, a ``DrawModel`` or an existing folder's path."""
    if value is None:
        return None
    from flax import nnx

    if isinstance(value, nnx.Module):
        return value
    if not isinstance(value, str | os.PathLike):
        raise InputError(
            f"checkpoint must be a folder path, a DrawModel or None, got {type(value).__name__}"
        )
    path = pathlib.Path(value)
    if not path.exists():
        raise InputError(f"checkpoint {str(path)!r}: no such file or directory")
    if not path.is_dir():
        raise InputError(
            f"checkpoint {str(path)!r} is a file; pass the bundle folder (with bundle.json) "
            "or the training workdir"
        )
    if not (path / "bundle.json").exists() and not (path / "config.json").exists():
        raise InputError(
            f"checkpoint {str(path)!r} is neither a jdraw bundle (no bundle.json) nor a "
            "training workdir (no config.json)"
        )
    return value


# ----------------------------------------------------------------------------- outputs


def gcode_template(name: str, template) -> str:
    r"""A pen template: G-code lines (``\n``-separated) naming only :data:`TEMPLATE_FIELDS`.

    Only plain ``{field}`` substitutions are allowed: no attribute or index
    access, conversions or format specs (``{{`` and ``}}`` are literal braces).
    """
    if not isinstance(template, str):
        raise InputError(f"{name} must be a string, got {type(template).__name__}")
    try:
        parts = list(string.Formatter().parse(template))
    except ValueError as e:
        raise InputError(
            f"{name} {template!r}: {e} (write {{{{ and }}}} for literal braces)"
        ) from None
    for _, field, spec, conv in parts:
        if field is None:
            continue
        if field not in TEMPLATE_FIELDS or spec or conv:
            known = ", ".join("{" + f + "}" for f in TEMPLATE_FIELDS)
            shown = field + ("!" + conv if conv else "") + (":" + spec if spec else "")
            raise InputError(f"{name} {template!r}: unknown field {{{shown}}}; use {known}")
    return template


def output_path(option: str, path) -> str:
    """An output file path whose folder exists and which is not itself a folder."""
    p = os.fspath(path)
    if not p:
        raise InputError(f"{option}: empty path")
    if os.path.isdir(p):
        raise InputError(f"{option} {p!r} is a directory; give a file name")
    parent = os.path.dirname(os.path.abspath(p))
    if not os.path.isdir(parent):
        raise InputError(f"{option} {p!r}: no such directory {os.path.dirname(p)!r}")
    if not os.access(parent, os.W_OK):
        raise InputError(f"{option} {p!r}: the directory is not writable")
    return p
