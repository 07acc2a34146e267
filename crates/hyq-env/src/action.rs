//! Actions to joint targets (spec §7.1, beyond the original spec: the system the original
//! describes drove 12 joint position targets through a joint PD law).
//!
//! For joint i with limits [lo_i, hi_i] and action value a_i:
//!
//! - `normalized`: q*_i = lo_i + (a_i + 1)/2 · (hi_i − lo_i), a_i ∈ [−1, 1];
//! - `absolute`:   q*_i = a_i (rad), a_i ∈ [lo_i, hi_i];
//! - `delta`:      q*_i = clip(θ_i + a_i · max_delta, lo_i, hi_i), a_i ∈ [−1, 1], θ_i the joint's
//!   angle at the start of the env step;
//! - `offset`:     q*_i = clip(s_i + a_i · max_offset, lo_i, hi_i), a_i ∈ [−1, 1], s_i the joint's
//!   angle in the robot profile's standing pose (a project-defined mode: a zero action holds
//!   the standing pose, and the policy's reach is bounded around it).
//!
//! A wrong length or a NaN or infinite value is always an error, naming the index, the joint and
//! the value. A finite value outside the action space is clipped to it (the default; the step's
//! info records that it happened) or refused, per [`OutOfRange`]. Checking comes before any
//! change, so a refused action changes nothing.

use hyq_physics::RobotModel;
use thiserror::Error;

use crate::config::{ActionConfig, ActionMode, OutOfRange};

/// Element types an action can be given in: `f64`, or `f32` as learning libraries produce.
pub trait ActionScalar: Copy + sealed::Sealed {
    /// The value as `f64` (exact for both types).
    fn to_f64(self) -> f64;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

impl ActionScalar for f64 {
    fn to_f64(self) -> f64 {
        self
    }
}

impl ActionScalar for f32 {
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

/// An action the environment refused; nothing changed in the environment.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ActionError {
    /// The action does not hold one value per joint.
    #[error("action has {got} values, expected {expected} (one per joint, in action order)")]
    Length {
        /// The number of joints.
        expected: usize,
        /// The number of values given.
        got: usize,
    },
    /// A value is NaN or infinite.
    #[error("action[{index}] ({joint}) is {value}: actions must be finite")]
    NonFinite {
        /// The value's index.
        index: usize,
        /// The joint it drives.
        joint: String,
        /// The value.
        value: f64,
    },
    /// A value outside the action space while `action.out_of_range = "error"`.
    #[error("action[{index}] ({joint}) = {value} is outside the action space [{low}, {high}]")]
    OutOfRange {
        /// The value's index.
        index: usize,
        /// The joint it drives.
        joint: String,
        /// The value.
        value: f64,
        /// The space's lower bound for this index.
        low: f64,
        /// The space's upper bound for this index.
        high: f64,
    },
}

/// The action space of an environment and its mapping onto joint targets (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct ActionSpace {
    mode: ActionMode,
    out_of_range: OutOfRange,
    max_delta: f64,
    max_offset: f64,
    standing: Vec<f64>,
    joint_names: Vec<String>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    low: Vec<f64>,
    high: Vec<f64>,
}

impl ActionSpace {
    /// The action space of `model`'s joints under `config`.
    pub fn new(model: &RobotModel, config: &ActionConfig) -> Self {
        let lower: Vec<f64> = model.joints().iter().map(|j| j.lower).collect();
        let upper: Vec<f64> = model.joints().iter().map(|j| j.upper).collect();
        let (low, high) = match config.mode {
            ActionMode::Absolute => (lower.clone(), upper.clone()),
            ActionMode::Normalized | ActionMode::Delta | ActionMode::Offset => {
                (vec![-1.0; lower.len()], vec![1.0; lower.len()])
            }
        };
        Self {
            mode: config.mode,
            out_of_range: config.out_of_range,
            max_delta: config.max_delta_rad,
            max_offset: config.max_offset_rad,
            standing: model.standing_pose().to_vec(),
            joint_names: model.joints().iter().map(|j| j.name.clone()).collect(),
            lower,
            upper,
            low,
            high,
        }
    }

    /// The mode.
    pub fn mode(&self) -> ActionMode {
        self.mode
    }

    /// The number of action values (one per joint).
    pub fn len(&self) -> usize {
        self.low.len()
    }

    /// Always false: a robot has at least one joint.
    pub fn is_empty(&self) -> bool {
        self.low.is_empty()
    }

    /// The space's lower bounds (−1, or the joint's lower limit in `absolute` mode).
    pub fn low(&self) -> &[f64] {
        &self.low
    }

    /// The space's upper bounds (+1, or the joint's upper limit in `absolute` mode).
    pub fn high(&self) -> &[f64] {
        &self.high
    }

    /// The joints' lower limits (rad), action order.
    pub fn joint_lower(&self) -> &[f64] {
        &self.lower
    }

    /// The joints' upper limits (rad), action order.
    pub fn joint_upper(&self) -> &[f64] {
        &self.upper
    }

    /// `max_delta_rad` of `delta` mode (rad per env step).
    pub fn max_delta(&self) -> f64 {
        self.max_delta
    }

    /// `max_offset_rad` of `offset` mode (rad from the standing pose).
    pub fn max_offset(&self) -> f64 {
        self.max_offset
    }

    /// The standing pose `offset` mode is relative to (rad, action order).
    pub fn standing(&self) -> &[f64] {
        &self.standing
    }

    /// Checks an action without using it: its length, that every value is finite, and (with
    /// `out_of_range = "error"`) that every value is inside the space. Allocates only to build an
    /// error.
    pub fn check<A: ActionScalar>(&self, action: &[A]) -> Result<(), ActionError> {
        if action.len() != self.len() {
            return Err(ActionError::Length {
                expected: self.len(),
                got: action.len(),
            });
        }
        for (index, a) in action.iter().enumerate() {
            let value = a.to_f64();
            if !value.is_finite() {
                return Err(ActionError::NonFinite {
                    index,
                    joint: self.joint_names[index].clone(),
                    value,
                });
            }
            if self.out_of_range == OutOfRange::Error
                && !(self.low[index]..=self.high[index]).contains(&value)
            {
                return Err(ActionError::OutOfRange {
                    index,
                    joint: self.joint_names[index].clone(),
                    value,
                    low: self.low[index],
                    high: self.high[index],
                });
            }
        }
        Ok(())
    }

    /// The joint targets (rad) of an action that passed [`ActionSpace::check`], written into
    /// `targets`; `current` holds the joint angles at the start of the step (used by `delta`).
    /// Returns whether any value was clipped to the action space. Allocates nothing.
    ///
    /// # Panics
    /// If the slices do not hold one value per joint.
    pub fn targets<A: ActionScalar>(
        &self,
        action: &[A],
        current: &[f64],
        targets: &mut [f64],
    ) -> bool {
        assert!(action.len() == self.len() && current.len() == self.len());
        assert_eq!(targets.len(), self.len());
        let mut clipped = false;
        for i in 0..self.len() {
            let raw = action[i].to_f64();
            let a = raw.clamp(self.low[i], self.high[i]);
            clipped |= a != raw;
            let (lo, hi) = (self.lower[i], self.upper[i]);
            targets[i] = match self.mode {
                ActionMode::Normalized => lo + 0.5 * (a + 1.0) * (hi - lo),
                ActionMode::Absolute => a,
                ActionMode::Delta => current[i] + a * self.max_delta,
                ActionMode::Offset => self.standing[i] + a * self.max_offset,
            }
            // The normalised map can round a hair past a limit; every mode ends inside them.
            .clamp(lo, hi);
        }
        clipped
    }

    /// The action that asks for `targets` (rad) from joint angles `current`: the inverse of
    /// [`ActionSpace::targets`], clipped to the space (a `delta` action can move a joint at most
    /// `max_delta` per step). Used by scripted policies, which think in joint targets.
    ///
    /// # Panics
    /// If the slices do not hold one value per joint.
    pub fn action_for_targets(&self, targets: &[f64], current: &[f64], out: &mut [f64]) {
        assert!(targets.len() == self.len() && current.len() == self.len());
        assert_eq!(out.len(), self.len());
        for i in 0..self.len() {
            let (lo, hi) = (self.lower[i], self.upper[i]);
            let q = targets[i].clamp(lo, hi);
            let a = match self.mode {
                ActionMode::Normalized => 2.0 * (q - lo) / (hi - lo) - 1.0,
                ActionMode::Absolute => q,
                ActionMode::Delta => (q - current[i]) / self.max_delta,
                ActionMode::Offset => (q - self.standing[i]) / self.max_offset,
            };
            out[i] = a.clamp(self.low[i], self.high[i]);
        }
    }
}
