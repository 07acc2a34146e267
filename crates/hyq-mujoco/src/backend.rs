//! [`MujocoBackend`]: the `hyq-physics` [`Backend`] trait on a MuJoCo 4.0 world.
//!
//! The world is compiled from the MJCF that [`hyq_formats::mjcf`] writes for the shared
//! [`RobotModel`] (same bodies, masses, inertias, joint frames, limits, damping and shapes as
//! every other backend), without actuators: the shared PD actuator
//! ([`hyq_physics::pd_substep`]) computes the joint torques, and the backend writes them into
//! MuJoCo's applied generalized forces for one step.
//!
//! Per-episode dynamics ([`Backend::apply_dynamics`]) are written into `mjModel` in place:
//! every geom's sliding friction (MuJoCo takes the larger of a contact's two, so the ground's
//! is set too, whatever its shape), every geom's contact `solref` for the drawn contact
//! stiffness and damping factors and restitution (the damping ratio whose bounce is e,
//! [`crate::restitution`]), each joint's damping, and each body's mass, centre of
//! mass and principal inertia (diagonalised by MuJoCo's own `mju_eig3`, as its compiler does);
//! then `mj_setConst` recomputes what MuJoCo derives from masses. A body given the model's own
//! values gets MuJoCo's compiled ones back bit for bit. A push adds to the free joint's
//! velocity and recomputes the velocity-dependent terms (`mj_step1`), keeping the contacts and
//! the warm start.

use std::sync::Arc;

use hyq_formats::mjcf::{Actuators, Mjcf, MjcfOptions, to_mjcf};
use hyq_physics::na::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use hyq_physics::{
    Backend, Dynamics, MassProperties, PhysicsError, PhysicsParams, RobotModel, RobotState,
    Terrain, TrunkState,
};

use crate::error::MujocoError;
use crate::options::MujocoOptions;
use crate::restitution::damping_ratio_for_restitution;
use crate::world::{Layout, StepError, World};

fn backend_error(message: String) -> PhysicsError {
    PhysicsError::Backend {
        backend: MujocoBackend::NAME,
        message,
    }
}

impl From<MujocoError> for PhysicsError {
    fn from(e: MujocoError) -> Self {
        backend_error(e.to_string())
    }
}

/// The MJCF the backend compiles for `model` under `params` and `options` on flat ground (no
/// actuators: the backend applies the shared actuator's torques itself). Useful to inspect, or
/// to load the same world in MuJoCo from elsewhere.
pub fn world_mjcf(
    model: &RobotModel,
    params: &PhysicsParams,
    options: &MujocoOptions,
) -> Result<Mjcf, PhysicsError> {
    world_mjcf_on(model, params, options, &Terrain::Flat)
}

/// [`world_mjcf`] on `terrain`: the MJCF the backend compiles once given that ground.
pub fn world_mjcf_on(
    model: &RobotModel,
    params: &PhysicsParams,
    options: &MujocoOptions,
    terrain: &Terrain,
) -> Result<Mjcf, PhysicsError> {
    params.validate()?;
    options.validate()?;
    let mjcf_options = MjcfOptions {
        actuators: Actuators::None,
        solver: options.clone(),
        autoreset: false,
        terrain: terrain.clone(),
        ..MjcfOptions::from_params(params)
    };
    to_mjcf(model, &mjcf_options).map_err(|e| backend_error(e.to_string()))
}

/// The layout the shim looks up in a compiled [`Mjcf`] of `model`.
pub fn layout(model: &RobotModel, mjcf: &Mjcf) -> Layout {
    let tracked_geoms = model
        .tracked()
        .iter()
        .enumerate()
        .flat_map(|(t, body)| {
            body.shapes
                .iter()
                .map(move |&s| (mjcf.geoms[body.link][s].clone(), t))
        })
        .collect();
    Layout {
        joints: mjcf.joints.clone(),
        bodies: mjcf.bodies.clone(),
        num_tracked: model.tracked().len(),
        tracked_geoms,
        actuators: mjcf.actuators.clone(),
    }
}

fn isometry(p: &[f64; 7]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::new_normalize(Quaternion::new(p[3], p[4], p[5], p[6])),
    )
}

/// One HyQ (or any [`RobotModel`]) on flat ground or a height field in its own MuJoCo world.
///
/// `Send` (worlds can move between threads, and several worlds can step on several threads at
/// once) but not `Sync`.
#[derive(Debug)]
pub struct MujocoBackend {
    world: World,
    model: Arc<RobotModel>,
    params: PhysicsParams,
    /// Contact flags of the last step, as the shim writes them and as reported.
    contact_bytes: Vec<u8>,
    contacts: Vec<bool>,
    /// Set when the world cannot be stepped until the next state change (a failed state change
    /// or a failed step).
    blocked: Option<String>,
    /// Set when MuJoCo refused dynamics (which were validated, so unexpectedly): the world
    /// cannot be stepped until dynamics are given again.
    refused_dynamics: Option<String>,
    /// The dynamics last given ([`Backend::apply_dynamics`]), which a new ground keeps;
    /// `None` while the world has the model's.
    dynamics: Option<Dynamics>,
    /// The solver settings the world was compiled with.
    options: MujocoOptions,
    /// The ground the world holds.
    terrain: Terrain,
}

impl MujocoBackend {
    /// Gives the compiled world the dynamics `dynamics` (see [`Backend::apply_dynamics`]).
    /// Dynamics MuJoCo refuses after validation may be half given: the world then refuses to
    /// step until dynamics it takes are given.
    fn give_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        let contact = &dynamics.contact;
        // A body whose values are the model's own gets MuJoCo's compiled values back bit for
        // bit (MuJoCo diagonalised the tensor when it compiled the model).
        let nominal: Vec<bool> = dynamics
            .bodies
            .iter()
            .zip(self.model.links())
            .map(|(b, l)| b.mass == l.mass && b.com == l.com && b.inertia == l.inertia)
            .collect();
        let bodies: Vec<[f64; 10]> = dynamics
            .bodies
            .iter()
            .map(|b| {
                let i = b.inertia;
                [
                    b.mass,
                    b.com.x,
                    b.com.y,
                    b.com.z,
                    i[(0, 0)],
                    i[(1, 1)],
                    i[(2, 2)],
                    i[(0, 1)],
                    i[(0, 2)],
                    i[(1, 2)],
                ]
            })
            .collect();
        let result = self.world.set_dynamics(
            dynamics.ground_friction,
            [
                contact.contact_stiffness_scale,
                contact.contact_damping_scale,
                // No restitution drawn keeps MuJoCo's own damping ratio.
                if contact.restitution > 0.0 {
                    damping_ratio_for_restitution(contact.restitution)
                } else {
                    0.0
                },
            ],
            &nominal,
            &bodies,
            &dynamics.joint_damping,
        );
        self.refused_dynamics = result
            .as_ref()
            .err()
            .map(|e| format!("MuJoCo refused the dynamics: {e}"));
        Ok(result?)
    }

    /// Contacts in MuJoCo's current list whose shapes touch or penetrate the ground (all robot
    /// shapes, tracked or not).
    pub fn num_touching(&self) -> usize {
        self.world.num_touching()
    }

    /// Simulated time since the last state change (s), as MuJoCo counts it.
    pub fn time(&self) -> f64 {
        self.world.time()
    }
}

impl Backend for MujocoBackend {
    type Options = MujocoOptions;
    const NAME: &'static str = "mujoco";

    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &Self::Options,
    ) -> Result<Self, PhysicsError> {
        let mjcf = world_mjcf(&model, params, options)?;
        let world = World::new(&mjcf.xml, &layout(&model, &mjcf))?;
        let tracked = model.tracked().len();
        let mut backend = Self {
            world,
            contact_bytes: vec![0; tracked],
            contacts: vec![false; tracked],
            params: params.clone(),
            blocked: None,
            refused_dynamics: None,
            dynamics: None,
            options: options.clone(),
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
        let t = &state.trunk;
        let p = t.pose.translation.vector;
        let r = t.pose.rotation;
        let q = r.quaternion();
        // MuJoCo's free joint: angular velocity in the body's axes.
        let w = r.inverse() * t.angvel;
        let pose = [p.x, p.y, p.z, q.w, q.i, q.j, q.k];
        let vel = [t.linvel.x, t.linvel.y, t.linvel.z, w.x, w.y, w.z];
        let result = self.world.set_state(&pose, &vel, &state.q, &state.qd);
        // A state MuJoCo refuses after validation leaves the world unusable: it refuses to
        // step until a state is given that MuJoCo takes.
        self.blocked = result
            .as_ref()
            .err()
            .map(|e| format!("the last set_state failed: {e}"));
        Ok(result?)
    }

    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        self.world.set_joint_torques(torques);
        Ok(())
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
        match self.world.step(&mut self.contact_bytes) {
            Ok(()) => {
                for (flag, &byte) in self.contacts.iter_mut().zip(&self.contact_bytes) {
                    *flag = byte != 0;
                }
                Ok(())
            }
            Err(e) => {
                self.contacts.fill(false);
                Err(match e {
                    StepError::Diverged(what) => {
                        self.blocked = Some(format!("the simulation diverged ({what})"));
                        PhysicsError::Diverged { what }
                    }
                    StepError::Failed(message) => {
                        self.blocked = Some(message.clone());
                        backend_error(message)
                    }
                })
            }
        }
    }

    fn joint_positions(&self, out: &mut [f64]) {
        self.world.joint_positions(out);
    }

    fn joint_velocities(&self, out: &mut [f64]) {
        self.world.joint_velocities(out);
    }

    fn trunk(&self) -> TrunkState {
        let (pose, vel) = self.world.root_state();
        let pose = isometry(&pose);
        TrunkState {
            linvel: Vector3::new(vel[0], vel[1], vel[2]),
            angvel: pose.rotation * Vector3::new(vel[3], vel[4], vel[5]),
            pose,
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
            *o = isometry(&self.world.body_pose(i));
        }
    }

    fn total_mass(&self) -> f64 {
        self.world.total_mass()
    }

    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        self.give_dynamics(dynamics)?;
        self.dynamics = Some(dynamics.clone());
        Ok(())
    }

    fn body_mass_properties(&self, link: usize) -> MassProperties {
        let v = self.world.body_inertial(link);
        MassProperties {
            mass: v[0],
            com: Vector3::new(v[1], v[2], v[3]),
            inertia: hyq_physics::na::Matrix3::new(
                v[4], v[7], v[8], v[7], v[5], v[9], v[8], v[9], v[6],
            ),
        }
    }

    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        Ok(self.world.add_root_velocity(&[dv.x, dv.y, dv.z])?)
    }

    fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        // MuJoCo's height field is part of the compiled model: the world is compiled anew
        // from the MJCF on the new ground, given the dynamics it had, and the robot put back
        // where it was.
        let state = self.state();
        let mjcf = world_mjcf_on(&self.model, &self.params, &self.options, terrain)?;
        self.world = World::new(&mjcf.xml, &layout(&self.model, &mjcf))?;
        self.terrain = terrain.clone();
        if let Some(d) = self.dynamics.clone() {
            self.give_dynamics(&d)?;
        }
        self.apply_state(&state)
    }
}

#[cfg(test)]
mod tests {
    //! Which shapes report contacts: each foot only through its own shape (a shin on the
    //! ground is not a foot contact), the trunk through its shapes, nothing else.
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn only_tracked_shapes_report_contacts_each_to_its_own_flag() {
        let model = hyq_physics::bundled::hyq();
        let mjcf =
            world_mjcf(&model, &PhysicsParams::default(), &MujocoOptions::default()).unwrap();
        let l = layout(&model, &mjcf);
        let mut expected = Vec::new();
        for (t, body) in model.tracked().iter().enumerate() {
            for &s in &body.shapes {
                expected.push((mjcf.geoms[body.link][s].clone(), t));
            }
        }
        assert_eq!(l.tracked_geoms, expected);
        let names: Vec<&str> = l.tracked_geoms.iter().map(|(n, _)| n.as_str()).collect();
        // The bundled HyQ: four foot spheres, then the trunk box.
        assert_eq!(names, ["lf_foot", "lh_foot", "rf_foot", "rh_foot", "trunk"]);
        let untracked: usize = model
            .links()
            .iter()
            .map(|l| l.collisions.len())
            .sum::<usize>()
            - names.len();
        assert_eq!(untracked, 8, "thighs and shins report nothing");
        assert_eq!(l.num_tracked, model.num_feet() + 1);
        assert!(
            l.actuators.is_empty(),
            "the backend's world has no actuator"
        );
    }
}
