//! Prints the bundled robot as MJCF (MuJoCo's XML model format), for loading it in MuJoCo from
//! anywhere (e.g. `mujoco.MjModel.from_xml_string` in Python), with MuJoCo's default solver
//! settings and the default physics parameters (1 ms step, μ = 1).
//!
//! ```sh
//! cargo run -p hyq-physics --example mjcf -- [none|motor|position] > hyq.xml
//! ```
//!
//! The argument chooses the actuators (`hyq_physics::mjcf::Actuators`): none (write joint
//! torques into `qfrc_applied` yourself), `<motor>`s (control = joint torque), or `<position>`
//! servos with the profile's PD gains (control = joint target; MuJoCo runs the PD inside its
//! step). Default: position.

use std::process::ExitCode;

use hyq_physics::mjcf::{Actuators, MjcfOptions, to_mjcf};

fn main() -> ExitCode {
    let arg = std::env::args().nth(1);
    let actuators = match arg.as_deref() {
        None | Some("position") => Actuators::Position,
        Some("motor") => Actuators::Motor,
        Some("none") => Actuators::None,
        Some(other) => {
            eprintln!("mjcf: unknown actuators {other:?} (expected none, motor or position)");
            return ExitCode::from(2);
        }
    };
    let options = MjcfOptions {
        actuators,
        ..MjcfOptions::default()
    };
    match to_mjcf(&hyq_physics::bundled::hyq(), &options) {
        Ok(m) => {
            print!("{}", m.xml);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("mjcf: {e}");
            ExitCode::FAILURE
        }
    }
}
