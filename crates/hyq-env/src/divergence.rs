//! Why a step diverged: the typed cause the sub-step, state-reading and observation paths of
//! [`crate::Env::step`] return, and that `info.divergence` holds. Its `Display` is the text the
//! info reports (the Python info's `divergence`).

use std::sync::Arc;

use hyq_physics::PhysicsError;
use hyq_spec::{ObservationError, StepError};
use serde::{Serialize, Serializer};
use thiserror::Error;

use crate::config::outside_world_reason;

/// What made a step diverge; the episode ends with the reason `diverged`.
#[derive(Clone, Debug, Error)]
pub enum Divergence {
    /// A physics sub-step failed: the backend's error (`PhysicsError::Diverged` or another), or
    /// a torque the actuator computed that is not finite.
    #[error("{0}")]
    Substep(Arc<PhysicsError>),
    /// A reading after the sub-steps is not finite although the backend reported success.
    #[error("{what} ({value}) is not finite after the step")]
    NonFiniteReading {
        /// The quantity, as `hyq_physics::RobotState::first_non_finite` names it.
        what: String,
        /// Its value.
        value: f64,
    },
    /// The trunk left the world (see [`crate::WORLD_HALF_EXTENT_M`]).
    #[error(
        "{row} = {value:?} m: the trunk left the world, which {}",
        outside_world_reason()
    )]
    OutsideWorld {
        /// The trunk position row of the coordinate out of bounds (`trunk_position_x`, …).
        row: String,
        /// The coordinate (m).
        value: f64,
    },
    /// The trunk left the height field's rectangle, beyond which there is no ground.
    #[error(
        "the trunk left the terrain at ({x:.2}, {y:.2}) m: the height field spans x {x_min:.2} .. \
         {x_max:.2} m, y {y_min:.2} .. {y_max:.2} m (terrain.size_m)"
    )]
    OffTerrain {
        /// The trunk's x (m).
        x: f64,
        /// The trunk's y (m).
        y: f64,
        /// The field's lowest x (m).
        x_min: f64,
        /// The field's highest x (m).
        x_max: f64,
        /// The field's lowest y (m).
        y_min: f64,
        /// The field's highest y (m).
        y_max: f64,
    },
    /// The rules could not evaluate the state.
    #[error(transparent)]
    Rules(#[from] StepError),
    /// The observation could not be formed (a value the layout refuses).
    #[error(transparent)]
    Observation(#[from] ObservationError),
    /// An observation value beyond float32's range, which the f32 observation cannot hold.
    #[error(
        "observation row {index} ({name}) = {value:?} is beyond float32's range (±{:e})",
        f32::MAX
    )]
    BeyondFloat32 {
        /// The row's index.
        index: usize,
        /// The row's name.
        name: String,
        /// The value.
        value: f64,
    },
}

impl From<PhysicsError> for Divergence {
    fn from(e: PhysicsError) -> Self {
        Divergence::Substep(Arc::new(e))
    }
}

/// Two causes are equal when they are of one kind with equal details (numbers bit for bit); a
/// sub-step's physics errors, which have no equality of their own, when they read the same.
impl PartialEq for Divergence {
    fn eq(&self, other: &Self) -> bool {
        use Divergence::*;
        match (self, other) {
            (Substep(a), Substep(b)) => Arc::ptr_eq(a, b) || a.to_string() == b.to_string(),
            (NonFiniteReading { what, value }, NonFiniteReading { what: w, value: v }) => {
                what == w && value.to_bits() == v.to_bits()
            }
            (OutsideWorld { row, value }, OutsideWorld { row: r, value: v }) => {
                row == r && value.to_bits() == v.to_bits()
            }
            (OffTerrain { x, y, .. }, OffTerrain { x: x2, y: y2, .. }) => {
                x.to_bits() == x2.to_bits() && y.to_bits() == y2.to_bits()
            }
            (Rules(a), Rules(b)) => a == b,
            (Observation(a), Observation(b)) => a == b,
            (
                BeyondFloat32 { index, name, value },
                BeyondFloat32 {
                    index: i,
                    name: n,
                    value: v,
                },
            ) => index == i && name == n && value.to_bits() == v.to_bits(),
            _ => false,
        }
    }
}

/// Serialised as its text.
impl Serialize for Divergence {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}
