#!/usr/bin/env python3
"""Derive assets/laikago/ from example-robot-data 6.0.0 (Unitree Laikago).

Writes `laikago.urdf`, `UPSTREAM.md` and `LICENSE-example-robot-data` next to this script from
the wheel's `robots/laikago_description/`, and checks that `profile.toml`'s standing pose is
STANDING below (the package has no SRDF: README.md here says how the pose was derived). The
derivation is `assets/example_robot_data.py`'s (its documentation says what is kept and
dropped); this file names the robot's files and feet.

    python3 -m pip download --no-deps -d erd example-robot-data==6.0.0
    python3 assets/laikago/derive.py erd/example_robot_data-6.0.0-0-py3-none-any.whl
    python3 assets/laikago/derive.py --check erd/example_robot_data-6.0.0-0-py3-none-any.whl
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import example_robot_data as erd  # noqa: E402

HEADER = """<!--
  Unitree's Laikago (12 revolute joints) for simulation, derived by derive.py in this directory from
  urdf/laikago.urdf of laikago_description in the PyPI wheel
  example_robot_data-6.0.0-0-py3-none-any.whl (sha256 {sha}); upstream
  https://github.com/unitreerobotics/laikago_ros.
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

# The package has no SRDF. Laikago's legs are A1's design at 1.25 times the size (thigh and calf
# 0.25 m against 0.2 m, the same joint axes and zero pose: leg straight down), so A1's SRDF
# standing angles (hip 0, thigh 0.8, calf -1.81 rad) give the same leg shape: the foot 0.61 of
# the leg's length below the thigh joint, 3 cm ahead of it. README.md here gives the figures.
STANDING = {
    f"{leg}_{joint}": angle
    for leg in ("FL", "FR", "RL", "RR")
    for joint, angle in (("hip_joint", 0.0), ("thigh_joint", 0.8), ("calf_joint", -1.81))
}

ROBOT = erd.Robot(
    here=__file__,
    package="laikago_description",
    urdf="urdf/laikago.urdf",
    srdf=None,
    out="laikago.urdf",
    header=HEADER,
    feet={"FL_foot": "lf_foot", "FR_foot": "rf_foot", "RL_foot": "lh_foot", "RR_foot": "rh_foot"},
    standing=STANDING,
)

if __name__ == "__main__":
    erd.main(ROBOT, __doc__)
