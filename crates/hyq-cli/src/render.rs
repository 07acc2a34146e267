//! `hyq render`: one episode of a policy drawn by hyq-render's CPU renderer (no display, no
//! GPU), written as an animated GIF or as numbered PNG frames.
//!
//! Frames are taken at a fixed simulated rate: frame k shows the state after env step
//! round(k / (fps · Δt_env)), frame 0 the state after reset. A GIF's delays are whole
//! hundredths of a second, so for a GIF the rate is first rounded to 100 / round(100 / fps)
//! (30 fps becomes 33.3 fps): the GIF then plays in real time. The rate cannot exceed the env
//! step rate (100 per simulated second by default), since there is no state between steps.
//!
//! Each frame shows the trunk box, the leg capsules and the feet (orange when in contact in any
//! sub-step of the env step, as the observation's contact rows say; the trunk turns red when it
//! touches the ground), the goal marker, and an overlay with the simulated time, D^t and the
//! return so far. The camera follows the trunk.

use std::path::{MAIN_SEPARATOR, Path, PathBuf};

use clap::Args;
use hyq_env::{Env, ResetOptions};
use hyq_physics::Backend;
use hyq_render::{
    Frame, GifWriter, PngSequence, RenderConfig, Renderer, WriteError, env_scene, gif_delay_cs,
};

use crate::Failure;
use crate::backend::with_backend;
use crate::options::{EnvArgs, PolicyArgs, make_env, usage};
use crate::output::{OutputFile, StagedDir, print_line, progress_bar};

/// `hyq render` arguments.
#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    env: EnvArgs,
    #[command(flatten)]
    policy: PolicyArgs,
    /// Simulated seconds to render; the episode may end sooner (reached, joint limit, fall or
    /// timeout) [default: the whole episode, up to task.max_time_steps]
    #[arg(long, value_name = "T")]
    seconds: Option<f64>,
    /// Image width (pixels, 16 to 4096).
    #[arg(long, default_value_t = hyq_render::DEFAULT_WIDTH_PX, value_parser = side_px())]
    width: u32,
    /// Image height (pixels, 16 to 4096).
    #[arg(long, default_value_t = hyq_render::DEFAULT_HEIGHT_PX, value_parser = side_px())]
    height: u32,
    /// Frames per simulated second: at most the env step rate (100 by default), and at most 50
    /// for a GIF.
    #[arg(long, default_value_t = 25.0)]
    fps: f64,
    /// Where to write: a path ending in `.gif` for an animated GIF, or a directory (a path
    /// ending in `/`, or an existing directory) for PNG frames `frame_000000.png`, …
    #[arg(long, value_name = "FILE.gif|DIR/")]
    out: PathBuf,
}

/// What `--out` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum OutKind {
    Gif,
    PngDir,
}

/// Reads `--out`: `.gif` (any case) is a GIF; a trailing separator or an existing directory
/// is a directory of PNG frames; anything else is an error, since guessing would write the
/// wrong kind of file.
fn out_kind(out: &Path) -> Result<OutKind, Failure> {
    let text = out.to_string_lossy();
    let is_gif = out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gif"));
    if is_gif && !text.ends_with(['/', MAIN_SEPARATOR]) && !out.is_dir() {
        Ok(OutKind::Gif)
    } else if text.ends_with(['/', MAIN_SEPARATOR]) || out.is_dir() {
        Ok(OutKind::PngDir)
    } else {
        Err(usage(format!(
            "--out {text}: expected a file ending in .gif (an animated GIF) or a directory \
             ending in / (PNG frames)"
        )))
    }
}

/// The frame writer `--out` names: writing beside the target (a hidden file or directory),
/// which the finished render replaces (see `crate::output`).
enum Output {
    Gif(GifWriter<OutputFile>),
    Pngs(PngSequence, StagedDir),
}

impl Output {
    fn push(&mut self, frame: &Frame) -> Result<(), WriteError> {
        match self {
            Output::Gif(gif) => gif.push(frame),
            Output::Pngs(seq, _) => seq.push(frame).map(|_| ()),
        }
    }

    /// Finishes the frames and puts them in place of the target.
    fn finish(self, out: &Path) -> Result<(), WriteError> {
        let io = |source| WriteError::Io {
            path: out.to_owned(),
            source,
        };
        match self {
            Output::Gif(gif) => gif.finish()?.finish().map_err(io),
            Output::Pngs(_, staged) => staged.publish().map(|_| ()).map_err(io),
        }
    }
}

/// The checked settings of one render.
struct Plan {
    kind: OutKind,
    /// The frame rate used (for a GIF, rounded to its hundredths of a second).
    fps: f64,
    /// Env steps to run at most.
    max_steps: u64,
}

/// Checks `--fps`, `--seconds` and `--out` against the environment's step.
fn plan(args: &RenderArgs, env_dt: f64, t_max: u64) -> Result<Plan, Failure> {
    let kind = out_kind(&args.out)?;
    let step_rate = 1.0 / env_dt;
    if !(args.fps.is_finite() && args.fps > 0.0) {
        return Err(usage(format!(
            "--fps {}: must be a number above 0",
            args.fps
        )));
    }
    // A rate within rounding of the step rate is the step rate.
    if args.fps > step_rate * (1.0 + 1e-9) {
        return Err(usage(format!(
            "--fps {}: above the env step rate, {step_rate} steps per simulated second (there \
             is no state between env steps)",
            args.fps
        )));
    }
    let fps = match kind {
        OutKind::Gif => {
            let delay = gif_delay_cs(args.fps).map_err(|e| usage(format!("--fps: {e}")))?;
            100.0 / f64::from(delay)
        }
        OutKind::PngDir => args.fps,
    };
    let max_steps = match args.seconds {
        None => t_max,
        Some(s) if s.is_finite() && s > 0.0 => {
            // At least one step; never more than the episode can take.
            ((s / env_dt).round().max(1.0) as u64).min(t_max)
        }
        Some(s) => {
            return Err(usage(format!(
                "--seconds {s}: must be a number of simulated seconds above 0"
            )));
        }
    };
    Ok(Plan {
        kind,
        fps,
        max_steps,
    })
}

/// Opens the writer (the temporary GIF file beside the target, or the directory and its
/// temporary one) before anything is simulated, so that an unwritable path fails at once.
fn open_output(args: &RenderArgs, plan: &Plan) -> Result<Output, Failure> {
    let out = &args.out;
    let failed = |e: WriteError| usage(format!("--out {}: {e}", out.display()));
    let io = |e: std::io::Error| usage(format!("--out {}: {e}", out.display()));
    Ok(match plan.kind {
        OutKind::Gif => {
            // The GIF's own checks (size, frame rate) before the file is created.
            gif_delay_cs(plan.fps).map_err(failed)?;
            let file = OutputFile::create(out).map_err(io)?;
            Output::Gif(GifWriter::new(file, args.width, args.height, plan.fps).map_err(failed)?)
        }
        OutKind::PngDir => {
            let staged = StagedDir::create(out).map_err(io)?;
            let seq = PngSequence::create(staged.path()).map_err(failed)?;
            Output::Pngs(seq, staged)
        }
    })
}

/// The image sides the renderer accepts (pixels).
fn side_px() -> clap::builder::RangedI64ValueParser<u32> {
    clap::value_parser!(u32)
        .range(i64::from(hyq_render::MIN_SIDE_PX)..=i64::from(hyq_render::MAX_SIDE_PX))
}

/// Runs `hyq render`.
pub fn execute(args: RenderArgs) -> Result<(), Failure> {
    let model = args.env.model()?;
    let config = args.policy.config(&args.env)?;
    with_backend!(args.env.backend, B => {
        let env = make_env::<B>(model, config)?;
        render_episode(env, &args)
    })
}

fn render_episode<B: Backend>(mut env: Env<B>, args: &RenderArgs) -> Result<(), Failure> {
    let plan = plan(args, env.env_dt(), env.config().task.max_time_steps)?;
    let mut policy = args.policy.make(&env)?;
    let render_config = RenderConfig {
        width: args.width,
        height: args.height,
        ..RenderConfig::default()
    };
    let mut renderer = Renderer::new(env.model().clone(), render_config)
        .map_err(|e| usage(format!("render settings: {e}")))?;
    let mut output = open_output(args, &plan)?;
    let write_failed = |e: WriteError| Failure {
        status: 1,
        message: format!("--out {}: {e}", args.out.display()),
    };

    env.reset(Some(args.policy.seed), &ResetOptions::default())
        .map_err(|e| Failure {
            status: 1,
            message: format!("reset: {e}"),
        })?;
    let mut frame = Frame::new(args.width, args.height);
    let mut action = vec![0.0; env.action_space().len()];
    let steps_per_frame = 1.0 / (plan.fps * env.env_dt());
    let mut frames = 0u64;
    let mut ret = 0.0;
    let bar = progress_bar(plan.max_steps);
    bar.set_message("rendering");
    let ended = loop {
        let t = env.info().t;
        // Frame k shows step round(k · steps_per_frame); the rate is at most the step rate, so
        // each step is due for at most one frame.
        if t == (frames as f64 * steps_per_frame).round() as u64 {
            renderer
                .render_into(&env_scene(&env, ret), &mut frame)
                .map_err(|e| Failure {
                    status: 1,
                    message: format!("render at t = {t}: {e}"),
                })?;
            output.push(&frame).map_err(write_failed)?;
            frames += 1;
        }
        if env.needs_reset() {
            let reasons: Vec<&str> = env.info().reasons.iter().map(|r| r.as_str()).collect();
            break reasons.join("+");
        }
        if t >= plan.max_steps {
            break "--seconds".to_owned();
        }
        policy.act(&env.policy_input(), &mut action);
        let step = env.step(&action).map_err(|e| Failure {
            status: 1,
            message: format!("step: {e}"),
        })?;
        ret += step.reward;
        bar.set_position(env.info().t);
    };
    output.finish(&args.out).map_err(write_failed)?;
    bar.finish_and_clear();
    let t = env.info().t;
    print_line(&format!(
        "wrote {frames} frames ({:.2} s simulated, {} env steps, {:.2} fps, {}x{}) to {}; \
         stopped by {ended}; return {ret:.3}, {}",
        t as f64 * env.env_dt(),
        t,
        plan.fps,
        args.width,
        args.height,
        args.out.display(),
        last_state(env.info()),
    ))
}

/// The summary's last words: under the velocity task the last command and the trunk's velocity
/// (the goal is not the task there), else the distance to the goal.
fn last_state(info: &hyq_env::StepInfo) -> String {
    match &info.velocity {
        Some(v) => format!(
            "command v_x {:.3} m/s, v_y {:.3} m/s, yaw rate {:.3} rad/s, trunk v_x {:.3} m/s, \
             v_y {:.3} m/s, yaw rate {:.3} rad/s",
            v.command[0], v.command[1], v.command[2], v.lin_vel[0], v.lin_vel[1], v.ang_vel[2]
        ),
        None => format!("distance to goal {:.3} m", info.distance_to_goal),
    }
}
