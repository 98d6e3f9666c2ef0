"""KanjiVG stroke-order data: parsing, the fixed split, augmentation.

The SVGs come from the ``kanjivg`` wheel (installed under ``site-packages/kanji``),
so nothing is downloaded at run time. Each stroke path (cubic Beziers in a
109x109 viewBox) becomes a list of cubic control points in the 100x100 canvas;
since an affine map of a Bezier is the Bezier of the mapped control points,
augmentation (shift, scale, shear) is applied to control points, exactly,
before rasterisation.

Which files are used:
  * code points below U+2E80 (ASCII letters, digits, punctuation) are left
    out, so that Latin script stays unseen by the model;
  * variant files (``04e00-Kaisho.svg`` ...) are alternative stroke orders and
    shapes of the same character. They go to the training split only, with
    their character, so train, validation and test never share a character
    and validation/test measure agreement with KanjiVG's main order.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.metadata
import json
import os
import pathlib
import re
import xml.etree.ElementTree as ET

import numpy as np

VIEWBOX = 109.0
CANVAS = 100
FIRST_CODE = 0x2E80
SPLIT_FILE = pathlib.Path(__file__).parent / "split.json"
_SVG_PATH = "{http://www.w3.org/2000/svg}path"
# A stroke's id: kvg:<code point>[-<variant>]-s<stroke number>.
_STROKE_ID = re.compile(r"kvg:([0-9a-f]+)(?:-[A-Za-z0-9]+)?-s(\d+)")


def kanjivg_dir() -> pathlib.Path:
    """Folder of the SVGs installed by the ``kanjivg`` wheel."""
    dist = importlib.metadata.distribution("kanjivg")
    for f in dist.files or ():
        if f.suffix == ".svg":
            return pathlib.Path(dist.locate_file(f)).parent
    raise FileNotFoundError("the kanjivg package is installed but holds no SVG files")


def kanjivg_version() -> str:
    return importlib.metadata.version("kanjivg")


def _cubics(d: str) -> np.ndarray:
    """Control points ``[K, 4, 2]`` (x, y in the 100 canvas) of one path."""
    from svgpathtools import CubicBezier, Line, QuadraticBezier, parse_path

    out = []
    for seg in parse_path(d):
        if isinstance(seg, CubicBezier):
            pts = [seg.start, seg.control1, seg.control2, seg.end]
        elif isinstance(seg, QuadraticBezier):
            p0, p1, p2 = seg.start, seg.control, seg.end
            pts = [p0, p0 + 2 / 3 * (p1 - p0), p2 + 2 / 3 * (p1 - p2), p2]
        elif isinstance(seg, Line):
            p0, p1 = seg.start, seg.end
            pts = [p0, p0 + (p1 - p0) / 3, p0 + 2 * (p1 - p0) / 3, p1]
        else:  # arcs do not occur in KanjiVG; approximate by their chord
            p0, p1 = seg.start, seg.end
            pts = [p0, p0 + (p1 - p0) / 3, p0 + 2 * (p1 - p0) / 3, p1]
        out.append([[p.real, p.imag] for p in pts])
    return np.asarray(out, np.float32) * (CANVAS / VIEWBOX)


@dataclasses.dataclass
class KanjiSet:
    """All parsed characters, flat.

    Attributes:
      names: ``[C]`` file stems (``"04e00"``, ``"04e00-Kaisho"``).
      codes: ``[C]`` int code points.
      stroke_start: ``[C + 1]`` offsets into the strokes of each character.
      seg_start: ``[S + 1]`` offsets into ``ctrl`` of each stroke.
      ctrl: ``[K, 4, 2]`` float32 cubic control points, canvas units.
      keep_turns: strokes may go back over their own line (cursive words'
        landings, scribbles' retraces): their demonstrations keep the way
        back (:func:`jdraw.data.demos.clean_path`). False for KanjiVG.
    """

    names: np.ndarray
    codes: np.ndarray
    stroke_start: np.ndarray
    seg_start: np.ndarray
    ctrl: np.ndarray
    keep_turns: bool = False

    @classmethod
    def from_strokes(cls, names, codes, chars, keep_turns: bool = False) -> KanjiSet:
        """A set of ``chars``: per character a list of ``[K, 4, 2]`` cubic strokes."""
        n_strokes = [len(c) for c in chars]
        n_segs = [len(s) for c in chars for s in c]
        return cls(
            names=np.asarray(names),
            codes=np.asarray(codes, np.int64),
            stroke_start=np.concatenate([[0], np.cumsum(n_strokes)]).astype(np.int64),
            seg_start=np.concatenate([[0], np.cumsum(n_segs)]).astype(np.int64),
            ctrl=np.concatenate([s for c in chars for s in c]).astype(np.float32),
            keep_turns=keep_turns,
        )

    def __len__(self) -> int:
        return len(self.names)

    def strokes(self, i: int) -> list[np.ndarray]:
        """Control points of character ``i``: list of ``[K, 4, 2]``."""
        s0, s1 = self.stroke_start[i], self.stroke_start[i + 1]
        return [self.ctrl[self.seg_start[s] : self.seg_start[s + 1]] for s in range(s0, s1)]

    def index(self) -> dict[str, int]:
        return {str(n): i for i, n in enumerate(self.names)}


def parse_svg(text: str) -> list[np.ndarray]:
    """Strokes of one KanjiVG file in stroke order: list of ``[K, 4, 2]``."""
    found = []
    for path in ET.fromstring(text).iter(_SVG_PATH):
        m = _STROKE_ID.fullmatch(path.get("id", ""))
        if m and path.get("d"):
            found.append((int(m[2]), path.get("d")))
    found.sort(key=lambda t: t[0])
    return [_cubics(d) for _, d in found]


def _cache_path() -> pathlib.Path:
    root = os.environ.get("JDRAW_CACHE", os.path.join(os.path.expanduser("~"), ".cache", "jdraw"))
    return pathlib.Path(root) / f"kanjivg-{kanjivg_version()}-v1.npz"


def load(progress: bool = True) -> KanjiSet:
    """Parses every usable KanjiVG file once, then reads a cache."""
    cache = _cache_path()
    if cache.exists():
        z = np.load(cache)
        return KanjiSet(**{k: z[k] for k in z.files if k != "keep_turns"})
    files = sorted(
        p for p in kanjivg_dir().glob("*.svg") if int(p.stem.split("-")[0], 16) >= FIRST_CODE
    )
    if progress:
        from tqdm import tqdm

        files = tqdm(files, desc="parsing KanjiVG", unit="file")
    names, codes, chars = [], [], []
    for p in files:
        strokes = [s for s in parse_svg(p.read_text(encoding="utf-8")) if len(s)]
        if not strokes:
            continue
        names.append(p.stem)
        codes.append(int(p.stem.split("-")[0], 16))
        chars.append(strokes)
    ks = KanjiSet.from_strokes(names, codes, chars)
    cache.parent.mkdir(parents=True, exist_ok=True)
    tmp = cache.with_suffix(".tmp.npz")
    arrays = {f.name: getattr(ks, f.name) for f in dataclasses.fields(ks) if f.name != "keep_turns"}
    np.savez(tmp, **arrays)
    os.replace(tmp, cache)
    return ks


# ----------------------------------------------------------------------------
# The split.


def make_split(codes, n_val: int = 1000, n_test: int = 1000) -> dict:
    """Deterministic split of code points by a hash of each code point."""
    uniq = sorted({int(c) for c in codes})
    key = lambda c: hashlib.sha256(f"jdraw-split-{c:05x}".encode()).hexdigest()
    order = sorted(uniq, key=key)
    return {
        "kanjivg_version": kanjivg_version(),
        "rule": "code points >= U+2E80 ordered by sha256('jdraw-split-%05x'); first n_test "
        "test, next n_val validation, rest train; variant files follow their code point and "
        "are kept in train only",
        "test": [f"{c:05x}" for c in sorted(order[:n_test])],
        "val": [f"{c:05x}" for c in sorted(order[n_test : n_test + n_val])],
    }


def split_indices(ks: KanjiSet, split: str) -> np.ndarray:
    """Indices into ``ks`` of the ``train``, ``val`` or ``test`` split.

    The split is ``jdraw/data/split.json``, written once by :func:`make_split`
    from KanjiVG's code points, so it does not change when KanjiVG grows.
    """
    spec = json.loads(SPLIT_FILE.read_text())
    held = {int(c, 16) for c in spec["test"]} | {int(c, 16) for c in spec["val"]}
    is_variant = np.array(["-" in str(n) for n in ks.names])
    if split == "train":
        mask = ~np.isin(ks.codes, list(held))
    elif split in ("val", "test"):
        mask = np.isin(ks.codes, [int(c, 16) for c in spec[split]]) & ~is_variant
    else:
        raise ValueError(f"unknown split {split!r}; expected 'train', 'val' or 'test'")
    return np.flatnonzero(mask)


# ----------------------------------------------------------------------------
# Augmentation and sampling.


def random_affine(rng: np.random.Generator, ctrl_all: np.ndarray, strength: float = 1.0):
    """A random shift/scale/shear ``(A [2,2], t [2])`` keeping the character on the canvas.

    Args:
      ctrl_all: ``[K, 4, 2]`` all control points of the character (its hull
        bounds the curves, so keeping it inside keeps the strokes inside).
      strength: 0 for the identity, 1 for the training range.
    """
    s = 1.0 + strength * rng.uniform(-0.25, 0.08)
    aspect = 1.0 + strength * rng.uniform(-0.1, 0.1)
    shear = strength * rng.uniform(-0.2, 0.2)
    a = np.array([[s * aspect, shear * s], [0.0, s / aspect]])
    pts = ctrl_all.reshape(-1, 2)
    q = pts @ a.T
    lo, hi = q.min(0), q.max(0)
    margin = 1.0
    t = np.empty(2)
    for k in range(2):
        room = (CANVAS - 1 - margin) - margin - (hi[k] - lo[k])
        if room < 0:  # shrink to fit
            f = ((CANVAS - 1 - 2 * margin) / (hi[k] - lo[k])) * 0.999
            a[k] *= f
            q[:, k] *= f
            lo[k], hi[k] = q[:, k].min(), q[:, k].max()
            room = 0.0
        centre_shift = (CANVAS - 1) / 2 - (lo[k] + hi[k]) / 2
        t[k] = centre_shift + strength * rng.uniform(-room / 2, room / 2)
    return a, t


def sample_cubics(ctrl: np.ndarray, step: float = 0.25) -> np.ndarray:
    """Dense points ``[n, 2]`` along cubic segments ``[K, 4, 2]``."""
    out = []
    for c in ctrl:
        length = np.sum(np.linalg.norm(np.diff(c, axis=0), axis=1))
        n = max(2, int(np.ceil(length / step)) + 1)
        t = np.linspace(0.0, 1.0, n)[:, None]
        mt = 1 - t
        out.append(mt**3 * c[0] + 3 * mt**2 * t * c[1] + 3 * mt * t**2 * c[2] + t**3 * c[3])
    return np.concatenate(out)
