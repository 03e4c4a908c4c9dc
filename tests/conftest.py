"""Shared test configuration."""
import numpy as np
import pytest


def pytest_sessionfinish(session, exitstatus):
    # "No tests collected" (exit status 5) is not a failure for CI.
    if exitstatus == 5:
        session.exitstatus = 0


@pytest.fixture
def rng():
    """Seeded generator: tests are reproducible."""
    return np.random.default_rng(20181)
