//! The default physics backend: [rapier3d] 0.36 (pure Rust), implementing
//! [`hyq_physics::Backend`].
//!
//! # Model
//! - **Reduced coordinates.** The robot is one rapier `Multibody` rooted at the trunk (a free
//!   root, 6 + one DoF per joint). Joints cannot come apart, and limits hold far better than with
//!   impulse joints (up to 0.2–0.7 rad overshoot and millimetres of separation there under full
//!   torque).
//! - **Explicit joint torques.** The shared actuator computes each torque; the backend applies
//!   it as an equal and opposite pair of body torques about the joint axis on the child and the
//!   parent body, which the multibody maps exactly onto that joint's DoF. No rapier motor is
//!   used.
//! - **Trunk body frame at its centre of mass.** A free multibody root whose local centre of
//!   mass is not at its frame origin conserves momentum wrongly in rapier 0.36 (its generalised
//!   velocity is integrated as the origin's but treated as the centre of mass's). The trunk's
//!   rigid body is therefore placed at the trunk's centre of mass; its collider and the frames
//!   of the joints on it are shifted accordingly, and [`Backend::trunk`] converts back to the
//!   URDF trunk frame.
//! - **Velocities from the multibody.** After a step, the rigid bodies of multibody links hold
//!   velocities from the solver's previous internal substep; joint and trunk velocities are
//!   read from the multibody's generalised velocities instead.
//! - **Damping.** The model's joint damping is the multibody's per-DoF damping (implicit in
//!   rapier); rapier's default 0.1 on the free root's rotation is set to 0.
//! - **Ground** is a half-space at z = 0, or, once given a height field
//!   ([`Backend::set_terrain`]), one rapier `HeightField` of the whole grid with internal-edge
//!   fixing on (rapier lets shapes sink at the seam between two fields, so there is never more
//!   than one). Robot shapes collide with it only (no self-collision), with Coulomb friction
//!   [`PhysicsParams::ground_friction`] and no restitution. Sleeping is off.
//!
//! # Contacts
//! A tracked body is in contact when, in the last step, one of its shapes' contacts with the
//! ground carried a normal impulse > 0 or was at most [`PhysicsParams::contact_distance`] from
//! it. Rapier also creates speculative contacts up to its prediction distance (2 cm): those
//! alone do not count.
//!
//! # Resets and determinism
//! [`Backend::apply_state`] restores a pristine copy of the world taken at build time (no
//! contact, warm start or solver state survives) and then places the robot, so a state and
//! the inputs that follow determine the trajectory bitwise.
//!
//! # Per-episode dynamics and pushes
//! [`Backend::apply_dynamics`] changes the world and its pristine copy in place
//! (`dynamics.rs`): every collider's friction and restitution (rapier averages a contact's two,
//! so the ground's and the robot's are set alike, whatever the ground's shape), the ground
//! contact's spring for the drawn stiffness and damping factors (natural frequency times √s,
//! damping ratio times d / √s, on the options' own), each body's additional mass
//! properties, the multibody's per-DoF damping, and, since the trunk's rigid body sits at its
//! centre of mass, the frames of the trunk's colliders and child joints for a moved centre of
//! mass, with the formulas the build uses: a world given dynamics runs bit for bit as one
//! built with them. A push adds to the root's generalised linear velocity (its centre of
//! mass's), so contacts and the solver's state are kept.
//!
//! # Settings
//! See [`RapierOptions`]. The rapier settings that are not options: contact recycling off (a
//! recycled contact's distance can be stale, and the contact flags read it), CCD off (the
//! ground is a half-space; fast bodies cannot tunnel through it), contact clustering and the
//! remaining integration parameters at rapier's defaults. A joint's limit constraint is
//! switched on before each step only if the joint may reach the limit during it (rapier's
//! limit constraint is inert until the joint is past its limit, but costs a mass-matrix solve
//! at every internal substep); this changes no result.
//!
//! # Speed
//! See the crate's `README.md` for measured figures and the command that produced them.
//!
//! [rapier3d]: https://rapier.rs

use std::sync::Arc;

use hyq_physics::na::{Isometry3, Translation3, Vector3};
use hyq_physics::{
    Backend, Dynamics, MassProperties, PhysicsError, PhysicsParams, RobotModel, RobotState,
    Terrain, TrunkState,
};
use rapier3d::prelude::*;

mod build;
mod convert;
mod dynamics;
#[cfg(test)]
mod limit_gating;
mod options;

use build::Sets;
use convert::{from_pose, to_pose};
pub use options::RapierOptions;

/// Distance (rad) beyond `|q̇|·dt` within which a joint's limit constraint is kept on (see
/// `RapierBackend::gate_limit_constraints`): it covers what the joint's speed can change within
/// one step. Under full torque into the limits, the farthest a joint came from to cross its
/// limit within one step was 0.006 rad beyond `|q̇|·dt`.
const LIMIT_REACH_MARGIN: Real = 0.05;

/// HyQ (or any [`RobotModel`]) in rapier; see the crate documentation.
pub struct RapierBackend {
    model: Arc<RobotModel>,
    params: PhysicsParams,
    options: RapierOptions,
    integration: IntegrationParameters,
    gravity: Vector,
    pipeline: PhysicsPipeline,
    world: Sets,
    /// The world as built, before any state was applied.
    pristine: Sets,
    /// Rigid body of each model link (index as in `RobotModel::links`).
    bodies: Vec<RigidBodyHandle>,
    multibody: MultibodyIndex,
    /// Multibody link id of each joint's child (profile order).
    joint_links: Vec<usize>,
    /// Index of each joint's DoF in the generalised velocity (profile order).
    joint_dofs: Vec<usize>,
    /// Each joint's axis in its parent body's frame (profile order).
    joint_axes: Vec<Vector>,
    /// Colliders of each tracked body.
    tracked_colliders: Vec<Vec<ColliderHandle>>,
    /// The trunk's colliders (its collision order), which follow its centre of mass.
    trunk_colliders: Vec<ColliderHandle>,
    ground: ColliderHandle,
    /// The ground the world holds (its collider is `ground`).
    terrain: Terrain,
    /// The dynamics last given ([`Backend::apply_dynamics`]), which a new ground keeps;
    /// `None` while the world has the model's.
    dynamics: Option<Dynamics>,
    /// The trunk's centre of mass in the trunk frame: the trunk body's offset.
    trunk_com: Vector3<f64>,
    /// Torques for the next step (profile order).
    torques: Vec<f64>,
    /// Scratch: body torque per link.
    body_torques: Vec<Vector>,
    /// Contact flags of the last step (tracked order).
    contacts: Vec<bool>,
    /// Each joint's `[lower, upper]` position limit (rad, profile order).
    joint_limits: Vec<[Real; 2]>,
    /// Whether `step` switches off the limit constraints of joints that cannot reach a limit
    /// (always, except in the test that proves it changes nothing).
    gate_limits: bool,
}

impl std::fmt::Debug for RapierBackend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RapierBackend")
            .field("robot", &self.model.name())
            .field("params", &self.params)
            .field("options", &self.options)
            .finish_non_exhaustive()
    }
}

impl RapierBackend {
    /// The rapier settings in use.
    pub fn options(&self) -> &RapierOptions {
        &self.options
    }

    /// Gives the world (and its pristine copy, which resets restore) the dynamics `d`.
    fn give_dynamics(&mut self, d: &Dynamics) {
        let handles = dynamics::Handles {
            bodies: &self.bodies,
            trunk_colliders: &self.trunk_colliders,
            multibody: self.multibody,
            joint_links: &self.joint_links,
            joint_dofs: &self.joint_dofs,
        };
        dynamics::apply(&mut self.world, &self.model, &handles, d);
        dynamics::apply(&mut self.pristine, &self.model, &handles, d);
        self.trunk_com = d.bodies[0].com;
        self.integration.static_contact_softness = dynamics::contact_softness(
            self.options.ground_contact_frequency,
            self.options.ground_contact_damping_ratio,
            &d.contact,
        );
    }

    fn multibody(&self) -> &Multibody {
        // Invariant: the multibody is created in `build` and never removed; restoring the
        // pristine copy keeps its index.
        #[allow(clippy::expect_used)]
        self.world
            .multibody_joints
            .get_multibody(self.multibody)
            .expect("the robot's multibody exists")
    }

    /// The first non-finite quantity of the simulated state, if any.
    fn non_finite(&self) -> Option<String> {
        if !self.pipeline.quarantine().is_empty() {
            return Some("a rigid body (rapier quarantined it)".into());
        }
        let mb = self.multibody();
        if mb.generalized_velocity().iter().any(|v| !v.is_finite()) {
            return Some("a generalised velocity".into());
        }
        for link in mb.links() {
            let p = link.local_to_world();
            if !(p.translation.is_finite() && p.rotation.is_finite()) {
                return Some(format!("the pose of multibody link {}", link.link_id()));
            }
        }
        None
    }

    /// Switches each joint's limit constraint on only if the joint may reach one of its limits
    /// during the coming step: within `|q̇|·dt +` [`LIMIT_REACH_MARGIN`] of it.
    ///
    /// rapier's multibody limit constraint only acts on a joint that is already past its limit
    /// when an internal substep starts (its impulse is bounded to zero otherwise), yet it costs
    /// a solve with the factorised mass matrix and a solver row at every internal substep. A
    /// joint farther than that from its limits has an inert constraint, so switching it off
    /// changes nothing; `limit_gating` proves it bitwise under full torque into the limits.
    fn gate_limit_constraints(&mut self) {
        let dt = self.params.dt as Real;
        let Some(mb) = self
            .world
            .multibody_joints
            .get_multibody_mut(self.multibody)
        else {
            return;
        };
        for (j, &id) in self.joint_links.iter().enumerate() {
            let reach =
                mb.generalized_velocity()[self.joint_dofs[j]].abs() * dt + LIMIT_REACH_MARGIN;
            let [lower, upper] = self.joint_limits[j];
            if let Some(link) = mb.link_mut(id) {
                let q = link.joint().coords()[3];
                let near = q - reach <= lower || q + reach >= upper;
                link.joint.data.limit_axes.set(JointAxesMask::ANG_X, near);
            }
        }
    }

    fn update_contacts(&mut self) {
        let threshold = self.params.contact_distance as Real;
        let narrow = &self.world.narrow_phase;
        for (flag, colliders) in self.contacts.iter_mut().zip(&self.tracked_colliders) {
            *flag = colliders.iter().any(|&c| {
                narrow.contact_pair(self.ground, c).is_some_and(|pair| {
                    pair.solver_manifolds().iter().any(|m| {
                        m.points
                            .iter()
                            .any(|p| p.data.impulse > 0.0 || p.dist <= threshold)
                    })
                })
            });
        }
    }
}

impl Backend for RapierBackend {
    type Options = RapierOptions;
    const NAME: &'static str = "rapier";

    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &RapierOptions,
    ) -> Result<Self, PhysicsError> {
        params.validate()?;
        options.validate()?;
        let built = build::build_world(&model, params.ground_friction as Real, &Terrain::Flat)?;
        let gravity = Vector::new(
            params.gravity[0] as Real,
            params.gravity[1] as Real,
            params.gravity[2] as Real,
        );
        let joints = model.joints();
        let spawn = model.spawn_state();
        let mut backend = Self {
            pristine: built.sets.clone(),
            world: built.sets,
            model: Arc::clone(&model),
            params: params.clone(),
            options: options.clone(),
            integration: build::integration_parameters(params, options),
            gravity,
            pipeline: PhysicsPipeline::new(),
            body_torques: vec![Vector::ZERO; built.bodies.handles.len()],
            tracked_colliders: tracked_colliders(&model, &built.bodies),
            trunk_colliders: built.bodies.colliders[0].clone(),
            bodies: built.bodies.handles,
            multibody: built.dofs.multibody,
            joint_links: built.dofs.joint_links,
            joint_dofs: built.dofs.joint_dofs,
            joint_axes: built.joint_axes,
            ground: built.ground,
            terrain: Terrain::Flat,
            dynamics: None,
            trunk_com: model.links()[0].com,
            torques: vec![0.0; joints.len()],
            contacts: vec![false; model.tracked().len()],
            joint_limits: joints
                .iter()
                .map(|j| [j.lower as Real, j.upper as Real])
                .collect(),
            gate_limits: true,
        };
        backend.apply_state(&spawn)?;
        Ok(backend)
    }

    fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    fn params(&self) -> &PhysicsParams {
        &self.params
    }

    fn apply_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        self.world.clone_from(&self.pristine);
        self.torques.fill(0.0);
        self.contacts.fill(false);
        let Sets {
            bodies,
            multibody_joints,
            ..
        } = &mut self.world;

        let com_pose = state.trunk.pose * Translation3::from(self.trunk_com);
        bodies[self.bodies[0]].set_position(to_pose(&com_pose), true);
        // Invariant: see `multibody()`.
        #[allow(clippy::expect_used)]
        let mb = multibody_joints
            .get_multibody_mut(self.multibody)
            .expect("the robot's multibody exists");
        // The pristine coordinates are all 0, so each displacement sets the angle.
        for (j, &id) in self.joint_links.iter().enumerate() {
            if let Some(link) = mb.link_mut(id) {
                link.joint.apply_displacement(&[state.q[j] as Real]);
            }
        }
        mb.forward_kinematics(bodies, true);
        mb.update_rigid_bodies(bodies, true);

        // The root's generalised linear velocity is its centre of mass's.
        let w = state.trunk.angvel;
        let v_com = state.trunk.linvel + w.cross(&(state.trunk.pose.rotation * self.trunk_com));
        let mut v = mb.generalized_velocity_mut();
        for k in 0..3 {
            v[k] = v_com[k] as Real;
            v[3 + k] = w[k] as Real;
        }
        for (j, &dof) in self.joint_dofs.iter().enumerate() {
            v[dof] = state.qd[j] as Real;
        }
        Ok(())
    }

    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        self.torques.copy_from_slice(torques);
        Ok(())
    }

    fn step(&mut self) -> Result<(), PhysicsError> {
        // Each joint torque becomes +τ·axis on the child and −τ·axis on the parent.
        self.body_torques.fill(Vector::ZERO);
        for (j, joint) in self.model.joints().iter().enumerate() {
            let tau = self.torques[j] as Real;
            if tau == 0.0 {
                continue;
            }
            let axis = self.world.bodies[self.bodies[joint.parent]].rotation() * self.joint_axes[j];
            self.body_torques[joint.child] += axis * tau;
            self.body_torques[joint.parent] -= axis * tau;
        }
        for (handle, torque) in self.bodies.iter().zip(&self.body_torques) {
            let body = &mut self.world.bodies[*handle];
            // User torques persist in rapier until reset.
            body.reset_torques(false);
            body.add_torque(*torque, false);
        }
        if self.gate_limits {
            self.gate_limit_constraints();
        }
        let w = &mut self.world;
        self.pipeline.step(
            self.gravity,
            &self.integration,
            &mut w.islands,
            &mut w.broad_phase,
            &mut w.narrow_phase,
            &mut w.bodies,
            &mut w.colliders,
            &mut w.impulse_joints,
            &mut w.multibody_joints,
            &mut w.soft_bodies,
            &mut w.ccd,
            &(),
            &(),
        );
        self.torques.fill(0.0);
        if let Some(what) = self.non_finite() {
            self.contacts.fill(false);
            return Err(PhysicsError::Diverged { what });
        }
        self.update_contacts();
        Ok(())
    }

    fn joint_positions(&self, out: &mut [f64]) {
        assert_eq!(out.len(), self.joint_links.len(), "one value per joint");
        let mb = self.multibody();
        for (o, &id) in out.iter_mut().zip(&self.joint_links) {
            // The revolute DoF is the angular x coordinate (index 3 of the spatial vector).
            *o = mb
                .link(id)
                .map_or(f64::NAN, |l| f64::from(l.joint().coords()[3]));
        }
    }

    fn joint_velocities(&self, out: &mut [f64]) {
        assert_eq!(out.len(), self.joint_dofs.len(), "one value per joint");
        let v = self.multibody().generalized_velocity();
        for (o, &dof) in out.iter_mut().zip(&self.joint_dofs) {
            *o = f64::from(v[dof]);
        }
    }

    fn trunk(&self) -> TrunkState {
        let com_pose = from_pose(self.world.bodies[self.bodies[0]].position());
        let pose = com_pose * Translation3::from(-self.trunk_com);
        let v = self.multibody().generalized_velocity();
        let v_com = Vector3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
        let angvel = Vector3::new(f64::from(v[3]), f64::from(v[4]), f64::from(v[5]));
        let to_origin = pose.translation.vector - com_pose.translation.vector;
        TrunkState {
            pose,
            linvel: v_com + angvel.cross(&to_origin),
            angvel,
        }
    }

    fn contacts(&self, out: &mut [bool]) {
        out.copy_from_slice(&self.contacts);
    }

    fn link_poses(&self, out: &mut [Isometry3<f64>]) {
        assert_eq!(out.len(), self.bodies.len(), "one pose per body");
        for (o, h) in out.iter_mut().zip(&self.bodies) {
            *o = from_pose(self.world.bodies[*h].position());
        }
        out[0] *= Translation3::from(-self.trunk_com);
    }

    fn total_mass(&self) -> f64 {
        self.bodies
            .iter()
            .map(|h| f64::from(self.world.bodies[*h].mass()))
            .sum()
    }

    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        self.give_dynamics(dynamics);
        self.dynamics = Some(dynamics.clone());
        Ok(())
    }

    fn body_mass_properties(&self, link: usize) -> MassProperties {
        dynamics::read(&self.world.bodies[self.bodies[link]], link, &self.trunk_com)
    }

    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        // Invariant: see `multibody()`.
        #[allow(clippy::expect_used)]
        let mb = self
            .world
            .multibody_joints
            .get_multibody_mut(self.multibody)
            .expect("the robot's multibody exists");
        // The root's generalised linear velocity is its centre of mass's; with the angular
        // velocity unchanged, every point of the trunk gains `dv`.
        let mut v = mb.generalized_velocity_mut();
        for k in 0..3 {
            v[k] += dv[k] as Real;
        }
        Ok(())
    }

    fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        let state = self.state();
        // The whole world is rebuilt in the order `build` uses, so every handle but the
        // ground's shape is as it was; they are all taken from the new build regardless.
        let built = build::build_world(&self.model, self.params.ground_friction as Real, terrain)?;
        self.tracked_colliders = tracked_colliders(&self.model, &built.bodies);
        self.trunk_colliders = built.bodies.colliders[0].clone();
        self.pristine = built.sets;
        self.ground = built.ground;
        self.bodies = built.bodies.handles;
        self.multibody = built.dofs.multibody;
        self.joint_links = built.dofs.joint_links;
        self.joint_dofs = built.dofs.joint_dofs;
        self.joint_axes = built.joint_axes;
        self.terrain = terrain.clone();
        // The new world is built with the model's dynamics; any given since are given again.
        self.trunk_com = self.model.links()[0].com;
        if let Some(d) = self.dynamics.clone() {
            self.give_dynamics(&d);
        }
        self.apply_state(&state)
    }
}

/// The colliders of each tracked body (tracked order).
fn tracked_colliders(model: &RobotModel, bodies: &build::Bodies) -> Vec<Vec<ColliderHandle>> {
    model
        .tracked()
        .iter()
        .map(|t| {
            t.shapes
                .iter()
                .map(|&s| bodies.colliders[t.link][s])
                .collect()
        })
        .collect()
}
