"""How far the splitter's seeds alone move the dev figures: one traced run, fitted again.

  PYTHONPATH=. python bench/splitter_seeds.py WORKDIR [--variant NAME] [--sets 3] [--words 40]

WORKDIR is a run of ``python train.py --config configs/default.py[:NAME] --workdir
WORKDIR`` that got as far as its bundle: the splitter stage's traced examples are in
``WORKDIR/splitter/examples``. Set ``k`` of ``--sets`` fits the splitter stage again
on those examples, with seeds ``k * m`` to ``k * m + m - 1`` (``m`` is the stage's
``members``, so set 0 is the run's own bundle, scored as it is). Each other set is
written as a bundle, ``WORKDIR/seeds/set_K/bundle``: the run's models and ranker, and
the set's splitter.
The set is scored as ``bench/dev_scores.py`` scores a bundle. The script prints one row
per set, then each figure's lowest and highest. A change to the planner that moves a
figure less than this spread has not been shown to move it (docs/scripts.md, 2026-12-08).

Each fit takes about 20 s on the 2-core CPU, and each set's scores about 1.5 min.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import shutil

import dev_scores

from configs import default
from jdraw.train import pipeline
from jdraw.train import splitter as splitter_train

# (name, how to read it from dev_scores.scores' dict)
COLUMNS = (
    ("KanjiVG val order", lambda r: r["kanji_val"]["order_all_pairs"]),
    ("KanjiVG val direction", lambda r: r["kanji_val"]["direction_agreement"]),
    ("Latin stroke (1 px)", lambda r: r["latin_dev"]["clean_1px"]["stroke_acc"]),
    ("Latin order (1 px)", lambda r: r["latin_dev"]["clean_1px"]["order_all_pairs"]),
    ("Latin direction (1 px)", lambda r: r["latin_dev"]["clean_1px"]["direction_agreement"]),
    ("cursive drawn/written", lambda r: r["words"]["stroke_ratio"]),
    ("cursive per piece", lambda r: r["words"]["strokes_per_piece"]),
    ("cursive stroke acc", lambda r: r["words"]["stroke_acc"]),
)


def fit_set(workdir: pathlib.Path, stage_cfg, k: int) -> pathlib.Path:
    """Set ``k``'s bundle: set 0 is the run's own; others are made once, then reused."""
    if k == 0:
        return workdir / "bundle"
    here = workdir / "seeds" / f"set_{k}"
    out = here / "bundle"
    if (out / "splitter.json").exists():
        return out
    cfg = pipeline.resolve(stage_cfg, workdir)
    cfg.seed = int(cfg.seed) + k * int(cfg.get("members", 1))
    cfg.out = str(here / "splitter_out")
    stage = here / "splitter"
    stage.mkdir(parents=True, exist_ok=True)
    if not (stage / "examples").exists():
        (stage / "examples").symlink_to((workdir / "splitter" / "examples").resolve())
    splitter_train.train(cfg, stage, progress=False)
    tmp = here / "bundle.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.copytree(workdir / "bundle", tmp)
    for ext in ("npz", "json"):
        shutil.copy2(pathlib.Path(cfg.out) / f"splitter.{ext}", tmp / f"splitter.{ext}")
    tmp.rename(out)
    return out


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("workdir", type=pathlib.Path)
    p.add_argument("--variant", default=None, help="configs/default.py's variant of the run")
    p.add_argument("--sets", type=int, default=3, help="seed sets (set 0: the run's own)")
    p.add_argument("--words", type=int, default=40, help="cursive val words")
    p.add_argument("--out", default=None, help="write every set's scores here as JSON")
    a = p.parse_args(argv)
    if a.sets < 1 or a.words < 1:
        p.error("--sets and --words must be at least 1")
    examples = a.workdir / "splitter" / "examples"
    if not (a.workdir / "bundle" / "bundle.json").exists() or not examples.is_dir():
        p.error(f"{a.workdir}: not a finished configs/default.py run (no bundle or examples)")
    stage_cfg = default.get_config(a.variant).stages.splitter
    rows = {}
    for k in range(a.sets):
        bundle = fit_set(a.workdir, stage_cfg, k)
        r = dev_scores.scores(str(bundle), a.words)
        rows[k] = [get(r) for _, get in COLUMNS]
        print(f"set {k}: " + ", ".join(f"{n} {v:.4f}" for (n, _), v in zip(COLUMNS, rows[k])))
    print("\n| figure | " + " | ".join(f"set {k}" for k in rows) + " | spread |")
    print("| --- |" + " ---: |" * (len(rows) + 1))
    for j, (name, _) in enumerate(COLUMNS):
        vals = [rows[k][j] for k in rows]
        cells = " | ".join(f"{v:.4f}" for v in vals)
        print(f"| {name} | {cells} | {min(vals):.4f}-{max(vals):.4f} |")
    if a.out:
        named = {k: dict(zip([n for n, _ in COLUMNS], v)) for k, v in rows.items()}
        pathlib.Path(a.out).write_text(json.dumps(named, indent=2) + "\n")


if __name__ == "__main__":
    main()
