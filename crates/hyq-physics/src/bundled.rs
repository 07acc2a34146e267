//! The robots shipped with the project (`assets/<name>/`), compiled into the crate so that tools
//! and bindings work from any directory, and [`resolve`]: the one way every front end turns a
//! user's robot choice (a bundled name or a profile path) into a model.
//!
//! | name | robot | source |
//! |---|---|---|
//! | `hyq` (the default) | IIT's HyQ, 86.8 kg, 12 joints | `assets/hyq/` |
//! | `anymal_c` | ANYbotics' ANYmal C, 52.1 kg, 12 joints | `assets/anymal_c/` |

use std::path::Path;
use std::sync::{Arc, OnceLock};

use crate::error::ModelError;
use crate::model::RobotModel;
use crate::profile::Profile;

/// The text of `assets/hyq/hyq.urdf`.
pub const HYQ_URDF: &str = include_str!("../../../assets/hyq/hyq.urdf");

/// The text of `assets/hyq/profile.toml`.
pub const HYQ_PROFILE: &str = include_str!("../../../assets/hyq/profile.toml");

/// The text of `assets/anymal_c/anymal_c.urdf`.
pub const ANYMAL_C_URDF: &str = include_str!("../../../assets/anymal_c/anymal_c.urdf");

/// The text of `assets/anymal_c/profile.toml`.
pub const ANYMAL_C_PROFILE: &str = include_str!("../../../assets/anymal_c/profile.toml");

/// The bundled robots' names, the default (`hyq`) first.
pub const NAMES: [&str; 2] = ["hyq", "anymal_c"];

/// The name of the robot front ends use when none is chosen.
pub const DEFAULT: &str = NAMES[0];

/// A bundled robot's files, as compiled in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sources {
    /// The robot's name (one of [`NAMES`]).
    pub name: &'static str,
    /// The URDF text.
    pub urdf: &'static str,
    /// The profile text.
    pub profile: &'static str,
}

/// The compiled-in files of bundled robot `name`, or `None` if there is no such robot.
pub fn sources(name: &str) -> Option<Sources> {
    let (urdf, profile) = match name {
        "hyq" => (HYQ_URDF, HYQ_PROFILE),
        "anymal_c" => (ANYMAL_C_URDF, ANYMAL_C_PROFILE),
        _ => return None,
    };
    Some(Sources {
        name: NAMES.iter().find(|n| **n == name)?,
        urdf,
        profile,
    })
}

/// Builds bundled robot `name` afresh (see [`by_name`] for the shared instance).
pub fn load(name: &str) -> Result<RobotModel, ModelError> {
    let s = sources(name).ok_or_else(|| unknown(name))?;
    let dir = format!("bundled assets/{}", s.name);
    let profile = Profile::from_toml_str(s.profile, &format!("{dir}/profile.toml"))?;
    RobotModel::from_urdf_str(s.urdf, &format!("{dir}/{}", profile.urdf), &profile)
}

/// Bundled robot `name`, parsed once per process and shared; `None` if there is no such robot.
pub fn by_name(name: &str) -> Option<Arc<RobotModel>> {
    static MODELS: [OnceLock<Arc<RobotModel>>; NAMES.len()] =
        [const { OnceLock::new() }; NAMES.len()];
    let i = NAMES.iter().position(|n| *n == name)?;
    Some(
        MODELS[i]
            .get_or_init(|| {
                // The bundled assets are compiled in and loaded by this crate's tests
                // (`tests/bundled_hyq.rs`, `tests/bundled_anymal_c.rs`), so a failure here is a
                // broken build, not bad input.
                #[allow(clippy::expect_used)]
                Arc::new(load(name).expect("the bundled robot assets are valid"))
            })
            .clone(),
    )
}

/// Builds the bundled HyQ afresh (see [`hyq`] for the shared instance).
pub fn load_hyq() -> Result<RobotModel, ModelError> {
    load("hyq")
}

/// The bundled HyQ, parsed once per process and shared.
pub fn hyq() -> Arc<RobotModel> {
    // `hyq` is in NAMES.
    #[allow(clippy::expect_used)]
    by_name("hyq").expect("hyq is bundled")
}

/// The bundled ANYmal C, parsed once per process and shared.
pub fn anymal_c() -> Arc<RobotModel> {
    // `anymal_c` is in NAMES.
    #[allow(clippy::expect_used)]
    by_name("anymal_c").expect("anymal_c is bundled")
}

/// A robot chosen by the user: a bundled robot's name ([`NAMES`]), or the path to a robot
/// profile (a `.toml` file next to its URDF, see [`crate::Profile`]). Bundled models are
/// shared; a profile is loaded afresh. Every front end resolves its robot option through this
/// one function, so they accept the same choices and give the same errors.
///
/// A choice that is neither gives an error naming it, the bundled names and what a path must
/// be; a profile that cannot be used gives the loader's error, naming the file.
pub fn resolve(choice: &str) -> Result<Arc<RobotModel>, ModelError> {
    if let Some(model) = by_name(choice) {
        return Ok(model);
    }
    let path = Path::new(choice);
    let looks_like_path = path.extension().is_some() || choice.contains(['/', '\\']);
    if !looks_like_path {
        return Err(unknown(choice));
    }
    RobotModel::load(path).map(Arc::new)
}

fn unknown(choice: &str) -> ModelError {
    ModelError::UnknownRobot {
        choice: choice.to_owned(),
        bundled: NAMES.join(", "),
    }
}
