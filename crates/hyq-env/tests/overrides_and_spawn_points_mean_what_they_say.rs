//! Invariant: overrides mean what they say and an accepted spawn point can run. `set_all`
//! applies its overrides together, so a table can be given key by key; a value holding more
//! than one TOML value (text after a line break) is refused, never cut; a spawn point that
//! leaves the robot no room inside the world is refused when the env is built (it used to end
//! every episode at its first step as `diverged`); and a goal pushed out of the world by the
//! spawn point is reported with the spawn point named.

mod common;

use hyq_env::testing::ScriptedBackend;
use hyq_env::{ConfigError, Env, EnvConfig};
use hyq_rapier::RapierBackend;
use hyq_spec::HeightPenalty;

fn set(pairs: &[(&str, &str)]) -> Result<EnvConfig, ConfigError> {
    let mut c = EnvConfig::default();
    c.set_all(pairs).map(|()| c)
}

#[test]
fn a_table_can_be_set_key_by_key() {
    let c = set(&[
        ("task.height_penalty.nominal_height_m", "0.58"),
        ("task.height_penalty.tolerance_m", "0.05"),
        ("task.height_penalty.rate_per_m", "1"),
    ])
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        c.task.height_penalty,
        Some(HeightPenalty {
            nominal_height_m: 0.58,
            tolerance_m: 0.05,
            rate_per_m: 1.0,
        })
    );
    // Given partly, the error names the first key and what is missing.
    let e = set(&[("task.height_penalty.nominal_height_m", "0.58")])
        .expect_err("incomplete")
        .to_string();
    assert!(
        e.contains("task.height_penalty.nominal_height_m") && e.contains("tolerance_m"),
        "{e}"
    );
    // A real error after an incomplete table is still blamed on its own key.
    let e = set(&[
        ("task.height_penalty.nominal_height_m", "0.58"),
        ("task.bogus", "1"),
    ])
    .expect_err("unknown key")
    .to_string();
    assert!(
        e.contains("setting task.bogus = 1") && e.contains("bogus"),
        "{e}"
    );
    let e = set(&[("task.max_time_steps", "x"), ("task.fall_penalty", "1")])
        .expect_err("wrong type")
        .to_string();
    assert!(e.contains("setting task.max_time_steps = x"), "{e}");
}

#[test]
fn text_after_a_line_break_in_a_value_is_refused_not_dropped() {
    for value in [
        "1\ntask.max_time_steps=3",
        "3\nfoo=5",
        "3\n[task]\nmax_time_steps=7",
    ] {
        let e = set(&[("task.fall_penalty", value)])
            .expect_err("two values")
            .to_string();
        assert!(
            e.contains("more than one TOML value") && !e.contains('\n'),
            "{value:?}: {e}"
        );
    }
    // A trailing line break is no second value.
    assert_eq!(
        set(&[("task.fall_penalty", "1\n")]).map(|c| c.task.fall_penalty),
        Ok(1.0)
    );
}

fn spawn_at(x: f64, y: f64) -> EnvConfig {
    let mut c = EnvConfig::default();
    c.reset.spawn_xy_m = [x, y];
    c.goal.distance_m = 0.5;
    c
}

#[test]
fn a_spawn_point_on_the_world_edge_is_refused_when_the_env_is_built() {
    for robot in [
        hyq_physics::bundled::hyq(),
        hyq_physics::bundled::anymal_c(),
    ] {
        let reach = robot.standing_reach();
        assert!(reach > 0.3 && reach < 2.0, "{reach}");
        for (x, y) in [(-100.0, 0.0), (0.0, -100.0), (reach / 2.0 - 100.0, 0.0)] {
            let e = Env::<ScriptedBackend>::new(robot.clone(), spawn_at(x, y))
                .err()
                .unwrap_or_else(|| panic!("[{x}, {y}] accepted"))
                .to_string();
            assert!(
                e.contains("reset.spawn_xy_m") && e.contains("no room"),
                "{e}"
            );
        }
        // At the largest spawn point accepted the robot runs: its first steps stay in the
        // world (the trunk is well inside it) on a real engine.
        let edge = -(100.0 - reach);
        let mut env = Env::<RapierBackend>::new(robot.clone(), spawn_at(edge, edge))
            .unwrap_or_else(|e| panic!("{e}"));
        env.reset(Some(0), &Default::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let standing = vec![0.0; env.action_space().len()];
        for _ in 0..5 {
            let step = env.step(&standing).unwrap_or_else(|e| panic!("{e}"));
            assert!(step.info.divergence.is_none(), "{:?}", step.info.divergence);
        }
    }
}

#[test]
fn a_goal_pushed_out_by_the_spawn_point_names_the_spawn_point() {
    let e = set(&[("reset.spawn_xy_m", "[100, 0]")])
        .expect_err("the default goal 5 m ahead is outside")
        .to_string();
    assert!(
        e.contains("goal.distance_m") && e.contains("reset.spawn_xy_m = [100.0, 0.0]"),
        "{e}"
    );
}
