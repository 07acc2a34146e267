"""Shared helpers of the training stage's tests (`cargo xtask test --with train`): they need
PyTorch, Stable-Baselines3 and rsl_rl (examples/requirements-train.txt), which CI does not
install (5.4 GB)."""

from __future__ import annotations

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "examples"
# The training scripts import their shared module (examples/recipes.py) by name.
sys.path.insert(0, str(EXAMPLES))
