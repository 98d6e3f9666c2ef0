"""Writes ``jdraw/data/single_line/ems_allure.json`` from the EMS Allure SVG font.

  apt-get download inkscape && dpkg -x inkscape_*.deb /tmp/ink
  python -m jdraw.data.make_single_line \
      /tmp/ink/usr/share/inkscape/extensions/svg_fonts/EMSAllure.svg

EMS Allure (SIL Open Font License, ``OFL.txt`` beside the output) is a joined
single-line script: each glyph is one or more polylines (``M x y L x y ...``)
in font units, y up, 1000 units to the em. Only the glyphs in ``CHARS`` are
kept, unchanged, except that a subpath repeated within a glyph is dropped
(EMS Allure's N draws its serif twice). The other font families beside it in the
package are held out for evaluation and are never read.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import re
import string
import xml.etree.ElementTree as ET

OUT = pathlib.Path(__file__).parent / "single_line" / "ems_allure.json"
CHARS = string.ascii_letters
_SVG = "{http://www.w3.org/2000/svg}"


def parse_path(d: str) -> list[list[list[float]]]:
    """Subpaths of an ``M x y L x y ... M ...`` path: lists of ``[x, y]``."""
    out = []
    for part in re.split(r"(?=[Mm])", d.strip()):
        if not part.strip():
            continue
        if part[0] != "M" or re.search(r"[^ML0-9eE.+\-\s,]", part):
            raise ValueError(f"expected absolute M/L polylines, got {part[:40]!r}")
        nums = [float(v) for v in re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", part)]
        if len(nums) % 2 or len(nums) < 4:
            raise ValueError(f"bad coordinate list in {part[:40]!r}")
        out.append([[nums[k], nums[k + 1]] for k in range(0, len(nums), 2)])
    return out


def read_font(svg_text: str, chars: str = CHARS) -> dict:
    """``{"font": ..., "units_per_em", "ascent", "descent", "glyphs": {ch: {"adv", "paths"}}}``."""
    root = ET.fromstring(svg_text)
    font = root.find(f".//{_SVG}font")
    face = root.find(f".//{_SVG}font-face")
    if font is None or face is None:
        raise ValueError("not an SVG font: no <font> / <font-face>")
    default_adv = float(font.get("horiz-adv-x", 0))
    glyphs = {}
    for g in font.iter(f"{_SVG}glyph"):
        ch = g.get("unicode")
        if ch is None or ch not in chars:
            continue
        paths = []
        for p in parse_path(g.get("d", "")):
            if p not in paths:
                paths.append(p)
        glyphs[ch] = {"adv": float(g.get("horiz-adv-x", default_adv)), "paths": paths}
    missing = [c for c in chars if c not in glyphs]
    if missing:
        raise ValueError(f"font lacks glyphs {''.join(missing)!r}")
    return {
        "font": face.get("font-family"),
        "source": "Debian package inkscape: usr/share/inkscape/extensions/svg_fonts/EMSAllure.svg",
        "license": "SIL Open Font License 1.1 (OFL.txt)",
        "units_per_em": float(face.get("units-per-em")),
        "ascent": float(face.get("ascent")),
        "descent": float(face.get("descent")),
        "glyphs": {c: glyphs[c] for c in chars},
    }


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("svg", help="path to EMSAllure.svg")
    p.add_argument("--out", default=str(OUT))
    a = p.parse_args(argv)
    font = read_font(pathlib.Path(a.svg).read_text(encoding="utf-8"))
    text = json.dumps(font, separators=(",", ":"))
    pathlib.Path(a.out).write_text(text + "\n")
    print(f"wrote {a.out}: {len(font['glyphs'])} glyphs, {len(text)} bytes")


if __name__ == "__main__":
    main()
