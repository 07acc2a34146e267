//! Spec §6.2 (Reach Joint Limits), as ruled (a **deviation**): at the end of each
//! step joint i has reached its limit when its angle θ^i is within ε_joint
//! (`accepted_dist_to_bounds`) of either end of its range [θ_min^i, θ_max^i], ends included:
//!
//! limit reached ⇔ ∃ i: θ^i ≤ θ_min^i + ε_joint  ∨  θ^i ≥ θ_max^i − ε_joint.
//!
//! The printed test, "False when θ_min < |θ − ε| < θ_max", is false for every angle of a joint
//! whose range is negative (HyQ's front knees, −2.44…−0.35 rad): |θ − ε| is never negative, so
//! every episode would end on its first step (kept in [`crate::printed::joint_limit_reached`] to
//! show why). The ranges are the robot's (for HyQ, the URDF's, equal to the §3 table to its six
//! printed digits).

use thiserror::Error;

/// A joint's range [lower, upper] in radians: finite, lower < upper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointRange {
    lower: f64,
    upper: f64,
}

/// A joint range that is not finite with lower < upper.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
#[error("invalid joint range [{lower}, {upper}]: both ends must be finite with lower < upper")]
pub struct JointRangeError {
    /// The rejected lower end, radians.
    pub lower: f64,
    /// The rejected upper end, radians.
    pub upper: f64,
}

impl JointRange {
    /// The range [`lower`, `upper`] in radians, or an error unless both are finite and
    /// `lower` < `upper`.
    pub const fn new(lower: f64, upper: f64) -> Result<Self, JointRangeError> {
        if lower.is_finite() && upper.is_finite() && lower < upper {
            Ok(JointRange { lower, upper })
        } else {
            Err(JointRangeError { lower, upper })
        }
    }

    /// θ_min, radians.
    pub const fn lower(self) -> f64 {
        self.lower
    }

    /// θ_max, radians.
    pub const fn upper(self) -> f64 {
        self.upper
    }
}

/// Which end of its range a joint has reached.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitSide {
    /// θ ≤ θ_min + ε_joint.
    Lower,
    /// θ ≥ θ_max − ε_joint.
    Upper,
}

/// The first joint (lowest index) found at a limit, reported with the §6.2 termination.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct JointLimitHit {
    /// The joint's index in the robot description's joint order (the spec order for HyQ).
    pub joint: usize,
    /// Its angle, radians.
    pub angle: f64,
    /// Which limit it reached.
    pub side: LimitSide,
}

/// Joint angles and joint ranges of different lengths: they pair by index, joint by joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
#[error("{angles} joint angles given for {ranges} joint ranges: they must pair one to one")]
pub struct JointCountMismatch {
    /// How many angles were given.
    pub angles: usize,
    /// How many ranges were given.
    pub ranges: usize,
}

/// Which limit `angle` (radians) has reached, if any: `Lower` when θ ≤ θ_min + ε, `Upper` when
/// θ ≥ θ_max − ε (`Lower` if both, which needs a range narrower than 2ε). NaN reaches neither.
pub fn joint_at_limit(
    angle: f64,
    range: JointRange,
    accepted_dist_to_bounds: f64,
) -> Option<LimitSide> {
    if angle <= range.lower + accepted_dist_to_bounds {
        Some(LimitSide::Lower)
    } else if angle >= range.upper - accepted_dist_to_bounds {
        Some(LimitSide::Upper)
    } else {
        None
    }
}

/// The first joint at a limit (§6.2), pairing `angles[i]` with `ranges[i]`; an error if the two
/// slices differ in length.
pub fn first_joint_at_limit(
    angles: &[f64],
    ranges: &[JointRange],
    accepted_dist_to_bounds: f64,
) -> Result<Option<JointLimitHit>, JointCountMismatch> {
    if angles.len() != ranges.len() {
        return Err(JointCountMismatch {
            angles: angles.len(),
            ranges: ranges.len(),
        });
    }
    Ok(angles
        .iter()
        .zip(ranges)
        .enumerate()
        .find_map(|(joint, (&angle, &range))| {
            joint_at_limit(angle, range, accepted_dist_to_bounds).map(|side| JointLimitHit {
                joint,
                angle,
                side,
            })
        }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_must_be_finite_and_ordered() {
        assert!(JointRange::new(-1.0, 1.0).is_ok());
        assert_eq!(
            JointRange::new(1.0, 1.0),
            Err(JointRangeError {
                lower: 1.0,
                upper: 1.0
            })
        );
        assert!(JointRange::new(1.0, -1.0).is_err());
        assert!(JointRange::new(f64::NAN, 1.0).is_err());
        assert!(JointRange::new(0.0, f64::INFINITY).is_err());
    }

    #[test]
    fn reports_the_first_joint_at_a_limit_and_rejects_mismatched_lengths()
    -> Result<(), JointRangeError> {
        let ranges = [
            JointRange::new(-1.0, 1.0)?,
            JointRange::new(0.35, 2.44)?,
            JointRange::new(-2.44, -0.35)?,
        ];
        let found = first_joint_at_limit(&[0.0, 1.0, -0.345], &ranges, 0.01);
        assert_eq!(
            found,
            Ok(Some(JointLimitHit {
                joint: 2,
                angle: -0.345,
                side: LimitSide::Upper
            }))
        );
        assert_eq!(
            first_joint_at_limit(&[0.0, 1.0, -1.0], &ranges, 0.01),
            Ok(None)
        );
        assert_eq!(
            first_joint_at_limit(&[0.0, 1.0], &ranges, 0.01),
            Err(JointCountMismatch {
                angles: 2,
                ranges: 3
            })
        );
        Ok(())
    }
}
