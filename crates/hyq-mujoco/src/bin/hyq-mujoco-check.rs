//! `hyq-mujoco-check`: says whether the MuJoCo backend can run here. Opens MuJoCo's library
//! (from `MUJOCO_DIR` if set, else where the crate was built against), builds one HyQ world and
//! steps it once; prints the library's path and version, or the one-line reason it cannot be
//! used, and exits with status 1 then.
//!
//! ```sh
//! cargo run -p hyq-mujoco --bin hyq-mujoco-check
//! ```

use std::process::ExitCode;

use hyq_mujoco::{MujocoBackend, library_path};
use hyq_physics::{Backend, PhysicsParams};

fn main() -> ExitCode {
    let path = library_path();
    let run = || -> Result<String, String> {
        let version = hyq_mujoco::check_library().map_err(|e| e.to_string())?;
        let mut b = MujocoBackend::build(
            hyq_physics::bundled::hyq(),
            &PhysicsParams::default(),
            &Default::default(),
        )
        .map_err(|e| e.to_string())?;
        b.step().map_err(|e| e.to_string())?;
        Ok(version)
    };
    match run() {
        Ok(version) => {
            println!("MuJoCo {version} at {} works", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("hyq-mujoco-check: {e}");
            ExitCode::FAILURE
        }
    }
}
