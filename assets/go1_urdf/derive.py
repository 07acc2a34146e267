#!/usr/bin/env python3
"""Derive assets/go1_urdf/ from example-robot-data 6.0.0 (Unitree Go1 (URDF)).

Writes `go1.urdf`, `UPSTREAM.md` and `LICENSE-example-robot-data` next to this script from the
wheel's `robots/go1_description/`, and checks that `profile.toml`'s standing pose is the
package's SRDF `standing` group state. The derivation is `assets/example_robot_data.py`'s (its
documentation says what is kept and dropped); this file names the robot's files and feet.

    python3 -m pip download --no-deps -d erd example-robot-data==6.0.0
    python3 assets/go1_urdf/derive.py erd/example_robot_data-6.0.0-0-py3-none-any.whl
    python3 assets/go1_urdf/derive.py --check erd/example_robot_data-6.0.0-0-py3-none-any.whl
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import example_robot_data as erd  # noqa: E402

HEADER = """<!--
  Unitree's Go1 (12 revolute joints) for simulation, derived by derive.py in this directory from
  urdf/go1.urdf of go1_description in the PyPI wheel
  example_robot_data-6.0.0-0-py3-none-any.whl (sha256 {sha}); upstream
  https://github.com/unitreerobotics/unitree_ros (robots/go1_description).
  This Source Code Form is subject to the terms of the Mozilla Public License, v. 2.0 (upstream's
  licence, as example-robot-data's package README states; the text is in LICENSE here). If a
  copy of the MPL was not distributed with this file, you can obtain one at
  https://mozilla.org/MPL/2.0/.

  Every link, joint, inertial figure, joint origin, axis, limit and dynamics element is
  upstream's, as written upstream. What differs: <visual>, <material>, <gazebo> and
  <transmission> elements are dropped (the meshes are not here); every <collision> is named:
  "<link>_<i>", and each foot sphere "<leg>_foot".
-->
"""

ROBOT = erd.Robot(
    here=__file__,
    package="go1_description",
    urdf="urdf/go1.urdf",
    srdf='srdf/go1.srdf',
    out="go1.urdf",
    header=HEADER,
    feet={"FL_foot": "lf_foot", "FR_foot": "rf_foot", "RL_foot": "lh_foot", "RR_foot": "rh_foot"},
)

if __name__ == "__main__":
    erd.main(ROBOT, __doc__)
