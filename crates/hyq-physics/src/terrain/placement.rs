//! Putting a robot down on the ground: its trunk tilted to the ground under its feet (or kept
//! as given), and raised or lowered until its lowest foot is a chosen clearance above the
//! ground.

use nalgebra::{Isometry3, Matrix3, UnitQuaternion, Vector3};

use super::Terrain;
use crate::model::RobotModel;
use crate::state::RobotState;

/// A robot's state put down on the ground (see [`place`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// The state: the given one with the trunk moved along z (and tilted, if asked).
    pub state: RobotState,
    /// The lowest foot's clearance above the ground (m): the clearance asked for, to within
    /// a micrometre.
    pub foot_clearance: f64,
    /// The lowest clearance (m) of any other shape of the robot (at most: the upper bound of
    /// its clearance). Negative when part of the robot other than a foot is in the ground: the
    /// robot cannot stand there.
    pub other_clearance: f64,
}

/// Puts `state` down on `terrain`: with `tilt`, the trunk's roll and pitch follow the plane
/// fitted (least squares) through the ground under the feet, its yaw kept; then the trunk
/// moves along z until the lowest foot is `clearance` (m) above the ground. The joints are
/// kept.
pub fn place(
    model: &RobotModel,
    terrain: &Terrain,
    state: &RobotState,
    tilt: bool,
    clearance: f64,
) -> Placed {
    let mut state = state.clone();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    if tilt {
        // The feet move a little as the trunk turns, so fit again from where they are.
        for _ in 0..3 {
            fk(model, &state, &mut poses);
            let feet: Vec<Vector3<f64>> = (0..model.num_feet())
                .map(|t| poses[model.tracked()[t].link].translation.vector)
                .collect();
            let (_, _, yaw) = state.trunk.pose.rotation.euler_angles();
            let (gx, gy) = ground_gradient(terrain, &feet);
            // The gradient along the trunk's heading (forward) and across it (left).
            let (sin, cos) = yaw.sin_cos();
            let (ahead, left) = (gx * cos + gy * sin, -gx * sin + gy * cos);
            // Rising ground ahead lifts the nose (negative pitch about the trunk's y); rising
            // ground to the left lifts the left side (positive roll about its x).
            let tilt = UnitQuaternion::from_euler_angles(left.atan(), -ahead.atan(), 0.0);
            state.trunk.pose.rotation =
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw) * tilt;
        }
    }
    let mut foot_clearance = f64::NAN;
    for _ in 0..50 {
        fk(model, &state, &mut poses);
        foot_clearance = lowest_foot(model, terrain, &poses);
        let error = clearance - foot_clearance;
        if error.abs() < 1e-7 {
            break;
        }
        state.trunk.pose.translation.z += error;
    }
    fk(model, &state, &mut poses);
    Placed {
        other_clearance: lowest_other(model, terrain, &poses),
        foot_clearance,
        state,
    }
}

/// Body poses of `state` (its joint angles are the model's length, as every state given
/// here).
fn fk(model: &RobotModel, state: &RobotState, poses: &mut [Isometry3<f64>]) {
    // A state of the model's lengths always has forward kinematics.
    if model
        .link_poses(&state.trunk.pose, &state.q, poses)
        .is_err()
    {
        poses.fill(Isometry3::identity());
    }
}

/// The gradient (dz/dx, dz/dy) of the plane fitted through the ground under the points
/// `feet` (their x and y), least squares; level if the feet are collinear.
fn ground_gradient(terrain: &Terrain, feet: &[Vector3<f64>]) -> (f64, f64) {
    let n = feet.len() as f64;
    let mean = feet.iter().sum::<Vector3<f64>>() / n;
    let hmean = feet
        .iter()
        .map(|f| terrain.height_at(f.x, f.y))
        .sum::<f64>()
        / n;
    let (mut a, mut b) = (Matrix3::zeros(), Vector3::zeros());
    for f in feet {
        let d = Vector3::new(f.x - mean.x, f.y - mean.y, 1.0);
        a += d * d.transpose();
        b += d * (terrain.height_at(f.x, f.y) - hmean);
    }
    a[(2, 2)] = n;
    match a.try_inverse() {
        Some(inv) => {
            let g = inv * b;
            (g.x, g.y)
        }
        None => (0.0, 0.0),
    }
}

/// The lowest clearance of the feet's shapes.
fn lowest_foot(model: &RobotModel, terrain: &Terrain, poses: &[Isometry3<f64>]) -> f64 {
    model.tracked()[..model.num_feet()]
        .iter()
        .flat_map(|t| {
            let link = &model.links()[t.link];
            t.shapes.iter().map(move |&s| {
                let c = &link.collisions[s];
                terrain
                    .clearance(&c.shape, &(poses[t.link] * c.origin))
                    .lower
            })
        })
        .fold(f64::INFINITY, f64::min)
}

/// The lowest clearance (upper bound) of every shape that is not a foot.
fn lowest_other(model: &RobotModel, terrain: &Terrain, poses: &[Isometry3<f64>]) -> f64 {
    let feet = &model.tracked()[..model.num_feet()];
    let is_foot =
        |link: usize, s: usize| feet.iter().any(|t| t.link == link && t.shapes.contains(&s));
    model
        .links()
        .iter()
        .enumerate()
        .flat_map(|(i, link)| {
            link.collisions
                .iter()
                .enumerate()
                .filter(move |&(s, _)| !is_foot(i, s))
                .map(move |(_, c)| terrain.clearance(&c.shape, &(poses[i] * c.origin)).upper)
        })
        .fold(f64::INFINITY, f64::min)
}
