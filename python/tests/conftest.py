"""Shared fixtures: a seeded generator whose seed is printed (pytest -v shows it on failure)."""
import os

import numpy as np
import pytest

SEED = int(os.environ.get("CJ_SEED", "20261126"))


@pytest.fixture
def rng():
    print(f"seed {SEED} (set CJ_SEED to replay)")
    return np.random.default_rng(SEED)


@pytest.fixture
def source_dir():
    return os.environ.get("CJ_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
