//! The DART 6.12 physics backend: Debian's `libdart`, called from Rust through [`cxx`].
//!
//! The robot is handed to DART as plain data (bodies with mass, centre of mass, inertia tensor,
//! joint frame, axis, limits and damping; box, sphere, capsule and cylinder collision shapes), not through DART's
//! URDF loader, so DART simulates exactly the masses, frames and shapes the other backends do.
//! Collision detection uses DART's Bullet detector, the one DART 6.12 detector that handles
//! boxes, spheres, capsules and cylinders and tolerates several worlds stepping on several threads.
//!
//! All C++ and all `unsafe` code of the project live in this crate: the bridge is
//! `src/bridge.rs` (the one `#[cxx::bridge]`), `include/hyq_dart.h` and `src/hyq_dart.cc`.

mod backend;
mod bridge;
mod error;
mod sim;

pub use backend::{DartBackend, DartOptions, GROUND_HALF_EXTENT_M};
pub use error::DartError;
