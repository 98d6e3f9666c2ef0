"""Where the planned strokes of cursive words end, and why: the writer's ends or not.

  python bench/cursive_ends.py [--split val] [--n 40] [--checkpoint BUNDLE] [--png FILE]

Plans the first ``--n`` words of a split of :mod:`jdraw.data.cursive` as
:mod:`jdraw.evaluation.words` draws them (100-300 px high, a 3-px marker) with
``plan_image``, and sorts every planned stroke end by what lies there:

* ``writer``: within 6 px of one of the writer's stroke ends;
* ``dead end``: on no other planned stroke, nor on its own stroke's line (a hump's
  top, an r's spike, an e's bar: where the writer turns back over the line);
* ``other's middle``: on another planned stroke, away from its ends (a T, a crossing);
* ``own line``: on its own stroke, further along (a loop's crossing);
* ``other's end``: at another planned stroke's end (two strokes that one join would make one).

It also counts the ends that are not the writer's and lie within 2.5 canvas px of a
tile border, and the planned strokes shorter than a tenth of the word's height (and
the writer's: the dots). ``--png`` draws the words with the largest excess of strokes,
tile borders in cyan, each stroke in its order colour (blue first, red last, a dot at
its start). This is how the tile-border and cusp faults of 2026-12-07 were found
(docs/scripts.md). About 20 s for 40 words on the 2-core CPU.
"""

from __future__ import annotations

import argparse
import collections

import numpy as np

from jdraw.data import cursive
from jdraw.evaluation import words as W
from jdraw.tiling.plan_image import plan_image

NEAR_WRITER = 6.0  # input px: an end this near one of the writer's is the writer's
ON_LINE = 4.0  # input px: an end this near a stroke's points lies on that stroke
ALONG = 6.0  # input px from a stroke's own end that still counts as that end
BORDER = 2.5  # canvas px: an end this near a tile border is at the border
SHORT = 0.1  # of the word's height: a stroke shorter than this is short


def _arclength(p: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])


def end_kind(k: int, at_end: bool, strokes, writer_ends: np.ndarray) -> str:
    """What lies at one end of planned stroke ``k`` (the module docstring's kinds)."""
    q = strokes[k][-1 if at_end else 0]
    if len(writer_ends) and np.hypot(*(writer_ends - q).T).min() <= NEAR_WRITER:
        return "writer"
    kind = "dead end"
    for j, t in enumerate(strokes):
        if j == k:
            continue
        d = np.hypot(*(t - q).T)
        if d.min() > ON_LINE:
            continue
        s = _arclength(t)
        i = int(d.argmin())
        if min(s[i], s[-1] - s[i]) <= ALONG:
            return "other's end"
        kind = "other's middle"
    if kind == "dead end":
        own = strokes[k]
        s = _arclength(own)
        far = np.abs(s - (s[-1] if at_end else 0.0)) > 2 * ALONG
        if (np.hypot(*(own - q).T)[far] <= ON_LINE).any():
            return "own line"
    return kind


def border_lines(plan) -> tuple[np.ndarray, np.ndarray]:
    """Input-pixel x of every tile's vertical borders and y of its horizontal ones."""
    xs, ys = set(), set()
    if len(plan.tiles) > 1:
        for t in plan.tiles:
            c = t.transform.to_input(np.array([[0.0, 0.0], [100.0, 100.0]]))
            xs |= {float(c[0, 0]), float(c[1, 0])}
            ys |= {float(c[0, 1]), float(c[1, 1])}
    return np.array(sorted(xs)), np.array(sorted(ys))


def measure(split: str, n: int, checkpoint=None) -> dict:
    kinds: collections.Counter = collections.Counter()
    at_border = not_writer = short = short_written = 0
    per_word = []
    for word in cursive.split_words(split)[:n]:
        h = W.word_height(word)
        img, written = W.render_word(word, h)
        plan = plan_image(img, checkpoint=checkpoint, polarity="dark", progress=False)
        strokes = [np.asarray(s, np.float64) for s in plan.strokes if len(s)]
        ends = np.array([p[i] for p in written for i in (0, -1)])
        xs, ys = border_lines(plan)
        tol = BORDER / plan.scale
        for k in range(len(strokes)):
            for at_end in (False, True):
                kind = end_kind(k, at_end, strokes, ends)
                kinds[kind] += 1
                if kind != "writer":
                    not_writer += 1
                    q = strokes[k][-1 if at_end else 0]
                    near = (len(xs) and np.abs(xs - q[0]).min() <= tol) or (
                        len(ys) and np.abs(ys - q[1]).min() <= tol
                    )
                    at_border += bool(near)
        short += sum(_arclength(p)[-1] < SHORT * h for p in strokes)
        short_written += sum(_arclength(np.asarray(p))[-1] < SHORT * h for p in written)
        per_word.append((len(strokes) - len(written), word, img, written, strokes, plan))
    return {
        "words": len(per_word),
        "written": sum(len(w[3]) for w in per_word),
        "drawn": sum(len(w[4]) for w in per_word),
        "kinds": dict(kinds),
        "not_writer": not_writer,
        "at_border": at_border,
        "short": short,
        "short_written": short_written,
        "per_word": per_word,
    }


def picture(per_word, path: str, n: int = 4) -> None:
    """The ``n`` words with the most strokes over the writer's, drawn one under another:
    :func:`jdraw.io.pictures.draw_strokes_png` (order colours, a dot at each start), tile
    borders in cyan."""
    import cv2

    from jdraw.io.figures import save_png
    from jdraw.io.pictures import draw_strokes_png

    rows = []
    for _, word, img, written, strokes, plan in sorted(per_word, key=lambda r: -r[0])[:n]:
        c = np.ascontiguousarray(draw_strokes_png(img, strokes, scale=1.0, line_width=2))
        xs, ys = border_lines(plan)
        for x in xs:
            cv2.line(c, (round(x), 0), (round(x), c.shape[0] - 1), (0, 200, 200), 1)
        for y in ys:
            cv2.line(c, (0, round(y)), (c.shape[1] - 1, round(y)), (0, 200, 200), 1)
        label = f"{word}: written {len(written)}, planned {len(strokes)}"
        cv2.putText(c, label, (5, 15), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (0, 0, 0), 1)
        rows.append(c)
    if rows:
        width = max(r.shape[1] for r in rows)
        pad = [((0, 4), (0, width - r.shape[1]), (0, 0)) for r in rows]
        save_png(path, np.vstack([np.pad(r, w, constant_values=255) for r, w in zip(rows, pad)]))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--split", default="val", choices=("train", "val", "test"))
    ap.add_argument("--n", type=int, default=40, help="words (the split's first)")
    ap.add_argument("--checkpoint", default=None, help="planner bundle (default: the bundled one)")
    ap.add_argument("--png", default=None, help="draw the words with the most extra strokes here")
    a = ap.parse_args(argv)
    r = measure(a.split, a.n, a.checkpoint)
    total = sum(r["kinds"].values())
    print(f"{r['words']} {a.split} words: {r['drawn']} planned strokes, {r['written']} written")
    print("| end of a planned stroke | ends | share |\n| --- | ---: | ---: |")
    for kind in ("writer", "dead end", "other's middle", "own line", "other's end"):
        m = r["kinds"].get(kind, 0)
        print(f"| {kind} | {m} | {m / max(total, 1):.2f} |")
    print(
        f"ends not the writer's within {BORDER} canvas px of a tile border: "
        f"{r['at_border']} of {r['not_writer']}"
    )
    print(
        f"strokes shorter than {SHORT:.0%} of the word's height: {r['short']} planned, "
        f"{r['short_written']} written"
    )
    if a.png:
        picture(r["per_word"], a.png)
        print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
