"""Cursive words written in EMS Allure, a joined single-line script, as a writer draws them.

The glyphs (:data:`FONT_FILE`, SIL OFL, see ``single_line/README.md``) are
polylines in font units. A word is laid out glyph by glyph at the font's
advance widths, and :func:`word_strokes` turns its polylines into the strokes
a cursive writer makes:

* **Joins.** Consecutive polylines of the word body are one stroke where the
  end of one meets an end of the next within :data:`JOIN_TOL` font units.
  EMS Allure's letters leave at ``(advance - 31.5, 183)`` and those that join
  from the left enter at ``(-31.5, 183)``, so joined letters meet to within
  0.5 units (l enters 9.4 units off); the next-nearest ends that are not a
  join lie 31.5 units apart (k's lead-in and its loop), hence 15.
* **Landings.** Where the font's connector ends on the next letter's line
  instead of at its start (a, c, d, e, g, o, q ...: over the words of
  :data:`WORDS`, 603 of 1,340 consecutive body polylines end within 15 units
  of the next one's line, most a quarter of the way along it, and the rest
  more than 15 units off, nearly all over 40), the pen goes on as a writer's
  does: back along the next letter from the landing point to its start (over
  the top of an a's oval), then round the whole letter, drawing that part
  twice. Likewise where a polyline starts on the line just drawn, the pen
  first goes back along it to there. This is what makes the writer's strokes
  per connected piece of ink about one, as the issue describes cursive.
* **Direction.** The font's own direction is not used (its a runs from the
  exit tail back to the oval). Every polyline is oriented by a rule: it ends
  at its letter's exit or starts at its letter's entry if an end lies within
  :data:`ORIENT_TOL` of either (``(advance - 31.5, 183)``, ``(-31.5, 183)``;
  f's tail stops 34 units short of its exit), else it starts at the end
  nearer the top left (smaller ``x - y``, y up), as a writer starts a stroke;
  two capitals' polylines where that is wrong are listed in :data:`TURNED`.
  Where two polylines meet end to end but the rule pointed them head to head,
  the later one is turned round: the line goes on, so the pen does.
* **Marks after the word.** The dots of i and j and the crosses of t and x
  (:data:`MARKS`) are drawn after the whole word body, left to right, as
  cursive is commonly taught ("finish the word, then dot the i's and cross
  the t's"). Other extra polylines (k's leg, o's tail, the bars of F and Z)
  are drawn with their letter.

The written strokes of a word are ``word_strokes(word)``; their count is the
number of pen-down motions a writer makes. :func:`fragments` cuts words into
2-5 letter fragments on the 100 x 100 canvas, as a
:class:`jdraw.data.kanji.KanjiSet` for the training pipeline.
"""

from __future__ import annotations

import functools
import hashlib
import json
import pathlib
import zlib

import numpy as np

from jdraw.data.kanji import CANVAS, KanjiSet

FONT_FILE = pathlib.Path(__file__).parent / "single_line" / "ems_allure.json"
JOIN_TOL = 15.0  # font units
ORIENT_TOL = 50.0  # font units: an end this near the entry or exit is that end (f's is 34 off)
ENTRY = np.array([-31.5, 183.0])  # where a joining letter starts, font units, y up
EXIT_DX = -31.5  # a letter leaves at (advance + EXIT_DX, 183)
# Polylines (index into the glyph's paths) drawn after the word body.
MARKS = {"i": (1,), "j": (1,), "t": (1,), "x": (1,)}
# Polylines the direction rule gets wrong, found by rendering every glyph with its
# start: O is written counter-clockwise from its top curl, K's arm comes in from the top.
TURNED = {"O": (0,), "K": (1,)}

# Common English words, mostly lower case; split by a hash (:func:`split_of`).
WORDS = tuple(
    """
    the be to of and a in that have it for not on with he as you do at this but his by
    from they we say her she or an will my one all would there their what so up out if
    about who get which go me when make can like time no just him know take people into
    year your good some could them see other than then now look only come its over think
    also back after use two how our work first well way even new want because any these
    give day most us is was are were been has had did said made went came took saw found
    told felt left kept held heard house world hand life part child eye woman place week
    case point number group problem fact home water room mother father area money story
    month lot right study book word issue side kind head service friend power hour game
    line end member law car city name team minute idea kid body back parent face others
    level office door health person art war history party result change morning reason
    research girl guy moment air teacher force education foot boy age policy music market
    sense nation plan college interest death course class table paper letter garden river
    apple orange bread milk coffee tea sugar salt window chair street bridge island forest
    mountain valley ocean summer winter spring autumn yellow purple silver golden little
    small large great long short high low old young early late happy quiet simple gentle
    careful hello thanks please sorry yes maybe always never often today tomorrow yesterday
    evening night cloud rain snow wind storm light dark sweet bitter fresh clean warm cold
    write read draw learn teach speak listen walk run jump swim sing dance laugh smile
    open close begin finish follow bring carry hold keep leave lose meet move pay play
    stand turn wait watch wish love hope dream believe remember forget understand between
    without through during before behind above below under inside outside around across
    along against toward until while where whose whom why which every each many much few
    more less best better worse quite rather almost already still again once twice half
    whole dozen hundred thousand million zero three four five six seven eight nine ten
    twelve twenty thirty forty fifty quick brown fox lazy dog jumped over kitchen pencil
    Monday Tuesday Friday Sunday January March April June July August October London Paris
    Boston Texas Anna Maria David Emma Oliver Hello Thank Dear Love Best The Good Happy
    """.split()
)
SPLIT_RULE = "sha256('jdraw-cursive-' + word.lower()) mod 100: < 70 train, < 85 val, else test"


@functools.lru_cache(maxsize=1)
def font() -> dict:
    """The committed glyph data (``single_line/ems_allure.json``)."""
    return json.loads(FONT_FILE.read_text())


def split_of(word: str) -> str:
    """``"train"``, ``"val"`` or ``"test"``, fixed by a hash of the word (:data:`SPLIT_RULE`)."""
    h = int(hashlib.sha256(f"jdraw-cursive-{word.lower()}".encode()).hexdigest(), 16) % 100
    return "train" if h < 70 else "val" if h < 85 else "test"


def split_words(split: str) -> list[str]:
    """The words of ``split`` (``train``, ``val`` or ``test``), in :data:`WORDS` order."""
    if split not in ("train", "val", "test"):
        raise ValueError(f"unknown split {split!r}; expected 'train', 'val' or 'test'")
    return [w for w in dict.fromkeys(WORDS) if split_of(w) == split]


def _check_word(word: str) -> None:
    glyphs = font()["glyphs"]
    if not isinstance(word, str) or not word:
        raise ValueError(f"expected a non-empty word, got {word!r}")
    bad = sorted({c for c in word if c not in glyphs})
    if bad:
        raise ValueError(f"no glyph for {''.join(bad)!r} in {word!r}; letters a-z, A-Z only")


def _orient(p: np.ndarray, adv: float) -> np.ndarray:
    """Polyline ``p`` (glyph units, y up) turned the way it is written (module docstring)."""
    exit_pt = np.array([adv + EXIT_DX, ENTRY[1]])
    near = lambda q, r: np.linalg.norm(q - r) <= ORIENT_TOL  # noqa: E731
    if near(p[0], exit_pt) or near(p[-1], ENTRY):
        return p[::-1]
    if near(p[-1], exit_pt) or near(p[0], ENTRY):
        return p
    return p if p[0, 0] - p[0, 1] <= p[-1, 0] - p[-1, 1] else p[::-1]


def letter_polylines(word: str) -> list[tuple[int, bool, np.ndarray]]:
    """``(letter index, is mark, [n, 2] polyline)`` of ``word`` in font units, y up, oriented.

    Glyphs are placed at the font's advance widths, the first at x = 0.
    """
    _check_word(word)
    glyphs = font()["glyphs"]
    out, x = [], 0.0
    for k, ch in enumerate(word):
        g = glyphs[ch]
        for j, p in enumerate(g["paths"]):
            q = _orient(np.asarray(p, np.float64), g["adv"])
            if j in TURNED.get(ch, ()):
                q = q[::-1]
            out.append((k, j in MARKS.get(ch, ()), q + (x, 0.0)))
        x += g["adv"]
    return out


def _nearest(q: np.ndarray, p: np.ndarray) -> tuple[float, int, np.ndarray]:
    """``(distance, k, point)``: the point of polyline ``p`` nearest ``q``, on segment ``k``."""
    a, d = p[:-1], np.diff(p, axis=0)
    t = np.clip(np.sum((q - a) * d, 1) / np.maximum(np.sum(d * d, 1), 1e-12), 0.0, 1.0)
    foot = a + t[:, None] * d
    dist = np.linalg.norm(foot - q, axis=1)
    k = int(np.argmin(dist))
    return float(dist[k]), k, foot[k]


def _chain(polys: list[np.ndarray], landings: bool = True) -> list[np.ndarray]:
    """Joins consecutive polylines where the pen goes on (module docstring).

    End to end within :data:`JOIN_TOL`: one line. With ``landings``, also where
    the stroke so far ends on the next polyline's line (at ``L``): the pen goes
    back along it from ``L`` to its start and then draws it from there, over
    that part again; and where the next polyline starts on the stroke's own
    line: the pen goes back along the stroke to there first.
    """
    out: list[np.ndarray] = []
    for p in polys:
        if not out:
            out.append(p)
            continue
        c = out[-1]
        if np.linalg.norm(c[-1] - p[0]) <= JOIN_TOL:
            out[-1] = np.concatenate([c, p[1:]])
            continue
        if np.linalg.norm(c[-1] - p[-1]) <= JOIN_TOL:
            out[-1] = np.concatenate([c, p[::-1][1:]])
            continue
        if landings and len(p) > 1:
            dist, k, foot = _nearest(c[-1], p)
            if dist <= JOIN_TOL:  # lands on p: back to p's start, then all of p
                out[-1] = np.concatenate([c, [foot], p[k::-1], p[1:]])
                continue
        if landings and len(c) > 1:
            dist, k, foot = _nearest(p[0], c)
            if dist <= JOIN_TOL:  # p starts on the stroke: back along it to there
                out[-1] = np.concatenate([c, c[-2:k:-1], [foot], p])
                continue
        out.append(p)
    return out


def word_strokes_units(word: str) -> list[np.ndarray]:
    """:func:`word_strokes` in font units, y up (baseline y = 0)."""
    parts = letter_polylines(word)
    body = _chain([p for _, mark, p in parts if not mark])
    marks = [p for _, mark, p in parts if mark]
    return body + marks


def word_strokes(word: str) -> list[np.ndarray]:
    """The strokes a cursive writer makes for ``word``, in writing order.

    Args:
      word: letters a-z, A-Z.

    Returns:
      list of ``[n, 2]`` float64 (x, y) polylines, font units (1000 to the
      em), y down: y = ascent - font y, so the baseline is y = 800. Body
      strokes left to right, then the marks (:data:`MARKS`) left to right.

    Raises:
      ValueError: an empty word or a character without a glyph.
    """
    asc = font()["ascent"]
    return [np.stack([p[:, 0], asc - p[:, 1]], 1) for p in word_strokes_units(word)]


# ----------------------------------------------------------------------------
# Fragments on the canvas, for training.

MARGIN = 4.0  # canvas pixels kept free around a fragment
MIN_SCALE = 0.05  # canvas pixels per font unit: x-height 15 px, e's loop about 5 px across


def to_cubics(p: np.ndarray) -> np.ndarray:
    """``[n - 1, 4, 2]`` float32 cubics of the straight segments of polyline ``p [n, 2]``."""
    p0, p1 = p[:-1], p[1:]
    d = p1 - p0
    return np.stack([p0, p0 + d / 3, p0 + 2 * d / 3, p1], 1).astype(np.float32)


def fit(strokes: list[np.ndarray], margin: float = MARGIN) -> tuple[float, np.ndarray]:
    """``(scale, offset [2])`` mapping ``strokes`` (y down) centred into the canvas.

    The scale is the largest that keeps ``margin`` pixels free on every side:
    canvas point = ``scale * p + offset``, inside ``[margin, CANVAS - 1 - margin]``.
    """
    pts = np.concatenate(strokes)
    lo, hi = pts.min(0), pts.max(0)
    room = CANVAS - 1 - 2 * margin
    scale = room / max(float(np.max(hi - lo)), 1e-9)
    offset = (CANVAS - 1) / 2 - scale * (lo + hi) / 2
    return scale, offset


def fragment_strokes(word: str, start: int, stop: int) -> list[np.ndarray]:
    """Strokes (y down, font units) of letters ``word[start:stop]`` as written in ``word``.

    Glyphs sit at advance widths and joins happen only where one letter meets
    the next, so cutting the word's strokes at letter boundaries gives the
    strokes of the letters laid out alone, shifted; the letters' own marks
    come after their body.
    """
    if not 0 <= start < stop <= len(word):
        raise ValueError(f"bad letter range {start}:{stop} of {word!r}")
    return word_strokes(word[start:stop])


def fragments(
    split: str, min_letters: int = 2, max_letters: int = 5, min_scale: float = MIN_SCALE
) -> KanjiSet:
    """Every fragment of ``min_letters``-``max_letters`` letters of the words of ``split``.

    A fragment is kept when it fits the canvas (:func:`fit`, :data:`MARGIN`)
    at ``min_scale`` canvas pixels per font unit or more, so its lines stay
    apart on the canvas. Each polyline segment is a cubic (straight:
    ``[p0, p0 + d/3, p0 + 2d/3, p1]``).

    Strokes that land on the next letter go back over part of it (module
    docstring), so the set says ``keep_turns``: its demonstrations
    (:func:`jdraw.data.demos.sample`, :func:`jdraw.data.variants.sample`)
    keep the way back instead of erasing that part of the line.

    Returns:
      a :class:`jdraw.data.kanji.KanjiSet`: ``names`` like ``"hello[1:4]"``,
      ``codes`` = 1000 * word index in :data:`WORDS` + 30 * start + stop,
      strokes in writing order, control points in canvas pixels.
    """
    words = split_words(split)
    index = {w: i for i, w in enumerate(dict.fromkeys(WORDS))}
    names, codes, chars = [], [], []
    for w in words:
        for n in range(min_letters, min(max_letters, len(w)) + 1):
            for s in range(len(w) - n + 1):
                strokes = fragment_strokes(w, s, s + n)
                scale, offset = fit(strokes)
                if scale < min_scale:
                    continue
                chars.append([to_cubics(p * scale + offset) for p in strokes if len(p) > 1])
                names.append(f"{w}[{s}:{s + n}]")
                codes.append(1000 * index[w] + 30 * s + s + n)
    if not names:
        raise ValueError(f"no fragment of the {split!r} words fits at min_scale={min_scale}")
    return KanjiSet.from_strokes(names, codes, chars, keep_turns=True)


def _length(p: np.ndarray) -> float:
    """Length of polyline ``p [n, 2]``."""
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def _prefix(strokes: list[np.ndarray], length: float) -> list[np.ndarray]:
    """The writer's strokes up to ``length`` font units of pen-down motion."""
    out = []
    for p in strokes:
        seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
        run = np.concatenate([[0.0], np.cumsum(seg)])
        if run[-1] <= length:
            out.append(p)
            length -= run[-1]
            continue
        if length > 0:  # stopped inside this stroke: up to the point that far along it
            k = int(np.searchsorted(run, length, side="right"))  # run[k - 1] <= length < run[k]
            t = (length - run[k - 1]) / max(seg[k - 1], 1e-9)
            out.append(np.concatenate([p[:k], (p[k - 1] + t * (p[k] - p[k - 1]))[None]]))
        break
    return out


def prefixes(
    split: str,
    n: int = 2000,
    seed: int = 0,
    min_share: float = 0.4,
    min_scale: float = MIN_SCALE,
) -> KanjiSet:
    """Fragments stopped part-way through their writing, wherever the pen happens to be.

    Each is a fragment of 2-5 letters of a word of ``split`` (as :func:`fragments`)
    written up to a random share, ``min_share`` to 1, of its pen-down length: its
    last stroke stops wherever the pen was then (going up an ascender, round a loop,
    along a join), and whatever the writer drew later (the rest, the dots and
    crosses) is not there. Fragments cut at letter boundaries end where a letter
    ends; these teach that a stroke's end is wherever its writing stopped, not only
    at a letter's exit, so its heading must be read from the line's run.

    Returns:
      a :class:`jdraw.data.kanji.KanjiSet` of ``n`` drawings (``names`` like
      ``"hello[1:4]@0.6312"``), fitted to the canvas as :func:`fragments` are.
    """
    words = split_words(split)
    rng = np.random.default_rng([seed, zlib.crc32(split.encode())])
    names, codes, chars = [], [], []
    tries = 0
    while len(names) < n:
        tries += 1
        if tries > 20 * n:
            raise ValueError(f"only {len(names)} of {n} prefixes of the {split!r} words fit")
        w = words[int(rng.integers(len(words)))]
        k = int(rng.integers(min(2, len(w)), min(5, len(w)) + 1))
        s = int(rng.integers(len(w) - k + 1))
        strokes = fragment_strokes(w, s, s + k)
        total = sum(_length(p) for p in strokes)
        share = float(rng.uniform(min_share, 1.0))
        cut = [p for p in _prefix(strokes, share * total) if len(p) > 1]
        if not cut:
            continue
        scale, offset = fit(cut)
        if scale < min_scale:
            continue
        chars.append([to_cubics(p * scale + offset) for p in cut])
        names.append(f"{w}[{s}:{s + k}]@{share:.4f}")
        codes.append(len(codes))
    return KanjiSet.from_strokes(names, codes, chars, keep_turns=True)
