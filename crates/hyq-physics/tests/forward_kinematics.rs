//! Forward kinematics composes X_child = X_parent · X_origin · Rot(axis, q); fixed links are
//! lumped with the parallel-axis theorem and their shapes carried into the parent's frame;
//! shape clearances and the centre of mass follow from the poses. Checked on a small robot
//! whose answers are known in closed form.

use hyq_physics::na::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};
use hyq_physics::{PhysicsError, Profile, RobotModel, Shape};

const URDF: &str = r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial><origin xyz="0 0 0"/><mass value="2"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision name="base_box"><origin xyz="0 0 0"/><geometry><box size="0.2 0.4 0.6"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.5" rpy="0 0 0"/>
    <parent link="base"/><child link="upper"/>
    <axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="10" velocity="5"/>
  </joint>
  <link name="upper">
    <inertial><origin xyz="0.5 0 0"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
  </link>
  <joint name="tip_mount" type="fixed">
    <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/>
    <parent link="upper"/><child link="tip"/>
  </joint>
  <link name="tip">
    <inertial><origin xyz="0 0 0"/><mass value="1"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
    <collision name="ball"><origin xyz="0 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
</robot>
"#;

const PROFILE: &str = r#"
name = "arm"
urdf = "arm.urdf"
trunk = "base"
feet = [{ name = "tip", link = "tip", collision = "ball" }]
joints = [{ name = "shoulder", urdf = "shoulder", standing = 0.0 }]
[spawn]
height = 1.0
[gains]
kp = 10.0
kd = 1.0
"#;

fn arm() -> RobotModel {
    let profile = Profile::from_toml_str(PROFILE, "arm profile").expect("profile");
    RobotModel::from_urdf_str(URDF, "arm urdf", &profile).expect("arm loads")
}

#[test]
fn fixed_links_are_lumped_with_the_parallel_axis_theorem() {
    let model = arm();
    assert_eq!(model.num_links(), 2, "the fixed tip joins the upper link");
    let upper = &model.links()[1];
    assert_eq!(upper.lumped, ["tip"]);
    assert_eq!(upper.mass, 2.0);
    // Masses 1 kg at x = 0.5 and x = 1: centre at 0.75, each 0.25 m away.
    assert!((upper.com - Vector3::new(0.75, 0.0, 0.0)).norm() < 1e-12);
    let expected = Matrix3::from_diagonal(&Vector3::new(0.01, 0.02 + 0.125, 0.02 + 0.125));
    assert!(
        (upper.inertia - expected).abs().max() < 1e-12,
        "{}",
        upper.inertia
    );
    // The tip's sphere is carried into the upper link's frame.
    let ball = &upper.collisions[0];
    assert_eq!(ball.urdf_link, "tip");
    assert!((ball.origin.translation.vector - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-12);
    assert_eq!(model.tracked()[0].link, 1);
    assert_eq!(model.tracked()[1].name, "base");
}

#[test]
fn link_poses_compose_origin_and_joint_rotation() {
    let model = arm();
    let root = Isometry3::from_parts(
        Translation3::new(1.0, 2.0, 3.0),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.5),
    );
    let q = 0.3;
    let mut poses = [Isometry3::identity(); 2];
    model.link_poses(&root, &[q], &mut poses).expect("fk");
    assert_eq!(poses[0], root);
    let expected = root
        * Translation3::new(0.0, 0.0, 0.5)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), q);
    assert!(
        (poses[1].to_homogeneous() - expected.to_homogeneous())
            .abs()
            .max()
            < 1e-12
    );
    // A rotation about +y by q tips +x down by sin q: the ball is at z = 3.5 − sin q.
    let ball = poses[1] * model.links()[1].collisions[0].origin;
    assert!((ball.translation.z - (3.5 - q.sin())).abs() < 1e-12);
}

#[test]
fn clearances_and_centre_of_mass() {
    let model = arm();
    let root = Isometry3::translation(0.0, 0.0, 1.0);
    let mut poses = [Isometry3::identity(); 2];
    model.link_poses(&root, &[0.0], &mut poses).expect("fk");
    // Box half-height 0.3 around z = 1; ball of radius 0.1 at z = 1.5.
    assert!((model.tracked_lowest_z(1, &poses) - 0.7).abs() < 1e-12);
    assert!((model.tracked_lowest_z(0, &poses) - 1.4).abs() < 1e-12);
    assert!((model.lowest_z(&poses) - 0.7).abs() < 1e-12);
    // 2 kg at (0, 0, 1) and 2 kg at (0.75, 0, 1.5).
    let com = model.centre_of_mass(&poses);
    assert!((com - Vector3::new(0.375, 0.0, 1.25)).norm() < 1e-12);
}

#[test]
fn lowest_point_of_each_shape() {
    let tilted = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 1.0),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
    );
    // Turned a quarter about x, the local z axis lies horizontal and local y points down.
    let capsule = Shape::Capsule {
        radius: 0.1,
        half_length: 0.5,
    };
    assert!((capsule.lowest_z(&tilted) - 0.9).abs() < 1e-12);
    let cylinder = Shape::Cylinder {
        radius: 0.1,
        half_length: 0.5,
    };
    assert!((cylinder.lowest_z(&tilted) - 0.9).abs() < 1e-12);
    let upright = Isometry3::translation(0.0, 0.0, 1.0);
    assert!((capsule.lowest_z(&upright) - 0.4).abs() < 1e-12);
    assert!((cylinder.lowest_z(&upright) - 0.5).abs() < 1e-12);
    let cube = Shape::Box {
        half_extents: Vector3::new(0.1, 0.2, 0.3),
    };
    assert!((cube.lowest_z(&tilted) - 0.8).abs() < 1e-12);
    assert!((Shape::Sphere { radius: 0.25 }.lowest_z(&tilted) - 0.75).abs() < 1e-12);
}

#[test]
fn wrong_lengths_are_errors() {
    let model = arm();
    let mut poses = [Isometry3::identity(); 2];
    assert!(matches!(
        model.link_poses(&Isometry3::identity(), &[0.0, 0.0], &mut poses),
        Err(PhysicsError::WrongLength {
            what: "joint angles",
            expected: 1,
            got: 2
        })
    ));
    let mut short = [Isometry3::identity(); 1];
    assert!(matches!(
        model.link_poses(&Isometry3::identity(), &[0.0], &mut short),
        Err(PhysicsError::WrongLength {
            expected: 2,
            got: 1,
            ..
        })
    ));
}
