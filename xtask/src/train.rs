//! `cargo xtask test --with train`: an optional stage that runs the training examples' tests
//! (`crates/hyq-py/tests_train`: the rsl_rl adapter against the Rust vector env, both training
//! scripts on a tiny budget twice, their exports and ONNX twins), in a venv of its own.
//!
//! Not part of CI: the pinned requirements (`examples/requirements-train.txt`: PyTorch from
//! PyPI, which pulls the CUDA toolkit, Stable-Baselines3, rsl-rl-lib) take 5.4 GB and minutes to
//! install, and rsl_rl's `VecEnv` and the adapter's tensors need PyTorch itself. The venv is
//! `$HYQ_TRAIN_VENV`, else `target/train-venv`, created and filled on first use and kept
//! between runs.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::python::{pytest_passed_count, venv_command, venv_python};
use crate::workspace::run;

fn train_venv(root: &Path) -> PathBuf {
    std::env::var_os("HYQ_TRAIN_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| crate::workspace::target_dir(root).join("train-venv"))
}

/// The stage: builds the venv if needed, installs the package into it and runs pytest on
/// `tests_train`; returns how many tests passed. The package is built as the training docs
/// build it (release, with `features`: the engines the Python stage builds it with, MuJoCo when
/// it is set up), since the venv is the one the recipes train in: a debug or rapier-only build
/// would leave them slow or refusing their engine.
pub fn stage(root: &Path, features: &str) -> Result<u64, String> {
    let venv = train_venv(root);
    let python = venv_python(&venv);
    if !python.is_file() {
        let system = std::env::var("HYQ_PYTHON").unwrap_or_else(|_| "python3".to_string());
        run(
            Command::new(&system).args(["-m", "venv"]).arg(&venv),
            &format!("{system} -m venv {}", venv.display()),
        )?;
    }
    let requirements = root.join("examples").join("requirements-train.txt");
    run(
        venv_command(&venv, root, &python)
            .args(["-m", "pip", "install", "-q", "-r"])
            .arg(&requirements),
        "pip install -r examples/requirements-train.txt",
    )?;
    let crate_dir = root.join("crates").join("hyq-py");
    let mut develop = vec!["-m", "maturin", "develop", "--locked", "--release"];
    if !features.is_empty() {
        develop.extend(["--features", features]);
    }
    run(
        venv_command(&venv, &crate_dir, &python).args(&develop),
        &format!(
            "maturin {} (into the training venv)",
            develop[2..].join(" ")
        ),
    )?;
    println!("\n$ python -m pytest tests_train");
    let out = venv_command(&venv, &crate_dir, &python)
        .args(["-m", "pytest", "-p", "no:cacheprovider", "tests_train"])
        .output()
        .map_err(|e| format!("cannot run pytest: {e}"))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    print!("{stdout}");
    if !out.status.success() {
        return Err(format!(
            "the training stage's pytest failed ({})",
            out.status
        ));
    }
    stdout
        .lines()
        .rev()
        .find_map(pytest_passed_count)
        .ok_or_else(|| "the training stage's pytest printed no summary line".to_string())
}
