"""A policy file holding a NaN or an infinity is refused by every Python reader and writer the
way ``hyq run --policy mlp:FILE`` refuses it (``tensor `layers.0.weight` holds a non-finite value
(NaN) at flat index 0``): ``read_policy``, ``write_onnx`` (no ONNX twin is written, so no model
that outputs NaN can be deployed), ``examples/export_policy.py --onnx``; and ``OnnxPolicy`` never
hands on a non-finite action."""

from __future__ import annotations

import json
import re
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import onnx
import pytest
from onnx import numpy_helper

from conftest import REPO
from hyq.policy_file import OnnxPolicy, check_finite, non_finite, read_policy, write_onnx

WALK = REPO / "assets" / "policies" / "hyq_walk.safetensors"


def with_value(tmp_path: Path, tensor: str, index: int, value: float) -> Path:
    """hyq_walk.safetensors with `tensor`'s float32 value at flat `index` set to `value`."""
    data = bytearray(WALK.read_bytes())
    (n,) = struct.unpack("<Q", data[:8])
    begin, _ = json.loads(data[8 : 8 + n])[tensor]["data_offsets"]
    at = 8 + n + begin + 4 * index
    data[at : at + 4] = struct.pack("<f", value)
    path = tmp_path / f"{tensor}_{value}.safetensors"
    path.write_bytes(bytes(data))
    return path


@pytest.mark.parametrize(("tensor", "index", "value", "words"), [
    ("layers.0.weight", 0, float("nan"), "tensor `layers.0.weight` holds a non-finite value (NaN) at flat index 0"),
    ("layers.2.bias", 3, float("inf"), "tensor `layers.2.bias` holds a non-finite value (inf) at flat index 3"),
])
def test_the_reader_and_the_onnx_writer_refuse_a_non_finite_tensor(
        hyq_cli: Path, tmp_path: Path, tensor: str, index: int, value: float, words: str) -> None:
    path = with_value(tmp_path, tensor, index, value)
    rust = subprocess.run([str(hyq_cli), "run", "--policy", f"mlp:{path}"], capture_output=True, text=True)
    assert rust.returncode == 2 and words in rust.stderr, rust.stderr
    with pytest.raises(ValueError, match="non-finite") as err:
        read_policy(path)
    assert str(err.value) == f"{path}: {words}"
    out = tmp_path / "twin.onnx"
    with pytest.raises(ValueError, match="non-finite"):
        write_onnx(path, out)
    assert not out.exists()
    example = subprocess.run([sys.executable, str(REPO / "examples" / "export_policy.py"), "--policy", str(path),
                              "--onnx"], capture_output=True, text=True)
    assert example.returncode == 2, example.stderr
    assert words in example.stderr and not path.with_suffix(".onnx").exists()


def test_every_tensor_with_a_non_finite_value_anywhere_is_refused_on_read_and_on_write(tmp_path: Path) -> None:
    """A seeded sweep, as the policy fuzz target pokes values into tensors: in each of the
    file's tensors, a NaN, +inf or -inf at a drawn place is named by the reader, and neither
    writer (``check_finite`` before a safetensors file, ``write_onnx``) writes anything."""
    rng = np.random.default_rng(38)
    data = WALK.read_bytes()
    (n,) = struct.unpack("<Q", data[:8])
    header = json.loads(data[8 : 8 + n])
    tensors = {name: spec for name, spec in header.items() if name != "__metadata__"}
    assert len(tensors) >= 8, sorted(tensors)
    kinds = {"F32": ("<f", 4, np.float32), "F64": ("<d", 8, np.float64)}
    for name, spec in sorted(tensors.items()):
        fmt, size, dtype = kinds[spec["dtype"]]
        index = int(rng.integers(int(np.prod(spec["shape"]))))
        value = float(rng.choice([np.nan, np.inf, -np.inf]))
        poked = bytearray(data)
        at = 8 + n + spec["data_offsets"][0] + size * index
        poked[at : at + size] = struct.pack(fmt, value)
        path = tmp_path / f"{name}.safetensors"
        path.write_bytes(bytes(poked))
        text = "NaN" if np.isnan(value) else ("inf" if value > 0 else "-inf")
        words = f"tensor `{name}` holds a non-finite value ({text}) at flat index {index}"
        with pytest.raises(ValueError) as err:
            read_policy(path)
        assert str(err.value) == f"{path}: {words}"
        arrays = {k: np.zeros(t["shape"], kinds[t["dtype"]][2]) for k, t in tensors.items()}
        arrays[name].reshape(-1)[index] = value
        with pytest.raises(ValueError, match=re.escape(words)):
            check_finite(arrays, "run")
        out = tmp_path / f"{name}.onnx"
        with pytest.raises(ValueError, match=re.escape(words)):
            write_onnx(path, out)
        assert not out.exists()


def test_non_finite_names_the_first_bad_value_in_the_readers_words() -> None:
    assert non_finite("w", np.zeros((2, 3), np.float32)) is None
    values = np.array([[1.0, 2.0], [-np.inf, np.nan]])
    assert non_finite("w", values) == "tensor `w` holds a non-finite value (-inf) at flat index 2"


def test_an_onnx_policy_never_hands_on_a_non_finite_action(tmp_path: Path) -> None:
    # A twin edited after it was written (not by write_onnx, which refuses): the last layer's
    # bias NaN, so the graph's every output is NaN.
    model = onnx.load(str(WALK.with_suffix(".onnx")))
    last = max(i.name for i in model.graph.initializer if i.name.endswith(".bias"))
    for init in model.graph.initializer:
        if init.name == last:
            bias = numpy_helper.to_array(init).copy()
            bias[0] = np.nan
            init.CopyFrom(numpy_helper.from_array(bias, init.name))
    path = tmp_path / "nan.onnx"
    onnx.save_model(model, str(path))
    policy = OnnxPolicy(path, robot="hyq")
    with pytest.raises(ValueError, match="non-finite action"):
        policy(np.zeros(39, np.float32))
