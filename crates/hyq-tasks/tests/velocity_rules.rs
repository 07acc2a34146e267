//! The velocity task's rules: seeded draws are deterministic and stay in their ranges, a fixed
//! range gives its value exactly, the keep/zero rule keeps, redraws or zeroes, a perfect
//! follower earns the tracking maximum, and every output is finite for finite inputs.

use hyq_tasks::command::{
    CommandConfig, ResamplingRule, ResamplingTiming, initial_command, keep_zero, resample,
    steps_until_resample,
};
use hyq_tasks::scales::{Preset, TermScales, VelocityConfig};
use hyq_tasks::step::{AirTime, VelocitySnapshot, evaluate, total};
use hyq_tasks::terms;
use hyq_tasks::{Command, TERM_NAMES, TermValues};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

fn range() -> impl Strategy<Value = [f64; 2]> {
    (-10.0..=10.0f64, -10.0..=10.0f64).prop_map(|(a, b)| [a.min(b), a.max(b)])
}

fn config() -> impl Strategy<Value = CommandConfig> {
    (
        (range(), range(), range()),
        0.01..100.0f64,
        prop_oneof![
            Just(ResamplingRule::Uniform),
            Just(ResamplingRule::KeepZero)
        ],
        prop_oneof![
            Just(ResamplingTiming::Fixed),
            Just(ResamplingTiming::Exponential)
        ],
        0.0..=1.0f64,
        0.0..=1.0f64,
        [0.0..=1.0f64, 0.0..=1.0f64, 0.0..=1.0f64],
    )
        .prop_map(|((x, y, w), t, rule, timing, p, min, b)| CommandConfig {
            lin_vel_x: x,
            lin_vel_y: y,
            ang_vel_yaw: w,
            resampling_time_s: t,
            resampling: rule,
            timing,
            standing_probability: p,
            min_lin_vel_mps: min,
            keep_nonzero_probability: b,
        })
}

/// Each component within its range, or 0 (a standing, zeroed or keep/zero draw).
fn in_range_or_zero(c: &Command, config: &CommandConfig) -> bool {
    c.as_array()
        .iter()
        .zip(config.ranges())
        .all(|(v, [lo, hi])| *v == 0.0 || (lo..=hi).contains(v))
}

proptest! {
    #[test]
    fn draws_are_seeded_in_range_and_finite(config in config(), seed in any::<u64>()) {
        prop_assert!(config.validate().is_ok());
        let (mut a, mut b) = (rng(seed), rng(seed));
        let mut c = initial_command(&config, &mut a);
        prop_assert_eq!(c, initial_command(&config, &mut b));
        prop_assert!(in_range_or_zero(&c, &config));
        for _ in 0..20 {
            let next = resample(&config, c, &mut a);
            prop_assert_eq!(next, resample(&config, c, &mut b));
            prop_assert!(in_range_or_zero(&next, &config), "{next:?} outside {config:?}");
            let n = steps_until_resample(&config, 0.01, &mut a);
            prop_assert_eq!(n, steps_until_resample(&config, 0.01, &mut b));
            prop_assert!(n >= 1);
            c = next;
        }
    }

    #[test]
    fn a_fixed_range_gives_its_value_exactly(v in -10.0..=10.0f64, seed in any::<u64>()) {
        let config = CommandConfig {
            lin_vel_x: [v, v],
            lin_vel_y: [0.0, 0.0],
            ang_vel_yaw: [-v, -v],
            ..CommandConfig::default()
        };
        let mut r = rng(seed);
        let c = initial_command(&config, &mut r);
        prop_assert_eq!(c.as_array(), [v, 0.0, -v]);
        prop_assert_eq!(resample(&config, c, &mut r).as_array(), [v, 0.0, -v]);
    }

    #[test]
    fn tracking_is_at_most_one_and_one_only_when_followed(
        c in [-10.0..10.0f64, -10.0..10.0, -10.0..10.0],
        e in [-1.0..1.0f64, -1.0..1.0, -1.0..1.0],
        sigma in 0.01..10.0f64,
    ) {
        let lin = terms::tracking_lin_vel([c[0], c[1]], [c[0] + e[0], c[1] + e[1]], sigma);
        let ang = terms::tracking_ang_vel(c[2], c[2] + e[2], sigma);
        prop_assert!((0.0..=1.0).contains(&lin) && (0.0..=1.0).contains(&ang));
        prop_assert_eq!(terms::tracking_lin_vel([c[0], c[1]], [c[0], c[1]], sigma), 1.0);
        prop_assert_eq!(terms::tracking_ang_vel(c[2], c[2], sigma), 1.0);
        if e[0] != 0.0 || e[1] != 0.0 {
            prop_assert!(lin < 1.0 || (e[0] * e[0] + e[1] * e[1]) / sigma < 1e-15);
        }
    }

    #[test]
    fn every_output_is_finite_for_finite_inputs(
        v in [-50.0..50.0f64, -50.0..50.0, -50.0..50.0],
        w in [-50.0..50.0f64, -50.0..50.0, -50.0..50.0],
        q in prop::collection::vec(-10.0..10.0f64, 12),
        qd in prop::collection::vec(-100.0..100.0f64, 12),
        tau in prop::collection::vec(-1000.0..1000.0f64, 12),
        a in prop::collection::vec(-10.0..10.0f64, 12),
        contacts in [any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>()],
        foot_v in [-10.0..10.0f64, -10.0..10.0],
        c in [-10.0..10.0f64, -10.0..10.0, -10.0..10.0],
        playground in any::<bool>(),
    ) {
        let preset = if playground { Preset::Playground } else { Preset::LeggedGym };
        let scales = preset.scales();
        let zeros = vec![0.0; 12];
        let soft = vec![terms::soft_limits(-1.0, 1.0, scales.soft_joint_limit_factor); 12];
        let mut air = AirTime::new(4);
        for _ in 0..3 {
            air.update(&[false; 4], 0.01);
        }
        let touchdown = air.update(&contacts, 0.01).to_vec();
        let g = [w[0] / 50.0, w[1] / 50.0, -0.5];
        let s = VelocitySnapshot {
            command: Command { lin_vel_x: c[0], lin_vel_y: c[1], ang_vel_yaw: c[2] },
            lin_vel: v,
            ang_vel: w,
            gravity: g,
            joint_angles: &q,
            joint_speeds: &qd,
            previous_joint_speeds: &zeros,
            standing: &zeros,
            soft_limits: &soft,
            torques: &tau,
            action: &a,
            previous_action: &zeros,
            foot_contacts: &contacts,
            foot_velocity_xy: &[foot_v; 4],
            air_at_touchdown: &touchdown,
            trunk_contact: false,
            trunk_contact_ends: false,
            env_dt: 0.01,
        };
        let out = evaluate(&scales, &s);
        prop_assert!(out.total.is_finite() && out.total >= 0.0);
        prop_assert!(out.terms.to_array().iter().all(|t| t.is_finite()));
        prop_assert!(!out.terminated);
        prop_assert_eq!(out.terms.to_array().len(), TERM_NAMES.len());
    }

    #[test]
    fn keep_zero_keeps_redraws_or_zeroes(x in -5.0..5.0f64, y in -5.0..5.0f64) {
        prop_assert_eq!(keep_zero(x, y, true, false), x);
        prop_assert_eq!(keep_zero(x, y, true, true), x);
        prop_assert_eq!(keep_zero(x, y, false, true), y);
        prop_assert_eq!(keep_zero(x, y, false, false), 0.0);
    }
}

#[test]
fn standing_probability_one_always_stands_and_zero_never_does() {
    let stand = CommandConfig {
        standing_probability: 1.0,
        lin_vel_x: [0.5, 1.0],
        ..CommandConfig::default()
    };
    let move_ = CommandConfig {
        lin_vel_x: [0.5, 1.0],
        ..CommandConfig::default()
    };
    let (mut r, mut s) = (rng(3), rng(3));
    for _ in 0..100 {
        assert_eq!(initial_command(&stand, &mut r), Command::ZERO);
        assert!(initial_command(&move_, &mut s).lin_vel_x >= 0.5);
    }
}

#[test]
fn standing_share_follows_its_probability() {
    let config = CommandConfig {
        standing_probability: 0.25,
        lin_vel_x: [0.5, 1.0],
        ..CommandConfig::default()
    };
    let mut r = rng(11);
    let n = 4000;
    let standing = (0..n)
        .filter(|_| initial_command(&config, &mut r) == Command::ZERO)
        .count();
    let share = standing as f64 / f64::from(n);
    // Binomial(4000, 0.25): standard deviation 0.0068; 5 of them.
    assert!((share - 0.25).abs() < 0.035, "standing share {share}");
}

#[test]
fn fixed_timing_redraws_every_resampling_time() {
    let config = CommandConfig {
        resampling_time_s: 4.0,
        ..CommandConfig::default()
    };
    assert_eq!(steps_until_resample(&config, 0.02, &mut rng(0)), 200);
    let exp = CommandConfig {
        timing: ResamplingTiming::Exponential,
        ..config
    };
    let mut r = rng(5);
    let mean = (0..4000)
        .map(|_| steps_until_resample(&exp, 0.02, &mut r) as f64)
        .sum::<f64>()
        / 4000.0;
    // Exponential with mean 200 steps: standard error 200/√4000 ≈ 3.2.
    assert!((mean - 200.0).abs() < 16.0, "mean {mean}");
}

#[test]
fn small_commands_are_zeroed_under_uniform_only() {
    let config = CommandConfig {
        lin_vel_x: [0.1, 0.1],
        lin_vel_y: [0.0, 0.0],
        min_lin_vel_mps: 0.2,
        ..CommandConfig::default()
    };
    let c = initial_command(&config, &mut rng(1));
    assert_eq!((c.lin_vel_x, c.lin_vel_y), (0.0, 0.0));
    let off = CommandConfig {
        min_lin_vel_mps: 0.0,
        ..config
    };
    assert_eq!(initial_command(&off, &mut rng(1)).lin_vel_x, 0.1);
}

#[test]
fn air_time_counts_touchdowns_after_flight_only() {
    let mut air = AirTime::new(2);
    // Both stand: no touchdown.
    assert_eq!(air.update(&[true, true], 0.02), &[0.0, 0.0]);
    // Foot 0 lifts for 3 steps, then lands on the 4th.
    for _ in 0..3 {
        assert_eq!(air.update(&[false, true], 0.02), &[0.0, 0.0]);
    }
    let t = air.update(&[true, true], 0.02).to_vec();
    assert!((t[0] - 0.08).abs() < 1e-12 && t[1] == 0.0, "{t:?}");
    assert_eq!(air.air(), &[0.0, 0.0]);
    assert_eq!(terms::feet_air_time(&t, 0.05, true), t[0] - 0.05);
    assert_eq!(terms::feet_air_time(&t, 0.05, false), 0.0);
}

#[test]
fn the_total_scales_by_dt_and_clips_at_zero() {
    let scales = Preset::LeggedGym.scales();
    let values = TermValues {
        tracking_lin_vel: 1.0,
        lin_vel_z: 10.0,
        ..TermValues::default()
    };
    // 1·1·0.02 − 2·10·0.02 < 0: clipped.
    assert_eq!(total(&scales, &values, 0.02), 0.0);
    let signed = hyq_tasks::RewardScales {
        only_positive: false,
        ..scales
    };
    let expected = 1.0 * 1.0 * 0.02 - 2.0 * 10.0 * 0.02;
    assert!((total(&signed, &values, 0.02) - expected).abs() < 1e-15);
}

#[test]
fn presets_are_the_anchors_numbers_and_keys_override_them() {
    assert_eq!(TermScales::LEGGED_GYM.lin_vel_z, -2.0);
    assert_eq!(TermScales::PLAYGROUND.orientation, -5.0);
    let config: VelocityConfig =
        toml::from_str("preset = \"playground\"\nlin_vel_z = -3.0\ntracking_sigma = 0.5")
            .expect("a valid table");
    config.validate().expect("in range");
    let s = config.resolve();
    assert_eq!(s.terms.lin_vel_z, -3.0);
    assert_eq!(s.terms.orientation, -5.0);
    assert_eq!(s.tracking_sigma, 0.5);
    assert_eq!(s.feet_air_time_threshold_s, 0.1);
    let bad = VelocityConfig {
        torques: Some(f64::NAN),
        ..VelocityConfig::default()
    };
    let e = bad.validate().expect_err("NaN refused").to_string();
    assert!(e.starts_with("velocity.torques = NaN"), "{e}");
    assert!(!e.contains('\n'));
}

#[test]
fn bad_command_values_name_their_key() {
    let cases = [
        (
            CommandConfig {
                lin_vel_x: [1.0, -1.0],
                ..CommandConfig::default()
            },
            "command.lin_vel_x",
        ),
        (
            CommandConfig {
                resampling_time_s: 0.0,
                ..CommandConfig::default()
            },
            "command.resampling_time_s",
        ),
        (
            CommandConfig {
                standing_probability: 1.5,
                ..CommandConfig::default()
            },
            "command.standing_probability",
        ),
        (
            CommandConfig {
                ang_vel_yaw: [f64::INFINITY, 1.0],
                ..CommandConfig::default()
            },
            "command.ang_vel_yaw",
        ),
    ];
    for (config, key) in cases {
        let e = config.validate().expect_err(key);
        assert_eq!(e.key, key);
        assert!(!e.to_string().contains('\n'));
    }
}

#[test]
fn upside_down_and_trunk_contact_end_an_episode() {
    use hyq_tasks::termination::terminated;
    assert!(!terminated([0.0, 0.0, -1.0], false, false));
    assert!(terminated([0.0, 0.0, 1.0], false, false));
    assert!(!terminated([1.0, 0.0, 0.0], true, false));
    assert!(terminated([0.0, 0.0, -1.0], true, true));
}

proptest! {
    /// A perfect follower (its body-frame velocity and yaw rate are the command) earns both
    /// tracking terms' maximum, 1, whatever the command; with every regulariser at rest its
    /// reward is the tracking scales' sum times Δt under either preset.
    #[test]
    fn a_perfect_follower_earns_the_tracking_maximum(
        c in [-10.0..10.0f64, -10.0..10.0, -10.0..10.0],
        playground in any::<bool>(),
    ) {
        let preset = if playground { Preset::Playground } else { Preset::LeggedGym };
        let scales = preset.scales();
        let zeros = [0.0; 12];
        let soft = [[-1.0, 1.0]; 12];
        let s = VelocitySnapshot {
            command: Command { lin_vel_x: c[0], lin_vel_y: c[1], ang_vel_yaw: c[2] },
            lin_vel: [c[0], c[1], 0.0],
            ang_vel: [0.0, 0.0, c[2]],
            gravity: [0.0, 0.0, -1.0],
            joint_angles: &zeros,
            joint_speeds: &zeros,
            previous_joint_speeds: &zeros,
            standing: &zeros,
            soft_limits: &soft,
            torques: &zeros,
            action: &zeros,
            previous_action: &zeros,
            foot_contacts: &[true; 4],
            foot_velocity_xy: &[[0.0; 2]; 4],
            air_at_touchdown: &[0.0; 4],
            trunk_contact: false,
            trunk_contact_ends: false,
            env_dt: 0.02,
        };
        let out = evaluate(&scales, &s);
        prop_assert_eq!(out.terms.tracking_lin_vel, 1.0);
        prop_assert_eq!(out.terms.tracking_ang_vel, 1.0);
        let t = scales.terms;
        let expected = (t.tracking_lin_vel + t.tracking_ang_vel) * 0.02;
        prop_assert!((out.total - expected).abs() < 1e-15, "{} vs {}", out.total, expected);
        // Any tracking error earns less.
        let slower = VelocitySnapshot { lin_vel: [c[0] - 0.1, c[1], 0.0], ..s };
        prop_assert!(evaluate(&scales, &slower).total < out.total);
    }
}
