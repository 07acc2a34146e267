//! The physics seam: the [`Backend`] trait every simulator implements. The plain data that
//! crosses it ([`PhysicsParams`], [`RobotState`], [`TrunkState`]) is `crate::state`'s.
//!
//! A backend simulates one robot ([`RobotModel`]) on the ground (world frame: x forward, y left,
//! z up): flat at z = 0 as built, or a height field ([`Terrain`]) once given one. It advances one physics sub-step at a time under joint torques the
//! caller computes (the shared actuator, [`crate::actuator`]), and reports joint state, trunk
//! state and which tracked bodies (feet, trunk) touched the ground during the last sub-step.
//!
//! Input policy: inputs that may come from users, files or policies (states, torques,
//! parameters) are validated, and bad ones are errors naming the value. Output buffers of the
//! wrong length are a programming error and panic, like `copy_from_slice`.

use std::fmt::Debug;
use std::sync::Arc;

use nalgebra::{Isometry3, Vector3};
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::dynamics::Dynamics;
use crate::error::PhysicsError;
use crate::inertia::MassProperties;
use crate::model::RobotModel;
use crate::state::{PhysicsParams, RobotState, TrunkState};
use crate::terrain::Terrain;

/// A physics engine simulating one robot on the ground: flat as built, or a height field.
///
/// Required: the small core below. Provided: validation ([`Backend::set_state`],
/// [`Backend::set_joint_torques`]) and whole-state reads. A backend:
/// - applies the model's joint damping itself, as passive viscous damping, and no other joint
///   friction, spring or motor;
/// - adds no actuator of its own: the torques given are the only joint torques;
/// - has no self-collision: robot shapes touch only the ground;
/// - is deterministic: the same state and inputs give bitwise the same results.
pub trait Backend: Sized + Send + 'static {
    /// Engine-specific settings (`[physics.<NAME>]` in an environment's TOML), e.g. solver
    /// iterations. `Default` gives the project's chosen settings.
    type Options: Clone + Debug + Default + PartialEq + Send + Sync + Serialize + DeserializeOwned;

    /// The backend's name, e.g. `"rapier"`.
    const NAME: &'static str;

    /// Builds a world with the robot at its spawn state ([`RobotModel::spawn_state`]).
    ///
    /// Must call [`PhysicsParams::validate`] and fail on invalid parameters or options.
    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &Self::Options,
    ) -> Result<Self, PhysicsError>;

    /// The name of the engine this world runs on: [`Backend::NAME`], except for a backend that
    /// wraps several engines (hyq-engines' `AnyBackend`), where it is the engine of this value.
    fn engine_name(&self) -> &'static str {
        Self::NAME
    }

    /// The robot being simulated.
    fn model(&self) -> &Arc<RobotModel>;

    /// The physics parameters the world was built with.
    fn params(&self) -> &PhysicsParams;

    /// Puts the world into exactly this (already validated) state as if freshly built: no warm
    /// start, contact cache or pending torque survives, so what follows depends only on the
    /// state and the inputs, bitwise. Contacts read as all false until the next step.
    ///
    /// Errors if the engine refuses the state after all (it was validated, so this is the
    /// engine's limit, not the caller's mistake); the world then refuses to step until a state
    /// is given that it takes.
    ///
    /// Callers use [`Backend::set_state`], which validates first.
    fn apply_state(&mut self, state: &RobotState) -> Result<(), PhysicsError>;

    /// Stores joint torques (N·m, profile order, already validated) for the next
    /// [`Backend::step`] only.
    ///
    /// Errors if the engine refuses them (see [`Backend::apply_state`]).
    ///
    /// Callers use [`Backend::set_joint_torques`], which validates first.
    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError>;

    /// Advances one physics sub-step of `params().dt` under the stored torques, then clears
    /// them (a step with no torques set is a step with zero torques).
    ///
    /// Errors with [`PhysicsError::Diverged`] when the state became non-finite; the world must
    /// then be reset with [`Backend::set_state`] before it is stepped again. After `Ok`, every
    /// read is finite.
    fn step(&mut self) -> Result<(), PhysicsError>;

    /// Joint angles (rad), profile order.
    ///
    /// # Panics
    /// If `out.len()` is not the number of joints.
    fn joint_positions(&self, out: &mut [f64]);

    /// Joint speeds (rad/s), profile order.
    ///
    /// # Panics
    /// If `out.len()` is not the number of joints.
    fn joint_velocities(&self, out: &mut [f64]);

    /// The trunk's pose and velocity (see [`TrunkState`] for which point and frame).
    fn trunk(&self) -> TrunkState;

    /// For each tracked body ([`RobotModel::tracked`]): did it really touch the ground during
    /// the last step? Real means carrying load (normal impulse > 0) or within
    /// `params().contact_distance` of the ground; merely being near it (an engine's speculative
    /// contact) does not count. All false after build and [`Backend::apply_state`].
    ///
    /// # Panics
    /// If `out.len()` is not the number of tracked bodies.
    fn contacts(&self, out: &mut [bool]);

    /// The world pose of every body frame as the engine holds it (index as in
    /// [`RobotModel::links`]). Independent of [`RobotModel::link_poses`], which recomputes them
    /// from the trunk pose and the joint angles: the two differ if joints come apart.
    ///
    /// # Panics
    /// If `out.len()` is not the number of bodies.
    fn link_poses(&self, out: &mut [Isometry3<f64>]);

    /// The total mass (kg) of the robot's bodies as the engine holds them.
    fn total_mass(&self) -> f64;

    // ---------------------------------------------------------------------------------------
    // Per-episode dynamics and pushes (domain randomisation, see `crate::dynamics`). A world
    // is built with the model's dynamics; these change them, and push the trunk.
    // ---------------------------------------------------------------------------------------

    /// Gives the world these (already validated) dynamics, as if it had been built with them:
    /// the ground friction acts on whatever shape the ground has, every body's mass
    /// properties and joint damping are replaced, and the ground contact takes the drawn
    /// stiffness and damping factors and restitution ([`crate::ContactDraw`]) as the engine's
    /// model allows: an engine whose contact has no such quantity refuses a value other than
    /// the nominal one, before changing anything, with an error naming the
    /// `randomize.` option. What the world does before the next
    /// [`Backend::apply_state`] is unspecified (an engine may have to move internal frames);
    /// that call must follow before a step.
    ///
    /// Errors if the engine refuses them after all; the world then refuses to step until
    /// dynamics it takes are given.
    ///
    /// Callers use [`Backend::set_dynamics`], which validates first and re-applies the state.
    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError>;

    /// The mass properties of body `link` (index as in [`RobotModel::links`]) as the engine
    /// holds them, in the body's link frame: what [`Backend::apply_dynamics`] gave it, read
    /// back (an engine in single precision rounds them).
    ///
    /// # Panics
    /// If `link` is not a body index.
    fn body_mass_properties(&self, link: usize) -> MassProperties;

    /// Adds `dv` (m/s, world frame, already validated) to the trunk's linear velocity now,
    /// leaving joint speeds, the angular velocity and everything the engine carries between
    /// steps (warm starts, contacts) as they are: a push, not a reset. The whole robot moves
    /// with the trunk, since joint speeds are relative.
    ///
    /// Errors if the engine refuses it (see [`Backend::apply_state`]).
    ///
    /// Callers use [`Backend::push_trunk`], which validates first.
    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError>;

    /// Validates `dynamics` against the model ([`Dynamics::validate`]), gives them to the
    /// world ([`Backend::apply_dynamics`]) and puts it back into the state it was in (the
    /// spawn state if that is not a valid state, after a divergence): afterwards the world is
    /// as if built with these dynamics and set to that state.
    fn set_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        dynamics.validate(self.model())?;
        let mut state = self.state();
        if state.validate(self.model()).is_err() {
            state = self.model().spawn_state();
        }
        self.apply_dynamics(dynamics)?;
        self.apply_state(&state)
    }

    /// Validates `dynamics` and `state`, then gives the world those dynamics and puts it into
    /// that state ([`Backend::apply_dynamics`], [`Backend::apply_state`]): a randomised
    /// episode's reset in one state change, where [`Backend::set_dynamics`] followed by
    /// [`Backend::set_state`] would make two (a DART state change installs a fresh collision
    /// detector, the larger part of its reset).
    fn reset_with_dynamics(
        &mut self,
        dynamics: &Dynamics,
        state: &RobotState,
    ) -> Result<(), PhysicsError> {
        dynamics.validate(self.model())?;
        state.validate(self.model())?;
        self.apply_dynamics(dynamics)?;
        self.apply_state(state)
    }

    /// Adds `dv` (m/s, world frame, finite) to the trunk's linear velocity now (see
    /// [`Backend::apply_trunk_velocity_change`]).
    fn push_trunk(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        if let Some(v) = dv.iter().find(|v| !v.is_finite()) {
            return Err(PhysicsError::NonFinite {
                what: "trunk velocity change".into(),
                value: *v,
            });
        }
        self.apply_trunk_velocity_change(dv)
    }

    // -------------------------------------------------------------------------------------
    // The ground under the robot: flat as built, or a height field.
    // -------------------------------------------------------------------------------------

    /// The ground this world simulates: [`Terrain::Flat`] (the plane z = 0) after
    /// [`Backend::build`], else what [`Backend::set_terrain`] last gave.
    fn terrain(&self) -> &Terrain;

    /// Replaces the ground with `terrain` (different from the current one), keeping the
    /// robot's state and the world's dynamics: afterwards the world is as
    /// [`Backend::apply_state`] leaves it with the state it held (no contact, warm start or
    /// pending torque survives), and the new ground has the ground friction the world had (the
    /// last [`Backend::set_dynamics`]'s, else [`PhysicsParams::ground_friction`]), the bodies
    /// the mass properties and damping they had. A height field is one field built from the
    /// whole grid, triangulated as [`crate::HeightGrid`] documents.
    ///
    /// Callers use [`Backend::set_terrain`].
    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError>;

    /// Replaces the ground with `terrain` (see [`Backend::apply_terrain`]); giving the ground
    /// the world already has changes nothing, so a flat world stays exactly as built.
    fn set_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        if self.terrain().same_as(terrain) {
            return Ok(());
        }
        self.apply_terrain(terrain)
    }

    /// Validates `state` against the model and puts the world into it (see
    /// [`Backend::apply_state`]).
    fn set_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        state.validate(self.model())?;
        self.apply_state(state)
    }

    /// Validates joint torques (one finite value per joint, N·m, profile order) and stores them
    /// for the next [`Backend::step`] only.
    fn set_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        check_joint_values(self.model(), "joint torques", "torque", torques)?;
        self.apply_joint_torques(torques)
    }

    /// Reads the whole state into `out`, resizing its joint vectors to the number of joints
    /// (no allocation once they have the capacity).
    fn read_state(&self, out: &mut RobotState) {
        let n = self.model().num_joints();
        out.q.resize(n, 0.0);
        out.qd.resize(n, 0.0);
        self.joint_positions(&mut out.q);
        self.joint_velocities(&mut out.qd);
        out.trunk = self.trunk();
    }

    /// The whole state (allocates; see [`Backend::read_state`] for hot paths).
    fn state(&self) -> RobotState {
        let mut out = RobotState {
            trunk: self.trunk(),
            q: Vec::new(),
            qd: Vec::new(),
        };
        self.read_state(&mut out);
        out
    }
}

/// Checks that `values` holds one finite value per joint; `what` names the slice and `each`
/// one value in errors (e.g. "joint torques", "torque").
pub fn check_joint_values(
    model: &RobotModel,
    what: &'static str,
    each: &str,
    values: &[f64],
) -> Result<(), PhysicsError> {
    if values.len() != model.num_joints() {
        return Err(PhysicsError::WrongLength {
            what,
            expected: model.num_joints(),
            got: values.len(),
        });
    }
    check_finite_joint_values(model, each, values)
}

/// Checks that every one of `values` (one per joint, a length the caller guarantees) is
/// finite; `each` names one value in the error, with its joint (e.g. "torque for joint lf_kfe").
pub(crate) fn check_finite_joint_values(
    model: &RobotModel,
    each: &str,
    values: &[f64],
) -> Result<(), PhysicsError> {
    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(PhysicsError::NonFinite {
            what: format!("{each} for joint {}", model.joints()[i].name),
            value: *v,
        });
    }
    Ok(())
}
