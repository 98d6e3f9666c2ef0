"""Table I: collects eval.py results and training logs into results/table1.{json,md}.

  python -m jdraw.evaluation.table [--results results] [--runs runs]

Each row needs ``results/<config name>.json`` (from ``eval.py --name <config
name>``) and its training workdir's ``metrics.jsonl``; a row without them is
listed as not measured, with the command that would measure it.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import pathlib

ROWS = [
    (1, "Proposed model (Fig. 2)", "paper", (0.9988, 0.9990, 0.9630, 0.9646)),
    (
        2,
        "Model 1 + (a) LSTM replaced by a fully connected layer",
        "row2_fc",
        (0.9985, 0.9973, 0.9564, 0.9532),
    ),
    (3, "Model 1 + (b) Initial Extraction", "row3_initial", (0.9964, 0.9957, 0.8746, 0.8822)),
    (4, "Model 3 + (a)", "row4_initial_fc", (0.9995, 0.9999, 0.8666, 0.8809)),
    (
        5,
        "(c) Global model without local model",
        "row5_global_only",
        (0.2693, 0.2773, 0.1565, 0.1680),
    ),
]


def _last_progress(metrics: pathlib.Path) -> dict:
    out = {}
    if metrics.exists():
        for line in metrics.read_text().splitlines():
            rec = json.loads(line)
            if "strokes_seen" in rec:
                out = rec
    return out


def _hash(path: pathlib.Path) -> str | None:
    return hashlib.sha256(path.read_bytes()).hexdigest()[:16] if path.exists() else None


def collect(results="results", runs="runs", bundles: dict | None = None) -> list[dict]:
    results, runs = pathlib.Path(results), pathlib.Path(runs)
    bundles = bundles or {}
    rows = []
    for rid, desc, name, paper in ROWS:
        res_path = results / f"{name}.json"
        res = json.loads(res_path.read_text()) if res_path.exists() else {}
        # A training log counts only for a row that has been evaluated; the copy under
        # results/ is the one committed, runs/ the live workdir.
        logs = [results / f"{name}_training_metrics.jsonl", runs / name / "metrics.jsonl"]
        log = next((p for p in logs if p.exists()), logs[-1])
        prog = _last_progress(log) if res else {}
        bundle = pathlib.Path(bundles.get(name, runs / name / "bundle"))
        row = {
            "id": rid,
            "description": desc,
            "config": f"configs/{name}.py",
            "checkpoint": {"path": str(bundle), "params_sha256_16": _hash(bundle / "params.npz")},
            "pixel_acc_train": res.get("train_random", {}).get("pixel_acc"),
            "pixel_acc_test": res.get("test_random", {}).get("pixel_acc"),
            "stroke_acc_train": res.get("train_random", {}).get("stroke_acc"),
            "stroke_acc_test": res.get("test_random", {}).get("stroke_acc"),
            "pixel_acc_test_full": res.get("test_full", {}).get("pixel_acc"),
            "stroke_acc_test_full": res.get("test_full", {}).get("stroke_acc"),
            "strokes_seen": prog.get("strokes_seen"),
            "global_seen": prog.get("global_seen"),
            "steps": prog.get("step"),
            "wall_time_s": prog.get("wall_time_s"),
            "paper": dict(
                zip(
                    ("pixel_acc_train", "pixel_acc_test", "stroke_acc_train", "stroke_acc_test"),
                    paper,
                )
            ),
            "command": f"python train.py --config configs/{name}.py --workdir runs/{name} && "
            f"python eval.py --checkpoint {bundle} --name {name}",
        }
        rows.append(row)
    return rows


def _f(v):
    return "—" if v is None else f"{v:.4f}"


def markdown(rows: list[dict]) -> str:
    lines = [
        "# Table I, reproduced",
        "",
        "Pixel and stroke accuracy (§IV-A) on 100 random training and 100 random test characters "
        "(test in parentheses, as the paper prints it), the paper's numbers beside ours. "
        "Made by `python -m jdraw.evaluation.table` from `results/<name>.json` (eval.py) "
        "and each run's "
        "`metrics.jsonl`.",
        "",
        "| id | model | pixel acc | paper | stroke acc | paper | whole test split (pixel / stroke) "
        "| strokes fed | wall time |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        p = r["paper"]
        wall = "—" if r["wall_time_s"] is None else f"{r['wall_time_s'] / 60:.0f} min"
        seen = "—" if r["strokes_seen"] is None else f"{r['strokes_seen']:,}"
        lines.append(
            f"| {r['id']} | {r['description']} "
            f"| {_f(r['pixel_acc_train'])} ({_f(r['pixel_acc_test'])}) "
            f"| {p['pixel_acc_train']:.4f} ({p['pixel_acc_test']:.4f}) "
            f"| {_f(r['stroke_acc_train'])} ({_f(r['stroke_acc_test'])}) "
            f"| {p['stroke_acc_train']:.4f} ({p['stroke_acc_test']:.4f}) "
            f"| {_f(r['pixel_acc_test_full'])} / {_f(r['stroke_acc_test_full'])} "
            f"| {seen} | {wall} |"
        )
    missing = [r for r in rows if r["stroke_acc_test"] is None]
    lines += ["", "Commands (train, then evaluate):", ""]
    lines += [f"- row {r['id']}: `{r['command']}`" for r in rows]
    if missing:
        lines += ["", "Not measured yet: " + ", ".join(f"row {r['id']}" for r in missing) + "."]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description="Collects Table I.")
    ap.add_argument("--results", default="results")
    ap.add_argument("--runs", default="runs")
    ap.add_argument("--notes", default=None, help="markdown file appended to table1.md")
    args = ap.parse_args()
    rows = collect(args.results, args.runs, {"paper": "jdraw/checkpoints/paper"})
    out = pathlib.Path(args.results)
    out.mkdir(parents=True, exist_ok=True)
    (out / "table1.json").write_text(json.dumps({"rows": rows}, indent=2) + "\n")
    md = markdown(rows)
    if args.notes:
        md += "\n" + pathlib.Path(args.notes).read_text()
    (out / "table1.md").write_text(md)
    print(md)


if __name__ == "__main__":
    main()
