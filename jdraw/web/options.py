"""The form fields of ``POST /api/plan``: ``jdraw draw``'s image, size and G-code options.

A field is named as the command's flag without its dashes (``width-mm``,
``travel-feed``; ``width_mm`` is read the same), takes the same values and
has the same default, so a request and a command line with the same options
plan and write the same thing. An empty field counts as not given (what an
empty ``<input>`` of an HTML form sends).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from jdraw import validate
from jdraw.io.gcode import PRESETS

POLARITIES = ("auto", "dark", "light")


@dataclasses.dataclass(frozen=True)
class PlanOptions:
    """What changes the strokes (``jdraw.plan_image``'s arguments)."""

    polarity: str = "auto"
    min_gap: float = 4.0


@dataclasses.dataclass(frozen=True)
class OutputOptions:
    """What changes only the files (``jdraw.write_outputs``' arguments).

    ``None`` keeps the default of the size (SVG in pixels, G-code 100 mm wide)
    or of the G-code preset, as the command does.
    """

    width_mm: float | None = None
    height_mm: float | None = None
    preset: str = "zaxis"
    origin_mm: tuple[float, float] = (0.0, 0.0)
    feed: float | None = None
    travel_feed: float | None = None
    pen_up: str | None = None
    pen_down: str | None = None
    z_up: float | None = None
    z_down: float | None = None

    def as_kwargs(self) -> dict:
        """Keyword arguments of :func:`jdraw.io.outputs.write_outputs`."""
        return dataclasses.asdict(self)


def _number(name: str, text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise validate.InputError(f"{name} must be a number, got {text!r}") from None
    return validate.finite(name, v)


def _origin(name: str, text: str) -> tuple[float, float]:
    parts = text.replace(",", " ").split()
    if len(parts) != 2:
        raise validate.InputError(f"{name} must be two numbers 'X Y', got {text!r}")
    return _number(name, parts[0]), _number(name, parts[1])


def _positive(name: str, text: str) -> float:
    return validate.positive(name, _number(name, text))


# Field -> (parser, which options it sets, attribute).
_FIELDS = {
    "polarity": (lambda n, t: validate.choice(n, t, POLARITIES), "plan", "polarity"),
    "min-gap": (_positive, "plan", "min_gap"),
    "width-mm": (_positive, "out", "width_mm"),
    "height-mm": (_positive, "out", "height_mm"),
    "preset": (lambda n, t: validate.choice(n, t, sorted(PRESETS)), "out", "preset"),
    "origin-mm": (_origin, "out", "origin_mm"),
    "feed": (_positive, "out", "feed"),
    "travel-feed": (_positive, "out", "travel_feed"),
    "pen-up": (validate.gcode_template, "out", "pen_up"),
    "pen-down": (validate.gcode_template, "out", "pen_down"),
    "z-up": (_number, "out", "z_up"),
    "z-down": (_number, "out", "z_down"),
}

FIELDS = tuple(_FIELDS)


def parse(form: Mapping[str, str]) -> tuple[PlanOptions, OutputOptions]:
    """The options a form asks for.

    Args:
      form: field name -> text (the ``image`` field already taken out).

    Raises:
      jdraw.validate.InputError: an unknown field or a bad value, named in one line.
    """
    plan: dict = {}
    out: dict = {}
    for key, text in form.items():
        name = key.replace("_", "-")
        if name not in _FIELDS:
            raise validate.InputError(
                f"unknown field {key!r}; the fields are image, " + ", ".join(FIELDS)
            )
        if not isinstance(text, str):
            raise validate.InputError(f"field {key!r} must be text, not a file")
        text = text.strip()
        if not text:
            continue
        parser, group, attr = _FIELDS[name]
        (plan if group == "plan" else out)[attr] = parser(name, text)
    return PlanOptions(**plan), OutputOptions(**out)
