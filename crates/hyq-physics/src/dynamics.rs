//! Per-episode variations of the physics (domain randomisation), as plain data: what a backend
//! takes ([`Dynamics`]: ground friction, every body's mass properties, joint damping, the
//! ground contact's stiffness and damping factors and restitution ([`ContactDraw`])), the
//! draw an environment makes of it from a model ([`DynamicsDraw`]), and the shared actuator's
//! variations ([`ActuatorScales`], [`TargetDelay`]).
//!
//! No random numbers are drawn here: the environment owns the seeded streams and turns its
//! draws into these values, so every backend receives the same numbers. The rules that keep
//! every drawn world physical live here, once:
//! - a body's mass scales by `s > 0` with its inertia tensor (`m' = s·m`, `I' = s·I`), so its
//!   radii of gyration stay those of its shape;
//! - the trunk's added mass `Δm` sits at its centre of mass, and its tensor follows the mass
//!   (`I' = I·(m + Δm)/m`), as a denser trunk of the same shape would; the whole mass must
//!   stay positive (`m + Δm > 0`);
//! - the trunk's centre-of-mass offset moves the centre of mass in the trunk's link frame and
//!   keeps the tensor about it.
//!
//! So a draw whose scales are positive and whose trunk mass stays positive gives positive
//! masses and positive definite tensors that satisfy the triangle inequality, for every body.
//! Positive is not enough for an engine: a body of 1e-30 kg or 1e308 kg passes it, and DART
//! aborts the process on either (an assertion no caller can catch). So every drawn body is held
//! to the same table the robot's own bodies are ([`crate::bounds`]: [`bounds::BODY_MASS`],
//! [`bounds::BODY_MOMENT`], [`bounds::JOINT_DAMPING`]), by [`Dynamics::validate`] before a
//! backend sees the values, and whole ranges of draws are checked once, when an environment is
//! built, by [`check_draw_ranges`]: a drawn mass, moment or damping is monotone in each factor
//! and in the added mass, so a range whose corners are inside the table has every draw inside.

use nalgebra::Vector3;
use serde::Deserialize;

use crate::bounds;
use crate::error::PhysicsError;
use crate::inertia::{MassProperties, check_inertia};
use crate::model::RobotModel;
use crate::state::PhysicsParams;

/// The physics a backend simulates beyond the model's geometry, for one episode: the ground's
/// friction, each body's mass properties and each joint's damping. [`Dynamics::nominal`] is
/// the model's own (what a freshly built world holds).
#[derive(Debug, Clone, PartialEq)]
pub struct Dynamics {
    /// Coulomb friction coefficient between every robot shape and the ground, whatever shape
    /// the ground has (finite, ≥ 0).
    pub ground_friction: f64,
    /// The mass properties of every body (index as in [`RobotModel::links`]) in its body
    /// (link) frame: mass (kg, > 0), centre of mass (m), inertia tensor about the centre of
    /// mass (kg·m², positive definite).
    pub bodies: Vec<MassProperties>,
    /// Viscous damping of every joint (N·m·s/rad, finite, ≥ 0), profile order.
    pub joint_damping: Vec<f64>,
    /// The contact: factors of the engine's own ground-contact stiffness and damping, and the
    /// restitution coefficient (see [`ContactDraw`]; each engine maps them onto its model).
    pub contact: ContactDraw,
}

/// The ground contact's variations: factors of each engine's nominal contact stiffness and
/// damping (> 0; 1 is the engine's own), and a restitution coefficient (in [0, 1]; 0, every
/// engine's nominal, is inelastic). Their field names are the configuration keys that draw
/// them. How each engine maps them is its `apply_dynamics`'s to say (docs/randomization.md):
/// an engine whose contact model has no such quantity refuses a value other than the nominal
/// one with an error naming it. A record that has none of them reads as nominal.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
pub struct ContactDraw {
    /// Factor of the contact's stiffness (> 0).
    #[serde(default = "one")]
    pub contact_stiffness_scale: f64,
    /// Factor of the contact's damping (> 0).
    #[serde(default = "one")]
    pub contact_damping_scale: f64,
    /// The contact's restitution coefficient (in [0, 1]).
    #[serde(default)]
    pub restitution: f64,
}

/// A factor's nominal value, for a record written before the contact was drawn.
fn one() -> f64 {
    1.0
}

impl ContactDraw {
    /// Every engine's own contact: factors of 1, no restitution.
    pub const NOMINAL: Self = Self {
        contact_stiffness_scale: 1.0,
        contact_damping_scale: 1.0,
        restitution: 0.0,
    };

    /// Whether this is [`ContactDraw::NOMINAL`].
    pub fn is_nominal(&self) -> bool {
        *self == Self::NOMINAL
    }

    /// Checks the factors finite and positive and the restitution in [0, 1] (the
    /// configuration holds the factors to a narrower range). The error names the quantity and
    /// the value.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        let invalid = |what: &str, reason: String| PhysicsError::InvalidState {
            what: what.into(),
            reason,
        };
        for (what, v) in [
            ("contact stiffness scale", self.contact_stiffness_scale),
            ("contact damping scale", self.contact_damping_scale),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(what, format!("{v} must be finite and positive")));
            }
        }
        let e = self.restitution;
        if !(0.0..=1.0).contains(&e) {
            return Err(invalid("restitution", format!("{e} must be in [0, 1]")));
        }
        Ok(())
    }
}

impl Dynamics {
    /// The model's own mass properties and damping, and the ground friction of `params`.
    pub fn nominal(model: &RobotModel, params: &PhysicsParams) -> Self {
        Self {
            ground_friction: params.ground_friction,
            bodies: model
                .links()
                .iter()
                .map(|l| MassProperties {
                    mass: l.mass,
                    com: l.com,
                    inertia: l.inertia,
                })
                .collect(),
            joint_damping: model.joints().iter().map(|j| j.damping).collect(),
            contact: ContactDraw::NOMINAL,
        }
    }

    /// The robot's total mass (kg).
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.mass).sum()
    }

    /// Checks that the values fit `model` (one body per link, one damping per joint) and are
    /// physical: friction finite and ≥ 0, masses finite and > 0, centres of mass finite,
    /// tensors valid and positive definite ([`check_inertia`]), damping finite and ≥ 0. The
    /// error names the body or joint and the value.
    pub fn validate(&self, model: &RobotModel) -> Result<(), PhysicsError> {
        let invalid = |what: String, reason: String| PhysicsError::InvalidState { what, reason };
        if !(self.ground_friction.is_finite() && self.ground_friction >= 0.0) {
            return Err(invalid(
                "ground friction".into(),
                format!("{} must be finite and non-negative", self.ground_friction),
            ));
        }
        if self.bodies.len() != model.num_links() {
            return Err(invalid(
                "body mass properties".into(),
                format!(
                    "expected one per body ({}), got {}",
                    model.num_links(),
                    self.bodies.len()
                ),
            ));
        }
        for (b, link) in self.bodies.iter().zip(model.links()) {
            let what = || format!("mass properties of body {}", link.name);
            check_body(b).map_err(|reason| invalid(what(), reason))?;
        }
        if self.joint_damping.len() != model.num_joints() {
            return Err(PhysicsError::WrongLength {
                what: "joint damping",
                expected: model.num_joints(),
                got: self.joint_damping.len(),
            });
        }
        for (d, joint) in self.joint_damping.iter().zip(model.joints()) {
            bounds::JOINT_DAMPING
                .check(*d)
                .map_err(|reason| invalid(format!("damping of joint {}", joint.name), reason))?;
        }
        self.contact.validate()
    }
}

/// Checks one moving body's drawn mass properties against the robot bounds table: the mass in
/// [`bounds::BODY_MASS`], a finite centre of mass, a valid positive definite tensor whose
/// principal moments are in [`bounds::BODY_MOMENT`]. The reason names the quantity, the value
/// and the range.
fn check_body(b: &MassProperties) -> Result<(), String> {
    bounds::BODY_MASS
        .check(b.mass)
        .map_err(|reason| format!("mass {reason}"))?;
    if !b.com.iter().all(|v| v.is_finite()) {
        return Err(format!(
            "centre of mass {:?} m must be finite",
            b.com.as_slice()
        ));
    }
    check_inertia(&b.inertia, true)?;
    let moments: [f64; 3] = b.inertia.symmetric_eigenvalues().into();
    for m in moments {
        bounds::BODY_MOMENT
            .check(m)
            .map_err(|reason| format!("principal moment of inertia {reason}"))?;
    }
    Ok(())
}

/// The ranges an environment draws its physical variations from, the nominal range (`[1, 1]`
/// factors, `[0, 0]` kg) for an option that is off. See [`check_draw_ranges`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawRanges {
    /// The factor of every body's mass and inertia.
    pub link_mass_scale: [f64; 2],
    /// The mass added to the trunk (kg).
    pub trunk_added_mass_kg: [f64; 2],
    /// The factor of every joint's damping.
    pub joint_damping_scale: [f64; 2],
}

impl DrawRanges {
    /// No variation.
    pub const NOMINAL: Self = Self {
        link_mass_scale: [1.0, 1.0],
        trunk_added_mass_kg: [0.0, 0.0],
        joint_damping_scale: [1.0, 1.0],
    };
}

/// Which range of [`DrawRanges`] a draw outside the bounds table comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawnQuantity {
    /// [`DrawRanges::link_mass_scale`].
    LinkMassScale,
    /// [`DrawRanges::trunk_added_mass_kg`].
    TrunkAddedMass,
    /// [`DrawRanges::joint_damping_scale`].
    JointDampingScale,
}

/// A range of [`DrawRanges`] that reaches outside what every engine holds.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawRangeFault {
    /// The range to blame.
    pub quantity: DrawnQuantity,
    /// What its extreme draw gives, and the table's range (one line, short numbers).
    pub reason: String,
}

/// Checks that every draw from `ranges` gives `model` dynamics inside the robot bounds table
/// (what rapier, DART and MuJoCo all hold; see the module docs), by checking the ranges'
/// corners: each drawn mass, principal moment and damping is monotone in its factor and in the
/// added mass. The link scales are checked first with no added mass, so that a fault is blamed
/// on the range that causes it. The ranges themselves must be finite and ordered with positive
/// factors (the configuration's checks).
pub fn check_draw_ranges(model: &RobotModel, ranges: &DrawRanges) -> Result<(), DrawRangeFault> {
    let corner = |scale: f64, added: f64, damping: f64| DynamicsDraw {
        ground_friction: 0.0,
        trunk_added_mass_kg: added,
        trunk_com_offset_m: [0.0; 3],
        link_mass_scale: vec![scale; model.num_links()],
        joint_damping_scale: vec![damping; model.num_joints()],
        contact: ContactDraw::NOMINAL,
    };
    let fault = |quantity, e: PhysicsError| DrawRangeFault {
        quantity,
        reason: match e {
            PhysicsError::InvalidState { what, reason } => format!("{what}: {reason}"),
            other => other.to_string(),
        },
    };
    for s in ranges.link_mass_scale {
        corner(s, 0.0, 1.0)
            .dynamics(model)
            .map_err(|e| fault(DrawnQuantity::LinkMassScale, e))?;
    }
    for s in ranges.link_mass_scale {
        for a in ranges.trunk_added_mass_kg {
            corner(s, a, 1.0)
                .dynamics(model)
                .map_err(|e| fault(DrawnQuantity::TrunkAddedMass, e))?;
        }
    }
    for d in ranges.joint_damping_scale {
        corner(1.0, 0.0, d)
            .dynamics(model)
            .map_err(|e| fault(DrawnQuantity::JointDampingScale, e))?;
    }
    Ok(())
}

/// One episode's drawn physical variations, as factors and offsets of the model's values;
/// [`DynamicsDraw::dynamics`] turns them into the [`Dynamics`] a backend takes (see the module
/// documentation for the rules). [`DynamicsDraw::nominal`] changes nothing. Its field names
/// are the configuration keys that draw them (and the names an environment's records use).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct DynamicsDraw {
    /// The ground friction coefficient itself (not a factor).
    pub ground_friction: f64,
    /// Mass added to the trunk at its centre of mass (kg; negative removes mass).
    pub trunk_added_mass_kg: f64,
    /// Offset of the trunk's centre of mass in its link frame (m).
    pub trunk_com_offset_m: [f64; 3],
    /// Factor of every body's mass and inertia tensor (index as in [`RobotModel::links`]).
    pub link_mass_scale: Vec<f64>,
    /// Factor of every joint's viscous damping (profile order).
    pub joint_damping_scale: Vec<f64>,
    /// The ground contact's factors and restitution.
    #[serde(flatten)]
    pub contact: ContactDraw,
}

impl DynamicsDraw {
    /// No variation: `dynamics` gives the model's own values and `params`' friction.
    pub fn nominal(model: &RobotModel, params: &PhysicsParams) -> Self {
        Self {
            ground_friction: params.ground_friction,
            trunk_added_mass_kg: 0.0,
            trunk_com_offset_m: [0.0; 3],
            link_mass_scale: vec![1.0; model.num_links()],
            joint_damping_scale: vec![1.0; model.num_joints()],
            contact: ContactDraw::NOMINAL,
        }
    }

    /// The dynamics of this draw for `model`, validated ([`Dynamics::validate`]): an error
    /// names what a draw outside the allowed ranges made unphysical.
    ///
    /// A factor of exactly 1, no added mass and no offset leave a value bit for bit the
    /// model's, so a nominal draw gives [`Dynamics::nominal`] exactly.
    pub fn dynamics(&self, model: &RobotModel) -> Result<Dynamics, PhysicsError> {
        if self.link_mass_scale.len() != model.num_links() {
            return Err(PhysicsError::InvalidState {
                what: "link mass scales".into(),
                reason: format!(
                    "expected one per body ({}), got {}",
                    model.num_links(),
                    self.link_mass_scale.len()
                ),
            });
        }
        if self.joint_damping_scale.len() != model.num_joints() {
            return Err(PhysicsError::WrongLength {
                what: "joint damping scales",
                expected: model.num_joints(),
                got: self.joint_damping_scale.len(),
            });
        }
        let mut bodies: Vec<MassProperties> = model
            .links()
            .iter()
            .zip(&self.link_mass_scale)
            .map(|(l, &s)| MassProperties {
                mass: l.mass * s,
                com: l.com,
                inertia: l.inertia * s,
            })
            .collect();
        let trunk = &mut bodies[0];
        if self.trunk_added_mass_kg != 0.0 {
            let mass = trunk.mass + self.trunk_added_mass_kg;
            trunk.inertia *= mass / trunk.mass;
            trunk.mass = mass;
        }
        trunk.com += Vector3::from(self.trunk_com_offset_m);
        let dynamics = Dynamics {
            ground_friction: self.ground_friction,
            bodies,
            joint_damping: model
                .joints()
                .iter()
                .zip(&self.joint_damping_scale)
                .map(|(j, &s)| j.damping * s)
                .collect(),
            contact: self.contact,
        };
        dynamics.validate(model)?;
        Ok(dynamics)
    }
}

/// Factors of the shared actuator's per-joint values for one episode (profile order): the PD
/// gains, the effort limit and the joint friction (see [`crate::Actuator::scale_from`]). Each
/// reads under the configuration key that draws it (and the name an environment's records use).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct ActuatorScales {
    /// Factor of each joint's proportional gain (> 0).
    #[serde(rename = "kp_scale")]
    pub kp: Vec<f64>,
    /// Factor of each joint's derivative gain (> 0).
    #[serde(rename = "kd_scale")]
    pub kd: Vec<f64>,
    /// Factor of each joint's effort limit (> 0).
    #[serde(rename = "effort_scale")]
    pub effort: Vec<f64>,
    /// Factor of each joint's Coulomb friction (≥ 0).
    #[serde(rename = "joint_friction_scale")]
    pub friction: Vec<f64>,
}

impl ActuatorScales {
    /// Factors of 1 for `num_joints` joints: the actuator unchanged.
    pub fn nominal(num_joints: usize) -> Self {
        Self {
            kp: vec![1.0; num_joints],
            kd: vec![1.0; num_joints],
            effort: vec![1.0; num_joints],
            friction: vec![1.0; num_joints],
        }
    }

    /// Checks one finite factor per joint for each field, positive for the gains and the
    /// effort, non-negative for the friction. The error names the field, the joint and the
    /// value.
    pub fn validate(&self, num_joints: usize) -> Result<(), PhysicsError> {
        for (what, scales, positive) in [
            ("kp scales", &self.kp, true),
            ("kd scales", &self.kd, true),
            ("effort scales", &self.effort, true),
            ("joint friction scales", &self.friction, false),
        ] {
            if scales.len() != num_joints {
                return Err(PhysicsError::WrongLength {
                    what,
                    expected: num_joints,
                    got: scales.len(),
                });
            }
            let bad = |s: f64| !s.is_finite() || s < 0.0 || (positive && s == 0.0);
            if let Some((j, s)) = scales.iter().enumerate().find(|(_, s)| bad(**s)) {
                return Err(PhysicsError::InvalidState {
                    what: format!("{what}[{j}]"),
                    reason: format!(
                        "{s} must be finite and {}",
                        if positive { "positive" } else { "non-negative" }
                    ),
                });
            }
        }
        Ok(())
    }
}

/// The actuator's delay: the PD law of sub-step `s` (0-based) of an env step sees the joint
/// targets of `k` sub-steps earlier. With `k` at most the env step's sub-steps, that is the
/// previous env step's targets for `s < k` and the current ones after; at the first step of
/// an episode, the "previous" targets are those the reset set (the initial joint angles).
/// `k = 0` is no delay: the current targets throughout.
///
/// Holds one env step of targets, so it allocates only when made.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetDelay {
    substeps: u32,
    previous: Vec<f64>,
}

impl TargetDelay {
    /// No delay, for a robot with `num_joints` joints.
    pub fn new(num_joints: usize) -> Self {
        Self {
            substeps: 0,
            previous: vec![0.0; num_joints],
        }
    }

    /// Sets the delay to `substeps` physics sub-steps; an error if it exceeds one env step of
    /// `substeps_per_env_step` sub-steps (older targets are not kept).
    pub fn set_substeps(
        &mut self,
        substeps: u32,
        substeps_per_env_step: u32,
    ) -> Result<(), PhysicsError> {
        if substeps > substeps_per_env_step {
            return Err(PhysicsError::InvalidState {
                what: "actuator delay".into(),
                reason: format!(
                    "{substeps} sub-steps is longer than an env step ({substeps_per_env_step} \
                     sub-steps)"
                ),
            });
        }
        self.substeps = substeps;
        Ok(())
    }

    /// The delay (physics sub-steps).
    pub fn substeps(&self) -> u32 {
        self.substeps
    }

    /// Starts an episode whose first targets before any action are `targets`.
    ///
    /// # Panics
    /// If `targets` is not one value per joint.
    pub fn reset(&mut self, targets: &[f64]) {
        self.previous.copy_from_slice(targets);
    }

    /// The targets the PD law sees at sub-step `substep` (0-based) of an env step whose own
    /// targets are `current`.
    pub fn seen<'a>(&'a self, substep: u32, current: &'a [f64]) -> &'a [f64] {
        if substep < self.substeps {
            &self.previous
        } else {
            current
        }
    }

    /// Ends an env step whose targets were `current`: they are the next step's previous ones.
    ///
    /// # Panics
    /// If `current` is not one value per joint.
    pub fn end_step(&mut self, current: &[f64]) {
        self.previous.copy_from_slice(current);
    }
}

#[cfg(test)]
mod tests {
    //! The draw's rules (scaled tensors, added mass at the centre of mass, offsets), the
    //! checks that refuse unphysical values, and the delay's bookkeeping.
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::bundled;

    #[test]
    fn a_nominal_draw_is_the_model_bit_for_bit() {
        let model = bundled::hyq();
        let params = PhysicsParams::default();
        let d = DynamicsDraw::nominal(&model, &params)
            .dynamics(&model)
            .unwrap();
        assert_eq!(d, Dynamics::nominal(&model, &params));
        assert_eq!(d.total_mass(), model.total_mass());
    }

    #[test]
    fn masses_scale_with_their_tensors_and_the_added_mass_sits_at_the_centre_of_mass() {
        let model = bundled::hyq();
        let mut draw = DynamicsDraw::nominal(&model, &PhysicsParams::default());
        draw.link_mass_scale[0] = 0.5;
        draw.link_mass_scale[3] = 1.2;
        draw.trunk_added_mass_kg = 10.0;
        draw.trunk_com_offset_m = [0.05, -0.02, 0.01];
        draw.joint_damping_scale[2] = 3.0;
        let d = draw.dynamics(&model).unwrap();
        let trunk = &model.links()[0];
        let m = 0.5 * trunk.mass + 10.0;
        assert!((d.bodies[0].mass - m).abs() < 1e-12);
        // The tensor grows with the mass: radii of gyration unchanged.
        let ratio = d.bodies[0].inertia[(0, 0)] / trunk.inertia[(0, 0)];
        assert!((ratio - m / trunk.mass).abs() < 1e-12, "{ratio}");
        assert_eq!(d.bodies[0].com, trunk.com + Vector3::new(0.05, -0.02, 0.01));
        let link = &model.links()[3];
        assert!((d.bodies[3].mass - 1.2 * link.mass).abs() < 1e-12);
        assert_eq!(d.bodies[3].inertia, link.inertia * 1.2);
        assert_eq!(d.bodies[3].com, link.com);
        assert_eq!(d.joint_damping[2], 3.0 * model.joints()[2].damping);
        let expected = model.total_mass() - 0.5 * trunk.mass + 10.0 + 0.2 * link.mass;
        assert!((d.total_mass() - expected).abs() < 1e-9);
    }

    #[test]
    fn unphysical_draws_are_refused_by_name() {
        let model = bundled::hyq();
        let nominal = DynamicsDraw::nominal(&model, &PhysicsParams::default());
        let trunk_mass = model.links()[0].mass;
        let cases: Vec<(DynamicsDraw, &str)> = vec![
            (
                DynamicsDraw {
                    trunk_added_mass_kg: -trunk_mass,
                    ..nominal.clone()
                },
                "mass properties of body trunk",
            ),
            (
                DynamicsDraw {
                    ground_friction: -0.1,
                    ..nominal.clone()
                },
                "ground friction",
            ),
            (
                DynamicsDraw {
                    trunk_com_offset_m: [f64::NAN, 0.0, 0.0],
                    ..nominal.clone()
                },
                "centre of mass",
            ),
            (
                DynamicsDraw {
                    link_mass_scale: vec![0.0; model.num_links()],
                    ..nominal.clone()
                },
                "mass 0 must be finite and in [1e-4, 1e6] kg",
            ),
            (
                DynamicsDraw {
                    joint_damping_scale: vec![-1.0; model.num_joints()],
                    ..nominal.clone()
                },
                "damping of joint",
            ),
            (
                DynamicsDraw {
                    link_mass_scale: vec![1.0; 2],
                    ..nominal.clone()
                },
                "link mass scales",
            ),
            (
                DynamicsDraw {
                    contact: ContactDraw {
                        contact_stiffness_scale: 0.0,
                        ..ContactDraw::NOMINAL
                    },
                    ..nominal.clone()
                },
                "contact stiffness scale",
            ),
            (
                DynamicsDraw {
                    contact: ContactDraw {
                        contact_damping_scale: f64::INFINITY,
                        ..ContactDraw::NOMINAL
                    },
                    ..nominal.clone()
                },
                "contact damping scale",
            ),
            (
                DynamicsDraw {
                    contact: ContactDraw {
                        restitution: 1.5,
                        ..ContactDraw::NOMINAL
                    },
                    ..nominal.clone()
                },
                "restitution",
            ),
        ];
        for (draw, says) in cases {
            let err = draw.dynamics(&model).unwrap_err().to_string();
            assert!(err.contains(says), "{err:?} should name {says:?}");
        }
    }

    #[test]
    fn draws_are_held_to_the_robot_bounds_table_and_blamed_on_their_range() {
        let model = bundled::hyq();
        let trunk = model.links()[0].mass;
        check_draw_ranges(&model, &DrawRanges::NOMINAL).unwrap();
        let cases = [
            (
                DrawRanges {
                    link_mass_scale: [1e-30, 1.0],
                    ..DrawRanges::NOMINAL
                },
                DrawnQuantity::LinkMassScale,
                "[1e-4, 1e6] kg",
            ),
            (
                DrawRanges {
                    trunk_added_mass_kg: [0.0, 1e6],
                    ..DrawRanges::NOMINAL
                },
                DrawnQuantity::TrunkAddedMass,
                "body trunk",
            ),
            (
                // Each factor alone is fine; the lightest trunk with the most mass removed is not.
                DrawRanges {
                    link_mass_scale: [0.5, 1.0],
                    trunk_added_mass_kg: [-0.5 * trunk, 0.0],
                    ..DrawRanges::NOMINAL
                },
                DrawnQuantity::TrunkAddedMass,
                "mass 0 must be",
            ),
        ];
        for (ranges, quantity, says) in cases {
            let fault = check_draw_ranges(&model, &ranges).unwrap_err();
            assert_eq!(fault.quantity, quantity, "{ranges:?}");
            assert!(fault.reason.contains(says), "{:?}", fault.reason);
        }
        // The heaviest and lightest draws inside the table pass.
        check_draw_ranges(
            &model,
            &DrawRanges {
                link_mass_scale: [0.01, 100.0],
                trunk_added_mass_kg: [-0.0099 * trunk, 9e5],
                ..DrawRanges::NOMINAL
            },
        )
        .unwrap();
    }

    #[test]
    fn actuator_scales_must_keep_gains_and_efforts_positive() {
        let n = 12;
        ActuatorScales::nominal(n).validate(n).unwrap();
        let mut s = ActuatorScales::nominal(n);
        s.friction[0] = 0.0;
        s.validate(n).unwrap();
        for (field, value) in [("kp", 0.0), ("kd", -1.0), ("effort", f64::INFINITY)] {
            let mut s = ActuatorScales::nominal(n);
            match field {
                "kp" => s.kp[4] = value,
                "kd" => s.kd[4] = value,
                _ => s.effort[4] = value,
            }
            let err = s.validate(n).unwrap_err().to_string();
            assert!(err.contains(&format!("{field} scales[4]")), "{err}");
        }
        let err = ActuatorScales::nominal(3).validate(n).unwrap_err();
        assert!(err.to_string().contains("expected 12"), "{err}");
    }

    #[test]
    fn the_delay_serves_the_previous_targets_for_its_first_sub_steps() {
        let mut delay = TargetDelay::new(2);
        let err = delay.set_substeps(11, 10).unwrap_err().to_string();
        assert!(err.contains("longer than an env step"), "{err}");
        delay.set_substeps(3, 10).unwrap();
        delay.reset(&[0.0, 0.0]);
        let a = [1.0, 2.0];
        let seen: Vec<f64> = (0..10).map(|s| delay.seen(s, &a)[0]).collect();
        assert_eq!(seen, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
        delay.end_step(&a);
        assert_eq!(delay.seen(0, &[5.0, 5.0]), a);
        delay.set_substeps(10, 10).unwrap();
        assert_eq!(delay.seen(9, &[5.0, 5.0]), a, "a whole env step late");
        delay.set_substeps(0, 10).unwrap();
        assert_eq!(delay.seen(0, &[5.0, 5.0]), [5.0, 5.0], "no delay");
    }
}
