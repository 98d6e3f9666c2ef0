"""The "beyond the paper" table: the paper's model beside ours, one ingredient at a time.

  python -m jdraw.evaluation.beyond [--results results] [--out results/beyond.md]

Reads the ``eval.py`` results ``beyond_{name}[_clean|_variants].json`` of the
paper's model (``paper``, scored with our ranker too) and of ours (``ours``,
``fast_local``, ``robust``, ``robust_canon``, ``robust_join``, ``lean``,
``lean_split``, ``lean_near``, ``lean_reach``) and
writes a Markdown table:
for each planner and stroke order, order agreement over matched pairs and
over all pairs, exact order, direction, stroke and pixel accuracy and drawn /
true strokes on the whole KanjiVG test split, and stroke accuracy and
drawn / true strokes on the split drawn by OpenCV 1 pixel, 3 and 5 pixels wide.
"""

from __future__ import annotations

import argparse
import json
import pathlib

ROWS = (
    ("paper", "model", "paper's model (Table I row 1), as traced"),
    ("paper", "xy", "paper's model, strokes sorted by start x + y (reference rule)"),
    ("paper", "ranker", "paper's model + learned stroke ranker"),
    ("ours", "model", "ours: whole-canvas start model, as traced"),
    ("ours", "xy", "ours, strokes sorted by start x + y"),
    ("ours", "ranker", "ours + learned stroke ranker"),
    ("fast_local", "ranker", "ours, smaller local model (fast_local, retired) + ranker"),
    (
        "robust",
        "model",
        "ours, robust: local and start models also on lines drawn other ways, as traced",
    ),
    ("robust", "ranker", "ours, robust + its ranker (previous default)"),
    (
        "robust_canon",
        "ranker",
        "ours, robust + its ranker; thick lines redrawn straight through junctions",
    ),
    ("robust_join", "ranker", "ours, robust + its ranker; and strokes joined through junctions"),
    (
        "lean",
        "model",
        "ours, lean: 8/16-channel local model, half-resolution start model, joins; as traced",
    ),
    ("lean", "ranker", "ours, lean + its ranker (previous default)"),
    (
        "lean_split",
        "model",
        "ours, lean + learned splitter: strokes cut at corners, joined, crumbs drawn on; as traced",
    ),
    ("lean_split", "ranker", "ours, lean + splitter + ranker (previous default)"),
    (
        "lean_near",
        "ranker",
        "ours, the previous default; strokes that others draw over dropped",
    ),
    (
        "lean_reach",
        "model",
        "ours, lean + splitter that also joins ends through the ink (configs/default.py); "
        "as traced",
    ),
    ("lean_reach", "ranker", "ours, lean + that splitter + ranker (bundled default)"),
)

# Files merged per planner, later ones overriding: whole test split, then other drawings.
_PARTS = ("beyond_{}.json", "beyond_{}_clean.json", "beyond_{}_variants.json")


def _cell(res: dict, split: str, order: str, key: str, fmt: str = "{:.4f}") -> str:
    try:
        return fmt.format(res[split]["by_order"][order][key])
    except KeyError:
        return "—"


def table(results_dir) -> str:
    d = pathlib.Path(results_dir)
    res: dict = {}
    for n in dict.fromkeys(name for name, _, _ in ROWS):
        for part in _PARTS:
            f = d / part.format(n)
            if f.exists():
                res.setdefault(n, {}).update(json.loads(f.read_text()))
    head = (
        "| planner and order | order, matched pairs | order, all pairs | exact order | "
        "direction | stroke acc | pixel acc | strokes / true | OpenCV: stroke acc, strokes / "
        "true | 3-px lines: stroke acc, strokes / true | 5-px lines: stroke acc, strokes / true |\n"
        + "| --- " * 11
        + "|"
    )
    lines = [head]
    for name, order, label in ROWS:
        r = res.get(name)
        if r is None:
            continue
        c = lambda split, key, fmt="{:.4f}", r=r, order=order: _cell(r, split, order, key, fmt)  # noqa: E731
        lines.append(
            f"| {label} | {c('test_full', 'order_agreement')} | "
            f"{c('test_full', 'order_all_pairs')} | {c('test_full', 'exact_order', '{:.3f}')} | "
            f"{c('test_full', 'direction_agreement')} | {c('test_full', 'stroke_acc')} | "
            f"{c('test_full', 'pixel_acc')} | {c('test_full', 'stroke_ratio', '{:.3f}')} | "
            f"{c('test_cv2', 'stroke_acc')}, {c('test_cv2', 'stroke_ratio', '{:.3f}')} | "
            f"{c('test_px3', 'stroke_acc')}, {c('test_px3', 'stroke_ratio', '{:.3f}')} | "
            f"{c('test_thick3', 'stroke_acc')}, {c('test_thick3', 'stroke_ratio', '{:.3f}')} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", default="results")
    p.add_argument("--out", default="results/beyond.md")
    a = p.parse_args(argv)
    text = table(a.results)
    pathlib.Path(a.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
