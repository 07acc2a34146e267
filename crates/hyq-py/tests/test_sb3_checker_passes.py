"""Stable-Baselines3's own environment checker (``check_env``, run from the pinned SB3 wheel;
see ``sb3_without_torch``) passes on ``HyQEnv`` with no warning and no assertion, on the default
env and on every combination of the options that shape the spaces: it asserts that every
observation lies in the observation space, which the default env's old space (the section 3
table) did not hold."""

from __future__ import annotations

import types
import warnings

import pytest

import hyq
from sb3_without_torch import sb3  # noqa: F401  (the fixture)

#: SB3's advice for a Box action space other than [-1, 1], which absolute actions draw by design.
NORMALIZE_ADVICE = "symmetric and normalized Box action space"


def sb3_warnings(sb3: types.SimpleNamespace, **kwargs) -> list[str]:
    env = hyq.HyQEnv(**kwargs)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sb3.check_env(env, warn=True)
    return [str(w.message) for w in caught]


@pytest.mark.parametrize("repeat", [1, 2, 3])
def test_sb3_check_env_is_silent_on_the_default_env(
    sb3: types.SimpleNamespace, repeat: int
) -> None:
    assert sb3_warnings(sb3) == []


@pytest.mark.parametrize("clip", [False, True])
@pytest.mark.parametrize("render_mode", [None, "rgb_array"])
@pytest.mark.parametrize("mode", ["normalized", "delta", "absolute", "offset"])
def test_sb3_check_env_is_silent_on_every_option_combination(
    sb3: types.SimpleNamespace, clip: bool, render_mode: str | None, mode: str
) -> None:
    caught = sb3_warnings(
        sb3, clip_observations=clip, render_mode=render_mode, action={"mode": mode}
    )
    if mode == "absolute":
        caught = [m for m in caught if NORMALIZE_ADVICE not in m]
    assert caught == []
