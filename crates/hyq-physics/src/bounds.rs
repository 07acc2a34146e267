//! The one table of bounds every number of a robot (its profile and its URDF) is checked
//! against when a [`crate::RobotModel`] is built, and the rule for the names a profile gives.
//!
//! A number that is merely finite is not enough: a model is only usable if everything derived
//! from it stays finite, in f64 and in the f32 that rapier, MuJoCo's single-precision paths and
//! the Python spaces hold. Joint limits of ±1.7e308 are finite, but their span is not, so the
//! normalised action map, the random policy and the midpoint of the range all overflow; a mass
//! of 1e39 kg is finite in f64 and infinite in f32; a gait frequency of 1e308 Hz overflows the
//! phase on the first step. Each row here is one quantity, its unit, its range and why the range
//! is what it is; `docs/adding-a-robot.md` prints the same table (a test keeps them equal).
//!
//! The bounds are wide: they refuse only numbers no robot has, and keep every derived value
//! (spans, midpoints, joint targets, observation bounds, masses and inertias as f32, the gait's
//! phase) finite with room to spare.

/// The range of one quantity: `low ≤ v ≤ high` (`low < v` when `low_open`, `v < high` when
/// `high_open`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound {
    /// What is bounded, as `docs/adding-a-robot.md` names it.
    pub quantity: &'static str,
    /// The unit of the bounds.
    pub unit: &'static str,
    /// The smallest value allowed (excluded when `low_open`).
    pub low: f64,
    /// Whether `low` itself is refused.
    pub low_open: bool,
    /// The largest value allowed (excluded when `high_open`).
    pub high: f64,
    /// Whether `high` itself is refused.
    pub high_open: bool,
    /// Why the range is what it is (one sentence, for the documentation).
    pub why: &'static str,
}

impl Bound {
    /// `value` if it is finite and within the bound; otherwise why not, in words that can
    /// follow a field name (`"1e308 must be finite and in [-1000, 1000] rad"`).
    pub fn check(&self, value: f64) -> Result<f64, String> {
        let above_low = if self.low_open {
            value > self.low
        } else {
            value >= self.low
        };
        let below_high = if self.high_open {
            value < self.high
        } else {
            value <= self.high
        };
        if value.is_finite() && above_low && below_high {
            Ok(value)
        } else {
            Err(format!(
                "{} must be finite and in {}",
                short(value),
                self.range()
            ))
        }
    }

    /// The range as text, e.g. `(0, 1000000] N·m`.
    pub fn range(&self) -> String {
        let open = if self.low_open { '(' } else { '[' };
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        let close = if self.high_open { ')' } else { ']' };
        format!(
            "{open}{}, {}{close}{unit}",
            short(self.low),
            short(self.high)
        )
    }

    /// Checks a count (of links, joints, shapes) against the bound's upper end.
    pub fn check_count(&self, count: usize) -> Result<usize, String> {
        // Counts are far below 2^53, so the conversion is exact.
        if (count as f64) <= self.high {
            Ok(count)
        } else {
            Err(format!(
                "{count} is more than the {} allowed",
                short(self.high)
            ))
        }
    }
}

/// A number in short form for messages: `1.7e308` rather than 309 digits, `1e-46` rather than
/// 46 zeros, `1e6` rather than `1000000`; a figure from 0.001 to a million as it is (`0.75`).
pub fn short(value: f64) -> String {
    if value == 0.0 || !value.is_finite() || (1e-3..1e6).contains(&value.abs()) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// Joint position limits and standing angles (rad). About 160 turns: beyond any joint's travel
/// (a continuous joint given limits to make it finite included), and where f32 still resolves
/// 6e-5 rad; the span of two such limits, their midpoint and every target between stay finite.
pub const JOINT_ANGLE: Bound = Bound {
    quantity: "joint limits (`lower`, `upper`) and `standing`",
    unit: "rad",
    low: -1000.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "about 160 turns, past any joint's travel; spans, midpoints and targets stay finite and f32 resolves 6e-5 rad there",
};

/// A joint's range, `upper − lower` (rad).
pub const JOINT_SPAN: Bound = Bound {
    quantity: "a joint's range `upper - lower`",
    unit: "rad",
    low: 1e-3,
    low_open: false,
    high: 2000.0,
    high_open: false,
    why: "a milliradian at least (a narrower joint is a fixed one), so float32 action spaces keep low < high",
};

/// Joint effort limit (N·m).
pub const JOINT_EFFORT: Bound = Bound {
    quantity: "joint `effort`",
    unit: "N·m",
    low: 0.0,
    low_open: true,
    high: 1e6,
    high_open: false,
    why: "a thousand times a large robot arm's joint; torques stay faithful in f32",
};

/// Joint velocity limit (rad/s): also the bounds of the joint-speed observation rows.
pub const JOINT_VELOCITY: Bound = Bound {
    quantity: "joint `velocity`",
    unit: "rad/s",
    low: 1e-3,
    low_open: false,
    high: 1e4,
    high_open: false,
    why: "a milliradian per second at least (a slower joint is a fixed one) and about 95 000 rpm at most; it bounds the joint-speed observation rows, which stay nonzero and finite in float32",
};

/// Passive joint damping (N·m·s/rad).
pub const JOINT_DAMPING: Bound = Bound {
    quantity: "joint `<dynamics damping>`",
    unit: "N·m·s/rad",
    low: 0.0,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "as the effort limit: faithful in f32",
};

/// Coulomb joint friction (N·m).
pub const JOINT_FRICTION: Bound = Bound {
    quantity: "joint `<dynamics friction>`",
    unit: "N·m",
    low: 0.0,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "as the effort limit: faithful in f32",
};

/// A joint's armature (MJCF `armature`: rotor inertia reflected through the gearbox, added to
/// the joint's own inertia about its axis).
pub const JOINT_ARMATURE: Bound = Bound {
    quantity: "joint `armature`",
    unit: "kg·m²",
    low: 0.0,
    low_open: false,
    high: 1e4,
    high_open: false,
    why: "a thousand times a large robot's leg inertia about its joint, faithful in f32",
};

/// A component of a joint's `<axis>` (the axis is normalised; its length must be at least
/// [`AXIS_MIN_LENGTH`]).
pub const AXIS_COMPONENT: Bound = Bound {
    quantity: "joint `<axis xyz>` component",
    unit: "",
    low: -1e6,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "the axis is normalised: its length must neither overflow nor vanish (at least 1e-6)",
};

/// The shortest `<axis>` that is normalised (its length).
pub const AXIS_MIN_LENGTH: f64 = 1e-6;

/// PD gain kp, per joint or for all (N·m/rad).
pub const GAIN_KP: Bound = Bound {
    quantity: "`gains.kp`, `joints[].kp`",
    unit: "N·m/rad",
    low: 0.0,
    low_open: false,
    high: 1e9,
    high_open: false,
    why: "kp times the widest joint span stays far inside f64 before the effort limit clamps it",
};

/// PD gain kd, per joint or for all (N·m·s/rad).
pub const GAIN_KD: Bound = Bound {
    quantity: "`gains.kd`, `joints[].kd`",
    unit: "N·m·s/rad",
    low: 0.0,
    low_open: false,
    high: 1e9,
    high_open: false,
    why: "as kp",
};

/// A URDF link's `<mass>` (kg): 0 for a frame or sensor that carries none.
pub const LINK_MASS: Bound = Bound {
    quantity: "a URDF link's `<mass>`",
    unit: "kg",
    low: 0.0,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "1000 t; a massless frame (0) is fine when fixed to a body with mass",
};

/// The mass of a moving body: a link with the links fixed to it (kg).
pub const BODY_MASS: Bound = Bound {
    quantity: "a moving body's mass (a link and the links fixed to it)",
    unit: "kg",
    low: 1e-4,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "an f32 engine keeps 7 digits: a body under 0.1 g beside a robot's kilograms is lost in rounding (and 1e39 kg is infinite in f32)",
};

/// An entry of a URDF link's inertia tensor (kg·m²).
pub const INERTIA_ENTRY: Bound = Bound {
    quantity: "a URDF link's `<inertia>` entry",
    unit: "kg·m²",
    low: -1e6,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "as the mass: faithful in f32 after lumping",
};

/// A principal moment of a moving body's inertia tensor (kg·m²).
pub const BODY_MOMENT: Bound = Bound {
    quantity: "a moving body's principal moments of inertia",
    unit: "kg·m²",
    low: 1e-8,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "0.1 g at 1 cm at least: smaller moments vanish in an f32 engine's rounding",
};

/// A coordinate of an `<origin xyz>` (joint, inertial or collision) (m).
pub const ORIGIN_OFFSET: Bound = Bound {
    quantity: "an `<origin xyz>` coordinate (joint, inertial, collision)",
    unit: "m",
    low: -100.0,
    low_open: false,
    high: 100.0,
    high_open: false,
    why: "the world is ±100 m on each axis, where f32 stays faithful; no part of a robot is further from its parent",
};

/// An angle of an `<origin rpy>` (rad).
pub const ORIGIN_ANGLE: Bound = Bound {
    quantity: "an `<origin rpy>` angle",
    unit: "rad",
    low: -1000.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "as the joint angles",
};

/// A size of a collision shape: box size, radius, cylinder length (m).
pub const SHAPE_SIZE: Bound = Bound {
    quantity: "a collision shape's size (box `size`, `radius`, cylinder `length`)",
    unit: "m",
    low: 1e-4,
    low_open: false,
    high: 100.0,
    high_open: false,
    why: "0.1 mm to the world's 100 m: contact tolerances and the renderer's projection stay meaningful",
};

/// A capsule's length between its cap centres (m); 0 makes it a sphere.
pub const CAPSULE_LENGTH: Bound = Bound {
    quantity: "a capsule's `length`",
    unit: "m",
    low: 0.0,
    low_open: false,
    high: 100.0,
    high_open: false,
    why: "as the shape sizes; 0 is a sphere",
};

/// The trunk frame's height at spawn, and the standing height (m).
pub const SPAWN_HEIGHT: Bound = Bound {
    quantity: "`spawn.height`, `spawn.standing_height`",
    unit: "m",
    low: 0.0,
    low_open: true,
    high: 10.0,
    high_open: false,
    why: "a legged robot's trunk stands well under 10 m; inside the ±100 m world, where the default goal's distance stays small",
};

/// A declared observation bound of the trunk rows (`[observation]`).
pub const OBSERVATION_BOUND: Bound = Bound {
    quantity: "`[observation]` bounds",
    unit: "m/s², m",
    low: -1e6,
    low_open: false,
    high: 1e6,
    high_open: false,
    why: "they become float32 space bounds and divide by their span when normalised: finite both",
};

/// The trot's frequency (Hz).
pub const GAIT_FREQUENCY: Bound = Bound {
    quantity: "`gait.frequency_hz`",
    unit: "Hz",
    low: 0.0,
    low_open: true,
    high: 50.0,
    high_open: false,
    why: "at the default 100 Hz control rate a cycle needs at least two env steps; the phase stays finite",
};

/// The trot's hip swing amplitude (rad).
pub const GAIT_HIP_AMPLITUDE: Bound = Bound {
    quantity: "`gait.hip_amplitude`",
    unit: "rad",
    low: -1000.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "as the joint angles",
};

/// The trot's knee lift (rad).
pub const GAIT_KNEE_LIFT: Bound = Bound {
    quantity: "`gait.knee_lift`",
    unit: "rad",
    low: 0.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "as the joint angles",
};

/// The trot's ramp time (s).
pub const GAIT_RAMP: Bound = Bound {
    quantity: "`gait.ramp_s`",
    unit: "s",
    low: 0.0,
    low_open: false,
    high: 3600.0,
    high_open: false,
    why: "an hour; 0 starts at full amplitude",
};

/// A leg's phase, as a fraction of a cycle (`[0, 1)`: 1 is refused, being 0 again).
pub const GAIT_PHASE: Bound = Bound {
    quantity: "`gait.legs[].phase`",
    unit: "cycle",
    low: 0.0,
    low_open: false,
    high: 1.0,
    high_open: true,
    why: "a fraction of a cycle (1 is 0 again)",
};

/// Links in the URDF.
pub const LINK_COUNT: Bound = Bound {
    quantity: "URDF links",
    unit: "",
    low: 1.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "ten times a detailed humanoid's; building the physics of tens of thousands takes minutes and gigabytes",
};

/// Joints in the URDF (fixed ones included).
pub const JOINT_COUNT: Bound = Bound {
    quantity: "URDF joints (fixed ones included)",
    unit: "",
    low: 0.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "as the links",
};

/// Collision shapes in the URDF.
pub const SHAPE_COUNT: Bound = Bound {
    quantity: "URDF collision shapes",
    unit: "",
    low: 0.0,
    low_open: false,
    high: 1000.0,
    high_open: false,
    why: "as the links",
};

/// Every bound, in the order `docs/adding-a-robot.md` lists them.
pub const TABLE: [&Bound; 28] = [
    &JOINT_ANGLE,
    &JOINT_SPAN,
    &JOINT_EFFORT,
    &JOINT_VELOCITY,
    &JOINT_DAMPING,
    &JOINT_FRICTION,
    &JOINT_ARMATURE,
    &AXIS_COMPONENT,
    &GAIN_KP,
    &GAIN_KD,
    &LINK_MASS,
    &BODY_MASS,
    &INERTIA_ENTRY,
    &BODY_MOMENT,
    &ORIGIN_OFFSET,
    &ORIGIN_ANGLE,
    &SHAPE_SIZE,
    &CAPSULE_LENGTH,
    &SPAWN_HEIGHT,
    &OBSERVATION_BOUND,
    &GAIT_FREQUENCY,
    &GAIT_HIP_AMPLITUDE,
    &GAIT_KNEE_LIFT,
    &GAIT_RAMP,
    &GAIT_PHASE,
    &LINK_COUNT,
    &JOINT_COUNT,
    &SHAPE_COUNT,
];

/// The longest name a profile gives (the robot's, a joint's, a foot's), in characters.
pub const NAME_MAX_CHARS: usize = 64;

/// Checks a name the profile gives (the robot's, a joint's short name, a foot's): 1 to
/// [`NAME_MAX_CHARS`] ASCII letters, digits, `_`, `-` and `.`. Names are printed in headers,
/// tables, observation row names and error messages, so nothing in them may move the cursor,
/// start a line or be empty.
pub fn check_name(name: &str) -> Result<&str, String> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.');
    if name.is_empty() {
        return Err("is empty; give a name of ASCII letters, digits, `_`, `-` or `.`".into());
    }
    if name.chars().count() > NAME_MAX_CHARS {
        return Err(format!(
            "is {} characters long; at most {NAME_MAX_CHARS}",
            name.chars().count()
        ));
    }
    if let Some(c) = name.chars().find(|c| !allowed(*c)) {
        return Err(format!(
            "{:?} holds {c:?}; a name is ASCII letters, digits, `_`, `-` and `.`",
            name.chars().take(NAME_MAX_CHARS).collect::<String>()
        ));
    }
    Ok(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bound_refuses_non_finite_and_out_of_range_values_in_short_form() {
        assert_eq!(JOINT_ANGLE.check(0.75), Ok(0.75));
        assert_eq!(JOINT_ANGLE.check(-1000.0), Ok(-1000.0));
        let e = JOINT_ANGLE.check(1.7e308).expect_err("beyond");
        assert_eq!(e, "1.7e308 must be finite and in [-1000, 1000] rad");
        assert!(JOINT_ANGLE.check(f64::NAN).is_err());
        assert!(
            JOINT_EFFORT
                .check(0.0)
                .expect_err("open")
                .contains("(0, 1e6] N·m")
        );
        assert!(
            GAIT_PHASE
                .check(1.0)
                .expect_err("open")
                .contains("[0, 1) cycle")
        );
        assert_eq!(short(0.0001), "1e-4");
        assert_eq!(short(-1.7e308), "-1.7e308");
        assert_eq!(LINK_COUNT.check_count(1000), Ok(1000));
        assert!(LINK_COUNT.check_count(1001).is_err());
    }

    #[test]
    fn every_bound_keeps_its_spans_and_products_finite() {
        for b in TABLE {
            assert!(
                b.low.is_finite() && b.high.is_finite() && b.low < b.high,
                "{b:?}"
            );
            assert!(
                (b.high - b.low).is_finite() && (b.high as f32).is_finite(),
                "{b:?}"
            );
        }
    }

    #[test]
    fn names_are_short_printable_ascii() {
        assert!(check_name("anymal_c-2.1").is_ok());
        for bad in ["", "x\u{1b}[31mRED", "a\nhyq: fake", "a b", "é"] {
            assert!(check_name(bad).is_err(), "{bad:?}");
        }
        assert!(check_name(&"a".repeat(65)).is_err());
    }
}
