//! Robot file formats: robots read from MuJoCo's MJCF into the
//! [`RobotModel`](hyq_physics::RobotModel) every engine builds from, and a loaded model written
//! as text for simulators and tools outside the project's engines, or for the MuJoCo backend.
//!
//! - [`mjcf_read`]: an MJCF robot (default classes, includes, hinges, primitive geoms,
//!   `<position>` and `<motor>` actuators, keyframes) read into the model through hyq-physics'
//!   own builder; what the model cannot represent is refused by element, attribute and line.
//! - [`draft`]: a robot profile drafted from a URDF (with an SRDF's standing pose) or an MJCF
//!   file, every value commented with where it came from (`hyq robot init`, and an MJCF file
//!   given alone to `--robot`).
//! - [`robots`]: the one resolver of the front ends' robot choice: the bundled URDF robots, the
//!   bundled MJCF robot Go1, profiles whose robot file is a URDF or an MJCF file, and an MJCF
//!   file alone with a keyframe and position servos.
//! - [`mjcf`]: the robot as MuJoCo's XML model format, pure text (no MuJoCo needed), with the
//!   MuJoCo backend's solver and contact settings ([`mjcf::MujocoOptions`]): what the MuJoCo
//!   backend compiles, what `hyq model --format mjcf` writes and what the MuJoCo-from-Python
//!   benchmark runs.
//! - [`urdf`]: the robot written back as URDF (fixed links lumped, primitive shapes only), for
//!   engines and tools outside the project that read URDF.
//! - `xml`: what the writers share (attribute escaping, the number form).
//!
//! The formats depend on the model, never the reverse: hyq-physics knows no file format but the
//! URDF it reads, and no engine; so the resolver that knows MJCF robots lives here. MuJoCo's solver settings live here, beside the `<option>`
//! element they become, rather than in the MuJoCo backend's crate: `hyq model --format mjcf`
//! writes them on a build without MuJoCo's library, which that crate needs to compile.

pub mod draft;
pub mod mjcf;
pub mod mjcf_read;
pub mod robots;
pub mod urdf;
mod xml;
