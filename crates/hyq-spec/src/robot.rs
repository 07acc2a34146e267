//! What the rules need to know about a robot: its joints (name, range, speed limit) in action
//! order, the feet whose ground contact is observed, and the trunk's observation bounds.
//!
//! Not a spec section: the spec describes HyQ only, but its rules hold for any legged robot, so
//! every rule in this crate takes the robot through this description (or slices of it) and none
//! assumes twelve joints or four feet. [`RobotDescription::hyq_spec`] is HyQ as the spec's §3
//! table states it.

use crate::nomenclature::{HyqJoint, Leg};
use crate::table::SPEC_TABLE;
use crate::termination::joint_limit::{JointRange, JointRangeError};
use std::collections::HashSet;
use thiserror::Error;

/// A closed interval [min, max] of declared observation values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The lower bound.
    pub min: f64,
    /// The upper bound.
    pub max: f64,
}

/// One actuated joint as the rules see it.
#[derive(Clone, Debug, PartialEq)]
pub struct JointDescription {
    /// The joint's short name, which prefixes its observation rows (`"lf_haa"` gives
    /// `lf_haa_angle` and `lf_haa_speed`).
    pub name: String,
    /// Its range [θ_min, θ_max], radians: the bounds of its angle row and the ends of the §6.2
    /// test.
    pub range: JointRange,
    /// Its speed limit, rad/s (> 0): its speed row's bounds are ±this.
    pub velocity_limit: f64,
}

/// The trunk as the observation sees it: its name and the declared bounds of its estimated rows.
#[derive(Clone, Debug, PartialEq)]
pub struct TrunkDescription {
    /// The trunk link's name, which prefixes its rows (`"trunk"` gives `trunk_contact_flag`,
    /// `trunk_rotation_w`, …).
    pub name: String,
    /// Declared bounds of the trunk's linear acceleration (x, y, z), m/s².
    pub acceleration: [Bounds; 3],
    /// Declared bounds of the trunk's position (x, y, z), metres.
    pub position: [Bounds; 3],
}

impl TrunkDescription {
    /// HyQ's trunk with the spec's §3 bounds (rows 33–38, estimates): acceleration ±50 m/s²,
    /// position x, y in ±10 m and z in [0, 1] m.
    pub fn spec() -> Self {
        let bounds = |row: usize| Bounds {
            min: SPEC_TABLE[row].min,
            max: SPEC_TABLE[row].max,
        };
        TrunkDescription {
            name: "trunk".to_owned(),
            acceleration: [bounds(33), bounds(34), bounds(35)],
            position: [bounds(36), bounds(37), bounds(38)],
        }
    }
}

/// A robot description that was checked: names present and unique, limits valid.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotDescription {
    joints: Vec<JointDescription>,
    joint_ranges: Vec<JointRange>,
    feet: Vec<String>,
    trunk: TrunkDescription,
}

/// An invalid robot description; each variant names what was wrong.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum RobotError {
    /// The description has no joints.
    #[error("a robot description needs at least one joint")]
    NoJoints,
    /// A joint, foot or trunk name is empty.
    #[error("{what} {index} has an empty name")]
    EmptyName {
        /// `"joint"`, `"foot"` or `"trunk"`.
        what: &'static str,
        /// Its position in its list (0 for the trunk).
        index: usize,
    },
    /// Two joints share a name, or a foot shares a name with another foot or the trunk (their
    /// observation rows would collide).
    #[error("the name `{name}` is used twice: observation row names must be unique")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },
    /// A joint's speed limit is not finite and > 0.
    #[error("joint `{joint}` has velocity limit {value}: it must be finite and > 0")]
    VelocityLimit {
        /// The joint's name.
        joint: String,
        /// The rejected limit.
        value: f64,
    },
    /// Declared trunk bounds that are not finite with min < max.
    #[error(
        "trunk {quantity} bounds [{min}, {max}] on axis {axis}: they must be finite with min < max"
    )]
    TrunkBounds {
        /// `"acceleration"` or `"position"`.
        quantity: &'static str,
        /// `'x'`, `'y'` or `'z'`.
        axis: char,
        /// The rejected lower bound.
        min: f64,
        /// The rejected upper bound.
        max: f64,
    },
}

impl RobotDescription {
    /// Checks and builds a description: `joints` in action order (their ranges are valid by
    /// construction), `feet` the names of the links whose ground contact is observed, in
    /// observation order, and the `trunk`.
    pub fn new(
        joints: Vec<JointDescription>,
        feet: Vec<String>,
        trunk: TrunkDescription,
    ) -> Result<Self, RobotError> {
        if joints.is_empty() {
            return Err(RobotError::NoJoints);
        }
        let mut joint_names = HashSet::new();
        for (index, joint) in joints.iter().enumerate() {
            if joint.name.is_empty() {
                return Err(RobotError::EmptyName {
                    what: "joint",
                    index,
                });
            }
            if !joint_names.insert(joint.name.as_str()) {
                return Err(RobotError::DuplicateName {
                    name: joint.name.clone(),
                });
            }
            if !(joint.velocity_limit.is_finite() && joint.velocity_limit > 0.0) {
                return Err(RobotError::VelocityLimit {
                    joint: joint.name.clone(),
                    value: joint.velocity_limit,
                });
            }
        }
        if trunk.name.is_empty() {
            return Err(RobotError::EmptyName {
                what: "trunk",
                index: 0,
            });
        }
        let mut contact_names = HashSet::from([trunk.name.as_str()]);
        for (index, foot) in feet.iter().enumerate() {
            if foot.is_empty() {
                return Err(RobotError::EmptyName {
                    what: "foot",
                    index,
                });
            }
            if !contact_names.insert(foot.as_str()) {
                return Err(RobotError::DuplicateName { name: foot.clone() });
            }
        }
        for (quantity, bounds) in [
            ("acceleration", &trunk.acceleration),
            ("position", &trunk.position),
        ] {
            for (b, axis) in bounds.iter().zip(['x', 'y', 'z']) {
                if !(b.min.is_finite() && b.max.is_finite() && b.min < b.max) {
                    return Err(RobotError::TrunkBounds {
                        quantity,
                        axis,
                        min: b.min,
                        max: b.max,
                    });
                }
            }
        }
        let joint_ranges = joints.iter().map(|j| j.range).collect();
        Ok(RobotDescription {
            joints,
            joint_ranges,
            feet,
            trunk,
        })
    }

    /// HyQ as the spec's §3 table states it: the twelve joints in the spec order with the table's
    /// ranges (rows 0–11) and speed limits (rows 12–23), the feet `lf, lh, rf, rh` (rows 24–27)
    /// and [`TrunkDescription::spec`]. The URDF's ranges agree with these to the table's six
    /// printed digits.
    pub fn hyq_spec() -> Self {
        let joints = HyqJoint::ALL
            .iter()
            .map(|joint| {
                let (angle, speed) = (&SPEC_TABLE[joint.index()], &SPEC_TABLE[12 + joint.index()]);
                JointDescription {
                    name: joint.name().to_owned(),
                    range: JointRange::new(angle.min, angle.max).unwrap_or_else(
                        |e: JointRangeError| {
                            unreachable!("the §3 table's joint rows are ordered: {e}")
                        },
                    ),
                    velocity_limit: speed.max,
                }
            })
            .collect();
        let feet = Leg::ALL
            .iter()
            .map(|leg| leg.short_name().to_owned())
            .collect();
        // Invariant: the §3 table's names are unique and its limits valid; the unit test
        // `hyq_spec_is_a_valid_description` checks it.
        Self::new(joints, feet, TrunkDescription::spec())
            .unwrap_or_else(|e| unreachable!("the §3 table describes a valid robot: {e}"))
    }

    /// The joints, in action order.
    pub fn joints(&self) -> &[JointDescription] {
        &self.joints
    }

    /// The joints' ranges, in action order: what [`crate::StepSnapshot::joint_ranges`] takes.
    pub fn joint_ranges(&self) -> &[JointRange] {
        &self.joint_ranges
    }

    /// The names of the feet whose contact is observed, in observation order.
    pub fn feet(&self) -> &[String] {
        &self.feet
    }

    /// The trunk.
    pub fn trunk(&self) -> &TrunkDescription {
        &self.trunk
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn joint(name: &str, velocity_limit: f64) -> JointDescription {
        let Ok(range) = JointRange::new(-1.0, 1.0) else {
            panic!("valid range")
        };
        JointDescription {
            name: name.to_owned(),
            range,
            velocity_limit,
        }
    }

    #[test]
    fn hyq_spec_is_a_valid_description() {
        let hyq = RobotDescription::hyq_spec();
        assert_eq!(hyq.joints().len(), 12);
        assert_eq!(hyq.feet(), ["lf", "lh", "rf", "rh"]);
        assert_eq!(hyq.joint_ranges()[2], hyq.joints()[2].range);
        let rebuilt = RobotDescription::new(
            hyq.joints().to_vec(),
            hyq.feet().to_vec(),
            hyq.trunk().clone(),
        );
        assert_eq!(rebuilt, Ok(hyq));
    }

    #[test]
    fn invalid_descriptions_name_what_is_wrong() {
        let feet = || vec!["a".to_owned()];
        let t = TrunkDescription::spec;
        assert_eq!(
            RobotDescription::new(vec![], feet(), t()),
            Err(RobotError::NoJoints)
        );
        let e = RobotDescription::new(vec![joint("knee", 1.0), joint("knee", 1.0)], feet(), t());
        assert_eq!(
            e,
            Err(RobotError::DuplicateName {
                name: "knee".into()
            })
        );
        let e = RobotDescription::new(vec![joint("knee", 0.0)], feet(), t());
        assert!(
            matches!(&e, Err(RobotError::VelocityLimit { joint, .. }) if joint == "knee"),
            "{e:?}"
        );
        let e = RobotDescription::new(vec![joint("", 1.0)], feet(), t());
        assert_eq!(
            e,
            Err(RobotError::EmptyName {
                what: "joint",
                index: 0
            })
        );
        let e = RobotDescription::new(vec![joint("knee", 1.0)], vec!["trunk".into()], t());
        assert_eq!(
            e,
            Err(RobotError::DuplicateName {
                name: "trunk".into()
            })
        );
        let mut trunk = t();
        trunk.position[2] = Bounds { min: 1.0, max: 0.0 };
        let e = RobotDescription::new(vec![joint("knee", 1.0)], feet(), trunk);
        assert!(
            matches!(
                e,
                Err(RobotError::TrunkBounds {
                    quantity: "position",
                    axis: 'z',
                    ..
                })
            ),
            "{e:?}"
        );
    }
}
