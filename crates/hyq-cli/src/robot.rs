//! `hyq robot init FILE`: a robot profile drafted from a URDF (with `--srdf` for its standing
//! pose) or an MJCF file, every value commented with where it came from (hyq-formats'
//! [`draft`]), its standing height measured by a settle run on rapier: the robot spawned at the
//! drafted height and held at the standing pose under the drafted gains for 1 s. Written to
//! stdout, or to `--out PROFILE` (an existing file only with `--force`).

use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use clap::{Args, Subcommand};
use hyq_env::settle::SETTLE_S;
use hyq_formats::draft::{self, Draft};

use crate::Failure;
use crate::options::{settle_height, usage};
use crate::output::{self, OutputFile};

/// `hyq robot`'s subcommands.
#[derive(Debug, Subcommand)]
pub enum RobotCommand {
    /// Draft a robot profile from a URDF or MJCF file (stdout, or --out PROFILE).
    ///
    /// The trunk (the root body), the feet (each leaf body's collision sphere, else its lowest
    /// shape), the joints in leg-major order with the project's names (lf, lh, rf, rh; haa,
    /// hfe, kfe) where the legs' placement and axes show them, the standing pose (the SRDF's
    /// group state "standing", the MJCF's `home` keyframe, else zeros), the spawn height (feet
    /// 1 mm above the ground by forward kinematics), the standing height (a 1 s settle run on
    /// rapier), PD gains (the MJCF's <position> actuators, else a rule from mass and inertia),
    /// joint limits and a trot: every value commented with where it came from. Read it, edit
    /// it, then `hyq run --robot PROFILE`.
    Init(InitArgs),
}

/// `hyq robot`: tools for bringing a robot.
#[derive(Debug, Args)]
pub struct RobotArgs {
    #[command(subcommand)]
    command: RobotCommand,
}

/// `hyq robot init`'s arguments.
#[derive(Debug, Args)]
pub struct InitArgs {
    /// The robot file: MJCF (.xml) or URDF (any other extension).
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// An SRDF whose `<group_state name="standing">` gives the standing pose.
    #[arg(long, value_name = "FILE")]
    pub srdf: Option<PathBuf>,
    /// Write the profile here instead of stdout (its `urdf` key is then relative to it).
    #[arg(long, value_name = "PROFILE")]
    pub out: Option<PathBuf>,
    /// Replace --out's file if it exists.
    #[arg(long)]
    pub force: bool,
}

/// Runs `hyq robot`.
pub fn execute(args: RobotArgs) -> Result<(), Failure> {
    match args.command {
        RobotCommand::Init(init) => init_profile(&init),
    }
}

fn init_profile(args: &InitArgs) -> Result<(), Failure> {
    if let Some(out) = &args.out
        && out.exists()
        && !args.force
    {
        return Err(usage(format!(
            "--out {}: the file exists; add --force to replace it",
            out.display()
        )));
    }
    let base = match &args.out {
        Some(out) => out.parent().map(Path::to_owned).unwrap_or_default(),
        None => PathBuf::new(),
    };
    let key = relative(&base, &args.file);
    let mut draft = draft::draft_file(&args.file, args.srdf.as_deref(), &key)
        .map_err(|e| usage(format!("hyq robot init: {e}")))?;
    settle(&mut draft);
    let text = draft.to_toml();
    match &args.out {
        None => output::print(&text),
        Some(out) => {
            let cannot = |e: std::io::Error| Failure {
                status: 1,
                message: format!("--out {}: {e}", out.display()),
            };
            let mut file = OutputFile::create(out).map_err(cannot)?;
            std::io::Write::write_all(&mut file, text.as_bytes()).map_err(cannot)?;
            file.finish().map_err(cannot)
        }
    }
}

/// Measures the draft's standing height on rapier and records it; a draft that does not
/// stand keeps the spawn height, its comment and a warning saying why.
fn settle(draft: &mut Draft) {
    let measured = draft
        .model()
        .map_err(|e| e.to_string())
        .and_then(|model| settle_height(Arc::new(model)));
    match measured {
        Ok(z) => draft.set_standing_height(
            z,
            &format!(
                "Where the trunk frame stands at the standing pose under these gains, measured \
                 by `hyq robot init` {SETTLE_S} s after spawn on rapier (default configuration, \
                 seed 0): {z:.5} m. Other engines settle within a few mm (measure them with \
                 `hyq run --policy stand`)."
            ),
        ),
        Err(why) => {
            let note = format!(
                "Not measured: the settle run on rapier failed ({why}); the environment takes \
                 the spawn height. Fix the standing pose or gains and run `hyq robot init` again."
            );
            output::warn(&format!("the drafted robot did not stand: {why}"));
            draft.set_standing_note(&note);
        }
    }
}

/// `file`'s path as seen from directory `base`: relative when both resolve and share more than
/// the root, else absolute (or as given).
fn relative(base: &Path, file: &Path) -> String {
    let resolve = |p: &Path| {
        let p = if p.as_os_str().is_empty() {
            Path::new(".")
        } else {
            p
        };
        p.canonicalize().ok()
    };
    let (Some(base), Some(target)) = (resolve(base), resolve(file)) else {
        return file.display().to_string();
    };
    let b: Vec<Component> = base.components().collect();
    let t: Vec<Component> = target.components().collect();
    let common = b.iter().zip(&t).take_while(|(x, y)| x == y).count();
    if common <= 1 {
        // Nothing in common but the root: the absolute path reads better than a climb to it.
        return target.display().to_string();
    }
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &t[common..] {
        out.push(c);
    }
    out.display().to_string()
}
