//! Invariant: `task.kind = "velocity"` poses the velocity-command task (docs/velocity.md) and
//! leaves the spec's task as it was. A commanded stand (zero command, the standing pose held by
//! the PD actuator) holds still on both bundled robots, on rapier and (with `--features dart` /
//! `mujoco`) on DART and MuJoCo, and earns the tracking terms' maximum; the task's observation
//! rows hold the command, gravity and the joint offsets; commands are seeded (the same seed
//! gives the same commands and rewards bit for bit, on a single env and a vector env alike); a
//! fixed range fixes the command; bad values are one-line errors naming their key; and the
//! default configuration reports no velocity info and keeps the spec's 39 rows.

use std::sync::Arc;

use hyq_env::policy::{Policy, Stand};
use hyq_env::{AutoReset, Env, EnvConfig, ResetOptions, TaskKind, VecEnv, VecStepOut};
use hyq_physics::{Backend, RobotModel, bundled};
use hyq_rapier::RapierBackend;

fn velocity_config(overrides: &[(&str, &str)]) -> EnvConfig {
    let mut pairs = vec![("task.kind", "velocity")];
    pairs.extend_from_slice(overrides);
    EnvConfig::load(None, &pairs).unwrap_or_else(|e| panic!("{e}"))
}

const STANDING: &[(&str, &str)] = &[
    ("command.lin_vel_x", "[0.0, 0.0]"),
    ("command.lin_vel_y", "[0.0, 0.0]"),
    ("command.ang_vel_yaw", "[0.0, 0.0]"),
];

/// Holds the standing pose for 3 s under the zero command; checks that the trunk stays put and
/// level, nothing ends the episode, and the tracking terms reach their maximum.
fn commanded_stand_holds_still<B: Backend>(model: &Arc<RobotModel>) {
    let config = velocity_config(STANDING);
    let mut env = Env::<B>::new(Arc::clone(model), config).unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let start = env.trunk().pose.translation.vector;
    let mut a = vec![0.0; model.num_joints()];
    let mut last = None;
    for t in 0..300 {
        Stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            !s.terminated && !s.truncated,
            "t = {t}: {:?}",
            s.info.reasons
        );
        let v = s.info.velocity.unwrap_or_else(|| panic!("velocity info"));
        assert_eq!(v.command, [0.0; 3]);
        assert!(s.reward.is_finite() && s.reward >= 0.0);
        last = Some((v, s.reward));
    }
    let (v, reward) = last.unwrap_or_else(|| panic!("stepped"));
    let end = env.trunk().pose.translation.vector;
    let drift = ((end.x - start.x).powi(2) + (end.y - start.y).powi(2)).sqrt();
    let name = model.name();
    assert!(drift < 0.05, "{name} on {}: drifted {drift} m", B::NAME);
    // Settled: the trunk's speed and turning are small, so both tracking terms are within
    // 1e-3 of their maximum, 1.
    assert!(
        v.terms.tracking_lin_vel > 1.0 - 1e-3 && v.terms.tracking_lin_vel <= 1.0,
        "{name} on {}: {v:?}",
        B::NAME
    );
    assert!(
        v.terms.tracking_ang_vel > 1.0 - 1e-3 && v.terms.tracking_ang_vel <= 1.0,
        "{name} on {}: {v:?}",
        B::NAME
    );
    // A zero command asks to stand: no air-time or slip term, and the trunk level.
    assert_eq!(v.terms.feet_air_time, 0.0);
    assert_eq!(v.terms.foot_slip, 0.0);
    assert!(v.terms.orientation < 1e-3, "{name}: {v:?}");
    // The reward is the preset's scaled sum of the reported terms, bit for bit; the tracking
    // part (1.0 + 0.5 under legged_gym's preset) outweighs the holding torques.
    let dt = env.env_dt();
    let scales = env.config().velocity.resolve();
    assert_eq!(reward, hyq_tasks::step::total(&scales, &v.terms, dt));
    assert!(
        reward > 0.8 * 1.5 * dt && reward <= 1.5 * dt,
        "{name}: reward {reward}"
    );
    // The task's rows: the command, gravity straight down, joints near the standing pose.
    let layout = env.observation_layout();
    let group = layout.groups().last().unwrap_or_else(|| panic!("a group"));
    assert_eq!(group.name, "velocity_task");
    let obs = &env.observation()[group.rows.clone()];
    assert_eq!(&obs[9..12], &[0.0; 3], "command rows");
    assert!(
        (obs[8] + 1.0).abs() < 1e-3,
        "projected gravity z: {}",
        obs[8]
    );
    let n = model.num_joints();
    assert_eq!(obs.len(), 12 + 2 * n);
    assert!(obs[12..12 + n].iter().all(|o| o.abs() < 0.1), "offsets");
}

#[test]
fn commanded_stand_holds_still_on_rapier() {
    commanded_stand_holds_still::<RapierBackend>(&bundled::hyq());
    commanded_stand_holds_still::<RapierBackend>(&bundled::anymal_c());
}

#[cfg(feature = "dart")]
#[test]
fn commanded_stand_holds_still_on_dart() {
    commanded_stand_holds_still::<hyq_dart::DartBackend>(&bundled::hyq());
    commanded_stand_holds_still::<hyq_dart::DartBackend>(&bundled::anymal_c());
}

#[cfg(feature = "mujoco")]
#[test]
fn commanded_stand_holds_still_on_mujoco() {
    commanded_stand_holds_still::<hyq_mujoco::MujocoBackend>(&bundled::hyq());
    commanded_stand_holds_still::<hyq_mujoco::MujocoBackend>(&bundled::anymal_c());
}

/// (commands, rewards) of 300 steps of the standing policy from `seed`.
fn run(config: &EnvConfig, seed: u64) -> (Vec<[f64; 3]>, Vec<u64>) {
    let model = bundled::hyq();
    let mut env =
        Env::<RapierBackend>::new(model.clone(), config.clone()).unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(seed), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut a = vec![0.0; model.num_joints()];
    let (mut commands, mut rewards) = (Vec::new(), Vec::new());
    for _ in 0..300 {
        Stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        let v = s.info.velocity.unwrap_or_else(|| panic!("velocity info"));
        commands.push(v.command);
        rewards.push(s.reward.to_bits());
        if s.terminated || s.truncated {
            break;
        }
    }
    (commands, rewards)
}

#[test]
fn commands_are_seeded_and_redrawn_on_schedule() {
    // A 1 s resampling time: 300 steps of 10 ms see three commands.
    let config = velocity_config(&[("command.resampling_time_s", "1.0")]);
    let a = run(&config, 7);
    assert_eq!(a, run(&config, 7), "same seed, same commands and rewards");
    assert_ne!(a.0, run(&config, 8).0, "another seed, other commands");
    let changes = a.0.windows(2).filter(|w| w[0] != w[1]).count();
    assert_eq!(changes, 2, "redrawn at t = 100 and 200");
    assert!(a.0.iter().flatten().all(|c| (-1.0..=1.0).contains(c)));
}

#[test]
fn a_fixed_range_fixes_the_command() {
    let config = velocity_config(&[
        ("command.lin_vel_x", "[0.5, 0.5]"),
        ("command.lin_vel_y", "[0, 0]"),
        ("command.ang_vel_yaw", "[0, 0]"),
        ("command.resampling_time_s", "0.5"),
    ]);
    let (commands, _) = run(&config, 3);
    assert!(
        commands.iter().all(|c| *c == [0.5, 0.0, 0.0]),
        "{commands:?}"
    );
}

#[test]
fn the_vector_env_gives_the_single_envs_rewards() {
    let config = velocity_config(&[("command.resampling_time_s", "0.5")]);
    let model = bundled::hyq();
    let mut vec =
        VecEnv::<RapierBackend>::new(model.clone(), config.clone(), 2, AutoReset::NextStep)
            .unwrap_or_else(|e| panic!("{e}"));
    let len = vec.env(0).observation().len();
    let mut obs = vec![0.0f32; 2 * len];
    vec.reset(Some(5), &mut obs)
        .unwrap_or_else(|e| panic!("{e}"));
    let n = model.num_joints();
    let (mut rewards, mut terminated, mut truncated) =
        (vec![0.0; 2], vec![false; 2], vec![false; 2]);
    let mut got = [Vec::new(), Vec::new()];
    let mut a = vec![0.0; 2 * n];
    for _ in 0..100 {
        for i in 0..2 {
            Stand.act(&vec.env(i).policy_input(), &mut a[i * n..(i + 1) * n]);
        }
        vec.step(
            &a,
            VecStepOut {
                observations: &mut obs,
                rewards: &mut rewards,
                terminated: &mut terminated,
                truncated: &mut truncated,
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
        for i in 0..2 {
            got[i].push(rewards[i].to_bits());
        }
    }
    for (i, seed) in [5, 6].into_iter().enumerate() {
        let (_, single) = run(&config, seed);
        assert_eq!(got[i], single[..100], "env {i}");
    }
}

#[test]
fn the_default_stays_the_spec_task() {
    let c = EnvConfig::default();
    assert_eq!(c.task.kind, TaskKind::Goal);
    assert!(
        !c.to_toml_string().contains("kind"),
        "the default writes no kind"
    );
    let mut env = Env::<RapierBackend>::new(bundled::hyq(), c).unwrap_or_else(|e| panic!("{e}"));
    let r = env
        .reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.observation.len(), 39);
    assert!(r.info.velocity.is_none());
    assert!(env.command().is_none());
    // A velocity configuration reads back through its text.
    let v = velocity_config(&[
        ("velocity.preset", "playground"),
        ("command.lin_vel_x", "[0, 1]"),
    ]);
    let text = v.to_toml_string();
    let back = EnvConfig::from_toml_str(&text, "t").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, v, "{text}");
}

#[test]
fn bad_values_are_one_line_errors_naming_the_key() {
    let cases: &[(&[(&str, &str)], &str)] = &[
        (&[("task.kind", "walk")], "task.kind"),
        (
            &[("task.kind", "velocity"), ("command.lin_vel_x", "[1, -1]")],
            "command.lin_vel_x",
        ),
        (
            &[
                ("task.kind", "velocity"),
                ("command.standing_probability", "2"),
            ],
            "command.standing_probability",
        ),
        (
            &[("task.kind", "velocity"), ("velocity.preset", "isaac")],
            "velocity.preset",
        ),
        (
            &[("task.kind", "velocity"), ("velocity.torques", "nan")],
            "velocity.torques",
        ),
        (&[("command.lin_vel_x", "[0.5, 0.5]")], "task.kind"),
        (
            &[("task.kind", "velocity"), ("command.speed", "1")],
            "speed",
        ),
    ];
    for (pairs, key) in cases {
        let e = EnvConfig::load(None, pairs)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_else(|| panic!("{pairs:?} accepted"));
        assert!(e.contains(key), "{pairs:?}: {e}");
        assert!(!e.contains('\n'), "{e}");
    }
    let text = "[task]\nkind = \"velocity\"\n[command]\nlin_vel_y = [2, 1]\n";
    let e = EnvConfig::from_toml_str(text, "t")
        .err()
        .map(|e| e.to_string());
    let e = e.unwrap_or_else(|| panic!("accepted"));
    assert!(
        e.contains("command.lin_vel_y") && e.contains("line 4"),
        "{e}"
    );
}

#[test]
fn the_info_keys_name_every_term_in_order() {
    let names: Vec<&str> = hyq_env::VELOCITY_INFO_KEYS
        .iter()
        .skip(5)
        .map(|k| k.name.trim_start_matches("velocity."))
        .collect();
    assert_eq!(names, hyq_tasks::TERM_NAMES);
}

#[test]
fn the_info_reward_key_reads_the_reward_step_returns() {
    let config = velocity_config(&[]);
    let model = bundled::hyq();
    let mut env =
        Env::<RapierBackend>::new(model.clone(), config).unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(2), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let key = hyq_env::INFO_KEYS
        .iter()
        .find(|k| k.name == "reward")
        .unwrap_or_else(|| panic!("the info has a reward key"));
    let hyq_env::InfoValue::Float(read) = key.value else {
        panic!("reward is a number")
    };
    let mut a = vec![0.0; model.num_joints()];
    let mut earned = 0;
    for _ in 0..20 {
        Stand.act(&env.policy_input(), &mut a);
        let reward = env.step(&a).unwrap_or_else(|e| panic!("{e}")).reward;
        assert_eq!(read(env.info()).to_bits(), reward.to_bits());
        earned += usize::from(reward != 0.0);
    }
    assert!(earned > 0, "standing steps of the task earn a reward");
}
