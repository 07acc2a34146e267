//! Invariant: the per-step JSONL record has exactly the keys its schema declares
//! (`RECORD_KEYS`, in that order; `terms.m_height` only when the height penalty is configured),
//! names the env's robot, its numbers read back to the same bits, its reasons use the stable
//! names, and unknown keys are refused when reading; a record written before records named their
//! robot still reads, and writes out to the same bytes.

mod common;

use common::{reset, scripted};
use hyq_env::{RECORD_KEYS, Reason, StepRecord};

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
