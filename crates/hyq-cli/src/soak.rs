//! `hyq soak`: uniformly random actions for many env steps (10⁶ by default), resetting whenever
//! an episode ends, checking that nothing panics and that every number the environment emits is
//! finite: every observation row (f64 and f32), the reward and each of its terms and
//! multipliers, D^t, D_n^t, roll, pitch, yaw, the goal, C^0 and the joint targets, after every
//! reset and every step. The first non-finite value stops the soak with an error naming the
//! step, the episode and the field (exit status 1).
//!
//! It also measures what the spec could only estimate: the summary gives, per observation row,
//! the smallest and largest value seen and the largest magnitude (rows 33–38, the trunk
//! acceleration and position, are marked `*` in the spec: "actual range unknown"), the number
//! of episodes and why they ended.
//!
//! `cargo xtask soak` runs this in a release build; the test suite runs a short soak.

use std::fmt::Write as _;

use clap::Args;
use hyq_env::{Env, Policy, RandomPolicy, ResetOptions, StepInfo};
use hyq_physics::Backend;
use indicatif::ProgressBar;
use serde::Serialize;

use crate::Failure;
use crate::backend::with_backend;
use crate::bench::Ended;
use crate::options::{EnvArgs, make_env};
use crate::output::{print, print_json_line, progress_bar};
use crate::table::Table;

/// `hyq soak` arguments.
#[derive(Debug, Args)]
pub struct SoakArgs {
    #[command(flatten)]
    env: EnvArgs,
    /// Env steps in all.
    #[arg(long, default_value_t = 1_000_000, value_parser = clap::value_parser!(u64).range(1..))]
    steps: u64,
    /// Seed of the random actions and of the first reset.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Print the summary as one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

/// What one observation row did over the soak.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RowRange {
    /// The row's index.
    pub index: usize,
    /// The row's name.
    pub name: String,
    /// The smallest value seen.
    pub min: f64,
    /// The largest value seen.
    pub max: f64,
    /// The largest |value| seen.
    pub max_abs: f64,
    /// The spec's declared lower bound.
    pub spec_min: f64,
    /// The spec's declared upper bound.
    pub spec_max: f64,
    /// Whether the spec marks the bounds as estimates (rows 33–38).
    pub estimated: bool,
}

/// The soak's summary (`--json`: one object).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SoakReport {
    /// The backend's name.
    pub backend: &'static str,
    /// The robot's name.
    pub robot: String,
    /// The seed.
    pub seed: u64,
    /// Env steps taken.
    pub steps: u64,
    /// Episodes that ended (each was reset).
    pub episodes: u64,
    /// Why they ended (a step may have several reasons).
    pub episodes_ended: Ended,
    /// Non-finite values found: always 0 in a report (the first one is an error).
    pub non_finite: u64,
    /// Per observation row, what was seen (after every reset and step).
    pub rows: Vec<RowRange>,
}

/// Runs `hyq soak`.
pub fn execute(args: SoakArgs) -> Result<(), Failure> {
    let model = args.env.model()?;
    let config = args.env.config()?;
    with_backend!(args.env.backend, B => {
        let mut env = make_env::<B>(model, config)?;
        let report = soak(&mut env, args.steps, args.seed, true)?;
        print_report(&report, args.json)
    })
}

/// The first non-finite number of an observation and an info, named.
fn first_non_finite(obs: &[f64], obs_f32: &[f32], info: &StepInfo) -> Option<(String, f64)> {
    if let Some(i) = obs.iter().position(|v| !v.is_finite()) {
        return Some((format!("observation[{i}]"), obs[i]));
    }
    if let Some(i) = obs_f32.iter().position(|v| !v.is_finite()) {
        return Some((format!("observation_f32[{i}]"), f64::from(obs_f32[i])));
    }
    let r = &info.reward;
    let named = [
        ("distance_to_goal", info.distance_to_goal),
        ("d_n", info.d_n),
        ("roll", info.roll),
        ("pitch", info.pitch),
        ("yaw", info.yaw),
    ];
    if !r.total.is_finite() {
        return Some(("reward.total".to_owned(), r.total));
    }
    if let Some((term, v)) = r.terms().find(|(_, v)| !v.is_finite()) {
        return Some((format!("reward.{}", term.name), v));
    }
    if let Some((name, v)) = named.iter().find(|(_, v)| !v.is_finite()) {
        return Some(((*name).to_owned(), *v));
    }
    for (what, values) in [
        ("goal", &info.goal[..]),
        ("initial_position", &info.initial_position[..]),
        ("joint_targets", &info.joint_targets[..]),
    ] {
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Some((format!("{what}[{i}]"), values[i]));
        }
    }
    None
}

/// Soaks `env` for `steps` env steps of random actions seeded with `seed`.
pub fn soak<B: Backend>(
    env: &mut Env<B>,
    steps: u64,
    seed: u64,
    progress: bool,
) -> Result<SoakReport, Failure> {
    let mut ranges = row_ranges(env);
    let bar = if progress {
        progress_bar(steps)
    } else {
        ProgressBar::hidden()
    };
    let mut policy = RandomPolicy::new(seed);
    let mut action = vec![0.0; env.action_space().len()];
    let mut episodes = 0;
    let mut ended = Ended::default();
    env.reset(Some(seed), &ResetOptions::default())
        .map_err(reset_failure::<B>)?;
    check_finite(env, "reset")?;
    observe(&mut ranges, env.observation());
    for n in 1..=steps {
        policy.act(&env.policy_input(), &mut action);
        let done = soak_step(env, &action, n)?;
        check_finite(env, "a step")?;
        observe(&mut ranges, env.observation());
        if done {
            episodes += 1;
            for reason in env.info().reasons.iter() {
                ended.add(reason);
            }
            env.reset(None, &ResetOptions::default())
                .map_err(reset_failure::<B>)?;
            check_finite(env, "reset")?;
            observe(&mut ranges, env.observation());
        }
        if n % 1000 == 0 {
            bar.set_position(n);
            bar.set_message(format!("{episodes} episodes"));
        }
    }
    bar.finish_and_clear();
    Ok(SoakReport {
        backend: B::NAME,
        robot: env.model().name().to_owned(),
        seed,
        steps,
        episodes,
        episodes_ended: ended,
        non_finite: 0,
        rows: ranges,
    })
}

/// An empty range per observation row of `env`, with the row's table bounds.
fn row_ranges<B: Backend>(env: &Env<B>) -> Vec<RowRange> {
    env.observation_layout()
        .rows()
        .iter()
        .map(|row| RowRange {
            index: row.index,
            name: row.name.to_string(),
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            max_abs: 0.0,
            spec_min: row.min,
            spec_max: row.max,
            estimated: row.estimated,
        })
        .collect()
}

/// Widens each row's range to take in the observation `obs`.
fn observe(ranges: &mut [RowRange], obs: &[f64]) {
    for (range, v) in ranges.iter_mut().zip(obs) {
        range.min = range.min.min(*v);
        range.max = range.max.max(*v);
        range.max_abs = range.max_abs.max(v.abs());
    }
}

/// The soak's failure when a value of `env`'s observation or info is not finite after `when`.
fn check_finite<B: Backend>(env: &Env<B>, when: &str) -> Result<(), Failure> {
    match first_non_finite(env.observation(), env.observation_f32(), env.info()) {
        None => Ok(()),
        Some((field, value)) => Err(Failure {
            status: 1,
            message: format!(
                "soak on {}: {field} is {value} after {when} (episode {}, t = {})",
                B::NAME,
                env.info().episode,
                env.info().t
            ),
        }),
    }
}

/// The soak's failure when a reset fails.
fn reset_failure<B: Backend>(e: hyq_env::EnvError) -> Failure {
    Failure {
        status: 1,
        message: format!("soak on {}: reset: {e}", B::NAME),
    }
}

/// Takes soak step `n` with `action`; whether the episode ended. A failed step or a non-finite
/// reward is the soak's failure.
fn soak_step<B: Backend>(env: &mut Env<B>, action: &[f64], n: u64) -> Result<bool, Failure> {
    let step = env.step(action).map_err(|e| Failure {
        status: 1,
        message: format!("soak on {}: step {n}: {e}", B::NAME),
    })?;
    if !step.reward.is_finite() {
        return Err(Failure {
            status: 1,
            message: format!(
                "soak on {}: the reward is {} at step {n}",
                B::NAME,
                step.reward
            ),
        });
    }
    Ok(step.terminated || step.truncated)
}

fn print_report(r: &SoakReport, json: bool) -> Result<(), Failure> {
    if json {
        return print_json_line(r, "a soak report");
    }
    let mut t = String::new();
    let e = &r.episodes_ended;
    let _ = writeln!(
        t,
        "hyq soak: {} on the {} backend, seed {}: {} env steps, {} episodes, no panic, no non-finite value",
        r.robot, r.backend, r.seed, r.steps, r.episodes
    );
    let _ = writeln!(
        t,
        "  episodes ended: fell {}, joint_limit {}, timeout {}, reached {}, diverged {}",
        e.fell, e.joint_limit, e.timeout, e.reached, e.diverged
    );
    let mut table = Table::new(&["row", "<name", "min", "max", "max_abs", "<spec range"]);
    for row in &r.rows {
        table.row(vec![
            row.index.to_string(),
            row.name.clone(),
            format!("{:.4}", row.min),
            format!("{:.4}", row.max),
            format!("{:.4}", row.max_abs),
            format!(
                "[{:.4}, {:.4}]{}",
                row.spec_min,
                row.spec_max,
                if row.estimated { " (estimated)" } else { "" }
            ),
        ]);
    }
    t.push_str(&table.render());
    print(&t)
}

#[cfg(test)]
mod tests {
    // In tests a failed unwrap is a failed test, with its location.
    #![allow(clippy::unwrap_used)]

    use super::first_non_finite;
    use hyq_env::testing::ScriptedBackend;
    use hyq_env::{Env, EnvConfig, ResetOptions};

    #[test]
    fn the_finiteness_check_names_the_first_bad_field() {
        let mut env: Env<ScriptedBackend> =
            Env::new(hyq_physics::bundled::hyq(), EnvConfig::default()).unwrap();
        env.reset(Some(0), &ResetOptions::default()).unwrap();
        let obs = env.observation().to_vec();
        let obs32 = env.observation_f32().to_vec();
        let mut info = env.info().clone();
        assert_eq!(first_non_finite(&obs, &obs32, &info), None);
        info.yaw = f64::NAN;
        let (field, _) = first_non_finite(&obs, &obs32, &info).unwrap();
        assert_eq!(field, "yaw");
        info.joint_targets[3] = f64::INFINITY;
        info.yaw = 0.0;
        assert_eq!(
            first_non_finite(&obs, &obs32, &info),
            Some(("joint_targets[3]".to_owned(), f64::INFINITY))
        );
        let mut bad = obs.clone();
        bad[38] = f64::NAN;
        let (field, _) = first_non_finite(&bad, &obs32, &info).unwrap();
        assert_eq!(field, "observation[38]");
    }
}
