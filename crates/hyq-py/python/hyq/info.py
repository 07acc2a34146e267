"""The schema of ``info``: every key ``HyQEnv.step`` and ``reset`` give, on every step, with
its one type (the README's env card states it with each key's meaning; a test keeps the two
equal). A vector env's info holds each key as an array over the envs, as Gymnasium's
``SyncVectorEnv`` would build it: ``int`` as int64, ``float`` as float64, ``bool`` as bool,
``str`` as an object array of str, and ``float64 array (k,)`` as float64 of shape (N, k)."""

from __future__ import annotations

from hyq import _core

#: Key -> type: ``"int"``, ``"float"``, ``"bool"``, ``"str"`` or ``"float64 array (k,)"``. The
#: reward terms are the core's (``_core.REWARD_TERMS``: hyq-spec's table of terms, in order).
INFO_SCHEMA: dict[str, str] = {
    "t": "int",
    **{term: "float" for term in _core.REWARD_TERMS},
    "reward": "float",
    "distance_to_goal": "float",
    "d_n": "float",
    "roll": "float",
    "pitch": "float",
    "yaw": "float",
    "reasons": "str",
    "reached": "bool",
    "joint_limit": "bool",
    "fell": "bool",
    "timeout": "bool",
    "diverged": "bool",
    "goal": "float64 array (3,)",
    "initial_position": "float64 array (3,)",
    "joint_targets": "float64 array (12,)",
    "action_clipped": "bool",
    "observation_clipped": "bool",
    "joint_at_limit": "str",
    "joint_at_limit_angle": "float",
    "joint_at_limit_side": "str",
    "divergence": "str",
}
