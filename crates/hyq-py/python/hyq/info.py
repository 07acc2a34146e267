"""The schema of ``info``: every key ``HyQEnv.step`` and ``reset`` give, on every step, with
its one type (the README's env card gives each key's meaning; both come from the core's one
schema). A vector env's info holds each key as an array over the envs, as Gymnasium's
``SyncVectorEnv`` would build it: ``int`` as int64, ``float`` as float64, ``bool`` as bool,
``str`` as an object array of str, and ``float64 array (k,)`` as float64 of shape (N, k)."""

from __future__ import annotations

from hyq import _core

#: Key -> type: ``"int"``, ``"float"``, ``"bool"``, ``"str"`` or ``"float64 array (k,)"``, in
#: the order the info holds them: the core's schema (hyq-env's ``INFO_KEYS``, every reward term
#: of ``_core.REWARD_TERMS`` and every end reason by name).
INFO_SCHEMA: dict[str, str] = dict(_core.INFO_SCHEMA)


def randomize_info_schema(num_links: int = 13, num_joints: int = 12) -> dict[str, str]:
    """The keys an env whose ``[randomize]`` is on adds to ``INFO_SCHEMA`` (on every step and
    reset, after the others; an env with it off has none of them), with their types, for a robot
    of ``num_links`` bodies and ``num_joints`` joints (HyQ's by default): the episode's drawn
    values under ``randomize.<key>``, the configuration key that drew each (nominal values for
    the options that are off), and the step's push, ``randomize.push_velocity_mps`` (m/s, world,
    zeros when none) and ``randomize.pushes`` (so far this episode). From the core's one schema
    (hyq-env's ``RANDOMIZE_INFO_KEYS``)."""
    return dict(_core.randomize_info_schema(num_links, num_joints))
