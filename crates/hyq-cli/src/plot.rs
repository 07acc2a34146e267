//! `hyq plot` and `hyq run --plot`: per-episode PNG plots drawn by hyq-render, the spec's
//! Figures 3–6 redrawn from a real run.
//!
//! Two files per episode, `episode_NNN_rewards.png` (every reward term per step, the §5.1
//! multipliers, the step reward with the fixed penalties, and the cumulative reward with the
//! cumulative r_b, r_n and r_e) and `episode_NNN_distance.png` (D_n over time, and the §4.3
//! curve R_e(D_n) with the episode's points (D_n^t, Σ r_e) on it). NNN counts the episodes of
//! the run or file from 001. Under `[regularizers]` a third, `episode_NNN_regularizers.png`;
//! under `task.kind = "velocity"` also `episode_NNN_velocity.png` (the command, the task's
//! reward and every task term unscaled, docs/velocity.md).
//!
//! A JSONL record does not carry the configuration it was made with, so `hyq plot` reads k_exp
//! (for the R_e curve) and the env step (for the time axis) from the same `--config` and `--set`
//! options as `hyq run`: given the run's options, the plots of a record are the plots
//! `hyq run --plot` drew live, byte for byte (tested). Given other options, the episode's points
//! leave the curve, which shows the mismatch.

use std::path::{Path, PathBuf};

use clap::Args;
use hyq_env::{EnvConfig, StepInfo};
use hyq_render::{
    EpisodeSeries, PlotError, PlotOptions, PlotRecord, TermValues, VelocityPlotRecord,
};

use crate::Failure;
use crate::options::{ConfigArgs, usage};
use crate::output::{StagedDir, print_line, warn};

/// `hyq plot` arguments.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// A JSONL step record, as `hyq run --record` writes it (one object per env step).
    #[arg(value_name = "FILE.jsonl")]
    file: PathBuf,
    /// The directory the PNGs are written to (created if missing) [default: beside FILE, named
    /// after it: `runs/a.jsonl` gives `runs/a_plots/`].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// The start of each plot's title, before ", episode N" [default: FILE's name].
    #[arg(long)]
    title: Option<String>,
    /// The run's configuration (k_exp and the env step are read from it).
    #[command(flatten)]
    configuration: ConfigArgs,
}

/// The plot options of a run with `config`: its k_exp and env step, and `title`.
pub fn plot_options(config: &EnvConfig, title: String) -> PlotOptions {
    PlotOptions {
        title,
        k_exp: config.task.exp_rew_scaling,
        env_dt_s: Some(config.env_dt()),
    }
}

/// A plotting failure as the command reports it: bad input (an unreadable or malformed record,
/// an empty one, an unwritable directory) is a usage error; a drawing failure is not.
fn plot_failure(e: PlotError) -> Failure {
    let status = match e {
        PlotError::Draw { .. } => 1,
        _ => 2,
    };
    Failure {
        status,
        message: e.to_string(),
    }
}

/// The default output directory for `file`: `<dir>/<stem>_plots`.
fn default_out(file: &Path) -> PathBuf {
    let stem = file
        .file_stem()
        .map_or_else(|| "hyq".into(), |s| s.to_string_lossy().into_owned());
    file.with_file_name(format!("{stem}_plots"))
}

/// Runs `hyq plot`.
pub fn execute(args: PlotArgs) -> Result<(), Failure> {
    let config = args.configuration.config()?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.file));
    let title = args.title.clone().unwrap_or_else(|| {
        args.file
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
    });
    let options = plot_options(&config, title);
    // The whole record is read before anything is written.
    let read = hyq_render::read_jsonl(&args.file).map_err(plot_failure)?;
    if let Some(line) = read.torn_last_line {
        warn(&format!(
            "{}: line {line} is incomplete (the run that wrote it was cut short?); plotted the \
             whole lines before it",
            args.file.display()
        ));
    }
    let staged = StagedDir::create(&out).map_err(|e| {
        usage(format!(
            "--out {}: cannot create the directory: {e}",
            out.display()
        ))
    })?;
    let origin = args.file.display().to_string();
    let plots = hyq_render::plot_records(&read.records, &origin, &options, staged.path())
        .map_err(plot_failure)?;
    staged.publish().map_err(|e| published_failure(&out, &e))?;
    for p in &plots {
        let optional = [p.regularizers.as_ref(), p.velocity.as_ref()];
        for path in [&p.rewards, &p.distance]
            .into_iter()
            .chain(optional.into_iter().flatten())
        {
            let name = path.file_name().unwrap_or_default();
            print_line(&out.join(name).display().to_string())?;
        }
    }
    Ok(())
}

/// Moving finished plots into their directory failed.
fn published_failure(dir: &Path, e: &std::io::Error) -> Failure {
    Failure {
        status: 1,
        message: format!("{}: cannot put the plots in place: {e}", dir.display()),
    }
}

/// Collects the steps of each episode of a live run and plots it when it ends
/// (`hyq run --plot DIR`); the plots are put in the directory when the run has finished.
pub struct LivePlots {
    dir: PathBuf,
    staged: StagedDir,
    options: PlotOptions,
    series: EpisodeSeries,
    written: usize,
}

impl LivePlots {
    /// Plots into `dir`, created now so that an unwritable directory fails before the run.
    pub fn new(dir: &Path, config: &EnvConfig, title: String) -> Result<Self, Failure> {
        let staged = StagedDir::create(dir).map_err(|e| {
            usage(format!(
                "--plot {}: cannot create the directory: {e}",
                dir.display()
            ))
        })?;
        Ok(Self {
            dir: dir.to_owned(),
            staged,
            options: plot_options(config, title),
            series: EpisodeSeries::new(),
            written: 0,
        })
    }

    /// Adds one env step of the current episode. Its terms are the record's: with the height
    /// penalty off, the env's m_height is 1, as an absent `m_height` reads in a record; its
    /// reward is the record's (the velocity task's under `task.kind = "velocity"`).
    pub fn push(&mut self, info: &StepInfo) {
        self.series.push(&PlotRecord {
            t: info.t,
            episode: Some(info.episode),
            reward: info.total_reward(),
            terms: TermValues::all(&info.reward),
            d_n: Some(info.d_n),
            distance_to_goal: info.distance_to_goal,
            regularizers: info.regularizers.map(|r| r.terms),
            velocity: info.velocity.map(|v| VelocityPlotRecord {
                command: v.command,
                terms: v.terms,
                reward: v.reward,
                measured: Some(v.measured()),
            }),
        });
    }

    /// Plots the episode collected so far as episode number `episode` and starts the next one.
    pub fn finish_episode(&mut self, episode: u64) -> Result<(), Failure> {
        self.written += 1;
        let options = PlotOptions {
            title: if self.options.title.is_empty() {
                format!("episode {episode}")
            } else {
                format!("{}, episode {episode}", self.options.title)
            },
            ..self.options.clone()
        };
        let stem = format!("episode_{:03}", self.written);
        hyq_render::plot_episode(&self.series, &options, self.staged.path(), &stem).map_err(
            |e| {
                let mut failure = plot_failure(e);
                failure.message = format!("--plot {}: {}", self.dir.display(), failure.message);
                failure
            },
        )?;
        self.series = EpisodeSeries::new();
        Ok(())
    }

    /// Puts every plot in the directory; returns how many there are.
    pub fn publish(self) -> Result<usize, Failure> {
        self.staged
            .publish()
            .map(|files| files.len())
            .map_err(|e| published_failure(&self.dir, &e))
    }
}
