//! The command's arguments.

use std::path::{Path, PathBuf};

use super::DEFAULT_VENV;
use crate::cli::{positive, value};

/// The command's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchArgs {
    /// Repetitions of the whole interleaved sequence.
    pub reps: usize,
    /// Env steps per `hyq bench` pass (one env).
    pub steps: u64,
    /// Vector steps per vector-env pass (each is 2 env steps).
    pub vec_steps: u64,
    /// Env steps per anchor run (MuJoCo and DART from Python).
    pub anchor_steps: u64,
    /// The anchors' virtual environment.
    pub venv: PathBuf,
    /// Measure the DART backend and DART from Python (when DART is installed).
    pub dart: bool,
    /// Measure the MuJoCo backend (when MuJoCo is set up); MuJoCo from Python runs either way,
    /// as the rapier targets' anchor.
    pub mujoco: bool,
}

impl BenchArgs {
    /// Whether `hyq bench --backend <name>` is wanted (`--no-dart`, `--no-mujoco` say no).
    pub fn wants(&self, backend: &str) -> bool {
        match backend {
            "dart" => self.dart,
            "mujoco" => self.mujoco,
            _ => true,
        }
    }
}

/// Parses the command's arguments; `root` is the workspace root (for the defaults and for
/// refusing a virtual environment among the repository's files); `env_venv` is
/// `$HYQ_ANCHOR_VENV`.
pub fn parse(args: &[String], root: &Path, env_venv: Option<PathBuf>) -> Result<BenchArgs, String> {
    const COMMAND: &str = "bench-vs-anchors";
    let mut out = BenchArgs {
        reps: 5,
        steps: 3000,
        vec_steps: 1500,
        anchor_steps: 3000,
        venv: env_venv.unwrap_or_else(|| crate::workspace::target_dir(root).join(DEFAULT_VENV)),
        dart: true,
        mujoco: true,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--reps" => out.reps = positive(&mut it, COMMAND, arg)? as usize,
            "--steps" => out.steps = positive(&mut it, COMMAND, arg)?,
            "--vec-steps" => out.vec_steps = positive(&mut it, COMMAND, arg)?,
            "--anchor-steps" => out.anchor_steps = positive(&mut it, COMMAND, arg)?,
            "--venv" => out.venv = PathBuf::from(value(&mut it, COMMAND, arg)?),
            "--no-dart" => out.dart = false,
            "--no-mujoco" => out.mujoco = false,
            other => {
                return Err(format!(
                    "`cargo xtask bench-vs-anchors`: unknown argument `{other}`"
                ));
            }
        }
    }
    if out.venv.is_relative() {
        out.venv = root.join(&out.venv);
    }
    // The repository's `target/` is git-ignored whatever the target directory is.
    let ignored = [root.join("target"), crate::workspace::target_dir(root)];
    if out.venv.starts_with(root) && !ignored.iter().any(|dir| out.venv.starts_with(dir)) {
        return Err(format!(
            "--venv {}: the anchors' virtual environment must be under target/, the \
             target directory or outside the repository ({}), not among its files",
            out.venv.display(),
            root.display()
        ));
    }
    Ok(out)
}
