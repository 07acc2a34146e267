//! The physics backend a subcommand runs on, one of hyq-engines' [`ENGINES`]: rapier (always
//! built) or an engine built in by the cargo feature of its name (`dart`, `mujoco`), since each
//! needs a C or C++ library.
//!
//! Subcommands are generic over `hyq_physics::Backend`; [`with_backend!`] turns the user's
//! choice into the concrete type (through `hyq_engines::with_engine!`), so the choice is made
//! once, at the top, and the hot loops are monomorphised per engine.

use clap::ValueEnum;
use clap::builder::PossibleValue;
use hyq_engines::{ENGINES, Engine};

/// A physics backend chosen by name (`--backend`, `--backends`): a row of hyq-engines' table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackendChoice(pub &'static Engine);

/// Every engine as a choice, in the table's order (what `--backend` accepts).
static CHOICES: [BackendChoice; ENGINES.len()] = {
    let mut out = [BackendChoice(&ENGINES[0]); ENGINES.len()];
    let mut i = 1;
    while i < ENGINES.len() {
        out[i] = BackendChoice(&ENGINES[i]);
        i += 1;
    }
    out
};

impl BackendChoice {
    /// The default engine.
    pub const DEFAULT: BackendChoice = BackendChoice(hyq_engines::DEFAULT);

    /// The backend's name on the command line (`rapier`, `dart`, `mujoco`).
    pub fn name(self) -> &'static str {
        self.0.name
    }

    /// Whether this `hyq` was built with the backend.
    pub fn built(self) -> bool {
        self.0.built
    }
}

impl ValueEnum for BackendChoice {
    fn value_variants<'a>() -> &'a [Self] {
        &CHOICES
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self.0.feature {
            Some(feature) => format!(
                "{} (needs a build with `--features {feature}`)",
                self.0.summary
            ),
            None => self.0.summary.to_owned(),
        };
        Some(PossibleValue::new(self.0.name).help(help))
    }
}

/// The one-line usage error for a backend asked for by `option` (e.g. `--backend dart`) in a
/// build without it: the cargo feature to build it with, and what that feature needs.
pub fn not_built(choice: BackendChoice, option: &str) -> crate::Failure {
    let engine = choice.0;
    let needs = engine.needs.map_or_else(
        || "always built".to_owned(),
        |n| format!("needs {}: {}", n.what, n.install),
    );
    crate::Failure {
        status: 2,
        message: format!(
            "{option}: this hyq was built without the {} backend; build it with \
             `cargo build --release -p hyq-cli --features {}` ({needs})",
            engine.title,
            engine.feature.unwrap_or(engine.name)
        ),
    }
}

/// A list of backends separated by commas (`rapier,dart,mujoco`), each a name of hyq-engines'
/// table: `hyq compare --backends` (which then asks for two or three different ones) and
/// `hyq bench --backends` (any number, repeats allowed). Whether each is built is checked where
/// the list is used, with [`not_built`]'s error.
pub fn parse_backend_list(s: &str) -> Result<Vec<BackendChoice>, String> {
    s.split(',')
        .map(str::trim)
        .map(|name| {
            <BackendChoice as ValueEnum>::from_str(name, false).map_err(|_| {
                format!(
                    "unknown backend {name:?} (possible backends: {})",
                    hyq_engines::NAMES.join(", ")
                )
            })
        })
        .collect()
}

/// Evaluates `$body` with the type alias `$b` bound to the chosen backend type; a choice that
/// was not built evaluates to `Err(not_built(choice, "--backend <name>"))`.
macro_rules! with_backend {
    ($choice:expr, $b:ident => $body:expr) => {{
        let choice: $crate::backend::BackendChoice = $choice;
        match hyq_engines::with_engine!(choice.name(), $b => $body) {
            Some(out) => out,
            None => Err($crate::backend::not_built(
                choice,
                &format!("--backend {}", choice.name()),
            )),
        }
    }};
}
pub(crate) use with_backend;
