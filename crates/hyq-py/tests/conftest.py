"""Shared helpers for the hyq package's tests.

The tests run against the installed package (``maturin develop`` or a wheel); ``cargo xtask
test`` builds and installs it into its venv first.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import hyq

REPO = Path(__file__).resolve().parents[3]


def pose_action(env: hyq.HyQEnv, fractions: tuple[float, float, float]) -> np.ndarray:
    """An absolute-mode action putting every leg's (haa, hfe, kfe) at these fractions of the
    joint's range (0 the lower limit, 1 the upper)."""
    low = env.action_space.low.astype(np.float64)
    high = env.action_space.high.astype(np.float64)
    f = np.tile(np.asarray(fractions, dtype=np.float64), 4)
    return low + f * (high - low)


@pytest.fixture(scope="session")
def hyq_cli() -> Path:
    """The ``hyq`` command: ``$HYQ_CLI`` if set (``cargo xtask test`` sets it), else built
    here with cargo."""
    given = os.environ.get("HYQ_CLI")
    if given:
        path = Path(given)
        assert path.is_file(), f"HYQ_CLI={given} is not a file"
        return path
    subprocess.run(["cargo", "build", "-q", "-p", "hyq-cli"], cwd=REPO, check=True)
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    path = target / "debug" / "hyq"
    assert path.is_file(), f"cargo built hyq-cli but {path} is missing"
    return path


@pytest.fixture(scope="session")
def recipes():
    """examples/recipes.py, the training examples' shared module, loaded from the checkout (it
    is not part of the installed package)."""
    spec = importlib.util.spec_from_file_location("recipes", REPO / "examples" / "recipes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
