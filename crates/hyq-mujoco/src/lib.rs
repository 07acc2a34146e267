//! The MuJoCo 4.0 physics backend: MuJoCo's C library (from the `mujoco-core` wheel on PyPI,
//! set up by `cargo xtask setup mujoco`), called through a small C shim.
//!
//! The robot reaches MuJoCo as the MJCF text that [`hyq_formats::mjcf`] generates from the
//! shared robot model (the same masses, inertias, joint frames, limits, damping and primitive
//! shapes every backend simulates), compiled from memory. The joint torques come from the
//! shared actuator; MuJoCo adds none of its own.
//!
//! The shim (`csrc/hyq_mujoco.c`), compiled against MuJoCo's own headers, is the only code that
//! touches `mjModel` and `mjData`; Rust passes it plain numbers. It opens the library at run
//! time, checks its version against the headers', and turns MuJoCo's errors (which would
//! otherwise end the process) into errors of the call. All of this crate's `unsafe` code is in
//! `src/world.rs`.

mod backend;
mod error;
mod options;
pub mod restitution;
mod world;

pub use backend::{MujocoBackend, world_mjcf, world_mjcf_on};
pub use error::MujocoError;
pub use options::MujocoOptions;
pub use world::{MUJOCO_VERSION, library_path};

/// Opens MuJoCo's library now (worlds open it on first use) and returns its version, or the
/// one-line reason it cannot be used (missing, or another version than the headers').
pub fn check_library() -> Result<String, MujocoError> {
    world::open_library()?;
    let v = world::library_version();
    // `open_library` refuses a library whose version differs from the headers'.
    debug_assert_eq!(v, world::header_version());
    Ok(format!(
        "{}.{}.{}",
        v / 1_000_000,
        v / 1000 % 1000,
        v % 1000
    ))
}

/// Low-level access for this crate's tests and benchmarks: a world compiled from any MJCF text
/// (for instance with actuators), driven by controls. Not part of the backend's contract.
#[doc(hidden)]
pub mod raw {
    pub use crate::backend::layout;
    pub use crate::world::{Layout, StepError, World};
}
