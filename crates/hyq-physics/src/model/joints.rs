//! Phase 3 of building a model: the profile's joints, resolved against the URDF and put in the
//! profile's order; then the bodies become [`Link`]s, each movable one attached by its actuated
//! [`Joint`]; and the standing pose is checked against the joints' limits.

use std::collections::{HashMap, HashSet};

use nalgebra::{Isometry3, Unit, Vector3};

use super::index::UrdfIndex;
use super::tree::BodyBuild;
use super::{Joint, Link};
use crate::error::ModelError;
use crate::profile::Profile;

/// Resolves every profile joint to its URDF joint: it must exist, be revolute, and be listed
/// once, under a short name used once. Returns the profile index of each resolved URDF joint.
pub(super) fn resolve(
    robot: &urdf_rs::Robot,
    index: &UrdfIndex<'_>,
    profile: &Profile,
) -> Result<HashMap<usize, usize>, ModelError> {
    let mut profile_index_of_urdf_joint: HashMap<usize, usize> = HashMap::new();
    let mut short_names: HashSet<&str> = HashSet::new();
    for (pi, entry) in profile.joints.iter().enumerate() {
        let field = format!("joints[{pi}].urdf");
        let ji = *index
            .joint_by_name
            .get(entry.urdf.as_str())
            .ok_or_else(|| ModelError::MissingJoint {
                joint: entry.urdf.clone(),
                referenced_by: field.clone(),
            })?;
        if robot.joints[ji].joint_type != urdf_rs::JointType::Revolute {
            return Err(ModelError::InvalidProfile {
                field,
                reason: format!(
                    "joint {:?} is {:?}; only revolute joints can be actuated",
                    entry.urdf, robot.joints[ji].joint_type
                ),
            });
        }
        if profile_index_of_urdf_joint.insert(ji, pi).is_some() {
            return Err(ModelError::InvalidProfile {
                field,
                reason: format!("joint {:?} is listed twice", entry.urdf),
            });
        }
        if !short_names.insert(entry.name.as_str()) {
            return Err(ModelError::InvalidProfile {
                field: format!("joints[{pi}].name"),
                reason: format!("short name {:?} is used twice", entry.name),
            });
        }
    }
    Ok(profile_index_of_urdf_joint)
}

/// Turns the bodies into links and makes each movable body's actuated joint, in profile order.
pub(super) fn assemble(
    robot: &urdf_rs::Robot,
    profile: &Profile,
    bodies: Vec<BodyBuild>,
    profile_index_of_urdf_joint: &HashMap<usize, usize>,
) -> Result<(Vec<Link>, Vec<Joint>), ModelError> {
    let mut joints: Vec<Option<Joint>> = vec![None; profile.joints.len()];
    let mut links = Vec::with_capacity(bodies.len());
    for (bi, body) in bodies.into_iter().enumerate() {
        let parent_joint = match body.urdf_joint {
            None => None,
            Some(ji) => {
                let urdf_joint = &robot.joints[ji];
                let pi = *profile_index_of_urdf_joint.get(&ji).ok_or_else(|| {
                    ModelError::InvalidJoint {
                        joint: urdf_joint.name.clone(),
                        reason: "is movable but not listed in the robot profile's joints".into(),
                    }
                })?;
                let parent = body.parent.ok_or_else(|| ModelError::Structure {
                    reason: format!("joint {:?} has no parent body", urdf_joint.name),
                })?;
                joints[pi] = Some(make_joint(
                    urdf_joint,
                    &profile.joints[pi].name,
                    parent,
                    bi,
                    body.joint_origin,
                )?);
                Some(pi)
            }
        };
        links.push(Link {
            name: body.name,
            parent: body.parent,
            parent_joint,
            mass: body.mass.mass,
            com: body.mass.com,
            inertia: body.mass.inertia,
            collisions: body.collisions,
            lumped: body.lumped,
        });
    }
    let joints: Vec<Joint> = joints
        .into_iter()
        .enumerate()
        .map(|(pi, j)| {
            // Every profile joint was resolved to a revolute URDF joint, and every revolute
            // joint reached from the trunk created a body; a revolute joint not reached means
            // its links are disconnected, which the walk refused.
            j.ok_or_else(|| ModelError::Structure {
                reason: format!(
                    "joint {:?} (joints[{pi}]) is not below the trunk",
                    profile.joints[pi].urdf
                ),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok((links, joints))
}

/// Checks that the profile's standing pose is within every joint's limits.
pub(super) fn check_standing(profile: &Profile, joints: &[Joint]) -> Result<(), ModelError> {
    for (pi, (entry, joint)) in profile.joints.iter().zip(joints).enumerate() {
        if !(joint.lower..=joint.upper).contains(&entry.standing) {
            return Err(ModelError::InvalidProfile {
                field: format!("joints[{pi}].standing"),
                reason: format!(
                    "{} rad is outside joint {:?}'s limits [{}, {}]",
                    entry.standing, entry.urdf, joint.lower, joint.upper
                ),
            });
        }
    }
    Ok(())
}

/// Validates a revolute URDF joint and turns it into an actuated [`Joint`].
fn make_joint(
    joint: &urdf_rs::Joint,
    short_name: &str,
    parent: usize,
    child: usize,
    origin: Isometry3<f64>,
) -> Result<Joint, ModelError> {
    let invalid = |reason: String| ModelError::InvalidJoint {
        joint: joint.name.clone(),
        reason,
    };
    let axis = Vector3::from(joint.axis.xyz.0);
    if !axis.iter().all(|v| v.is_finite()) || axis.norm() < 1e-9 {
        return Err(invalid(format!(
            "axis {:?} must be finite and non-zero",
            joint.axis.xyz.0
        )));
    }
    let l = &joint.limit;
    if !(l.lower.is_finite() && l.upper.is_finite() && l.lower < l.upper) {
        return Err(invalid(format!(
            "position limits [{}, {}] must be finite with lower < upper",
            l.lower, l.upper
        )));
    }
    if !(l.effort.is_finite() && l.effort > 0.0) {
        return Err(invalid(format!(
            "effort limit {} N·m must be finite and positive",
            l.effort
        )));
    }
    if !(l.velocity.is_finite() && l.velocity > 0.0) {
        return Err(invalid(format!(
            "velocity limit {} rad/s must be finite and positive",
            l.velocity
        )));
    }
    let (damping, friction) = joint
        .dynamics
        .as_ref()
        .map_or((0.0, 0.0), |d| (d.damping, d.friction));
    if !(damping.is_finite() && damping >= 0.0) {
        return Err(invalid(format!(
            "damping {damping} N·m·s/rad must be finite and non-negative"
        )));
    }
    if friction != 0.0 {
        return Err(invalid(format!(
            "Coulomb joint friction {friction} N·m is not supported (must be 0)"
        )));
    }
    Ok(Joint {
        name: short_name.to_owned(),
        urdf_name: joint.name.clone(),
        parent,
        child,
        origin,
        axis: Unit::new_normalize(axis),
        lower: l.lower,
        upper: l.upper,
        effort: l.effort,
        velocity: l.velocity,
        damping,
    })
}
