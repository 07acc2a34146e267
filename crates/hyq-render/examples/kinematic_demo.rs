//! Renders a scripted (kinematic, not simulated) trot of HyQ towards a goal, logs its per-step
//! records as the environment would (rewards from `hyq-spec`'s rules) and plots them.
//!
//! ```sh
//! cargo run --release -p hyq-render --example kinematic_demo -- target/hyq-render-demo
//! ```
//!
//! Writes `trot.gif`, `frames/frame_*.png` (every 20th frame), `records.jsonl` and
//! `plots/episode_001_{rewards,distance}.png` into the directory given (default
//! `hyq-render-demo` in the system's temporary directory). The motion is a script: the feet
//! slide a little and nothing pushes back. It shows what the renderer and the plots draw, not
//! how HyQ walks; the environment's `hyq render` draws real episodes.

use std::io::Write as _;
use std::path::PathBuf;

use hyq_physics::na::{Isometry3, Point3, Translation3, UnitQuaternion};
use hyq_render::{
    GifWriter, Overlay, PlotOptions, PlotRecord, PngSequence, RenderConfig, Renderer, RobotPose,
    Scene, TermValues, plot_jsonl,
};
use hyq_spec::{EpisodeRules, RobotDescription, StepSnapshot, TaskConfig};

/// Env step (s), GIF frame rate, episode length (s), trunk speed (m/s), gait frequency (Hz).
const DT: f64 = 0.01;
const FPS: f64 = 20.0;
const SECONDS: f64 = 8.0;
const SPEED: f64 = 0.55;
const GAIT_HZ: f64 = 1.6;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).map_or_else(
        || std::env::temp_dir().join("hyq-render-demo"),
        PathBuf::from,
    );
    std::fs::create_dir_all(&out)?;

    let model = hyq_physics::bundled::hyq();
    let mut renderer = Renderer::new(model.clone(), RenderConfig::default())?;
    let config = TaskConfig {
        base_rew_scaling: Some(1.0),
        norm_rew_scaling: Some(10.0),
        reach_target_bonus_reward: 50.0,
        ..TaskConfig::default()
    };
    let description = RobotDescription::hyq_spec();
    let height = model.spawn_height() - 0.02;
    let start = Point3::new(0.0, 0.0, height);
    let goal = Point3::new(5.0, 0.0, height);
    let rules = EpisodeRules::new(&config, start, goal)?;

    let mut gif = GifWriter::create(out.join("trot.gif"), 480, 360, FPS)?;
    let mut pngs = PngSequence::create(out.join("frames"))?;
    let mut log = std::io::BufWriter::new(std::fs::File::create(out.join("records.jsonl"))?);
    let standing = model.standing_pose().to_vec();
    let mut q = standing.clone();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    let mut contacts = vec![false; model.tracked().len()];
    let mut previous = start;
    let mut episode_return = 0.0;
    let steps = (SECONDS / DT).round() as u64;
    let frame_every = (1.0 / (FPS * DT)).round() as u64;

    for step in 1..=steps {
        let t = step as f64 * DT;
        let (trunk, position) = trot_pose(&standing, t, height, &mut q);
        model.link_poses(&trunk, &q, &mut poses)?;
        for (i, c) in contacts.iter_mut().enumerate() {
            *c = model.tracked_lowest_z(i, &poses) < 0.012;
        }

        let outcome = rules.evaluate_step(&StepSnapshot {
            step,
            previous_position: previous,
            position,
            orientation: trunk.rotation,
            joint_angles: &q,
            joint_ranges: description.joint_ranges(),
            trunk_contact: contacts[model.trunk_tracked_index()],
        })?;
        previous = position;
        episode_return += outcome.reward.total;
        writeln!(log, "{}", serde_json::to_string(&record(step, &outcome))?)?;

        if step % frame_every == 0 {
            let scene = Scene::new(RobotPose::Links(&poses), &contacts)
                .with_goal(goal)
                .with_overlay(Overlay {
                    time_s: t,
                    distance_to_goal_m: outcome.distance,
                    episode_return,
                });
            let frame = renderer.render(&scene)?;
            gif.push(&frame)?;
            if gif.frames_written() % 20 == 1 {
                pngs.push(&frame)?;
            }
        }
        if outcome.terminated() || outcome.truncated() {
            break;
        }
    }
    gif.finish()?;
    log.into_inner()?; // flushed and closed before the plots read it
    let options = PlotOptions {
        title: "scripted trot (kinematic)".into(),
        k_exp: config.exp_rew_scaling,
        env_dt_s: Some(DT),
    };
    let plots = plot_jsonl(out.join("records.jsonl"), &options, out.join("plots"))?.plots;
    println!(
        "wrote {} and {} plot pairs",
        out.join("trot.gif").display(),
        plots.len()
    );
    Ok(())
}

/// The JSONL record of step `step` of the episode, scored as `outcome`.
fn record(step: u64, outcome: &hyq_spec::StepOutcome) -> PlotRecord {
    let b = outcome.reward;
    PlotRecord {
        t: step,
        episode: Some(1),
        reward: b.total,
        terms: TermValues::all(&b),
        d_n: outcome.normalised_distance,
        distance_to_goal: outcome.distance,
        regularizers: None,
        velocity: None,
    }
}

/// The scripted trot at time `t` (s): the joint angles into `q` (from the `standing` pose),
/// and the trunk's pose and position at trunk height about `height`.
fn trot_pose(
    standing: &[f64],
    t: f64,
    height: f64,
    q: &mut [f64],
) -> (Isometry3<f64>, Point3<f64>) {
    let phase = std::f64::consts::TAU * GAIT_HZ * t;
    // Trot: diagonal pairs (left front with right hind, right front with left hind) swing
    // half a cycle apart. Each leg sweeps its hip forward and back and bends its knee
    // while swinging.
    for (leg, chunk) in q.chunks_mut(3).enumerate() {
        let pair_phase = if leg == 0 || leg == 3 {
            phase
        } else {
            phase + std::f64::consts::PI
        };
        let base = &standing[leg * 3..leg * 3 + 3];
        let lift = pair_phase.sin().max(0.0);
        chunk[0] = base[0];
        chunk[1] = base[1] - 0.22 * pair_phase.cos() * base[1].signum();
        chunk[2] = base[2] + 0.45 * lift * base[2].signum();
    }
    let yaw = 0.06 * (0.5 * phase).sin();
    let position = Point3::new(
        SPEED * t,
        0.05 * (0.25 * phase).sin(),
        height + 0.01 * (2.0 * phase).cos(),
    );
    let trunk = Isometry3::from_parts(
        Translation3::from(position.coords),
        UnitQuaternion::from_euler_angles(0.0, 0.015 * phase.cos(), yaw),
    );
    (trunk, position)
}
