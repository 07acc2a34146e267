//! A scripted backend for tests: [`ScriptedBackend`] implements `hyq_physics::Backend` with a
//! trivial, deterministic, allocation-free model, and lets a test rewrite the world after every
//! physics sub-step (contacts, trunk state, joint state, or a divergence), so that contracts
//! about sub-steps can be tested exactly: a contact that happens only in a middle sub-step, a
//! trunk velocity with a known change, a NaN reading, a `Diverged` error.
//!
//! The model: each joint is a unit inertia driven by its torque and damped by the joint damping
//! (the model's, or the last dynamics given), integrated with semi-implicit Euler and stopped at its limits; the trunk moves with
//! its velocity (no gravity, no ground: the ground friction and the masses it is given are only
//! reported back; a terrain it is given is remembered and ignored), and a push adds to that velocity. After each sub-step every foot reads as touching the
//! ground and the trunk as not touching ([`ScriptedOptions::feet_touch`]), then the script, if
//! any, runs.
//!
//! It is not a physics engine: use it for the environment's bookkeeping, never for behaviour.

use std::fmt;
use std::sync::Arc;

use hyq_physics::na::{Isometry3, UnitQuaternion, Vector3};
use hyq_physics::{
    Backend, Dynamics, MassProperties, PhysicsError, PhysicsParams, RobotModel, RobotState,
    Terrain, TrunkState,
};
use serde::{Deserialize, Serialize};

/// Options of [`ScriptedBackend`] (`[physics.scripted]` is not read: use `Default` or
/// [`ScriptedBackend::options_mut`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ScriptedOptions {
    /// Each joint's inertia (kg·m²) in the toy joint model. (default: 1.0)
    pub joint_inertia: f64,
    /// Whether the feet read as touching the ground after each sub-step before the script
    /// runs. (default: true)
    pub feet_touch: bool,
}

impl Default for ScriptedOptions {
    fn default() -> Self {
        Self {
            joint_inertia: 1.0,
            feet_touch: true,
        }
    }
}

/// The world a script sees and may change after each sub-step.
pub struct ScriptedWorld<'a> {
    /// Sub-steps taken since the last `set_state`, counting this one (1 after the first).
    pub substep: u64,
    /// Joint angles (rad).
    pub q: &'a mut [f64],
    /// Joint speeds (rad/s).
    pub qd: &'a mut [f64],
    /// The trunk.
    pub trunk: &'a mut TrunkState,
    /// Contact flags of this sub-step, tracked order (feet, then the trunk).
    pub contacts: &'a mut [bool],
    /// The torques applied in this sub-step (read-only).
    pub torques: &'a [f64],
}

/// A script run after every sub-step; an `Err` is returned by `Backend::step` (e.g.
/// `PhysicsError::Diverged`).
pub type Script = Box<dyn FnMut(&mut ScriptedWorld<'_>) -> Result<(), PhysicsError> + Send>;

/// The scripted backend (see the module docs).
pub struct ScriptedBackend {
    model: Arc<RobotModel>,
    params: PhysicsParams,
    options: ScriptedOptions,
    q: Vec<f64>,
    qd: Vec<f64>,
    torques: Vec<f64>,
    applied: Vec<f64>,
    trunk: TrunkState,
    contacts: Vec<bool>,
    substep: u64,
    script: Option<Script>,
    dynamics: Dynamics,
    /// The terrain last given; the toy model has no ground, so it changes nothing.
    terrain: Terrain,
}

impl fmt::Debug for ScriptedBackend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ScriptedBackend")
            .field("substep", &self.substep)
            .field("q", &self.q)
            .field("trunk", &self.trunk)
            .field("contacts", &self.contacts)
            .field("script", &self.script.is_some())
            .finish()
    }
}

impl ScriptedBackend {
    /// Runs `script` after every sub-step from now on (replacing any previous one).
    pub fn set_script(
        &mut self,
        script: impl FnMut(&mut ScriptedWorld<'_>) -> Result<(), PhysicsError> + Send + 'static,
    ) {
        self.script = Some(Box::new(script));
    }

    /// Removes the script.
    pub fn clear_script(&mut self) {
        self.script = None;
    }

    /// Sub-steps taken since the last `set_state`.
    pub fn substeps(&self) -> u64 {
        self.substep
    }

    /// The options, to change them after the backend was built.
    pub fn options_mut(&mut self) -> &mut ScriptedOptions {
        &mut self.options
    }
}

impl Backend for ScriptedBackend {
    type Options = ScriptedOptions;
    const NAME: &'static str = "scripted";

    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &Self::Options,
    ) -> Result<Self, PhysicsError> {
        params.validate()?;
        if !(options.joint_inertia.is_finite() && options.joint_inertia > 0.0) {
            return Err(PhysicsError::InvalidParam {
                field: "scripted.joint_inertia",
                value: options.joint_inertia.to_string(),
                reason: "must be finite and positive",
            });
        }
        let state = model.spawn_state();
        let n = model.num_joints();
        let tracked = model.tracked().len();
        Ok(Self {
            params: params.clone(),
            options: options.clone(),
            q: state.q,
            qd: state.qd,
            torques: vec![0.0; n],
            applied: vec![0.0; n],
            trunk: state.trunk,
            contacts: vec![false; tracked],
            substep: 0,
            script: None,
            dynamics: Dynamics::nominal(&model, params),
            terrain: Terrain::Flat,
            model,
        })
    }

    fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    fn params(&self) -> &PhysicsParams {
        &self.params
    }

    fn apply_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        self.q.copy_from_slice(&state.q);
        self.qd.copy_from_slice(&state.qd);
        self.trunk = state.trunk;
        self.torques.fill(0.0);
        self.contacts.fill(false);
        self.substep = 0;
        Ok(())
    }

    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        self.torques.copy_from_slice(torques);
        Ok(())
    }

    fn step(&mut self) -> Result<(), PhysicsError> {
        let dt = self.params.dt;
        let inertia = self.options.joint_inertia;
        for (i, joint) in self.model.joints().iter().enumerate() {
            let acc = (self.torques[i] - self.dynamics.joint_damping[i] * self.qd[i]) / inertia;
            self.qd[i] += dt * acc;
            self.q[i] += dt * self.qd[i];
            if self.q[i] < joint.lower || self.q[i] > joint.upper {
                self.q[i] = self.q[i].clamp(joint.lower, joint.upper);
                self.qd[i] = 0.0;
            }
        }
        let t = &mut self.trunk;
        t.pose.translation.vector += dt * t.linvel;
        t.pose.rotation = UnitQuaternion::from_scaled_axis(dt * t.angvel) * t.pose.rotation;
        let feet = self.model.num_feet();
        for (i, c) in self.contacts.iter_mut().enumerate() {
            *c = i < feet && self.options.feet_touch;
        }
        self.applied.copy_from_slice(&self.torques);
        self.torques.fill(0.0);
        self.substep += 1;
        match self.script.as_mut() {
            None => Ok(()),
            Some(script) => script(&mut ScriptedWorld {
                substep: self.substep,
                q: &mut self.q,
                qd: &mut self.qd,
                trunk: &mut self.trunk,
                contacts: &mut self.contacts,
                torques: &self.applied,
            }),
        }
    }

    fn joint_positions(&self, out: &mut [f64]) {
        out.copy_from_slice(&self.q);
    }

    fn joint_velocities(&self, out: &mut [f64]) {
        out.copy_from_slice(&self.qd);
    }

    fn trunk(&self) -> TrunkState {
        self.trunk
    }

    fn contacts(&self, out: &mut [bool]) {
        out.copy_from_slice(&self.contacts);
    }

    fn link_poses(&self, out: &mut [Isometry3<f64>]) {
        // Invariant: `q` always holds one angle per joint and callers size `out` per body, as
        // the trait requires (it panics otherwise, like every backend).
        if let Err(e) = self.model.link_poses(&self.trunk.pose, &self.q, out) {
            panic!("link pose buffer: {e}");
        }
    }

    fn total_mass(&self) -> f64 {
        self.dynamics.total_mass()
    }

    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        self.dynamics.clone_from(dynamics);
        Ok(())
    }

    fn body_mass_properties(&self, link: usize) -> MassProperties {
        self.dynamics.bodies[link]
    }

    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        self.trunk.linvel += dv;
        Ok(())
    }

    fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        self.terrain = terrain.clone();
        self.torques.fill(0.0);
        self.contacts.fill(false);
        self.substep = 0;
        Ok(())
    }
}
