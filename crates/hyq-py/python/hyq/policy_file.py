"""Trained policies as files: the project's ``hyq-mlp-policy`` safetensors file (what ``hyq run
--policy mlp:FILE`` replays in Rust) and its ONNX twin, for deployment anywhere ONNX runs.

::

    from hyq.policy_file import OnnxPolicy, read_policy, write_onnx

    write_onnx("assets/policies/hyq_walk.safetensors", "hyq_walk.onnx")   # needs `onnx`
    policy = OnnxPolicy("hyq_walk.onnx", robot="hyq")                     # needs `onnxruntime`
    actions = policy(observations)          # float32 (N, 39) -> float32 (N, 12)

The ONNX graph is built from the safetensors file alone (no PyTorch), operator for operator as
the Rust forward pass computes (``crates/hyq-env/src/mlp.rs``): the observation normalised by
the training statistics and clipped (in float64, as in Rust), the linear layers with the file's
activation between them, the action clipped to the environment's action space. The layers run
in float32 (the Rust pass runs them in f64 on the same f32 weights; the two agree within 1e-5,
tested on every committed policy). Opset 17, input ``obs`` (batch, n), output ``actions`` (batch, m). Its
metadata (``metadata_props``) names the robot, the observation rows and the joints in order,
the action mode and scale, the environment it was trained in and the SHA-256 of the file it was
made from; :func:`check_onnx_layout` refuses an ONNX file whose layout is not the robot's,
naming what differs (given the environment's ``env_config``, a height scan of another geometry
too).

Reading a policy file needs numpy only; building ONNX needs the ``onnx`` package and running it
``onnxruntime`` (both on PyPI), imported when used.
"""

from __future__ import annotations

import hashlib
import json
import os
import stat
import struct
from dataclasses import dataclass, field
from pathlib import Path
from collections.abc import Mapping
from typing import Any

import numpy as np

#: The ``format`` metadata of a policy file (crates/hyq-env/src/mlp.rs).
FORMAT = "hyq-mlp-policy"
#: The ``format`` metadata of its ONNX twin.
ONNX_FORMAT = "hyq-mlp-policy-onnx"
#: The ONNX operator set the graph uses (every operator in it exists since 13).
OPSET = 17
#: The ONNX IR version written: the oldest that opset 17 allows, so older runtimes load it.
IR_VERSION = 8

_DTYPES = {"F32": np.float32, "F64": np.float64}
#: The largest policy file read (bytes): the Rust reader's cap (hyq-physics' ``input::POLICY``).
MAX_POLICY_BYTES = 256 * 2**20
_ACTIVATIONS = ("tanh", "relu", "elu")


@dataclass
class PolicyFile:
    """A ``hyq-mlp-policy`` file's contents: the metadata as stored, the observation
    statistics and the layers ((out, in) weights and (out,) biases, float32), input first."""

    path: str
    metadata: dict[str, str]
    obs_mean: np.ndarray
    obs_var: np.ndarray
    layers: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    sha256: str = ""

    @property
    def robot(self) -> str:
        return self.metadata["robot"]

    @property
    def observation(self) -> list[str]:
        return json.loads(self.metadata["observation"])

    @property
    def action(self) -> list[str]:
        return json.loads(self.metadata["action"])

    @property
    def activation(self) -> str:
        return self.metadata["activation"]

    @property
    def obs_clip(self) -> float:
        return float(self.metadata["obs_clip"])

    @property
    def obs_epsilon(self) -> float:
        return float(self.metadata["obs_epsilon"])

    @property
    def env_config(self) -> dict[str, str]:
        """The configuration it was trained in: dotted keys to TOML values."""
        return json.loads(self.metadata["env_config"])


def _refuse(path: Any, reason: str) -> ValueError:
    return ValueError(f"{path}: {reason}")


def non_finite(name: str, values: np.ndarray) -> str | None:
    """Why tensor `name` cannot be part of a policy, in the Rust reader's words (``tensor
    `layers.0.weight` holds a non-finite value (NaN) at flat index 0``), or ``None`` when every
    value is finite. The reader, the ONNX writer and ``examples/export_policy.py`` all ask it, so
    a policy that ``hyq run`` refuses is never written, exported or loaded."""
    flat = np.asarray(values).reshape(-1)
    bad = np.flatnonzero(~np.isfinite(flat))
    if bad.size == 0:
        return None
    i = int(bad[0])
    value = float(flat[i])
    text = "NaN" if np.isnan(value) else ("inf" if value > 0 else "-inf")
    return f"tensor `{name}` holds a non-finite value ({text}) at flat index {i}"


def check_finite(tensors: dict[str, np.ndarray], path: Any) -> None:
    """Raises ``ValueError`` naming `path` and the first tensor of `tensors` (in their order)
    holding a non-finite value (see :func:`non_finite`)."""
    for name, values in tensors.items():
        reason = non_finite(name, values)
        if reason is not None:
            raise _refuse(path, reason)


def _read_capped(path: str | Path) -> bytes:
    """The bytes of a policy file, under the Rust reader's rule: only a regular file (a FIFO is
    opened without waiting for a writer, then refused), at most :data:`MAX_POLICY_BYTES`."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            raise _refuse(path, "is not a regular file (a FIFO, device, socket or directory): only "
                                "files are read, since a pipe would block its reader forever and a "
                                "device may never end")
        data = f.read(MAX_POLICY_BYTES + 1)
    if len(data) > MAX_POLICY_BYTES:
        raise _refuse(path, "larger than 256 MiB, which no policy is (is it the right file?)")
    return data


def read_policy(path: str | Path) -> PolicyFile:
    """Reads a ``hyq-mlp-policy`` safetensors file (numpy only). A file that is not one, whose
    shapes do not chain or which holds a non-finite value, is a ``ValueError`` naming the file
    and what is wrong, in the Rust reader's words (the Rust reader also checks the action
    mode's scale)."""
    data = _read_capped(path)
    if len(data) < 8:
        raise _refuse(path, "not a safetensors policy file (shorter than its 8-byte header length)")
    (n,) = struct.unpack("<Q", data[:8])
    try:
        header = json.loads(data[8 : 8 + n])
    except (ValueError, UnicodeDecodeError) as e:
        raise _refuse(path, f"not a safetensors policy file (its header is not JSON: {e})") from None
    if not isinstance(header, dict):
        raise _refuse(path, "not a safetensors policy file (its header is not a JSON object)")
    metadata = header.pop("__metadata__", None) or {}
    if metadata.get("format") != FORMAT:
        raise _refuse(path, f"metadata `format` is {metadata.get('format')!r}, expected {FORMAT!r}")
    for key in ("robot", "observation", "action", "activation", "obs_clip", "obs_epsilon", "env_config"):
        if key not in metadata:
            raise _refuse(path, f"metadata has no `{key}` entry (not a `{FORMAT}` file)")
    if metadata["activation"] not in _ACTIVATIONS:
        raise _refuse(path, f"unknown activation {metadata['activation']!r} (expected tanh, relu or elu)")
    body = data[8 + n :]

    def tensor(name: str, dtype: str) -> np.ndarray:
        info = header.get(name)
        if info is None:
            raise _refuse(path, f"has no tensor `{name}`")
        if info.get("dtype") != dtype:
            raise _refuse(path, f"tensor `{name}` is {info.get('dtype')}, expected {dtype}")
        try:
            begin, end = info["data_offsets"]
            values = np.frombuffer(body[begin:end], dtype=np.dtype(_DTYPES[dtype]).newbyteorder("<"))
            check_finite({name: values}, path)
            return values.reshape(info["shape"]).astype(_DTYPES[dtype])
        except (KeyError, TypeError, ValueError) as e:
            if str(e).startswith(str(path)):
                raise
            raise _refuse(path, f"tensor `{name}`: its data offsets, shape and dtype do not fit "
                                f"the file ({e})") from None

    policy = PolicyFile(
        path=str(path),
        metadata=dict(metadata),
        obs_mean=tensor("obs_mean", "F64"),
        obs_var=tensor("obs_var", "F64"),
        sha256=hashlib.sha256(data).hexdigest(),
    )
    inputs = len(policy.observation)
    if policy.obs_mean.shape != (inputs,) or policy.obs_var.shape != (inputs,):
        raise _refuse(path, f"the observation statistics are not one per observation row ({inputs})")
    while f"layers.{len(policy.layers)}.weight" in header:
        k = len(policy.layers)
        weight, bias = tensor(f"layers.{k}.weight", "F32"), tensor(f"layers.{k}.bias", "F32")
        if weight.ndim != 2 or weight.shape[1] != inputs or bias.shape != (weight.shape[0],):
            raise _refuse(path, f"layer {k} has weight {weight.shape} and bias {bias.shape}, "
                                f"expected (_, {inputs}) and (_,)")
        policy.layers.append((weight, bias))
        inputs = weight.shape[0]
    if not policy.layers:
        raise _refuse(path, "has no tensor `layers.0.weight`")
    if inputs != len(policy.action):
        raise _refuse(path, f"the last layer has {inputs} outputs, the metadata's action layout "
                            f"{len(policy.action)}")
    return policy


def action_bounds(policy: PolicyFile) -> tuple[np.ndarray, np.ndarray]:
    """The action space the Rust forward pass clips to: [-1, 1] per joint, or the joint limits
    (radians) in the `absolute` mode, taken from the robot's environment."""
    from hyq.env import HyQEnv

    mode = policy.metadata.get("action_mode", "normalized")
    env = HyQEnv(robot=policy.robot, action={"mode": mode})
    try:
        return (np.asarray(env.action_space.low, dtype=np.float32),
                np.asarray(env.action_space.high, dtype=np.float32))
    finally:
        env.close()


def to_onnx(policy: PolicyFile, low: np.ndarray, high: np.ndarray):  # noqa: ANN201 - onnx.ModelProto
    """The policy as an ONNX model (see the module docs); `low` and `high` are the action
    space's bounds."""
    import onnx
    from onnx import TensorProto, helper, numpy_helper

    n_obs, n_act = len(policy.observation), len(policy.action)
    # A non-finite weight would make a graph whose every output is NaN (the action clip's
    # Min/Max keep NaN): refused, as the reader refuses it, however `policy` was made.
    tensors = {"obs_mean": policy.obs_mean, "obs_var": policy.obs_var}
    for k, (weight, bias) in enumerate(policy.layers):
        tensors.update({f"layers.{k}.weight": weight, f"layers.{k}.bias": bias})
    check_finite(tensors, policy.path)
    std = np.sqrt(policy.obs_var + policy.obs_epsilon)
    # The normalisation runs in float64 on the float64 statistics, as the Rust pass does, so
    # the first layer sees the same float32 inputs to the bit.
    inits = [
        numpy_helper.from_array(policy.obs_mean.astype(np.float64), "obs_mean"),
        numpy_helper.from_array(std.astype(np.float64), "obs_std"),
        numpy_helper.from_array(np.array(-policy.obs_clip, dtype=np.float64), "obs_clip_low"),
        numpy_helper.from_array(np.array(policy.obs_clip, dtype=np.float64), "obs_clip_high"),
        numpy_helper.from_array(np.asarray(low, dtype=np.float32), "action_low"),
        numpy_helper.from_array(np.asarray(high, dtype=np.float32), "action_high"),
    ]
    nodes = [
        helper.make_node("Cast", ["obs"], ["obs64"], to=TensorProto.DOUBLE),
        helper.make_node("Sub", ["obs64", "obs_mean"], ["centred"]),
        helper.make_node("Div", ["centred", "obs_std"], ["scaled"]),
        helper.make_node("Clip", ["scaled", "obs_clip_low", "obs_clip_high"], ["clipped"]),
        helper.make_node("Cast", ["clipped"], ["h0"], to=TensorProto.FLOAT),
    ]
    activation = {"tanh": "Tanh", "relu": "Relu", "elu": "Elu"}[policy.activation]
    last = len(policy.layers) - 1
    for k, (weight, bias) in enumerate(policy.layers):
        inits += [numpy_helper.from_array(weight, f"layers.{k}.weight"),
                  numpy_helper.from_array(bias, f"layers.{k}.bias")]
        out = "raw_actions" if k == last else f"z{k}"
        nodes.append(helper.make_node("Gemm", [f"h{k}", f"layers.{k}.weight", f"layers.{k}.bias"],
                                      [out], transB=1))
        if k != last:
            extra = {"alpha": 1.0} if activation == "Elu" else {}
            nodes.append(helper.make_node(activation, [out], [f"h{k + 1}"], **extra))
    nodes += [
        helper.make_node("Min", ["raw_actions", "action_high"], ["below_high"]),
        helper.make_node("Max", ["below_high", "action_low"], ["actions"]),
    ]
    graph = helper.make_graph(
        nodes,
        f"{policy.robot}_policy",
        [helper.make_tensor_value_info("obs", TensorProto.FLOAT, ["batch", n_obs])],
        [helper.make_tensor_value_info("actions", TensorProto.FLOAT, ["batch", n_act])],
        inits,
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", OPSET)],
                              producer_name="hyq.policy_file")
    model.ir_version = IR_VERSION
    props = {k: v for k, v in policy.metadata.items() if k not in ("format", "format_version")}
    props.update({"format": ONNX_FORMAT, "format_version": "1",
                  "source": Path(policy.path).name, "source_sha256": policy.sha256})
    helper.set_model_props(model, props)
    onnx.checker.check_model(model, full_check=True)
    return model


def write_onnx(policy_path: str | Path, onnx_path: str | Path) -> Path:
    """Writes the ONNX twin of a policy file; returns its path."""
    import onnx

    policy = read_policy(policy_path)
    model = to_onnx(policy, *action_bounds(policy))
    onnx_path = Path(onnx_path)
    onnx_path.parent.mkdir(parents=True, exist_ok=True)
    onnx.save_model(model, str(onnx_path))
    return onnx_path


def _mismatch(what: str, trained: list[str], env: list[str]) -> str | None:
    if len(trained) != len(env):
        return f"trained on {len(trained)} {what} values, the environment has {len(env)}"
    for i, (t, e) in enumerate(zip(trained, env)):
        if t != e:
            return f"{what} value {i} was {t!r} in training, the environment's is {e!r}"
    return None


def _observation_options(props: dict[str, str], path: Any) -> dict[str, Any]:
    """The ``observation`` keys of a policy's ``env_config`` (TOML values) as ``HyQEnv``'s
    ``observation`` table: the rows it reads beyond its robot's (a height scan, say)."""
    import tomllib

    try:
        pairs = json.loads(props.get("env_config", "{}"))
        table = {key.split(".", 1)[1]: tomllib.loads(f"v = {value}")["v"]
                 for key, value in pairs.items() if key.startswith("observation.")}
    except (ValueError, AttributeError, TypeError) as e:
        raise _refuse(path, f"metadata `env_config` is not a table of TOML values ({e})") from None
    return {"observation": table} if table else {}


def _scan_geometry(env: Any) -> dict[str, Any]:
    """The height scan's geometry an environment reads (its ``observation.height_scan_*``
    keys as its written configuration holds them), or ``{}`` without a height scan."""
    import tomllib

    table = tomllib.loads(env.config_toml()).get("observation", {})
    if "height_scan" not in table.get("extra", []):
        return {}
    return {key: table.get(f"height_scan_{key}") for key in ("x_m", "y_m", "spacing_m")}


def _caller_mismatch(props: dict[str, str], caller: Any, path: Any) -> str | None:
    """Why the caller's environment `caller` reads its height scan at other points than the
    file was trained on (the same rows and names can lie elsewhere), if it does."""
    from hyq.env import HyQEnv

    ours = _scan_geometry(caller)
    if not ours:
        return None
    trained_env = HyQEnv(robot=caller.robot, **_observation_options(props, path))
    try:
        trained = _scan_geometry(trained_env)
    finally:
        trained_env.close()
    for key, value in ours.items():
        if trained.get(key) != value:
            return (f"trained with observation.height_scan_{key} = {trained.get(key)!r}, the "
                    f"environment has {value!r}: the same scan rows would read the ground at "
                    "other points")
    return None


def check_onnx_layout(model: Any, robot: str, path: Any = "ONNX policy",
                      env_config: Mapping[str, Any] | None = None) -> dict[str, str]:
    """Checks that an ONNX policy (an ``onnx.ModelProto`` or an onnxruntime session) is one of
    these files and fits `robot`'s environment: the robot's name, the observation rows and the
    joints, in order, and the graph's input and output widths. The environment is the caller's,
    `env_config` (``HyQEnv``'s argument of that name) when given, and then its height scan must
    read the ground at the points the file was trained on (the same rows and names can lie
    elsewhere); without it, the environment the file's own `env_config` names. Returns its
    metadata; raises ``ValueError`` naming the file and the first difference."""
    from hyq.env import HyQEnv

    if hasattr(model, "get_modelmeta"):
        props = dict(model.get_modelmeta().custom_metadata_map)
        widths = (model.get_inputs()[0].shape[-1], model.get_outputs()[0].shape[-1])
    else:
        props = {p.key: p.value for p in model.metadata_props}
        dims = lambda v: v.type.tensor_type.shape.dim[-1].dim_value  # noqa: E731
        widths = (dims(model.graph.input[0]), dims(model.graph.output[0]))
    if props.get("format") != ONNX_FORMAT:
        raise _refuse(path, f"metadata `format` is {props.get('format')!r}, expected {ONNX_FORMAT!r} "
                            "(written by hyq.policy_file.write_onnx)")
    for key in ("robot", "observation", "action"):
        if key not in props:
            raise _refuse(path, f"metadata has no `{key}` entry")
    if env_config is None:
        env = HyQEnv(robot=robot, **_observation_options(props, path))
    else:
        env = HyQEnv(robot=robot, env_config=env_config)
    try:
        if props["robot"] != env.robot:
            raise _refuse(path, f"trained for robot {props['robot']!r}, the environment runs {env.robot!r}")
        for what, trained, names in (("observation", props["observation"], env.observation_names),
                                     ("action", props["action"], env.joint_names)):
            reason = _mismatch(what, json.loads(trained), list(names))
            if reason is not None:
                raise _refuse(path, reason)
        if env_config is not None:
            reason = _caller_mismatch(props, env, path)
            if reason is not None:
                raise _refuse(path, reason)
        expected = (len(env.observation_names), len(env.joint_names))
    finally:
        env.close()
    if tuple(widths) != expected:
        raise _refuse(path, f"the graph maps {widths[0]} inputs to {widths[1]} outputs, the "
                            f"environment has {expected[0]} observation values and {expected[1]} actions")
    return props


class OnnxPolicy:
    """An ONNX policy run by onnxruntime, checked against `robot`'s layout when loaded
    (:func:`check_onnx_layout`, against the caller's `env_config` when given: pass the one the
    policy will run in, so that a height scan of another geometry is refused). Calling it maps
    float32 observations (n,) or (batch, n) to actions of the same batch shape."""

    def __init__(self, path: str | Path, robot: str = "hyq",
                 env_config: Mapping[str, Any] | None = None) -> None:
        import onnxruntime

        options = onnxruntime.SessionOptions()
        # One thread: the same arithmetic on every run, and no pool competing with the envs.
        options.intra_op_num_threads = 1
        options.inter_op_num_threads = 1
        self.path = str(path)
        self.session = onnxruntime.InferenceSession(str(path), options, providers=["CPUExecutionProvider"])
        self.metadata = check_onnx_layout(self.session, robot, path, env_config)

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        x = np.asarray(obs, dtype=np.float32)
        single = x.ndim == 1
        out = self.session.run(["actions"], {"obs": x[None, :] if single else x})[0]
        # Never hand on a non-finite action: a graph made from a non-finite tensor (or one whose
        # float32 sums overflow) says so here instead of driving a robot with NaN.
        bad = np.argwhere(~np.isfinite(out))
        if bad.size:
            where = tuple(int(i) for i in bad[0])
            raise ValueError(f"{self.path}: the ONNX policy output a non-finite action "
                             f"{float(out[where])} at {where}")
        return out[0] if single else out
