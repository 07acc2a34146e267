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
