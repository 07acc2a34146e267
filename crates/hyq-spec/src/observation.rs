//! Spec §3 (Observations): the observation is a flat vector whose rows are, in
//! order, for a robot with N joints and F observed feet,
//!
//! | rows | field | unit | HyQ rows |
//! |---|---|---|---|
//! | 0 … N−1 | joint angles θ^i, `<joint>_angle` | rad | 0–11 |
//! | N … 2N−1 | joint speeds θ̇^i, `<joint>_speed` | rad/s | 12–23 |
//! | 2N … 2N+F−1 | foot contact flags, `<foot>_contact_flag` | 0 or 1 | 24–27 |
//! | 2N+F | trunk contact flag, `trunk_contact_flag` | 0 or 1 | 28 |
//! | +1 … +4 | trunk quaternion w, x, y, z (world), `trunk_rotation_*` | — | 29–32 |
//! | +5 … +7 | trunk linear acceleration (world), `trunk_accel_*` | m/s² | 33–35 |
//! | +8 … +10 | trunk position C^t (world), `trunk_position_*` | m | 36–38 |
//!
//! 2N + F + 11 rows in all: 39 for HyQ. [`SPEC_TABLE`] is the spec's table verbatim (the one
//! copy of it); [`ObservationLayout`] builds the same rows from any [`RobotDescription`] and
//! writes an [`Observation`] into a buffer.
//!
//! - Contact flags are 1 if that link touched the ground in **any** physics sub-step of the env
//!   step, else 0 (spec §3); row 28 is the §6.3 fall fact.
//! - The quaternion is as the physics reports it; w ≥ 0 is not required.
//! - The acceleration is the coordinate acceleration of the trunk centre, gravity not included:
//!   a^t = (v^t − v^{t−1}) / Δt_env, 0 after reset ([`trunk_acceleration`]).
//! - Values are **not** clipped by default: rows 33–38 are only estimated ranges (`*` in the
//!   spec). [`Clipping::ToDeclaredBounds`] clips each value to its row's [min, max].
//!
//! Beyond the spec, an environment may append groups of rows of its own after these
//! ([`ObservationLayout::with_group`]: a height scan, the goal in the trunk's frame, ...). The
//! layout then names and bounds them too (their bounds estimated), [`ObservationLayout::write`]
//! fills the §3 rows and the environment the rest; without groups the layout is the spec's.

use crate::robot::RobotDescription;
use nalgebra::{Point3, UnitQuaternion, Vector3};
use std::borrow::Cow;
use std::ops::Range;
use thiserror::Error;

pub use crate::table::{ObservationRow, SPEC_TABLE};

/// Whether [`ObservationLayout::write`] clips values to their rows' declared bounds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Clipping {
    /// Write the values as measured (the default, spec §3).
    #[default]
    Off,
    /// Clip each value to its row's [min, max].
    ToDeclaredBounds,
}

/// One step's observation as named fields, borrowed from the environment's buffers.
#[derive(Clone, Copy, Debug)]
pub struct Observation<'a> {
    /// Joint angles θ^i, rad, in the description's joint order.
    pub joint_angles: &'a [f64],
    /// Joint speeds θ̇^i, rad/s, in the description's joint order.
    pub joint_speeds: &'a [f64],
    /// Whether each observed foot touched the ground in any sub-step of the step, in the
    /// description's foot order.
    pub foot_contacts: &'a [bool],
    /// Whether the trunk touched the ground in any sub-step of the step (the §6.3 fall fact).
    pub trunk_contact: bool,
    /// The trunk's orientation in the world frame (written as w, x, y, z).
    pub trunk_rotation: UnitQuaternion<f64>,
    /// The trunk centre's coordinate acceleration in the world frame, m/s², gravity not
    /// included (see [`trunk_acceleration`]).
    pub trunk_acceleration: Vector3<f64>,
    /// The trunk centre's position C^t in the world frame, m.
    pub trunk_position: Point3<f64>,
}

/// An observation that does not fit its layout, or a value that cannot be observed.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ObservationError {
    /// A field or the output buffer has the wrong length for the layout.
    #[error("observation {field} has {got} values but the layout expects {expected}")]
    Length {
        /// `"joint_angles"`, `"joint_speeds"`, `"foot_contacts"` or `"output buffer"`.
        field: &'static str,
        /// The layout's length for it.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A value is NaN or infinite (the physics diverged, or an input was bad).
    #[error("observation row {index} ({name}) is {value}: observations must be finite")]
    NonFinite {
        /// The row's index.
        index: usize,
        /// The row's name.
        name: String,
        /// The value.
        value: f64,
    },
    /// The env step's duration given to [`trunk_acceleration`] is not finite and > 0.
    #[error("env time step {value} s: it must be finite and > 0")]
    TimeStep {
        /// The rejected duration, seconds.
        value: f64,
    },
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// The element types an observation can be written as: `f64`, and `f32` for learning libraries
/// (Gymnasium's `Box` is usually float32).
pub trait ObservationScalar: Copy + sealed::Sealed {
    /// The value rounded to this type (to nearest for `f32`).
    fn from_f64(value: f64) -> Self;
}

impl ObservationScalar for f32 {
    fn from_f64(value: f64) -> f32 {
        // Rounding to nearest is the conversion wanted: it is monotone, so a value clipped to
        // [min, max] in f64 stays within the f32-rounded bounds.
        value as f32
    }
}

impl ObservationScalar for f64 {
    fn from_f64(value: f64) -> f64 {
        value
    }
}

/// The rows of a robot's observation, built from its description, with named index ranges.
#[derive(Clone, Debug, PartialEq)]
pub struct ObservationLayout {
    rows: Vec<ObservationRow>,
    joints: usize,
    feet: usize,
    /// The number of §3 rows (2N + F + 11); the groups follow them.
    spec_len: usize,
    groups: Vec<RowGroup>,
}

/// A group of rows an environment appends after the §3 rows (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct RowGroup {
    /// The group's name, e.g. `"height_scan"`.
    pub name: Cow<'static, str>,
    /// The unit of its rows, e.g. `"m"`.
    pub unit: &'static str,
    /// Its rows' indices.
    pub rows: Range<usize>,
}

/// The trunk rows after the foot contacts: contact, quaternion (4), acceleration (3), position (3).
const TRUNK_ROWS: usize = 11;

impl ObservationLayout {
    /// The rows for `robot`, in the §3 order (see the module docs).
    pub fn new(robot: &RobotDescription) -> Self {
        let mut rows =
            Vec::with_capacity(2 * robot.joints().len() + robot.feet().len() + TRUNK_ROWS);
        let mut push = |name: String, min: f64, max: f64, estimated: bool| {
            rows.push(ObservationRow {
                index: rows.len(),
                name: Cow::Owned(name),
                min,
                max,
                estimated,
            });
        };
        for joint in robot.joints() {
            push(
                format!("{}_angle", joint.name),
                joint.range.lower(),
                joint.range.upper(),
                false,
            );
        }
        for joint in robot.joints() {
            push(
                format!("{}_speed", joint.name),
                -joint.velocity_limit,
                joint.velocity_limit,
                false,
            );
        }
        let trunk = robot.trunk();
        for link in robot.feet().iter().chain(std::iter::once(&trunk.name)) {
            push(format!("{link}_contact_flag"), 0.0, 1.0, false);
        }
        for axis in ["w", "x", "y", "z"] {
            push(format!("{}_rotation_{axis}", trunk.name), -1.0, 1.0, false);
        }
        for (b, axis) in trunk.acceleration.iter().zip(["x", "y", "z"]) {
            push(format!("{}_accel_{axis}", trunk.name), b.min, b.max, true);
        }
        for (b, axis) in trunk.position.iter().zip(["x", "y", "z"]) {
            push(
                format!("{}_position_{axis}", trunk.name),
                b.min,
                b.max,
                true,
            );
        }
        ObservationLayout {
            spec_len: rows.len(),
            rows,
            joints: robot.joints().len(),
            feet: robot.feet().len(),
            groups: Vec::new(),
        }
    }

    /// This layout with a group `name` of rows appended, each `(name, min, max)` in `unit`,
    /// their bounds estimated (not an invariant of every value).
    pub fn with_group(
        mut self,
        name: impl Into<Cow<'static, str>>,
        unit: &'static str,
        rows: impl IntoIterator<Item = (String, f64, f64)>,
    ) -> Self {
        let start = self.rows.len();
        for (row_name, min, max) in rows {
            self.rows.push(ObservationRow {
                index: self.rows.len(),
                name: Cow::Owned(row_name),
                min,
                max,
                estimated: true,
            });
        }
        self.groups.push(RowGroup {
            name: name.into(),
            unit,
            rows: start..self.rows.len(),
        });
        self
    }

    /// The number of rows: 2N + F + 11, plus the groups' rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// The §3 rows (2N + F + 11 of them, first).
    pub fn spec_rows(&self) -> Range<usize> {
        0..self.spec_len
    }

    /// The groups appended after the §3 rows, in order.
    pub fn groups(&self) -> &[RowGroup] {
        &self.groups
    }

    /// Always false: a layout has at least the eleven trunk rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Every row, in order.
    pub fn rows(&self) -> &[ObservationRow] {
        &self.rows
    }

    /// The joint-angle rows (`<joint>_angle`).
    pub fn joint_angles(&self) -> Range<usize> {
        0..self.joints
    }

    /// The joint-speed rows (`<joint>_speed`).
    pub fn joint_speeds(&self) -> Range<usize> {
        self.joints..2 * self.joints
    }

    /// The foot contact-flag rows (`<foot>_contact_flag`).
    pub fn foot_contacts(&self) -> Range<usize> {
        2 * self.joints..2 * self.joints + self.feet
    }

    /// The trunk contact-flag row (`trunk_contact_flag`).
    pub fn trunk_contact(&self) -> usize {
        2 * self.joints + self.feet
    }

    /// The trunk quaternion rows, w, x, y, z (`trunk_rotation_*`).
    pub fn trunk_rotation(&self) -> Range<usize> {
        let start = self.trunk_contact() + 1;
        start..start + 4
    }

    /// The trunk acceleration rows, x, y, z (`trunk_accel_*`).
    pub fn trunk_acceleration(&self) -> Range<usize> {
        let start = self.trunk_rotation().end;
        start..start + 3
    }

    /// The trunk position rows, x, y, z (`trunk_position_*`).
    pub fn trunk_position(&self) -> Range<usize> {
        let start = self.trunk_acceleration().end;
        start..start + 3
    }

    /// Writes `observation` into the §3 rows of `out` (exactly [`Self::len`] long: the
    /// groups' rows after them are the caller's) in row order, as `f32` or `f64`, clipped or
    /// not. Allocates nothing unless it fails.
    ///
    /// Errors: a field or `out` of the wrong length, or a non-finite value (named by its row).
    pub fn write<T: ObservationScalar>(
        &self,
        observation: &Observation<'_>,
        clipping: Clipping,
        out: &mut [T],
    ) -> Result<(), ObservationError> {
        let lengths = [
            ("joint_angles", self.joints, observation.joint_angles.len()),
            ("joint_speeds", self.joints, observation.joint_speeds.len()),
            ("foot_contacts", self.feet, observation.foot_contacts.len()),
            ("output buffer", self.len(), out.len()),
        ];
        for (field, expected, got) in lengths {
            if expected != got {
                return Err(ObservationError::Length {
                    field,
                    expected,
                    got,
                });
            }
        }
        let flag = |touched: bool| if touched { 1.0 } else { 0.0 };
        let q = &observation.trunk_rotation;
        let values = observation
            .joint_angles
            .iter()
            .chain(observation.joint_speeds)
            .copied()
            .chain(observation.foot_contacts.iter().map(|c| flag(*c)))
            .chain([flag(observation.trunk_contact), q.w, q.i, q.j, q.k])
            .chain(observation.trunk_acceleration.iter().copied())
            .chain(observation.trunk_position.iter().copied());
        for ((slot, value), row) in out.iter_mut().zip(values).zip(&self.rows) {
            if !value.is_finite() {
                return Err(ObservationError::NonFinite {
                    index: row.index,
                    name: row.name.to_string(),
                    value,
                });
            }
            let value = match clipping {
                Clipping::Off => value,
                Clipping::ToDeclaredBounds => value.clamp(row.min, row.max),
            };
            *slot = T::from_f64(value);
        }
        Ok(())
    }
}

/// Spec §3, rows 33–35: the trunk centre's coordinate acceleration over the env step,
/// a^t = (v^t − v^{t−1}) / Δt_env, with Δt_env = sub-steps × physics dt in seconds. Gravity is
/// not included (0 at rest); after reset the environment reports 0.
pub fn trunk_acceleration(
    previous_velocity: &Vector3<f64>,
    velocity: &Vector3<f64>,
    env_dt: f64,
) -> Result<Vector3<f64>, ObservationError> {
    if !(env_dt.is_finite() && env_dt > 0.0) {
        return Err(ObservationError::TimeStep { value: env_dt });
    }
    Ok((velocity - previous_velocity) / env_dt)
}
