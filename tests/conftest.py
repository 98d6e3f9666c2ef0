import os

# Tests run on the CPU with a small, fixed thread budget; no test asserts on time.
os.environ.setdefault("JAX_PLATFORMS", "cpu")

import numpy as np
import pytest


@pytest.fixture(scope="session")
def kanji_set():
    from jdraw.data import kanji

    return kanji.load(progress=False)


@pytest.fixture
def rng():
    return np.random.default_rng(0)
