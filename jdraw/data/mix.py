"""Training sets beyond KanjiVG, by name, and mixtures of them.

For the tracer-trained parts (splitter, ranker), a config's ``extra`` maps a
set's name to how many augmented examples of it to trace beside the KanjiVG
characters, e.g. ``{"latin": 1500}`` (``latin_words``: rows of Latin glyphs,
:func:`jdraw.data.latin.words`; ``cursive_prefix``: cursive fragments written only
part-way, :func:`jdraw.data.cursive.prefixes`). For the model stages (local and start
models), ``data.extra`` maps a set's name to the share of characters drawn
from it (:class:`Mixture`; KanjiVG takes the rest). Each set is a
:class:`jdraw.data.kanji.KanjiSet` with the pool of indices to draw from, so
every pipeline that takes KanjiVG takes it unchanged.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from jdraw.data import kanji
from jdraw.data.kanji import KanjiSet


def load(name: str, progress: bool = True) -> tuple[KanjiSet, np.ndarray]:
    """``(ks, pool)``: the training set ``name`` and the indices to sample."""
    if name == "kanji":
        ks = kanji.load(progress=progress)
        return ks, kanji.split_indices(ks, "train")
    if name == "latin":
        from jdraw.data import latin

        ks = latin.load("train")
        return ks, np.arange(len(ks))
    if name == "latin_words":
        from jdraw.data import latin

        ks = latin.words("train")
        return ks, np.arange(len(ks))
    if name == "cursive":
        from jdraw.data import cursive

        ks = cursive.fragments("train")
        return ks, np.arange(len(ks))
    if name == "cursive_prefix":
        from jdraw.data import cursive

        ks = cursive.prefixes("train")
        return ks, np.arange(len(ks))
    if name == "scribble":
        from jdraw.data import scribbles

        ks = scribbles.load()
        return ks, np.arange(len(ks))
    raise ValueError(
        f"unknown training set {name!r}; "
        "expected 'kanji', 'latin', 'latin_words', 'cursive', 'cursive_prefix' or 'scribble'"
    )


@dataclasses.dataclass
class Mixture:
    """Several training sets, each character drawn from one of them at random.

    Attributes:
      sets: ``(ks, pool)`` per set, KanjiVG's first.
      p: ``[len(sets)]`` float, the probability of each.
      names: each set's name.
    """

    sets: list
    p: np.ndarray
    names: tuple

    def pick(self, rng: np.random.Generator) -> tuple[KanjiSet, int]:
        """``(ks, i)``: a set by :attr:`p`, then a character of its pool."""
        ks, pool = self.sets[int(rng.choice(len(self.sets), p=self.p))]
        return ks, int(rng.choice(pool))


def mixture(kanji_set: KanjiSet, pool, extra, progress: bool = True) -> Mixture:
    """KanjiVG (``kanji_set``, ``pool``) and the sets of ``extra`` (``{name: share}``).

    KanjiVG takes ``1 - sum(shares)`` of the characters.
    """
    shares = {str(k): float(v) for k, v in dict(extra).items()}
    rest = 1.0 - sum(shares.values())
    if rest < 0 or any(v < 0 for v in shares.values()) or "kanji" in shares:
        raise ValueError(f"data.extra {shares}: shares of other sets, >= 0, summing to <= 1")
    sets = [(kanji_set, np.asarray(pool))] + [load(k, progress) for k in shares]
    p = np.asarray([rest, *shares.values()], np.float64)
    return Mixture(sets=sets, p=p / p.sum(), names=("kanji", *shares))


def salt(name: str) -> int:
    """A seed component that keeps each extra set's random draws apart (0 for KanjiVG)."""
    return 0 if name == "kanji" else 1 + sum(ord(c) for c in name)
