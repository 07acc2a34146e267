#!/usr/bin/env python3
"""Derive assets/anymal_c/ from example-robot-data 6.0.0 (ANYmal C, BSD-3-Clause).

Writes `anymal_c.urdf` and `LICENSE` next to this script from the package's
`robots/anymal_c_simple_description/`, and checks that `profile.toml`'s standing pose is the
package's SRDF `standing` group state. Standard library only; the output is a pure function of
the input, so running it again gives the same bytes.

    python3 -m pip download --no-deps -d erd example-robot-data==6.0.0
    python3 assets/anymal_c/derive.py erd/example_robot_data-6.0.0-0-py3-none-any.whl
    python3 assets/anymal_c/derive.py --check erd/example_robot_data-6.0.0-0-py3-none-any.whl

`--check` writes nothing and exits with status 1 if a committed file differs from what the
package gives (the wheel is 131 MB, so this is a command to run by hand, not a CI stage).

What the derivation does (README.md in this directory says why):
  * keeps every link, joint, inertial figure, joint origin, axis, limit and dynamics element
    of upstream `urdf/anymal.urdf`, attribute values as written upstream, in upstream order;
  * drops <visual>, <material> and <self_filter> elements (meshes are not redistributed);
  * names every <collision>: "<link>_<i>" (i counts the link's collisions from 0), except each
    foot's sphere on link "<LEG>_FOOT", named "<leg>_foot" (lower case), so that the profile
    can track the foot sphere alone and not the lower-shank tube on the same link.
"""

import argparse
import hashlib
import re
import sys
import zipfile
import xml.etree.ElementTree as ET
from pathlib import Path

WHEEL_SHA256 = "424092a8093411ac2cd4ccc0572382bfc6b5eb4833aa984ef5e671dd67cd0a6e"
PACKAGE_DIR = "cmeel.prefix/share/example-robot-data/robots/anymal_c_simple_description/"
HERE = Path(__file__).resolve().parent

HEADER = """<!--
  ANYbotics' ANYmal C (52.1 kg, 12 revolute joints) for simulation, derived by derive.py in this
  directory from urdf/anymal.urdf of anymal_c_simple_description in the PyPI wheel
  example_robot_data-6.0.0-0-py3-none-any.whl (sha256 {sha}).
  Copyright 2020, ANYbotics AG; BSD 3-Clause License, see LICENSE and README.md here.

  Every link, joint, inertial figure, joint origin, axis, limit and dynamics element is
  upstream's, as written upstream. What differs:
    * <visual>, <material> and <self_filter> elements are dropped (the meshes are not here);
    * every <collision> is named: "<link>_<i>", and each foot sphere "<leg>_foot".
  Upstream's fixed sensor links keep their inertial figures; five of them (the four depth
  cameras and the hatch) have tensors that violate the triangle inequality on their own. The
  model loader checks each rigid body after lumping fixed links into it, where they are valid.
-->
"""

KEEP_IN_LINK = ("inertial", "collision")
KEEP_IN_JOINT = ("parent", "child", "origin", "axis", "limit", "dynamics")
KEEP_IN_INERTIAL = ("origin", "mass", "inertia")
KEEP_IN_COLLISION = ("origin", "geometry")


def read_package(path):
    """The package's URDF, SRDF and LICENSE texts, from the wheel or an unpacked copy."""
    path = Path(path)
    names = ("urdf/anymal.urdf", "srdf/anymal.srdf", "LICENSE")
    if path.is_dir():
        return [(path / n).read_text(encoding="utf-8") for n in names]
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    if digest != WHEEL_SHA256:
        sys.exit(f"{path}: sha256 {digest}, expected {WHEEL_SHA256} (example-robot-data 6.0.0)")
    with zipfile.ZipFile(path) as wheel:
        return [wheel.read(PACKAGE_DIR + n).decode("utf-8") for n in names]


def attributes(element):
    return "".join(f' {k}="{v}"' for k, v in element.attrib.items())


def write_element(element, keep, indent, out, name=None):
    """`element` and the children whose tags are in `keep` (all of them when `keep` is None)."""
    pad = "  " * indent
    attrs = attributes(element)
    if name is not None:
        attrs = f' name="{name}"' + attrs
    children = [c for c in element if keep is None or c.tag in keep]
    if not children:
        out.append(f"{pad}<{element.tag}{attrs}/>")
        return
    out.append(f"{pad}<{element.tag}{attrs}>")
    for child in children:
        inner = {"inertial": KEEP_IN_INERTIAL, "collision": KEEP_IN_COLLISION}.get(child.tag)
        write_element(child, inner, indent + 1, out)
    out.append(f"{pad}</{element.tag}>")


def collision_names(link):
    """The name of each of `link`'s collisions (see the module documentation)."""
    name = link.get("name")
    names = []
    for i, collision in enumerate(link.findall("collision")):
        if collision.get("name") is not None:
            sys.exit(f"link {name}: upstream collision #{i} is already named; update derive.py")
        is_sphere = collision.find("geometry/sphere") is not None
        if name.endswith("_FOOT") and is_sphere:
            names.append(name[: -len("_FOOT")].lower() + "_foot")
        else:
            names.append(f"{name}_{i}")
    return names


def derive_urdf(text):
    robot = ET.fromstring(text)
    out = ['<?xml version="1.0" encoding="utf-8"?>', HEADER.format(sha=WHEEL_SHA256).rstrip()]
    out.append(f"<robot{attributes(robot)}>")
    for element in robot:
        if element.tag == "link":
            names = iter(collision_names(element))
            out.append(f"  <link{attributes(element)}>")
            for child in element:
                if child.tag not in KEEP_IN_LINK:
                    continue
                if child.tag == "collision":
                    write_element(child, KEEP_IN_COLLISION, 2, out, name=next(names))
                else:
                    write_element(child, KEEP_IN_INERTIAL, 2, out)
            out.append("  </link>")
        elif element.tag == "joint":
            write_element(element, KEEP_IN_JOINT, 1, out)
        else:
            sys.exit(f"unexpected top-level element <{element.tag}>; update derive.py")
    out.append("</robot>")
    return "\n".join(out) + "\n"


def srdf_standing(text):
    """The SRDF `standing` group state's joint values, by URDF joint name."""
    srdf = ET.fromstring(text)
    for state in srdf.iter("group_state"):
        if state.get("name") == "standing":
            return {
                j.get("name"): float(j.get("value"))
                for j in state.findall("joint")
                if j.get("name") != "root_joint"
            }
    sys.exit("the SRDF has no group state 'standing'")


def check_profile_standing(standing):
    """profile.toml's standing angle of every joint equals the SRDF's."""
    profile = (HERE / "profile.toml").read_text(encoding="utf-8")
    entries = re.findall(r'urdf = "(\w+)", standing = (-?[0-9.]+)', profile)
    found = {urdf: float(value) for urdf, value in entries}
    if found != standing:
        sys.exit(f"profile.toml's standing pose {found} is not the SRDF's {standing}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("package", help="the example-robot-data 6.0.0 wheel, or the unpacked "
                        "robots/anymal_c_simple_description directory")
    parser.add_argument("--check", action="store_true",
                        help="compare with the committed files instead of writing them")
    args = parser.parse_args()
    urdf, srdf, licence = read_package(args.package)
    check_profile_standing(srdf_standing(srdf))
    outputs = {"anymal_c.urdf": derive_urdf(urdf), "LICENSE": licence}
    differ = []
    for name, text in outputs.items():
        target = HERE / name
        if args.check:
            if not target.exists() or target.read_bytes() != text.encode("utf-8"):
                differ.append(name)
        else:
            target.write_bytes(text.encode("utf-8"))
    if differ:
        sys.exit(f"differs from the package's derivation: {', '.join(differ)}")
    print("checked" if args.check else "wrote", ", ".join(outputs),
          "and the profile's standing pose")


if __name__ == "__main__":
    main()
