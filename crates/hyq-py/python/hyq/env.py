"""``HyQEnv``: the Gymnasium environment (``HyQ-v0``) around the Rust core."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces

from hyq import _core
from hyq._checks import (
    RENDER_SIDES,
    as_actions,
    as_real_array,
    check_count,
    check_flag,
    check_options,
    check_path,
)
from hyq._config import config_pairs, split_options
from hyq.observation import ObservationRow

#: The render modes this environment implements.
RENDER_MODES = ["rgb_array"]


def check_render_mode(render_mode: str | None) -> None:
    """Refuses, at construction, a render mode that is not implemented."""
    if render_mode is not None and render_mode not in RENDER_MODES:
        raise ValueError(
            f"render_mode={render_mode!r} is not implemented: use None or 'rgb_array' "
            "(for a window, wrap an 'rgb_array' env in gymnasium.wrappers.HumanRendering; "
            "gym.make(..., render_mode='human') does this for you)"
        )


def reset_goal(options: Mapping[str, Any] | None) -> list[float] | None:
    """The goal in ``reset(options=...)``; any key but ``goal`` is refused, and so is a goal
    of anything but three real numbers (strings are not parsed, as in actions)."""
    options = check_options(options)
    if not options:
        return None
    unknown = sorted(str(k) for k in set(options) - {"goal"})
    if unknown:
        raise ValueError(f"reset options {unknown}: unknown (the only option is 'goal')")
    goal = options.get("goal")
    if goal is None:
        return None
    goal = as_real_array("reset option goal", goal)
    if goal.shape != (3,):
        raise ValueError(f"reset option goal has shape {goal.shape}, expected (3,): [x, y, z] in m")
    return [float(v) for v in goal]


def check_choice(name: str, value: Any, default: str) -> str:
    """``robot`` or ``backend``: a string (a path-like robot profile is taken as its path)."""
    if value is None:
        return default
    if hasattr(value, "__fspath__"):
        value = value.__fspath__()
    if not isinstance(value, str):
        raise TypeError(f"{name} = {value!r}: expected a string")
    return value


def core_options(env_options: Mapping[str, Any]) -> dict[str, Any]:
    """The core's keyword arguments for the robot, the backend, clipping and frame size, checked
    by name; the defaults are the core's."""
    clip = env_options.get("clip_observations", _core.CLIP_OBSERVATIONS_DEFAULT)
    width = env_options.get("render_width", _core.RENDER_WIDTH_DEFAULT)
    height = env_options.get("render_height", _core.RENDER_HEIGHT_DEFAULT)
    return {
        "robot": check_choice("robot", env_options.get("robot"), _core.DEFAULT_ROBOT),
        "backend": check_choice("backend", env_options.get("backend"), _core.DEFAULT_BACKEND),
        "clip_observations": check_flag("clip_observations", clip),
        "render_width": check_count("render_width", width, *RENDER_SIDES),
        "render_height": check_count("render_height", height, *RENDER_SIDES),
    }


def check_seed(seed: int | None) -> int | None:
    """A seed for the core: an integer in [0, 2**64)."""
    if seed is None:
        return None
    if isinstance(seed, (bool, float)) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed = {seed!r}: expected an integer in [0, 2**64)")
    if not 0 <= int(seed) < 2**64:
        raise ValueError(f"seed = {seed}: expected an integer in [0, 2**64)")
    return int(seed)


class HyQEnv(gymnasium.Env):
    """A legged robot walking its trunk to a goal: IIT's HyQ quadruped (87 kg, 12 joints) by
    default, or ``robot="anymal_c"`` (registered as ``ANYmalC-v0``) or any robot profile path;
    on rapier physics, or ``backend="mujoco"`` / ``"dart"`` in a build with those engines.

    The sizes below are HyQ's; they come from the robot model, so another robot's spaces have
    its own (``n`` joints and ``f`` feet: ``2n + f + 12`` observation rows, ``n`` actions;
    ANYmal C's are also 39 and 12).

    **Observation**: ``Box(39,)`` float32, the spec's §3 table in order and units (joint angles,
    joint speeds, four foot contact flags, trunk contact flag, trunk quaternion w x y z, trunk
    acceleration, trunk position). As the project's spec requires (§3), values are **not**
    clipped by default, and the physics does leave the table (joint speeds past ±12 rad/s in
    about a quarter of first steps under random actions, accelerations past ±50 m/s² on
    impacts), so the space declares the table's bounds only where they always hold (the contact
    flags and the quaternion) and leaves every other row unbounded (the finite float32 range), as
    Gymnasium's MuJoCo locomotion envs do: every observation lies in it.
    ``clip_observations=True`` declares the table as the space and clips each value to its row's
    bounds (``info["observation_clipped"]`` says when). The table itself is
    ``hyq.OBSERVATION_TABLE`` for HyQ (``env.observation_table`` for the env's robot).
    ``observation={"extra": ["height_scan", "goal_vector", "trunk_velocity"]}`` (any of them,
    off by default) appends rows after the §3 ones: the terrain's heights around the trunk, the
    goal in the trunk's frame, the trunk's velocity in its frame (``env.observation_table``
    names and bounds them; docs/terrain.md).

    **Ground**: flat by default; ``terrain={"kind": "rough", "amplitude_m": 0.05}`` (or
    ``"slope"``, ``"stairs"``, ``"heightfield"`` with ``"file"``) walks on a height field, the
    robot put down standing on it and the goal's height following it (docs/terrain.md).

    **Action**: ``Box(-1, 1, (12,), float32)`` joint position targets in the default
    ``normalized`` mode (−1 a joint's lower limit, +1 its upper); ``action={"mode":
    "absolute"}`` takes radians within the joint limits, ``action={"mode": "delta"}`` a change
    of ±``max_delta_rad`` from the current angle, ``action={"mode": "offset"}`` an offset of
    ±``max_offset_rad`` from the standing pose. A NaN or a wrong shape raises ``ValueError``.

    **Reward and info**: the spec's reward; ``info`` holds every term of
    ``hyq.REWARD_TERMS``, every reason the episode ended (``reasons`` and one flag each), the
    distance to the goal, the attitude, the goal and the joint targets: every key of
    ``hyq.INFO_SCHEMA`` on every step, each with one type. ``regularizers={"preset":
    "legged_gym"}`` (or a scale per term of ``hyq.REGULARIZER_TERMS``; all off by default) adds
    gait regularisers to the reward, Σ scale · term · Δt, and ``info["regularizers.reward"]``
    and ``info["regularizers.<term>"]`` for each term that is on (docs/regularizers.md).

    **Episode end**: ``terminated`` when the goal is reached, a joint reaches a limit, the
    trunk touches the ground, or the physics diverges; ``truncated`` at ``max_time_steps``
    (default 1000 env steps = 10 s).

    Arguments: ``robot`` (a bundled robot's name, ``"hyq"`` (default) or ``"anymal_c"``, or the
    path to a robot profile TOML next to its URDF), ``backend`` (``"rapier"`` (default),
    ``"mujoco"``, ``"dart"``: those in ``hyq.BACKENDS``; another is a ``ValueError`` naming the
    build option), ``render_mode`` (None or ``"rgb_array"``), ``env_config`` (one dict, RLlib's
    convention), ``config_file`` (a TOML file), ``clip_observations``, ``render_width`` and
    ``render_height`` (pixels, default 480 × 360), and the configuration keys (see
    ``hyq._config``): the spec's user variables by name, the other TOML tables as dicts.
    """

    # One frame per env step: 100 fps at the default 10 sub-steps of 1 ms (set per instance
    # from the configuration).
    metadata = {"render_modes": RENDER_MODES, "render_fps": 100}

    def __init__(
        self,
        render_mode: str | None = None,
        env_config: Mapping[str, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        env_options, config = split_options(env_config, kwargs)
        render_mode = env_options.pop("render_mode", render_mode)
        check_render_mode(render_mode)
        self.render_mode = render_mode
        self._core = _core.Core(
            config_pairs(config),
            config_file=check_path("config_file", env_options.get("config_file")),
            **core_options(env_options),
        )
        self.observation_space = spaces.Box(
            low=self._core.observation_low(),
            high=self._core.observation_high(),
            dtype=np.float32,
        )
        self.action_space = spaces.Box(
            low=self._core.action_low(),
            high=self._core.action_high(),
            dtype=np.float32,
        )
        # Simulated frames per second of an episode: one frame per env step.
        self.metadata = {**self.metadata, "render_fps": round(1.0 / self._core.env_dt)}
        self._table: tuple[ObservationRow, ...] | None = None
        self._closed = False

    @property
    def robot(self) -> str:
        """The robot's name (its profile's ``name``: ``"hyq"``, ``"anymal_c"``, ...)."""
        return self._core.robot

    @property
    def max_time_steps(self) -> int:
        """t_max: the env step at which the core truncates the episode."""
        return self._core.max_time_steps

    @property
    def observation_names(self) -> list[str]:
        """The observation rows' names, in order (39 for HyQ)."""
        return self._core.observation_names()

    @property
    def observation_table(self) -> tuple[ObservationRow, ...]:
        """This env's observation table (the spec's section 3 table for HyQ, then the rows of
        ``observation.extra`` if any): each row's name, bounds, unit and kind."""
        if self._table is None:
            self._table = tuple(ObservationRow(*row) for row in self._core.observation_table())
        return self._table

    @property
    def joint_names(self) -> list[str]:
        """The joints' names, in action order (12 for HyQ)."""
        return self._core.joint_names()

    def config_toml(self) -> str:
        """The whole configuration in force, as TOML (readable by ``hyq run --config``)."""
        return self._core.config_toml()

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Starts an episode. ``seed`` seeds the core's goal and reset-noise streams exactly as
        ``hyq run --seed`` does (None continues them); ``options={"goal": [x, y, z]}`` sets
        this episode's goal."""
        seed = check_seed(seed)
        goal = reset_goal(options)
        super().reset(seed=seed)
        return self._core.reset(seed=seed, goal=goal)

    def step(
        self, action: Any
    ) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """One env step (10 physics sub-steps of 1 ms by default)."""
        # A 1-D action of the wrong length is refused by the core, with its message.
        return self._core.step(as_actions(action, 1, self.action_space.shape))

    def render(self) -> np.ndarray | None:
        """With ``render_mode="rgb_array"``: the current state as a uint8 (H, W, 3) frame."""
        if self.render_mode is None:
            gymnasium.logger.warn(
                "render() called without a render_mode: make the env with "
                'render_mode="rgb_array"'
            )
            return None
        return self._core.render()

    def close(self) -> None:
        """Nothing to release but memory; safe to call twice."""
        self._closed = True
