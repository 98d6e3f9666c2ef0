"""Fuzzes ``jdraw.plan`` with thousands of valid and invalid inputs; prints counts by outcome.

Command (bundled model, ~N / 64 planner calls of 64 images):

  nice -n 10 python bench/fuzz.py --cases 5120

Valid 100x100 images (noise of any density, single pixels, borders,
checkerboards, random lines, blanks) are planned in batches; each image's
plan must keep every stroke on ink and report ``truncated`` exactly when ink
is left undrawn. Invalid inputs (wrong shapes, NaN/inf, complex, strings,
objects, empty and ragged batches, bad ``max_steps``/``checkpoint``) must
raise ``ValueError``. A call running past ``--timeout`` counts as a hang.
"""

from __future__ import annotations

import argparse
import collections
import signal
import time

import cv2
import numpy as np

import jdraw
from jdraw.images import canonical
from jdraw.plans import render

KINDS = ("noise", "pixels", "border", "checker", "lines", "blank")


def valid_image(rng: np.random.Generator) -> np.ndarray:
    kind = KINDS[rng.integers(len(KINDS))]
    img = np.zeros((100, 100), np.uint8)
    if kind == "noise":
        img = rng.random((100, 100)) < rng.choice([0.001, 0.01, 0.05, 0.2, 0.5, 0.9, 1.0])
    elif kind == "pixels":
        n = rng.integers(1, 8)
        img[rng.integers(0, 100, n), rng.integers(0, 100, n)] = 1
    elif kind == "border":
        w = rng.integers(1, 4)
        img[:w], img[-w:], img[:, :w], img[:, -w:] = 1, 1, 1, 1
    elif kind == "checker":
        k = rng.integers(1, 9)
        yy, xx = np.mgrid[:100, :100]
        img = (yy // k + xx // k) % 2 == 0
    elif kind == "lines":
        for _ in range(rng.integers(1, 5)):
            a, b = rng.integers(0, 100, 2), rng.integers(0, 100, 2)
            cv2.line(img, (int(a[0]), int(a[1])), (int(b[0]), int(b[1])), 1, 1)
    return np.asarray(img) != 0


def invalid_input(rng: np.random.Generator):
    """``(images, kwargs)`` that ``plan`` must reject with a ValueError."""
    ok = np.zeros((100, 100))
    k = rng.integers(10)
    if k == 0:
        shape = tuple(rng.integers(0, 120, rng.integers(0, 4)))
        if shape in ((100, 100), (100, 100, 1)) or (len(shape) == 3 and shape[1:] == (100, 100)):
            shape = (99, 100)
        return np.zeros(shape), {}
    if k == 1:
        x = ok.copy()
        x[rng.integers(100), rng.integers(100)] = rng.choice([np.nan, np.inf, -np.inf])
        return x, {}
    if k == 2:
        return ok.astype(complex), {}
    if k == 3:
        return ok.astype(str), {}
    if k == 4:
        return ok.astype(object), {}
    if k == 5:
        return np.zeros((0, 100, 100)), {}
    if k == 6:
        return [[0.0] * 100] * 99 + [[0.0] * int(rng.integers(1, 99))], {}
    if k == 7:
        return ok, {"max_steps": int(rng.integers(-5, 1))}
    if k == 8:
        return ok, {"checkpoint": int(rng.integers(100))}
    return np.zeros((int(rng.integers(1, 4)), 1, 100, 100)), {}


class Hang(Exception):
    pass


def _alarm(signum, frame):
    raise Hang


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=5000)
    ap.add_argument("--batch", type=int, default=64)
    ap.add_argument("--max-steps", type=int, nargs="+", default=[16, 200])
    ap.add_argument("--invalid-fraction", type=float, default=0.2)
    ap.add_argument("--timeout", type=int, default=600, help="seconds a call may take")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    signal.signal(signal.SIGALRM, _alarm)
    counts: collections.Counter = collections.Counter()
    n_invalid = int(args.cases * args.invalid_fraction)
    t0 = time.perf_counter()
    for _ in range(n_invalid):
        images, kwargs = invalid_input(rng)
        signal.alarm(args.timeout)
        try:
            jdraw.plan(images, **kwargs)
            counts["invalid: accepted (BAD)"] += 1
        except Hang:
            counts["invalid: hang (BAD)"] += 1
        except ValueError:
            counts["invalid: ValueError"] += 1
        except Exception as e:  # noqa: BLE001 - counted, that is the point
            counts[f"invalid: {type(e).__name__} (BAD)"] += 1
        finally:
            signal.alarm(0)
    done = n_invalid
    while done < args.cases:
        b = min(args.batch, args.cases - done)
        ms = int(rng.choice(args.max_steps))
        targets = np.stack([valid_image(rng) for _ in range(b)])
        signal.alarm(args.timeout)
        try:
            p = jdraw.plan(targets, max_steps=ms)
        except Hang:
            counts["valid: hang (BAD)"] += b
            continue
        except Exception as e:  # noqa: BLE001
            counts[f"valid: {type(e).__name__} (BAD)"] += b
            continue
        finally:
            signal.alarm(0)
            done += b
        drawn = render(p)
        # jdraw.plan draws the input's canonical lines (jdraw.images.canonical):
        # judge against those.
        for t, d, tr in zip(map(canonical.canonicalise, targets), drawn, p.truncated):
            left = bool((t & ~d).any())
            if (d & ~t).any():
                counts["valid: stroke off ink (BAD)"] += 1
            elif bool(tr) != left:
                counts["valid: dishonest truncated (BAD)"] += 1
            else:
                counts["valid: truncated, honest" if left else "valid: complete"] += 1
        print(f"{done}/{args.cases} cases, {time.perf_counter() - t0:.0f} s", flush=True)
    print(f"\n{sum(counts.values())} cases in {time.perf_counter() - t0:.0f} s (seed {args.seed})")
    print(f"| {'outcome':<36} | {'cases':>6} |")
    print(f"| {'-' * 36} | {'-' * 6} |")
    for k in sorted(counts):
        print(f"| {k:<36} | {counts[k]:>6} |")


if __name__ == "__main__":
    main()
