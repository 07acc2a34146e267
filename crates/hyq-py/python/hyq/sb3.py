"""``HyQVecEnv``: the Rust-batched HyQ envs as a Stable-Baselines3 ``VecEnv``.

Stable-Baselines3 does not take Gymnasium vector envs. Its ``VecEnv`` resets an env in the
step that ends its episode and reports, per env, ``terminal_observation`` (the final
observation, which PPO bootstraps from on a timeout) and ``TimeLimit.truncated`` (timeout and
not terminated). This adapter runs the core's vector env in same-step autoreset mode and fills
those keys, so a training loop gets the same data ``DummyVecEnv`` over N ``HyQEnv`` would give,
at the core's speed::

    from stable_baselines3 import PPO
    from hyq.sb3 import HyQVecEnv

    venv = HyQVecEnv(num_envs=8, seed=0)
    PPO("MlpPolicy", venv).learn(100_000)

Importing this module needs Stable-Baselines3 (and so PyTorch).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env import VecEnv

from hyq.vector import HyQVectorEnv


def _indices(num_envs: int, indices: None | int | Sequence[int]) -> list[int]:
    if indices is None:
        return list(range(num_envs))
    if isinstance(indices, int):
        return [indices]
    return list(indices)


class HyQVecEnv(VecEnv):
    """``num_envs`` HyQ envs as a Stable-Baselines3 ``VecEnv`` (same-step autoreset).

    Arguments: ``num_envs``, ``seed`` (env i is seeded ``seed + i`` at the first reset; as
    ``VecEnv.seed``), and every argument of ``hyq.HyQEnv`` (configuration keys, ``env_config``,
    ``render_mode``), ``backend`` also a list of engines assigned round-robin to the envs
    (``backend=["rapier", "mujoco"]``, as ``hyq.HyQVectorEnv`` takes it; ``infos[i]["backend"]``
    names env i's). ``infos[i]`` is ``HyQEnv``'s info of env i's step, plus
    ``TimeLimit.truncated`` and, on the step that ended an episode, ``terminal_observation``
    (the info is the final step's; the returned observation is the next episode's first).
    """

    def __init__(
        self,
        num_envs: int = 1,
        seed: int | None = None,
        env_config: Mapping[str, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        self.venv = HyQVectorEnv(
            num_envs=num_envs,
            env_config=env_config,
            autoreset_mode=AutoresetMode.SAME_STEP,
            **kwargs,
        )
        self._actions: np.ndarray | None = None
        super().__init__(
            self.venv.num_envs,
            self.venv.single_observation_space,
            self.venv.single_action_space,
        )
        if seed is not None:
            # gymnasium seeds a space's sampler from the OS's entropy when a vector env batches
            # it; seeded here, what a run pickles with the spaces (VecNormalize's statistics
            # file) repeats byte for byte.
            self.observation_space.seed(seed)
            self.action_space.seed(seed)
            self.seed(seed)

    def reset(self) -> np.ndarray:
        """Resets every env with the seeds and options set since the last reset."""
        seeds = list(self._seeds)
        options = self._options
        if any(options):
            goals = {repr(o.get("goal")) for o in options}
            if len(goals) > 1:
                raise ValueError("per-env reset options differ: this VecEnv takes one goal for all")
        option = options[0] if options else {}
        obs, _ = self.venv.reset(
            seed=None if all(s is None for s in seeds) else seeds,
            options=option or None,
        )
        self.reset_infos = [self.venv.env_info(i) for i in range(self.num_envs)]
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        """Stores the actions for ``step_wait``."""
        self._actions = np.asarray(actions)

    def step_wait(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[dict[str, Any]]]:
        """Steps every env (in Rust); returns (observations, rewards, dones, infos)."""
        if self._actions is None:
            raise RuntimeError("step_wait() called without step_async(actions)")
        actions, self._actions = self._actions, None
        obs, rewards, terminated, truncated, _ = self.venv.step(actions)
        dones = terminated | truncated
        infos: list[dict[str, Any]] = []
        for i in range(self.num_envs):
            if dones[i]:
                info = self.venv.final_info(i)
                info["terminal_observation"] = self.venv.final_observation(i)
                self.reset_infos[i] = self.venv.env_info(i)
            else:
                info = self.venv.env_info(i)
            info["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            infos.append(info)
        return obs, rewards.astype(np.float32), dones, infos

    def close(self) -> None:
        """Closes the vector env."""
        self.venv.close()

    def get_images(self) -> Sequence[np.ndarray | None]:
        """One frame per env (``render_mode="rgb_array"``)."""
        frames = self.venv.render()
        return list(frames) if frames is not None else [None] * self.num_envs

    def get_attr(self, attr_name: str, indices: None | int | Sequence[int] = None) -> list[Any]:
        """An attribute of the envs: they share one configuration, so the vector env's."""
        value = getattr(self.venv, attr_name)
        return [value for _ in _indices(self.num_envs, indices)]

    def set_attr(
        self, attr_name: str, value: Any, indices: None | int | Sequence[int] = None
    ) -> None:
        """Refused: the envs live in Rust and share one configuration."""
        raise AttributeError(
            f"cannot set {attr_name!r}: the HyQ envs share one configuration, fixed at construction"
        )

    def env_method(
        self,
        method_name: str,
        *method_args: Any,
        indices: None | int | Sequence[int] = None,
        **method_kwargs: Any,
    ) -> list[Any]:
        """Calls the vector env's per-env methods (``env_info``, ``final_info``, ...) for each
        index."""
        method = getattr(self.venv, method_name)
        return [
            method(i, *method_args, **method_kwargs)
            for i in _indices(self.num_envs, indices)
        ]

    def env_is_wrapped(
        self, wrapper_class: type, indices: None | int | Sequence[int] = None
    ) -> list[bool]:
        """No env is wrapped (they are not Python objects)."""
        return [False for _ in _indices(self.num_envs, indices)]
