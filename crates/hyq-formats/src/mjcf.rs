//! The robot as MuJoCo's XML model format (MJCF), generated from a [`RobotModel`]: pure text,
//! no MuJoCo needed.
//!
//! One generator serves every place that hands the robot to MuJoCo (the `hyq-mujoco` backend,
//! a MuJoCo-from-Python benchmark, a user's own MuJoCo scripts), so they all simulate the model
//! every other backend simulates: the same bodies (fixed links already lumped), masses, centres
//! of mass, full inertia tensors, joint frames, axes, position limits and damping, the same
//! primitive collision shapes, one Coulomb friction coefficient, robot shapes that touch only
//! the ground (no self-collision) and the ground: an infinite plane at z = 0, or one height
//! field ([`MjcfOptions::terrain`]).
//!
//! What the generator writes, element by element:
//! - `<compiler>`: radians; inertias taken only from the `<inertial>` elements (never from the
//!   shapes), no mass or inertia bounds, no rebalancing, no fusing of bodies;
//! - `<option>`: the time step, gravity and the solver settings of [`MujocoOptions`];
//! - `<default>`: every robot shape has `contype="1" conaffinity="0"` and the ground
//!   `contype="0" conaffinity="1"`, so robot shapes collide with the ground and never with each
//!   other; `condim="3"` (sliding friction, no torsional or rolling friction); the friction
//!   coefficient; the contact `solref`/`solimp`; `margin="0"` and `gap` = the contact detection
//!   distance, so MuJoCo lists a contact up to that distance apart but pushes only on touch
//!   (MuJoCo 4.0's meaning of the two; MuJoCo 3 read them differently and would let shapes sink
//!   by `gap` before pushing: the text is written for MuJoCo 4.0);
//! - `<asset>`, over a height field only: the `<hfield>` `terrain`, the grid's heights written
//!   inline (`elevation`, rows from the far edge, highest y, to the near one; each scaled to
//!   [0, 1] between the grid's lowest and highest height, which MuJoCo requires), `size` its
//!   half sides, its height range and a 1 m base below its lowest point;
//! - `<worldbody>`: the ground (a plane, or a geom of type `hfield` at the grid's centre and
//!   lowest height, so that MuJoCo's prisms span the grid's heights), then the trunk with a `<freejoint/>` at its spawn pose and
//!   the rest of the tree below it, each body at its joint frame with one `hinge` joint (`axis`,
//!   `range`, `damping`, and `armature` when the model has one: an MJCF robot's), an
//!   `<inertial>` (`pos`, `mass`, `fullinertia`) and its shapes (`box`,
//!   `sphere`, `capsule`, `cylinder`: MuJoCo's sizes are half-lengths along the shape's z, as in
//!   [`Shape`]);
//! - `<actuator>`: by [`Actuators`]: none (the caller writes joint torques itself, e.g. into
//!   `mjData.qfrc_applied`), `<motor>`s (control = joint torque, clamped to the effort limit),
//!   or `<position>` servos (MuJoCo runs the PD law `kp (q* − q) − kd q̇` with the model's gains,
//!   clamped to the effort limit);
//! - `<keyframe>`: `spawn`, the model's spawn state ([`RobotModel::spawn_state`]).
//!
//! Joint Coulomb friction (the URDF's `<dynamics friction>`) is not written: the joints keep
//! MuJoCo's `frictionloss="0"`. In the project every backend leaves joint friction to the
//! shared actuator ([`hyq_physics::actuator`]), which adds it to the joint torques it computes, so a
//! model that also had MuJoCo apply it would count it twice. A user who simulates the written
//! model on its own (with `<position>` or `<motor>` actuators) gets no joint friction; the
//! bundled robots' URDFs give none (`friction="0"`).
//!
//! Names: bodies carry their URDF link names, joints their URDF joint names, shapes their URDF
//! `<collision name>` when it is unique (else `<link>_collision_<i>`), the ground `ground`, and
//! actuators the joints' profile names; [`Mjcf`] lists them all so callers can look the elements
//! up in the compiled model.
//!
//! Numbers are written in Rust's shortest round-trip form, so MuJoCo parses back exactly the
//! `f64` values of the model.
//!
//! Users get this text from the command line: `hyq model --format mjcf [--actuators
//! position|motor|none]` (crates/hyq-cli) writes it for the chosen robot (`--robot`) and the
//! configuration (`--config`, `--set`), with the MuJoCo backend's solver settings (the
//! configuration's `[physics.mujoco]`, [`MujocoOptions::default`] where it sets none).

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

use nalgebra::{Isometry3, Matrix3};
use serde::{Deserialize, Serialize};

use crate::xml::{attr, nums};
use hyq_physics::PhysicsParams;
use hyq_physics::{HeightGrid, Terrain};
use hyq_physics::{RobotModel, Shape};

/// MuJoCo's numerical integrator (`<option integrator>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Semi-implicit Euler, joint damping implicit (`Euler`, MuJoCo's default).
    Euler,
    /// Implicit in velocity without the Coriolis derivatives (`implicitfast`).
    Implicitfast,
}

/// MuJoCo's friction cone (`<option cone>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cone {
    /// Pyramid with four edges per contact (MuJoCo's default).
    Pyramidal,
    /// The Coulomb cone.
    Elliptic,
}

/// MuJoCo's constraint solver (`<option solver>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    /// Newton's method on the primal problem (MuJoCo's default).
    Newton,
    /// Conjugate gradient on the primal problem.
    Cg,
    /// Projected Gauss-Seidel on the dual problem.
    Pgs,
}

impl Integrator {
    fn mjcf(self) -> &'static str {
        match self {
            Integrator::Euler => "Euler",
            Integrator::Implicitfast => "implicitfast",
        }
    }
}

impl Cone {
    fn mjcf(self) -> &'static str {
        match self {
            Cone::Pyramidal => "pyramidal",
            Cone::Elliptic => "elliptic",
        }
    }
}

impl Solver {
    fn mjcf(self) -> &'static str {
        match self {
            Solver::Newton => "Newton",
            Solver::Cg => "CG",
            Solver::Pgs => "PGS",
        }
    }
}

/// Who produces the joint torques in the generated model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Actuators {
    /// No actuator: the caller applies joint torques itself (`mjData.qfrc_applied`), e.g.
    /// from the shared PD actuator ([`hyq_physics::actuator`]), which also applies the velocity-limit
    /// rule.
    None,
    /// One `<motor>` per joint, profile order: the control is the joint torque (N·m), clamped
    /// by MuJoCo to the joint's effort limit.
    Motor,
    /// One `<position>` servo per joint, profile order: the control is the joint target (rad);
    /// MuJoCo applies `kp (q* − q) − kd q̇` with the model's default gains
    /// ([`RobotModel::kp`], [`RobotModel::kd`]), clamped to the effort limit, inside every step.
    /// Unlike the shared actuator it has no velocity-limit rule.
    Position,
}

/// MuJoCo's solver and contact settings: the `<option>` attributes and the contact and
/// joint-limit `solref`/`solimp` the generator writes, and the MuJoCo backend's
/// `[physics.mujoco]` table in an environment's TOML. Each field maps to the MJCF attribute of
/// the same name.
///
/// Two sets of values: [`MujocoOptions::default`], the MuJoCo backend's (and `hyq model`'s),
/// and [`MujocoOptions::mujoco_defaults`], MuJoCo 4.0's own, which differ in three fields;
/// each field's doc gives both where they differ. The backend's choices are measured in the
/// hyq-mujoco crate's README (settings table).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MujocoOptions {
    /// Integrator: `"euler"` (semi-implicit Euler, joint damping implicit) or `"implicitfast"`
    /// (implicit in velocity without the Coriolis derivatives) (default: euler, MuJoCo's).
    pub integrator: Integrator,
    /// Friction cone: `"pyramidal"` (four edges per contact) or `"elliptic"` (the Coulomb
    /// cone) (default: pyramidal, MuJoCo's).
    pub cone: Cone,
    /// Ratio of frictional to normal constraint impedance, ≥ 1; above 1 makes friction stiffer
    /// (default: 1, MuJoCo's).
    pub impratio: f64,
    /// Constraint solver: `"newton"`, `"cg"` or `"pgs"` (default: newton, MuJoCo's).
    pub solver: Solver,
    /// Maximum solver iterations per step (default: 100, MuJoCo's).
    pub iterations: u32,
    /// Maximum line-search iterations per solver iteration, Newton and CG (default: 50,
    /// MuJoCo's).
    pub ls_iterations: u32,
    /// Early-termination tolerance of the solver (default: 1e-8, MuJoCo's).
    pub tolerance: f64,
    /// Iterations of the no-slip post-solver; 0 disables it (default: 10; MuJoCo's is 0).
    /// Without it a standing HyQ's feet creep 6 mm in 9 s (14.9 mm with the stiff contacts
    /// below).
    pub noslip_iterations: u32,
    /// Ground-contact `solref`: time constant (s) and damping ratio of the contact's reference
    /// acceleration (default: [0.002, 1]; MuJoCo's is [0.02, 1], at which a standing HyQ's feet
    /// sink 2.5 mm). MuJoCo raises a time constant below two time steps to two time steps.
    pub contact_solref: [f64; 2],
    /// Ground-contact `solimp`: d0, d_width, width (m), midpoint, power of the impedance curve
    /// (default: [0.9, 0.95, 0.001, 0.5, 2], MuJoCo's).
    pub contact_solimp: [f64; 5],
    /// Joint-limit `solref` (default: [0.002, 1]; MuJoCo's is [0.02, 1], at which joints driven
    /// at full torque overshoot their limits by 0.36 rad).
    pub limit_solref: [f64; 2],
    /// Joint-limit `solimp` (default: [0.9, 0.95, 0.001, 0.5, 2], MuJoCo's).
    pub limit_solimp: [f64; 5],
}

impl MujocoOptions {
    /// MuJoCo 4.0's own defaults, the values a model without these attributes gets.
    pub fn mujoco_defaults() -> Self {
        Self {
            integrator: Integrator::Euler,
            cone: Cone::Pyramidal,
            impratio: 1.0,
            solver: Solver::Newton,
            iterations: 100,
            ls_iterations: 50,
            tolerance: 1e-8,
            noslip_iterations: 0,
            contact_solref: [0.02, 1.0],
            contact_solimp: [0.9, 0.95, 0.001, 0.5, 2.0],
            limit_solref: [0.02, 1.0],
            limit_solimp: [0.9, 0.95, 0.001, 0.5, 2.0],
        }
    }

    /// Checks every field as a key of `[physics.mujoco]`; the error names the first invalid
    /// one (`mujoco.<field>`).
    pub fn validate(&self) -> Result<(), hyq_physics::PhysicsError> {
        self.check().map_err(|e| match e {
            MjcfError::InvalidOption {
                field,
                value,
                reason,
            } => hyq_physics::PhysicsError::InvalidParam {
                field: table_key(field),
                value,
                reason,
            },
            other => hyq_physics::PhysicsError::Backend {
                backend: "mujoco",
                message: other.to_string(),
            },
        })
    }
}

impl Default for MujocoOptions {
    /// The MuJoCo backend's settings: MuJoCo's own defaults except three, each measured in the
    /// hyq-mujoco crate's README: stiff ground contacts and joint limits (time constant 2 ms,
    /// the shortest MuJoCo accepts at a 1 ms step) and 10 no-slip iterations, so that HyQ
    /// stands where the rigid-contact engines put it, does not creep, and its joints overshoot
    /// their limits no more than on rapier.
    fn default() -> Self {
        Self {
            noslip_iterations: 10,
            contact_solref: [0.002, 1.0],
            limit_solref: [0.002, 1.0],
            ..Self::mujoco_defaults()
        }
    }
}

/// `field` of [`MujocoOptions`] as a key of `[physics.mujoco]`.
fn table_key(field: &'static str) -> &'static str {
    match field {
        "impratio" => "mujoco.impratio",
        "iterations" => "mujoco.iterations",
        "ls_iterations" => "mujoco.ls_iterations",
        "tolerance" => "mujoco.tolerance",
        "contact_solref" => "mujoco.contact_solref",
        "contact_solimp" => "mujoco.contact_solimp",
        "limit_solref" => "mujoco.limit_solref",
        "limit_solimp" => "mujoco.limit_solimp",
        other => other,
    }
}

/// What to generate.
#[derive(Debug, Clone, PartialEq)]
pub struct MjcfOptions {
    /// Time step (s).
    pub timestep: f64,
    /// Gravity, world frame (m/s²).
    pub gravity: [f64; 3],
    /// Coulomb friction coefficient of every robot shape and of the ground.
    pub friction: f64,
    /// Distance (m) up to which MuJoCo lists a robot shape's contact with the ground without
    /// pushing on it (the shapes' `gap`); 0 lists only touching shapes.
    pub contact_distance: f64,
    /// The actuators.
    pub actuators: Actuators,
    /// Solver and contact settings.
    pub solver: MujocoOptions,
    /// Let MuJoCo reset the state by itself when it becomes non-finite or huge (its
    /// `autoreset` flag). A simulator that must see and report divergence turns it off.
    pub autoreset: bool,
    /// The ground: the plane z = 0, or a height field written as an `<hfield>`.
    pub terrain: Terrain,
}

impl MjcfOptions {
    /// Options from the engine-independent physics parameters, with MuJoCo's own default
    /// solver settings ([`MujocoOptions::mujoco_defaults`]), no actuator and MuJoCo's
    /// automatic reset off.
    pub fn from_params(params: &PhysicsParams) -> Self {
        Self {
            timestep: params.dt,
            gravity: params.gravity,
            friction: params.ground_friction,
            contact_distance: params.contact_distance,
            actuators: Actuators::None,
            solver: MujocoOptions::mujoco_defaults(),
            autoreset: false,
            terrain: Terrain::Flat,
        }
    }
}

impl Default for MjcfOptions {
    fn default() -> Self {
        Self::from_params(&PhysicsParams::default())
    }
}

/// A generated model: the XML text and the names of its elements.
#[derive(Debug, Clone, PartialEq)]
pub struct Mjcf {
    /// The MJCF document.
    pub xml: String,
    /// Body names, in [`RobotModel::links`] order (index 0, the trunk, has the free joint).
    pub bodies: Vec<String>,
    /// Joint names, in profile order ([`RobotModel::joints`]).
    pub joints: Vec<String>,
    /// Shape (geom) names: `geoms[link][i]` is shape `i` of [`hyq_physics::Link::collisions`].
    pub geoms: Vec<Vec<String>>,
    /// Actuator names in profile order (empty with [`Actuators::None`]).
    pub actuators: Vec<String>,
    /// The ground plane's name.
    pub ground: String,
}

/// Why a model could not be written as MJCF.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MjcfError {
    /// An option is out of its valid range.
    #[error("MJCF option {field} = {value}: {reason}")]
    InvalidOption {
        /// The option, e.g. `timestep` or `impratio` (a [`MujocoOptions`] field).
        field: &'static str,
        /// The rejected value, formatted.
        value: String,
        /// The valid range.
        reason: &'static str,
    },
    /// The model holds something MJCF generation does not support.
    #[error("cannot write the model as MJCF: {0}")]
    Unsupported(String),
}

fn invalid(field: &'static str, value: impl std::fmt::Debug, reason: &'static str) -> MjcfError {
    MjcfError::InvalidOption {
        field,
        value: format!("{value:?}"),
        reason,
    }
}

impl MjcfOptions {
    /// Checks every option; the error names the first invalid one.
    pub fn validate(&self) -> Result<(), MjcfError> {
        if !(self.timestep.is_finite() && self.timestep > 0.0) {
            return Err(invalid("timestep", self.timestep, "must be finite and > 0"));
        }
        if !self.gravity.iter().all(|g| g.is_finite()) {
            return Err(invalid("gravity", self.gravity, "must be finite"));
        }
        if !(self.friction.is_finite() && self.friction >= 0.0) {
            return Err(invalid(
                "friction",
                self.friction,
                "must be finite and >= 0",
            ));
        }
        if !(self.contact_distance.is_finite() && self.contact_distance >= 0.0) {
            return Err(invalid(
                "contact_distance",
                self.contact_distance,
                "must be finite and >= 0 (m)",
            ));
        }
        self.solver.check()
    }
}

impl MujocoOptions {
    /// Checks every setting; the error names the first invalid one by its field name.
    fn check(&self) -> Result<(), MjcfError> {
        let s = self;
        if !(s.impratio.is_finite() && s.impratio >= 1.0) {
            return Err(invalid("impratio", s.impratio, "must be finite and >= 1"));
        }
        if s.iterations == 0 {
            return Err(invalid("iterations", s.iterations, "must be >= 1"));
        }
        if s.ls_iterations == 0 {
            return Err(invalid("ls_iterations", s.ls_iterations, "must be >= 1"));
        }
        if !(s.tolerance.is_finite() && s.tolerance >= 0.0) {
            return Err(invalid("tolerance", s.tolerance, "must be finite and >= 0"));
        }
        for (field, solref) in [
            ("contact_solref", s.contact_solref),
            ("limit_solref", s.limit_solref),
        ] {
            if !(solref.iter().all(|v| v.is_finite()) && solref[0] > 0.0 && solref[1] > 0.0) {
                return Err(invalid(
                    field,
                    solref,
                    "must be [time constant > 0 s, damping ratio > 0]",
                ));
            }
        }
        for (field, solimp) in [
            ("contact_solimp", s.contact_solimp),
            ("limit_solimp", s.limit_solimp),
        ] {
            let [d0, dwidth, width, mid, power] = solimp;
            let ok = solimp.iter().all(|v| v.is_finite())
                && (0.0..1.0).contains(&d0)
                && (0.0..1.0).contains(&dwidth)
                && width >= 0.0
                && (0.0..=1.0).contains(&mid)
                && power >= 1.0;
            if !ok {
                return Err(invalid(
                    field,
                    solimp,
                    "must be [d0 in [0, 1), d_width in [0, 1), width >= 0 m, midpoint in [0, 1], power >= 1]",
                ));
            }
        }
        Ok(())
    }
}

fn pos_quat(pose: &Isometry3<f64>) -> String {
    let t = pose.translation.vector;
    let q = pose.rotation.quaternion();
    format!(
        "pos=\"{}\" quat=\"{}\"",
        nums(&[t.x, t.y, t.z]),
        nums(&[q.w, q.i, q.j, q.k])
    )
}

fn full_inertia(i: &Matrix3<f64>) -> String {
    nums(&[
        i[(0, 0)],
        i[(1, 1)],
        i[(2, 2)],
        i[(0, 1)],
        i[(0, 2)],
        i[(1, 2)],
    ])
}

/// The names of every element, chosen before any text is written.
fn names(model: &RobotModel, actuators: Actuators) -> Mjcf {
    let mut counts: HashMap<&str, usize> = HashMap::new();
    for link in model.links() {
        for c in &link.collisions {
            if let Some(name) = &c.name {
                *counts.entry(name.as_str()).or_default() += 1;
            }
        }
    }
    let reserved: HashSet<&str> = ["ground"].into_iter().collect();
    let geoms = model
        .links()
        .iter()
        .map(|link| {
            link.collisions
                .iter()
                .enumerate()
                .map(|(i, c)| match &c.name {
                    Some(name)
                        if counts[name.as_str()] == 1 && !reserved.contains(name.as_str()) =>
                    {
                        name.clone()
                    }
                    _ => format!("{}_collision_{i}", link.name),
                })
                .collect()
        })
        .collect();
    Mjcf {
        xml: String::new(),
        bodies: model.links().iter().map(|l| l.name.clone()).collect(),
        joints: model.joints().iter().map(|j| j.urdf_name.clone()).collect(),
        geoms,
        actuators: match actuators {
            Actuators::None => Vec::new(),
            Actuators::Motor | Actuators::Position => {
                model.joints().iter().map(|j| j.name.clone()).collect()
            }
        },
        ground: "ground".into(),
    }
}

/// Writes `model` as an MJCF document (see the module documentation for what it contains).
pub fn to_mjcf(model: &RobotModel, options: &MjcfOptions) -> Result<Mjcf, MjcfError> {
    options.validate()?;
    let mut out = names(model, options.actuators);
    let mut x = String::with_capacity(16 * 1024);
    write_header(&mut x, model, options);
    if let Terrain::Field(grid) = &options.terrain {
        write_hfield(&mut x, grid);
    }
    x.push_str("  <worldbody>\n");
    match &options.terrain {
        Terrain::Flat => {
            let _ = writeln!(
                x,
                "    <geom name=\"{}\" class=\"ground\" type=\"plane\" size=\"0 0 1\"/>",
                attr(&out.ground)
            );
        }
        Terrain::Field(grid) => {
            let [cx, cy] = grid.center();
            let _ = writeln!(
                x,
                "    <geom name=\"{}\" class=\"ground\" type=\"hfield\" hfield=\"{HFIELD}\" \
                 pos=\"{}\"/>",
                attr(&out.ground),
                nums(&[cx, cy, grid.min_height()])
            );
        }
    }

    let children = children_of(model)?;
    write_bodies(&mut x, model, &out, &children)?;
    x.push_str("  </worldbody>\n");
    write_actuators(&mut x, model, options, &out);
    write_keyframe(&mut x, model, &children);
    out.xml = x;
    Ok(out)
}

// Writing to a String cannot fail: every `write!` result below is ignored for that reason.

/// The height field's name in the MJCF.
pub const HFIELD: &str = "terrain";

/// The depth (m) of MuJoCo's height field below the grid's lowest point (its `base`): its
/// prisms reach that far down, so a shape that sinks less than this is pushed back up.
const HFIELD_BASE_M: f64 = 1.0;

/// The `<asset>` holding the height field of `grid` (see the module documentation).
fn write_hfield(x: &mut String, grid: &HeightGrid) {
    let (low, high) = (grid.min_height(), grid.max_height());
    let range = high - low;
    // MuJoCo needs a positive height range even for a level grid, whose values are all 0.
    let elevation = if range > 0.0 { range } else { 1.0 };
    let [sx, sy] = grid.size();
    let _ = writeln!(
        x,
        "  <asset>\n    <hfield name=\"{HFIELD}\" nrow=\"{}\" ncol=\"{}\" size=\"{}\"",
        grid.rows(),
        grid.columns(),
        nums(&[0.5 * sx, 0.5 * sy, elevation, HFIELD_BASE_M])
    );
    x.push_str("      elevation=\"");
    // MuJoCo keeps heights in single precision: each is written as the f32 it will hold.
    for k in (0..grid.rows()).rev() {
        x.push_str("\n       ");
        for c in 0..grid.columns() {
            let scaled = if range > 0.0 {
                (grid.height(c, k) - low) / range
            } else {
                0.0
            };
            let _ = write!(x, " {}", scaled as f32);
        }
    }
    x.push_str("\"/>\n  </asset>\n");
}

/// The document's head: the compiler settings, the solver options and the defaults.
fn write_header(x: &mut String, model: &RobotModel, options: &MjcfOptions) {
    let s = &options.solver;
    let _ = writeln!(
        x,
        "<mujoco model=\"{}\">\n  <!-- Generated from the robot model (URDF + robot profile); do not edit. -->",
        attr(model.name())
    );
    x.push_str(
        "  <compiler angle=\"radian\" autolimits=\"true\" inertiafromgeom=\"false\" \
         boundmass=\"0\" boundinertia=\"0\" balanceinertia=\"false\" fusestatic=\"false\"/>\n",
    );
    let _ = writeln!(
        x,
        "  <option timestep=\"{}\" gravity=\"{}\" integrator=\"{}\" cone=\"{}\" impratio=\"{}\" \
         solver=\"{}\" iterations=\"{}\" ls_iterations=\"{}\" tolerance=\"{}\" \
         noslip_iterations=\"{}\">",
        nums(&[options.timestep]),
        nums(&options.gravity),
        s.integrator.mjcf(),
        s.cone.mjcf(),
        nums(&[s.impratio]),
        s.solver.mjcf(),
        s.iterations,
        s.ls_iterations,
        nums(&[s.tolerance]),
        s.noslip_iterations
    );
    let _ = writeln!(
        x,
        "    <flag autoreset=\"{}\"/>\n  </option>",
        if options.autoreset {
            "enable"
        } else {
            "disable"
        }
    );
    let friction = nums(&[options.friction, 0.005, 0.0001]);
    let _ = writeln!(
        x,
        "  <default>\n    <geom contype=\"1\" conaffinity=\"0\" condim=\"3\" friction=\"{friction}\" \
         solref=\"{}\" solimp=\"{}\" margin=\"0\" gap=\"{}\"/>\n    \
         <joint solreflimit=\"{}\" solimplimit=\"{}\" armature=\"0\" frictionloss=\"0\"/>\n    \
         <default class=\"ground\">\n      <geom contype=\"0\" conaffinity=\"1\" gap=\"0\"/>\n    \
         </default>\n  </default>",
        nums(&s.contact_solref),
        nums(&s.contact_solimp),
        nums(&[options.contact_distance]),
        nums(&s.limit_solref),
        nums(&s.limit_solimp),
    );
}

/// The children of every body, in model order (parents come before children).
fn children_of(model: &RobotModel) -> Result<Vec<Vec<usize>>, MjcfError> {
    let links = model.links();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); links.len()];
    for (i, link) in links.iter().enumerate() {
        if let Some(p) = link.parent {
            if p >= i {
                return Err(MjcfError::Unsupported(format!(
                    "body {} comes before its parent",
                    link.name
                )));
            }
            children[p].push(i);
        }
    }
    Ok(children)
}

/// Every body, nested depth first from the trunk (children in model order).
fn write_bodies(
    x: &mut String,
    model: &RobotModel,
    out: &Mjcf,
    children: &[Vec<usize>],
) -> Result<(), MjcfError> {
    let mut stack: Vec<(usize, bool)> = vec![(0, false)];
    let mut depth = 0usize;
    while let Some((i, closing)) = stack.pop() {
        let indent = "  ".repeat(depth + 2);
        if closing {
            depth -= 1;
            let _ = writeln!(x, "{}</body>", "  ".repeat(depth + 2));
            continue;
        }
        write_body(x, model, out, i, &indent)?;
        stack.push((i, true));
        for &child in children[i].iter().rev() {
            stack.push((child, false));
        }
        depth += 1;
    }
    Ok(())
}

/// One body's opening tag, its joint, its inertia and its collision geoms (`indent`: the body
/// tag's).
fn write_body(
    x: &mut String,
    model: &RobotModel,
    out: &Mjcf,
    i: usize,
    indent: &str,
) -> Result<(), MjcfError> {
    let link = &model.links()[i];
    let frame = match link.parent_joint {
        None => model.spawn_state().trunk.pose,
        Some(j) => model.joints()[j].origin,
    };
    let _ = writeln!(
        x,
        "{indent}<body name=\"{}\" {}>",
        attr(&out.bodies[i]),
        pos_quat(&frame)
    );
    let inner = format!("{indent}  ");
    match link.parent_joint {
        None => {
            let _ = writeln!(
                x,
                "{inner}<freejoint name=\"{}\"/>",
                attr(&format!("{}_root", link.name))
            );
        }
        Some(j) => {
            let joint = &model.joints()[j];
            let a = joint.axis;
            let _ = writeln!(
                x,
                "{inner}<joint name=\"{}\" type=\"hinge\" axis=\"{}\" range=\"{}\" damping=\"{}\"{}/>",
                attr(&out.joints[j]),
                nums(&[a.x, a.y, a.z]),
                nums(&[joint.lower, joint.upper]),
                nums(&[joint.damping]),
                // Written only when set, so a URDF robot's MJCF is unchanged.
                if joint.armature > 0.0 {
                    format!(" armature=\"{}\"", nums(&[joint.armature]))
                } else {
                    String::new()
                }
            );
        }
    }
    let c = link.com;
    let _ = writeln!(
        x,
        "{inner}<inertial pos=\"{}\" mass=\"{}\" fullinertia=\"{}\"/>",
        nums(&[c.x, c.y, c.z]),
        nums(&[link.mass]),
        full_inertia(&link.inertia)
    );
    for (k, collision) in link.collisions.iter().enumerate() {
        let (kind, size) = geom_type_size(&collision.shape).ok_or_else(|| {
            MjcfError::Unsupported(format!(
                "link {}: collision shape {:?}",
                link.name, collision.shape
            ))
        })?;
        let _ = writeln!(
            x,
            "{inner}<geom name=\"{}\" type=\"{kind}\" size=\"{size}\" {}/>",
            attr(&out.geoms[i][k]),
            pos_quat(&collision.origin)
        );
    }
    Ok(())
}

/// A geom's MuJoCo `type` and `size` for `shape` (half sizes, as MuJoCo takes them), or `None`
/// for a shape MuJoCo is not given.
fn geom_type_size(shape: &Shape) -> Option<(&'static str, String)> {
    Some(match *shape {
        Shape::Box { half_extents } => (
            "box",
            nums(&[half_extents.x, half_extents.y, half_extents.z]),
        ),
        Shape::Sphere { radius } => ("sphere", nums(&[radius])),
        Shape::Capsule {
            radius,
            half_length,
        } => ("capsule", nums(&[radius, half_length])),
        Shape::Cylinder {
            radius,
            half_length,
        } => ("cylinder", nums(&[radius, half_length])),
        // `Shape` is non-exhaustive: a shape added to the model later must be mapped here
        // before MuJoCo can simulate it.
        _ => return None,
    })
}

/// The actuators of `options.actuators`, one per joint.
fn write_actuators(x: &mut String, model: &RobotModel, options: &MjcfOptions, out: &Mjcf) {
    match options.actuators {
        Actuators::None => {}
        Actuators::Motor | Actuators::Position => {
            x.push_str("  <actuator>\n");
            for (j, joint) in model.joints().iter().enumerate() {
                let range = nums(&[-joint.effort, joint.effort]);
                let name = attr(&out.actuators[j]);
                let target = attr(&out.joints[j]);
                let _ = match options.actuators {
                    Actuators::Motor => writeln!(
                        x,
                        "    <motor name=\"{name}\" joint=\"{target}\" gear=\"1\" \
                         ctrllimited=\"false\" forcerange=\"{range}\"/>"
                    ),
                    _ => writeln!(
                        x,
                        "    <position name=\"{name}\" joint=\"{target}\" kp=\"{}\" kv=\"{}\" \
                         ctrllimited=\"false\" forcerange=\"{range}\"/>",
                        nums(&[model.kp()[j]]),
                        nums(&[model.kd()[j]])
                    ),
                };
            }
            x.push_str("  </actuator>\n");
        }
    }
}

/// The spawn keyframe: the free joint's position and orientation, then the hinge angles in
/// MuJoCo's order, which is the depth-first order the bodies were written in.
fn write_keyframe(x: &mut String, model: &RobotModel, children: &[Vec<usize>]) {
    let links = model.links();
    let spawn = model.spawn_state();
    let mut qpos = {
        let t = spawn.trunk.pose.translation.vector;
        let q = spawn.trunk.pose.rotation.quaternion();
        vec![t.x, t.y, t.z, q.w, q.i, q.j, q.k]
    };
    for i in depth_first(children) {
        if let Some(j) = links[i].parent_joint {
            qpos.push(spawn.q[j]);
        }
    }
    let _ = writeln!(
        x,
        "  <keyframe>\n    <key name=\"spawn\" qpos=\"{}\"/>\n  </keyframe>\n</mujoco>",
        nums(&qpos)
    );
}

/// Body indices in the order the bodies are written (depth first, children in model order).
fn depth_first(children: &[Vec<usize>]) -> Vec<usize> {
    let mut order = Vec::with_capacity(children.len());
    let mut stack = vec![0];
    while let Some(i) = stack.pop() {
        order.push(i);
        stack.extend(children[i].iter().rev());
    }
    order
}

#[cfg(test)]
mod tests {
    //! The generated text says what the model says: one body per link with its exact mass
    //! properties, one hinge per joint with its exact frame, axis, range and damping, one geom
    //! per collision shape, contact filtering that leaves only robot–ground pairs, and the
    //! requested actuators; bad options are refused by name.
    #![allow(clippy::unwrap_used)]

    use super::*;
    use hyq_physics::bundled;

    /// The value of attribute `name` in the first element of `line` that has it.
    fn attr_of<'a>(line: &'a str, name: &str) -> Option<&'a str> {
        let key = format!(" {name}=\"");
        let start = line.find(&key)? + key.len();
        let end = line[start..].find('"')? + start;
        Some(&line[start..end])
    }

    fn floats(s: &str) -> Vec<f64> {
        s.split_whitespace().map(|v| v.parse().unwrap()).collect()
    }

    #[test]
    fn every_link_joint_and_shape_appears_with_its_exact_numbers() {
        let model = bundled::hyq();
        let m = to_mjcf(&model, &MjcfOptions::default()).unwrap();
        let lines: Vec<&str> = m.xml.lines().map(str::trim).collect();
        for (i, link) in model.links().iter().enumerate() {
            let at = lines
                .iter()
                .position(|l| l.starts_with("<body ") && attr_of(l, "name") == Some(&m.bodies[i]))
                .unwrap_or_else(|| panic!("no body {}", link.name));
            let inertial = lines[at..]
                .iter()
                .find(|l| l.starts_with("<inertial "))
                .unwrap();
            assert_eq!(
                floats(attr_of(inertial, "mass").unwrap()),
                [link.mass],
                "{}",
                link.name
            );
            assert_eq!(
                floats(attr_of(inertial, "pos").unwrap()),
                link.com.as_slice(),
                "{}",
                link.name
            );
            let full = floats(attr_of(inertial, "fullinertia").unwrap());
            let i3 = link.inertia;
            assert_eq!(
                full,
                [
                    i3[(0, 0)],
                    i3[(1, 1)],
                    i3[(2, 2)],
                    i3[(0, 1)],
                    i3[(0, 2)],
                    i3[(1, 2)]
                ]
            );
            let body = lines[at];
            if let Some(j) = link.parent_joint {
                let joint = &model.joints()[j];
                let origin = joint.origin;
                assert_eq!(
                    floats(attr_of(body, "pos").unwrap()),
                    origin.translation.vector.as_slice()
                );
                let q = origin.rotation.quaternion();
                assert_eq!(floats(attr_of(body, "quat").unwrap()), [q.w, q.i, q.j, q.k]);
                let hinge = lines[at + 1];
                assert!(hinge.starts_with("<joint "), "{hinge}");
                assert_eq!(attr_of(hinge, "name"), Some(joint.urdf_name.as_str()));
                assert_eq!(
                    floats(attr_of(hinge, "axis").unwrap()),
                    joint.axis.as_slice()
                );
                assert_eq!(
                    floats(attr_of(hinge, "range").unwrap()),
                    [joint.lower, joint.upper]
                );
                assert_eq!(floats(attr_of(hinge, "damping").unwrap()), [joint.damping]);
            } else {
                assert!(lines[at + 1].starts_with("<freejoint "));
            }
            for (k, c) in link.collisions.iter().enumerate() {
                let geom = lines
                    .iter()
                    .find(|l| l.starts_with("<geom ") && attr_of(l, "name") == Some(&m.geoms[i][k]))
                    .unwrap();
                let size = floats(attr_of(geom, "size").unwrap());
                let expected = match c.shape {
                    Shape::Box { half_extents } => half_extents.as_slice().to_vec(),
                    Shape::Sphere { radius } => vec![radius],
                    Shape::Capsule {
                        radius,
                        half_length,
                    }
                    | Shape::Cylinder {
                        radius,
                        half_length,
                    } => vec![radius, half_length],
                    _ => panic!("{}: a shape this test does not know", m.geoms[i][k]),
                };
                assert_eq!(size, expected, "{}", m.geoms[i][k]);
                assert_eq!(
                    floats(attr_of(geom, "pos").unwrap()),
                    c.origin.translation.vector.as_slice()
                );
            }
        }
        assert_eq!(
            lines.iter().filter(|l| l.starts_with("<body ")).count(),
            model.num_links()
        );
        assert_eq!(
            lines
                .iter()
                .filter(|l| l.starts_with("<joint name="))
                .count(),
            model.num_joints()
        );
        let shapes: usize = model.links().iter().map(|l| l.collisions.len()).sum();
        // The robot's shapes plus the ground.
        assert_eq!(
            lines
                .iter()
                .filter(|l| l.starts_with("<geom name="))
                .count(),
            shapes + 1
        );
    }

    #[test]
    fn robot_shapes_collide_only_with_the_ground() {
        let m = to_mjcf(&bundled::hyq(), &MjcfOptions::default()).unwrap();
        // The robot's default class: contype 1, conaffinity 0; the ground's: 0 and 1. A pair
        // collides when (contype_a & conaffinity_b) | (contype_b & conaffinity_a) is non-zero:
        // robot–robot 0, robot–ground 1.
        let default_geom = m
            .xml
            .lines()
            .map(str::trim)
            .find(|l| l.starts_with("<geom contype="))
            .unwrap();
        assert_eq!(attr_of(default_geom, "contype"), Some("1"));
        assert_eq!(attr_of(default_geom, "conaffinity"), Some("0"));
        assert_eq!(attr_of(default_geom, "condim"), Some("3"));
        let ground_class = m.xml.find("<default class=\"ground\">").unwrap();
        let ground_geom = m.xml[ground_class..].lines().nth(1).unwrap().trim();
        assert_eq!(attr_of(ground_geom, "contype"), Some("0"));
        assert_eq!(attr_of(ground_geom, "conaffinity"), Some("1"));
        // No robot geom overrides the classes.
        for line in m
            .xml
            .lines()
            .map(str::trim)
            .filter(|l| l.starts_with("<geom name="))
        {
            assert!(attr_of(line, "contype").is_none(), "{line}");
            assert!(attr_of(line, "conaffinity").is_none(), "{line}");
        }
    }

    #[test]
    fn actuator_styles_give_one_actuator_per_joint_in_profile_order() {
        let model = bundled::hyq();
        let none = to_mjcf(&model, &MjcfOptions::default()).unwrap();
        assert!(!none.xml.contains("<actuator>"));
        assert!(none.actuators.is_empty());
        for style in [Actuators::Motor, Actuators::Position] {
            let m = to_mjcf(
                &model,
                &MjcfOptions {
                    actuators: style,
                    ..MjcfOptions::default()
                },
            )
            .unwrap();
            let tag = if style == Actuators::Motor {
                "<motor "
            } else {
                "<position "
            };
            let lines: Vec<&str> = m
                .xml
                .lines()
                .map(str::trim)
                .filter(|l| l.starts_with(tag))
                .collect();
            assert_eq!(lines.len(), model.num_joints());
            for (j, (line, joint)) in lines.iter().zip(model.joints()).enumerate() {
                assert_eq!(attr_of(line, "joint"), Some(joint.urdf_name.as_str()));
                assert_eq!(attr_of(line, "name"), Some(joint.name.as_str()));
                assert_eq!(
                    floats(attr_of(line, "forcerange").unwrap()),
                    [-joint.effort, joint.effort]
                );
                if style == Actuators::Position {
                    assert_eq!(floats(attr_of(line, "kp").unwrap()), [model.kp()[j]]);
                    assert_eq!(floats(attr_of(line, "kv").unwrap()), [model.kd()[j]]);
                }
            }
        }
    }

    #[test]
    fn spawn_keyframe_holds_the_spawn_pose_in_mujocos_joint_order() {
        let model = bundled::hyq();
        let m = to_mjcf(&model, &MjcfOptions::default()).unwrap();
        let key = m
            .xml
            .lines()
            .map(str::trim)
            .find(|l| l.starts_with("<key "))
            .unwrap();
        let qpos = floats(attr_of(key, "qpos").unwrap());
        assert_eq!(qpos.len(), 7 + model.num_joints());
        let spawn = model.spawn_state();
        assert_eq!(qpos[..3], *spawn.trunk.pose.translation.vector.as_slice());
        let q = spawn.trunk.pose.rotation.quaternion();
        assert_eq!(qpos[3..7], [q.w, q.i, q.j, q.k]);
        // Hinges appear in the document in the same order as in the keyframe.
        let hinge_order: Vec<&str> = m
            .xml
            .lines()
            .map(str::trim)
            .filter(|l| l.starts_with("<joint "))
            .filter_map(|l| attr_of(l, "name"))
            .collect();
        for (k, name) in hinge_order.iter().enumerate() {
            let j = model
                .joints()
                .iter()
                .position(|jt| jt.urdf_name == *name)
                .unwrap();
            assert_eq!(qpos[7 + k], spawn.q[j], "{name}");
        }
    }

    #[test]
    fn options_reach_the_option_element() {
        let options = MjcfOptions {
            timestep: 0.0005,
            gravity: [0.0, 0.5, -9.0],
            friction: 0.8,
            contact_distance: 0.002,
            actuators: Actuators::None,
            solver: MujocoOptions {
                integrator: Integrator::Implicitfast,
                cone: Cone::Elliptic,
                impratio: 10.0,
                solver: Solver::Cg,
                iterations: 7,
                ls_iterations: 3,
                tolerance: 1e-6,
                noslip_iterations: 2,
                contact_solref: [0.005, 1.0],
                contact_solimp: [0.95, 0.99, 0.0005, 0.5, 2.0],
                limit_solref: [0.004, 1.0],
                limit_solimp: [0.95, 0.99, 0.001, 0.5, 2.0],
            },
            autoreset: true,
            terrain: Terrain::Flat,
        };
        let m = to_mjcf(&bundled::hyq(), &options).unwrap();
        let option = m
            .xml
            .lines()
            .map(str::trim)
            .find(|l| l.starts_with("<option "))
            .unwrap();
        for (key, value) in [
            ("timestep", "0.0005"),
            ("gravity", "0 0.5 -9"),
            ("integrator", "implicitfast"),
            ("cone", "elliptic"),
            ("impratio", "10"),
            ("solver", "CG"),
            ("iterations", "7"),
            ("ls_iterations", "3"),
            ("tolerance", "0.000001"),
            ("noslip_iterations", "2"),
        ] {
            assert_eq!(attr_of(option, key), Some(value), "{key}");
        }
        assert!(m.xml.contains("<flag autoreset=\"enable\"/>"));
        assert!(m.xml.contains("friction=\"0.8 0.005 0.0001\""));
        assert!(m.xml.contains("gap=\"0.002\""));
        assert!(m.xml.contains("solref=\"0.005 1\""));
        assert!(m.xml.contains("solreflimit=\"0.004 1\""));
    }

    #[test]
    fn backend_defaults_are_mujocos_but_for_three_documented_fields() {
        let mujoco = MujocoOptions::mujoco_defaults();
        let backend = MujocoOptions::default();
        assert_eq!(
            MujocoOptions {
                noslip_iterations: mujoco.noslip_iterations,
                contact_solref: mujoco.contact_solref,
                limit_solref: mujoco.limit_solref,
                ..backend.clone()
            },
            mujoco
        );
        assert_eq!(
            (
                backend.noslip_iterations,
                backend.contact_solref,
                backend.limit_solref
            ),
            (10, [0.002, 1.0], [0.002, 1.0])
        );
        assert_eq!(MjcfOptions::default().solver, mujoco);
    }

    #[test]
    fn invalid_options_are_refused_by_name() {
        let base = MjcfOptions::default();
        let cases: Vec<(&str, MjcfOptions)> = vec![
            (
                "timestep",
                MjcfOptions {
                    timestep: 0.0,
                    ..base.clone()
                },
            ),
            (
                "friction",
                MjcfOptions {
                    friction: f64::NAN,
                    ..base.clone()
                },
            ),
            (
                "impratio",
                MjcfOptions {
                    solver: MujocoOptions {
                        impratio: 0.5,
                        ..MujocoOptions::mujoco_defaults()
                    },
                    ..base.clone()
                },
            ),
            (
                "contact_solimp",
                MjcfOptions {
                    solver: MujocoOptions {
                        contact_solimp: [0.9, 1.5, 0.001, 0.5, 2.0],
                        ..MujocoOptions::mujoco_defaults()
                    },
                    ..base.clone()
                },
            ),
            (
                "limit_solref",
                MjcfOptions {
                    solver: MujocoOptions {
                        limit_solref: [0.0, 1.0],
                        ..MujocoOptions::mujoco_defaults()
                    },
                    ..base.clone()
                },
            ),
        ];
        for (field, options) in cases {
            match to_mjcf(&bundled::hyq(), &options) {
                Err(MjcfError::InvalidOption { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: expected InvalidOption, got {other:?}"),
            }
        }
    }

    #[test]
    fn names_are_escaped_and_unique() {
        assert_eq!(attr("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&apos;");
        let model = bundled::hyq();
        let m = to_mjcf(&model, &MjcfOptions::default()).unwrap();
        let mut all: Vec<&String> = m.geoms.iter().flatten().collect();
        all.push(&m.ground);
        let unique: HashSet<&String> = all.iter().copied().collect();
        assert_eq!(unique.len(), all.len(), "geom names repeat: {all:?}");
        // The feet keep their URDF collision names, which the robot profile refers to.
        for t in &model.tracked()[..model.num_feet()] {
            let link = &model.links()[t.link];
            for &s in &t.shapes {
                assert_eq!(Some(&m.geoms[t.link][s]), link.collisions[s].name.as_ref());
            }
        }
    }

    #[test]
    fn a_height_field_is_written_inline_with_its_rows_from_the_far_edge() {
        // 3 columns (x) by 2 rows (y), heights 0.1 .. 0.6 m over 2 × 1 m centred on (1, -1).
        let heights = vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
        let grid = HeightGrid::new([1.0, -1.0], [2.0, 1.0], 3, 2, heights).unwrap();
        let options = MjcfOptions {
            terrain: Terrain::field(grid),
            ..MjcfOptions::default()
        };
        let m = to_mjcf(&bundled::hyq(), &options).unwrap();
        let hfield = m.xml.lines().find(|l| l.contains("<hfield ")).unwrap();
        assert_eq!(attr_of(hfield, "nrow"), Some("2"));
        assert_eq!(attr_of(hfield, "ncol"), Some("3"));
        // Half sides, height range (0.5 m), base.
        let size = floats(attr_of(hfield, "size").unwrap());
        assert_eq!(size.len(), 4);
        assert_eq!((size[0], size[1], size[3]), (1.0, 0.5, 1.0));
        assert!((size[2] - 0.5).abs() < 1e-15);
        let start = m.xml.find("elevation=\"").unwrap() + "elevation=\"".len();
        let end = start + m.xml[start..].find('"').unwrap();
        let values = floats(&m.xml[start..end]);
        // The far row (y = -0.5: 0.4, 0.5, 0.6) first, each scaled to [0, 1].
        let expected = [0.6, 0.8, 1.0, 0.0, 0.2, 0.4];
        assert_eq!(values.len(), 6);
        for (v, e) in values.iter().zip(expected) {
            assert!((v - e).abs() < 1e-7, "{values:?}");
        }
        let ground = m
            .xml
            .lines()
            .find(|l| l.contains("name=\"ground\""))
            .unwrap();
        assert_eq!(attr_of(ground, "type"), Some("hfield"));
        assert_eq!(attr_of(ground, "hfield"), Some(HFIELD));
        assert_eq!(floats(attr_of(ground, "pos").unwrap()), [1.0, -1.0, 0.1]);
        // Flat ground keeps the plane and writes no asset.
        let flat = to_mjcf(&bundled::hyq(), &MjcfOptions::default()).unwrap();
        assert!(!flat.xml.contains("<asset>") && flat.xml.contains("type=\"plane\""));
    }
}
