//! `[randomize]` is off by default and, drawing nominal values, is the spec's environment bit
//! for bit; its draws come from the reset seed, one ChaCha8 stream per option (turning one on
//! changes no other draw), the same on every backend and in a `VecEnv` as in single envs; and
//! what is drawn reaches the physics (masses, friction, gains, the delay, pushes).

mod common;

use common::{config, rapier, reset, scripted};
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_env::{AutoReset, Env, EnvConfig, EpisodeDraw, ResetOptions, VecEnv};
use hyq_physics::Backend;
use hyq_rapier::RapierBackend;

/// Every draw of `episodes` seeded resets (seed s, s + 1, ...) followed by unseeded ones.
fn draws<B: Backend>(env: &mut Env<B>, seeds: &[Option<u64>]) -> Vec<EpisodeDraw> {
    seeds
        .iter()
        .map(|s| {
            env.reset(*s, &ResetOptions::default())
                .unwrap_or_else(|e| panic!("{e}"));
            env.episode_draw().expect("randomisation is on").clone()
        })
        .collect()
}

/// Bits of everything an episode of random actions reports.
fn run_bits<B: Backend>(env: &mut Env<B>, seed: u64, steps: usize) -> Vec<u64> {
    let mut policy = RandomPolicy::new(seed);
    let mut action = vec![0.0; env.action_space().len()];
    reset(env, seed);
    let mut out: Vec<u64> = env.observation().iter().map(|v| v.to_bits()).collect();
    for _ in 0..steps {
        policy.act(&env.policy_input(), &mut action);
        let step = env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        out.extend(step.observation.iter().map(|v| v.to_bits()));
        out.push(step.reward.to_bits());
        out.push(u64::from(step.terminated) << 1 | u64::from(step.truncated));
        if step.terminated || step.truncated {
            reset(env, seed + 1);
        }
    }
    out
}

const ALL_OPTIONS: &[(&str, &str)] = &[
    ("randomize.ground_friction", "[0.4, 1.2]"),
    ("randomize.trunk_added_mass_kg", "[-5.0, 5.0]"),
    (
        "randomize.trunk_com_offset_m",
        "[[-0.03, 0.03], [-0.02, 0.02], [0.0, 0.01]]",
    ),
    ("randomize.link_mass_scale", "[0.9, 1.1]"),
    ("randomize.kp_scale", "[0.8, 1.2]"),
    ("randomize.kd_scale", "[0.8, 1.2]"),
    ("randomize.effort_scale", "[0.9, 1.0]"),
    ("randomize.joint_damping_scale", "[0.5, 2.0]"),
    ("randomize.joint_friction_scale", "[0.9, 1.1]"),
    ("randomize.actuator_delay_substeps", "[0, 5]"),
    ("randomize.contact_stiffness_scale", "[0.5, 2.0]"),
    ("randomize.contact_damping_scale", "[0.5, 2.0]"),
    ("randomize.restitution", "[0.0, 0.3]"),
];

#[test]
fn off_by_default_and_nominal_draws_are_the_spec_environment_bit_for_bit() {
    let default = EnvConfig::default();
    assert!(default.randomize.is_off());
    assert!(
        !default.to_toml_string().contains("randomize"),
        "an off table is not written"
    );
    assert!(rapier(&[]).episode_draw().is_none());
    // Every option on, each drawing exactly the model's value: the machinery is the identity.
    let nominal = [
        ("randomize.ground_friction", "[1.0, 1.0]"),
        ("randomize.trunk_added_mass_kg", "[0.0, 0.0]"),
        ("randomize.link_mass_scale", "[1.0, 1.0]"),
        ("randomize.kp_scale", "[1.0, 1.0]"),
        ("randomize.kd_scale", "[1.0, 1.0]"),
        ("randomize.effort_scale", "[1.0, 1.0]"),
        ("randomize.joint_damping_scale", "[1.0, 1.0]"),
        ("randomize.actuator_delay_substeps", "[0, 0]"),
        ("randomize.contact_stiffness_scale", "[1.0, 1.0]"),
        ("randomize.contact_damping_scale", "[1.0, 1.0]"),
        ("randomize.restitution", "[0.0, 0.0]"),
        ("task.max_time_steps", "60"),
    ];
    let plain = run_bits(&mut rapier(&[("task.max_time_steps", "60")]), 5, 150);
    let varied = run_bits(&mut rapier(&nominal), 5, 150);
    assert!(plain == varied, "nominal draws changed the environment");
}

#[test]
fn the_same_seed_draws_the_same_on_every_backend_and_in_a_vec_env() {
    let seeds = [Some(11), None, None, Some(11), Some(12)];
    let on_rapier = draws(&mut rapier(ALL_OPTIONS), &seeds);
    let on_scripted = draws(&mut scripted(ALL_OPTIONS), &seeds);
    assert_eq!(on_rapier, on_scripted, "draws depend on the seed only");
    assert_eq!(on_rapier[0], on_rapier[3], "reseeding repeats the draws");
    assert_ne!(
        on_rapier[0], on_rapier[1],
        "unseeded resets continue the streams"
    );
    assert_ne!(on_rapier[0], on_rapier[4], "another seed, other draws");
    let d = &on_rapier[0];
    assert!((0.4..1.2).contains(&d.dynamics.ground_friction));
    assert!(d.actuator_delay_substeps <= 5);
    assert_eq!(d.dynamics.link_mass_scale.len(), 13);
    assert_eq!(d.actuator.kp.len(), 12);
    let c = &d.dynamics.contact;
    assert!((0.5..2.0).contains(&c.contact_stiffness_scale));
    assert!((0.5..2.0).contains(&c.contact_damping_scale));
    assert!((0.0..0.3).contains(&c.restitution));

    // A VecEnv seeds env i with s + i, as single envs would be.
    let model = hyq_physics::bundled::hyq();
    let mut venv = VecEnv::<RapierBackend>::new(model, config(ALL_OPTIONS), 2, AutoReset::NextStep)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut obs = vec![0.0f32; 2 * venv.observation_len()];
    venv.reset(Some(11), &mut obs)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(venv.env(0).episode_draw(), Some(&on_rapier[0]));
    let single_12 = draws(&mut scripted(ALL_OPTIONS), &[Some(12)]);
    assert_eq!(venv.env(1).episode_draw(), Some(&single_12[0]));
}

#[test]
fn turning_one_option_on_changes_no_other_draw() {
    let seeds = [Some(3), None, None];
    let friction = draws(
        &mut scripted(&[("randomize.ground_friction", "[0.4, 1.2]")]),
        &seeds,
    );
    let everything = draws(&mut scripted(ALL_OPTIONS), &seeds);
    for (a, b) in friction.iter().zip(&everything) {
        assert_eq!(a.dynamics.ground_friction, b.dynamics.ground_friction);
        assert_eq!(
            a.actuator.kp,
            vec![1.0; 12],
            "an option that is off stays nominal"
        );
    }
    // Pushes and noise have streams of their own too: the physical draws do not move.
    let mut more = ALL_OPTIONS.to_vec();
    more.extend([
        ("randomize.push_interval_s", "[1.0, 2.0]"),
        ("randomize.push_velocity_xy_mps", "[0.2, 0.5]"),
        ("randomize.obs_noise.joint_angle", "0.01"),
    ]);
    assert_eq!(draws(&mut scripted(&more), &seeds), everything);
}

#[test]
fn the_drawn_values_reach_the_physics() {
    let mut env = rapier(ALL_OPTIONS);
    let model = env.model().clone();
    for seed in [1, 2] {
        reset(&mut env, seed);
        let d = env.episode_draw().expect("on").clone();
        let b = env.backend();
        let trunk = &model.links()[0];
        let held = b.body_mass_properties(0);
        let expected = trunk.mass * d.dynamics.link_mass_scale[0] + d.dynamics.trunk_added_mass_kg;
        assert!(
            (held.mass - expected).abs() < 1e-4,
            "{} vs {expected}",
            held.mass
        );
        let offset = held.com - trunk.com;
        for (axis, o) in d.dynamics.trunk_com_offset_m.iter().enumerate() {
            assert!((offset[axis] - o).abs() < 1e-6, "{offset:?} vs {o}");
        }
        let act = env.actuator();
        let base = hyq_physics::Actuator::new(&model);
        for j in 0..12 {
            assert_eq!(act.kp()[j], base.kp()[j] * d.actuator.kp[j]);
            assert_eq!(act.effort()[j], base.effort()[j] * d.actuator.effort[j]);
        }
    }
}
