"""Stable-Baselines3's own environment checker and ``VecEnv`` base class, without PyTorch.

SB3 cannot be imported whole without PyTorch: its package ``__init__`` imports every algorithm,
and PyTorch from PyPI is a 5.4 GB install (it pulls the CUDA toolkit even on a CPU-only
machine; measured: 1 min 12 s and 5.4 GB for ``stable-baselines3==2.9.2``), too heavy for every
test run. The checker itself needs no PyTorch: it inspects the spaces and steps the env with
NumPy through SB3's ``DummyVecEnv`` and ``VecCheckNan``. So the tests install SB3's pinned wheel
without its dependencies (``requirements-test-nodeps.txt``, 2 MB) and load here the real modules
``check_env`` uses, from that wheel, without running the packages' ``__init__`` files. Of
PyTorch, ``common.preprocessing`` only evaluates two names at import time (type annotations);
a stand-in module provides exactly those and nothing else, so a checker path that really needed
PyTorch would raise instead of passing. Where PyTorch is installed, the real package is used.
"""

from __future__ import annotations

import importlib.util
import sys
import types
from pathlib import Path

import pytest

#: SB3's modules ``check_env`` and ``VecEnv`` need, in load order.
MODULES = [
    "common.preprocessing",
    "common.vec_env.base_vec_env",
    "common.vec_env.patch_gym",
    "common.vec_env.util",
    "common.vec_env.dummy_vec_env",
    "common.vec_env.vec_check_nan",
    "common.env_checker",
]


def torch_stand_in() -> dict[str, types.ModuleType]:
    """``torch``, ``torch.nn`` and ``torch.nn.functional`` with only the class ``Tensor``
    (for annotations); any other name raises AttributeError."""
    torch = types.ModuleType("torch")
    nn = types.ModuleType("torch.nn")
    functional = types.ModuleType("torch.nn.functional")
    torch.Tensor = type("Tensor", (), {"__doc__": "stand-in: PyTorch is not installed"})
    torch.nn = nn
    nn.functional = functional
    return {"torch": torch, "torch.nn": nn, "torch.nn.functional": functional}


def load(monkeypatch: pytest.MonkeyPatch) -> types.SimpleNamespace:
    """SB3's ``check_env``, ``VecEnv`` and ``DummyVecEnv``; every module put in
    ``sys.modules`` is taken out again when the test ends."""
    if importlib.util.find_spec("torch") is not None:
        from stable_baselines3.common.env_checker import check_env
        from stable_baselines3.common.vec_env import DummyVecEnv, VecEnv

        return types.SimpleNamespace(check_env=check_env, VecEnv=VecEnv, DummyVecEnv=DummyVecEnv)
    spec = importlib.util.find_spec("stable_baselines3")
    assert spec is not None and spec.submodule_search_locations, (
        "stable-baselines3 is not installed: pip install --no-deps -r requirements-test-nodeps.txt"
    )
    root = Path(next(iter(spec.submodule_search_locations)))
    for name, module in torch_stand_in().items():
        monkeypatch.setitem(sys.modules, name, module)
    packages = {}
    for name in ["", "common", "common.vec_env"]:
        full = "stable_baselines3" + (f".{name}" if name else "")
        package = types.ModuleType(full)
        package.__path__ = [str(root.joinpath(*name.split(".")) if name else root)]
        monkeypatch.setitem(sys.modules, full, package)
        packages[name] = package
    loaded = {}
    for name in MODULES:
        full = f"stable_baselines3.{name}"
        path = root.joinpath(*name.split(".")).with_suffix(".py")
        module_spec = importlib.util.spec_from_file_location(full, path)
        assert module_spec is not None and module_spec.loader is not None
        module = importlib.util.module_from_spec(module_spec)
        monkeypatch.setitem(sys.modules, full, module)
        module_spec.loader.exec_module(module)
        loaded[name] = module
        if name == "common.vec_env.vec_check_nan":
            # What the vec_env package exports to env_checker.
            vec_env = packages["common.vec_env"]
            vec_env.VecEnv = loaded["common.vec_env.base_vec_env"].VecEnv
            vec_env.DummyVecEnv = loaded["common.vec_env.dummy_vec_env"].DummyVecEnv
            vec_env.VecCheckNan = module.VecCheckNan
    vec_env = packages["common.vec_env"]
    return types.SimpleNamespace(
        check_env=loaded["common.env_checker"].check_env,
        VecEnv=vec_env.VecEnv,
        DummyVecEnv=vec_env.DummyVecEnv,
    )


@pytest.fixture()
def sb3(monkeypatch: pytest.MonkeyPatch) -> types.SimpleNamespace:
    """SB3's checker and base classes for one test (see the module docs)."""
    return load(monkeypatch)
