//! Invariant: a `hyq-mlp-policy` file is either read whole and checked, or refused with one
//! line naming the file and what is wrong (a missing file, another format, a layout that does
//! not match the robot or the action mode, a non-finite number); a policy that was read
//! computes the documented forward pass (VecNormalize's clipped standardisation, the
//! activation, a linear head, clipping to the action space), gives the same bits for the same
//! observation on every call, and allocates nothing per action.

mod common;

use std::collections::HashMap;

use common::{reset, scripted};
use hyq_env::{MlpPolicy, Policy};
use safetensors::tensor::TensorView;
use safetensors::{Dtype, serialize};

const N_OBS: usize = 39;
const N_ACT: usize = 12;
const HIDDEN: usize = 4;

fn hyq_rows() -> Vec<String> {
    hyq_env::observation_layout_of(&hyq_physics::bundled::hyq())
        .unwrap_or_else(|e| panic!("{e}"))
        .rows()
        .iter()
        .map(|r| r.name.to_string())
        .collect()
}

fn hyq_joints() -> Vec<String> {
    hyq_physics::bundled::hyq()
        .joints()
        .iter()
        .map(|j| j.name.clone())
        .collect()
}

/// A small policy file: 39 → 4 (tanh) → 12, with the given metadata changes (an empty value
/// removes the key) and weights.
struct FileSpec {
    meta: Vec<(&'static str, String)>,
    w0: Vec<f32>,
    w1: Vec<f32>,
    mean: Vec<f64>,
    var: Vec<f64>,
}

impl Default for FileSpec {
    fn default() -> Self {
        Self {
            meta: vec![],
            w0: (0..HIDDEN * N_OBS)
                .map(|i| ((i % 7) as f32 - 3.0) * 0.05)
                .collect(),
            w1: (0..N_ACT * HIDDEN)
                .map(|i| ((i % 5) as f32 - 2.0) * 0.4)
                .collect(),
            mean: (0..N_OBS).map(|i| 0.01 * i as f64).collect(),
            var: (0..N_OBS).map(|i| 0.5 + 0.1 * i as f64).collect(),
        }
    }
}

fn bytes_of_f32(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn bytes_of_f64(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

impl FileSpec {
    fn bytes(&self) -> Vec<u8> {
        let mut meta: HashMap<String, String> = [
            ("format", "hyq-mlp-policy".to_owned()),
            ("format_version", "1".to_owned()),
            ("robot", "hyq".to_owned()),
            (
                "observation",
                serde_json::to_string(&hyq_rows()).unwrap_or_default(),
            ),
            (
                "action",
                serde_json::to_string(&hyq_joints()).unwrap_or_default(),
            ),
            ("action_mode", "offset".to_owned()),
            ("action_scale_rad", "0.5".to_owned()),
            ("activation", "tanh".to_owned()),
            ("obs_clip", "10.0".to_owned()),
            ("obs_epsilon", "1e-08".to_owned()),
            (
                "env_config",
                r#"{"action.mode": "\"offset\"", "task.fall_penalty": "5.0"}"#.to_owned(),
            ),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_owned(), v))
        .collect();
        for (k, v) in &self.meta {
            if v.is_empty() {
                meta.remove(*k);
            } else {
                meta.insert((*k).to_owned(), v.clone());
            }
        }
        let data = [
            (
                "obs_mean",
                Dtype::F64,
                vec![self.mean.len()],
                bytes_of_f64(&self.mean),
            ),
            (
                "obs_var",
                Dtype::F64,
                vec![self.var.len()],
                bytes_of_f64(&self.var),
            ),
            (
                "layers.0.weight",
                Dtype::F32,
                vec![HIDDEN, self.w0.len() / HIDDEN],
                bytes_of_f32(&self.w0),
            ),
            (
                "layers.0.bias",
                Dtype::F32,
                vec![HIDDEN],
                bytes_of_f32(&[0.1, -0.2, 0.3, 0.0]),
            ),
            (
                "layers.1.weight",
                Dtype::F32,
                vec![self.w1.len() / HIDDEN, HIDDEN],
                bytes_of_f32(&self.w1),
            ),
            (
                "layers.1.bias",
                Dtype::F32,
                vec![self.w1.len() / HIDDEN],
                bytes_of_f32(&vec![0.05; self.w1.len() / HIDDEN]),
            ),
        ];
        let views: Vec<(String, TensorView<'_>)> = data
            .iter()
            .map(|(name, dtype, shape, bytes)| {
                let view = TensorView::new(*dtype, shape.clone(), bytes)
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                ((*name).to_owned(), view)
            })
            .collect();
        serialize(views, Some(meta)).unwrap_or_else(|e| panic!("{e}"))
    }

    fn load(&self) -> Result<MlpPolicy, hyq_env::MlpError> {
        MlpPolicy::from_bytes(&self.bytes(), "test.safetensors")
    }
}

fn loaded(spec: &FileSpec) -> MlpPolicy {
    spec.load().unwrap_or_else(|e| panic!("{e}"))
}

/// The forward pass written out from the module docs, for one observation.
fn reference(spec: &FileSpec, obs: &[f64]) -> Vec<f64> {
    let x: Vec<f64> = obs
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let z = (f64::from(*o as f32) - spec.mean[i]) / (spec.var[i] + 1e-8).sqrt();
            f64::from(z.clamp(-10.0, 10.0) as f32)
        })
        .collect();
    let b0 = [0.1f32, -0.2, 0.3, 0.0];
    let h: Vec<f64> = (0..HIDDEN)
        .map(|j| {
            let s: f64 = (0..N_OBS)
                .map(|i| f64::from(spec.w0[j * N_OBS + i]) * x[i])
                .sum();
            (s + f64::from(b0[j])).tanh()
        })
        .collect();
    (0..N_ACT)
        .map(|k| {
            let s: f64 = (0..HIDDEN)
                .map(|j| f64::from(spec.w1[k * HIDDEN + j]) * h[j])
                .sum();
            (s + f64::from(0.05f32)).clamp(-1.0, 1.0)
        })
        .collect()
}

#[test]
fn the_forward_pass_is_the_documented_formula_and_repeats_to_the_bit() {
    let spec = FileSpec::default();
    let mut policy = loaded(&spec);
    assert_eq!(policy.widths(), vec![N_OBS, HIDDEN, N_ACT]);
    let mut env = scripted(&[("action.mode", "offset")]);
    reset(&mut env, 0);
    policy
        .check_env(env.model(), env.config(), "test.safetensors")
        .unwrap_or_else(|e| panic!("{e}"));
    let mut first = Vec::new();
    for step in 0..20 {
        let mut action = vec![0.0; N_ACT];
        policy.act(&env.policy_input(), &mut action);
        let want = reference(&spec, env.observation());
        for (got, want) in action.iter().zip(&want) {
            assert!((got - want).abs() < 1e-12, "step {step}: {got} vs {want}");
        }
        let mut again = vec![0.0; N_ACT];
        policy.act(&env.policy_input(), &mut again);
        assert_eq!(
            action.iter().map(|a| a.to_bits()).collect::<Vec<_>>(),
            again.iter().map(|a| a.to_bits()).collect::<Vec<_>>()
        );
        if step == 0 {
            first = action.clone();
        }
        let s = env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        if s.terminated || s.truncated {
            reset(&mut env, step + 1);
        }
    }
    // A fresh copy of the file gives the first action again, to the bit.
    let mut fresh = loaded(&spec);
    let mut env = scripted(&[("action.mode", "offset")]);
    reset(&mut env, 0);
    let mut action = vec![0.0; N_ACT];
    fresh.act(&env.policy_input(), &mut action);
    assert_eq!(action, first);
    // Some outputs are inside the space and some clipped, so both paths are exercised.
    assert!(first.iter().any(|a| a.abs() < 1.0), "{first:?}");
}

#[test]
fn the_metadata_carries_the_training_environment() {
    let policy = loaded(&FileSpec::default());
    let m = policy.metadata();
    assert_eq!(m.robot, "hyq");
    assert_eq!(m.action_scale_rad, Some(0.5));
    assert_eq!(
        m.env_config,
        vec![
            ("action.mode".to_owned(), "\"offset\"".to_owned()),
            ("task.fall_penalty".to_owned(), "5.0".to_owned()),
        ]
    );
}

#[test]
fn acting_allocates_nothing() {
    let mut policy = loaded(&FileSpec::default());
    let mut env = scripted(&[("action.mode", "offset")]);
    reset(&mut env, 0);
    let mut action = vec![0.0; N_ACT];
    let info = allocation_counter::measure(|| {
        for _ in 0..100 {
            policy.act(&env.policy_input(), &mut action);
        }
    });
    assert_eq!(info.count_total, 0);
}

fn refused(spec: &FileSpec, needles: &[&str]) {
    let e = match spec.load() {
        Err(e) => e.to_string(),
        Ok(_) => panic!("expected {needles:?} to be refused"),
    };
    assert!(e.starts_with("test.safetensors: "), "{e}");
    assert!(!e.contains('\n'), "one line: {e:?}");
    for n in needles {
        assert!(e.contains(n), "{e:?} should contain {n:?}");
    }
}

#[test]
fn a_missing_file_or_another_format_is_refused_naming_the_file() {
    let missing = std::env::temp_dir().join("hyq-no-such-policy.safetensors");
    let e = MlpPolicy::from_file(&missing)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        e.contains("hyq-no-such-policy.safetensors") && e.contains("cannot read"),
        "{e}"
    );
    for (bytes, needle) in [
        (b"".as_slice(), "not a safetensors policy file"),
        (
            b"\x89PNG\r\n\x1a\n0000000000".as_slice(),
            "not a safetensors policy file",
        ),
        (
            br#"{"format": "hyq-mlp-policy"}"#.as_slice(),
            "not a safetensors policy file",
        ),
    ] {
        let e = MlpPolicy::from_bytes(bytes, "x.safetensors")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.starts_with("x.safetensors: ") && e.contains(needle),
            "{e}"
        );
        assert!(!e.contains('\n'), "{e:?}");
    }
    // A valid safetensors file of another kind (no `format`, or another one).
    refused(
        &FileSpec {
            meta: vec![("format", String::new())],
            ..FileSpec::default()
        },
        &["no `format`"],
    );
    refused(
        &FileSpec {
            meta: vec![("format", "gguf".into())],
            ..FileSpec::default()
        },
        &["\"gguf\"", "hyq-mlp-policy"],
    );
    refused(
        &FileSpec {
            meta: vec![("format_version", "2".into())],
            ..FileSpec::default()
        },
        &["version \"2\""],
    );
}

#[test]
fn non_finite_or_misshapen_numbers_are_refused_by_tensor() {
    let mut w0 = FileSpec::default().w0;
    w0[17] = f32::NAN;
    refused(
        &FileSpec {
            w0,
            ..FileSpec::default()
        },
        &["layers.0.weight", "non-finite", "17"],
    );
    let mut var = FileSpec::default().var;
    var[3] = f64::INFINITY;
    refused(
        &FileSpec {
            var,
            ..FileSpec::default()
        },
        &["obs_var", "non-finite"],
    );
    refused(
        &FileSpec {
            mean: vec![0.0; 38],
            ..FileSpec::default()
        },
        &["obs_mean", "[38]", "[39]"],
    );
    refused(
        &FileSpec {
            w0: vec![0.1; HIDDEN * 40],
            ..FileSpec::default()
        },
        &["layers.0.weight", "[4, 40]", "[_, 39]"],
    );
    refused(
        &FileSpec {
            w1: vec![0.1; 8 * HIDDEN],
            ..FileSpec::default()
        },
        &["8 outputs", "12"],
    );
    refused(
        &FileSpec {
            meta: vec![("activation", "softsign".into())],
            ..FileSpec::default()
        },
        &["softsign"],
    );
}

#[test]
fn an_environment_of_another_robot_or_action_layout_is_refused() {
    let policy = loaded(&FileSpec::default());
    let check = |overrides: &[(&str, &str)]| {
        let env = scripted(overrides);
        policy
            .check_env(env.model(), env.config(), "walk.safetensors")
            .err()
            .map(|e| e.to_string())
    };
    assert_eq!(check(&[("action.mode", "offset")]), None);
    let e = check(&[]).unwrap_or_default();
    assert!(
        e.starts_with("walk.safetensors: ")
            && e.contains("\"offset\"")
            && e.contains("\"normalized\""),
        "{e}"
    );
    let e =
        check(&[("action.mode", "offset"), ("action.max_offset_rad", "0.3")]).unwrap_or_default();
    assert!(
        e.contains("action.max_offset_rad") && e.contains("0.3"),
        "{e}"
    );

    // Another robot: ANYmal C's profile names its own robot and joints.
    let anymal = hyq_physics::bundled::anymal_c();
    let env_config = hyq_env::EnvConfig::default();
    let e = policy
        .check_env(&anymal, &env_config, "walk.safetensors")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(e.contains("\"hyq\"") && e.contains("anymal"), "{e}");

    // The right robot's name with another joint order.
    let mut joints = hyq_joints();
    joints.swap(0, 3);
    let policy = loaded(&FileSpec {
        meta: vec![("action", serde_json::to_string(&joints).unwrap_or_default())],
        ..FileSpec::default()
    });
    let env = scripted(&[("action.mode", "offset")]);
    let e = policy
        .check_env(env.model(), env.config(), "walk.safetensors")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(e.contains("action value 0") && e.contains("lh_haa"), "{e}");
}

/// A policy trained with `observation.extra` lists those rows after the spec's: it runs in an
/// environment with the same rows, and is refused, naming the observation, by one without them
/// (and the spec's file by one with them).
#[test]
fn a_policy_file_names_the_extra_rows_it_was_trained_with() {
    let n_obs = N_OBS + 3;
    let mut rows = hyq_rows();
    rows.extend(["goal_vector_x", "goal_vector_y", "goal_vector_z"].map(String::from));
    let extended = FileSpec {
        meta: vec![(
            "observation",
            serde_json::to_string(&rows).unwrap_or_default(),
        )],
        w0: (0..HIDDEN * n_obs)
            .map(|i| ((i % 7) as f32 - 3.0) * 0.05)
            .collect(),
        mean: vec![0.0; n_obs],
        var: vec![1.0; n_obs],
        ..FileSpec::default()
    };
    let with_goal = common::config(&[
        ("action.mode", "\"offset\""),
        ("observation.extra", r#"["goal_vector"]"#),
    ]);
    let without = common::config(&[("action.mode", "\"offset\"")]);
    let model = hyq_physics::bundled::hyq();
    let mut policy = loaded(&extended);
    assert_eq!(policy.widths(), vec![n_obs, HIDDEN, N_ACT]);
    policy
        .check_env(&model, &with_goal, "test.safetensors")
        .unwrap_or_else(|e| panic!("{e}"));
    let mut env = common::env::<hyq_env::testing::ScriptedBackend>(&[
        ("action.mode", "\"offset\""),
        ("observation.extra", r#"["goal_vector"]"#),
    ]);
    reset(&mut env, 0);
    let mut action = vec![0.0; N_ACT];
    policy.act(&env.policy_input(), &mut action);
    assert!(action.iter().all(|a| a.is_finite()));
    for (file, config) in [(&extended, &without), (&FileSpec::default(), &with_goal)] {
        let e = loaded(file)
            .check_env(&model, config, "test.safetensors")
            .map(|()| String::new())
            .unwrap_or_else(|e| e.to_string());
        assert!(e.contains("observation"), "{e:?}");
        assert!(!e.contains('\n'), "{e:?}");
    }
}

/// A policy that reads the height scan runs only on the scan it was trained on: another
/// extent or spacing with the same row count and names reads the ground at other points, and
/// was accepted (the committed rough-ground policy then fell at a joint limit).
#[test]
fn a_height_scan_policy_refuses_a_scan_of_another_geometry() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/policies/hyq_walk_rough.safetensors");
    let policy = MlpPolicy::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let model = hyq_physics::bundled::hyq();
    let mut base: Vec<(&str, &str)> = policy
        .metadata()
        .env_config
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    base.push(("terrain.kind", "\"rough\""));
    policy
        .check_env(&model, &common::config(&base), "rough.safetensors")
        .unwrap_or_else(|e| panic!("its own scan: {e}"));
    for (key, value) in [
        // 17 × 11 points either way: same rows, other points.
        ("observation.height_scan_x_m", "[-0.6, 1.0]"),
        ("observation.height_scan_y_m", "[-0.4, 0.6]"),
    ] {
        let mut pairs = base.clone();
        pairs.push((key, value));
        let e = policy
            .check_env(&model, &common::config(&pairs), "rough.safetensors")
            .map(|()| String::new())
            .unwrap_or_else(|e| e.to_string());
        assert!(
            e.contains(key) && e.contains("trained with") && !e.contains('\n'),
            "{key} = {value}: {e:?}"
        );
    }
    // The same row count from a wider extent at a coarser spacing (17 × 11 again).
    let mut pairs = base.clone();
    pairs.extend([
        ("observation.height_scan_x_m", "[-1.6, 1.6]"),
        ("observation.height_scan_y_m", "[-1.0, 1.0]"),
        ("observation.height_scan_spacing_m", "0.2"),
    ]);
    let e = policy
        .check_env(&model, &common::config(&pairs), "rough.safetensors")
        .map(|()| String::new())
        .unwrap_or_else(|e| e.to_string());
    assert!(e.contains("observation.height_scan_"), "{e:?}");
}
