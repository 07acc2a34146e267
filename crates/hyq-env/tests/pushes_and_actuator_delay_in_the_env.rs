//! Pushes come at the drawn times with the drawn speed, added to the trunk's velocity at the
//! start of their env step; the actuator's delay serves the previous env step's targets (the
//! reset's at the first step) for its first k sub-steps, so a delay of a whole env step is the
//! undelayed environment one action late.

mod common;

use common::{rapier, reset, stand_action};
use hyq_env::Env;
use hyq_rapier::RapierBackend;

#[test]
fn pushes_come_every_interval_and_move_the_trunk() {
    let mut env = rapier(&[
        ("task.max_time_steps", "200"),
        ("randomize.push_interval_s", "[0.5, 0.5]"),
        ("randomize.push_velocity_xy_mps", "[0.8, 0.8]"),
    ]);
    let mut still = rapier(&[("task.max_time_steps", "200")]);
    reset(&mut env, 1);
    reset(&mut still, 1);
    let stand = stand_action(&env);
    let mut pushed_at = Vec::new();
    for _ in 0..160 {
        let before = env.trunk().linvel;
        let step = env.step(&stand).unwrap_or_else(|e| panic!("{e}"));
        let t = step.info.t;
        still.step(&stand).unwrap_or_else(|e| panic!("{e}"));
        let (pushed, count) = env.last_push().expect("pushes are on");
        if pushed != [0.0; 3] {
            pushed_at.push(t);
            let speed = (pushed[0].powi(2) + pushed[1].powi(2)).sqrt();
            assert!(
                (speed - 0.8).abs() < 1e-12 && pushed[2] == 0.0,
                "{pushed:?}"
            );
            // The trunk keeps most of the push over the step (the feet's friction takes some).
            let gained = env.trunk().linvel - before;
            let along = gained.x * pushed[0] / speed + gained.y * pushed[1] / speed;
            assert!(
                along > 0.3,
                "step {t}: gained {gained:?} for a push {pushed:?}"
            );
        }
        assert_eq!(count, pushed_at.len() as u64);
    }
    // Steps of 0.01 s: pushes at 0.5, 1.0 and 1.5 s start steps 51, 101 and 151.
    assert_eq!(pushed_at, [51, 101, 151]);
    let moved = (env.trunk().pose.translation.vector - still.trunk().pose.translation.vector).xy();
    assert!(
        moved.norm() > 0.05,
        "the pushed robot is where the unpushed one is: {moved:?}"
    );
}

/// The joint angles and trunk state after each of `actions`, bitwise.
fn trace(env: &mut Env<RapierBackend>, actions: &[Vec<f64>]) -> Vec<Vec<u64>> {
    actions
        .iter()
        .map(|a| {
            env.step(a).unwrap_or_else(|e| panic!("{e}"));
            let t = env.trunk();
            env.joint_angles()
                .iter()
                .chain(t.pose.translation.vector.iter())
                .chain(t.linvel.iter())
                .map(|v| v.to_bits())
                .collect()
        })
        .collect()
}

#[test]
fn a_delay_of_one_env_step_is_the_environment_one_action_late() {
    let absolute = [
        ("action.mode", "\"absolute\""),
        ("task.max_time_steps", "50"),
    ];
    let mut delayed = rapier(&[
        ("action.mode", "\"absolute\""),
        ("task.max_time_steps", "50"),
        ("randomize.actuator_delay_substeps", "[10, 10]"),
    ]);
    let mut prompt = rapier(&absolute);
    reset(&mut delayed, 4);
    reset(&mut prompt, 4);
    assert_eq!(
        delayed.episode_draw().map(|d| d.actuator_delay_substeps),
        Some(10)
    );
    let start = prompt.joint_angles().to_vec();
    let stand = stand_action(&prompt);
    let bent: Vec<f64> = stand.iter().map(|q| q + 0.1).collect();
    let actions = vec![bent.clone(), stand.clone(), bent.clone(), stand.clone()];
    let late: Vec<Vec<f64>> = std::iter::once(start)
        .chain(actions[..3].iter().cloned())
        .collect();
    assert!(
        trace(&mut delayed, &actions) == trace(&mut prompt, &late),
        "a delay of 10 sub-steps of 10 must run the previous action's targets"
    );
}
