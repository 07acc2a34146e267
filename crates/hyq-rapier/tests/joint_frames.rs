//! Any URDF joint axis and origin (not only HyQ's z axes) maps onto rapier's revolute DoF with
//! the URDF's angle and sign: the engine's body poses equal the model's forward kinematics for
//! arbitrary angles, including a body whose frame is not at its centre of mass and a fixed link.

use hyq_physics::na::{Isometry3, Translation3, UnitQuaternion};
use hyq_physics::{Backend, PhysicsParams, Profile, RobotModel, RobotState, TrunkState};
use hyq_rapier::RapierBackend;

const URDF: &str = r#"<?xml version="1.0"?>
<robot name="odd">
  <link name="body">
    <inertial><origin xyz="0.1 -0.05 0.02"/><mass value="5"/>
      <inertia ixx="0.2" ixy="0.01" ixz="0" iyy="0.3" iyz="0" izz="0.25"/></inertial>
    <collision name="hull"><geometry><box size="0.4 0.3 0.2"/></geometry></collision>
  </link>
  <joint name="a" type="revolute">
    <origin xyz="0.2 0.1 -0.1" rpy="0.3 -0.2 0.7"/>
    <parent link="body"/><child link="l1"/>
    <axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="5"/>
  </joint>
  <link name="l1">
    <inertial><origin xyz="0.1 0 0" rpy="0.1 0.2 0.3"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
    <collision name="rod"><origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/>
      <geometry><cylinder radius="0.02" length="0.2"/></geometry></collision>
  </link>
  <joint name="b" type="revolute">
    <origin xyz="0.2 0 0" rpy="0 0 0"/>
    <parent link="l1"/><child link="l2"/>
    <axis xyz="0.6 0 -0.8"/>
    <limit lower="-3" upper="3" effort="10" velocity="5"/>
  </joint>
  <link name="l2">
    <inertial><origin xyz="0 0.1 0"/><mass value="0.5"/>
      <inertia ixx="0.005" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.005"/></inertial>
  </link>
  <joint name="c" type="revolute">
    <origin xyz="0 0.2 0" rpy="1 0 0"/>
    <parent link="l2"/><child link="l3"/>
    <axis xyz="-1 0 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="5"/>
  </joint>
  <link name="l3">
    <inertial><origin xyz="0 0 0.05"/><mass value="0.3"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="mount" type="fixed">
    <origin xyz="0 0 0.1" rpy="0 0.4 0"/>
    <parent link="l3"/><child link="pad"/>
  </joint>
  <link name="pad">
    <inertial><mass value="0.1"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision name="pad"><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
</robot>
"#;

const PROFILE: &str = r#"
name = "odd"
urdf = "odd.urdf"
trunk = "body"
feet = [{ name = "pad", link = "pad" }]
joints = [
    { name = "c", urdf = "c", standing = 0.0 },
    { name = "a", urdf = "a", standing = 0.0 },
    { name = "b", urdf = "b", standing = 0.0 },
]
[spawn]
height = 1.0
[gains]
kp = 10.0
kd = 1.0
"#;

#[test]
fn engine_poses_equal_forward_kinematics_for_any_axis() {
    let profile = Profile::from_toml_str(PROFILE, "odd profile").expect("profile");
    let model = std::sync::Arc::new(
        RobotModel::from_urdf_str(URDF, "odd urdf", &profile).expect("odd robot loads"),
    );
    let params = PhysicsParams {
        gravity: [0.0; 3],
        ..PhysicsParams::default()
    };
    let mut b = RapierBackend::build(model.clone(), &params, &Default::default()).expect("builds");
    for (i, q) in [[0.0, 0.0, 0.0], [0.5, -1.0, 2.0], [-2.5, 2.9, -0.3]]
        .iter()
        .enumerate()
    {
        let trunk = Isometry3::from_parts(
            Translation3::new(0.3, -0.2, 2.0 + i as f64),
            UnitQuaternion::from_euler_angles(0.4 * i as f64, -0.3, 1.1),
        );
        let state = RobotState {
            trunk: TrunkState::at_rest(trunk),
            q: q.to_vec(),
            qd: vec![0.0; 3],
        };
        b.set_state(&state).expect("valid state");
        let mut fk = vec![Isometry3::identity(); model.num_links()];
        model.link_poses(&trunk, q, &mut fk).expect("fk");
        let mut engine = vec![Isometry3::identity(); model.num_links()];
        b.link_poses(&mut engine);
        for (l, (a, e)) in fk.iter().zip(&engine).enumerate() {
            let dp = (a.translation.vector - e.translation.vector).norm();
            let dr = a.rotation.angle_to(&e.rotation);
            assert!(
                dp < 1e-5 && dr < 1e-5,
                "q {q:?}: body {l} off by {dp} m, {dr} rad"
            );
        }
        let back = b.state();
        for (j, (&set, &read)) in q.iter().zip(&back.q).enumerate() {
            assert!(
                (set - read).abs() < 1e-5,
                "joint {j}: set {set}, read {read}"
            );
        }
        assert!((back.trunk.pose.translation.vector - trunk.translation.vector).norm() < 1e-5);
    }
    // A joint torque turns its own joint the way the URDF axis says: positive torque,
    // positive acceleration.
    let mut state = model.spawn_state();
    state.trunk.pose.translation.z = 3.0;
    for j in 0..3 {
        b.set_state(&state).expect("valid state");
        let mut tau = vec![0.0; 3];
        tau[j] = 1.0;
        b.set_joint_torques(&tau).expect("torques");
        b.step().expect("steps");
        let mut qd = vec![0.0; 3];
        b.joint_velocities(&mut qd);
        assert!(
            qd[j] > 0.0,
            "a positive torque on joint {j} gave speed {}",
            qd[j]
        );
    }
    assert!((b.total_mass() - model.total_mass()).abs() < 1e-5);
}
