//! Invariant: the configuration file has the tables [task] [goal] [action] [control] [physics]
//! (+ engine tables) [reset] and the optional [terrain] [observation]; every key is optional
//! with the documented default; unknown keys, misspelt engine tables and invalid values are errors naming the key (and value); `set` /
//! `set_all` overrides by dotted key with the same checks and leave the configuration unchanged
//! on error; engine tables become the backend's options when an env is built. Messages are one
//! line (the CLI prints them as they are).

mod common;

use hyq_env::{ActionMode, ConfigError, Env, EnvConfig, Gains, GoalMode, OutOfRange};
use hyq_rapier::{RapierBackend, RapierOptions};

fn parse_err(text: &str) -> String {
    match EnvConfig::from_toml_str(text, "test.toml") {
        Ok(c) => panic!("expected an error for {text:?}, got {c:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn an_empty_file_is_the_documented_defaults() {
    let c = EnvConfig::from_toml_str("", "empty").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(c, EnvConfig::default());
    assert_eq!(c.task.spec, hyq_spec::TaskConfig::default());
    assert_eq!(c.task.kind, hyq_env::TaskKind::Goal);
    assert_eq!(c.goal.mode, GoalMode::Ahead);
    assert_eq!(c.goal.distance_m, 5.0);
    assert_eq!(c.goal.heading_range_deg, [0.0, 0.0]);
    assert_eq!(c.action.mode, ActionMode::Normalized);
    assert_eq!(c.action.out_of_range, OutOfRange::Clip);
    assert_eq!(c.action.max_delta_rad, 0.1);
    assert_eq!(c.action.max_offset_rad, 0.5);
    assert_eq!(c.control.sim_steps_per_env_step, 10);
    assert_eq!(
        (c.control.kp.clone(), c.control.kd.clone()),
        (Gains::Profile, Gains::Profile)
    );
    assert_eq!(c.physics.params, hyq_physics::PhysicsParams::default());
    assert!(c.physics.engines.is_empty());
    assert_eq!(c.reset.joint_noise_rad, 0.0);
    assert_eq!(c.env_dt(), 0.01);
}

#[test]
fn a_full_file_reads_every_table() {
    let text = r#"
        [task]
        norm_rew_scaling = 10.0
        exp_rew_scaling = "off"
        fall_penalty = 1.5
        max_time_steps = 500

        [goal]
        mode = "random"
        distance_range_m = [2.0, 4.0]
        heading_range_deg = [-20.0, 20.0]
        height_m = 0.55

        [action]
        mode = "delta"
        out_of_range = "error"
        max_delta_rad = 0.05

        [control]
        sim_steps_per_env_step = 5
        kp = 2000
        kd = [30, 30, 30, 30, 30, 30, 30, 30, 30, 30, 30, 30]
        velocity_limit = false

        [physics]
        dt = 0.002
        ground_friction = 0.8

        [physics.rapier]
        solver_iterations = 4

        [physics.dart]

        [reset]
        spawn_xy_m = [1.0, -2.0]
        yaw_deg = 10.0
        yaw_noise_deg = 5.0
        joint_noise_rad = 0.02
    "#;
    let c = EnvConfig::from_toml_str(text, "full").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(c.task.norm_rew_scaling, Some(10.0));
    assert_eq!(c.task.exp_rew_scaling, None);
    assert_eq!(c.task.max_time_steps, 500);
    assert_eq!(c.goal.mode, GoalMode::Random);
    assert_eq!(c.goal.height_m, Some(0.55));
    assert_eq!(c.action.mode, ActionMode::Delta);
    assert_eq!(c.control.kp, Gains::All(2000.0));
    assert_eq!(c.control.kd, Gains::PerJoint(vec![30.0; 12]));
    assert!(!c.control.velocity_limit);
    assert_eq!(c.physics.params.dt, 0.002);
    assert_eq!(c.env_dt(), 0.01);
    assert_eq!(c.reset.spawn_xy_m, [1.0, -2.0]);
    // Round trip through the TOML writer.
    let again = EnvConfig::from_toml_str(&c.to_toml_string(), "round trip")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(again, c);
    // The engine table reaches the backend.
    let env =
        Env::<RapierBackend>::new(hyq_physics::bundled::hyq(), c).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(env.backend_options().solver_iterations, 4);
    assert_eq!(env.actuator().kp(), &[2000.0; 12]);
}

/// A table is registered once, by its row in `EnvConfig`: the list of tables, the tables of the
/// written-out configuration and the tables whose keys are checked are the same. The optional
/// tables (`[terrain]`, `[observation]`, `[randomize]`, the velocity task's `[command]`
/// and `[velocity]`, and the goal task's `[regularizers]`) are written when they hold anything
/// but their defaults, so the default configuration is written as it was before they existed.
#[test]
fn every_registered_table_is_written_read_and_checked() {
    const OPTIONAL: [&str; 6] = [
        "command",
        "observation",
        "randomize",
        "regularizers",
        "terrain",
        "velocity",
    ];
    let tables_of = |c: &EnvConfig| -> Vec<String> {
        let written: toml::Table =
            toml::from_str(&c.to_toml_string()).unwrap_or_else(|e| panic!("{e}"));
        let mut tables: Vec<String> = written.keys().cloned().collect();
        tables.sort_unstable();
        tables
    };
    let mut registered = EnvConfig::TABLES.to_vec();
    registered.sort_unstable();
    let mut all = EnvConfig::default();
    all.set_all(&[
        ("terrain.kind", "\"rough\""),
        ("observation.extra", "[\"goal_vector\"]"),
        ("randomize.ground_friction", "[0.5, 1.25]"),
        ("task.kind", "velocity"),
        ("command.lin_vel_x", "[0, 1]"),
        ("velocity.preset", "playground"),
    ])
    .unwrap_or_else(|e| panic!("{e}"));
    // `[regularizers]` belongs to the goal task, the other tables above to the velocity task.
    let mut goal = EnvConfig::default();
    goal.set("regularizers.torques", "-1e-5")
        .unwrap_or_else(|e| panic!("{e}"));
    let mut written = tables_of(&all);
    let more: Vec<String> = tables_of(&goal)
        .into_iter()
        .filter(|t| !written.contains(t))
        .collect();
    written.extend(more);
    written.sort_unstable();
    assert_eq!(written, registered);
    let required: Vec<&str> = registered
        .iter()
        .copied()
        .filter(|t| !OPTIONAL.contains(t))
        .collect();
    assert_eq!(tables_of(&EnvConfig::default()), required);
    for table in EnvConfig::TABLES {
        let msg = parse_err(&format!("[{table}]\nno_such_key = 1\n"));
        assert!(msg.contains("no_such_key"), "{table}: {msg}");
        let mut c = EnvConfig::default();
        let msg = c
            .set(&format!("{table}.no_such_key"), "1")
            .expect_err("refused")
            .to_string();
        assert!(msg.contains("no_such_key"), "{table}: {msg}");
    }
}

#[test]
fn unknown_keys_are_errors_naming_the_key() {
    for (text, key) in [
        ("[task]\nfall_penaltyy = 1", "fall_penaltyy"),
        ("[goal]\ndistance = 1", "distance"),
        ("[action]\nmodee = \"absolute\"", "modee"),
        ("[control]\nsubsteps = 3", "substeps"),
        ("[physics]\ntimestep = 0.001", "timestep"),
        ("[reset]\nnoise = 0.1", "noise"),
        ("[rewards]\nx = 1", "rewards"),
        ("[physics.rapeir]\nsolver_iterations = 1", "physics.rapeir"),
    ] {
        let msg = parse_err(text);
        assert!(msg.contains(key), "{msg:?} should name {key:?}");
        assert!(
            !msg.contains('\n') && msg.contains("line "),
            "one line with the line number: {msg:?}"
        );
    }
    // An unknown key inside an engine table is caught when an env on that engine is built.
    let c = EnvConfig::from_toml_str("[physics.rapier]\niterations = 3", "t")
        .unwrap_or_else(|e| panic!("{e}"));
    let msg = Env::<RapierBackend>::new(hyq_physics::bundled::hyq(), c)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        msg.contains("physics.rapier") && msg.contains("iterations"),
        "{msg}"
    );
}

#[test]
fn invalid_values_are_errors_naming_the_key_and_value() {
    for (text, needles) in [
        (
            "[task]\naccepted_error = -1.0",
            &["accepted_error", "-1"][..],
        ),
        ("[goal]\ndistance_m = 0.0", &["goal.distance_m", "0"]),
        ("[goal]\nmode = \"fixed\"", &["goal.position", "fixed"]),
        (
            "[goal]\ndistance_range_m = [5.0, 2.0]",
            &["goal.distance_range_m", "5"],
        ),
        (
            "[goal]\nheading_range_deg = [0.0, 200.0]",
            &["goal.heading_range_deg", "200"],
        ),
        ("[goal]\nmode = \"sideways\"", &["sideways"]),
        (
            "[action]\nmax_delta_rad = -0.1",
            &["action.max_delta_rad", "-0.1"],
        ),
        (
            "[action]\nmax_offset_rad = 0",
            &["action.max_offset_rad", "0"],
        ),
        (
            "[control]\nsim_steps_per_env_step = 0",
            &["control.sim_steps_per_env_step", "0"],
        ),
        ("[control]\nkp = -5", &["control.kp", "-5"]),
        ("[control]\nkp = \"stiff\"", &["stiff"]),
        ("[physics]\ndt = 0.5", &["physics.dt", "0.5"]),
        ("[reset]\nyaw_deg = 270", &["reset.yaw_deg", "270"]),
        (
            "[reset]\njoint_noise_rad = -0.1",
            &["reset.joint_noise_rad", "-0.1"],
        ),
    ] {
        let msg = parse_err(text);
        for needle in needles {
            assert!(msg.contains(needle), "{msg:?} should contain {needle:?}");
        }
    }
    // Per-joint gains of the wrong length are caught against the robot.
    let c = EnvConfig::from_toml_str("[control]\nkd = [1, 2, 3]", "t")
        .unwrap_or_else(|e| panic!("{e}"));
    let msg = Env::<RapierBackend>::new(hyq_physics::bundled::hyq(), c)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(msg.contains("control.kd") && msg.contains("12"), "{msg}");
}

#[test]
fn set_overrides_by_dotted_key() {
    let mut c = EnvConfig::default();
    c.set("task.fall_penalty", "1.5")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set("task.exp_rew_scaling", "off")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set("action.mode", "absolute")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set("action.mode", "\"delta\"")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set("control.kp", "[1,2,3,4,5,6,7,8,9,10,11,12]")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set("physics.rapier.solver_iterations", "4")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set("physics.gravity", "[0, 0, -1.62]")
        .unwrap_or_else(|e| panic!("{e}"));
    c.set_all(&[("goal.mode", "fixed"), ("goal.position", "[5, 1, 0.6]")])
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(c.task.fall_penalty, 1.5);
    assert_eq!(c.task.exp_rew_scaling, None);
    assert_eq!(c.action.mode, ActionMode::Delta);
    assert_eq!(
        c.control.kp,
        Gains::PerJoint((1..=12).map(f64::from).collect())
    );
    assert_eq!(c.physics.params.gravity, [0.0, 0.0, -1.62]);
    assert_eq!(c.goal.position, Some([5.0, 1.0, 0.6]));
    let options: RapierOptions = c
        .physics
        .engine_options("rapier")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(options.solver_iterations, 4);
}

#[test]
fn bad_overrides_name_the_key_and_change_nothing() {
    let mut c = EnvConfig::default();
    c.set("task.fall_penalty", "2")
        .unwrap_or_else(|e| panic!("{e}"));
    let before = c.clone();
    for (key, value, needles) in [
        (
            "task.fall_penaltyy",
            "1",
            &["task.fall_penaltyy", "fall_penaltyy"][..],
        ),
        ("tasks.fall_penalty", "1", &["tasks.fall_penalty"]),
        ("fall_penalty", "1", &["fall_penalty", "table.name"]),
        ("task.fall_penalty", "-3", &["task.fall_penalty", "-3"]),
        (
            "task.max_time_steps",
            "1.5",
            &["task.max_time_steps", "1.5"],
        ),
        ("goal.distance_m", "abc", &["goal.distance_m", "abc"]),
        ("physics.rapeir.solver_iterations", "2", &["physics.rapeir"]),
        ("reset.yaw_deg", "500", &["reset.yaw_deg", "500"]),
        ("goal.mode", "fixed", &["goal.position"]),
    ] {
        let err = c.set(key, value).err();
        let msg = err.as_ref().map(|e| e.to_string()).unwrap_or_default();
        for needle in needles {
            assert!(
                msg.contains(needle),
                "set({key}, {value}): {msg:?} lacks {needle:?}"
            );
        }
        assert!(
            matches!(
                err,
                Some(ConfigError::Set { .. } | ConfigError::Invalid { .. })
            ),
            "{err:?}"
        );
        assert_eq!(c, before, "set({key}, {value}) changed the configuration");
    }
}

#[test]
fn a_config_file_is_read_from_disk_and_a_missing_one_names_the_path() {
    let dir = std::env::temp_dir().join(format!("hyq-env-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("env.toml");
    std::fs::write(&path, "[task]\nfall_penalty = 4.0\n").unwrap_or_else(|e| panic!("{e}"));
    let c = EnvConfig::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(c.task.fall_penalty, 4.0);
    let missing = dir.join("missing.toml");
    let msg = EnvConfig::from_file(&missing)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(msg.contains("missing.toml"), "{msg}");
    std::fs::remove_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
}

/// Overrides, and the words their error must contain.
type Case<'a> = (&'a [(&'a str, &'a str)], &'a [&'a str]);

#[test]
fn goal_keys_of_another_mode_are_refused_by_name() {
    // Each key is read in some modes only; given in another, it used to be silently ignored.
    let cases: &[Case<'_>] = &[
        (
            &[("goal.position", "[9, 9, 0.6]")],
            &["goal.position", "\"fixed\"", "\"ahead\""],
        ),
        (
            &[
                ("goal.mode", "fixed"),
                ("goal.position", "[1, 2, 0.6]"),
                ("goal.distance_m", "9"),
            ],
            &["goal.distance_m", "\"ahead\"", "\"fixed\""],
        ),
        (
            &[("goal.distance_range_m", "[1, 2]")],
            &["goal.distance_range_m", "\"random\""],
        ),
        (
            &[("goal.mode", "random"), ("goal.distance_m", "4")],
            &["goal.distance_m", "\"random\""],
        ),
        (
            &[("goal.heading_range_deg", "[-10, 10]")],
            &["goal.heading_range_deg", "\"random\""],
        ),
        (
            &[
                ("goal.mode", "fixed"),
                ("goal.position", "[1, 2, 0.6]"),
                ("goal.height_m", "0.5"),
            ],
            &["goal.height_m", "\"fixed\""],
        ),
    ];
    for (pairs, words) in cases {
        let mut c = EnvConfig::default();
        let e = c.set_all(pairs).expect_err("refused").to_string();
        for w in *words {
            assert!(e.contains(w), "{pairs:?}: {e} lacks {w}");
        }
        assert_eq!(c, EnvConfig::default());
    }
    // The same in a file.
    let e = parse_err("[goal]\nmode = \"random\"\nposition = [1, 2, 0.6]\n");
    assert!(e.contains("goal.position"), "{e}");
    // A mode's own keys, and the other modes' keys at their defaults (as a written-out
    // configuration holds them), are accepted; so is switching modes on top of the defaults.
    for pairs in [
        &[
            ("goal.mode", "random"),
            ("goal.distance_range_m", "[1, 2]"),
            ("goal.height_m", "0.5"),
        ][..],
        &[("goal.mode", "fixed"), ("goal.position", "[1, 2, 0.6]")][..],
        &[("goal.distance_m", "4"), ("goal.height_m", "0.5")][..],
    ] {
        let mut c = EnvConfig::default();
        c.set_all(pairs)
            .unwrap_or_else(|e| panic!("{pairs:?}: {e}"));
        let text = c.to_toml_string();
        assert_eq!(EnvConfig::from_toml_str(&text, "written").ok(), Some(c));
    }
}

#[test]
fn terrain_keys_of_another_kind_are_refused_by_name() {
    // Each key is read by some kinds only; given with another, it used to be silently ignored.
    let cases: &[Case<'_>] = &[
        (
            &[("terrain.step_height_m", "0.2")],
            &["terrain.step_height_m", "0.2", "\"stairs\"", "\"flat\""],
        ),
        (
            &[("terrain.kind", "slope"), ("terrain.amplitude_m", "0.1")],
            &["terrain.amplitude_m", "\"rough\"", "\"slope\""],
        ),
        (
            &[
                ("terrain.kind", "rough"),
                ("terrain.file", "\"heights.npy\""),
            ],
            &[
                "terrain.file",
                "heights.npy",
                "\"heightfield\"",
                "\"rough\"",
            ],
        ),
        (
            &[("terrain.kind", "stairs"), ("terrain.seed", "\"episode\"")],
            &["terrain.seed", "episode", "\"rough\"", "\"stairs\""],
        ),
        (
            &[("terrain.kind", "rough"), ("terrain.stairs", "down")],
            &["terrain.stairs", "\"down\""],
        ),
        (
            &[("terrain.size_m", "[4, 4]")],
            &["terrain.size_m", "\"flat\""],
        ),
        (
            &[
                ("terrain.kind", "slope"),
                ("terrain.direction_deg", "90"),
                ("terrain.start_m", "2"),
            ],
            &["terrain.start_m", "\"stairs\"", "\"slope\""],
        ),
    ];
    for (pairs, words) in cases {
        let mut c = EnvConfig::default();
        let e = c.set_all(pairs).expect_err("refused").to_string();
        for w in *words {
            assert!(e.contains(w), "{pairs:?}: {e} lacks {w}");
        }
        assert!(!e.contains('\n'), "one line: {e}");
        assert_eq!(c, EnvConfig::default());
    }
    // The same in a file.
    let e = parse_err("[terrain]\nkind = \"rough\"\nslope_deg = 5\n");
    assert!(
        e.contains("terrain.slope_deg") && e.contains("\"slope\""),
        "{e}"
    );
    // A kind's own keys, and the other kinds' keys at their defaults (as a written-out
    // configuration holds them), are accepted, and a written table reads back as it was.
    for pairs in [
        &[
            ("terrain.kind", "stairs"),
            ("terrain.direction_deg", "90"),
            ("terrain.stairs", "down"),
        ][..],
        &[
            ("terrain.kind", "rough"),
            ("terrain.seed", "\"episode\""),
            ("terrain.curriculum", "true"),
        ][..],
        &[
            ("terrain.kind", "slope"),
            ("terrain.amplitude_m", "0.05"),
            ("terrain.slope_deg", "-5"),
        ][..],
    ] {
        let mut c = EnvConfig::default();
        c.set_all(pairs)
            .unwrap_or_else(|e| panic!("{pairs:?}: {e}"));
        let text = c.to_toml_string();
        assert!(
            text.contains("[terrain]") && text.contains("amplitude_m"),
            "{text}"
        );
        assert_eq!(EnvConfig::from_toml_str(&text, "written").ok(), Some(c));
    }
}

#[test]
fn messages_name_the_key_at_its_line_in_plain_words_and_short_numbers() {
    let file = |text: &str| parse_err(text);
    let set = |key: &str, value: &str| {
        let mut c = EnvConfig::default();
        c.set(key, value).expect_err("refused").to_string()
    };
    let checks: Vec<(String, &[&str], &[&str])> = vec![
        // A NaN was reported at the line of the [task] header (line 1 of a one-table file).
        (
            file(
                "# c\n[goal]\nmode = \"ahead\"\n\n[task]\nmax_time_steps = 10\nfall_penalty = nan\n",
            ),
            &["line 7", "task.fall_penalty", "NaN"],
            &["line 5"],
        ),
        (
            file("task.fall_penalty = nan\n"),
            &["line 1", "task.fall_penalty"],
            &[],
        ),
        (
            file(
                "[task]\nheight_penalty = {nominal_height_m = 0.6, tolerance_m = -1, rate_per_m = 1}\n",
            ),
            &["line 2", "task.height_penalty.tolerance_m"],
            &[],
        ),
        (
            file("[goal]\n\ndistance_m = -1e300\n"),
            &["line 3", "goal.distance_m", "-1e300"],
            &[],
        ),
        // Hundreds of digits.
        (
            set("task.fall_penalty", "-1e308"),
            &["-1e308"],
            &["00000000"],
        ),
        // "invalid type: string" for a number too large for TOML's integers.
        (
            set("task.max_time_steps", "18446744073709551615"),
            &[
                "task.max_time_steps",
                "18446744073709551615",
                "9223372036854775807",
            ],
            &["string"],
        ),
        // Rust's debug text.
        (set("control.kp", "-1"), &["control.kp = -1"], &["All("]),
        (
            set("control.kd", "[1, -2]"),
            &["control.kd = [1.0, -2.0]"],
            &["PerJoint"],
        ),
        (
            file("[control]\nkp = -1\n"),
            &["line 2", "control.kp = -1"],
            &["All("],
        ),
    ];
    for (message, present, absent) in checks {
        for p in present {
            assert!(message.contains(p), "{message:?} lacks {p:?}");
        }
        for a in absent {
            assert!(!message.contains(a), "{message:?} holds {a:?}");
        }
        assert!(
            message.len() < 300 && !message.contains('\n'),
            "{message:?}"
        );
    }
}

#[test]
fn a_config_file_is_read_up_to_its_size_limit_so_endless_input_is_refused() {
    // /dev/zero used to be read until memory ran out; now only a regular file is read.
    let msg = EnvConfig::from_file("/dev/zero")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        msg.contains("/dev/zero") && msg.contains("is not a regular file"),
        "{msg}"
    );
    let dir = std::env::temp_dir().join(format!("hyq-env-config-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("big.toml");
    let mut text = "[task]\nfall_penalty = 4.0\n#".to_owned();
    text.push_str(&"x".repeat(hyq_env::config::CONFIG_FILE_MAX_BYTES - text.len()));
    std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        EnvConfig::from_file(&path).is_ok(),
        "exactly the limit is read"
    );
    text.push('x');
    std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        EnvConfig::from_file(&path).is_err(),
        "one byte more is refused"
    );
    std::fs::remove_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_number_past_a_floats_range_is_named_as_such_not_as_a_string() {
    for value in ["1e400", "-2e308", "1_0e400"] {
        let mut c = EnvConfig::default();
        let msg = c
            .set_all(&[("task.fall_penalty", value)])
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            msg.contains("task.fall_penalty") && msg.contains("beyond a float's range"),
            "{value}: {msg}"
        );
        assert!(!msg.contains("string"), "{value}: {msg}");
    }
}
