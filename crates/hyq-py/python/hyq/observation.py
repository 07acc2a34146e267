"""The spec's section 3 observation table as data: one row per observation value, with its
name, the table's bounds, its unit, whether the spec gives the bounds only as estimates (rows
33-38) and whether every value respects them (the contact flags and the quaternion, rows 24-32).

The env's observation space declares these bounds only on the invariant rows (unless
``clip_observations=True``); users who normalise by the table read it here::

    import numpy as np, hyq
    low = np.array([r.low for r in hyq.OBSERVATION_TABLE], dtype=np.float32)
    high = np.array([r.high for r in hyq.OBSERVATION_TABLE], dtype=np.float32)
"""

from __future__ import annotations

from typing import NamedTuple

from hyq import _core


class ObservationRow(NamedTuple):
    """One row of the observation table."""

    #: Position in the observation vector.
    index: int
    #: The row's name, e.g. ``"lf_haa_angle"``.
    name: str
    #: The table's lower bound.
    low: float
    #: The table's upper bound.
    high: float
    #: ``"rad"``, ``"rad/s"``, ``"0/1"``, ``"1"`` (quaternion), ``"m/s^2"`` or ``"m"``.
    unit: str
    #: Whether the spec gives these bounds only as estimates (rows 33-38).
    estimated: bool
    #: Whether every observation respects these bounds (rows 24-32).
    invariant: bool


#: The 39 rows, in observation order.
OBSERVATION_TABLE: tuple[ObservationRow, ...] = tuple(
    ObservationRow(*row) for row in _core.observation_table()
)
