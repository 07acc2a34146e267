//! Phase 3 of building a model: the profile's joints, resolved against the URDF and put in the
//! profile's order; then the bodies become [`Link`]s, each movable one attached by its actuated
//! [`Joint`]; and the standing pose is checked against the joints' limits.

use std::collections::{HashMap, HashSet};

use nalgebra::{Isometry3, Unit, Vector3};

use super::index::UrdfIndex;
use super::profile_values;
use super::{BodyBuild, Joint, Link};
use crate::bounds::{self, Bound, short};
use crate::error::ModelError;
use crate::profile::{JointEntry, Profile};

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
                available: robot
                    .joints
                    .iter()
                    .filter(|j| is_movable(&j.joint_type))
                    // Escaped: the names are the file's, whatever they hold.
                    .map(|j| crate::printable(&j.name))
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
        if !is_movable(&robot.joints[ji].joint_type) {
            return Err(ModelError::InvalidProfile {
                field,
                reason: format!(
                    "joint {:?} is {:?}; only revolute and continuous joints can be actuated",
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

/// Whether a URDF joint type is one the model actuates (a revolute DoF).
pub(super) fn is_movable(kind: &urdf_rs::JointType) -> bool {
    matches!(
        kind,
        urdf_rs::JointType::Revolute | urdf_rs::JointType::Continuous
    )
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
                    pi,
                    &profile.joints[pi],
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
                    short(entry.standing),
                    entry.urdf,
                    short(joint.lower),
                    short(joint.upper)
                ),
            });
        }
    }
    Ok(())
}

/// Validates a movable URDF joint and turns it into an actuated [`Joint`], with the limits the
/// profile entry `joints[pi]` overrides.
fn make_joint(
    joint: &urdf_rs::Joint,
    pi: usize,
    entry: &JointEntry,
    parent: usize,
    child: usize,
    origin: Isometry3<f64>,
) -> Result<Joint, ModelError> {
    let invalid = |reason: String| ModelError::InvalidJoint {
        joint: joint.name.clone(),
        reason,
    };
    let axis = Vector3::from(joint.axis.xyz.0);
    for v in axis.iter() {
        bounds::AXIS_COMPONENT
            .check(*v)
            .map_err(|reason| invalid(format!("axis {:?}: {reason}", joint.axis.xyz.0)))?;
    }
    if axis.norm() < bounds::AXIS_MIN_LENGTH {
        return Err(invalid(format!(
            "axis {:?} must be non-zero (at least {} long)",
            joint.axis.xyz.0,
            bounds::AXIS_MIN_LENGTH
        )));
    }
    let limits = Limits::of(joint, pi, entry)?;
    let (damping, friction) = joint
        .dynamics
        .as_ref()
        .map_or((0.0, 0.0), |d| (d.damping, d.friction));
    bounds::JOINT_DAMPING
        .check(damping)
        .map_err(|reason| invalid(format!("damping: {reason}")))?;
    bounds::JOINT_FRICTION
        .check(friction)
        .map_err(|reason| invalid(format!("Coulomb friction: {reason}")))?;
    Ok(Joint {
        name: entry.name.clone(),
        urdf_name: joint.name.clone(),
        parent,
        child,
        origin,
        axis: Unit::new_normalize(axis),
        lower: limits.lower,
        upper: limits.upper,
        effort: limits.effort,
        velocity: limits.velocity,
        damping,
        friction,
        armature: 0.0,
    })
}

/// A joint's limits: the URDF's, each replaced by the profile's override when it has one.
struct Limits {
    lower: f64,
    upper: f64,
    effort: f64,
    velocity: f64,
}

impl Limits {
    fn of(joint: &urdf_rs::Joint, pi: usize, entry: &JointEntry) -> Result<Self, ModelError> {
        let field = |key: &str| format!("joints[{pi}].{key}");
        let overridden = |key: &str, value: Option<f64>, bound: &Bound| {
            value
                .map(|v| profile_values::bounded(bound, field(key), v))
                .transpose()
        };
        let l = &joint.limit;
        let continuous = joint.joint_type == urdf_rs::JointType::Continuous;
        // A continuous joint's <limit> has no position limits, whatever it says.
        let (urdf_lower, urdf_upper) = if continuous {
            (None, None)
        } else {
            (Some(l.lower), Some(l.upper))
        };
        let lower = overridden("lower", entry.lower, &bounds::JOINT_ANGLE)?.or(urdf_lower);
        let upper = overridden("upper", entry.upper, &bounds::JOINT_ANGLE)?.or(urdf_upper);
        let effort = overridden("effort", entry.effort, &bounds::JOINT_EFFORT)?.unwrap_or(l.effort);
        let velocity =
            overridden("velocity", entry.velocity, &bounds::JOINT_VELOCITY)?.unwrap_or(l.velocity);
        let invalid = |reason: String| ModelError::InvalidJoint {
            joint: joint.name.clone(),
            reason,
        };
        let (Some(lower), Some(upper)) = (lower, upper) else {
            return Err(invalid(format!(
                "a continuous joint has no position limits; give {} and {} in the robot profile",
                field("lower"),
                field("upper")
            )));
        };
        if lower == 0.0 && upper == 0.0 && entry.lower.is_none() && entry.upper.is_none() {
            return Err(invalid(format!(
                "the URDF gives no position limits (no <limit lower upper>); add them to the \
                 URDF or give {} and {} in the robot profile",
                field("lower"),
                field("upper")
            )));
        }
        let limits = Self {
            lower,
            upper,
            effort,
            velocity,
        };
        limits.check(&joint.name, pi)?;
        Ok(limits)
    }

    /// Checks the limits (the URDF's figures and the profile's overrides, which were checked
    /// under their own keys already) against the bounds table, and the range for lower < upper.
    fn check(&self, joint: &str, pi: usize) -> Result<(), ModelError> {
        let field = |key: &str| format!("joints[{pi}].{key}");
        let invalid = |reason: String| ModelError::InvalidJoint {
            joint: joint.to_owned(),
            reason,
        };
        let (lower, upper, effort, velocity) = (self.lower, self.upper, self.effort, self.velocity);
        let urdf_bound = |what: &str, key: &str, v: f64, bound: &Bound| {
            bound.check(v).map_err(|reason| {
                invalid(format!(
                    "{what}: {reason} (the profile's {} overrides the URDF's)",
                    field(key)
                ))
            })
        };
        urdf_bound("lower position limit", "lower", lower, &bounds::JOINT_ANGLE)?;
        urdf_bound("upper position limit", "upper", upper, &bounds::JOINT_ANGLE)?;
        if lower >= upper {
            return Err(invalid(format!(
                "position limits [{}, {}] must have lower < upper \
                 (the profile's {} and {} override the URDF's)",
                short(lower),
                short(upper),
                field("lower"),
                field("upper")
            )));
        }
        bounds::JOINT_SPAN.check(upper - lower).map_err(|reason| {
            invalid(format!(
                "position limits [{}, {}]: the range {reason} (the profile's {} and \
                 {} override the URDF's)",
                short(lower),
                short(upper),
                field("lower"),
                field("upper")
            ))
        })?;
        urdf_bound("effort limit", "effort", effort, &bounds::JOINT_EFFORT)?;
        urdf_bound(
            "velocity limit",
            "velocity",
            velocity,
            &bounds::JOINT_VELOCITY,
        )?;
        Ok(())
    }
}
