"""IIT's HyQ quadruped walking to a goal, as a Gymnasium environment on a Rust core.

Importing this package registers ``HyQ-v0``::

    import gymnasium as gym
    import hyq

    env = gym.make("HyQ-v0")                    # or gym.make("hyq:HyQ-v0") without the import
    envs = gym.make_vec("HyQ-v0", num_envs=8)   # the Rust-batched vector env (rayon)
    env = gym.make("HyQ-v0", robot="anymal_c", backend="mujoco")  # another robot, engine

and one id per bundled robot (``ANYmalC-v0`` is ``HyQ-v0`` with ``robot="anymal_c"``, ``Go1-v0``
with ``robot="go1"``; ``A1-v0``, ``Go1URDF-v0``, ``ANYmalB-v0``, ``Laikago-v0`` likewise). The velocity-command task (docs/velocity.md) has its own ids,
``HyQ-Velocity-v0`` and ``ANYmalC-Velocity-v0`` (the same env with ``task.kind = "velocity"``)::

    env = gym.make("HyQ-Velocity-v0", env_config={"command.lin_vel_x": [0.5, 0.5]})

``hyq.HyQEnv`` is the single environment, ``hyq.HyQVectorEnv`` the vector env and
``hyq.sb3.HyQVecEnv`` an adapter for Stable-Baselines3 (import ``hyq.sb3`` only where
Stable-Baselines3 is installed).
"""

import gymnasium

from hyq import _core
from hyq.env import HyQEnv
from hyq.info import INFO_SCHEMA, randomize_info_schema
from hyq.observation import OBSERVATION_TABLE, ObservationRow, observation_table
from hyq.vector import HyQVectorEnv

__version__ = _core.__version__

#: The registered id (HyQ by default; ``robot=`` picks another).
ENV_ID = "HyQ-v0"

#: The bundled robots' names, the default (``"hyq"``) first.
ROBOTS: tuple[str, ...] = tuple(_core.ROBOTS)

#: The physics backends this build has, the default (``"rapier"``) first.
BACKENDS: tuple[str, ...] = tuple(_core.backends())

#: The reward terms, in the order the info and the records hold them (hyq-spec's table).
REWARD_TERMS: tuple[str, ...] = tuple(_core.REWARD_TERMS)

#: The gait regularisers ``regularizers={...}`` can switch on (docs/regularizers.md), in the
#: order the info holds them: ``info["regularizers.<name>"]`` for each one that is on, beside
#: ``info["regularizers.reward"]``, what they add to the spec's reward.
REGULARIZER_TERMS: tuple[str, ...] = tuple(_core.REGULARIZER_TERMS)

#: The registered id of each bundled robot other than the default: the same env with its
#: ``robot``.
ROBOT_IDS = {
    "anymal_c": "ANYmalC-v0",
    "go1": "Go1-v0",
    "a1": "A1-v0",
    "go1_urdf": "Go1URDF-v0",
    "anymal_b": "ANYmalB-v0",
    "laikago": "Laikago-v0",
}

#: The registered ``max_episode_steps``: the core's default t_max (``max_time_steps``), so that
#: ``env.spec.max_episode_steps`` is the episode length the core enforces.
MAX_EPISODE_STEPS = _core.default_max_time_steps()

if ENV_ID not in gymnasium.registry:
    gymnasium.register(
        id=ENV_ID,
        entry_point="hyq.env:HyQEnv",
        vector_entry_point="hyq.vector:HyQVectorEnv",
        max_episode_steps=MAX_EPISODE_STEPS,
    )
#: The registered id of the velocity-command task on each bundled robot (``task.kind =
#: "velocity"``, docs/velocity.md), the spec's ids being the goal task's.
VELOCITY_IDS = {"hyq": "HyQ-Velocity-v0", "anymal_c": "ANYmalC-Velocity-v0"}

for _robot, _id in VELOCITY_IDS.items():
    if _id not in gymnasium.registry:
        gymnasium.register(
            id=_id,
            entry_point="hyq.env:HyQEnv",
            vector_entry_point="hyq.vector:HyQVectorEnv",
            max_episode_steps=MAX_EPISODE_STEPS,
            kwargs={"robot": _robot, "kind": "velocity"},
        )
for _robot, _id in ROBOT_IDS.items():
    if _id not in gymnasium.registry:
        gymnasium.register(
            id=_id,
            entry_point="hyq.env:HyQEnv",
            vector_entry_point="hyq.vector:HyQVectorEnv",
            max_episode_steps=MAX_EPISODE_STEPS,
            kwargs={"robot": _robot},
        )

__all__ = [
    "BACKENDS",
    "ENV_ID",
    "INFO_SCHEMA",
    "MAX_EPISODE_STEPS",
    "OBSERVATION_TABLE",
    "REGULARIZER_TERMS",
    "REWARD_TERMS",
    "ROBOTS",
    "ROBOT_IDS",
    "VELOCITY_IDS",
    "HyQEnv",
    "HyQVectorEnv",
    "ObservationRow",
    "__version__",
    "observation_table",
    "randomize_info_schema",
]
