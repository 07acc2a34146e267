//! `cargo xtask soak [--steps N] [--backend rapier|dart|mujoco] [--seed S]`: the long random-action
//! soak. It builds the `hyq` command in release mode and runs `hyq soak`, which takes N env
//! steps (10⁶ by default) of uniformly random actions, resetting whenever an episode ends, and
//! fails on a panic or on the first non-finite number in any observation, reward term or info
//! field; it prints the steps, the episodes and why they ended, and the range seen on every
//! observation row (the measured ranges of the rows the spec only estimates, 33–38).
//!
//! The test suite runs a short soak (5·10³ steps, `crates/hyq-cli/tests`); this is the long one.

use crate::cli::{positive, value};
use crate::stages::engine_missing;
use crate::workspace::{run_cargo, workspace_root};

/// The soak's settings.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SoakArgs {
    /// Env steps in all.
    pub steps: u64,
    /// `rapier`, `dart` or `mujoco`.
    pub backend: String,
    /// The seed of the random actions and of the first reset.
    pub seed: u64,
}

/// Parses `--steps N`, `--backend rapier|dart|mujoco` and `--seed S`.
pub fn parse(args: &[String]) -> Result<SoakArgs, String> {
    let mut out = SoakArgs {
        steps: 1_000_000,
        backend: hyq_engines::DEFAULT.name.into(),
        seed: 0,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--steps" => out.steps = positive(&mut it, "soak", arg)?,
            "--seed" => {
                let v = value(&mut it, "soak", arg)?;
                out.seed = v
                    .parse()
                    .map_err(|_| format!("`--seed {v}`: expected a whole number"))?;
            }
            "--backend" => {
                let v = value(&mut it, "soak", arg)?;
                if hyq_engines::find(v).is_none() {
                    return Err(format!(
                        "`--backend {v}`: expected {}",
                        hyq_engines::all_names().replace(" and ", " or ")
                    ));
                }
                out.backend = v.clone();
            }
            other => return Err(format!("`cargo xtask soak`: unknown argument `{other}`")),
        }
    }
    Ok(out)
}

/// The cargo arguments that build and run the soak.
pub fn cargo_args(args: &SoakArgs) -> Vec<String> {
    let mut cargo: Vec<String> = ["run", "--release", "--locked", "-p", "hyq-cli"]
        .map(String::from)
        .to_vec();
    if let Some(feature) = hyq_engines::find(&args.backend).and_then(|e| e.feature) {
        cargo.extend(["--features".into(), feature.to_owned()]);
    }
    cargo.extend(
        [
            "--",
            "soak",
            "--backend",
            &args.backend,
            "--steps",
            &args.steps.to_string(),
            "--seed",
            &args.seed.to_string(),
        ]
        .map(String::from),
    );
    cargo
}

/// `cargo xtask soak`.
pub fn soak(args: &[String]) -> Result<(), String> {
    let args = parse(args)?;
    // The same check as the test stages'.
    if let Some(engine) = hyq_engines::find(&args.backend)
        && let Some(why) = engine_missing(engine, &workspace_root())
    {
        return Err(format!("the {} backend needs it: {why}", engine.title));
    }
    let status = run_cargo(&workspace_root(), &cargo_args(&args))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("the soak failed ({status})"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::strings;

    #[test]
    fn defaults_are_a_million_steps_on_rapier() {
        let parsed = parse(&[]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            parsed,
            SoakArgs {
                steps: 1_000_000,
                backend: "rapier".into(),
                seed: 0
            }
        );
        assert_eq!(
            cargo_args(&parsed).join(" "),
            "run --release --locked -p hyq-cli -- soak --backend rapier --steps 1000000 --seed 0"
        );
    }

    #[test]
    fn dart_builds_the_feature_and_bad_arguments_are_named() {
        let parsed = parse(&strings(&[
            "--backend",
            "dart",
            "--steps",
            "5000",
            "--seed",
            "3",
        ]))
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            cargo_args(&parsed).join(" "),
            "run --release --locked -p hyq-cli --features dart -- soak --backend dart --steps 5000 --seed 3"
        );
        let parsed = parse(&strings(&["--backend", "mujoco"])).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            cargo_args(&parsed).join(" "),
            "run --release --locked -p hyq-cli --features mujoco -- soak --backend mujoco --steps 1000000 --seed 0"
        );
        for (bad, named) in [
            (&["--steps", "0"][..], "--steps 0"),
            (&["--steps", "many"], "--steps many"),
            (&["--backend", "bullet"], "bullet"),
            (&["--steps"], "--steps"),
            (&["--fast"], "--fast"),
        ] {
            let err = parse(&strings(bad)).err().unwrap_or_default();
            assert!(err.contains(named), "{bad:?}: {err}");
        }
    }
}
