//! [`DartBackend`]: the `hyq-physics` [`Backend`] trait on a DART 6.12 world.
//!
//! The DART skeleton is built from the shared [`RobotModel`] body by body (mass, centre of mass,
//! inertia tensor, joint frame, axis, limits, damping, primitive collision shapes), so DART and
//! every other backend simulate the same robot by construction. The torques come from the
//! shared actuator ([`hyq_physics::pd_substep`]); DART adds none of its own.
//!
//! Per-episode dynamics ([`Backend::apply_dynamics`]) are set in place on the DART world: the
//! friction of every shape node, the ground's included (DART takes the smaller of a contact's
//! two), each body node's inertia, each joint's damping; the root body's frame sits at its
//! centre of mass, so a moved centre of mass moves the root's shape and child-joint frames
//! with it, exactly as the build places them (a world given dynamics runs bit for bit as one
//! built with them). A push adds to the free joint's velocity.

use std::sync::Arc;

use hyq_physics::na::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use hyq_physics::{
    Backend, Dynamics, HeightGrid, Link, MassProperties, PhysicsError, PhysicsParams, RobotModel,
    RobotState, Shape, Terrain, TrunkState,
};
use serde::{Deserialize, Serialize};

use crate::error::DartError;
use crate::sim::{
    BaseState, BodyDesc, Inertial, JointKind, Pose, ShapeDesc, ShapeKind, Sim, WorldDesc,
};

/// Half the side (m) of the square ground box whose top face is the plane z = 0. Bullet works in
/// single precision, and its contact geometry for a box loses precision in proportion to the
/// box's size, so the ground is large enough for any episode (an episode of 1000 env steps lasts
/// 10 s, in which HyQ covers well under 50 m) but no larger.
pub const GROUND_HALF_EXTENT_M: f64 = 100.0;

/// DART-specific settings (`[physics.dart]`). The collision detector (Bullet), the LCP solver
/// (Dantzig) and DART's contact and joint-limit constraint parameters (its defaults) are fixed;
/// see the crate's README for why.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DartOptions {
    /// Lay every contact's friction pyramid along the world's x and y axes (each shape's
    /// first friction direction is world x) (default: false, DART's own choice). DART bounds
    /// friction along two tangent directions separately; by default it builds them from the
    /// contact normal, which for a foot on flat ground is tilted by rounding in a direction
    /// that varies from contact to contact, so a sliding foot feels anywhere between μN and
    /// √2 μN. With world axes it feels μN along x or y, as Coulomb friction says, and √2 μN
    /// along the diagonals (docs/backend-comparison.md, "Contact audit").
    pub world_friction_axes: bool,
}

/// A tracked collision shape, for the geometric half of the contact test.
#[derive(Debug, Clone)]
struct TrackedShape {
    tracked: usize,
    link: usize,
    origin: Isometry3<f64>,
    shape: Shape,
}

/// One HyQ (or any [`RobotModel`]) on flat ground in its own DART world.
///
/// `Send` (worlds can move between threads, and several worlds can step on several threads at
/// once) but not `Sync`.
#[derive(Debug)]
pub struct DartBackend {
    sim: Sim,
    model: Arc<RobotModel>,
    params: PhysicsParams,
    tracked_shapes: Vec<TrackedShape>,
    /// Body poses after the last step or state change, 7 values per body (model link order).
    poses: Vec<f64>,
    /// Contact flags of the last step.
    contacts: Vec<bool>,
    /// Scratch for the finiteness check after a step.
    q: Vec<f64>,
    qd: Vec<f64>,
    /// Set when the world cannot be stepped until the next state change (a failed state change
    /// or a diverged step).
    blocked: Option<String>,
    /// Set when DART refused dynamics (which were validated, so unexpectedly): the world
    /// cannot be stepped until dynamics are given again.
    refused_dynamics: Option<String>,
    /// The ground the world holds.
    terrain: Terrain,
}

fn backend_error(message: String) -> PhysicsError {
    PhysicsError::Backend {
        backend: DartBackend::NAME,
        message,
    }
}

impl From<DartError> for PhysicsError {
    fn from(e: DartError) -> Self {
        backend_error(e.to_string())
    }
}

fn pose(iso: &Isometry3<f64>) -> Pose {
    let t = iso.translation.vector;
    let q = iso.rotation.quaternion();
    Pose {
        translation: [t.x, t.y, t.z],
        rotation: [q.w, q.i, q.j, q.k],
    }
}

/// The bridge's description of `model`: bodies in model order (parents first), shapes with the
/// tracked body they report to.
fn describe(
    model: &RobotModel,
    params: &PhysicsParams,
    options: &DartOptions,
) -> Result<(Vec<BodyDesc>, Vec<ShapeDesc>, WorldDesc), PhysicsError> {
    let mut tracked_of = std::collections::HashMap::new();
    for (t, body) in model.tracked().iter().enumerate() {
        for &s in &body.shapes {
            if let Some(other) = tracked_of.insert((body.link, s), t) {
                return Err(backend_error(format!(
                    "collision {s} of link {} belongs to two tracked bodies ({} and {})",
                    model.links()[body.link].name,
                    model.tracked()[other].name,
                    body.name
                )));
            }
        }
    }

    let mut bodies = Vec::with_capacity(model.num_links());
    let mut shapes = Vec::new();
    for (i, link) in model.links().iter().enumerate() {
        bodies.push(body_desc(model, link)?);

        for (s, collision) in link.collisions.iter().enumerate() {
            let (kind, size) = match collision.shape {
                Shape::Box { half_extents } => (
                    ShapeKind::Box,
                    [half_extents.x, half_extents.y, half_extents.z],
                ),
                Shape::Sphere { radius } => (ShapeKind::Sphere, [radius, 0.0, 0.0]),
                Shape::Capsule {
                    radius,
                    half_length,
                } => (ShapeKind::Capsule, [radius, half_length, 0.0]),
                Shape::Cylinder {
                    radius,
                    half_length,
                } => (ShapeKind::Cylinder, [radius, half_length, 0.0]),
                // `Shape` is non-exhaustive: a shape added to the model later must be mapped
                // here before DART can simulate it.
                #[allow(unreachable_patterns)]
                ref other => {
                    return Err(backend_error(format!(
                        "link {}: collision shape {other:?} is not supported by the DART backend",
                        link.name
                    )));
                }
            };
            shapes.push(ShapeDesc {
                body: u32::try_from(i)
                    .map_err(|_| backend_error(format!("link index {i} too large")))?,
                kind,
                size,
                pose: pose(&collision.origin),
                tracked: tracked_of
                    .get(&(i, s))
                    .map_or(-1, |&t| i32::try_from(t).unwrap_or(i32::MAX)),
            });
        }
    }
    let world = WorldDesc {
        dt: params.dt,
        gravity: params.gravity,
        friction: params.ground_friction,
        restitution: 0.0,
        world_friction_axes: options.world_friction_axes,
        ground_height: 0.0,
        ground_half_extent: GROUND_HALF_EXTENT_M,
        num_tracked: u32::try_from(model.tracked().len())
            .map_err(|_| backend_error("too many tracked bodies".into()))?,
    };
    Ok((bodies, shapes, world))
}

/// The bridge's description of one body (`link`) and the joint to its parent (free for the
/// root).
fn body_desc(model: &RobotModel, link: &Link) -> Result<BodyDesc, PhysicsError> {
    let i3 = link.inertia;
    let mut body = BodyDesc {
        name: link.name.clone(),
        parent: -1,
        joint_kind: JointKind::Free,
        joint_name: format!("{}_free", link.name),
        joint_index: 0,
        joint_origin: Pose::IDENTITY,
        axis: [0.0; 3],
        lower: 0.0,
        upper: 0.0,
        damping: 0.0,
        mass: link.mass,
        com: [link.com.x, link.com.y, link.com.z],
        inertia: [
            i3[(0, 0)],
            i3[(1, 1)],
            i3[(2, 2)],
            i3[(0, 1)],
            i3[(0, 2)],
            i3[(1, 2)],
        ],
    };
    match (link.parent, link.parent_joint) {
        (None, _) => {}
        (Some(parent), Some(j)) => {
            let joint = &model.joints()[j];
            body.parent = i32::try_from(parent).map_err(|_| {
                backend_error(format!(
                    "link {}: parent index {parent} too large",
                    link.name
                ))
            })?;
            body.joint_kind = JointKind::Revolute;
            body.joint_name = joint.urdf_name.clone();
            body.joint_index = u32::try_from(j)
                .map_err(|_| backend_error(format!("joint {}: index {j} too large", joint.name)))?;
            body.joint_origin = pose(&joint.origin);
            body.axis = [joint.axis.x, joint.axis.y, joint.axis.z];
            body.lower = joint.lower;
            body.upper = joint.upper;
            body.damping = joint.damping;
        }
        (Some(_), None) => {
            return Err(backend_error(format!(
                "link {} has a parent but no actuated joint",
                link.name
            )));
        }
    }
    Ok(body)
}

fn base_state(trunk: &TrunkState) -> BaseState {
    let t = trunk.pose.translation.vector;
    let q = trunk.pose.rotation.quaternion();
    BaseState {
        position: [t.x, t.y, t.z],
        orientation: [q.w, q.i, q.j, q.k],
        linear_velocity: [trunk.linvel.x, trunk.linvel.y, trunk.linvel.z],
        angular_velocity: [trunk.angvel.x, trunk.angvel.y, trunk.angvel.z],
    }
}

fn isometry(p: &[f64]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::new_normalize(Quaternion::new(p[3], p[4], p[5], p[6])),
    )
}

impl DartBackend {
    /// Why the trunk is off the ground, if it is: beyond the flat ground box, or outside the
    /// height field's rectangle (there is no ground beyond either).
    fn off_ground(&self) -> Option<String> {
        let (x, y) = (self.poses[0], self.poses[1]);
        match &self.terrain {
            Terrain::Flat if x.abs().max(y.abs()) > GROUND_HALF_EXTENT_M => Some(format!(
                "the trunk left DART's ground at ({x:.1}, {y:.1}) m (the ground ends at \
                 ±{GROUND_HALF_EXTENT_M} m in x and y)"
            )),
            Terrain::Field(grid) if !grid.contains(x, y) => {
                let [x0, y0] = grid.origin();
                let [sx, sy] = grid.size();
                Some(format!(
                    "the trunk left DART's ground at ({x:.1}, {y:.1}) m (the height field spans \
                     x {x0:.1} .. {:.1} m, y {y0:.1} .. {:.1} m)",
                    x0 + sx,
                    y0 + sy
                ))
            }
            _ => None,
        }
    }

    /// Touching or penetrating contact points in the last step (all robot shapes, tracked or
    /// not).
    pub fn num_contact_points(&self) -> usize {
        self.sim.num_contacts()
    }

    /// Simulated time since the last state change (s), as DART counts it.
    pub fn time(&self) -> f64 {
        self.sim.time()
    }

    /// Gives the DART world `d`'s friction, restitution, mass properties and damping. DART
    /// takes the product of a contact's two restitution coefficients, so every shape holds
    /// √e for a contact's to be e.
    fn give_dynamics(&mut self, d: &Dynamics) -> Result<(), DartError> {
        self.sim.set_friction(d.ground_friction)?;
        self.sim.set_restitution(d.contact.restitution.sqrt())?;
        for (i, b) in d.bodies.iter().enumerate() {
            let t = b.inertia;
            let inertial = Inertial {
                mass: b.mass,
                com: [b.com.x, b.com.y, b.com.z],
                inertia: [
                    t[(0, 0)],
                    t[(1, 1)],
                    t[(2, 2)],
                    t[(0, 1)],
                    t[(0, 2)],
                    t[(1, 2)],
                ],
            };
            self.sim.set_inertial(i, &inertial)?;
        }
        for (j, &damping) in d.joint_damping.iter().enumerate() {
            self.sim.set_joint_damping(j, damping)?;
        }
        Ok(())
    }

    /// Re-reads the body poses the contact test and [`Backend::link_poses`] use.
    fn refresh_poses(&mut self) {
        self.sim.body_poses(&mut self.poses);
    }

    /// Names the first joint whose angle or speed is not finite, or else the trunk, after a
    /// step the bridge reported as diverged. Reads only joint values: DART would abort on
    /// anything that computes a transform from this state.
    fn diverged_quantity(&mut self) -> String {
        self.sim.joint_positions(&mut self.q);
        self.sim.joint_velocities(&mut self.qd);
        let joints = self.model.joints();
        if let Some(i) = self.q.iter().position(|v| !v.is_finite()) {
            return format!("angle of joint {}", joints[i].name);
        }
        if let Some(i) = self.qd.iter().position(|v| !v.is_finite()) {
            return format!("speed of joint {}", joints[i].name);
        }
        "trunk pose or velocity (or a value beyond the bridge's sanity bound of 1e8)".into()
    }

    /// Sets the contact flags of the step just taken: a tracked shape touched the ground if it
    /// touched or penetrated it in the contacts DART's solver used in this step (taken before
    /// the step moved the bodies), or if it ends the step within `contact_distance` of the
    /// ground.
    fn update_contacts(&mut self) {
        self.sim.contacts(&mut self.contacts);
        for t in &self.tracked_shapes {
            if self.contacts[t.tracked] {
                continue;
            }
            let body = isometry(&self.poses[7 * t.link..7 * t.link + 7]);
            if self
                .terrain
                .within(&t.shape, &(body * t.origin), self.params.contact_distance)
            {
                self.contacts[t.tracked] = true;
            }
        }
    }
}

impl Backend for DartBackend {
    type Options = DartOptions;
    const NAME: &'static str = "dart";

    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &Self::Options,
    ) -> Result<Self, PhysicsError> {
        params.validate()?;
        let (bodies, shapes, world) = describe(&model, params, options)?;
        let sim = Sim::new(&bodies, &shapes, &world)?;
        let tracked_shapes = model
            .tracked()
            .iter()
            .enumerate()
            .flat_map(|(t, body)| {
                let link = &model.links()[body.link];
                body.shapes.iter().map(move |&s| TrackedShape {
                    tracked: t,
                    link: body.link,
                    origin: link.collisions[s].origin,
                    shape: link.collisions[s].shape.clone(),
                })
            })
            .collect();
        let n = model.num_joints();
        let mut backend = Self {
            sim,
            tracked_shapes,
            poses: vec![0.0; 7 * model.num_links()],
            contacts: vec![false; model.tracked().len()],
            q: vec![0.0; n],
            qd: vec![0.0; n],
            params: params.clone(),
            blocked: None,
            refused_dynamics: None,
            terrain: Terrain::Flat,
            model,
        };
        let spawn = backend.model.spawn_state();
        backend.set_state(&spawn)?;
        Ok(backend)
    }

    fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    fn params(&self) -> &PhysicsParams {
        &self.params
    }

    fn apply_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        self.contacts.fill(false);
        let result = self
            .sim
            .set_state(&base_state(&state.trunk), &state.q, &state.qd);
        // A state DART refuses after validation leaves the world unusable: it refuses to step
        // until a state is given that DART takes.
        self.blocked = result
            .as_ref()
            .err()
            .map(|e| format!("the last set_state failed: {e}"));
        self.refresh_poses();
        Ok(result?)
    }

    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        Ok(self.sim.set_joint_torques(torques)?)
    }

    fn step(&mut self) -> Result<(), PhysicsError> {
        if let Some(reason) = &self.refused_dynamics {
            return Err(backend_error(format!(
                "{reason}; call set_dynamics before stepping again"
            )));
        }
        if let Some(reason) = &self.blocked {
            return Err(backend_error(format!(
                "{reason}; call set_state before stepping again"
            )));
        }
        if !self.sim.step()? {
            let what = self.diverged_quantity();
            self.blocked = Some(format!("the simulation diverged ({what} is not finite)"));
            self.contacts.fill(false);
            return Err(PhysicsError::Diverged { what });
        }
        self.refresh_poses();
        if let Some(reason) = self.off_ground() {
            self.blocked = Some(reason.clone());
            return Err(backend_error(reason));
        }
        self.update_contacts();
        Ok(())
    }

    fn joint_positions(&self, out: &mut [f64]) {
        self.sim.joint_positions(out);
    }

    fn joint_velocities(&self, out: &mut [f64]) {
        self.sim.joint_velocities(out);
    }

    fn trunk(&self) -> TrunkState {
        let b = self.sim.base_state();
        let p = [
            b.position[0],
            b.position[1],
            b.position[2],
            b.orientation[0],
            b.orientation[1],
            b.orientation[2],
            b.orientation[3],
        ];
        TrunkState {
            pose: isometry(&p),
            linvel: Vector3::from(b.linear_velocity),
            angvel: Vector3::from(b.angular_velocity),
        }
    }

    fn contacts(&self, out: &mut [bool]) {
        out.copy_from_slice(&self.contacts);
    }

    fn link_poses(&self, out: &mut [Isometry3<f64>]) {
        assert_eq!(
            out.len(),
            self.model.num_links(),
            "link_poses: one pose per body"
        );
        for (i, o) in out.iter_mut().enumerate() {
            *o = isometry(&self.poses[7 * i..7 * i + 7]);
        }
    }

    fn total_mass(&self) -> f64 {
        self.sim.total_mass()
    }

    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        let c = &dynamics.contact;
        if c.contact_stiffness_scale != 1.0 || c.contact_damping_scale != 1.0 {
            // Refused before anything is given, so the world keeps its dynamics.
            return Err(PhysicsError::Backend {
                backend: Self::NAME,
                message: format!(
                    "randomize.contact_stiffness_scale / contact_damping_scale drew {} / {}, but \
                     DART 6.12's contact is rigid (an LCP): its only softness settings, the \
                     error reduction and constraint force mixing, are process-wide, and mapped \
                     onto them as a spring-damper the factors change only how fast a \
                     penetration is undone, not the depth at rest",
                    c.contact_stiffness_scale, c.contact_damping_scale
                ),
            });
        }
        let result = self.give_dynamics(dynamics);
        // Dynamics DART refuses after validation may be half given: the world refuses to step
        // until dynamics it takes are given.
        self.refused_dynamics = result
            .as_ref()
            .err()
            .map(|e| format!("DART refused the dynamics: {e}"));
        Ok(result?)
    }

    fn body_mass_properties(&self, link: usize) -> MassProperties {
        let i = self.sim.inertial(link);
        let [ixx, iyy, izz, ixy, ixz, iyz] = i.inertia;
        MassProperties {
            mass: i.mass,
            com: Vector3::from(i.com),
            inertia: hyq_physics::na::Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz),
        }
    }

    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        Ok(self.sim.add_base_velocity([dv.x, dv.y, dv.z])?)
    }

    fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        let state = self.state();
        match terrain {
            Terrain::Flat => self.sim.set_ground_flat()?,
            Terrain::Field(grid) => {
                let (heights, width, depth, spacing, pose) = heightmap(grid);
                self.sim
                    .set_ground_heights(&heights, width, depth, spacing, &pose)?;
            }
        }
        self.terrain = terrain.clone();
        self.apply_state(&state)
    }
}

/// DART's height field of `grid`: its matrix (row after row), width, depth, spacing and pose.
///
/// DART hands Bullet the matrix with its rows reversed (Bullet's row `j` is DART's row
/// `depth − 1 − j`), Bullet lays row `j` along its local y and a row's values along its local x,
/// centred on the shape's frame, and splits each cell between its corners (x+1, j) and
/// (x, j+1) (the split the bridge puts back, see `SplitAlikeBulletDetector` in `hyq_dart.cc`). Turned a quarter
/// turn about +z, local x runs along world +y and local y along world −x: DART's row `r` is then
/// the grid's column `r`, a row's `k`-th value the grid's row `k`, and Bullet's split the grid's
/// (x₀, y₀)–(x₁, y₁) diagonal, the split every backend uses. So the matrix is the grid
/// transposed.
fn heightmap(grid: &HeightGrid) -> (Vec<f32>, usize, usize, [f64; 2], crate::sim::Pose) {
    let (columns, rows) = (grid.columns(), grid.rows());
    let mut heights = Vec::with_capacity(columns * rows);
    for c in 0..columns {
        for k in 0..rows {
            heights.push(grid.height(c, k) as f32);
        }
    }
    let [dx, dy] = grid.spacing();
    let [cx, cy] = grid.center();
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
    let pose = pose(&Isometry3::from_parts(Translation3::new(cx, cy, 0.0), turn));
    (heights, rows, columns, [dy, dx], pose)
}

#[cfg(test)]
mod tests {
    //! `[physics.dart]` parses from TOML: empty is the default, anything else is refused by
    //! name.
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn leaving_the_ground_box_is_an_error_not_a_silent_fall() {
        let model = hyq_physics::bundled::hyq();
        let mut b = DartBackend::build(
            model.clone(),
            &PhysicsParams::default(),
            &DartOptions::default(),
        )
        .unwrap();
        let mut state = model.spawn_state();
        state.trunk.pose.translation.x = GROUND_HALF_EXTENT_M - 0.5;
        b.set_state(&state).unwrap();
        b.step().unwrap();
        state.trunk.pose.translation.x = GROUND_HALF_EXTENT_M + 0.5;
        b.set_state(&state).unwrap();
        let err = b.step().unwrap_err().to_string();
        assert!(err.contains("left DART's ground"), "{err}");
        let err = b.step().unwrap_err().to_string();
        assert!(err.contains("call set_state"), "{err}");
        b.set_state(&model.spawn_state()).unwrap();
        b.step().unwrap();
    }

    #[test]
    fn options_parse_empty_and_reject_unknown_fields() {
        assert_eq!(
            toml::from_str::<DartOptions>("").unwrap(),
            DartOptions::default()
        );
        let err = toml::from_str::<DartOptions>("detector = \"ode\"")
            .unwrap_err()
            .to_string();
        assert!(err.contains("detector"), "{err}");
        assert!(
            toml::from_str::<DartOptions>("world_friction_axes = true")
                .unwrap()
                .world_friction_axes
        );
    }
}
