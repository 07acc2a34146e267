"""IIT's HyQ quadruped walking to a goal, as a Gymnasium environment on a Rust core.

Importing this package registers ``HyQ-v0``::

    import gymnasium as gym
    import hyq

    env = gym.make("HyQ-v0")                    # or gym.make("hyq:HyQ-v0") without the import
    envs = gym.make_vec("HyQ-v0", num_envs=8)   # the Rust-batched vector env (rayon)

``hyq.HyQEnv`` is the single environment, ``hyq.HyQVectorEnv`` the vector env and
``hyq.sb3.HyQVecEnv`` an adapter for Stable-Baselines3 (import ``hyq.sb3`` only where
Stable-Baselines3 is installed).
"""

import gymnasium

from hyq import _core
from hyq.env import HyQEnv
from hyq.info import INFO_SCHEMA
from hyq.observation import OBSERVATION_TABLE, ObservationRow
from hyq.vector import HyQVectorEnv

__version__ = _core.__version__

#: The registered id.
ENV_ID = "HyQ-v0"

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

__all__ = [
    "ENV_ID",
    "INFO_SCHEMA",
    "MAX_EPISODE_STEPS",
    "OBSERVATION_TABLE",
    "HyQEnv",
    "HyQVectorEnv",
    "ObservationRow",
    "__version__",
]
