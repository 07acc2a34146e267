//! `cargo xtask fuzz [--seconds N] [--cases N] [--seed S] [TARGET...]`: the fuzz targets of
//! `crates/hyq-fuzz` (configuration, robot profile, URDF, policy, step records, ledger, terrain
//! height file) run in a release build for N seconds each (default 60), or N cases, from seed S
//! (default: the time). An input that fails is saved to `crates/hyq-fuzz/corpus/<target>/`,
//! where the crate's tests replay it from then on. `cargo xtask test` runs the same targets
//! briefly (a fixed seed and case count, in hyq-fuzz's tests).

use crate::workspace::{run_cargo, workspace_root};

/// Runs the fuzz targets (see the module docs); an error when one found a failing input.
pub fn fuzz(args: &[String]) -> Result<(), String> {
    let root = workspace_root();
    let mut cargo_args: Vec<String> = ["run", "--release", "--locked", "-p", "hyq-fuzz", "--"]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    cargo_args.extend(args.iter().cloned());
    let status = run_cargo(&root, &cargo_args)?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "the fuzz run failed ({status}): a finding is saved under crates/hyq-fuzz/corpus/, \
             and its target's tests now replay it"
        ))
    }
}
