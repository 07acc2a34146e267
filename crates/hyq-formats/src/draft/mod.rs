//! A robot profile drafted from a robot file (`hyq robot init`): the trunk, the feet, the
//! joints in the project's order and names, the standing pose, the spawn height, PD gains,
//! joint limits and a scripted trot, each written with a comment saying where it came from, for
//! a user to read, check and edit.
//!
//! - Trunk: the file's root (the URDF's root link, the MJCF's free body).
//! - Legs: each leaf body (after fixed links are lumped) ends a leg, whose joints are those on
//!   its way back to the trunk; its foot is its collision sphere (the lowest, if several),
//!   else its lowest collision shape at the standing pose.
//! - Names and order: four legs of three joints, one hip in each quadrant about the trunk
//!   (x forward, y left), an abduction axis along x then two flexion axes along y, become
//!   lf, lh, rf, rh with haa, hfe, kfe, leg-major; anything else keeps the file's order and
//!   names (and gets no trot).
//! - Standing pose: an SRDF's `<group_state name="standing">`, else an MJCF's `home`
//!   keyframe (else its first keyframe), else zeros, said so in the comment.
//! - Spawn height: forward kinematics at the standing pose, the lowest collision shape
//!   [`CLEARANCE`] above the ground, rounded up to 0.1 mm.
//! - Standing height: measured by a settle run on an engine, which this crate has none of: the
//!   caller runs it and records it with [`Draft::set_standing_height`] (`hyq robot init` runs
//!   rapier for 1 s); left out, the environment uses the spawn height.
//! - Gains: an MJCF's `<position>` actuators' `kp` and `kv`, else a rule (each foot carrying
//!   an equal share of the weight, the most loaded joint sagging at most 0.05 rad; a leg in
//!   the air damped at a ratio of 0.6).
//! - Limits: the URDF's ranges and velocity limits, written out; an MJCF gives ranges but no
//!   velocity limit: [`DEFAULT_VELOCITY`], said so.
//! - Trot: when the legs are named, a diagonal trot at ANYmal C's tuned figures, a start to
//!   tune from.

mod gains;
mod legs;
mod standing;
mod text;
mod types;

use std::path::Path;

use hyq_physics::{
    ModelError, Profile, RobotModel, input,
    profile::{FootEntry, Gains, GaitEntry, GaitLegEntry, JointEntry, Spawn},
};
use urdf_rs::JointType;

use crate::mjcf_read::{self, MjcfRobot};
pub use types::{CLEARANCE, DEFAULT_VELOCITY, DraftError, TROT};
use types::{Notes, Source};

/// A drafted profile, its robot and where each value came from.
#[derive(Debug, Clone)]
pub struct Draft {
    profile: Profile,
    source: Source,
    notes: Notes,
}

/// Drafts a profile for the robot file at `robot` (MJCF when its extension is `.xml`, else
/// URDF), with the standing pose from `srdf` when given; `urdf_key` is what the profile's
/// `urdf` key says (the robot file's path relative to where the profile will be).
pub fn draft_file(robot: &Path, srdf: Option<&Path>, urdf_key: &str) -> Result<Draft, DraftError> {
    let origin = robot.display().to_string();
    // An `.xml` robot file is MJCF, as for `--robot` and a profile's `urdf` key.
    let is_mjcf = robot
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"));
    let source = if is_mjcf {
        Source::Mjcf(Box::new(mjcf_read::read_file(robot)?))
    } else {
        Source::Urdf(read_urdf(robot)?)
    };
    draft(source, &origin, srdf, urdf_key)
}

/// Drafts a profile for an MJCF robot already read (`origin` names its file in messages).
pub fn draft_mjcf(robot: MjcfRobot, origin: &str, urdf_key: &str) -> Result<Draft, DraftError> {
    draft(Source::Mjcf(Box::new(robot)), origin, None, urdf_key)
}

impl Draft {
    /// The drafted profile.
    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// The robot with the drafted profile.
    pub fn model(&self) -> Result<RobotModel, ModelError> {
        self.source.model(&self.profile)
    }

    /// Records the standing height (m) a settle run measured, and how (a sentence for the
    /// comment: the engine, the time, the pose).
    pub fn set_standing_height(&mut self, height: f64, how: &str) {
        // Rounded to 0.1 mm, as the bundled profiles write it.
        self.profile.spawn.standing_height = Some((height * 1e4).round() / 1e4);
        self.notes.standing_height = how.to_owned();
    }

    /// Says why the standing height was not measured (the comment above its absent key).
    pub fn set_standing_note(&mut self, note: &str) {
        note.clone_into(&mut self.notes.standing_height);
    }

    /// The profile as commented TOML.
    pub fn to_toml(&self) -> String {
        text::write(&self.profile, &self.notes)
    }
}

/// A URDF file read through the capped reader and parsed, its nesting checked first.
fn read_urdf(path: &Path) -> Result<urdf_rs::Robot, DraftError> {
    let origin = path.display().to_string();
    let text = input::read_text(path, &input::URDF).map_err(|e| DraftError::at(&origin, e))?;
    hyq_physics::model::parse_urdf(&text)
        .map_err(|e| DraftError::at(&origin, format_args!("not a URDF: {e}")))
}

/// The draft: the provisional model (file order) gives the legs, which give the order and
/// names; the named model gives the heights, gains and limits.
fn draft(
    source: Source,
    origin: &str,
    srdf: Option<&Path>,
    urdf_key: &str,
) -> Result<Draft, DraftError> {
    let model_err = |e: ModelError| DraftError::at(origin, e);
    let desc = source.description();
    let hinges: Vec<String> = desc
        .joints
        .iter()
        .filter(|j| matches!(j.joint_type, JointType::Revolute | JointType::Continuous))
        .map(|j| j.name.clone())
        .collect();
    let trunk = root(&source, origin)?;
    if hinges.is_empty() {
        return Err(DraftError::at(
            origin,
            "a robot with no legs: it has no hinge (revolute) joint",
        ));
    }
    let standing = standing::standing(&source, &hinges, srdf)?;
    let velocity = matches!(source, Source::Mjcf(_)).then_some(DEFAULT_VELOCITY);
    let mut profile = Profile {
        name: robot_name(&source, origin),
        urdf: urdf_key.to_owned(),
        trunk,
        feet: Vec::new(),
        joints: hinges
            .iter()
            .enumerate()
            .map(|(i, h)| JointEntry {
                name: format!("j{i}"),
                urdf: h.clone(),
                standing: standing
                    .angles
                    .get(h)
                    .copied()
                    .unwrap_or_else(|| zero_within(desc, h)),
                kp: None,
                kd: None,
                lower: None,
                upper: None,
                effort: None,
                velocity,
            })
            .collect(),
        spawn: Spawn {
            height: 1.0,
            standing_height: None,
        },
        gains: Gains { kp: 1.0, kd: 0.0 },
        observation: None,
        gait: None,
    };
    let provisional = source.model(&profile).map_err(model_err)?;
    let legs = legs::legs(&provisional, origin)?;
    let mut notes = Notes::default();
    order(&provisional, &legs, &mut profile, &mut notes);
    let model = source.model(&profile).map_err(model_err)?;
    spawn(&model, &mut profile, &mut notes);
    let drafted = gains::gains(&source, &model);
    profile.gains = Gains {
        kp: drafted.kp,
        kd: drafted.kd,
    };
    limits(&source, &model, &drafted, &mut profile, &mut notes);
    if legs.named {
        profile.gait = Some(trot());
    }
    text::describe(
        &source,
        origin,
        &standing.source,
        &legs,
        &drafted.why,
        &mut notes,
    );
    // The draft must load as it is written.
    source.model(&profile).map_err(model_err)?;
    Ok(Draft {
        profile,
        source,
        notes,
    })
}

/// 0, or the nearer end of joint `name`'s range when 0 is outside it: the standing angle of
/// a joint no source gives one for.
fn zero_within(desc: &urdf_rs::Robot, name: &str) -> f64 {
    desc.joints
        .iter()
        .find(|j| j.name == name && j.joint_type == JointType::Revolute)
        .map_or(0.0, |j| {
            let (lo, hi) = (j.limit.lower, j.limit.upper);
            if lo <= hi { 0.0f64.clamp(lo, hi) } else { 0.0 }
        })
}

/// The trunk: the MJCF's free body, or the URDF's one root link (not `world`: a robot fixed
/// to the world has no free root).
fn root(source: &Source, origin: &str) -> Result<String, DraftError> {
    let desc = match source {
        Source::Mjcf(m) => return Ok(m.root.clone()),
        Source::Urdf(r) => r,
    };
    let roots: Vec<&str> = desc
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !desc.joints.iter().any(|j| j.child.link == *l))
        .collect();
    match roots.as_slice() {
        [one] if one.eq_ignore_ascii_case("world") => Err(DraftError::at(
            origin,
            "no free root: the root link is `world`, so the robot is fixed to the ground; remove \
             `world` and its joint to make the trunk free",
        )),
        [one] => Ok((*one).to_owned()),
        [] => Err(DraftError::at(
            origin,
            "no root link: every link is some joint's child",
        )),
        many => Err(DraftError::at(
            origin,
            format_args!(
                "{} root links (one robot is read): {}",
                many.len(),
                many.iter().take(4).copied().collect::<Vec<_>>().join(", ")
            ),
        )),
    }
}

/// The robot's name: the file's (MJCF `model`, URDF `name`), reduced to the characters a
/// profile name allows, else the file's stem, else `robot`.
fn robot_name(source: &Source, origin: &str) -> String {
    let given = match source {
        Source::Mjcf(m) => m.name.clone().unwrap_or_default(),
        Source::Urdf(r) => r.name.clone(),
    };
    let stem = Path::new(origin)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    [given, stem]
        .iter()
        .map(|n| text::clean_name(n))
        .find(|n| hyq_physics::bounds::check_name(n).is_ok())
        .unwrap_or_else(|| "robot".to_owned())
}

/// Puts the joints and feet in their order with their names: leg-major with the project's
/// names when the legs are named, else the file's order and names.
fn order(model: &RobotModel, legs: &legs::Legs, profile: &mut Profile, notes: &mut Notes) {
    let file_order = profile.joints.clone();
    let links = model.links();
    profile.feet = legs
        .legs
        .iter()
        .enumerate()
        .map(|(i, leg)| {
            let c = &links[leg.leaf].collisions[leg.foot];
            let name = if legs.named {
                legs::LEG_NAMES[i].to_owned()
            } else {
                text::name_or(&c.urdf_link, &format!("foot{i}"))
            };
            let which = if c.name.is_some() {
                ""
            } else {
                " (unnamed: every shape of the link is the foot)"
            };
            notes.foot.push(format!("{}{which}", leg.foot_why));
            FootEntry {
                name,
                link: c.urdf_link.clone(),
                collision: c.name.clone(),
            }
        })
        .collect();
    if legs.named {
        profile.joints = legs
            .legs
            .iter()
            .enumerate()
            .flat_map(|(i, leg)| {
                leg.joints.iter().enumerate().map(move |(k, &j)| {
                    (
                        format!("{}_{}", legs::LEG_NAMES[i], legs::JOINT_ROLES[k]),
                        j,
                    )
                })
            })
            .map(|(name, j)| JointEntry {
                name,
                ..file_order[j].clone()
            })
            .collect();
    } else {
        for (i, entry) in profile.joints.iter_mut().enumerate() {
            entry.name = text::name_or(&entry.urdf, &format!("j{i}"));
        }
    }
}

/// The spawn height: the lowest collision shape [`CLEARANCE`] above the ground at the standing
/// pose, trunk level, rounded up to 0.1 mm.
fn spawn(model: &RobotModel, profile: &mut Profile, notes: &mut Notes) {
    let poses = legs::standing_poses(model);
    let depth = -model.lowest_z(&poses);
    let feet = (0..model.num_feet())
        .map(|f| -model.tracked_lowest_z(f, &poses))
        .fold(f64::NEG_INFINITY, f64::max);
    let height = ((depth + CLEARANCE) * 1e4).ceil() / 1e4;
    profile.spawn.height = height;
    let what = if feet >= depth - 1e-9 {
        "the foot bottoms".to_owned()
    } else {
        format!(
            "the robot's lowest collision shape ({:.6} m; the feet {feet:.6} m: a shape below the feet, check it)",
            depth
        )
    };
    notes.spawn_height = format!(
        "Height (m) of the trunk frame's origin at spawn, trunk level, joints at the standing \
         pose. Forward kinematics puts {what} {depth:.6} m below the trunk frame, so {height} \
         leaves them {:.2} mm above the ground.",
        (height - depth) * 1e3
    );
    notes.standing_height = "Not measured (no settle run): the environment takes the spawn height as the standing height.".to_owned();
}

/// Each joint's range and velocity limit (written out), its own gains where they differ, and
/// its comment.
fn limits(
    source: &Source,
    model: &RobotModel,
    drafted: &gains::Drafted,
    profile: &mut Profile,
    notes: &mut Notes,
) {
    for ((entry, joint), own) in profile
        .joints
        .iter_mut()
        .zip(model.joints())
        .zip(&drafted.per_joint)
    {
        let finite = joint.lower.is_finite() && joint.upper.is_finite();
        if finite {
            entry.lower = Some(joint.lower);
            entry.upper = Some(joint.upper);
        }
        entry.velocity = Some(joint.velocity);
        if let Some((kp, kd)) = own {
            entry.kp = Some(*kp);
            entry.kd = Some(*kd);
        }
        let mut note = format!(
            "{} {:?}",
            source.format(),
            hyq_physics::printable(&entry.urdf)
        );
        if !finite {
            note.push_str(", no finite range");
        }
        if own.is_some() {
            note.push_str(", kp/kd: its <position> actuator");
        }
        notes.joint.push(note);
    }
}

/// The drafted trot: diagonal pairs lf + rh and rf + lh half a cycle apart, at [`TROT`].
fn trot() -> GaitEntry {
    let leg = |name: &str, phase: f64| GaitLegEntry {
        hip: format!("{name}_hfe"),
        knee: format!("{name}_kfe"),
        phase,
    };
    GaitEntry {
        frequency_hz: TROT[0],
        hip_amplitude: TROT[1],
        knee_lift: TROT[2],
        ramp_s: TROT[3],
        legs: vec![
            leg("lf", 0.0),
            leg("lh", 0.5),
            leg("rf", 0.5),
            leg("rh", 0.0),
        ],
    }
}
