//! An independent reading of the URDF: figures parsed here and composed by hand with 4×4
//! matrices, sharing no code with `RobotModel`'s loader or forward kinematics, so that the
//! forward-kinematics test compares two computations that cannot share a mistake.

use std::collections::HashMap;

use nalgebra::Isometry3;

use super::fixtures::Robot;
use hyq_physics::RobotState;
use hyq_physics::model::RobotModel;

type Mat4 = [[f64; 4]; 4];

fn mat_mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut c = [[0.0; 4]; 4];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// `T = [Rz(yaw) Ry(pitch) Rx(roll) | xyz]`, written out from the URDF specification.
fn urdf_transform(xyz: [f64; 3], rpy: [f64; 3]) -> Mat4 {
    let (sr, cr) = rpy[0].sin_cos();
    let (sp, cp) = rpy[1].sin_cos();
    let (sy, cy) = rpy[2].sin_cos();
    [
        [
            cy * cp,
            cy * sp * sr - sy * cr,
            cy * sp * cr + sy * sr,
            xyz[0],
        ],
        [
            sy * cp,
            sy * sp * sr + cy * cr,
            sy * sp * cr - cy * sr,
            xyz[1],
        ],
        [-sp, cp * sr, cp * cr, xyz[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Rotation by `angle` about a unit `axis` (Rodrigues' formula).
fn axis_angle(axis: [f64; 3], angle: f64) -> Mat4 {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let [x, y, z] = [axis[0] / n, axis[1] / n, axis[2] / n];
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn isometry_to_mat(p: &Isometry3<f64>) -> Mat4 {
    let m = p.to_homogeneous();
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = m[(i, j)];
        }
    }
    out
}

/// World position of each foot's collision-shape centre, from the URDF text, the profile and a
/// state, by walking each foot's chain up to the root and composing transforms by hand.
pub(super) fn independent_foot_centres(fixture: &Robot, state: &RobotState) -> Vec<[f64; 3]> {
    let robot = urdf_rs::read_from_string(&fixture.urdf).expect("the robot's URDF parses");
    let profile = &fixture.profile;
    let angle_of: HashMap<&str, f64> = profile
        .joints
        .iter()
        .zip(&state.q)
        .map(|(j, &q)| (j.urdf.as_str(), q))
        .collect();
    let joint_to_child: HashMap<&str, &urdf_rs::Joint> = robot
        .joints
        .iter()
        .map(|j| (j.child.link.as_str(), j))
        .collect();
    let root = isometry_to_mat(&state.trunk.pose);
    profile
        .feet
        .iter()
        .map(|foot| {
            let link = robot
                .links
                .iter()
                .find(|l| l.name == foot.link)
                .expect("foot link in the URDF");
            let collision = link
                .collision
                .iter()
                .find(|c| {
                    foot.collision
                        .as_ref()
                        .is_none_or(|n| c.name.as_ref() == Some(n))
                })
                .expect("foot collision in the URDF");
            // Chain of transforms from the foot link up to the root.
            let mut chain: Vec<Mat4> = Vec::new();
            let mut current = foot.link.as_str();
            while let Some(joint) = joint_to_child.get(current) {
                let mut t = urdf_transform(joint.origin.xyz.0, joint.origin.rpy.0);
                if joint.joint_type != urdf_rs::JointType::Fixed {
                    let q = angle_of[joint.name.as_str()];
                    t = mat_mul(&t, &axis_angle(joint.axis.xyz.0, q));
                }
                chain.push(t);
                current = joint.parent.link.as_str();
            }
            let mut world = root;
            for t in chain.iter().rev() {
                world = mat_mul(&world, t);
            }
            let c = collision.origin.xyz.0;
            std::array::from_fn(|i| {
                world[i][0] * c[0] + world[i][1] * c[1] + world[i][2] * c[2] + world[i][3]
            })
        })
        .collect()
}

pub(super) fn foot_centres_from(model: &RobotModel, poses: &[Isometry3<f64>]) -> Vec<[f64; 3]> {
    model.tracked()[..model.num_feet()]
        .iter()
        .map(|t| {
            let link = &model.links()[t.link];
            let c = poses[t.link] * link.collisions[t.shapes[0]].origin;
            c.translation.vector.into()
        })
        .collect()
}

pub(super) fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}
