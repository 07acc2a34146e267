#!/usr/bin/env python3
"""Derive assets/go1/ from MuJoCo Playground 0.2.0 (Unitree Go1 MJCF, Apache-2.0).

Writes `go1.xml` and `LICENSE` next to this script from the PyPI wheel
playground-0.2.0-py3-none-any.whl, and checks that `profile.toml`'s standing pose is the
`home` keyframe. Standard library only; the output is a pure function of the input, so
running it again gives the same bytes.

    python3 -m pip download --no-deps -d pg playground==0.2.0
    python3 assets/go1/derive.py pg/playground-0.2.0-py3-none-any.whl
    python3 assets/go1/derive.py --check pg/playground-0.2.0-py3-none-any.whl

`--check` writes nothing and exits with status 1 if a committed file differs from what the
wheel gives.

What the derivation does (README.md in this directory says why):
  * keeps mujoco_playground/_src/locomotion/go1/xmls/go1_mjx_fullcollisions.xml as written
    (it includes no other file), behind a comment saying where it comes from;
  * appends the `home` keyframe of scene_mjx_fullcollisions_flat_terrain.xml (the scene that
    includes the robot), so the standing pose travels with the robot;
  * copies the wheel's LICENSE (Apache-2.0). No mesh is copied: the meshes live in MuJoCo
    Menagerie, and the project reads only the primitive collision geoms.
"""

import argparse
import hashlib
import re
import sys
import zipfile
import xml.etree.ElementTree as ET
from pathlib import Path

WHEEL_SHA256 = "c0f2df426186bd681d8f536cead80d43460ea6431db09ced32251910d4eef850"
XMLS = "mujoco_playground/_src/locomotion/go1/xmls/"
ROBOT = XMLS + "go1_mjx_fullcollisions.xml"
SCENE = XMLS + "scene_mjx_fullcollisions_flat_terrain.xml"
LICENCE = "playground-0.2.0.dist-info/licenses/LICENSE"
HERE = Path(__file__).resolve().parent

# Profile joint order (lf, lh, rf, rh; haa, hfe, kfe) as MJCF joint names.
PROFILE_ORDER = [
    f"{leg}_{part}_joint"
    for leg in ("FL", "RL", "FR", "RR")
    for part in ("hip", "thigh", "calf")
]

HEADER = """<!--
  Unitree Go1 (12 hinge joints) for simulation, derived by derive.py in this directory from
    {robot}
  in the PyPI wheel playground-0.2.0-py3-none-any.whl
    (sha256 {sha}).
  MuJoCo Playground: Copyright 2025 DeepMind Technologies Limited, Apache License 2.0 (LICENSE
  here). The model derives from MuJoCo Menagerie's unitree_go1 (BSD-3-Clause), itself derived
  from Unitree Robotics' go1_description URDF; see NOTICE and README.md here.

  The text below is upstream's as written; what differs: this comment, and the `home` keyframe
  appended from
    {scene}.
  The visual meshes it names are not shipped (the project reads the primitive collision geoms
  only).
-->
"""


def read_wheel(path):
    """The robot MJCF, the scene MJCF and the licence texts from the wheel."""
    path = Path(path)
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    if digest != WHEEL_SHA256:
        sys.exit(f"{path}: sha256 {digest}, expected {WHEEL_SHA256} (playground 0.2.0)")
    with zipfile.ZipFile(path) as wheel:
        return [wheel.read(n).decode("utf-8") for n in (ROBOT, SCENE, LICENCE)]


def home_key(scene):
    """The scene's `home` keyframe: qpos and ctrl, whitespace collapsed."""
    for key in ET.fromstring(scene).iter("key"):
        if key.get("name") == "home":
            return {a: " ".join(key.get(a).split()) for a in ("qpos", "ctrl")}
    sys.exit("the scene has no keyframe 'home'")


def derive_mjcf(robot, key):
    if "<include" in robot or "<keyframe" in robot:
        sys.exit("the robot file now includes files or has keyframes; update derive.py")
    body, end = robot.rstrip().rsplit("</mujoco>", 1)
    if end.strip():
        sys.exit("text after </mujoco>; update derive.py")
    keyframe = (
        "  <keyframe>\n"
        f'    <key name="home" qpos="{key["qpos"]}" ctrl="{key["ctrl"]}"/>\n'
        "  </keyframe>\n"
    )
    header = HEADER.format(robot=ROBOT, scene=SCENE, sha=WHEEL_SHA256)
    return header + body.rstrip() + "\n\n" + keyframe + "</mujoco>\n"


def robot_joints(robot):
    """The hinge joints in file order (the order of qpos after the free joint)."""
    return [j.get("name") for j in ET.fromstring(robot).find("worldbody").iter("joint")]


def check_profile_standing(robot, key):
    """profile.toml's standing angle of every joint equals the home keyframe's."""
    values = [float(v) for v in key["qpos"].split()][7:]
    home = dict(zip(robot_joints(robot), values))
    profile = (HERE / "profile.toml").read_text(encoding="utf-8")
    entries = re.findall(r'urdf = "(\w+)", standing = (-?[0-9.]+)', profile)
    found = {urdf: float(value) for urdf, value in entries}
    if [urdf for urdf, _ in entries] != PROFILE_ORDER or found != home:
        sys.exit(f"profile.toml's standing pose {found} is not the home keyframe's {home}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("wheel", help="the playground 0.2.0 wheel")
    parser.add_argument("--check", action="store_true",
                        help="compare with the committed files instead of writing them")
    args = parser.parse_args()
    robot, scene, licence = read_wheel(args.wheel)
    key = home_key(scene)
    check_profile_standing(robot, key)
    outputs = {"go1.xml": derive_mjcf(robot, key), "LICENSE": licence}
    differ = []
    for name, text in outputs.items():
        target = HERE / name
        if args.check:
            if not target.exists() or target.read_bytes() != text.encode("utf-8"):
                differ.append(name)
        else:
            target.write_bytes(text.encode("utf-8"))
    if differ:
        sys.exit(f"differs from the wheel's derivation: {', '.join(differ)}")
    print("checked" if args.check else "wrote", ", ".join(outputs),
          "and the profile's standing pose")


if __name__ == "__main__":
    main()
