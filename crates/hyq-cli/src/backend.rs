//! The physics backend a subcommand runs on: rapier (always built) or DART (built only with the
//! cargo feature `dart`, since it needs Debian's libdart).
//!
//! Subcommands are generic over `hyq_physics::Backend`; [`with_backend!`] turns the user's
//! choice into the concrete type, so the choice is made once, at the top, and the hot loops are
//! monomorphised per engine.

use clap::ValueEnum;

/// The install line for DART's C++ library (Debian's packages, as the hyq-dart crate says).
const DART_INSTALL: &str = "apt-get install -y libdart-dev libdart-collision-bullet-dev";

/// A physics backend by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BackendChoice {
    /// rapier3d, pure Rust (the default).
    Rapier,
    /// DART 6.12 through C++ (needs a build with `--features dart`).
    Dart,
}

impl BackendChoice {
    /// The backend's name on the command line (`rapier`, `dart`).
    pub fn name(self) -> &'static str {
        match self {
            BackendChoice::Rapier => "rapier",
            BackendChoice::Dart => "dart",
        }
    }
}

/// The one-line usage error for DART asked for by `option` (e.g. `--backend dart`) in a build
/// without the `dart` feature.
pub fn dart_not_built(option: &str) -> crate::Failure {
    crate::Failure {
        status: 2,
        message: format!(
            "{option}: this hyq was built without the DART backend; build it with \
             `cargo build --release -p hyq-cli --features dart` (needs DART 6.12: \
             {DART_INSTALL})"
        ),
    }
}

/// Evaluates `$body` with the type alias `$b` bound to the chosen backend type; a choice that
/// was not built evaluates to `Err(dart_not_built("--backend dart"))`.
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
            #[cfg(not(feature = "dart"))]
            $crate::backend::BackendChoice::Dart => {
                Err($crate::backend::dart_not_built("--backend dart"))
            }
        }
    };
}
pub(crate) use with_backend;
