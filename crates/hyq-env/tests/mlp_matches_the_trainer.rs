//! Invariant: the Rust forward pass of the committed trained policy
//! (`assets/policies/hyq_walk.safetensors`) gives Stable-Baselines3's own deterministic actions
//! for the observations the export script recorded (`tests/fixtures/hyq_walk_actions.safetensors`,
//! written with the policy by `examples/export_policy.py --fixture`), within 1e-5 on every
//! value; and the committed file fits the bundled robot in the environment it was trained in.

use std::path::PathBuf;

use hyq_env::{ActionSpace, EnvConfig, MlpPolicy, Policy, PolicyInput};
use safetensors::{Dtype, SafeTensors};

fn repo_file(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(relative)
}

fn f32_tensor(tensors: &SafeTensors<'_>, name: &str) -> (Vec<usize>, Vec<f32>) {
    let view = tensors
        .tensor(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(view.dtype(), Dtype::F32, "{name}");
    let values = view
        .data()
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    (view.shape().to_vec(), values)
}

fn committed_policy() -> MlpPolicy {
    MlpPolicy::from_file(&repo_file("../../assets/policies/hyq_walk.safetensors"))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The configuration the policy was trained in (its metadata applied over the defaults).
fn trained_config(policy: &MlpPolicy) -> EnvConfig {
    let pairs: Vec<(&str, &str)> = policy
        .metadata()
        .env_config
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    let mut config = EnvConfig::default();
    config.set_all(&pairs).unwrap_or_else(|e| panic!("{e}"));
    config
}

#[test]
fn rust_actions_match_stable_baselines3_on_recorded_observations() {
    let bytes = std::fs::read(repo_file("tests/fixtures/hyq_walk_actions.safetensors"))
        .unwrap_or_else(|e| panic!("{e}"));
    let fixture = SafeTensors::deserialize(&bytes).unwrap_or_else(|e| panic!("{e}"));
    let (obs_shape, observations) = f32_tensor(&fixture, "observations");
    let (act_shape, actions) = f32_tensor(&fixture, "actions");
    assert_eq!(obs_shape[0], act_shape[0]);
    assert!(
        obs_shape[0] >= 20,
        "too few recorded observations: {obs_shape:?}"
    );

    let mut policy = committed_policy();
    let model = hyq_physics::bundled::hyq();
    let config = trained_config(&policy);
    let space = ActionSpace::new(&model, &config.action);
    let (n_obs, n_act) = (obs_shape[1], act_shape[1]);
    let mut action = vec![0.0; n_act];
    let mut worst = 0.0f64;
    let mut inside = 0;
    for (obs, want) in observations
        .chunks_exact(n_obs)
        .zip(actions.chunks_exact(n_act))
    {
        let obs: Vec<f64> = obs.iter().map(|v| f64::from(*v)).collect();
        let input = PolicyInput {
            t: 0,
            env_dt: 0.01,
            observation: &obs,
            joint_angles: &obs[..n_act],
            standing: model.standing_pose(),
            space: &space,
        };
        policy.act(&input, &mut action);
        for (got, want) in action.iter().zip(want) {
            worst = worst.max((got - f64::from(*want)).abs());
            inside += usize::from(got.abs() < 1.0);
        }
    }
    eprintln!("largest difference from SB3's actions: {worst:e}, {inside} values inside the space");
    assert!(
        worst <= 1e-5,
        "largest difference from SB3's actions: {worst:e}"
    );
    // Most values are not clipped, so the comparison is of the network, not of the clip.
    assert!(
        inside * 2 > actions.len(),
        "{inside} of {} values inside the space",
        actions.len()
    );
}

#[test]
fn the_committed_policy_fits_hyq_in_its_training_environment() {
    let policy = committed_policy();
    let model = hyq_physics::bundled::hyq();
    let config = trained_config(&policy);
    policy
        .check_env(&model, &config, "hyq_walk.safetensors")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(policy.widths().first(), Some(&39));
    assert_eq!(policy.widths().last(), Some(&12));
    let size = std::fs::metadata(repo_file("../../assets/policies/hyq_walk.safetensors"))
        .map(|m| m.len())
        .unwrap_or(u64::MAX);
    assert!(size < 1 << 20, "{size} bytes");
}
