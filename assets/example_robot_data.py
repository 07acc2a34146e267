"""The derivation shared by assets/{a1,go1_urdf,anymal_b,laikago}/derive.py.

Each of those scripts names one robot directory of the PyPI wheel example-robot-data 6.0.0
(`example_robot_data-6.0.0-0-py3-none-any.whl`) and calls `main` here, which writes, next to
the calling script:

  * `<name>.urdf`: upstream's URDF with every link, joint, inertial figure, joint origin, axis,
    limit and dynamics element kept as written upstream (attribute text unchanged, upstream
    order), <visual>, <material>, <gazebo>, <transmission> and <self_filter> elements dropped
    (no mesh is redistributed; no collision upstream is a mesh, which `derive_urdf` checks),
    and every <collision> named: "<link>_<i>" (i counts the link's collisions from 0), except
    the foot spheres, named "<leg>_foot" so that a profile can track the sphere alone;
  * `UPSTREAM.md`: the package's README.md as shipped (upstream repository and licence);
  * `LICENSE-example-robot-data`: the wheel's own licence file (the packaging's);

and checks that the profile's standing pose is the SRDF's `standing` group state (or, for a
robot without an SRDF, the pose its script derives). Standard library only; the output is a
pure function of the wheel, so running it again gives the same bytes. `--check` writes nothing
and exits with status 1 naming any committed file that differs.
"""

import argparse
import hashlib
import re
import sys
import zipfile
import xml.etree.ElementTree as ET
from pathlib import Path

WHEEL_SHA256 = "424092a8093411ac2cd4ccc0572382bfc6b5eb4833aa984ef5e671dd67cd0a6e"
ROBOTS_DIR = "cmeel.prefix/share/example-robot-data/robots/"
WHEEL_LICENSE = "example_robot_data-6.0.0.dist-info/licenses/LICENSE"

KEEP_IN_LINK = ("inertial", "collision")
KEEP_IN_JOINT = ("parent", "child", "origin", "axis", "limit", "dynamics")
KEEP_IN_INERTIAL = ("origin", "mass", "inertia")
KEEP_IN_COLLISION = ("origin", "geometry")
DROPPED_TOP_LEVEL = ("material", "gazebo", "transmission")
PRIMITIVES = ("box", "sphere", "cylinder", "capsule")


class Robot:
    """One robot of the wheel: where its files are and what its derivation names."""

    def __init__(self, *, here, package, urdf, srdf, out, header, feet, standing=None):
        self.here = Path(here).resolve().parent
        self.package = package  # the robot's directory under ROBOTS_DIR
        self.urdf = urdf  # the URDF's path in that directory
        self.srdf = srdf  # the SRDF's path, or None
        self.out = out  # the derived URDF's file name
        self.header = header  # the provenance comment, with {sha}
        self.feet = feet  # foot link name -> foot collision name
        self.standing = standing  # joint -> angle, for a robot without an SRDF


def read_wheel(path, robot):
    """The robot's URDF, SRDF (or None), README and the wheel's licence, as text."""
    digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
    if digest != WHEEL_SHA256:
        sys.exit(f"{path}: sha256 {digest}, expected {WHEEL_SHA256} (example-robot-data 6.0.0)")
    base = ROBOTS_DIR + robot.package + "/"
    with zipfile.ZipFile(path) as wheel:
        def read(name):
            return wheel.read(name).decode("utf-8")
        srdf = read(base + robot.srdf) if robot.srdf else None
        return read(base + robot.urdf), srdf, read(base + "README.md"), read(WHEEL_LICENSE)


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


def collision_names(link, feet):
    """The name of each of `link`'s collisions (see the module documentation)."""
    name = link.get("name")
    names = []
    for i, collision in enumerate(link.findall("collision")):
        if collision.get("name") is not None:
            sys.exit(f"link {name}: upstream collision #{i} is already named; update derive.py")
        shape = collision.find("geometry")[0].tag
        if shape not in PRIMITIVES:
            sys.exit(f"link {name}: collision #{i} is a {shape}, not a primitive")
        if name in feet and shape == "sphere":
            names.append(feet[name])
        else:
            names.append(f"{name}_{i}")
    return names


def derive_urdf(text, robot):
    root = ET.fromstring(text)
    out = ['<?xml version="1.0" encoding="utf-8"?>',
           robot.header.format(sha=WHEEL_SHA256).rstrip()]
    out.append(f"<robot{attributes(root)}>")
    named_feet = 0
    for element in root:
        if element.tag == "link":
            names = collision_names(element, robot.feet)
            named_feet += sum(1 for n in names if n in robot.feet.values())
            names = iter(names)
            out.append(f"  <link{attributes(element)}>")
            for child in element:
                if child.tag == "collision":
                    write_element(child, KEEP_IN_COLLISION, 2, out, name=next(names))
                elif child.tag in KEEP_IN_LINK:
                    write_element(child, KEEP_IN_INERTIAL, 2, out)
            out.append("  </link>")
        elif element.tag == "joint":
            write_element(element, KEEP_IN_JOINT, 1, out)
        elif element.tag not in DROPPED_TOP_LEVEL:
            sys.exit(f"unexpected top-level element <{element.tag}>; update derive.py")
    if named_feet != len(robot.feet):
        sys.exit(f"named {named_feet} foot spheres, expected {len(robot.feet)}")
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


def check_profile_standing(robot, standing):
    """profile.toml's standing angle of every joint equals `standing`."""
    profile = (robot.here / "profile.toml").read_text(encoding="utf-8")
    entries = re.findall(r'urdf = "(\w+)", standing = (-?[0-9.]+)', profile)
    found = {urdf: float(value) for urdf, value in entries}
    if found != standing:
        sys.exit(f"profile.toml's standing pose {found} is not {standing}")


def main(robot, doc):
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("wheel", help="example_robot_data-6.0.0-0-py3-none-any.whl")
    parser.add_argument("--check", action="store_true",
                        help="compare with the committed files instead of writing them")
    args = parser.parse_args()
    urdf, srdf, readme, licence = read_wheel(args.wheel, robot)
    standing = srdf_standing(srdf) if srdf is not None else robot.standing
    check_profile_standing(robot, standing)
    outputs = {
        robot.out: derive_urdf(urdf, robot),
        "UPSTREAM.md": readme,
        "LICENSE-example-robot-data": licence,
    }
    differ = []
    for name, text in outputs.items():
        target = robot.here / name
        if args.check:
            if not target.exists() or target.read_bytes() != text.encode("utf-8"):
                differ.append(name)
        else:
            target.write_bytes(text.encode("utf-8"))
    if differ:
        sys.exit(f"differs from the package's derivation: {', '.join(differ)}")
    print("checked" if args.check else "wrote", ", ".join(outputs),
          "and the profile's standing pose")
