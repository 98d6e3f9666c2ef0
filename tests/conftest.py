import os
import tempfile

# Tests run on the CPU with a small, fixed thread budget; no test asserts on time.
os.environ.setdefault("JAX_PLATFORMS", "cpu")
# The persistent compilation cache (jdraw.compile_cache) goes to a temporary folder, never
# the user's ~/.cache; kept between runs on one machine, so a second run compiles less.
os.environ.setdefault(
    "JDRAW_CACHE_DIR", os.path.join(tempfile.gettempdir(), f"jdraw-test-cache-{os.getuid()}")
)

import numpy as np
import pytest


@pytest.fixture(scope="session")
def kanji_set():
    from jdraw.data import kanji

    return kanji.load(progress=False)


@pytest.fixture
def rng():
    return np.random.default_rng(0)


# CI sets JDRAW_NO_SKIP=1: there a skipped test (a missing GL context, a missing browser)
# fails, since a test that CI skips tests nothing. Elsewhere a skip says why and passes.
@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if os.environ.get("JDRAW_NO_SKIP") and report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else report.longrepr
        report.outcome = "failed"
        report.longrepr = f"skipped, and JDRAW_NO_SKIP is set (CI): {reason}"
