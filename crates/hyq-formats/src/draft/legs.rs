//! The legs of a provisional model (joints in file order): each leaf body is a leg's end, its
//! chain of joints back to the trunk is the leg, its foot is the leaf's collision sphere (or
//! its lowest shape); four legs of three joints, placed front/hind and left/right about the
//! trunk with an abduction axis along x and two flexion axes along y, get the project's names.

use hyq_physics::na::{Isometry3, Vector3};
use hyq_physics::{RobotModel, Shape};

use super::types::DraftError;

/// The project's leg names, in the profile's (leg-major) order.
pub(crate) const LEG_NAMES: [&str; 4] = ["lf", "lh", "rf", "rh"];

/// The project's joint names along a leg, trunk first.
pub(crate) const JOINT_ROLES: [&str; 3] = ["haa", "hfe", "kfe"];

/// A leg of the provisional model.
#[derive(Debug, Clone)]
pub(crate) struct Leg {
    /// Its joints (model indices, file order), trunk first.
    pub(crate) joints: Vec<usize>,
    /// The leaf body.
    pub(crate) leaf: usize,
    /// The foot shape: an index into the leaf body's collisions.
    pub(crate) foot: usize,
    /// How the foot was chosen (for the comment).
    pub(crate) foot_why: String,
    /// The first joint's position in the trunk frame at the standing pose.
    pub(crate) hip: Vector3<f64>,
}

/// The legs, and their names when the project's naming applies.
#[derive(Debug, Clone)]
pub(crate) struct Legs {
    /// The legs: in [`LEG_NAMES`] order when named, else in the model's body order.
    pub(crate) legs: Vec<Leg>,
    /// Whether the legs are named lf, lh, rf, rh with joints haa, hfe, kfe.
    pub(crate) named: bool,
    /// Why the naming applies or does not (a sentence for the comment).
    pub(crate) why: String,
}

/// Every body pose at the standing pose, trunk at the origin.
pub(crate) fn standing_poses(model: &RobotModel) -> Vec<Isometry3<f64>> {
    let mut poses = vec![Isometry3::identity(); model.links().len()];
    // One angle per joint and one pose per body: the call cannot fail.
    let _ = model.link_poses(&Isometry3::identity(), model.standing_pose(), &mut poses);
    poses
}

/// The legs of `model` (built with its joints in file order), `origin` naming the file.
pub(crate) fn legs(model: &RobotModel, origin: &str) -> Result<Legs, DraftError> {
    let links = model.links();
    let poses = standing_poses(model);
    let leaves: Vec<usize> = (1..links.len())
        .filter(|&i| !links.iter().any(|l| l.parent == Some(i)))
        .collect();
    if leaves.is_empty() {
        return Err(DraftError::at(
            origin,
            "a robot with no legs: no body hangs from the trunk by a hinge",
        ));
    }
    let mut legs = Vec::with_capacity(leaves.len());
    for leaf in leaves {
        let mut joints = Vec::new();
        let mut body = leaf;
        while let (Some(parent), Some(j)) = (links[body].parent, links[body].parent_joint) {
            joints.push(j);
            body = parent;
        }
        joints.reverse();
        let (foot, foot_why) = foot(model, leaf, &poses[leaf]).ok_or_else(|| {
            DraftError::at(
                origin,
                format_args!(
                    "leg ending in body {:?} has no collision shape to be its foot",
                    hyq_physics::printable(&links[leaf].name)
                ),
            )
        })?;
        let first = &model.joints()[joints[0]];
        let hip = (poses[first.parent] * first.origin).translation.vector;
        legs.push(Leg {
            joints,
            leaf,
            foot,
            foot_why,
            hip,
        });
    }
    Ok(name_legs(model, &poses, legs))
}

/// The leaf body's foot: its lowest collision sphere at the standing pose, else its lowest
/// shape; with why it was chosen.
fn foot(model: &RobotModel, leaf: usize, pose: &Isometry3<f64>) -> Option<(usize, String)> {
    let shapes = &model.links()[leaf].collisions;
    let lowest = |sphere: bool| {
        shapes
            .iter()
            .enumerate()
            .filter(|(_, c)| !sphere || matches!(c.shape, Shape::Sphere { .. }))
            .map(|(i, c)| (i, c.shape.lowest_z(&(pose * c.origin))))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    };
    let spheres = shapes
        .iter()
        .filter(|c| matches!(c.shape, Shape::Sphere { .. }))
        .count();
    match spheres {
        0 => lowest(false).map(|i| {
            (
                i,
                "its lowest collision shape at the standing pose (no sphere)".to_owned(),
            )
        }),
        1 => lowest(true).map(|i| (i, "its collision sphere".to_owned())),
        n => lowest(true).map(|i| {
            (
                i,
                format!("the lowest of its {n} collision spheres at the standing pose"),
            )
        }),
    }
}

/// Names the legs (and puts them in [`LEG_NAMES`] order) when there are four of three joints
/// each, one in each quadrant about the trunk (x forward, y left), each with its first axis
/// along x and the other two along y; leaves them in body order otherwise.
fn name_legs(model: &RobotModel, poses: &[Isometry3<f64>], legs: Vec<Leg>) -> Legs {
    let unnamed = |legs: Vec<Leg>, why: String| Legs {
        legs,
        named: false,
        why,
    };
    if legs.len() != 4 || legs.iter().any(|l| l.joints.len() != 3) {
        let shape: Vec<String> = legs.iter().map(|l| l.joints.len().to_string()).collect();
        return unnamed(
            legs,
            format!(
                "the legs are not four of three joints each (joints per leg: {})",
                shape.join(", ")
            ),
        );
    }
    let mut joints: Vec<usize> = legs.iter().flat_map(|l| l.joints.iter().copied()).collect();
    joints.sort_unstable();
    joints.dedup();
    if joints.len() != model.num_joints() {
        return unnamed(legs, "the legs share joints".to_owned());
    }
    let along = |j: usize, axis: usize| {
        let joint = &model.joints()[j];
        let world = (poses[joint.parent] * joint.origin).rotation * joint.axis.into_inner();
        world[axis].abs() >= 0.9
    };
    for leg in &legs {
        if !(along(leg.joints[0], 0) && along(leg.joints[1], 1) && along(leg.joints[2], 1)) {
            let name = &model.links()[leg.leaf].name;
            return unnamed(
                legs.clone(),
                format!(
                    "the leg ending in {:?} does not have its first joint's axis along x and the \
                 other two along y (abduction, then two flexions)",
                    hyq_physics::printable(name)
                ),
            );
        }
    }
    let label = |l: &Leg| -> Option<usize> {
        let (x, y) = (l.hip.x, l.hip.y);
        if x == 0.0 || y == 0.0 {
            return None;
        }
        Some(match (y > 0.0, x > 0.0) {
            (true, true) => 0,
            (true, false) => 1,
            (false, true) => 2,
            (false, false) => 3,
        })
    };
    let mut slots: [Option<Leg>; 4] = Default::default();
    for leg in &legs {
        match label(leg) {
            Some(k) if slots[k].is_none() => slots[k] = Some(leg.clone()),
            _ => {
                return unnamed(
                    legs,
                    "the legs' hips are not one in each quadrant about the trunk \
                     (front/hind by x, left/right by y)"
                        .to_owned(),
                );
            }
        }
    }
    Legs {
        legs: slots.into_iter().flatten().collect(),
        named: true,
        why: "four legs of three joints, one hip in each quadrant about the trunk (x forward, \
              y left), each leg's first axis along x and the other two along y"
            .to_owned(),
    }
}
