"""Checks of the arguments Python would otherwise coerce silently: each refusal names the
argument. ``TypeError`` for a value of the wrong kind, ``ValueError`` for one out of range (and,
as for every bad action, for an action that is not an array of real numbers)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

import numpy as np

from hyq import _core

#: The most envs (and pool threads) a vector env may have: the core's bound.
MAX_ENVS = _core.MAX_ENVS
MAX_THREADS = _core.MAX_THREADS
#: The frame sides ``render_width`` and ``render_height`` accept (pixels).
RENDER_SIDES = (_core.RENDER_SIDE_MIN, _core.RENDER_SIDE_MAX)


def check_flag(name: str, value: Any) -> bool:
    """A real bool (``True``, ``False`` or a NumPy bool): ``bool("no")`` is True."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"{name} = {value!r}: expected True or False")


def check_count(name: str, value: Any, low: int, high: int) -> int:
    """An integer (not a bool, not a float) from `low` to `high`."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} = {value!r}: expected an integer from {low} to {high}")
    if not low <= int(value) <= high:
        raise ValueError(f"{name} = {value}: expected an integer from {low} to {high}")
    return int(value)


def check_index(value: Any, count: int) -> int:
    """An env index: an integer from 0 to `count` - 1."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"env index {value!r}: expected an integer from 0 to {count - 1}")
    if not 0 <= int(value) < count:
        raise IndexError(f"env index {value} out of range: there are {count} envs")
    return int(value)


def check_path(name: str, value: Any) -> str | None:
    """A file path (a string or an ``os.PathLike``), or None."""
    if value is None:
        return None
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise TypeError(f"{name} = {value!r}: expected a path (a str or os.PathLike) or None")
    return value


def check_options(value: Any) -> Mapping[str, Any]:
    """``reset(options=...)``: a mapping (``{"goal": [x, y, z]}``), or None for none."""
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise TypeError(
            f"reset options = {value!r}: expected a dict such as {{'goal': [x, y, z]}}, or None"
        )
    return value


def as_real_array(name: str, value: Any) -> np.ndarray:
    """`value` as a float64 array, refusing anything but real numbers (strings would be parsed,
    a complex number would lose its imaginary part), with `name` in the message."""
    if np.ma.isMaskedArray(value):
        raise ValueError(f"{name} is a masked array, whose mask would be ignored: pass a plain array")
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name} = {value!r}: expected real numbers ({e})") from None
    if array.dtype.kind not in "biuf":
        raise ValueError(f"{name} = {value!r} has dtype {array.dtype}: expected real numbers")
    return array.astype(np.float64)


def as_actions(value: Any, ndim: int, shape: tuple[int, ...]) -> np.ndarray:
    """`value` as a contiguous float64 array of `ndim` dimensions, refusing what would lose
    information on the way: a masked array (its mask would be ignored), and anything but real
    numbers (a complex action would lose its imaginary part; strings and objects would be
    parsed)."""
    if np.ma.isMaskedArray(value):
        raise ValueError(
            "action is a masked array, whose mask would be ignored: pass a plain array "
            "(np.ma.filled(a, value) fills the masked entries)"
        )
    array = np.asarray(value)
    if array.dtype.kind not in "biuf":
        raise ValueError(
            f"action has dtype {array.dtype}: expected real numbers (float, int or bool)"
        )
    if array.ndim != ndim:
        raise ValueError(f"action has shape {array.shape}, expected {shape}")
    return np.ascontiguousarray(array, dtype=np.float64)
