//! The physics engines the environment runs on, each named once, and the one way a front turns
//! an engine's name into its `Backend` type.
//!
//! [`ENGINES`] has a row per engine: the name users type (`--backend dart`, `backend="dart"`,
//! `[physics.dart]`, the backend's `Backend::NAME`), its crate and cargo feature, what it needs
//! installed and the line that installs it, and whether this build has it. Every front reads
//! it: the `hyq` command's `--backend` values and errors, the Python package's `backend=` and
//! `hyq.backends()`, hyq-env's engine tables, spec-tests' per-engine modules, and xtask's test
//! stages. [`with_engine!`] dispatches a name to its backend type and [`for_each_engine!`]
//! instantiates items once per built engine; both compile an engine's code only when its
//! feature is on. `AnyBackend` (with any engine built) is one backend type whose values run on
//! different engines, for a vector env whose envs do: its options, `AnyOptions`, name the
//! engine of each value.
//!
//! A front builds an engine in by turning on this crate's feature of the engine's name (the
//! fronts' own `dart` and `mujoco` features do). Without any feature, the crate is the table
//! alone and compiles no engine, which is how hyq-env and xtask use it.
//!
//! Adding an engine: its crate, its row here, its two arms in [`with_engine!`]'s and
//! [`for_each_engine!`]'s helper macros, and its cargo features (ARCHITECTURE.md, "Adding an
//! engine").

#[cfg(feature = "mixed")]
mod mixed;
#[cfg(feature = "mixed")]
pub use mixed::{AnyBackend, AnyOptions};

/// Where an engine's options come from (for [`AnyOptions::read`](mixed::AnyOptions::read)):
/// hyq-env's `[physics]` configuration implements it by reading the table `[physics.<engine>]`
/// (absent: the engine's defaults). Here, without any engine, so that hyq-env can implement it.
pub trait OptionsSource {
    /// Why options could not be read.
    type Error;
    /// The options of engine `engine`.
    fn engine_options<O: serde::de::DeserializeOwned + Default>(
        &self,
        engine: &str,
    ) -> Result<O, Self::Error>;
}

/// One physics engine.
#[derive(Debug, PartialEq, Eq)]
pub struct Engine {
    /// The name users type and configurations use (`--backend`, `backend=`,
    /// `[physics.<name>]`), equal to the backend's `Backend::NAME`.
    pub name: &'static str,
    /// The name as prose writes it (`"DART"`).
    pub title: &'static str,
    /// A few words on what it is, for help texts.
    pub summary: &'static str,
    /// The backend crate.
    pub crate_name: &'static str,
    /// The cargo feature that builds it into a front (the same name in every front and here);
    /// `None` when every build has it.
    pub feature: Option<&'static str>,
    /// What it needs beyond a Rust toolchain, and the command that installs that; `None` when
    /// nothing.
    pub needs: Option<Needs>,
    /// Whether `cargo xtask test` builds the Python package with it when its stage ran, so that
    /// the package's tests run on it too. DART's is off: its C++ build would add minutes to the
    /// Python stage for code the package shares with every engine (the bindings are generic over
    /// the backend), and a package without it keeps the not-built error of Python tested.
    pub python_tests: bool,
    /// Whether this build has it.
    pub built: bool,
}

/// What an engine needs installed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Needs {
    /// What (`"DART 6.12"`).
    pub what: &'static str,
    /// The command that installs it, as a user on Debian or Ubuntu runs it.
    pub install: &'static str,
    /// How a tool tells that it is installed.
    pub probe: Probe,
}

/// How to tell that an engine's library is installed (xtask's stages skip an engine's tests,
/// with the install line, when it is not).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Probe {
    /// A file its packages install.
    File(&'static str),
    /// `cargo xtask setup <name>` fetched it into the workspace, where xtask's setup command
    /// checks it.
    XtaskSetup,
}

/// Every engine, the default first.
pub static ENGINES: [Engine; 3] = [
    Engine {
        name: "rapier",
        title: "rapier",
        summary: "rapier3d, pure Rust (the default)",
        crate_name: "hyq-rapier",
        feature: None,
        needs: None,
        python_tests: true,
        built: cfg!(feature = "rapier"),
    },
    Engine {
        name: "dart",
        title: "DART",
        summary: "DART 6.12 through C++",
        crate_name: "hyq-dart",
        feature: Some("dart"),
        needs: Some(Needs {
            what: "DART 6.12",
            install: "apt-get install -y libdart-dev libdart-collision-bullet-dev",
            // The header of DART's Bullet collision detector, which the backend uses.
            probe: Probe::File("/usr/include/dart/collision/bullet/BulletCollisionDetector.hpp"),
        }),
        python_tests: false,
        built: cfg!(feature = "dart"),
    },
    Engine {
        name: "mujoco",
        title: "MuJoCo",
        summary: "MuJoCo 4.0 through its C API",
        crate_name: "hyq-mujoco",
        feature: Some("mujoco"),
        needs: Some(Needs {
            what: "MuJoCo 4.0.0's library",
            install: "cargo xtask setup mujoco",
            probe: Probe::XtaskSetup,
        }),
        python_tests: true,
        built: cfg!(feature = "mujoco"),
    },
];

/// The default engine.
pub static DEFAULT: &Engine = &ENGINES[0];

/// Every engine's name, in [`ENGINES`]' order.
pub const NAMES: [&str; ENGINES.len()] = {
    let mut names = [""; ENGINES.len()];
    let mut i = 0;
    while i < ENGINES.len() {
        names[i] = ENGINES[i].name;
        i += 1;
    }
    names
};

/// The engine called `name`.
pub fn find(name: &str) -> Option<&'static Engine> {
    ENGINES.iter().find(|e| e.name == name)
}

/// The engines this build has, in [`ENGINES`]' order.
pub fn built() -> impl Iterator<Item = &'static Engine> {
    ENGINES.iter().filter(|e| e.built)
}

/// Every engine's name as prose lists them: `"rapier, dart and mujoco"`.
pub fn all_names() -> String {
    match NAMES.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => NAMES.join(""),
    }
}

/// The backend types of the engines this build has, for [`with_engine!`] and
/// [`for_each_engine!`] (and for a front that names one directly, such as a test).
pub mod backends {
    /// rapier3d.
    #[cfg(feature = "rapier")]
    pub use hyq_rapier::RapierBackend as Rapier;

    /// DART.
    #[cfg(feature = "dart")]
    pub use hyq_dart::DartBackend as Dart;

    /// MuJoCo.
    #[cfg(feature = "mujoco")]
    pub use hyq_mujoco::MujocoBackend as Mujoco;
}

/// Evaluates `$body` with the type alias `$b` bound to the backend of the engine named `$name`
/// (a `&str`): `Some(value)` when this build has that engine, `None` when it does not or no
/// engine has that name. The body is compiled once per built engine, so what it runs is
/// monomorphised per engine; `?` and `return` in it act on the enclosing function. For example,
/// `with_engine!(name, B => <B as Backend>::NAME)` is `Some("rapier")` for `"rapier"` and `None`
/// for `"bullet"` (this crate's test `every_built_engine_dispatches_to_the_backend_of_its_name`
/// runs it on every engine; a doctest would link an engine into one more binary for nothing).
#[macro_export]
macro_rules! with_engine {
    ($name:expr, $b:ident => $body:expr) => {
        match $name {
            "rapier" => $crate::__rapier!(expr $b => $body),
            "dart" => $crate::__dart!(expr $b => $body),
            "mujoco" => $crate::__mujoco!(expr $b => $body),
            _ => None,
        }
    };
}

/// Instantiates the items it is given once per engine this build has, each in a module of the
/// engine's name (`rapier`, `dart`, `mujoco`) where the type alias `Engine` is that engine's
/// backend and the enclosing module's items are in scope (rustls instantiates its tests once per
/// crypto provider the same way).
#[macro_export]
macro_rules! for_each_engine {
    ($($body:tt)*) => {
        $crate::__rapier!(items $($body)*);
        $crate::__dart!(items $($body)*);
        $crate::__mujoco!(items $($body)*);
    };
}

// rapier's arms of `with_engine!` and `for_each_engine!`: its code when the `rapier` feature is
// on, nothing when it is off. (A `#[cfg]` inside an exported macro would read the calling crate's
// features, so the choice is made here, where the macro is defined.)

#[cfg(feature = "rapier")]
#[doc(hidden)]
#[macro_export]
macro_rules! __rapier {
    (expr $b:ident => $body:expr) => {
        Some({
            type $b = $crate::backends::Rapier;
            $body
        })
    };
    (items $($body:tt)*) => {
        /// These items on the rapier backend.
        mod rapier {
            #[allow(unused_imports)]
            use super::*;
            /// The backend these items run on.
            #[allow(dead_code)]
            type Engine = $crate::backends::Rapier;
            $($body)*
        }
    };
}

#[cfg(not(feature = "rapier"))]
#[doc(hidden)]
#[macro_export]
macro_rules! __rapier {
    (expr $b:ident => $body:expr) => {
        None
    };
    (items $($body:tt)*) => {};
}

// DART's arms of `with_engine!` and `for_each_engine!`: its code when the `dart` feature is
// on, nothing when it is off. (A `#[cfg]` inside an exported macro would read the calling crate's
// features, so the choice is made here, where the macro is defined.)

#[cfg(feature = "dart")]
#[doc(hidden)]
#[macro_export]
macro_rules! __dart {
    (expr $b:ident => $body:expr) => {
        Some({
            type $b = $crate::backends::Dart;
            $body
        })
    };
    (items $($body:tt)*) => {
        /// These items on the DART backend.
        mod dart {
            #[allow(unused_imports)]
            use super::*;
            /// The backend these items run on.
            #[allow(dead_code)]
            type Engine = $crate::backends::Dart;
            $($body)*
        }
    };
}

#[cfg(not(feature = "dart"))]
#[doc(hidden)]
#[macro_export]
macro_rules! __dart {
    (expr $b:ident => $body:expr) => {
        None
    };
    (items $($body:tt)*) => {};
}

// MuJoCo's arms of `with_engine!` and `for_each_engine!`: its code when the `mujoco` feature is
// on, nothing when it is off. (A `#[cfg]` inside an exported macro would read the calling crate's
// features, so the choice is made here, where the macro is defined.)

#[cfg(feature = "mujoco")]
#[doc(hidden)]
#[macro_export]
macro_rules! __mujoco {
    (expr $b:ident => $body:expr) => {
        Some({
            type $b = $crate::backends::Mujoco;
            $body
        })
    };
    (items $($body:tt)*) => {
        /// These items on the MuJoCo backend.
        mod mujoco {
            #[allow(unused_imports)]
            use super::*;
            /// The backend these items run on.
            #[allow(dead_code)]
            type Engine = $crate::backends::Mujoco;
            $($body)*
        }
    };
}

#[cfg(not(feature = "mujoco"))]
#[doc(hidden)]
#[macro_export]
macro_rules! __mujoco {
    (expr $b:ident => $body:expr) => {
        None
    };
    (items $($body:tt)*) => {};
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_the_default_is_built_first() {
        for (i, engine) in ENGINES.iter().enumerate() {
            assert_eq!(NAMES[i], engine.name);
            assert_eq!(find(engine.name), Some(engine));
            assert!(ENGINES[..i].iter().all(|e| e.name != engine.name));
            // An engine every build has needs nothing installed; one that needs something has
            // a feature to leave it out.
            assert_eq!(
                engine.feature.is_none(),
                engine.needs.is_none(),
                "{}",
                engine.name
            );
        }
        assert_eq!(DEFAULT.name, ENGINES[0].name);
        assert!(DEFAULT.feature.is_none() && DEFAULT.built);
        assert_eq!(built().next().map(|e| e.name), Some(DEFAULT.name));
        assert_eq!(find("bullet"), None);
        assert_eq!(all_names(), "rapier, dart and mujoco");
    }

    /// Each built engine's row names the backend its name dispatches to.
    #[test]
    fn every_built_engine_dispatches_to_the_backend_of_its_name() {
        use hyq_physics::Backend;
        for engine in built() {
            assert_eq!(
                with_engine!(engine.name, B => <B as Backend>::NAME),
                Some(engine.name)
            );
        }
        for engine in ENGINES.iter().filter(|e| !e.built) {
            assert_eq!(with_engine!(engine.name, B => <B as Backend>::NAME), None);
        }
        assert_eq!(with_engine!("bullet", B => <B as Backend>::NAME), None);
    }
}
