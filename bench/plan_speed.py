"""Characters per second of ``jdraw.plan``: exact window encoder vs full-image encoder.

  python bench/plan_speed.py [--checkpoint DIR] [--chars 64]

Same weights, same characters (held-out KanjiVG test split); the two
encodings must give identical actions (checked). Prints a table.
"""

import argparse
import time

import numpy as np

import jdraw
from jdraw import demo, kanji


def bench(targets, batch, encoding, checkpoint):
    n = (len(targets) // batch) * batch
    chunks = [targets[i : i + batch] for i in range(0, n, batch)]
    jdraw.plan(chunks[0], checkpoint=checkpoint, local_encoding=encoding)  # compile
    t = time.perf_counter()
    plans = [jdraw.plan(c, checkpoint=checkpoint, local_encoding=encoding) for c in chunks]
    dt = time.perf_counter() - t
    actions = [a[:m] for p in plans for a, m in zip(p.actions, p.lengths)]
    return n / dt, actions, int(sum(p.lengths.sum() for p in plans))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--checkpoint", default=None, help="bundle folder (default: the bundled model)")
    ap.add_argument("--chars", type=int, default=64, help="characters per measurement")
    ap.add_argument(
        "--full-chars", type=int, default=8, help="characters for the slow full encoder at batch 1"
    )
    args = ap.parse_args()
    ks = kanji.load()
    idx = kanji.split_indices(ks, "test")[: args.chars]
    targets = np.stack([demo.sample(ks, int(i)).target for i in idx])
    rows = []
    for batch in (1, 64):
        if batch > len(targets):
            continue
        sub_full = targets[: max(args.full_chars, batch)] if batch == 1 else targets[:batch]
        w_cps, w_act, steps = bench(
            targets if batch > 1 else sub_full, batch, "window", args.checkpoint
        )
        f_cps, f_act, _ = bench(sub_full, batch, "full", args.checkpoint)
        same = all(np.array_equal(a, b) for a, b in zip(w_act, f_act))
        rows.append((batch, w_cps, f_cps, w_cps / f_cps, same))
    head = f"{'batch':>5} | {'window chars/s':>14} | {'full chars/s':>12} | {'ratio':>6}"
    print(head + " | identical actions")
    print("-" * 66)
    for b, w, f, r, same in rows:
        print(f"{b:>5} | {w:>14.2f} | {f:>12.3f} | {r:>5.1f}x | {same}")


if __name__ == "__main__":
    main()
