"""``HyQVectorEnv``: N HyQ environments stepped together in Rust (rayon, GIL released).

Registered as ``HyQ-v0``'s ``vector_entry_point``, so ``gym.make_vec("HyQ-v0", num_envs=N)``
returns it. Env i of ``reset(seed=s)`` is seeded ``s + i``, as Gymnasium's own vector envs do,
and gives exactly what a single ``HyQEnv`` reset with that seed and given the same actions
gives, across autoresets too.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from hyq import _core
from hyq._config import config_pairs, split_options
from hyq._checks import (
    MAX_ENVS,
    MAX_THREADS,
    as_actions,
    check_count,
    check_index,
    check_options,
    check_path,
)
from hyq.env import check_choice, check_render_mode, check_seed, core_options, reset_goal
from hyq.observation import ObservationRow

_MODES = {
    AutoresetMode.NEXT_STEP: "next_step",
    AutoresetMode.SAME_STEP: "same_step",
    AutoresetMode.DISABLED: "disabled",
}


def split_backends(env_options: Mapping[str, Any]) -> tuple[dict[str, Any], list[str] | None]:
    """``backend`` as a list (or tuple) of engine names, taken out of ``env_options``: the
    engines assigned round-robin to the envs (env i on the ``i % len``-th). A single name stays
    in the options, and the list is None."""
    options = dict(env_options)
    backend = options.get("backend")
    if not isinstance(backend, (list, tuple)):
        return options, None
    del options["backend"]
    names = [check_choice("backend", name, "") for name in backend]
    if not names:
        raise ValueError("backend = []: expected a backend's name or a non-empty list of them")
    return options, names


class HyQVectorEnv(VectorEnv):
    """``num_envs`` environments of one robot and configuration, on one backend or a mix of
    them, stepped in one call.

    Arguments: ``num_envs``; ``autoreset_mode`` (``AutoresetMode.NEXT_STEP`` by default, the
    Gymnasium default: the step after an episode ends resets that env, ignoring its action and
    returning its first observation with reward 0; also ``SAME_STEP`` and ``DISABLED``);
    ``max_episode_steps`` (what ``gym.make_vec`` passes from the registration: the core's t_max
    unless ``max_time_steps`` is given); ``threads`` (a dedicated rayon pool; results do not
    depend on it); and every argument of ``HyQEnv``. ``backend`` may also be a list of engines,
    assigned round-robin to the envs (``backend=["rapier", "mujoco"]``: env i on the
    ``i % 2``-th), each built in and each given at least one env; env i then gives exactly what
    a single ``HyQEnv`` on its engine gives, and ``infos["backend"]`` names each env's engine.

    ``infos`` holds every key of ``HyQEnv``'s info (``hyq.INFO_SCHEMA``) as an array over the
    envs, each with Gymnasium's ``_key`` mask, as ``SyncVectorEnv`` would give them.
    """

    metadata = {
        "autoreset_mode": AutoresetMode.NEXT_STEP,
        "render_modes": ["rgb_array"],
        "render_fps": 100,
    }

    def __init__(
        self,
        num_envs: int = 1,
        render_mode: str | None = None,
        env_config: Mapping[str, Any] | None = None,
        autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
        max_episode_steps: int | None = None,
        threads: int | None = None,
        **kwargs: Any,
    ) -> None:
        env_options, config = split_options(env_config, kwargs)
        render_mode = env_options.pop("render_mode", render_mode)
        check_render_mode(render_mode)
        mode = AutoresetMode(autoreset_mode)
        # t_max is `max_time_steps` when given, else `max_episode_steps` (which
        # gym.make_vec passes from the registration), else the core's default.
        task = config.get("task")
        given = "max_time_steps" in config or (
            isinstance(task, Mapping) and "max_time_steps" in task
        )
        if max_episode_steps is not None and not given:
            # Checked here, under its own name: the core would blame `task.max_time_steps`,
            # which the caller did not set.
            if isinstance(max_episode_steps, bool) or not isinstance(max_episode_steps, (int, np.integer)):
                raise TypeError(f"max_episode_steps = {max_episode_steps!r}: expected an integer")
            if not 1 <= max_episode_steps < 2**63:
                raise ValueError(f"max_episode_steps = {max_episode_steps}: expected an integer "
                                 "from 1 to 2**63 - 1")
            config["max_time_steps"] = int(max_episode_steps)
        self.render_mode = render_mode
        num_envs = check_count("num_envs", num_envs, 1, MAX_ENVS)
        if threads is not None:
            threads = check_count("threads", threads, 1, MAX_THREADS)
        env_options, backends = split_backends(env_options)
        self._core = _core.VecCore(
            config_pairs(config),
            num_envs,
            autoreset_mode=_MODES[mode],
            config_file=check_path("config_file", env_options.get("config_file")),
            threads=threads,
            backends=backends,
            **core_options(env_options),
        )
        self.num_envs = self._core.num_envs
        self.single_observation_space = spaces.Box(
            low=self._core.observation_low(),
            high=self._core.observation_high(),
            dtype=np.float32,
        )
        self.single_action_space = spaces.Box(
            low=self._core.action_low(),
            high=self._core.action_high(),
            dtype=np.float32,
        )
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.metadata = {
            **self.metadata,
            "autoreset_mode": mode,
            "render_fps": round(1.0 / self._core.env_dt),
        }

    @property
    def max_time_steps(self) -> int:
        """t_max: the env step at which the core truncates an episode."""
        return self._core.max_time_steps

    @property
    def backends(self) -> tuple[str, ...]:
        """Each env's engine, in env order."""
        return tuple(self._core.backends())

    @property
    def robot(self) -> str:
        """The robot's name (its profile's ``name``)."""
        return self._core.robot

    @property
    def observation_table(self) -> tuple[ObservationRow, ...]:
        """The envs' observation table (``hyq.HyQEnv.observation_table``: the robot's rows, then
        those of ``observation.extra``), the same for every env."""
        return tuple(ObservationRow(*row) for row in self._core.observation_table())

    def reset(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Resets the envs. ``seed``: an int (env i gets ``seed + i``), a list of one seed (or
        None) per env, or None (each env continues its streams). ``options``: ``goal`` (every
        env reset gets this goal) and ``reset_mask`` (reset only these envs; the others report
        their current observation)."""
        options = dict(check_options(options))
        mask = options.pop("reset_mask", None)
        goal = reset_goal(options)
        if mask is not None:
            mask = np.asarray(mask, dtype=bool)
            if mask.shape != (self.num_envs,):
                raise ValueError(
                    f"reset_mask has shape {mask.shape}, expected ({self.num_envs},)"
                )
            mask = [bool(m) for m in mask]
        seeds = None
        if seed is not None and not isinstance(seed, (int, np.integer)):
            seeds = [check_seed(s) for s in seed]
            if len(seeds) != self.num_envs:
                raise ValueError(f"{len(seeds)} seeds given for {self.num_envs} envs")
            seed = None
        seed = check_seed(seed)
        if seed is not None and seed + self.num_envs - 1 >= 2**64:
            # Env i is seeded seed + i: past 2**64 - 1 it would wrap to seed 0 silently.
            raise ValueError(f"seed = {seed}: env i is seeded seed + i, so {self.num_envs} envs "
                             f"need a seed up to 2**64 - {self.num_envs}")
        super().reset(seed=seed)
        return self._core.reset(seed=seed, seeds=seeds, goal=goal, mask=mask)

    def step(
        self, actions: Any
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Steps every env with its row of ``actions`` (shape (num_envs, 12))."""
        return self._core.step(as_actions(actions, 2, self.action_space.shape))

    def render(self) -> tuple[np.ndarray, ...] | None:
        """With ``render_mode="rgb_array"``: one uint8 (H, W, 3) frame per env."""
        if self.render_mode is None:
            gymnasium.logger.warn(
                "render() called without a render_mode: make the env with "
                'render_mode="rgb_array"'
            )
            return None
        return tuple(self._core.render(i) for i in range(self.num_envs))

    def env_info(self, i: int) -> dict[str, Any]:
        """Env ``i``'s info of its last step or reset, as ``HyQEnv`` gives it."""
        return self._core.env_info(check_index(i, self.num_envs))

    def final_observation(self, i: int) -> np.ndarray | None:
        """With ``SAME_STEP`` autoreset: env ``i``'s final observation if its episode ended in
        the last step, else None."""
        return self._core.final_observation(check_index(i, self.num_envs))

    def final_info(self, i: int) -> dict[str, Any] | None:
        """With ``SAME_STEP`` autoreset: env ``i``'s final info if its episode ended in the last
        step, else None."""
        return self._core.final_info(check_index(i, self.num_envs))
