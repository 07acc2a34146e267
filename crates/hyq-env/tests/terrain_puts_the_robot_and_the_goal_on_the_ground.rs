//! Invariant: `[terrain]` is flat by default and then the spec's environment bit for bit; over a
//! height field the robot is put down standing on the surface under its spawn point, the goal's
//! height follows the surface under the goal, the trunk touching the field is a fall and the
//! trunk leaving it ends the episode as diverged; rough ground drawn per episode follows the reset
//! seed; the curriculum moves its level by legged_gym's rule; bad terrain input is refused in one
//! line naming the key or the file before anything runs (docs/spec.md §7.10).

mod common;

use common::{config, rapier, scripted, stand_action};
use hyq_env::terrain::Ground;
use hyq_env::{Env, EnvConfig, Reason, ResetOptions, TerrainKind, TerrainSeed};
use hyq_physics::na::{Isometry3, UnitQuaternion};
use hyq_physics::{Backend, RobotModel, RobotState, Terrain};
use hyq_rapier::RapierBackend;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const ROUGH: &[(&str, &str)] = &[
    ("terrain.kind", "\"rough\""),
    ("terrain.amplitude_m", "0.05"),
    ("terrain.seed", "3"),
];

/// The lowest clearance of the robot's feet above `terrain` in `state` (m).
fn lowest_foot(model: &RobotModel, terrain: &Terrain, state: &RobotState) -> f64 {
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&state.trunk.pose, &state.q, &mut poses)
        .unwrap_or_else(|e| panic!("{e}"));
    model.tracked()[..model.num_feet()]
        .iter()
        .flat_map(|t| {
            let link = &model.links()[t.link];
            let pose = poses[t.link];
            t.shapes.iter().map(move |&s| {
                let c = &link.collisions[s];
                terrain.clearance(&c.shape, &(pose * c.origin)).lower
            })
        })
        .fold(f64::INFINITY, f64::min)
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Flat ground written out (with other kinds' keys at their defaults, as a written table holds
/// them) is the default: the same written configuration and the same episode, bit for bit.
#[test]
fn flat_terrain_is_the_spec_environment_bit_for_bit() {
    let written = EnvConfig::default().to_toml_string();
    assert!(!written.contains("[terrain]") && !written.contains("[observation]"));
    let mut plain: Env<RapierBackend> = rapier(&[]);
    let mut flat: Env<RapierBackend> = rapier(&[
        ("terrain.kind", "\"flat\""),
        ("terrain.amplitude_m", "0.05"),
        ("observation.extra", "[]"),
    ]);
    assert!(flat.terrain().is_flat() && flat.backend().terrain().is_flat());
    let options = ResetOptions::default();
    let a = bits(
        plain
            .reset(Some(5), &options)
            .unwrap_or_else(|e| panic!("{e}"))
            .observation,
    );
    let b = bits(
        flat.reset(Some(5), &options)
            .unwrap_or_else(|e| panic!("{e}"))
            .observation,
    );
    assert_eq!(a, b);
    let action = stand_action(&plain);
    for t in 1..=30 {
        let a = plain.step(&action).unwrap_or_else(|e| panic!("{e}"));
        let a = (bits(a.observation), a.reward.to_bits());
        let b = flat.step(&action).unwrap_or_else(|e| panic!("{e}"));
        let b = (bits(b.observation), b.reward.to_bits());
        assert_eq!(a, b, "step {t}");
    }
}

/// On rough ground the reset state has the feet's lowest clearance it has above flat ground,
/// the goal is the standing height above the surface under it, and the robot then stands:
/// its trunk never touches the ground and all four feet are down.
#[test]
fn the_robot_spawns_standing_on_rough_ground_and_the_goal_follows_the_surface() {
    let model = hyq_physics::bundled::hyq();
    let flat_clearance = lowest_foot(&model, &Terrain::Flat, &model.spawn_state());
    let mut env: Env<RapierBackend> = rapier(ROUGH);
    let r = env
        .reset(Some(1), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let goal = r.info.goal;
    let terrain = env.terrain().clone();
    assert!(!terrain.is_flat() && env.backend().terrain().same_as(&terrain));
    let surface = terrain.height_at(goal[0], goal[1]);
    assert!(
        surface.abs() > 1e-3,
        "the goal's ground is level: {surface}"
    );
    assert_eq!(goal, [5.0, 0.0, model.standing_height() + surface]);
    let state = env.state().clone();
    let clearance = lowest_foot(&model, &terrain, &state);
    assert!(
        (clearance - flat_clearance).abs() < 1e-6,
        "{clearance} vs {flat_clearance} on flat ground"
    );
    let (roll, pitch, _) = state.trunk.pose.rotation.euler_angles();
    assert!(
        roll != 0.0 || pitch != 0.0,
        "the trunk was not tilted to the ground"
    );

    let action = stand_action(&env);
    let flags = env.observation_layout().foot_contacts();
    let trunk_row = env.observation_layout().trunk_contact();
    let mut last = Vec::new();
    for t in 1..=60 {
        let s = env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        assert!(!s.terminated, "t = {t}: {:?}", s.info.reasons);
        assert_eq!(s.observation[trunk_row], 0.0, "t = {t}");
        last = s.observation[flags.clone()].to_vec();
    }
    assert_eq!(last, vec![1.0; 4], "not every foot is down");
}

/// Dropped upside down onto a 0.5 m step, the trunk touches the step's top (far above the
/// flat floor) and that is a fall.
#[test]
fn touching_the_terrain_is_a_fall() {
    let mut env: Env<RapierBackend> = rapier(&[
        ("terrain.kind", "\"stairs\""),
        ("terrain.step_height_m", "0.5"),
        ("terrain.step_depth_m", "2.0"),
        ("terrain.start_m", "1.0"),
    ]);
    let mut state = env.model().spawn_state();
    state.trunk.pose.translation.vector.x = 2.0;
    state.trunk.pose.translation.vector.z = 0.5 + 0.25;
    state.trunk.pose.rotation = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let options = ResetOptions {
        state: Some(state),
        ..ResetOptions::default()
    };
    env.reset(Some(0), &options)
        .unwrap_or_else(|e| panic!("{e}"));
    let action = stand_action(&env);
    for t in 1..=40 {
        let s = env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        if s.terminated {
            assert!(
                s.info.reasons.contains(Reason::Fell),
                "t = {t}: {:?}",
                s.info.reasons
            );
            let z = env.state().trunk.pose.translation.z;
            assert!(z > 0.5, "the trunk fell through the step to z = {z}");
            return;
        }
    }
    panic!("the trunk lay on the step for 40 steps without a fall");
}

/// Beyond the field's rectangle there is no ground: a trunk there ends the episode as diverged,
/// the info naming where it is and where the field is.
#[test]
fn leaving_the_field_ends_the_episode_as_diverged() {
    let mut env = scripted(&[
        ("terrain.kind", "\"slope\""),
        ("terrain.slope_deg", "5"),
        ("terrain.size_m", "[2.0, 2.0]"),
        ("terrain.resolution_m", "0.1"),
        // The goal on the field (a field not under the goal is refused).
        ("goal.distance_m", "0.9"),
    ]);
    let mut state = env.model().spawn_state();
    state.trunk.pose.translation.vector.x = 1.5;
    let options = ResetOptions {
        state: Some(state),
        ..ResetOptions::default()
    };
    env.reset(Some(0), &options)
        .unwrap_or_else(|e| panic!("{e}"));
    let action = stand_action(&env);
    let s = env.step(&action).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.terminated && s.info.reasons.contains(Reason::Diverged));
    assert!(s.observation.iter().all(|v| v.is_finite()));
    let why = s.info.divergence.as_ref().map(ToString::to_string);
    let why = why.unwrap_or_default();
    assert!(
        why.contains("left the terrain") && why.contains("-1.00 .. 1.00"),
        "{why}"
    );
}

/// `seed = "episode"` draws the ground from the reset seed (the same seed, the same ground; a
/// new seed, new ground), where a fixed seed keeps one ground, not even rebuilt.
#[test]
fn rough_ground_drawn_per_episode_follows_the_reset_seed() {
    let heights = |env: &Env<hyq_env::testing::ScriptedBackend>| {
        let grid = env.terrain().grid().map(|g| g.heights().to_vec());
        grid.unwrap_or_default()
    };
    let mut per_episode = scripted(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.seed", "\"episode\""),
        ("terrain.size_m", "[4.0, 4.0]"),
        ("goal.distance_m", "1.5"),
    ]);
    let mut seen = Vec::new();
    for seed in [1, 2, 1] {
        common::reset(&mut per_episode, seed);
        assert!(
            per_episode
                .backend()
                .terrain()
                .same_as(per_episode.terrain())
        );
        seen.push(heights(&per_episode));
    }
    assert!(!seen[0].is_empty());
    assert_ne!(seen[0], seen[1]);
    assert_eq!(bits(&seen[0]), bits(&seen[2]));

    let mut fixed = scripted(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.seed", "7"),
        ("terrain.size_m", "[4.0, 4.0]"),
        ("goal.distance_m", "1.5"),
    ]);
    common::reset(&mut fixed, 1);
    let first = fixed.terrain().clone();
    common::reset(&mut fixed, 2);
    match (&first, fixed.terrain()) {
        (Terrain::Field(a), Terrain::Field(b)) => assert!(std::sync::Arc::ptr_eq(a, b)),
        other => panic!("not a field: {other:?}"),
    }
}

/// The curriculum starts at level 0 with the relief scaled by 1 / levels, goes up a level after
/// an episode that covered half the way, down after one that covered less than a quarter, and
/// stays within 0 ..= levels − 1.
#[test]
fn the_curriculum_raises_the_level_on_progress_and_lowers_it_on_failure() {
    let c = config(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.amplitude_m", "0.08"),
        ("terrain.curriculum", "true"),
        ("terrain.levels", "4"),
        ("terrain.size_m", "[4.0, 4.0]"),
        ("goal.distance_m", "1.5"),
    ]);
    let model = hyq_physics::bundled::hyq();
    let mut ground = Ground::new(&c, &model).unwrap_or_else(|e| panic!("{e}"));
    let relief = |g: &Ground| {
        let grid = g.terrain().grid().map(|g| (g.min_height(), g.max_height()));
        let (lo, hi) = grid.unwrap_or((f64::NAN, f64::NAN));
        lo.abs().max(hi.abs())
    };
    assert_eq!(ground.level(), 0);
    assert!(relief(&ground) <= 0.02 + 1e-12 && relief(&ground) > 0.01);
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let mut levels = Vec::new();
    for progress in [0.6, 0.3, 0.5, 0.9, 0.9, 0.9, 0.1, 0.24, 0.24] {
        ground
            .next_episode(&mut rng, Some(progress))
            .unwrap_or_else(|e| panic!("{e}"));
        levels.push(ground.level());
        let scale = f64::from(ground.level() + 1) / 4.0;
        assert!(
            relief(&ground) <= 0.08 * scale + 1e-12,
            "level {}",
            ground.level()
        );
    }
    assert_eq!(levels, [1, 1, 2, 3, 3, 3, 2, 1, 0]);
    ground
        .next_episode(&mut rng, None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(ground.level(), 0);
}

/// Every key the scripts rely on is read by its name.
#[test]
fn the_terrain_keys_are_read_by_their_names() {
    // Each kind with its own keys (a key of another kind is refused, unless at its default).
    let c = config(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.amplitude_m", "0.03"),
        ("terrain.feature_m", "0.5"),
        ("terrain.seed", "\"episode\""),
        ("terrain.size_m", "[10.0, 6.0]"),
        ("terrain.resolution_m", "0.04"),
        (
            "observation.extra",
            "[\"height_scan\", \"goal_vector\", \"trunk_velocity\"]",
        ),
    ]);
    let t = &c.terrain;
    assert_eq!(t.kind, TerrainKind::Rough);
    assert_eq!((t.amplitude_m, t.feature_m), (0.03, 0.5));
    assert_eq!(t.seed, TerrainSeed::Episode);
    assert_eq!((t.size_m, t.resolution_m), ([10.0, 6.0], 0.04));
    assert_eq!(c.observation.extra.len(), 3);
    let again = EnvConfig::from_toml_str(&c.to_toml_string(), "round trip")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(again, c);
    let slope = config(&[("terrain.kind", "\"slope\""), ("terrain.slope_deg", "-12")]);
    assert_eq!(slope.terrain.slope_deg, -12.0);
    let stairs = config(&[
        ("terrain.kind", "\"stairs\""),
        ("terrain.step_height_m", "0.12"),
        ("terrain.step_depth_m", "0.35"),
    ]);
    assert_eq!(
        (stairs.terrain.step_height_m, stairs.terrain.step_depth_m),
        (0.12, 0.35)
    );
    let field = config(&[
        ("terrain.kind", "\"heightfield\""),
        ("terrain.file", "\"ground.npy\""),
    ]);
    assert_eq!(
        field.terrain.file.as_deref(),
        Some(std::path::Path::new("ground.npy"))
    );
    let again = EnvConfig::from_toml_str(&field.to_toml_string(), "round trip")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(again, field);
}

/// Overrides (key, value) and the words their refusal must hold.
type BadCase<'a> = (Vec<(&'a str, String)>, Vec<&'a str>);

fn refused(overrides: &[(&str, &str)]) -> String {
    let mut c = EnvConfig::default();
    let msg = match c.set_all(overrides) {
        Err(e) => e.to_string(),
        Ok(()) => {
            match Env::<hyq_env::testing::ScriptedBackend>::new(hyq_physics::bundled::hyq(), c) {
                Err(e) => e.to_string(),
                Ok(_) => panic!("{overrides:?} was accepted"),
            }
        }
    };
    assert!(!msg.contains('\n'), "{msg}");
    msg
}

/// Bad terrain and observation input, each refused in one line naming what was wrong, before an
/// environment exists.
#[test]
fn bad_terrain_input_is_refused_in_one_line_naming_the_key() {
    let dir = std::env::temp_dir().join(format!("hyq-terrain-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let text = dir.join("words.npy");
    std::fs::write(&text, "not numbers").unwrap_or_else(|e| panic!("{e}"));
    let missing = dir.join("missing.npy");
    let path = |p: &std::path::Path| format!("{:?}", p.display().to_string());
    let cases: Vec<BadCase<'_>> = vec![
        (
            vec![("terrain.kind", "\"lava\"".into())],
            vec!["terrain.kind", "lava"],
        ),
        (vec![("terrain.bumpiness", "1".into())], vec!["bumpiness"]),
        (
            vec![
                ("terrain.kind", "\"slope\"".into()),
                ("terrain.slope_deg", "40".into()),
            ],
            vec!["terrain.slope_deg", "40"],
        ),
        (
            vec![
                ("terrain.kind", "\"rough\"".into()),
                ("terrain.amplitude_m", "-0.1".into()),
            ],
            vec!["terrain.amplitude_m"],
        ),
        (
            vec![
                ("terrain.kind", "\"rough\"".into()),
                ("terrain.size_m", "[0.0, 4.0]".into()),
            ],
            vec!["terrain.size_m"],
        ),
        (vec![("terrain.seed", "-1".into())], vec!["terrain.seed"]),
        (
            vec![("terrain.kind", "\"heightfield\"".into())],
            vec!["terrain.file", "required"],
        ),
        (
            vec![
                ("terrain.kind", "\"heightfield\"".into()),
                ("terrain.file", path(&missing)),
            ],
            vec!["terrain.file", "missing.npy"],
        ),
        (
            vec![
                ("terrain.kind", "\"heightfield\"".into()),
                ("terrain.file", path(&text)),
            ],
            vec!["terrain.file", "words.npy"],
        ),
        (
            vec![
                ("terrain.kind", "\"heightfield\"".into()),
                ("terrain.file", path(&text)),
                ("terrain.curriculum", "true".into()),
            ],
            vec!["terrain.curriculum"],
        ),
        (
            vec![
                ("terrain.kind", "\"stairs\"".into()),
                ("terrain.step_height_m", "0.5".into()),
                ("terrain.start_m", "-0.2".into()),
            ],
            vec!["terrain.step_height_m", "cannot be put down standing"],
        ),
        (
            vec![("observation.extra", "[\"lidar\"]".into())],
            vec!["observation.extra", "lidar"],
        ),
        (
            vec![(
                "observation.extra",
                "[\"goal_vector\", \"goal_vector\"]".into(),
            )],
            vec!["observation.extra", "twice"],
        ),
        (
            vec![("observation.height_scan_x_m", "[0.5, -0.5]".into())],
            vec!["observation.height_scan_x_m"],
        ),
        (
            vec![("observation.height_scan_spacing_m", "0.02".into())],
            vec!["observation.height_scan_spacing_m", "1024"],
        ),
    ];
    for (overrides, words) in &cases {
        let pairs: Vec<(&str, &str)> = overrides.iter().map(|(k, v)| (*k, v.as_str())).collect();
        let msg = refused(&pairs);
        for w in words {
            assert!(
                msg.contains(w),
                "{overrides:?}: {msg:?} does not name {w:?}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A field that does not lie under the robot's feet at its spawn point is refused naming the
/// key that put it there: outside the field no engine has ground, and every episode ended
/// `diverged` at its first step (the edge cell's plane, extended, put the robot 1.9 m up).
#[test]
fn a_field_not_under_the_feet_is_refused_naming_the_key() {
    for (key, value) in [
        ("terrain.center_m", "[9.0, 0.0]"),
        ("terrain.center_m", "[20.0, 0.0]"),
        ("terrain.center_m", "[8.0, 0.0]"),
        ("terrain.size_m", "[0.1, 0.1]"),
    ] {
        // The velocity task walks to no goal: a field this small is also not under the goal,
        // which the goal task refuses first (`a_field_not_under_the_goal_is_refused`).
        let msg = refused(&[
            ("task.kind", "\"velocity\""),
            ("terrain.kind", "\"rough\""),
            (key, value),
        ]);
        assert!(
            msg.contains(&format!("{key} = {value}"))
                && msg.contains("does not lie under the robot's foot"),
            "{key} = {value}: {msg}"
        );
    }
    // A field that holds the feet is built.
    Env::<hyq_env::testing::ScriptedBackend>::new(
        hyq_physics::bundled::hyq(),
        config(&[
            ("terrain.kind", "\"rough\""),
            ("terrain.center_m", "[7.0, 0.0]"),
        ]),
    )
    .unwrap_or_else(|e| panic!("{e}"));
}

/// A put-down refusal quotes the key's own value (it quoted the terrain's kind), and a slope of
/// exactly ±30°, the documented limit, is accepted both ways (+30 was refused as "30°, more
/// than 30°").
#[test]
fn put_down_refusals_quote_the_key_and_the_slope_limit_is_inclusive() {
    let msg = refused(&[
        ("terrain.kind", "\"stairs\""),
        ("terrain.step_height_m", "0.5"),
        ("terrain.start_m", "0.0"),
    ]);
    assert!(msg.contains("terrain.step_height_m = 0.5:"), "{msg}");
    let msg = refused(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.amplitude_m", "1.0"),
    ]);
    assert!(msg.contains("terrain.amplitude_m = 1.0:"), "{msg}");
    for slope in ["30", "-30"] {
        Env::<hyq_env::testing::ScriptedBackend>::new(
            hyq_physics::bundled::hyq(),
            config(&[("terrain.kind", "\"slope\""), ("terrain.slope_deg", slope)]),
        )
        .unwrap_or_else(|e| panic!("slope {slope}: {e}"));
    }
}

/// A range refusal blames the key the user set and prints its numbers short: a resolution of
/// 1e308 was blamed on `terrain.feature_m`, and a centre of 1e308 on `terrain.size_m`, with the
/// centre printed in 309 digits.
#[test]
fn terrain_range_refusals_blame_the_key_set_in_short_numbers() {
    let msg = refused(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.resolution_m", "1e308"),
    ]);
    assert!(
        msg.contains("terrain.resolution_m = 1e308") && msg.contains("the field's smaller side"),
        "{msg}"
    );
    let msg = refused(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.center_m", "[1e308, 0.0]"),
    ]);
    assert!(msg.contains("terrain.center_m = [1e308, 0.0]"), "{msg}");
    assert!(!msg.contains(&"0".repeat(30)), "{msg}");
}

/// A 2 × 2 float64 `.npy` file of zeros in `dir`, as a TOML string of its path.
fn zeros_npy(dir: &std::path::Path) -> String {
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("{e}"));
    let file = dir.join("flat.npy");
    let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }";
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    let pad = 64 - (10 + header.len() + 1) % 64;
    let len = u16::try_from(header.len() + pad + 1).unwrap_or_else(|e| panic!("{e}"));
    npy.extend(len.to_le_bytes());
    npy.extend(header.bytes());
    npy.extend(std::iter::repeat_n(b' ', pad));
    npy.push(b'\n');
    npy.extend([0u8; 32]);
    std::fs::write(&file, npy).unwrap_or_else(|e| panic!("{e}"));
    format!("{:?}", file.display().to_string())
}

/// Overrides and the words their refusal must hold.
type GoalCase<'a> = (&'a [(&'a str, &'a str)], &'a [&'a str]);

/// A field that does not lie under every goal the `[goal]` table can give is refused, naming
/// the field's key and the goal's: outside the field there is no ground, so the robot walked
/// off its edge on the way and every episode ended `diverged` (a 4 m field with the default
/// goal 5 m ahead, a field moved behind the robot, a random goal that can be drawn off it).
#[test]
fn a_field_not_under_the_goal_is_refused() {
    let dir = std::env::temp_dir().join(format!("hyq-terrain-goal-{}", std::process::id()));
    let file = zeros_npy(&dir);
    let cases: [GoalCase<'_>; 5] = [
        (
            &[
                ("terrain.kind", "\"rough\""),
                ("terrain.size_m", "[4.0, 4.0]"),
            ],
            &[
                "terrain.size_m = [4.0, 4.0]",
                "goal.distance_m = 5",
                "[5.00, 0.00]",
            ],
        ),
        (
            &[
                ("terrain.kind", "\"slope\""),
                ("terrain.center_m", "[-5.0, 0.0]"),
            ],
            &[
                "terrain.center_m = [-5.0, 0.0]",
                "x -13.00 .. 3.00, y -8.00 .. 8.00 m",
            ],
        ),
        (
            &[
                ("terrain.kind", "\"heightfield\""),
                ("terrain.file", &file),
                ("terrain.size_m", "[6.0, 6.0]"),
            ],
            &["terrain.size_m = [6.0, 6.0]", "terrain.file", "flat.npy"],
        ),
        (
            &[
                ("terrain.kind", "\"rough\""),
                ("goal.mode", "\"random\""),
                ("goal.distance_range_m", "[1.0, 3.0]"),
                ("goal.heading_range_deg", "[-120.0, -60.0]"),
                ("terrain.size_m", "[8.0, 5.6]"),
            ],
            // Both ends of the heading range are on the field (y = -2.60); straight to the
            // right, between them, is not.
            &["goal.heading_range_deg", "[0.00, -3.00]"],
        ),
        (
            &[
                ("terrain.kind", "\"stairs\""),
                ("goal.mode", "\"fixed\""),
                ("goal.position", "[2.0, 9.0, 0.6]"),
            ],
            &[
                "terrain.size_m = [16.0, 16.0]",
                "goal.position",
                "[2.00, 9.00]",
            ],
        ),
    ];
    for (overrides, words) in cases {
        let msg = refused(overrides);
        for w in words.iter().chain(&["is not under the goal"]) {
            assert!(
                msg.contains(w),
                "{overrides:?}: {msg:?} does not name {w:?}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The other side of `a_field_not_under_the_goal_is_refused`: a goal on the field, its edge
/// included, is accepted; so is any field under the velocity task, which walks to no goal; flat
/// ground has no edge.
#[test]
fn a_field_under_every_goal_is_built() {
    let build = |overrides: &[(&str, &str)]| {
        Env::<hyq_env::testing::ScriptedBackend>::new(
            hyq_physics::bundled::hyq(),
            config(overrides),
        )
        .unwrap_or_else(|e| panic!("{overrides:?}: {e}"));
    };
    // A goal on the edge: 5 m ahead on a 10 m field centred on the spawn point.
    build(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.size_m", "[10.0, 4.0]"),
    ]);
    // The random goal of the refused case, with a field that holds all of its draws.
    build(&[
        ("terrain.kind", "\"rough\""),
        ("goal.mode", "\"random\""),
        ("goal.distance_range_m", "[1.0, 3.0]"),
        ("goal.heading_range_deg", "[-120.0, -60.0]"),
        ("terrain.size_m", "[8.0, 6.0]"),
    ]);
    build(&[
        ("task.kind", "\"velocity\""),
        ("terrain.kind", "\"rough\""),
        ("terrain.size_m", "[4.0, 4.0]"),
    ]);
    build(&[("goal.distance_m", "50")]);
}

/// A resolution between the field's side and 50 m (the feature's upper bound) was blamed on
/// `terrain.feature_m` ("must be within [16, 50] m", the grid's side as its lower end), as was
/// one coarser than the default bump; each now names `terrain.resolution_m`, and the key the
/// user did change is still the one named.
#[test]
fn a_coarse_resolution_is_blamed_on_the_resolution() {
    for (kind, resolution, words) in [
        (
            "rough",
            "20",
            &["terrain.resolution_m = 20:", "at most 16 m", "smaller side"][..],
        ),
        (
            "stairs",
            "40",
            &["terrain.resolution_m = 40:", "at most 16 m"][..],
        ),
        (
            "rough",
            "1.0",
            &["terrain.resolution_m = 1:", "terrain.feature_m = 0.4"][..],
        ),
        (
            "stairs",
            "0.2",
            &["terrain.resolution_m = 0.2:", "terrain.step_depth_m = 0.3"][..],
        ),
    ] {
        let msg = refused(&[
            ("terrain.kind", &format!("{kind:?}")),
            ("terrain.resolution_m", resolution),
        ]);
        for w in words {
            assert!(
                msg.contains(w),
                "{kind} at {resolution}: {msg:?} lacks {w:?}"
            );
        }
        assert!(!msg.contains("invalid terrain.feature_m"), "{msg}");
    }
    // A field shrunk below the default spacing is blamed on its size.
    let msg = refused(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.size_m", "[0.01, 0.01]"),
    ]);
    assert!(
        msg.starts_with("invalid terrain.size_m = [0.01, 0.01]")
            && msg.contains("terrain.resolution_m = 0.05"),
        "{msg}"
    );
    // A bump the user set smaller than the grid's spacing is blamed on the bump.
    let msg = refused(&[("terrain.kind", "\"rough\""), ("terrain.feature_m", "0.01")]);
    assert!(msg.starts_with("invalid terrain.feature_m = 0.01"), "{msg}");
}
