#!/usr/bin/env python3
"""Derive assets/anymal_b/ from example-robot-data 6.0.0 (ANYbotics ANYmal B).

Writes `anymal_b.urdf`, `UPSTREAM.md` and `LICENSE-example-robot-data` next to this script from
the wheel's `robots/anymal_b_simple_description/`, and checks that `profile.toml`'s standing
pose is the package's SRDF `standing` group state. The derivation is
`assets/example_robot_data.py`'s (its documentation says what is kept and dropped); this file
names the robot's files and feet.

    python3 -m pip download --no-deps -d erd example-robot-data==6.0.0
    python3 assets/anymal_b/derive.py erd/example_robot_data-6.0.0-0-py3-none-any.whl
    python3 assets/anymal_b/derive.py --check erd/example_robot_data-6.0.0-0-py3-none-any.whl
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import example_robot_data as erd  # noqa: E402

HEADER = """<!--
  ANYbotics' ANYmal B (12 revolute joints) for simulation, derived by derive.py in this directory from
  robots/anymal.urdf of anymal_b_simple_description in the PyPI wheel
  example_robot_data-6.0.0-0-py3-none-any.whl (sha256 {sha}); upstream
  https://github.com/ANYbotics/anymal_b_simple_description.
  Copyright 2019 ANYbotics; BSD 3-Clause License (upstream's licence, as example-robot-data's
  package README states), see LICENSE and README.md here.

  Every link, joint, inertial figure, joint origin, axis, limit and dynamics element is
  upstream's, as written upstream. What differs: <visual>, <material>, <gazebo> and
  <transmission> elements are dropped (the meshes are not here); every <collision> is named:
  "<link>_<i>", and each foot sphere "<leg>_foot".
-->
"""

ROBOT = erd.Robot(
    here=__file__,
    package="anymal_b_simple_description",
    urdf="robots/anymal.urdf",
    srdf='srdf/anymal.srdf',
    out="anymal_b.urdf",
    header=HEADER,
    feet={"LF_FOOT": "lf_foot", "RF_FOOT": "rf_foot", "LH_FOOT": "lh_foot", "RH_FOOT": "rh_foot"},
)

if __name__ == "__main__":
    erd.main(ROBOT, __doc__)
