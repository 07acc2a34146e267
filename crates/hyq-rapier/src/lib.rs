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
//! - **Ground** is a half-space at z = 0. Robot shapes collide with it only (no self-collision),
//!   with Coulomb friction [`PhysicsParams::ground_friction`] and no restitution. Sleeping is off.
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

use hyq_physics::na::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use hyq_physics::{
    Backend, PhysicsError, PhysicsParams, RobotModel, RobotState, Shape, TrunkState,
};
use rapier3d::prelude::*;
use serde::{Deserialize, Serialize};

#[cfg(test)]
mod limit_gating;

/// Distance (rad) beyond `|q̇|·dt` within which a joint's limit constraint is kept on (see
/// `RapierBackend::gate_limit_constraints`): it covers what the joint's speed can change within
/// one step. Under full torque into the limits, the farthest a joint came from to cross its
/// limit within one step was 0.006 rad beyond `|q̇|·dt`.
const LIMIT_REACH_MARGIN: Real = 0.05;

/// rapier-specific settings (`[physics.rapier]` in an environment's TOML).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RapierOptions {
    /// Internal solver substeps per physics step (rapier's `num_solver_iterations`)
    /// (default: 2; rapier's own default is 4). The main cost knob: a HyQ sub-step costs about
    /// 310, 480 and 820 thousand instructions at 1, 2 and 4 (random targets; see the crate's
    /// README). The conformance suite passes at all three; fewer make joint limits softer under
    /// full torque (worst overshoot 0.087 rad at 1, 0.032 at 2, 0.015 at 4) and free-floating
    /// momentum drift larger (6.4, 1.8, 0.7 mm in a violent second). Standing is the same at 1
    /// to 4.
    pub solver_iterations: usize,
    /// Natural frequency (Hz) of the ground-contact constraint (rapier's
    /// `static_contact_softness`) (default: 240; rapier's own default is 60). A standing HyQ's
    /// feet sink 0.2–0.3 mm at 240 Hz and 3–4.5 mm at 60 Hz; at 240 Hz its trunk settles at
    /// the height DART's rigid contacts give (0.5895 m against 0.5897 m), so the engines
    /// compare.
    pub ground_contact_frequency: f64,
    /// Damping ratio of the ground-contact constraint (default: 10, rapier's).
    pub ground_contact_damping_ratio: f64,
    /// Distance (m) within which rapier creates speculative contacts
    /// (`normalized_prediction_distance`) (default: 0.02, rapier's). They keep fast feet from
    /// tunnelling; they never count as contact flags.
    pub prediction_distance: f64,
}

impl Default for RapierOptions {
    fn default() -> Self {
        Self {
            solver_iterations: 2,
            ground_contact_frequency: 240.0,
            ground_contact_damping_ratio: 10.0,
            prediction_distance: 0.02,
        }
    }
}

impl RapierOptions {
    /// Checks every field; the error names the first invalid one.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        let bad = |field: &'static str, value: String, reason: &'static str| {
            Err(PhysicsError::InvalidParam {
                field,
                value,
                reason,
            })
        };
        if !(1..=64).contains(&self.solver_iterations) {
            return bad(
                "rapier.solver_iterations",
                self.solver_iterations.to_string(),
                "must be in 1..=64",
            );
        }
        if !(self.ground_contact_frequency.is_finite() && self.ground_contact_frequency > 0.0) {
            return bad(
                "rapier.ground_contact_frequency",
                self.ground_contact_frequency.to_string(),
                "must be finite and positive (Hz)",
            );
        }
        if !(self.ground_contact_damping_ratio.is_finite()
            && self.ground_contact_damping_ratio > 0.0)
        {
            return bad(
                "rapier.ground_contact_damping_ratio",
                self.ground_contact_damping_ratio.to_string(),
                "must be finite and positive",
            );
        }
        if !(self.prediction_distance.is_finite() && self.prediction_distance >= 0.0) {
            return bad(
                "rapier.prediction_distance",
                self.prediction_distance.to_string(),
                "must be finite and non-negative (m)",
            );
        }
        Ok(())
    }
}

/// Everything rapier simulates: cloned whole to snapshot and restore a world.
#[derive(Clone)]
struct Sets {
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    islands: IslandManager,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
    ccd: CCDSolver,
    soft_bodies: SoftBodySet,
}

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
    ground: ColliderHandle,
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

fn to_vec(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x as Real, v.y as Real, v.z as Real)
}

fn from_vec(v: Vector) -> Vector3<f64> {
    Vector3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

fn to_pose(p: &Isometry3<f64>) -> Pose {
    let q = p.rotation.quaternion();
    let rotation = Rotation::from_xyzw(q.i as Real, q.j as Real, q.k as Real, q.w as Real);
    Pose::from_parts(to_vec(&p.translation.vector), rotation.normalize())
}

fn from_pose(p: &Pose) -> Isometry3<f64> {
    let r = p.rotation;
    Isometry3::from_parts(
        Translation3::from(from_vec(p.translation)),
        UnitQuaternion::new_normalize(Quaternion::new(
            f64::from(r.w),
            f64::from(r.x),
            f64::from(r.y),
            f64::from(r.z),
        )),
    )
}

/// The shortest rotation taking the x axis onto `axis` (rapier's revolute DoF is about x).
fn x_onto(axis: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::rotation_between(&Vector3::x(), axis).unwrap_or_else(|| {
        // `axis` is -x: any half turn about an axis orthogonal to x.
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI)
    })
}

fn backend_error(message: String) -> PhysicsError {
    PhysicsError::Backend {
        backend: RapierBackend::NAME,
        message,
    }
}

impl RapierBackend {
    /// The rapier settings in use.
    pub fn options(&self) -> &RapierOptions {
        &self.options
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
        let friction = params.ground_friction as Real;
        let mut world = Sets {
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            ccd: CCDSolver::new(),
            soft_bodies: SoftBodySet::new(),
        };
        let robot_groups =
            InteractionGroups::new(Group::GROUP_1, Group::GROUP_2, InteractionTestMode::And);
        let ground_groups =
            InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And);

        let ground_body = world.bodies.insert(RigidBodyBuilder::fixed());
        let ground = world.colliders.insert_with_parent(
            ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Z))
                .friction(friction)
                .restitution(0.0)
                .collision_groups(ground_groups),
            ground_body,
            &mut world.bodies,
        );

        // Bodies at the spawn configuration (the multibody overwrites their poses from its
        // coordinates anyway), the trunk's at its centre of mass.
        let links = model.links();
        let spawn = model.spawn_state();
        let mut link_poses = vec![Isometry3::identity(); links.len()];
        model.link_poses(&spawn.trunk.pose, &spawn.q, &mut link_poses)?;
        let trunk_com = links[0].com;
        let shift = |i: usize| {
            if i == 0 {
                Isometry3::from(Translation3::from(trunk_com))
            } else {
                Isometry3::identity()
            }
        };
        let mut bodies = Vec::with_capacity(links.len());
        let mut collider_of: Vec<Vec<ColliderHandle>> = Vec::with_capacity(links.len());
        for (i, link) in links.iter().enumerate() {
            let com = if i == 0 { Vector3::zeros() } else { link.com };
            let inertia = Matrix::from_cols(
                to_vec(&link.inertia.column(0).into_owned()),
                to_vec(&link.inertia.column(1).into_owned()),
                to_vec(&link.inertia.column(2).into_owned()),
            );
            let mass =
                MassProperties::with_inertia_matrix(to_vec(&com), link.mass as Real, inertia);
            let handle = world.bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(to_pose(&(link_poses[i] * shift(i))))
                    .additional_mass_properties(mass)
                    .can_sleep(false)
                    .ccd_enabled(false),
            );
            let mut handles = Vec::with_capacity(link.collisions.len());
            for c in &link.collisions {
                let in_body = shift(i).inverse() * c.origin;
                let builder = match c.shape {
                    Shape::Box { half_extents } => ColliderBuilder::cuboid(
                        half_extents.x as Real,
                        half_extents.y as Real,
                        half_extents.z as Real,
                    )
                    .position(to_pose(&in_body)),
                    Shape::Sphere { radius } => {
                        ColliderBuilder::ball(radius as Real).position(to_pose(&in_body))
                    }
                    Shape::Capsule {
                        radius,
                        half_length,
                    } => ColliderBuilder::capsule_z(half_length as Real, radius as Real)
                        .position(to_pose(&in_body)),
                    Shape::Cylinder {
                        radius,
                        half_length,
                    } => {
                        // rapier's cylinder lies along y; turn y onto the model's z.
                        let y_to_z = UnitQuaternion::from_axis_angle(
                            &Vector3::x_axis(),
                            std::f64::consts::FRAC_PI_2,
                        );
                        ColliderBuilder::cylinder(half_length as Real, radius as Real)
                            .position(to_pose(&(in_body * y_to_z)))
                    }
                    ref other => {
                        return Err(backend_error(format!(
                            "link {:?}: unsupported shape {other:?}",
                            link.name
                        )));
                    }
                };
                handles.push(
                    world.colliders.insert_with_parent(
                        builder
                            .density(0.0)
                            .friction(friction)
                            .restitution(0.0)
                            .collision_groups(robot_groups),
                        handle,
                        &mut world.bodies,
                    ),
                );
            }
            // Mass properties are otherwise only folded in at the first step; the pristine
            // world and the multibody's kinematics need them now.
            world.bodies[handle].recompute_mass_properties_from_colliders(&world.colliders);
            bodies.push(handle);
            collider_of.push(handles);
        }

        // Joints, parents before children. Body frame = link frame · shift, so the joint frame
        // on the parent is shift⁻¹ · origin · (x onto axis), and on the child (x onto axis).
        let joints = model.joints();
        let mut joint_axes = vec![Vector::ZERO; joints.len()];
        for (i, link) in links.iter().enumerate().skip(1) {
            let Some(j) = link.parent_joint else {
                return Err(backend_error(format!(
                    "link {:?} has no parent joint",
                    link.name
                )));
            };
            let joint = &joints[j];
            let a = x_onto(&joint.axis);
            let frame1 = shift(joint.parent).inverse() * joint.origin * a;
            let frame2 = shift(i).inverse() * Isometry3::from_parts(Translation3::identity(), a);
            let data = GenericJointBuilder::new(JointAxesMask::LOCKED_REVOLUTE_AXES)
                .local_frame1(to_pose(&frame1))
                .local_frame2(to_pose(&frame2))
                .limits(JointAxis::AngX, [joint.lower as Real, joint.upper as Real])
                .contacts_enabled(false)
                .build();
            world
                .multibody_joints
                .insert(bodies[joint.parent], bodies[i], data, true)
                .ok_or_else(|| {
                    backend_error(format!("rapier refused joint {:?}", joint.urdf_name))
                })?;
            joint_axes[j] = to_vec(&(joint.origin.rotation * joint.axis.into_inner()));
        }

        let root_link = world
            .multibody_joints
            .rigid_body_link(bodies[0])
            .ok_or_else(|| backend_error("the trunk is not in a multibody".into()))?;
        let multibody = root_link.multibody;
        let mut joint_links = vec![0; joints.len()];
        for (j, joint) in joints.iter().enumerate() {
            let link = world
                .multibody_joints
                .rigid_body_link(bodies[joint.child])
                .ok_or_else(|| {
                    backend_error(format!(
                        "joint {:?} is not in the multibody",
                        joint.urdf_name
                    ))
                })?;
            if link.multibody != multibody {
                return Err(backend_error(format!(
                    "joint {:?} is in another multibody",
                    joint.urdf_name
                )));
            }
            joint_links[j] = link.id;
        }
        let mb = world
            .multibody_joints
            .get_multibody_mut(multibody)
            .ok_or_else(|| backend_error("the robot's multibody vanished".into()))?;
        if mb.root().rigid_body_handle() != bodies[0] {
            return Err(backend_error(
                "the trunk is not the multibody's root".into(),
            ));
        }
        mb.set_self_contacts_enabled(false);
        let mut joint_dofs = vec![0; joints.len()];
        for (j, &id) in joint_links.iter().enumerate() {
            let link = mb
                .link(id)
                .ok_or_else(|| backend_error(format!("multibody link {id} missing")))?;
            joint_dofs[j] = link.assembly_id();
        }
        // Joint damping from the model; none on the free root (rapier puts 0.1 on its rotation).
        mb.damping_mut().fill(0.0);
        for (j, &dof) in joint_dofs.iter().enumerate() {
            mb.damping_mut()[dof] = joints[j].damping as Real;
        }

        let tracked_colliders = model
            .tracked()
            .iter()
            .map(|t| t.shapes.iter().map(|&s| collider_of[t.link][s]).collect())
            .collect();

        let integration = IntegrationParameters {
            dt: params.dt as Real,
            num_solver_iterations: options.solver_iterations,
            static_contact_softness: SpringCoefficients::new(
                options.ground_contact_frequency as Real,
                options.ground_contact_damping_ratio as Real,
            ),
            normalized_prediction_distance: options.prediction_distance as Real,
            contact_recycling: false,
            max_ccd_substeps: 0,
            ..IntegrationParameters::default()
        };
        let gravity = Vector::new(
            params.gravity[0] as Real,
            params.gravity[1] as Real,
            params.gravity[2] as Real,
        );
        let n = joints.len();
        let mut backend = Self {
            pristine: world.clone(),
            world,
            model: Arc::clone(&model),
            params: params.clone(),
            options: options.clone(),
            integration,
            gravity,
            pipeline: PhysicsPipeline::new(),
            bodies,
            multibody,
            joint_links,
            joint_dofs,
            joint_axes,
            tracked_colliders,
            ground,
            trunk_com,
            torques: vec![0.0; n],
            body_torques: vec![Vector::ZERO; links.len()],
            contacts: vec![false; model.tracked().len()],
            joint_limits: joints
                .iter()
                .map(|j| [j.lower as Real, j.upper as Real])
                .collect(),
            gate_limits: true,
        };
        backend.apply_state(&spawn);
        Ok(backend)
    }

    fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    fn params(&self) -> &PhysicsParams {
        &self.params
    }

    fn apply_state(&mut self, state: &RobotState) {
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
    }

    fn apply_joint_torques(&mut self, torques: &[f64]) {
        self.torques.copy_from_slice(torques);
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
}
