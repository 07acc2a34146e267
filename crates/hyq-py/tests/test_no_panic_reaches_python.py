"""No Rust panic reaches Python as ``pyo3_runtime.PanicException`` (a ``BaseException`` that
``except Exception`` in a training loop does not catch): inputs that used to panic are refused
by name, and a panic that still happened (a bug) would arrive as a ``RuntimeError`` saying so,
after which that env refuses every call. Two threads on one env get a message that says what is
wrong, not PyO3's bare "Already borrowed"."""

from __future__ import annotations

import threading

import gymnasium as gym
import numpy as np
import pytest

import hyq


def test_a_joint_noise_that_used_to_panic_is_refused_by_name() -> None:
    # 1e308 passed validation and panicked in the uniform sampler at every reset.
    with pytest.raises(ValueError, match="reset.joint_noise_rad"):
        hyq.HyQEnv(reset={"joint_noise_rad": 1e308})
    with pytest.raises(ValueError, match="reset.joint_noise_rad"):
        gym.make_vec("HyQ-v0", num_envs=2, reset={"joint_noise_rad": 1e308})


@pytest.mark.parametrize("make", [lambda: hyq.HyQEnv(), lambda: hyq.HyQVectorEnv(num_envs=2)])
def test_a_panic_arrives_as_a_runtime_error_and_the_env_is_retired(make) -> None:
    env = make()
    env.reset(seed=0)
    with pytest.raises(RuntimeError, match="internal error") as err:
        env._core._panic_for_tests()
    assert isinstance(err.value, Exception)
    assert "please report" in str(err.value)
    with pytest.raises(RuntimeError, match="internal error"):
        env.reset(seed=0)


def test_two_threads_on_one_env_are_told_what_is_wrong() -> None:
    env = hyq.HyQEnv(max_time_steps=100_000)
    env.reset(seed=0)
    action = np.zeros(12, dtype=np.float32)
    errors: list[str] = []
    steps = [0, 0]

    def worker(k: int) -> None:
        for _ in range(300):
            try:
                env.step(action)
                steps[k] += 1
            except RuntimeError as e:
                errors.append(str(e))

    threads = [threading.Thread(target=worker, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors, "the two threads were expected to meet"
    assert all("another thread" in e for e in errors), errors[:3]
    assert not any("Already borrowed" in e for e in errors)
    # Nothing was corrupted: every successful step counted once, and the env works on.
    *_, info = env.step(action)
    assert info["t"] == sum(steps) + 1
