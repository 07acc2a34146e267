//! How far the feet slide on the ground under the same actions on rapier, DART and MuJoCo: the
//! measurement behind docs/training.md's account of the learned walker's sim-to-sim gap.
//!
//! ```sh
//! cargo run --release -p hyq-compare --features dart,mujoco --example foot_slip \
//!     -- assets/policies/hyq_walk.safetensors [KEY=VALUE]...
//! ```
//!
//! The trained policy runs one episode closed loop on rapier (first reset seed 1000, the
//! evaluation's reset noise, the file's environment, then the `KEY=VALUE` overrides), and its
//! actions are replayed open loop on each engine from the same reset, as `hyq compare --policy`
//! replays them. Per engine it prints the trunk's travel along x and, over every env step on
//! which a foot's latched contact flag was set on that step and the one before, the foot
//! collision sphere's centre's horizontal motion (taken from the engine's own link poses):
//! its total, its mean per such foot-step, and its part along +x.

// An example: a failed unwrap ends it with the location, which is all it needs.
#![allow(clippy::unwrap_used, missing_docs)]

use std::path::PathBuf;
use std::sync::Arc;

use hyq_env::{Env, EnvConfig, MlpPolicy, Policy, ResetOptions};
use hyq_physics::na::{Isometry3, Vector3};
use hyq_physics::{Backend, RobotModel};

const SEED: u64 = 1000;

fn replay<B: Backend>(model: &Arc<RobotModel>, config: &EnvConfig, actions: &[Vec<f64>]) {
    let mut env = Env::<B>::new(model.clone(), config.clone()).unwrap();
    env.reset(Some(SEED), &ResetOptions::default()).unwrap();
    // The feet are the tracked bodies but the trunk (the last one).
    let feet = &model.tracked()[..model.tracked().len() - 1];
    let centres = |poses: &[Isometry3<f64>]| -> Vec<Vector3<f64>> {
        feet.iter()
            .map(|t| {
                let sphere = &model.links()[t.link].collisions[t.shapes[0]];
                (poses[t.link] * sphere.origin).translation.vector
            })
            .collect()
    };
    let mut poses = vec![Isometry3::identity(); model.links().len()];
    env.backend().link_poses(&mut poses);
    let mut before = centres(&poses);
    let mut touching_before = vec![false; feet.len()];
    let x0 = env.trunk().pose.translation.x;
    let (mut slide, mut along_x, mut foot_steps) = (0.0, 0.0, 0u64);
    for action in actions {
        env.step(action).unwrap();
        env.backend().link_poses(&mut poses);
        let now = centres(&poses);
        let touching = env.contacts()[..feet.len()].to_vec();
        for k in 0..feet.len() {
            if touching[k] && touching_before[k] {
                let d = now[k] - before[k];
                slide += d.x.hypot(d.y);
                along_x += d.x;
                foot_steps += 1;
            }
        }
        before = now;
        touching_before = touching;
    }
    println!(
        "{}: trunk travel along x {:.3} m; {} foot-steps touching; feet slid {:.3} m while touching ({:.2} mm per foot-step), {:.3} m of it along +x",
        B::NAME,
        env.trunk().pose.translation.x - x0,
        foot_steps,
        slide,
        1000.0 * slide / foot_steps.max(1) as f64,
        along_x
    );
}

fn main() {
    let mut args = std::env::args().skip(1);
    let file = PathBuf::from(
        args.next()
            .unwrap_or("assets/policies/hyq_walk.safetensors".into()),
    );
    let model = hyq_physics::bundled::hyq();
    let mut policy = MlpPolicy::from_file(&file).unwrap();
    let mut pairs = policy.metadata().env_config.clone();
    pairs.push(("reset.joint_noise_rad".into(), "0.05".into()));
    pairs.push(("reset.yaw_noise_deg".into(), "5".into()));
    for item in args {
        let (key, value) = item.split_once('=').unwrap();
        pairs.push((key.into(), value.into()));
    }
    let pairs: Vec<(&str, &str)> = pairs
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    let config = EnvConfig::load::<&str, &str>(None, &pairs).unwrap();
    policy
        .check_env(&model, &config, &file.display().to_string())
        .unwrap();

    let mut env = Env::<hyq_rapier::RapierBackend>::new(model.clone(), config.clone()).unwrap();
    env.reset(Some(SEED), &ResetOptions::default()).unwrap();
    let mut actions = Vec::new();
    let mut action = vec![0.0; env.action_space().len()];
    loop {
        policy.act(&env.policy_input(), &mut action);
        let step = env.step(&action).unwrap();
        actions.push(action.clone());
        if step.terminated || step.truncated {
            break;
        }
    }
    replay::<hyq_rapier::RapierBackend>(&model, &config, &actions);
    replay::<hyq_dart::DartBackend>(&model, &config, &actions);
    replay::<hyq_mujoco::MujocoBackend>(&model, &config, &actions);
}
