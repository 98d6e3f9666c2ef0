"""How well the start candidates (jdraw.model.start_net.start_candidates) fit KanjiVG's starts.

  python bench/start_candidates.py [--chars 400]

For every stroke of the first training characters, in KanjiVG's order: is
its true start a candidate, given the strokes before it; and what fraction
of the pixels a start may take (jdraw.state.allowed_starts) are candidates.
"""

import argparse

import jax.numpy as jnp
import numpy as np

from jdraw import state
from jdraw.data import batches, kanji
from jdraw.data import demos as demo
from jdraw.model.start_net import start_candidates


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--chars", type=int, default=400)
    a = p.parse_args()
    ks = kanji.load(progress=False)
    hit = total = cand = allowed = 0
    for i in kanji.split_indices(ks, "train")[: a.chars]:
        d = demo.sample(ks, int(i))
        t = jnp.asarray(d.target)
        visited = np.zeros_like(d.target)
        for s in d.strokes:
            v = jnp.asarray(visited)
            x = state.global_state(t, v, jnp.zeros_like(t), jnp.zeros(2, jnp.int32), False)
            c = np.asarray(start_candidates(x[None]))[0]
            ok = np.asarray(state.allowed_starts(t, v, False))
            hit += bool(c[s[0][1], s[0][0]])
            total += 1
            cand += int((c & ok).sum())
            allowed += int(ok.sum())
            visited = visited | batches._union([s])
    print(
        f"{total} strokes of {a.chars} characters: true start is a candidate for "
        f"{hit / total:.4f}; candidates are {cand / allowed:.4f} of the allowed pixels"
    )


if __name__ == "__main__":
    main()
