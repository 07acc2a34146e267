//! `cargo xtask test --with rllib`: an optional stage that runs `examples/rllib_scale_out.py`
//! for two training iterations with Ray's RLlib, in a venv of its own.
//!
//! Not part of CI: the pinned requirements (`examples/requirements-rllib.txt`: ray[rllib]
//! 2.60.0 and PyTorch from PyPI, which pulls the CUDA toolkit) take 6.1 GB and about 3 minutes
//! to install, more than the rest of the test run. The venv is `$HYQ_RLLIB_VENV`, else
//! `target/rllib-venv`, created and filled on first use and kept between runs.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::python::{venv_command, venv_python};
use crate::workspace::run;

/// The optional stages `--with` names.
const OPTIONAL: [&str; 2] = ["rllib", "train"];

/// Splits `--with NAME` pairs off `args`: (the optional stages asked for, the other arguments).
pub fn split_with(args: &[String]) -> Result<(Vec<String>, Vec<String>), String> {
    let (mut with, mut rest) = (Vec::new(), Vec::new());
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "--with" {
            let name = it
                .next()
                .ok_or("`--with` needs a value: rllib or train")?
                .to_string();
            if !OPTIONAL.contains(&name.as_str()) {
                return Err(format!(
                    "`--with {name}`: unknown optional stage (expected rllib or train)"
                ));
            }
            with.push(name);
        } else {
            rest.push(arg.clone());
        }
    }
    Ok((with, rest))
}

fn rllib_venv(root: &Path) -> PathBuf {
    std::env::var_os("HYQ_RLLIB_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| crate::workspace::target_dir(root).join("rllib-venv"))
}

/// The stage: builds the venv if needed, installs the package into it, runs the example for
/// two iterations and with a wrong configuration key; returns how many checks passed.
pub fn stage(root: &Path) -> Result<u64, String> {
    let venv = rllib_venv(root);
    let python = venv_python(&venv);
    if !python.is_file() {
        let system = std::env::var("HYQ_PYTHON").unwrap_or_else(|_| "python3".to_string());
        run(
            Command::new(&system).args(["-m", "venv"]).arg(&venv),
            &format!("{system} -m venv {}", venv.display()),
        )?;
    }
    let requirements = root.join("examples").join("requirements-rllib.txt");
    run(
        venv_command(&venv, root, &python)
            .args(["-m", "pip", "install", "-q", "-r"])
            .arg(&requirements),
        "pip install -r examples/requirements-rllib.txt",
    )?;
    run(
        venv_command(&venv, &root.join("crates").join("hyq-py"), &python)
            .args(["-m", "maturin", "develop", "--locked"]),
        "maturin develop (into the RLlib venv)",
    )?;
    let example = root.join("examples").join("rllib_scale_out.py");

    println!(
        "\n$ python examples/rllib_scale_out.py --runners 2 --envs-per-runner 2 --iterations 2"
    );
    let out = venv_command(&venv, root, &python)
        .arg(&example)
        .args([
            "--runners",
            "2",
            "--envs-per-runner",
            "2",
            "--iterations",
            "2",
            "--batch",
            "1000",
        ])
        .output()
        .map_err(|e| format!("cannot run the RLlib example: {e}"))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    print!("{stdout}");
    if !out.status.success() {
        return Err(format!(
            "the RLlib example failed ({}): {}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let iterations = stdout
        .lines()
        .filter(|l| {
            let first = l.split_whitespace().next();
            first == Some("1") || first == Some("2")
        })
        .count();
    if iterations != 2 {
        return Err(format!(
            "the RLlib example printed {iterations} iteration lines, expected 2"
        ));
    }

    println!("\n$ python examples/rllib_scale_out.py --env-config '{{\"bogus\": 1}}'");
    let out = venv_command(&venv, root, &python)
        .arg(&example)
        .args(["--env-config", "{\"bogus\": 1}"])
        .output()
        .map_err(|e| format!("cannot run the RLlib example: {e}"))?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    print!("{stderr}");
    let one_line = stderr.lines().count() == 1 && stderr.contains("bogus");
    if out.status.code() != Some(2) || !one_line {
        return Err(format!(
            "a wrong env_config key should be one error line and status 2, got {} and: {stderr}",
            out.status
        ));
    }
    Ok(2)
}

#[cfg(test)]
mod tests {
    use super::split_with;
    use crate::cli::strings;

    #[test]
    fn with_flags_are_split_off_and_unknown_stages_refused() {
        let (with, rest) = split_with(&strings(&["--require", "all", "--with", "rllib"]))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            (with, rest),
            (strings(&["rllib"]), strings(&["--require", "all"]))
        );
        assert!(split_with(&strings(&["--with", "tensorflow"])).is_err());
        assert!(split_with(&strings(&["--with"])).is_err());
    }
}
