//! The HyQ robot shipped with the project (`assets/hyq/`), compiled into the crate so that
//! tools and bindings work from any directory.

use std::sync::{Arc, OnceLock};

use crate::error::ModelError;
use crate::model::RobotModel;
use crate::profile::Profile;

/// The text of `assets/hyq/hyq.urdf`.
pub const HYQ_URDF: &str = include_str!("../../../assets/hyq/hyq.urdf");

/// The text of `assets/hyq/profile.toml`.
pub const HYQ_PROFILE: &str = include_str!("../../../assets/hyq/profile.toml");

/// Builds the bundled HyQ afresh (see [`hyq`] for the shared instance).
pub fn load_hyq() -> Result<RobotModel, ModelError> {
    let profile = Profile::from_toml_str(HYQ_PROFILE, "bundled assets/hyq/profile.toml")?;
    RobotModel::from_urdf_str(HYQ_URDF, "bundled assets/hyq/hyq.urdf", &profile)
}

/// The bundled HyQ, parsed once per process and shared.
pub fn hyq() -> Arc<RobotModel> {
    static HYQ: OnceLock<Arc<RobotModel>> = OnceLock::new();
    HYQ.get_or_init(|| {
        // The bundled assets are compiled in and loaded by this crate's tests
        // (`tests/bundled_hyq.rs`), so a failure here is a broken build, not bad input.
        #[allow(clippy::expect_used)]
        Arc::new(load_hyq().expect("the bundled HyQ assets are valid"))
    })
    .clone()
}
