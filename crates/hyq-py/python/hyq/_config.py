"""Keyword arguments and ``env_config`` dicts as the core's dotted configuration keys.

The configuration mirrors the TOML file (``hyq run --config``) table for table:

* the spec's user variables by their own names, e.g. ``fall_penalty=1.0``,
  ``exp_rew_scaling=None`` (off), ``max_time_steps=500`` (these are the ``[task]`` table; a
  ``task={...}`` dict works too);
* the other tables (``TABLES``) as dicts: ``goal={"mode": "fixed", "position": [5, 1, 0.6]}``,
  ``action={"mode": "absolute"}``, ``physics={...}``, ...;
* dotted keys as the file and ``hyq run --set`` name them: ``{"task.kind": "velocity",
  "command.lin_vel_x": [0.5, 0.5]}`` (``kind="velocity"`` is the same as ``task.kind``);
* gait regularisers added to the spec's reward, all off by default:
  ``regularizers={"preset": "legged_gym"}`` or a scale per term, e.g.
  ``regularizers={"action_rate": -0.01, "foot_slip": -0.1}`` (``hyq.REGULARIZER_TERMS``,
  docs/regularizers.md);
* ``config_file="hyq.toml"``: a TOML file read first, the keyword arguments applied on top.

``robot`` (a bundled robot's name, ``"hyq"`` or ``"anymal_c"``, or the path to a robot profile)
and ``backend`` (``"rapier"``, or ``"mujoco"`` / ``"dart"`` when the package was built with
them) choose what is simulated and how; they are not configuration keys.

Everything is checked by the core (one parser for TOML files, ``hyq run --set`` and Python):
an unknown key or a bad value raises ``ValueError`` naming the key and the value.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from typing import Any

from hyq import _core

#: The TOML tables, each given as a dict (``task`` too, beside the spec's user variables by
#: name), from the core's one list of them.
TABLES = tuple(_core.CONFIG_TABLES)

#: Keyword arguments that are not configuration keys.
ENV_KEYS = (
    "robot",
    "backend",
    "render_mode",
    "config_file",
    "clip_observations",
    "render_width",
    "render_height",
)


def toml_string(text: str) -> str:
    """`text` as a TOML basic string: quotes, backslashes and control characters escaped,
    everything else as it is (JSON's escapes differ: it writes characters beyond U+FFFF as
    surrogate pairs, which TOML refuses)."""
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def toml_key(key: Any) -> str:
    """A dict key as one TOML key: bare when it is one (letters, digits, `_`, `-`), else a
    quoted key, so that no key can spell more than itself."""
    if not isinstance(key, str):
        raise ValueError(f"configuration key {key!r}: keys are strings")
    if re.fullmatch(r"[A-Za-z0-9_-]+", key):
        return key
    return toml_string(key)


def toml_value(value: Any, key: str) -> str:
    """``value`` written as a TOML value (``None`` is ``"off"``, which unsets an optional
    reward scaling)."""
    if value is None:
        return "off"
    # NumPy arrays and scalars first: numpy.float64 is a float whose repr
    # ("np.float64(1.5)") is not a TOML number.
    if hasattr(value, "tolist"):
        return toml_value(value.tolist(), key)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        if not -(2**63) <= value < 2**63:
            # TOML's integers are 64-bit: a larger one would be read back as a malformed string.
            raise ValueError(f"{key}: an integer of {value.bit_length()} bits, beyond TOML's "
                             "64-bit integers")
        return str(value)
    if isinstance(value, float):
        # A float's repr is a TOML float, "nan", "inf" and "-inf" included.
        return repr(value)
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, os.PathLike):
        # A path (`pathlib.Path`) is its text, as `config_file` and `robot` take it.
        return toml_string(os.fsdecode(os.fspath(value)))
    if isinstance(value, Mapping):
        items = ", ".join(
            f"{toml_key(k)} = {toml_value(v, f'{key}.{k}')}" for k, v in value.items()
        )
        return "{" + items + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v, key) for v in value) + "]"
    raise ValueError(f"{key} = {value!r}: not a number, boolean, string, list or dict")


def config_pairs(options: Mapping[str, Any]) -> list[tuple[str, str]]:
    """The dotted ``(key, TOML value)`` pairs of configuration keyword arguments."""
    pairs: list[tuple[str, str]] = []
    for name, value in options.items():
        if name in TABLES:
            if not isinstance(value, Mapping):
                raise ValueError(
                    f"{name} = {value!r}: the [{name}] table is given as a dict, "
                    f"e.g. {name}={{...}}"
                )
            for key, v in value.items():
                pairs.append((f"{name}.{key}", toml_value(v, f"{name}.{key}")))
        elif "." in name:
            # A dotted key as the TOML file and ``hyq --set`` name it (``"task.kind"``,
            # ``"command.lin_vel_x"``), given as it is.
            pairs.append((name, toml_value(value, name)))
        else:
            # Every other name is a spec user variable of the [task] table; the core names
            # the accepted ones if this is not one of them.
            pairs.append((f"task.{name}", toml_value(value, name)))
    return pairs


def split_options(
    env_config: Mapping[str, Any] | None, kwargs: Mapping[str, Any]
) -> tuple[dict[str, Any], dict[str, Any]]:
    """Merges ``env_config`` (RLlib's single dict) and keyword arguments (which win), then
    splits them into (environment options, configuration options)."""
    merged: dict[str, Any] = {}
    if env_config is not None:
        if not isinstance(env_config, Mapping):
            raise ValueError(f"env_config = {env_config!r}: expected a dict")
        merged.update(env_config)
    merged.update(kwargs)
    env_options = {k: merged.pop(k) for k in ENV_KEYS if k in merged}
    return env_options, merged
