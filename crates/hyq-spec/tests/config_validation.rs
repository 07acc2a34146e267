//! Invariant: the configuration (spec §2) defaults to the §2 table, accepts exactly
//! the documented values, and rejects every other value (negative, NaN, infinite, zero where it
//! must be positive, out of range, unknown key, wrong type) with an error whose message names
//! the field, from the parser (keys and types) or from `TaskConfig::validate` (ranges); a valid
//! configuration survives a TOML round trip unchanged.

use hyq_spec::{ConfigError, EXP_REW_SCALING_MAX, HeightPenalty, REWARD_SCALE_MAX, TaskConfig};
use proptest::prelude::*;

/// A configuration read from TOML and validated, as the environment reads one; the error is the
/// parser's (keys, types) or the range check's, as text.
fn parse(text: &str) -> Result<TaskConfig, String> {
    let config: TaskConfig = toml::from_str(text).map_err(|e| e.to_string())?;
    config.validate().map_err(|e| e.to_string())?;
    Ok(config)
}

/// The §2 table, written out independently of `Default`.
#[test]
fn every_default_is_the_spec_table() {
    let d = TaskConfig::default();
    assert_eq!(d.base_rew_scaling, None, "base_rew_scaling: No impl");
    assert_eq!(d.exp_rew_scaling, Some(5.0), "exp_rew_scaling: 5.0");
    assert_eq!(d.norm_rew_scaling, None, "norm_rew_scaling: No impl");
    assert_eq!(
        d.reach_target_bonus_reward, 0.0,
        "reach_target_bonus_reward: 0.0"
    );
    assert_eq!(d.accepted_error, 0.001, "accepted_error: 0.001 m");
    assert_eq!(
        d.accepted_dist_to_bounds, 0.01,
        "accepted_dist_to_bounds: 0.01 rad"
    );
    assert_eq!(
        d.reach_bounds_penalty, 0.0,
        "reach_bounds_penalty: 0.0 (§2)"
    );
    assert_eq!(d.fall_penalty, 0.0, "fall_penalty: 0.0 (§2)");
    assert_eq!(d.max_time_steps, 1000, "max_time_steps: 1000 (§2)");
    assert_eq!(d.yaw_limit_deg, 2.5, "yaw limit: ±2.5° (§5.1.1)");
    assert_eq!(d.pitch_limit_deg, 2.5, "pitch limit: ±2.5° (§5.1.2)");
    assert_eq!(d.height_penalty, None, "§5.2 is TBD: off");
    assert_eq!(d.validate(), Ok(()));
    assert_eq!(
        parse("").map_err(|e| e.to_string()),
        Ok(d),
        "an empty file is the defaults"
    );
}

#[test]
fn off_unsets_a_scaling_and_numbers_set_it() {
    let c = parse("exp_rew_scaling = \"off\"\nbase_rew_scaling = 2\nnorm_rew_scaling = 10.0");
    let c = c.map_err(|e| e.to_string());
    assert_eq!(
        c,
        Ok(TaskConfig {
            exp_rew_scaling: None,
            base_rew_scaling: Some(2.0),
            norm_rew_scaling: Some(10.0),
            ..TaskConfig::default()
        })
    );
    assert_eq!(
        parse("base_rew_scaling = \"off\"")
            .map(|c| c.base_rew_scaling)
            .ok(),
        Some(None)
    );
    let e = parse("exp_rew_scaling = \"on\"")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        e.contains("exp_rew_scaling") && e.contains("\"off\""),
        "{e}"
    );
}

#[test]
fn json_null_also_unsets_a_scaling() {
    let c: Result<TaskConfig, _> =
        serde_json::from_str(r#"{"exp_rew_scaling": null, "base_rew_scaling": 1}"#);
    let c = c.map_err(|e| e.to_string());
    assert_eq!(
        c,
        Ok(TaskConfig {
            exp_rew_scaling: None,
            base_rew_scaling: Some(1.0),
            ..TaskConfig::default()
        })
    );
    let c: Result<TaskConfig, _> = serde_json::from_str(r#"{"accepted_error": -1.0}"#);
    let message = c
        .map_err(|e| e.to_string())
        .and_then(|c| c.validate().map_err(|e| e.to_string()))
        .err()
        .unwrap_or_default();
    assert!(message.contains("accepted_error = -1"), "{message}");
}

#[test]
fn the_height_penalty_is_a_table_of_three_fields() {
    let text = "[height_penalty]\nnominal_height_m = 0.62\ntolerance_m = 0.1\nrate_per_m = 2.0\n";
    let expected = HeightPenalty {
        nominal_height_m: 0.62,
        tolerance_m: 0.1,
        rate_per_m: 2.0,
    };
    assert_eq!(
        parse(text).map(|c| c.height_penalty).ok(),
        Some(Some(expected))
    );
    for (text, field) in [
        (
            "[height_penalty]\nnominal_height_m = 0.62\ntolerance_m = 0.1\n",
            "rate_per_m",
        ),
        (
            "[height_penalty]\nnominal_height_m = 0.62\ntolerance_m = 0.1\nrate_per_m = 2.0\nrate = 1\n",
            "rate",
        ),
        (
            "[height_penalty]\nnominal_height_m = nan\ntolerance_m = 0.1\nrate_per_m = 2.0\n",
            "height_penalty.nominal_height_m",
        ),
        (
            "[height_penalty]\nnominal_height_m = 0.6\ntolerance_m = -0.1\nrate_per_m = 2.0\n",
            "height_penalty.tolerance_m",
        ),
        (
            "[height_penalty]\nnominal_height_m = 0.6\ntolerance_m = 0.1\nrate_per_m = 0.0\n",
            "height_penalty.rate_per_m",
        ),
    ] {
        let message = parse(text).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            message.contains(field),
            "{text:?}: error {message:?} does not name {field}"
        );
    }
}

#[test]
fn unknown_keys_are_rejected_by_name() {
    for key in [
        "acepted_error",
        "exp_rew_scale",
        "sim_steps_per_env_step",
        "k_exp",
    ] {
        let message = parse(&format!("{key} = 1.0"))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            message.contains(key) && message.contains("unknown field"),
            "{key}: {message:?}"
        );
    }
}

/// Every real-valued field and what it accepts: "scaling" (> 0, at most `REWARD_SCALE_MAX`),
/// "k_exp" (> 0, at most `EXP_REW_SCALING_MAX`), "amount" (≥ 0, at most `REWARD_SCALE_MAX`),
/// "positive" (> 0), "non-negative" (≥ 0) or "angle" ([0, 180]).
const REAL_FIELDS: [(&str, &str); 10] = [
    ("base_rew_scaling", "scaling"),
    ("exp_rew_scaling", "k_exp"),
    ("norm_rew_scaling", "scaling"),
    ("reach_target_bonus_reward", "amount"),
    ("accepted_error", "positive"),
    ("accepted_dist_to_bounds", "non-negative"),
    ("reach_bounds_penalty", "amount"),
    ("fall_penalty", "amount"),
    ("yaw_limit_deg", "angle"),
    ("pitch_limit_deg", "angle"),
];

/// Sets the real field `name` of a default configuration to `value`.
fn with_field(name: &str, value: f64) -> TaskConfig {
    let mut c = TaskConfig::default();
    match name {
        "base_rew_scaling" => c.base_rew_scaling = Some(value),
        "exp_rew_scaling" => c.exp_rew_scaling = Some(value),
        "norm_rew_scaling" => c.norm_rew_scaling = Some(value),
        "reach_target_bonus_reward" => c.reach_target_bonus_reward = value,
        "accepted_error" => c.accepted_error = value,
        "accepted_dist_to_bounds" => c.accepted_dist_to_bounds = value,
        "reach_bounds_penalty" => c.reach_bounds_penalty = value,
        "fall_penalty" => c.fall_penalty = value,
        "yaw_limit_deg" => c.yaw_limit_deg = value,
        "pitch_limit_deg" => c.pitch_limit_deg = value,
        other => panic!("no real field {other}"),
    }
    c
}

fn is_valid(kind: &str, value: f64) -> bool {
    match kind {
        "scaling" => value.is_finite() && value > 0.0 && value <= REWARD_SCALE_MAX,
        "k_exp" => value.is_finite() && value > 0.0 && value <= EXP_REW_SCALING_MAX,
        "amount" => (0.0..=REWARD_SCALE_MAX).contains(&value),
        "positive" => value.is_finite() && value > 0.0,
        "non-negative" => value.is_finite() && value >= 0.0,
        _ => (0.0..=180.0).contains(&value),
    }
}

/// TOML spelling of a float, NaN and infinities included.
fn toml_float(value: f64) -> String {
    if value.is_nan() {
        "nan".into()
    } else if value.is_infinite() {
        if value > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        }
    } else {
        format!("{value:?}")
    }
}

/// A value aimed at the edges of the accepted ranges.
fn edge_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(f64::MIN_POSITIVE),
        Just(-f64::MIN_POSITIVE),
        Just(180.0),
        Just(180.0f64.next_up()),
        Just(EXP_REW_SCALING_MAX),
        Just(EXP_REW_SCALING_MAX.next_up()),
        Just(REWARD_SCALE_MAX),
        Just(REWARD_SCALE_MAX.next_up()),
        -1e3f64..1e3,
        -1e-6f64..1e-6,
    ]
}

/// A field is accepted exactly when its value is valid; when it is not, both the in-code check
/// and the TOML parser reject it with a message naming the field and the value.
fn check_field(name: &str, kind: &str, value: f64) {
    let config = with_field(name, value);
    let parsed = parse(&format!("{name} = {}", toml_float(value)));
    if is_valid(kind, value) {
        assert_eq!(config.validate(), Ok(()), "{name} = {value} is valid");
        assert_eq!(parsed.map_err(|e| e.to_string()), Ok(config));
    } else {
        match config.validate() {
            Err(ConfigError::Real {
                field, value: v, ..
            }) => {
                assert_eq!(field, name);
                assert!(v.to_bits() == value.to_bits());
            }
            other => panic!("{name} = {value}: {other:?}"),
        }
        let message = parsed.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(message.contains(name), "{name} = {value}: {message:?}");
        assert!(
            message.contains(&format!("{value}")),
            "{name} = {value}: {message:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    #[test]
    fn each_real_field_accepts_exactly_its_range(field in 0..REAL_FIELDS.len(), value in edge_value()) {
        let (name, kind) = REAL_FIELDS[field];
        check_field(name, kind, value);
    }

    #[test]
    fn valid_configurations_survive_a_toml_round_trip(
        scalings in (
            prop::option::of(1e-3f64..1e3),
            prop::option::of(1e-3f64..=EXP_REW_SCALING_MAX),
            prop::option::of(1e-3f64..1e3),
        ),
        amounts in (0.0f64..1e3, 1e-6f64..1.0, 0.0f64..0.5, 0.0f64..1e3, 0.0f64..1e3),
        max_time_steps in 1u64..1_000_000,
        limits in (0.0f64..=180.0, 0.0f64..=180.0),
        height in prop::option::of((0.0f64..2.0, 0.0f64..0.5, 1e-3f64..10.0)),
    ) {
        let config = TaskConfig {
            base_rew_scaling: scalings.0,
            exp_rew_scaling: scalings.1,
            norm_rew_scaling: scalings.2,
            reach_target_bonus_reward: amounts.0,
            accepted_error: amounts.1,
            accepted_dist_to_bounds: amounts.2,
            reach_bounds_penalty: amounts.3,
            fall_penalty: amounts.4,
            max_time_steps,
            yaw_limit_deg: limits.0,
            pitch_limit_deg: limits.1,
            height_penalty: height.map(|(z, tol, rate)| HeightPenalty {
                nominal_height_m: z,
                tolerance_m: tol,
                rate_per_m: rate,
            }),
        };
        let text = toml::to_string(&config).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let back = parse(&text).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(back, config, "{}", text);
    }
}

#[test]
fn max_time_steps_must_be_a_positive_integer() {
    let zero = TaskConfig {
        max_time_steps: 0,
        ..TaskConfig::default()
    };
    let e = zero.validate();
    assert!(
        matches!(
            e,
            Err(ConfigError::Integer {
                field: "max_time_steps",
                value: 0,
                ..
            })
        ),
        "{e:?}"
    );
    for text in [
        "max_time_steps = 0",
        "max_time_steps = -1",
        "max_time_steps = 1.5",
        "max_time_steps = \"10\"",
    ] {
        let message = parse(text).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(message.contains("max_time_steps"), "{text}: {message:?}");
    }
    assert_eq!(
        parse("max_time_steps = 1").map(|c| c.max_time_steps).ok(),
        Some(1)
    );
}

#[test]
fn wrong_types_are_rejected_by_name() {
    for (name, value) in [
        ("accepted_error", "\"0.001\""),
        ("fall_penalty", "true"),
        ("yaw_limit_deg", "[2.5]"),
        ("base_rew_scaling", "true"),
        ("height_penalty", "1.0"),
    ] {
        let text = format!("{name} = {value}");
        let message = parse(&text)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(message.contains(name), "{text}: {message:?}");
    }
}

#[test]
fn the_error_message_names_the_field_the_value_and_the_range() {
    let e = with_field("accepted_error", -0.5)
        .validate()
        .err()
        .map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("invalid accepted_error = -0.5: must be finite and > 0")
    );
    let e = with_field("yaw_limit_deg", f64::NAN)
        .validate()
        .err()
        .map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("invalid yaw_limit_deg = NaN: must be finite and in [0, 180] degrees")
    );
}
