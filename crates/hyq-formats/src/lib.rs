//! Robot file formats: a loaded [`RobotModel`](hyq_physics::RobotModel) written as text for
//! simulators and tools outside the project's engines, or for the MuJoCo backend.
//!
//! - [`mjcf`]: the robot as MuJoCo's XML model format, pure text (no MuJoCo needed), with the
//!   MuJoCo backend's solver and contact settings ([`mjcf::MujocoOptions`]): what the MuJoCo
//!   backend compiles, what `hyq model --format mjcf` writes and what the MuJoCo-from-Python
//!   benchmark runs.
//! - [`urdf`]: the robot written back as URDF (fixed links lumped, primitive shapes only), for
//!   engines and tools outside the project that read URDF.
//! - `xml`: what the writers share (attribute escaping, the number form).
//!
//! The formats depend on the model, never the reverse: hyq-physics knows no file format but the
//! URDF it reads, and no engine. MuJoCo's solver settings live here, beside the `<option>`
//! element they become, rather than in the MuJoCo backend's crate: `hyq model --format mjcf`
//! writes them on a build without MuJoCo's library, which that crate needs to compile.

pub mod mjcf;
pub mod mjcf_read;
pub mod robots;
pub mod urdf;
mod xml;
