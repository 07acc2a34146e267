//! `hyq model`: the robot the environment simulates, written for tools outside the project.
//!
//! Three formats, one file each (stdout unless `--out FILE`):
//! - `mjcf`: MuJoCo's XML model (hyq-formats' [`mjcf`] generator) with the configuration's
//!   time step, gravity, friction and contact distance, the MuJoCo backend's solver and contact
//!   settings (`[physics.mujoco]`: the backend's defaults, stiff 2 ms contacts and limits and
//!   10 no-slip iterations, unless the configuration changes them), and the chosen actuators: `position`
//!   servos (default: MuJoCo runs kp (q* − q) − kd q̇ clamped to the effort limit inside every
//!   step, without the shared actuator's velocity-limit rule), `motor`s (control = torque) or
//!   `none`;
//! - `urdf`: the loaded robot as URDF (hyq-formats' [`urdf`]: fixed links lumped,
//!   primitive shapes), capsules as `<capsule>` (default) or as `<cylinder>`s spanning them for
//!   urdfdom-based loaders such as DART's;
//! - `json`: the facts a simulator loop outside the project needs to run the environment's
//!   workload on that model: sub-steps and time step, t_max and ε_joint, physics parameters,
//!   the joints in action order (limits, effort, speed limit, standing angle, gains), the
//!   trunk and feet as (link, shape indices), the spawn state and every collision shape
//!   ([`Facts`], `schema_version` 1).
//!
//! The MuJoCo and DART-from-Python benchmarks (`bench/anchors/`) load these three files, which
//! `cargo xtask bench-vs-anchors` writes afresh from this command at every run.

use std::io::Write as _;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use hyq_env::EnvConfig;
use hyq_formats::mjcf::{Actuators, MjcfOptions, MujocoOptions, to_mjcf};
use hyq_formats::urdf::{CapsuleAs, UrdfOptions, to_urdf};
use hyq_formats::{mjcf, urdf};
use hyq_physics::RobotModel;
use hyq_physics::{Collision, Shape};
use serde::Serialize;

use crate::Failure;
use crate::options::{ConfigArgs, RobotArgs, usage};
use crate::output::{self, OutputFile};

/// The file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// MuJoCo's XML model format.
    Mjcf,
    /// URDF.
    Urdf,
    /// The facts a simulator loop needs (JSON).
    Json,
}

/// The MJCF's actuators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ActuatorChoice {
    /// One position servo per joint (the PD runs inside MuJoCo).
    Position,
    /// One motor per joint (control = joint torque).
    Motor,
    /// None (the caller writes joint torques).
    None,
}

/// How capsules are written in the URDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CapsuleChoice {
    /// `<capsule radius length>` (read by MuJoCo, PyBullet and this project).
    Capsule,
    /// A `<cylinder>` spanning the capsule, caps included (for urdfdom, e.g. DART).
    Cylinder,
}

/// `hyq model` arguments.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// What to write.
    #[arg(long, value_enum)]
    format: Format,
    /// The MJCF's actuators (mjcf only).
    #[arg(long, value_enum, default_value_t = ActuatorChoice::Position)]
    actuators: ActuatorChoice,
    /// How the URDF writes capsules (urdf only).
    #[arg(long, value_enum, default_value_t = CapsuleChoice::Capsule)]
    capsules: CapsuleChoice,
    /// The file to write [default: stdout].
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// The robot.
    #[command(flatten)]
    robot: RobotArgs,
    /// The configuration (time step, gravity, friction, contact distance, gains, sub-steps,
    /// t_max, ε_joint are read from it).
    #[command(flatten)]
    configuration: ConfigArgs,
}

/// A collision shape of a link, in the link's frame.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FactShape {
    /// The URDF `<collision name>`, if any.
    pub name: Option<String>,
    /// `"box"`, `"sphere"`, `"capsule"` or `"cylinder"`.
    pub shape: &'static str,
    /// Half sizes along x, y, z (box only; m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_extents: Option<[f64; 3]>,
    /// Radius (sphere, capsule, cylinder; m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Half the cap-centre distance (capsule) or half the length (cylinder), along the shape's
    /// z axis (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_length: Option<f64>,
    /// The shape frame's origin in the link frame (m).
    pub position: [f64; 3],
    /// The shape frame's orientation in the link frame (w, x, y, z).
    pub quaternion_wxyz: [f64; 4],
}

/// A body of the simulated robot.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FactLink {
    /// The URDF link name.
    pub name: String,
    /// Collision shapes, in URDF order (the order the URDF and MJCF files list them in).
    pub collisions: Vec<FactShape>,
}

/// An actuated joint, in action order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FactJoint {
    /// The profile's short name.
    pub name: String,
    /// The URDF (and MJCF) joint name.
    pub urdf_name: String,
    /// Lower position limit (rad).
    pub lower: f64,
    /// Upper position limit (rad).
    pub upper: f64,
    /// Effort limit (N·m): the PD torque is clamped to ± this.
    pub effort: f64,
    /// Speed limit (rad/s).
    pub velocity: f64,
    /// The standing angle (rad), the spawn pose.
    pub standing: f64,
    /// Proportional gain (N·m/rad).
    pub kp: f64,
    /// Derivative gain (N·m·s/rad).
    pub kd: f64,
}

/// A tracked body: a link and which of its shapes count.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FactTracked {
    /// The profile's name (a foot's, or the trunk link's).
    pub name: String,
    /// The link.
    pub link: String,
    /// Indices into the link's `collisions`.
    pub shapes: Vec<usize>,
}

/// The spawn state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FactSpawn {
    /// The trunk frame's position (m, world).
    pub position: [f64; 3],
    /// The trunk frame's orientation (w, x, y, z).
    pub quaternion_wxyz: [f64; 4],
    /// Joint angles, action order (rad).
    pub q: Vec<f64>,
}

/// `hyq model --format json`: one object, keys stable (`schema_version` 1).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Facts {
    /// 1.
    pub schema_version: u32,
    /// The robot's name.
    pub robot: String,
    /// Physics time step (s).
    pub dt: f64,
    /// Physics sub-steps per env step.
    pub substeps: u32,
    /// t_max: an episode times out after this many env steps (§6.4).
    pub max_env_steps: u64,
    /// ε_joint (rad): a joint within this of a limit ends the episode (§6.2).
    pub joint_limit_margin: f64,
    /// Gravity (m/s², world).
    pub gravity: [f64; 3],
    /// Coulomb friction coefficient between any robot shape and the ground.
    pub ground_friction: f64,
    /// A tracked shape within this distance (m) of the ground counts as touching it.
    pub contact_distance: f64,
    /// Total mass (kg).
    pub total_mass: f64,
    /// The trunk (its shapes give the §6.3 fall fact).
    pub trunk: FactTracked,
    /// The feet, in observation order.
    pub feet: Vec<FactTracked>,
    /// The actuated joints, in action order.
    pub joints: Vec<FactJoint>,
    /// The spawn state (at the origin, facing +x; the `[reset]` options are not applied).
    pub spawn: FactSpawn,
    /// Every body, in model order (parents first).
    pub links: Vec<FactLink>,
}

fn vec3(v: &hyq_physics::na::Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

fn quat(q: &hyq_physics::na::UnitQuaternion<f64>) -> [f64; 4] {
    [q.w, q.i, q.j, q.k]
}

/// The facts of `model` under `config`.
pub fn facts(model: &RobotModel, config: &EnvConfig) -> Result<Facts, Failure> {
    let gains = |g: &hyq_env::config::Gains, profile: &[f64], key: &str| {
        g.resolve(profile).ok_or_else(|| {
            usage(format!(
                "{key}: expected one gain per joint ({})",
                profile.len()
            ))
        })
    };
    let kp = gains(&config.control.kp, model.kp(), "control.kp")?;
    let kd = gains(&config.control.kd, model.kd(), "control.kd")?;
    let links = model.links();
    let tracked = |i: usize| {
        let t = &model.tracked()[i];
        FactTracked {
            name: t.name.clone(),
            link: links[t.link].name.clone(),
            shapes: t.shapes.clone(),
        }
    };
    let spawn = model.spawn_state();
    let fact_links = links
        .iter()
        .map(|link| -> Result<FactLink, Failure> {
            Ok(FactLink {
                name: link.name.clone(),
                collisions: link
                    .collisions
                    .iter()
                    .map(|c| fact_shape(&link.name, c))
                    .collect::<Result<_, _>>()?,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let params = &config.physics.params;
    Ok(Facts {
        schema_version: 1,
        robot: model.name().to_owned(),
        dt: params.dt,
        substeps: config.control.sim_steps_per_env_step,
        max_env_steps: config.task.max_time_steps,
        joint_limit_margin: config.task.accepted_dist_to_bounds,
        gravity: params.gravity,
        ground_friction: params.ground_friction,
        contact_distance: params.contact_distance,
        total_mass: model.total_mass(),
        trunk: tracked(model.trunk_tracked_index()),
        feet: (0..model.num_feet()).map(tracked).collect(),
        joints: fact_joints(model, &kp, &kd),
        spawn: FactSpawn {
            position: vec3(&spawn.trunk.pose.translation.vector),
            quaternion_wxyz: quat(&spawn.trunk.pose.rotation),
            q: spawn.q.clone(),
        },
        links: fact_links,
    })
}

/// The joints of `model` in action order, with their PD gains `kp` and `kd`.
fn fact_joints(model: &RobotModel, kp: &[f64], kd: &[f64]) -> Vec<FactJoint> {
    model
        .joints()
        .iter()
        .enumerate()
        .map(|(j, joint)| FactJoint {
            name: joint.name.clone(),
            urdf_name: joint.urdf_name.clone(),
            lower: joint.lower,
            upper: joint.upper,
            effort: joint.effort,
            velocity: joint.velocity,
            standing: model.standing_pose()[j],
            kp: kp[j],
            kd: kd[j],
        })
        .collect()
}

/// A collision shape of link `link` as the facts write it.
fn fact_shape(link: &str, c: &Collision) -> Result<FactShape, Failure> {
    let (shape, half_extents, radius, half_length) = match c.shape {
        Shape::Box { half_extents } => ("box", Some(vec3(&half_extents)), None, None),
        Shape::Sphere { radius } => ("sphere", None, Some(radius), None),
        Shape::Capsule {
            radius,
            half_length,
        } => ("capsule", None, Some(radius), Some(half_length)),
        Shape::Cylinder {
            radius,
            half_length,
        } => ("cylinder", None, Some(radius), Some(half_length)),
        // `Shape` is non-exhaustive: a new shape must be described here first.
        #[allow(unreachable_patterns)]
        ref other => {
            return Err(Failure {
                status: 1,
                message: format!("link {link}: collision shape {other:?} has no JSON form"),
            });
        }
    };
    Ok(FactShape {
        name: c.name.clone(),
        shape,
        half_extents,
        radius,
        half_length,
        position: vec3(&c.origin.translation.vector),
        quaternion_wxyz: quat(&c.origin.rotation),
    })
}

/// The text of the chosen format.
fn render(args: &ModelArgs, model: &RobotModel, config: &EnvConfig) -> Result<String, Failure> {
    match args.format {
        Format::Mjcf => {
            let actuators = match args.actuators {
                ActuatorChoice::Position => Actuators::Position,
                ActuatorChoice::Motor => Actuators::Motor,
                ActuatorChoice::None => Actuators::None,
            };
            if actuators == Actuators::Position {
                let f = facts(model, config)?;
                let profile = f
                    .joints
                    .iter()
                    .zip(model.kp().iter().zip(model.kd()))
                    .all(|(j, (kp, kd))| j.kp == *kp && j.kd == *kd);
                if !profile {
                    return Err(usage(
                        "--actuators position: the MJCF's servos take the robot profile's \
                         gains; drop the control.kp / control.kd settings or use \
                         --actuators motor",
                    ));
                }
            }
            // The MuJoCo backend's solver and contact settings (`[physics.mujoco]`, its
            // defaults when absent), so that MuJoCo run on this file simulates what the
            // backend simulates.
            let mujoco: MujocoOptions = config
                .physics
                .engine_options("mujoco")
                .map_err(|e| usage(e.to_string()))?;
            mujoco.validate().map_err(|e| usage(e.to_string()))?;
            // The ground of the configuration (`[terrain]`): its first episode's, as an
            // environment built with it starts on.
            let ground =
                hyq_env::terrain::Ground::new(config, model).map_err(|e| usage(e.to_string()))?;
            let options = MjcfOptions {
                actuators,
                solver: mujoco,
                terrain: ground.terrain().clone(),
                ..MjcfOptions::from_params(&config.physics.params)
            };
            to_mjcf(model, &options)
                .map(|m| m.xml)
                .map_err(|e: mjcf::MjcfError| usage(e.to_string()))
        }
        Format::Urdf => {
            let options = UrdfOptions {
                capsules: match args.capsules {
                    CapsuleChoice::Capsule => CapsuleAs::Capsule,
                    CapsuleChoice::Cylinder => CapsuleAs::Cylinder,
                },
            };
            to_urdf(model, &options).map_err(|e: urdf::UrdfExportError| Failure {
                status: 1,
                message: e.to_string(),
            })
        }
        Format::Json => {
            let f = facts(model, config)?;
            serde_json::to_string_pretty(&f)
                .map(|mut s| {
                    s.push('\n');
                    s
                })
                .map_err(|e| Failure {
                    status: 1,
                    message: format!("cannot write the facts as JSON: {e}"),
                })
        }
    }
}

/// Runs `hyq model`.
pub fn execute(args: ModelArgs) -> Result<(), Failure> {
    let model = args.robot.model()?;
    let config = args.configuration.config()?;
    let text = render(&args, &model, &config)?;
    match &args.out {
        // A closed stdout ends the command quietly; a full one is an error (status 1).
        None => output::print(&text),
        // Written beside the file and renamed onto it once whole, as every output file is: a
        // failed write leaves the file as it was.
        Some(path) => {
            let cannot = |e: std::io::Error| Failure {
                status: 1,
                message: format!("cannot write {}: {e}", path.display()),
            };
            let mut file = OutputFile::create(path).map_err(cannot)?;
            file.write_all(text.as_bytes()).map_err(cannot)?;
            file.finish().map_err(cannot)
        }
    }
}
