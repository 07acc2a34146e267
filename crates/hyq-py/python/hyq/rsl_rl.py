"""``HyQRslRlVecEnv``: the Rust-batched HyQ envs as an rsl_rl ``VecEnv``.

rsl_rl (``pip install rsl-rl-lib``; the learner of legged_gym, Isaac Lab, Genesis and mjlab)
drives a batched environment through ``get_observations()`` and ``step(actions)``, with torch
tensors in and out: observations as a ``TensorDict`` of groups, rewards, dones, and an
``extras`` dict whose ``time_outs`` mark the envs whose episode hit the time limit (PPO then
bootstraps them instead of treating the limit as a terminal state) and whose ``log`` entries
reach rsl_rl's logger. This adapter runs the core's vector env in same-step autoreset mode
(an env that ends its episode is reset in the same call, and ``step`` returns its next
episode's first observation, as rsl_rl expects) and fills those keys::

    from rsl_rl.runners import OnPolicyRunner
    from hyq.rsl_rl import HyQRslRlVecEnv

    env = HyQRslRlVecEnv(num_envs=16, seed=0, action={"mode": "offset"})
    OnPolicyRunner(env, train_cfg, log_dir="runs/rsl", device="cpu").learn(100)

The observation group is ``"policy"`` (map it with ``obs_groups = {"actor": ["policy"],
"critic": ["policy"]}``). ``extras["log"]`` holds, over the episodes that ended in the step,
``hyq/distance_m`` (K − D^T), ``hyq/reach_rate``, ``hyq/fall_rate``,
``hyq/joint_limit_rate`` and ``hyq/episode_return`` (on several engines, also each engine's
``hyq/<engine>_distance_m`` and ``hyq/<engine>_reach_rate``); rsl_rl's logger averages each
over the iteration. Episode lengths belong to the core: ``episode_length_buf`` reports them, and
assigning it (rsl_rl's ``init_at_random_ep_len``) is refused.

Importing this module needs rsl_rl (and so PyTorch and tensordict).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import torch
from gymnasium.vector import AutoresetMode
from rsl_rl.env import VecEnv
from tensordict import TensorDict

from hyq.vector import HyQVectorEnv

#: The observation group the adapter returns.
OBS_GROUP = "policy"


def _distance_walked(info: Mapping[str, Any]) -> float:
    """K - D^T: how much closer to the goal the trunk ended than it started (m)."""
    goal = np.asarray(info["goal"], dtype=np.float64)
    start = np.asarray(info["initial_position"], dtype=np.float64)
    return float(np.linalg.norm(goal - start) - info["distance_to_goal"])


class HyQRslRlVecEnv(VecEnv):
    """``num_envs`` HyQ envs as an rsl_rl ``VecEnv`` (same-step autoreset, CPU tensors).

    Arguments: ``num_envs``; ``seed`` (env i is seeded ``seed + i`` at the first reset, made
    when the adapter is built); ``device`` (where the tensors go; the envs step on the CPU);
    ``threads`` (a dedicated rayon pool; results do not depend on it); and every argument of
    ``hyq.HyQEnv`` (``robot``, ``backend``, configuration keys, ``env_config``), ``backend``
    also a list of engines assigned round-robin to the envs (``backend=["rapier", "mujoco"]``,
    as ``hyq.HyQVectorEnv`` takes it; ``backends`` names each env's).
    """

    def __init__(
        self,
        num_envs: int = 1,
        seed: int = 0,
        device: str | torch.device = "cpu",
        env_config: Mapping[str, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        self.venv = HyQVectorEnv(
            num_envs=num_envs,
            env_config=env_config,
            autoreset_mode=AutoresetMode.SAME_STEP,
            **kwargs,
        )
        self.num_envs = self.venv.num_envs
        #: Each env's engine, in env order.
        self.backends = self.venv.backends
        self.num_actions = int(self.venv.single_action_space.shape[0])
        self.max_episode_length = int(self.venv.max_time_steps)
        self.device = torch.device(device)
        #: The observation rows' names, in order.
        self.observation_names = [row.name for row in self.venv.observation_table]
        self.cfg = {
            "robot": self.venv.robot,
            "num_envs": self.num_envs,
            "seed": seed,
            "config": {**(dict(env_config) if env_config else {}), **kwargs},
        }
        #: The final infos (``hyq.HyQEnv``'s) of the episodes that ended in the last step, with
        #: their returns and lengths: ``(env index, info, return, length)``.
        self.ended: list[tuple[int, dict[str, Any], float, int]] = []
        self._lengths = np.zeros(self.num_envs, dtype=np.int64)
        self._returns = np.zeros(self.num_envs, dtype=np.float64)
        self._obs = self._tensor_obs(self.venv.reset(seed=int(seed))[0])

    @property
    def episode_length_buf(self) -> torch.Tensor:
        """Each env's steps since its reset (the core's t)."""
        return torch.as_tensor(self._lengths.copy(), device=self.device)

    @episode_length_buf.setter
    def episode_length_buf(self, value: torch.Tensor) -> None:
        raise ValueError(
            "episode_length_buf: the episode lengths are the core's (t of each env) and cannot be "
            "set; rsl_rl's init_at_random_ep_len is not supported"
        )

    def _tensor_obs(self, obs: np.ndarray) -> TensorDict:
        return TensorDict(
            {OBS_GROUP: torch.as_tensor(obs, device=self.device)},
            batch_size=[self.num_envs],
            device=self.device,
        )

    def get_observations(self) -> TensorDict:
        """The current observations, as ``{"policy": (num_envs, n)}`` float32."""
        return self._obs

    def reset(self, seed: int | None = None) -> tuple[TensorDict, dict]:
        """Resets every env (env i seeded ``seed + i``, or continuing its streams)."""
        obs, _ = self.venv.reset(seed=seed)
        self._lengths[:] = 0
        self._returns[:] = 0.0
        self._obs = self._tensor_obs(obs)
        return self._obs, {}

    def step(self, actions: torch.Tensor) -> tuple[TensorDict, torch.Tensor, torch.Tensor, dict]:
        """Steps every env with its row of ``actions``; returns (observations, rewards, dones,
        extras). A finite action outside the action space is clipped by the core (and flagged
        in its info), as rsl_rl's Gaussian samples are unbounded. A NumPy array (or a nested
        list) of numbers is taken as the tensor it converts to."""
        if not isinstance(actions, torch.Tensor):
            try:
                actions = torch.as_tensor(np.asarray(actions, dtype=np.float32))
            except (TypeError, ValueError) as e:
                raise ValueError(f"actions: expected a tensor or an array of numbers, got "
                                 f"{type(actions).__name__} ({e})") from None
        a = actions.detach().to("cpu", torch.float32).numpy()
        obs, rewards, terminated, truncated, _ = self.venv.step(a)
        dones = terminated | truncated
        self._lengths += 1
        self._returns += rewards
        extras: dict[str, Any] = {
            # The core's truncated is timeout and not terminated (spec §6).
            "time_outs": torch.as_tensor(truncated, device=self.device),
        }
        ended = np.flatnonzero(dones)
        self.ended = [
            (int(i), self.venv.final_info(int(i)), float(self._returns[i]), int(self._lengths[i]))
            for i in ended
        ]
        if ended.size:
            extras["log"] = self._episode_log(ended)
            self._lengths[ended] = 0
            self._returns[ended] = 0.0
        self._obs = self._tensor_obs(obs)
        return (
            self._obs,
            torch.as_tensor(rewards, dtype=torch.float32, device=self.device),
            torch.as_tensor(dones, dtype=torch.long, device=self.device),
            extras,
        )

    def _episode_log(self, ended: np.ndarray) -> dict[str, torch.Tensor]:
        """The facts of the episodes that ended in this step, one value per episode."""
        infos = [info for _, info, _, _ in self.ended]
        column = lambda values: torch.tensor(values, dtype=torch.float32, device=self.device)  # noqa: E731
        log = {
            "hyq/distance_m": column([_distance_walked(info) for info in infos]),
            "hyq/reach_rate": column([float(info["reached"]) for info in infos]),
            "hyq/fall_rate": column([float(info["fell"]) for info in infos]),
            "hyq/joint_limit_rate": column([float(info["joint_limit"]) for info in infos]),
            "hyq/episode_return": column(self._returns[ended].tolist()),
            "hyq/episode_length": column(self._lengths[ended].astype(np.float64).tolist()),
        }
        if len(set(self.backends)) > 1:
            # On several engines, each engine's distance and reach rate too.
            for engine in dict.fromkeys(info["backend"] for info in infos):
                mine = [info for info in infos if info["backend"] == engine]
                log[f"hyq/{engine}_distance_m"] = column([_distance_walked(i) for i in mine])
                log[f"hyq/{engine}_reach_rate"] = column([float(i["reached"]) for i in mine])
        return log

    def final_info(self, i: int) -> dict[str, Any] | None:
        """Env ``i``'s final info if its episode ended in the last step, else None."""
        return self.venv.final_info(i)

    def close(self) -> None:
        """Closes the vector env."""
        self.venv.close()
