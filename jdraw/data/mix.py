"""Training sets beyond KanjiVG, by name, for the tracer-trained parts (splitter, ranker).

A config's ``extra`` maps a set's name to how many augmented examples of it
to trace beside the KanjiVG characters, e.g. ``{"latin": 1500}``. Each set is
a :class:`jdraw.data.kanji.KanjiSet` with the pool of indices to draw from,
so every pipeline that takes KanjiVG takes it unchanged.
"""

from __future__ import annotations

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
    if name == "cursive":
        from jdraw.data import cursive

        ks = cursive.fragments("train")
        return ks, np.arange(len(ks))
    raise ValueError(f"unknown training set {name!r}; expected 'kanji', 'latin' or 'cursive'")


def salt(name: str) -> int:
    """A seed component that keeps each extra set's random draws apart (0 for KanjiVG)."""
    return 0 if name == "kanji" else 1 + sum(ord(c) for c in name)
