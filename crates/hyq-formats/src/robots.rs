//! Every robot a front end can name, whatever its file format: the bundled URDF robots of
//! [`hyq_physics::bundled`], the bundled MJCF robot Go1 (`assets/go1/`), and robot profiles
//! whose robot file is a URDF or an MJCF file (`urdf = "robot.xml"`: a `.xml` robot file is
//! read as MJCF), and an MJCF file alone when it has a keyframe and a `<position>` actuator on
//! every joint (its profile drafted in memory, [`crate::draft`]). [`resolve_with`] is what the
//! command line and the Python bindings call, so they accept the same choices and give the
//! same errors.
//!
//! | name | robot | source |
//! |---|---|---|
//! | `hyq` (the default) | IIT's HyQ, 86.8 kg, 12 joints | `assets/hyq/` (URDF) |
//! | `anymal_c` | ANYbotics' ANYmal C, 52.1 kg, 12 joints | `assets/anymal_c/` (URDF) |
//! | `go1` | Unitree Go1, 12.7 kg, 12 joints | `assets/go1/` (MJCF, MuJoCo Playground) |
//! | `a1` | Unitree A1, 13.7 kg, 12 joints | `assets/a1/` (URDF, example-robot-data) |
//! | `go1_urdf` | Unitree Go1, 13.1 kg, 12 joints | `assets/go1_urdf/` (URDF, example-robot-data) |
//! | `anymal_b` | ANYbotics' ANYmal B, 30.5 kg, 12 joints | `assets/anymal_b/` (URDF, example-robot-data) |
//! | `laikago` | Unitree Laikago, 25.4 kg, 12 joints | `assets/laikago/` (URDF, example-robot-data) |

use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use hyq_physics::{ModelError, Profile, RobotModel, bundled, input};

use crate::draft::{self, DraftError};
use crate::mjcf_read::{self, ActuatorKind, MjcfReadError, MjcfRobot};

/// The text of `assets/go1/go1.xml`.
pub const GO1_MJCF: &str = include_str!("../../../assets/go1/go1.xml");

/// The text of `assets/go1/profile.toml`.
pub const GO1_PROFILE: &str = include_str!("../../../assets/go1/profile.toml");

/// The field's URDF robots from example-robot-data 6.0.0, compiled in as (name, URDF text,
/// profile text): small files of primitives (15 to 29 kB of URDF each).
pub const FIELD: [(&str, &str, &str); 4] = [
    (
        "a1",
        include_str!("../../../assets/a1/a1.urdf"),
        include_str!("../../../assets/a1/profile.toml"),
    ),
    (
        "go1_urdf",
        include_str!("../../../assets/go1_urdf/go1.urdf"),
        include_str!("../../../assets/go1_urdf/profile.toml"),
    ),
    (
        "anymal_b",
        include_str!("../../../assets/anymal_b/anymal_b.urdf"),
        include_str!("../../../assets/anymal_b/profile.toml"),
    ),
    (
        "laikago",
        include_str!("../../../assets/laikago/laikago.urdf"),
        include_str!("../../../assets/laikago/profile.toml"),
    ),
];

/// Every bundled robot's name: [`hyq_physics::bundled::NAMES`] (the URDF robots, the default
/// first), then the MJCF one, then the field's URDF robots ([`FIELD`]).
pub const NAMES: [&str; 7] = [
    "hyq", "anymal_c", "go1", "a1", "go1_urdf", "anymal_b", "laikago",
];

/// Why a robot could not be had.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RobotError {
    /// The model could not be built (or a URDF robot's files read).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// The MJCF file could not be read.
    #[error(transparent)]
    Mjcf(#[from] MjcfReadError),
    /// A profile file whose robot could not be had: the profile's path, then why.
    #[error("robot profile {}: {source}", path.display())]
    InProfile {
        /// The profile file.
        path: PathBuf,
        /// What was wrong with it or its robot file.
        #[source]
        source: Box<RobotError>,
    },
    /// An MJCF file given alone that cannot run without a profile.
    #[error(
        "{}: {why}, so it runs only through a robot profile that names it (`urdf = \"{}\"`): \
         draft one with `hyq robot init {}`; see docs/adding-a-robot.md",
        path.display(),
        path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
        path.display()
    )]
    NeedsProfile {
        /// The MJCF file given.
        path: PathBuf,
        /// What it lacks.
        why: String,
    },
    /// The profile drafted for an MJCF file given alone could not be made, or its robot did not
    /// stand.
    #[error(transparent)]
    Draft(#[from] DraftError),
    /// A choice that is neither a bundled robot nor a path.
    #[error(
        "unknown robot {choice:?}: not a bundled robot ({}) nor a path to a robot profile (a \
         .toml file next to its URDF or MJCF file)",
        NAMES.join(", ")
    )]
    Unknown {
        /// What was asked for.
        choice: String,
    },
}

/// The bundled Go1 as read from its MJCF (the notes and keyframes with it).
pub fn go1_mjcf() -> Result<MjcfRobot, MjcfReadError> {
    mjcf_read::read_str(GO1_MJCF, "bundled assets/go1/go1.xml")
}

/// The bundled Go1's profile.
pub fn go1_profile() -> Result<Profile, ModelError> {
    Profile::from_toml_str(GO1_PROFILE, "bundled assets/go1/profile.toml")
}

/// The bundled Go1 as URDF text: the description its model is built from
/// ([`MjcfRobot::urdf_description`]), before fixed bodies are lumped; what the conformance
/// kit's checks against a URDF read independently.
pub fn go1_urdf() -> Result<String, RobotError> {
    let robot = go1_mjcf()?.urdf_description()?;
    urdf_rs::write_to_string(&robot).map_err(|e| {
        RobotError::Mjcf(MjcfReadError(format!(
            "bundled Go1: its URDF description does not write: {e}"
        )))
    })
}

/// Builds the bundled Go1 afresh (see [`by_name`] for the shared instance).
pub fn load_go1() -> Result<RobotModel, RobotError> {
    Ok(go1_mjcf()?.model(&go1_profile()?)?)
}

/// Builds field robot `name` (one of [`FIELD`]) afresh; `None` if there is no such robot.
pub fn load_field(name: &str) -> Option<Result<RobotModel, ModelError>> {
    let (_, urdf, profile) = FIELD.iter().find(|(n, _, _)| *n == name)?;
    let dir = format!("bundled assets/{name}");
    Some(
        Profile::from_toml_str(profile, &format!("{dir}/profile.toml"))
            .and_then(|p| RobotModel::from_urdf_str(urdf, &format!("{dir}/{}", p.urdf), &p)),
    )
}

/// Bundled robot `name` (any of [`NAMES`]), parsed once per process and shared; `None` if
/// there is no such robot.
pub fn by_name(name: &str) -> Option<Arc<RobotModel>> {
    if let Some(model) = bundled::by_name(name) {
        return Some(model);
    }
    static FIELD_MODELS: [OnceLock<Arc<RobotModel>>; FIELD.len()] =
        [const { OnceLock::new() }; FIELD.len()];
    if let Some(i) = FIELD.iter().position(|(n, _, _)| *n == name) {
        return Some(
            FIELD_MODELS[i]
                .get_or_init(|| {
                    // Compiled in and loaded by this crate's tests (`tests/field_robots.rs`), so
                    // a failure here is a broken build, not bad input.
                    #[allow(clippy::expect_used)]
                    Arc::new(
                        load_field(name)
                            .expect("a field robot")
                            .expect("valid assets"),
                    )
                })
                .clone(),
        );
    }
    static GO1: OnceLock<Arc<RobotModel>> = OnceLock::new();
    (name == "go1").then(|| {
        GO1.get_or_init(|| {
            // The bundled assets are compiled in and loaded by this crate's tests
            // (`tests/bundled_go1.rs`), so a failure here is a broken build, not bad input.
            #[allow(clippy::expect_used)]
            Arc::new(load_go1().expect("the bundled Go1 assets are valid"))
        })
        .clone()
    })
}

/// A robot chosen by the user: a bundled robot's name ([`NAMES`]) or the path to a robot
/// profile whose robot file is a URDF or an MJCF (`.xml`) file. Bundled models are shared; a
/// profile is loaded afresh.
pub fn resolve(choice: &str) -> Result<Arc<RobotModel>, RobotError> {
    resolve_with(choice, None)
}

/// How a front end measures a drafted robot's standing height: the trunk frame's height (m)
/// after a settle run (the front ends hold the standing pose for 1 s on rapier), or why it
/// could not stand.
pub type Settle<'a> = &'a dyn Fn(Arc<RobotModel>) -> Result<f64, String>;

/// [`resolve`], with an MJCF file given alone drafted in memory ([`mjcf_alone`]) and its
/// standing height measured by `settle` (without one, the spawn height stands for it).
pub fn resolve_with(
    choice: &str,
    settle: Option<Settle<'_>>,
) -> Result<Arc<RobotModel>, RobotError> {
    if let Some(model) = by_name(choice) {
        return Ok(model);
    }
    let path = Path::new(choice);
    let looks_like_path = path.extension().is_some() || choice.contains(['/', '\\']);
    if !looks_like_path {
        return Err(RobotError::Unknown {
            choice: choice.to_owned(),
        });
    }
    if is_mjcf(path) {
        return mjcf_alone(path, settle).map(Arc::new);
    }
    load_profile(path).map(Arc::new)
}

/// An MJCF file with no profile: it must give a standing pose (a keyframe) and gains (a
/// `<position>` actuator on every joint); the rest is drafted as `hyq robot init` drafts it,
/// and the standing height measured by `settle` when given.
pub fn mjcf_alone(path: &Path, settle: Option<Settle<'_>>) -> Result<RobotModel, RobotError> {
    let robot = mjcf_read::read_file(path)?;
    let servo = |j: &String| {
        robot
            .actuators
            .iter()
            .any(|a| &a.joint == j && matches!(a.kind, ActuatorKind::Position { .. }))
    };
    let why = if !robot.keyframes.iter().any(|k| !k.qpos.is_empty()) {
        Some("it has no keyframe with joint positions (its standing pose)".to_owned())
    } else {
        robot
            .joints
            .iter()
            .find(|j| !servo(j))
            .map(|j| format!("joint {j:?} has no <position> actuator (its gains)"))
    };
    if let Some(why) = why {
        return Err(RobotError::NeedsProfile {
            path: path.to_owned(),
            why,
        });
    }
    let origin = path.display().to_string();
    let key = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let mut draft = draft::draft_mjcf(robot, &origin, &key)?;
    if let Some(settle) = settle {
        let model = Arc::new(draft.model()?);
        let z = settle(model).map_err(|why| {
            DraftError(format!(
                "{origin}: the robot drafted from it does not stand ({why}): write \
                 a profile with `hyq robot init` and fix its standing pose or gains"
            ))
        })?;
        draft.set_standing_height(z, "measured by the front end's settle run");
    }
    Ok(draft.model()?)
}

/// Whether a robot file is read as MJCF: its extension is `.xml` (any case).
pub fn is_mjcf(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// Loads a robot from its profile file, its robot file (URDF, or MJCF for `.xml`) relative to
/// the profile. Errors name the profile.
pub fn load_profile(profile_path: &Path) -> Result<RobotModel, RobotError> {
    let text =
        input::read_text(profile_path, &input::ROBOT_PROFILE).map_err(|source| ModelError::Io {
            what: "robot profile",
            path: profile_path.to_owned(),
            source,
        })?;
    let profile = Profile::from_toml_str(&text, &profile_path.display().to_string())?;
    let robot_file = profile_path
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .join(&profile.urdf);
    if !is_mjcf(&robot_file) {
        return Ok(RobotModel::load(profile_path)?);
    }
    let built = mjcf_read::read_file(&robot_file)
        .map_err(RobotError::from)
        .and_then(|robot| Ok(robot.model(&profile)?));
    built.map_err(|e| match e {
        // These already name the MJCF file.
        RobotError::Mjcf(_) => e,
        other => RobotError::InProfile {
            path: profile_path.to_owned(),
            source: Box::new(other),
        },
    })
}
