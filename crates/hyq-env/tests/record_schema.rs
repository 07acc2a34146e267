//! Invariant: the per-step JSONL record has exactly the keys its schema declares
//! (`RECORD_KEYS`, in that order; `terms.m_height` only when the height penalty is configured),
//! names the env's robot, its numbers read back to the same bits, its reasons use the stable
//! names, and unknown keys are refused when reading; a record written before records named their
//! robot still reads, and writes out to the same bytes; `randomize` (the episode's draws and the
//! step's push) is written only when `[randomize]` is on, last, holding every
//! `RANDOMIZE_INFO_KEYS` value the info reads, and reads back; `regularizers` (the terms that
//! are on) is written only when `[regularizers]` is on, last, holding the info's values of the
//! terms that are on and no other, and reads back.

mod common;

use common::{rapier, reset, scripted, stand_action};
use hyq_env::randomize::RANDOMIZE_PREFIX;
use hyq_env::{InfoValue, RANDOMIZE_INFO_KEYS, RECORD_KEYS, Reason, StepRecord};

#[test]
fn a_record_has_the_schema_keys_and_round_trips_bit_for_bit() {
    let mut env = scripted(&[
        ("task.norm_rew_scaling", "10"),
        ("task.max_time_steps", "2"),
    ]);
    reset(&mut env, 0);
    env.backend_mut().set_script(|w| {
        w.trunk.linvel.x = 0.123456789;
        Ok(())
    });
    let action = [
        0.1,
        -0.2,
        0.3,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0 / 3.0,
    ];
    env.step(&action).unwrap_or_else(|e| panic!("{e}"));
    env.step(&action).unwrap_or_else(|e| panic!("{e}"));
    let record = StepRecord::from_env(&env, &action);
    let line = record.to_json_line();
    assert!(!line.contains('\n'));
    let value: serde_json::Value = serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}"));
    let object = value
        .as_object()
        .unwrap_or_else(|| panic!("not an object: {line}"));
    let mut keys: Vec<&str> = object.keys().map(String::as_str).collect();
    keys.sort_unstable();
    // Every key but the optional ones, which this configuration leaves unset.
    let written = RECORD_KEYS.iter().filter(|k| !k.optional);
    let mut expected: Vec<&str> = written.clone().map(|k| k.name).collect();
    expected.sort_unstable();
    assert_eq!(keys, expected);
    // Written in the schema's order.
    let positions: Vec<usize> = written
        .map(|k| {
            line.find(&format!("\"{}\":", k.name))
                .unwrap_or_else(|| panic!("{} not in {line}", k.name))
        })
        .collect();
    assert!(
        positions.is_sorted(),
        "keys out of the schema's order: {line}"
    );
    let mut terms: Vec<&str> = value["terms"]
        .as_object()
        .map(|o| o.keys().map(String::as_str).collect())
        .unwrap_or_default();
    terms.sort_unstable();
    assert_eq!(
        terms,
        [
            "fall_penalty",
            "joint_penalty",
            "m_pitch",
            "m_yaw",
            "r_b",
            "r_e",
            "r_n",
            "r_reach"
        ]
    );
    assert_eq!(value["obs"].as_array().map(Vec::len), Some(39));
    assert_eq!(value["reasons"], serde_json::json!(["timeout"]));
    assert_eq!(value["truncated"], serde_json::json!(true));
    assert_eq!(value["t"], serde_json::json!(2));
    assert_eq!(value["robot"], serde_json::json!(env.model().name()));
    assert_eq!(value["robot"], serde_json::json!("hyq"));

    let back = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, record);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&back.obs), bits(env.observation()));
    assert_eq!(back.reward.to_bits(), env.info().reward.total.to_bits());
    assert_eq!(
        back.reason_set().iter().collect::<Vec<_>>(),
        [Reason::Timeout]
    );
}

#[test]
fn m_height_is_written_only_when_the_height_penalty_is_configured() {
    let text =
        "[task.height_penalty]\nnominal_height_m = 0.62\ntolerance_m = 0.1\nrate_per_m = 2.0";
    let config = hyq_env::EnvConfig::from_toml_str(text, "t").unwrap_or_else(|e| panic!("{e}"));
    let mut env =
        hyq_env::Env::<hyq_env::testing::ScriptedBackend>::new(hyq_physics::bundled::hyq(), config)
            .unwrap_or_else(|e| panic!("{e}"));
    reset(&mut env, 0);
    env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let line = StepRecord::from_env(&env, &[0.0; 12]).to_json_line();
    assert!(line.contains("\"m_height\":1.0"), "{line}");
}

#[test]
fn reading_refuses_unknown_keys_and_reason_names() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let line = StepRecord::from_env(&env, &[0.0; 12]).to_json_line();
    let extra = line.replacen('{', "{\"extra\":1,", 1);
    assert!(StepRecord::from_json_line(&extra).is_err());
    let bad_reason = line.replace("\"reasons\":[]", "\"reasons\":[\"tripped\"]");
    assert_ne!(bad_reason, line);
    assert!(StepRecord::from_json_line(&bad_reason).is_err());
}

#[test]
fn a_record_without_the_robot_key_reads_and_writes_back_the_same_bytes() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let line = StepRecord::from_env(&env, &[0.0; 12]).to_json_line();
    let old = line.replacen("\"robot\":\"hyq\",", "", 1);
    assert!(old.starts_with("{\"episode\":1,"), "{old}");
    let back = StepRecord::from_json_line(&old).unwrap_or_else(|e| panic!("{e}: {old}"));
    assert_eq!(back.robot, None);
    assert_eq!(back.to_json_line(), old);
    let named = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}: {line}"));
    assert_eq!(named.robot.as_deref(), Some("hyq"));
    assert_eq!(named.to_json_line(), line);
}

#[test]
fn randomize_is_written_only_when_randomize_is_on_and_reads_back() {
    let mut env = scripted(&[
        ("randomize.kp_scale", "[0.8, 1.2]"),
        ("randomize.trunk_added_mass_kg", "[-5, 5]"),
        ("randomize.actuator_delay_substeps", "[1, 3]"),
        ("randomize.push_interval_s", "[0.01, 0.01]"),
        ("randomize.push_velocity_xy_mps", "[0.5, 0.5]"),
    ]);
    reset(&mut env, 0);
    // The first push is due one interval after reset: at the second step's start.
    for _ in 0..2 {
        env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    }
    let info = env.info().randomize.clone().expect("randomize is on");
    assert_eq!(Some(&info.draw), env.episode_draw());
    assert_eq!(info.pushes, 1);
    let line = StepRecord::from_env(&env, &[0.0; 12]).to_json_line();
    let value: serde_json::Value = serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}"));
    // The schema's last key but `velocity` and `regularizers`, written after every other that is
    // set.
    assert_eq!(
        RECORD_KEYS.iter().rev().nth(2).map(|k| k.name),
        Some("randomize")
    );
    assert!(
        line.rfind("\"randomize\":") > line.rfind("\"reasons\":"),
        "{line}"
    );
    let written = value["randomize"]
        .as_object()
        .unwrap_or_else(|| panic!("no randomize object: {line}"));
    assert_eq!(written.len(), RANDOMIZE_INFO_KEYS.len());
    for key in &RANDOMIZE_INFO_KEYS {
        let name = key.name.strip_prefix(RANDOMIZE_PREFIX).unwrap_or(key.name);
        let read = match key.value {
            InfoValue::Float(read) => serde_json::json!(read(env.info())),
            InfoValue::Int(read) => serde_json::json!(read(env.info())),
            InfoValue::Vector(read, _) => serde_json::json!(read(env.info())),
            _ => panic!("{name}: a randomisation key is a number, a count or a vector"),
        };
        assert_eq!(written.get(name), Some(&read), "{name}");
    }
    // Written in the key list's order (the draw's two halves interleave there).
    let tail = &line[line.rfind("\"randomize\":").unwrap_or(0)..];
    let at: Vec<Option<usize>> = RANDOMIZE_INFO_KEYS
        .iter()
        .map(|k| {
            let name = k.name.strip_prefix(RANDOMIZE_PREFIX).unwrap_or(k.name);
            tail.find(&format!("\"{name}\":"))
        })
        .collect();
    assert!(at.iter().all(Option::is_some), "{tail}");
    assert!(at.windows(2).all(|w| w[0] < w[1]), "out of order: {tail}");
    assert_ne!(value["randomize"]["kp_scale"][0], serde_json::json!(1.0));
    let back = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.randomize.as_deref(), Some(&info));
    assert_eq!(back.to_json_line(), line);

    let mut plain = scripted(&[]);
    reset(&mut plain, 0);
    plain.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(plain.info().randomize.is_none());
    assert!(
        !StepRecord::from_env(&plain, &[0.0; 12])
            .to_json_line()
            .contains("randomize")
    );
}

/// With observation noise on, `obs` is the noisy view the policy saw, so a record also holds
/// the true observation (`true_obs`), from which the reward is recomputed: its trunk position
/// is C^t, at `distance_to_goal` from the goal. Without noise no `true_obs` is written.
#[test]
fn with_observation_noise_the_record_keeps_the_true_observation_beside_the_noisy_one() {
    let mut env = common::rapier(&[
        ("randomize.obs_noise.trunk_position", "0.5"),
        ("task.max_time_steps", "20"),
    ]);
    reset(&mut env, 5);
    let position = env.observation_layout().trunk_position();
    let mut largest_noise = 0.0f64;
    for _ in 0..10 {
        env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
        let line = StepRecord::from_env(&env, &[0.0; 12]).to_json_line();
        let record = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}"));
        let truth = record
            .true_obs
            .as_deref()
            .expect("true_obs is written with noise on");
        assert_eq!(truth, env.true_observation());
        assert_eq!(&*record.obs, env.observation());
        let c = &truth[position.clone()];
        let d = (0..3)
            .map(|i| (c[i] - record.goal[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(
            (d - record.distance_to_goal).abs() < 1e-12,
            "{d} vs {}",
            record.distance_to_goal
        );
        let seen = &record.obs[position.clone()];
        largest_noise = (0..3)
            .map(|i| (seen[i] - c[i]).abs())
            .fold(largest_noise, f64::max);
        // Written right after `obs`, in the schema's order.
        assert!(line.find("\"true_obs\":") > line.find("\"obs\":"), "{line}");
        assert!(
            line.find("\"true_obs\":") < line.find("\"action\":"),
            "{line}"
        );
    }
    assert!(
        largest_noise > 0.05,
        "the obs rows are noisy: {largest_noise}"
    );

    let mut plain = common::rapier(&[("randomize.kp_scale", "[0.9, 1.1]")]);
    reset(&mut plain, 5);
    plain.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let line = StepRecord::from_env(&plain, &[0.0; 12]).to_json_line();
    assert!(!line.contains("true_obs"), "{line}");
}

#[test]
fn regularizers_are_written_only_when_on_last_and_read_back() {
    let mut env = scripted(&[
        ("randomize.kp_scale", "[0.8, 1.2]"),
        ("regularizers.action_rate", "-0.01"),
        ("regularizers.base_height", "-2"),
    ]);
    reset(&mut env, 0);
    let action = [0.25; 12];
    env.step(&action).unwrap_or_else(|e| panic!("{e}"));
    let line = StepRecord::from_env(&env, &action).to_json_line();
    assert_eq!(RECORD_KEYS.last().map(|k| k.name), Some("regularizers"));
    assert!(
        line.rfind("\"regularizers\":") > line.rfind("\"randomize\":"),
        "{line}"
    );
    let value: serde_json::Value = serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}"));
    let written = value["regularizers"]
        .as_object()
        .unwrap_or_else(|| panic!("no regularizers object: {line}"));
    let names: Vec<&str> = written.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        ["action_rate", "base_height"],
        "the terms that are on, no other"
    );
    let info = env.info().regularizers.unwrap_or_else(|| panic!("on"));
    let keys: Vec<&str> = hyq_env::regularizer_info_keys(env.info())
        .map(|k| k.name)
        .collect();
    assert_eq!(
        keys,
        [
            "regularizers.reward",
            "regularizers.action_rate",
            "regularizers.base_height"
        ]
    );
    for key in hyq_env::regularizer_info_keys(env.info()).skip(1) {
        let InfoValue::Float(read) = key.value else {
            panic!("{}: a number", key.name)
        };
        let name = key.name.strip_prefix("regularizers.").unwrap_or(key.name);
        assert_eq!(
            written.get(name),
            Some(&serde_json::json!(read(env.info()))),
            "{name}"
        );
    }
    assert_eq!(written["action_rate"], serde_json::json!(12.0 * 0.0625));
    let back = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.regularizers, Some(info.terms));
    assert_eq!(back.to_json_line(), line);
    assert_eq!(back.reward, env.info().reward.total + info.reward);
    assert_ne!(info.reward, 0.0);
    let bad = line.replace("\"base_height\"", "\"stumble\"");
    assert!(
        StepRecord::from_json_line(&bad).is_err(),
        "an unknown term is refused"
    );

    let mut plain = scripted(&[]);
    reset(&mut plain, 0);
    plain.step(&action).unwrap_or_else(|e| panic!("{e}"));
    assert!(plain.info().regularizers.is_none());
    assert!(
        !StepRecord::from_env(&plain, &action)
            .to_json_line()
            .contains("regularizers")
    );
}

#[test]
fn a_velocity_task_record_holds_its_command_terms_reward_and_measured_velocity() {
    // On rapier, standing: the scripted backend's still trunk earns a clipped 0, which the
    // spec's neutral reward would equal.
    let mut env = rapier(&[("task.kind", "velocity")]);
    reset(&mut env, 3);
    let action = stand_action(&env);
    for _ in 0..5 {
        env.step(&action).unwrap_or_else(|e| panic!("{e}"));
    }
    let task = env
        .info()
        .velocity
        .unwrap_or_else(|| panic!("velocity task"));
    assert_ne!(task.reward, 0.0, "a step of the task earns a reward");
    let line = StepRecord::from_env(&env, &action).to_json_line();
    let value: serde_json::Value = serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(value["reward"], serde_json::json!(task.reward), "{line}");
    assert_eq!(value["velocity"]["reward"], serde_json::json!(task.reward));
    assert_eq!(
        value["velocity"]["command"],
        serde_json::json!(task.command)
    );
    let terms = value["velocity"]["terms"]
        .as_object()
        .unwrap_or_else(|| panic!("no terms object: {line}"));
    assert_eq!(terms.len(), hyq_env::velocity::TERM_NAMES.len());
    for (name, v) in hyq_env::velocity::TERM_NAMES
        .iter()
        .zip(task.terms.to_array())
    {
        assert_eq!(terms[*name], serde_json::json!(v), "{name}");
    }
    // What the command was compared with: the trunk's v_x, v_y and ω_z in its frame.
    assert_eq!(
        value["velocity"]["measured"],
        serde_json::json!([task.lin_vel[0], task.lin_vel[1], task.ang_vel[2]])
    );
    assert!(
        task.lin_vel[0] != 0.0 || task.ang_vel[2] != 0.0,
        "the trunk moves a little"
    );
    let back = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.to_json_line(), line);
    assert_eq!(back.reward, task.reward);

    let mut plain = rapier(&[]);
    reset(&mut plain, 3);
    plain.step(&action).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        !StepRecord::from_env(&plain, &action)
            .to_json_line()
            .contains("\"velocity\"")
    );
}
