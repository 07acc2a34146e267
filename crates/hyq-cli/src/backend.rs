//! The physics backend a subcommand runs on: rapier (always built), DART (built only with the
//! cargo feature `dart`, since it needs Debian's libdart) or MuJoCo (built only with the cargo
//! feature `mujoco`, since it needs MuJoCo's library).
//!
//! Subcommands are generic over `hyq_physics::Backend`; [`with_backend!`] turns the user's
//! choice into the concrete type, so the choice is made once, at the top, and the hot loops are
//! monomorphised per engine.

use clap::ValueEnum;

/// The install line for DART's C++ library (Debian's packages, as the hyq-dart crate says).
const DART_INSTALL: &str = "apt-get install -y libdart-dev libdart-collision-bullet-dev";

/// The command that fetches MuJoCo's C library (as the hyq-mujoco crate says).
const MUJOCO_SETUP: &str = "cargo xtask setup mujoco";

/// A physics backend by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BackendChoice {
    /// rapier3d, pure Rust (the default).
    Rapier,
    /// DART 6.12 through C++ (needs a build with `--features dart`).
    Dart,
    /// MuJoCo 4.0 through its C API (needs a build with `--features mujoco`).
    Mujoco,
}

impl BackendChoice {
    /// The backend's name on the command line (`rapier`, `dart`, `mujoco`).
    pub fn name(self) -> &'static str {
        match self {
            BackendChoice::Rapier => "rapier",
            BackendChoice::Dart => "dart",
            BackendChoice::Mujoco => "mujoco",
        }
    }

    /// Whether this `hyq` was built with the backend.
    pub fn built(self) -> bool {
        match self {
            BackendChoice::Rapier => true,
            BackendChoice::Dart => cfg!(feature = "dart"),
            BackendChoice::Mujoco => cfg!(feature = "mujoco"),
        }
    }
}

/// The one-line usage error for a backend asked for by `option` (e.g. `--backend dart`) in a
/// build without it: the cargo feature to build it with, and what that feature needs.
pub fn not_built(choice: BackendChoice, option: &str) -> crate::Failure {
    let (name, needs) = match choice {
        BackendChoice::Dart => ("DART", format!("needs DART 6.12: {DART_INSTALL}")),
        BackendChoice::Mujoco => (
            "MuJoCo",
            format!("needs MuJoCo 4.0.0's library, from `{MUJOCO_SETUP}`"),
        ),
        BackendChoice::Rapier => ("rapier", "always built".to_owned()),
    };
    crate::Failure {
        status: 2,
        message: format!(
            "{option}: this hyq was built without the {name} backend; build it with \
             `cargo build --release -p hyq-cli --features {}` ({needs})",
            choice.name()
        ),
    }
}

/// Evaluates `$body` with the type alias `$b` bound to the chosen backend type; a choice that
/// was not built evaluates to `Err(not_built(choice, "--backend <name>"))`.
macro_rules! with_backend {
    ($choice:expr, $b:ident => $body:expr) => {
        match $choice {
            $crate::backend::BackendChoice::Rapier => {
                type $b = hyq_rapier::RapierBackend;
                $body
            }
            #[cfg(feature = "dart")]
            $crate::backend::BackendChoice::Dart => {
                type $b = hyq_dart::DartBackend;
                $body
            }
            #[cfg(feature = "mujoco")]
            $crate::backend::BackendChoice::Mujoco => {
                type $b = hyq_mujoco::MujocoBackend;
                $body
            }
            #[allow(unreachable_patterns)]
            other => Err($crate::backend::not_built(
                other,
                &format!("--backend {}", other.name()),
            )),
        }
    };
}
pub(crate) use with_backend;
