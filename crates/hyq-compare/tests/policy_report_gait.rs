//! Invariant: a policy comparison states each engine's gait (foot slip per stance step, actions
//! at their bounds, action change per step, stance duration) and each pair's foot-contact
//! pattern agreement, every figure as `{"mean", "ci95"}` over the episodes; the feet it measures
//! are where the engine holds them; an engine whose ground differs shows it in these figures;
//! the same inputs give the same figures byte for byte.

#![allow(clippy::unwrap_used)]

use hyq_compare::policy::PolicySide;
use hyq_compare::{PolicyPlan, PolicyReport, PolicySpec};
use hyq_env::{EnvConfig, Trot};
use hyq_physics::na::Isometry3;
use hyq_rapier::RapierBackend;
use serde_json::Value;

/// The trot's plan on rapier: 4 episodes of 200 steps with reset noise, seed 7, the ground's
/// friction coefficient `friction`.
fn plan(friction: f64) -> PolicyPlan<Trot> {
    let model = hyq_physics::bundled::hyq();
    let mut config = EnvConfig::default();
    config.task.max_time_steps = 200;
    config.reset.joint_noise_rad = 0.05;
    config.reset.yaw_noise_deg = 5.0;
    config.physics.params.ground_friction = friction;
    let policy = Trot::from_profile(&model).unwrap();
    let spec = PolicySpec {
        policy: "trot".into(),
        seed: 7,
        episodes: 4,
        configuration: Vec::new(),
    };
    PolicyPlan::new(model, config, policy, spec).unwrap()
}

fn side(friction: f64, label: &str) -> PolicySide {
    plan(friction).run_side::<RapierBackend>(label).unwrap()
}

fn report(sides: &[PolicySide]) -> PolicyReport {
    plan(1.0).report(sides, &[])
}

fn mean_ci(v: &Value) -> (f64, f64, f64) {
    let ci = v["ci95"].as_array().unwrap();
    (
        v["mean"].as_f64().unwrap(),
        ci[0].as_f64().unwrap(),
        ci[1].as_f64().unwrap(),
    )
}

#[test]
fn every_gait_figure_is_a_mean_with_its_interval_and_one_engine_agrees_with_itself() {
    let r = report(&[side(1.0, "a"), side(1.0, "b")]);
    let json: Value = serde_json::from_str(&r.to_json()).unwrap();
    let gait = &json["sides"][0]["gait"];
    for figure in [
        "foot_slip_mm",
        "actions_at_bounds",
        "action_change",
        "stance_s",
    ] {
        let (mean, lo, hi) = mean_ci(&gait[figure]);
        assert!(lo <= mean && mean <= hi, "{figure}: {}", gait[figure]);
        assert_eq!(gait[figure]["episodes"], 4, "{figure}");
    }
    assert_eq!(json["sides"][1]["gait"], *gait, "the same engine twice");
    // The trot's stance lasts about half its 0.5 s period, its feet grip on friction 1 and its
    // scripted targets stay inside the action space while changing every step.
    let (stance, ..) = mean_ci(&gait["stance_s"]);
    assert!((0.1..0.5).contains(&stance), "stance {stance} s");
    let (slip, ..) = mean_ci(&gait["foot_slip_mm"]);
    assert!((0.0..5.0).contains(&slip), "slip {slip} mm");
    assert_eq!(mean_ci(&gait["actions_at_bounds"]).0, 0.0);
    assert!(mean_ci(&gait["action_change"]).0 > 0.0);
    // Every episode carries its own figures.
    let e = &json["sides"][0]["episodes"][0]["gait"];
    assert!(e["foot_slip_mm"].as_f64().unwrap() >= 0.0, "{e}");
    assert_eq!(
        mean_ci(&json["pairs"][0]["contact_agreement"]),
        (1.0, 1.0, 1.0)
    );
    let md = r.to_markdown("c");
    for text in [
        "## Gait",
        "| foot slip per stance step (mm) | ",
        "| stance duration (s) | ",
        "| a vs b | 100.0 [100.0, 100.0] |",
    ] {
        assert!(md.contains(text), "report.md lacks {text:?}:\n{md}");
    }
}

#[test]
fn a_slippery_ground_shows_in_the_slip_and_in_the_contact_pattern() {
    let r = report(&[side(1.0, "grip"), side(0.1, "ice")]);
    let json: Value = serde_json::from_str(&r.to_json()).unwrap();
    let slip = |k: usize| mean_ci(&json["sides"][k]["gait"]["foot_slip_mm"]);
    let (grip, ice) = (slip(0), slip(1));
    assert!(ice.1 > grip.2, "ice {ice:?} slips more than grip {grip:?}");
    let (agree, _, hi) = mean_ci(&json["pairs"][0]["contact_agreement"]);
    assert!(hi < 1.0 && agree > 0.0, "agreement {agree}");
    // The same inputs, the same report.
    let again = report(&[side(1.0, "grip"), side(0.1, "ice")]);
    assert_eq!(r.to_json(), again.to_json());
    assert_eq!(r.to_markdown("c"), again.to_markdown("c"));
}

#[test]
fn the_measured_feet_are_the_foot_spheres_where_the_engine_holds_them() {
    let s = side(1.0, "a");
    let t = s.first_episode();
    let model = hyq_physics::bundled::hyq();
    let mut poses = vec![Isometry3::identity(); model.links().len()];
    assert_eq!(t.foot_centres.len(), t.len() * model.num_feet());
    for (k, state) in t.states.iter().enumerate().step_by(37) {
        model
            .link_poses(&state.trunk.pose, &state.q, &mut poses)
            .unwrap();
        for (f, foot) in model.tracked()[..model.num_feet()].iter().enumerate() {
            let sphere = &model.links()[foot.link].collisions[foot.shapes[0]];
            let want = (poses[foot.link] * sphere.origin).translation.vector;
            let got = t.foot_centres[k * model.num_feet() + f];
            let gap =
                ((got[0] - want.x).powi(2) + (got[1] - want.y).powi(2) + (got[2] - want.z).powi(2))
                    .sqrt();
            // The engine's joints hold together to well under a millimetre.
            assert!(gap < 1e-3, "sample {k} foot {f}: {got:?} vs {want:?}");
        }
    }
}
