//! The anchors' Python virtual environment: the pinned packages, created and installed on
//! demand.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::ANCHORS_DIR;
use super::command::run;
use crate::cli::strings;
use crate::python::{PYTHON_INSTALL, PYTHON_MIN, venv_python};

/// The pinned `name==version` lines of a requirements file (comments and blank lines skipped);
/// any other line is an error naming it.
pub fn parse_requirements(text: &str) -> Result<Vec<(String, String)>, String> {
    let mut pins = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        match line.split_once("==") {
            Some((name, version)) if !name.trim().is_empty() && !version.trim().is_empty() => {
                pins.push((name.trim().to_string(), version.trim().to_string()));
            }
            _ => {
                return Err(format!(
                    "{ANCHORS_DIR}/requirements.txt line {}: `{line}` is not a `name==version` pin",
                    i + 1
                ));
            }
        }
    }
    Ok(pins)
}

/// The Python that creates the anchors' venv: `$HYQ_PYTHON`, else `python3`.
fn system_python() -> String {
    std::env::var("HYQ_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// Creates the anchors' virtual environment if needed and installs the pins that are missing
/// or at another version; returns its Python and notes on what could not be installed (only
/// dartpy may be missing: its rows are then left out).
pub(super) fn setup_venv(
    venv: &Path,
    pins: &[(String, String)],
) -> Result<(PathBuf, Vec<String>), String> {
    let python = venv_python(venv);
    if !python.exists() {
        create_venv(venv)?;
    }
    if run(
        &python,
        &strings(&["-m", "pip", "--version"]),
        Path::new("/"),
        &[],
    )
    .is_err()
    {
        return Err(format!(
            "the anchors' virtual environment {} has no pip (remove it to have it created \
             again, or: {PYTHON_INSTALL})",
            venv.display()
        ));
    }
    let notes = install_pins(&python, venv, pins)?;
    Ok((python, notes))
}

/// Creates the virtual environment `venv` with the system's Python, after checking that it is
/// recent enough and has venv and pip.
fn create_venv(venv: &Path) -> Result<(), String> {
    let system = system_python();
    let check = format!(
        "import sys, venv, ensurepip; sys.exit(0 if sys.version_info >= {PYTHON_MIN:?} else 3)"
    );
    match Command::new(&system).args(["-c", &check]).status() {
        Err(e) => {
            return Err(format!(
                "`{system}` cannot be run ({e}): the anchors need Python {}.{}+ with venv \
                 and pip ({PYTHON_INSTALL}; or set HYQ_PYTHON)",
                PYTHON_MIN.0, PYTHON_MIN.1
            ));
        }
        Ok(s) if s.code() == Some(3) => {
            return Err(format!(
                "`{system}` is older than Python {}.{}, which the pinned numpy needs; set \
                 HYQ_PYTHON to a newer interpreter",
                PYTHON_MIN.0, PYTHON_MIN.1
            ));
        }
        Ok(s) if !s.success() => {
            return Err(format!(
                "`{system}` lacks the venv or ensurepip module, which the anchors' virtual \
                 environment needs: {PYTHON_INSTALL}"
            ));
        }
        Ok(_) => {}
    }
    println!(
        "creating the anchors' virtual environment at {}",
        venv.display()
    );
    run(
        Path::new(&system),
        &strings(&["-m", "venv", &venv.to_string_lossy()]),
        Path::new("/"),
        &[],
    )
    .map_err(|e| format!("cannot create the anchors' virtual environment: {e}"))?;
    Ok(())
}

/// Installs into the environment of `python` (at `venv`) each pin that is missing or at
/// another version; returns notes on what could not be installed (only dartpy may fail).
fn install_pins(
    python: &Path,
    venv: &Path,
    pins: &[(String, String)],
) -> Result<Vec<String>, String> {
    let mut notes = Vec::new();
    for (package, version) in pins {
        let check = format!(
            "import importlib.metadata as m, sys; sys.exit(0 if m.version('{package}') == '{version}' else 1)"
        );
        if run(python, &strings(&["-c", &check]), Path::new("/"), &[]).is_ok() {
            continue;
        }
        println!("installing {package}=={version} into {}", venv.display());
        let pin = format!("{package}=={version}");
        let env = [("PIP_DISABLE_PIP_VERSION_CHECK", "1")];
        if let Err(e) = run(
            python,
            &strings(&["-m", "pip", "install", "-q", &pin]),
            Path::new("/"),
            &env,
        ) {
            if package == "dartpy" {
                notes.push(format!(
                    "dartpy {version} could not be installed, so DART from Python was not \
                     measured: {e}"
                ));
            } else {
                return Err(format!("pip could not install {pin}: {e}"));
            }
        }
    }
    Ok(notes)
}

/// The anchors' environment: one thread for every numerical library; no bytecode written into
/// the repository.
pub(super) const PYTHON_ENV: [(&str, &str); 5] = [
    ("OMP_NUM_THREADS", "1"),
    ("OPENBLAS_NUM_THREADS", "1"),
    ("MKL_NUM_THREADS", "1"),
    ("NUMEXPR_NUM_THREADS", "1"),
    ("PYTHONDONTWRITEBYTECODE", "1"),
];

/// The anchors' pinned packages (`requirements.txt` in `anchors`).
pub(super) fn read_pins(anchors: &Path) -> Result<Vec<(String, String)>, String> {
    let requirements = anchors.join("requirements.txt");
    parse_requirements(
        &std::fs::read_to_string(&requirements)
            .map_err(|e| format!("cannot read {}: {e}", requirements.display()))?,
    )
}
