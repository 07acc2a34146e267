//! Invariant: the command line's bad inputs (a new user's mistakes and an attacker's inputs)
//! each end as documented: a usage error (status 2) or a run-time error (status 1) printed as
//! one line `hyq: error: …` naming what was wrong, never a panic, a hang or hundreds of digits;
//! and the odd-but-valid inputs run. Cases with a file of their own:
//! closed and full stdout (`closed_or_full_stdout.rs`), outputs kept on failure
//! (`outputs_are_replaced_only_by_a_finished_run.rs`), no null in records
//! (`records_and_summaries_hold_no_null.rs`).

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::Path;

use common::{hyq, hyq_ok, scratch, stderr};

/// `hyq args` exits with `status` and one error line containing every one of `words`, with no
/// panic and no run of 30 digits (a number printed in full instead of its short form).
#[track_caller]
fn fails(status: i32, args: &[&str], words: &[&str]) {
    let out = hyq(args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(status), "hyq {args:?}: {err}");
    assert_eq!(
        err.lines().count(),
        1,
        "hyq {args:?}: one line, got:\n{err}"
    );
    assert!(err.starts_with("hyq: error: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!err.contains(&"0".repeat(30)), "a number in full: {err}");
    for w in words {
        assert!(
            err.contains(w),
            "hyq {args:?}: the error does not name `{w}`: {err}"
        );
    }
}

/// `hyq run --set …` with these overrides is a usage error naming `words`.
#[track_caller]
fn bad_set(sets: &[&str], words: &[&str]) {
    let mut args = vec!["run"];
    for s in sets {
        args.extend(["--set", s]);
    }
    fails(2, &args, words);
}

fn write(name: &str, bytes: &[u8]) -> String {
    let path = scratch(name);
    std::fs::write(&path, bytes).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn configuration_keys_and_values() {
    // unknown keys and tables.
    bad_set(&["task.bogus=1"], &["bogus"]);
    bad_set(&["bogus.key=1"], &["bogus"]);
    bad_set(&["physics.bogus.x=1"], &["bogus"]);
    bad_set(&["physics.rapier.bogus=1"], &["bogus"]);
    // malformed --set.
    for s in [
        "task.fall_penalty",
        "=5",
        "task=1",
        "task..x=1",
        "task.fall_penalty.x=1",
    ] {
        fails(2, &["run", "--set", s], &["--set"]);
    }
    // a key of another terrain kind, which would be ignored.
    bad_set(
        &["terrain.kind=\"slope\"", "terrain.step_height_m=0.2"],
        &["terrain.step_height_m", "\"stairs\"", "\"slope\""],
    );
    // wrong types.
    bad_set(&["task.fall_penalty=abc"], &["fall_penalty"]);
    bad_set(&["control.velocity_limit=maybe"], &["velocity_limit"]);
    bad_set(
        &["physics.rapier.solver_iterations=1e1"],
        &["solver_iterations"],
    );
    // NaN, infinities and negatives of every real [task] key.
    for key in [
        "fall_penalty",
        "base_rew_scaling",
        "exp_rew_scaling",
        "norm_rew_scaling",
        "reach_target_bonus_reward",
        "accepted_error",
        "accepted_dist_to_bounds",
        "reach_bounds_penalty",
        "yaw_limit_deg",
        "pitch_limit_deg",
    ] {
        for value in ["nan", "inf", "-inf", "-1"] {
            bad_set(&[&format!("task.{key}={value}")], &[key]);
        }
    }
    // zero where > 0 is required.
    for key in [
        "exp_rew_scaling",
        "base_rew_scaling",
        "norm_rew_scaling",
        "accepted_error",
    ] {
        bad_set(&[&format!("task.{key}=0")], &[key]);
    }
    // max_time_steps, and integers beyond TOML's.
    for value in ["0", "-1", "1.5", "1e30"] {
        bad_set(
            &[&format!("task.max_time_steps={value}")],
            &["max_time_steps"],
        );
    }
    bad_set(
        &["task.max_time_steps=18446744073709551615"],
        &["max_time_steps", "9223372036854775807"],
    );
}

#[test]
fn values_that_would_emit_non_finite_numbers_or_panic() {
    // scalings whose terms or sums overflow.
    bad_set(
        &["task.exp_rew_scaling=1000"],
        &["task.exp_rew_scaling", "500"],
    );
    bad_set(
        &["task.base_rew_scaling=1e308"],
        &["task.base_rew_scaling", "1e308"],
    );
    bad_set(
        &["task.norm_rew_scaling=1.5e308", "goal.distance_m=1.5"],
        &["task.norm_rew_scaling"],
    );
    // goals so far that D overflows, or that only reset would have found.
    bad_set(
        &["goal.mode=fixed", "goal.position=[1e308, 1e308, 0]"],
        &["goal.position", "100 m"],
    );
    bad_set(&["goal.distance_m=1e308"], &["goal.distance_m"]);
    bad_set(&["goal.height_m=1e308"], &["goal.height_m"]);
    bad_set(
        &["goal.mode=fixed", "goal.position=[1e200, 0, 0]"],
        &["goal.position"],
    );
    bad_set(
        &["goal.mode=random", "goal.distance_range_m=[1e300, 1e300]"],
        &["goal.distance_range_m"],
    );
    // bad goal values.
    for s in [
        "goal.distance_m=nan",
        "goal.distance_m=0",
        "goal.distance_m=-1",
        "goal.distance_m=inf",
        "goal.heading_range_deg=[nan, 0]",
        "goal.heading_range_deg=[-181, 0]",
        "goal.height_m=nan",
        "goal.mode=bogus",
    ] {
        let key = s.split('=').next().unwrap();
        bad_set(&[s], &[key]);
    }
    for s in ["[1, 2]", "[nan, 0, 0]"] {
        bad_set(
            &["goal.mode=fixed", &format!("goal.position={s}")],
            &["goal.position"],
        );
    }
    for s in ["[0, 1]", "[2, 1]", "[1, inf]", "[1, 2, 3]"] {
        bad_set(
            &["goal.mode=random", &format!("goal.distance_range_m={s}")],
            &["goal.distance_range_m"],
        );
    }
    bad_set(&["goal.mode=fixed"], &["goal.position"]);
    // a goal at the start.
    bad_set(
        &["goal.mode=fixed", "goal.position=[0, 0, 0.6003]"],
        &["goal"],
    );
    // a goal key the mode does not read.
    bad_set(&["goal.position=[9, 9, 0.6]"], &["goal.position", "fixed"]);
    bad_set(
        &[
            "goal.mode=fixed",
            "goal.position=[1, 1, 0.6]",
            "goal.distance_m=9",
        ],
        &["goal.distance_m", "ahead"],
    );
    // spawn points beyond what rapier's f32 holds faithfully.
    for s in ["[1e39, 0]", "[1e5, 0]"] {
        bad_set(
            &[&format!("reset.spawn_xy_m={s}")],
            &["reset.spawn_xy_m", "f32"],
        );
    }
    // [reset] ranges.
    for s in [
        "reset.spawn_xy_m=[nan, 0]",
        "reset.spawn_xy_m=[inf, 0]",
        "reset.spawn_xy_m=[1, 2, 3]",
        "reset.yaw_deg=nan",
        "reset.yaw_deg=181",
        "reset.yaw_noise_deg=-1",
        "reset.yaw_noise_deg=nan",
        "reset.joint_noise_rad=-1",
        "reset.joint_noise_rad=nan",
        "reset.joint_noise_rad=inf",
        "reset.bogus=1",
    ] {
        let key = s.split('=').next().unwrap().rsplit('.').next().unwrap();
        bad_set(&[s], &[key]);
    }
    // joint noise that panicked the sampler.
    bad_set(&["reset.joint_noise_rad=1e308"], &["reset.joint_noise_rad"]);
}

#[test]
fn actions_control_and_physics() {
    bad_set(&["action.mode=bogus"], &["mode"]);
    bad_set(&["action.out_of_range=bogus"], &["out_of_range"]);
    for v in ["nan", "0", "-1", "inf"] {
        bad_set(
            &[&format!("action.max_delta_rad={v}")],
            &["action.max_delta_rad"],
        );
    }
    for v in ["0", "1001", "-1", "4294967296", "1.5"] {
        bad_set(
            &[&format!("control.sim_steps_per_env_step={v}")],
            &["sim_steps_per_env_step"],
        );
    }
    // gains, named without Rust's debug text.
    for v in [
        "-1",
        "nan",
        "inf",
        "[1, 2]",
        "[]",
        "[-1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]",
    ] {
        let out = hyq(&["run", "--set", &format!("control.kp={v}")]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains("control.kp") || err.contains("kp"), "{err}");
        assert!(!err.contains("All(") && !err.contains("PerJoint"), "{err}");
    }
    for v in ["-20", "nan"] {
        bad_set(&[&format!("control.kd={v}")], &["control.kd"]);
    }
    // absurd time steps.
    for v in ["0", "-0.001", "nan", "inf", "0.1001"] {
        bad_set(&[&format!("physics.dt={v}")], &["dt"]);
    }
    // accepted extremes run, ending as diverged where the physics blows up.
    let out = hyq_ok(&["run", "--json", "--set", "physics.dt=0.1"]);
    assert!(out.contains("\"diverged\""), "{out}");
    hyq_ok(&[
        "run",
        "--set",
        "task.max_time_steps=20",
        "--set",
        "control.kp=1e308",
    ]);
    let out = hyq_ok(&["run", "--json", "--set", "physics.gravity=[0, 0, 1e308]"]);
    assert!(out.contains("\"diverged\""), "{out}");
}

#[test]
fn configuration_files() {
    // an empty file is the defaults.
    let empty = write("empty.toml", b"");
    hyq_ok(&["run", "--config", &empty, "--set", "task.max_time_steps=2"]);
    // malformed TOML, at its line.
    let malformed = write("malformed.toml", b"[task\nfall_penalty=");
    fails(
        2,
        &["run", "--config", &malformed],
        &["malformed.toml", "line 1"],
    );
    // binary garbage, NUL.
    let garbage: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    let garbage = write("garbage.toml", &garbage);
    fails(2, &["run", "--config", &garbage], &["garbage.toml"]);
    let nul = write("nul.toml", b"[task]\n\0");
    fails(2, &["run", "--config", &nul], &["nul.toml"]);
    // a directory, a missing file.
    let dir = scratch("adir");
    let _ = std::fs::remove_file(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    fails(2, &["run", "--config", dir.to_str().unwrap()], &["adir"]);
    fails(
        2,
        &["run", "--config", "/nonexistent/missing.toml"],
        &["missing.toml"],
    );
    // a NaN literal, at the key's own line.
    let nan = write(
        "nan.toml",
        b"[task]\nmax_time_steps = 10\nfall_penalty = nan\n",
    );
    fails(
        2,
        &["run", "--config", &nan],
        &["line 3", "task.fall_penalty"],
    );
    let dup = write("dup.toml", b"[task]\nfall_penalty = 1\nfall_penalty = 2\n");
    fails(2, &["run", "--config", &dup], &["dup.toml"]);
    // endless input: a device is not read at all.
    fails(
        2,
        &["run", "--config", "/dev/zero"],
        &["/dev/zero", "is not a regular file"],
    );
}

#[test]
fn command_line_arguments() {
    for args in [
        &["run", "--episodes", "0"][..],
        &["run", "--seed", "-1"],
        &["run", "--seed", "18446744073709551616"],
        &["run", "--policy", "walk"],
        &["run", "--bogus"],
        &["frobnicate"],
        &["render", "--out", "r.png"],
        &["render", "--fps", "0", "--out", "x.gif"],
        &["render", "--width", "15", "--out", "x.gif"],
        &["render", "--width", "4097", "--out", "x.gif"],
        &["bench", "--steps", "0"],
        &["bench", "--num-envs", "4097"],
        &["bench", "--threads", "2"],
        &["soak", "--steps", "0"],
    ] {
        fails(2, args, &[]);
    }
}

/// A record of `steps` steps, written by `hyq run`.
fn record(name: &str, steps: u32) -> String {
    let path = scratch(name);
    hyq_ok(&[
        "run",
        "--set",
        &format!("task.max_time_steps={steps}"),
        "--record",
        path.to_str().unwrap(),
    ]);
    path.to_str().unwrap().to_owned()
}

#[test]
fn records_and_plots() {
    // a record path in a missing directory, or a directory.
    fails(
        2,
        &["run", "--record", "/nonexistent/sub/x.jsonl"],
        &["--record"],
    );
    let dir = scratch("record-dir");
    let _ = std::fs::remove_file(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    fails(
        2,
        &["run", "--record", dir.to_str().unwrap()],
        &["--record"],
    );

    let good = record("plot-good.jsonl", 5);
    let text = std::fs::read_to_string(&good).unwrap();
    let out_dir = scratch("plot-out");
    let out = out_dir.to_str().unwrap();
    // a torn last line is left out with a warning; the whole lines are plotted.
    let torn = write("plot-torn.jsonl", &text.as_bytes()[..text.len() - 40]);
    let run = hyq(&["plot", &torn, "--out", out]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(stderr(&run).starts_with("hyq: warning: ") && stderr(&run).contains("line 5"));
    // nothing to plot (empty, blank, or only a torn line).
    for (name, bytes) in [
        ("plot-empty.jsonl", &b""[..]),
        ("plot-blank.jsonl", b"\n\n  \n"),
        ("plot-trunc.jsonl", &text.as_bytes()[..700]),
    ] {
        let path = write(name, bytes);
        let run = hyq(&["plot", &path, "--out", out]);
        assert_eq!(run.status.code(), Some(2), "{name}: {}", stderr(&run));
        assert!(stderr(&run).contains("no step"), "{name}: {}", stderr(&run));
    }
    // NaN, null, not JSON, an array, binary, missing, a directory.
    let first = text.lines().next().unwrap();
    let reward = first.find("\"reward\":").unwrap() + 9;
    let end = reward + first[reward..].find(',').unwrap();
    for (name, line) in [
        (
            "plot-nan.jsonl",
            format!("{}NaN{}", &first[..reward], &first[end..]),
        ),
        (
            "plot-null.jsonl",
            format!("{}null{}", &first[..reward], &first[end..]),
        ),
        ("plot-notjson.jsonl", "hello".to_owned()),
        ("plot-array.jsonl", "[1, 2, 3]".to_owned()),
    ] {
        let path = write(name, format!("{line}\n").as_bytes());
        fails(2, &["plot", &path, "--out", out], &["line 1"]);
    }
    let binary = write("plot-binary.jsonl", &[0xff, 0xfe, 0x00, 0x01, b'\n']);
    fails(2, &["plot", &binary, "--out", out], &[]);
    fails(2, &["plot", "/nonexistent/x.jsonl"], &["x.jsonl"]);
    fails(2, &["plot", dir.to_str().unwrap(), "--out", out], &[]);
    // endless input: a device is not read at all.
    fails(
        2,
        &["plot", "/dev/zero", "--out", out],
        &["is not a regular file"],
    );
    // values spanning more than f64 holds: the plot finishes (it used to hang).
    let mut huge = String::new();
    for (i, line) in text.lines().enumerate() {
        let v = if i % 2 == 0 { "1e308" } else { "-1e308" };
        let start = line.find("\"reward\":").unwrap() + 9;
        let end = start + line[start..].find(',').unwrap();
        huge.push_str(&format!("{}{v}{}\n", &line[..start], &line[end..]));
    }
    let huge = write("plot-huge.jsonl", huge.as_bytes());
    hyq_ok(&["plot", &huge, "--out", out]);
    // --out an existing file.
    fails(2, &["plot", &good, "--out", &good], &[]);
    assert!(Path::new(&good).is_file());
}

#[test]
fn randomization_keys_and_values() {
    // Reversed and non-finite ranges.
    bad_set(
        &["randomize.ground_friction=[1.0, 0.5]"],
        &["randomize.ground_friction", "[1.0, 0.5]", "lo <= hi"],
    );
    bad_set(
        &["randomize.link_mass_scale=[nan, 1]"],
        &["randomize.link_mass_scale", "[NaN, 1.0]", "finite"],
    );
    bad_set(
        &["randomize.trunk_added_mass_kg=[-1, inf]"],
        &["randomize.trunk_added_mass_kg", "inf", "finite"],
    );
    bad_set(
        &["randomize.push_velocity_xy_mps=[1, 0.5]"],
        &["randomize.push_velocity_xy_mps", "[1.0, 0.5]"],
    );
    // A scale that can make a mass, a gain or an effort zero or negative.
    for key in ["kp_scale", "kd_scale", "effort_scale", "link_mass_scale"] {
        let set = format!("randomize.{key}=[0, 1]");
        bad_set(
            &[&set],
            &[&format!("randomize.{key}"), "[0.0, 1.0]", "lo > 0"],
        );
    }
    // Known only against the robot: HyQ's trunk cannot lose 100 kg.
    bad_set(
        &["randomize.trunk_added_mass_kg=[-100, 0]"],
        &[
            "randomize.trunk_added_mass_kg",
            "[-100.0, 0.0]",
            "[1e-4, 1e6] kg",
        ],
    );
    // A delay longer than an env step (10 sub-steps by default).
    bad_set(
        &["randomize.actuator_delay_substeps=[0, 11]"],
        &[
            "randomize.actuator_delay_substeps",
            "[0, 11]",
            "longer than an env step",
        ],
    );
    // A negative or non-finite deviation, a probability above 1.
    bad_set(
        &["randomize.obs_noise.joint_speed=-1"],
        &["randomize.obs_noise.joint_speed", "-1"],
    );
    bad_set(
        &["randomize.obs_noise.quaternion=nan"],
        &["randomize.obs_noise.quaternion", "NaN"],
    );
    bad_set(
        &["randomize.obs_noise.contact_flip=1.5"],
        &["randomize.obs_noise.contact_flip", "1.5", "probability"],
    );
    // Pushes without a speed, or at intervals of 0.
    bad_set(
        &["randomize.push_interval_s=[2, 4]"],
        &["randomize.push_interval_s", "speed"],
    );
    bad_set(
        &[
            "randomize.push_interval_s=[0, 4]",
            "randomize.push_velocity_xy_mps=[0.5, 0.5]",
        ],
        &["randomize.push_interval_s", "[0.0, 4.0]", "lo > 0"],
    );
    // Unknown keys, a bad preset, a scalar for a range.
    bad_set(&["randomize.bogus=1"], &["randomize.bogus", "bogus"]);
    bad_set(
        &["randomize.obs_noise.bogus=1"],
        &["randomize.obs_noise.bogus"],
    );
    bad_set(&["randomize.preset=gym"], &["randomize.preset", "gym"]);
    // A name given as a number is said as such, not in the TOML parser's words.
    bad_set(
        &["randomize.preset=1"],
        &["randomize.preset", "one of this key's names, in quotes"],
    );
    bad_set(
        &["terrain.kind=1"],
        &["terrain.kind", "one of this key's names, in quotes"],
    );
    bad_set(
        &["randomize.ground_friction=0.5"],
        &["randomize.ground_friction", "0.5"],
    );

    // Before anything runs: no record is started, from --set or from --config.
    let record = scratch("randomize-bad.jsonl");
    let _ = std::fs::remove_file(&record);
    let config = write(
        "randomize-bad.toml",
        b"[randomize]\nground_friction = [1.0, 0.2]\n",
    );
    let record_arg = record.to_str().unwrap();
    fails(
        2,
        &["run", "--config", &config, "--record", record_arg],
        &["randomize.ground_friction", "[1.0, 0.2]"],
    );
    fails(
        2,
        &[
            "run",
            "--set",
            "randomize.kp_scale=[0, 1]",
            "--record",
            record_arg,
        ],
        &["randomize.kp_scale"],
    );
    assert!(!record.exists());
    // hyq compare --policy refuses before its output directory is made.
    let out = scratch("randomize-bad-compare");
    let _ = std::fs::remove_dir_all(&out);
    let policy = format!("mlp:{}", common::committed_policy().display());
    fails(
        2,
        &[
            "compare",
            "--backends",
            "rapier,rapier",
            "--policy",
            &policy,
            "--config",
            &config,
            "--out",
            out.to_str().unwrap(),
        ],
        &["randomize.ground_friction", "[1.0, 0.2]"],
    );
    assert!(!out.exists());
    // So does a scenario comparison (its plan, checked before --out is made, is the same for
    // two engines and three).
    fails(
        2,
        &[
            "compare",
            "--backends",
            "rapier,rapier",
            "--scenario",
            "trot",
            "--seconds",
            "0.1",
            "--set",
            "randomize.ground_friction=[1.0, 0.2]",
            "--out",
            out.to_str().unwrap(),
        ],
        &["randomize.ground_friction", "[1.0, 0.2]"],
    );
    assert!(!out.exists());
    // A push interval of 0 says why pushes need one, not why masses and gains do.
    bad_set(
        &[
            "randomize.push_interval_s=[0, 4]",
            "randomize.push_velocity_xy_mps=[0.5, 0.5]",
        ],
        &["randomize.push_interval_s", "push at every step"],
    );
}

/// A copy of the bundled HyQ (profile and URDF) in scratch directory `name`, with `profile` and
/// `urdf` edits (exact text, each present) applied; returns the profile's path.
fn robot(name: &str, profile: (&str, &str), urdf: (&str, &str)) -> String {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/hyq");
    let dir = scratch(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, (from, to)) in [("profile.toml", profile), ("hyq.urdf", urdf)] {
        let text = std::fs::read_to_string(assets.join(file)).unwrap();
        assert!(text.contains(from), "fixture: {from:?} not in {file}");
        std::fs::write(dir.join(file), text.replacen(from, to, 1)).unwrap();
    }
    dir.join("profile.toml").to_str().unwrap().to_owned()
}

const LF_HAA: &str = "{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2 }";

#[test]
fn robot_files_outside_the_bounds_table() {
    let none = ("", "");
    // Joint limits whose span overflows: refused at load, before the random policy (which
    // panicked in absolute mode) or the normalised map (NaN targets) can see them.
    let span = robot(
        "robot-span",
        (
            LF_HAA,
            "{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2, lower = -1.7e308, upper = 1.7e308 }",
        ),
        none,
    );
    for args in [
        &["run", "--policy", "random", "--set", "action.mode=absolute"][..],
        &["soak", "--steps", "10"],
        &["bench", "--steps", "10"],
    ] {
        let mut args = args.to_vec();
        args.extend(["--robot", &span]);
        fails(
            2,
            &args,
            &["robot-span", "joints[0].lower", "[-1000, 1000] rad"],
        );
    }
    // A deeply nested URDF (it overflowed the stack: an abort, status 134).
    let nest = format!("{}{}</robot>", "<a>".repeat(20_000), "</a>".repeat(20_000));
    let deep = robot("robot-deep", none, ("</robot>", &nest));
    fails(
        2,
        &["model", "--format", "json", "--robot", &deep],
        &["hyq.urdf", "nested more than 64 deep"],
    );
    // Endless files, a profile and a URDF named by one: devices are not read at all.
    fails(
        2,
        &["run", "--robot", "/dev/zero"],
        &["is not a regular file"],
    );
    let zero = robot(
        "robot-zero",
        ("urdf = \"hyq.urdf\"", "urdf = \"/dev/zero\""),
        none,
    );
    fails(
        2,
        &["run", "--robot", &zero],
        &["/dev/zero", "is not a regular file"],
    );
    // Masses an f32 engine cannot hold, a gait frequency the trot cannot use, a 1e6 m box (it
    // panicked the renderer), a spawn height that failed at reset with status 1.
    for (name, profile, urdf, words) in [
        (
            "robot-mass",
            none,
            ("<mass value=\"2.93\"/>", "<mass value=\"1e300\"/>"),
            &["lf_hipassembly", "kg"][..],
        ),
        (
            "robot-light",
            none,
            ("<mass value=\"2.93\"/>", "<mass value=\"1e-30\"/>"),
            &["lf_hipassembly", "kg"],
        ),
        (
            "robot-gait",
            ("frequency_hz = 3.0", "frequency_hz = 1e308"),
            none,
            &["gait.frequency_hz", "1e308"],
        ),
        (
            "robot-box",
            none,
            (
                "<box size=\"1.2898 0.5954 0.3737\"/>",
                "<box size=\"1e6 1e6 1e6\"/>",
            ),
            &["trunk", "[1e-4, 100] m"],
        ),
        (
            "robot-spawn",
            ("height = 0.6003", "height = 1e6"),
            none,
            &["spawn.height", "(0, 10] m"],
        ),
        (
            "robot-stand",
            ("standing_height = 0.5895", "standing_height = 1e308"),
            none,
            &["spawn.standing_height"],
        ),
    ] {
        let p = robot(name, profile, urdf);
        fails(2, &["run", "--policy", "trot", "--robot", &p], words);
    }
    let p = robot(
        "robot-render",
        none,
        (
            "<box size=\"1.2898 0.5954 0.3737\"/>",
            "<box size=\"1e6 1e6 1e6\"/>",
        ),
    );
    fails(
        2,
        &[
            "render",
            "--robot",
            &p,
            "--seconds",
            "0.1",
            "--out",
            scratch("r.gif").to_str().unwrap(),
        ],
        &["[1e-4, 100] m"],
    );
}

#[test]
fn robot_names_are_printed_as_names() {
    // Escapes, a forged line, an empty name: refused, never printed raw in a header.
    for (name, value) in [
        ("robot-name-esc", "x\\u001b[31mRED\\nhyq: fake"),
        ("robot-name-empty", ""),
    ] {
        let p = robot(
            name,
            ("name = \"hyq\"", &format!("name = \"{value}\"")),
            ("", ""),
        );
        let out = hyq(&["run", "--robot", &p, "--set", "task.max_time_steps=2"]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            !err.contains('\u{1b}') && err.lines().count() == 1,
            "{err:?}"
        );
        assert!(err.contains("robot profile field name"), "{err}");
    }
}

#[test]
fn urdfs_with_too_many_parts() {
    let mut extra = String::new();
    for i in 0..1001 {
        extra.push_str(&format!(
            "<link name=\"x{i}\"><collision><geometry><sphere radius=\"0.01\"/></geometry>\
             </collision></link><joint name=\"xj{i}\" type=\"fixed\"><parent link=\"trunk\"/>\
             <child link=\"x{i}\"/></joint>\n"
        ));
    }
    let p = robot(
        "robot-many",
        ("", ""),
        ("</robot>", &format!("{extra}</robot>")),
    );
    fails(
        2,
        &["run", "--robot", &p],
        &["links", "more than the 1000 allowed"],
    );
}

/// The committed policy file with its metadata's `env_config` replaced by `env_config` (a JSON
/// object of dotted keys to TOML values), written to scratch file `name`.
fn policy_with_env_config(name: &str, env_config: &str) -> String {
    let bytes = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/policies/hyq_walk.safetensors"),
    )
    .unwrap();
    let len = u64::from_le_bytes(bytes[..8].try_into().unwrap()) as usize;
    let mut header: serde_json::Value = serde_json::from_slice(&bytes[8..8 + len]).unwrap();
    header["__metadata__"]["env_config"] = serde_json::Value::String(env_config.to_owned());
    let header = serde_json::to_vec(&header).unwrap();
    let mut out = (header.len() as u64).to_le_bytes().to_vec();
    out.extend(header);
    out.extend(&bytes[8 + len..]);
    write(name, &out)
}

#[test]
fn policy_files() {
    // An endless policy file is not read (it was read until memory ran out).
    fails(
        2,
        &["run", "--policy", "mlp:/dev/zero"],
        &["/dev/zero", "is not a regular file"],
    );
    // A bad entry of the policy's own environment names the file, not `--set`.
    let bad = policy_with_env_config(
        "bad-env-config.safetensors",
        r#"{"action.mode": "\"offset\"", "action.max_offset_rad": "0.5", "task.exp_rew_scaling": "1000"}"#,
    );
    let out = hyq(&["run", "--policy", &format!("mlp:{bad}")]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bad-env-config.safetensors: its env_config")
            && err.contains("task.exp_rew_scaling")
            && !err.contains("--set"),
        "{err}"
    );
    // A bad `--set` beside it is still the user's.
    fails(
        2,
        &[
            "run",
            "--policy",
            &format!("mlp:{bad}"),
            "--set",
            "task.bogus=1",
        ],
        &["--set", "task.bogus"],
    );
}

#[test]
fn configuration_overrides_mean_what_they_say() {
    // A table key by key (each `--set` used to be read alone: `missing field tolerance_m`).
    hyq_ok(&[
        "run",
        "--set",
        "task.max_time_steps=3",
        "--set",
        "task.height_penalty.nominal_height_m=0.58",
        "--set",
        "task.height_penalty.tolerance_m=0.05",
        "--set",
        "task.height_penalty.rate_per_m=1",
    ]);
    // Text after a line break was dropped silently (1000 steps ran).
    fails(
        2,
        &["run", "--set", "task.fall_penalty=1\ntask.max_time_steps=3"],
        &["task.fall_penalty", "more than one TOML value"],
    );
    // A spawn point on the world's edge: every episode ended at step 1 as diverged.
    fails(
        2,
        &["run", "--set", "reset.spawn_xy_m=[-100,0]"],
        &["reset.spawn_xy_m", "no room"],
    );
    // A spawn point that pushes the default goal out names itself, not only the goal.
    fails(
        2,
        &["run", "--set", "reset.spawn_xy_m=[100,0]"],
        &["goal.distance_m", "reset.spawn_xy_m = [100.0, 0.0]"],
    );
}

#[test]
fn comparison_ledgers() {
    // An endless ledger stops at its cap (it was read until memory ran out).
    let out = scratch("ledger-zero-out");
    fails(
        2,
        &[
            "compare",
            "--scenario",
            "stand",
            "--backends",
            "rapier,rapier",
            "--seconds",
            "0.1",
            "--ledger",
            "/dev/zero",
            "--out",
            out.to_str().unwrap(),
        ],
        &["/dev/zero", "is not a regular file"],
    );
}

#[test]
fn output_errors_name_the_output_not_its_hidden_temporary_file() {
    // Each output is staged in a hidden `.NAME.xxxxxx.partial` beside it; the messages named
    // that file instead of the one asked for.
    for args in [
        &[
            "run",
            "--set",
            "task.max_time_steps=3",
            "--record",
            "/proc/nope.jsonl",
        ][..],
        &["model", "--format", "json", "--out", "/proc/nope.json"][..],
    ] {
        let out = hyq(args);
        let err = stderr(&out);
        assert!(!out.status.success(), "hyq {args:?} fails");
        assert_eq!(err.lines().count(), 1, "hyq {args:?}: {err}");
        assert!(
            !err.contains(".partial") && err.contains("nope"),
            "hyq {args:?}: {err}"
        );
    }
}

#[test]
fn an_error_echoing_a_long_value_stays_a_short_line() {
    // A 120 KB value used to come back twice in one 240 KB line.
    let long = "a".repeat(120_000);
    let set = format!("task.fall_penalty=\"{long}\"");
    let out = hyq(&["run", "--set", &set]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{}", &err[..err.len().min(400)]);
    assert_eq!(err.lines().count(), 1);
    assert!(err.len() < 400, "{} bytes", err.len());
    assert!(
        err.contains("task.fall_penalty") && err.contains("bytes left out"),
        "{err}"
    );
}

#[test]
fn robot_init_bad_inputs() {
    let hyq_urdf = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/hyq/hyq.urdf")
        .display()
        .to_string();
    fails(
        2,
        &["robot", "init", "/nonexistent/robot.urdf"],
        &["/nonexistent/robot.urdf"],
    );
    let not_xml = write("init-not-xml.urdf", b"\x00\x01 not xml");
    fails(2, &["robot", "init", &not_xml], &["init-not-xml.urdf"]);
    let not_xml_mjcf = write("init-not-xml.xml", b"{ \"a\": 1 }");
    fails(2, &["robot", "init", &not_xml_mjcf], &["init-not-xml.xml"]);
    let inertial = r#"<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>"#;
    let one_link = format!(
        r#"<robot name="r"><link name="base"><collision><geometry><box size="1 1 1"/></geometry></collision>{inertial}</link></robot>"#
    );
    let no_legs = write("init-no-legs.urdf", one_link.as_bytes());
    fails(2, &["robot", "init", &no_legs], &["no legs"]);
    let world = one_link.replace(
        "</robot>",
        r#"<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint></robot>"#,
    );
    let world = write("init-world.urdf", world.as_bytes());
    fails(2, &["robot", "init", &world], &["no free root", "world"]);
    let no_free = write(
        "init-no-free.xml",
        br#"<mujoco><worldbody><body name="b"><geom size="0.1"/></body></worldbody></mujoco>"#,
    );
    fails(2, &["robot", "init", &no_free], &["free joint"]);
    let srdf = write(
        "init-unknown.srdf",
        br#"<robot name="hyq"><group_state name="standing" group="all"><joint name="lf_elbow" value="1"/></group_state></robot>"#,
    );
    fails(
        2,
        &["robot", "init", &hyq_urdf, "--srdf", &srdf],
        &["init-unknown.srdf", "lf_elbow"],
    );
    let nest = format!(
        "<robot>{}{}</robot>",
        "<a>".repeat(20_000),
        "</a>".repeat(20_000)
    );
    let deep = write("init-deep.urdf", nest.as_bytes());
    fails(2, &["robot", "init", &deep], &["init-deep.urdf", "deep"]);
    let deep_mjcf = write("init-deep.xml", nest.replace("robot", "mujoco").as_bytes());
    fails(2, &["robot", "init", &deep_mjcf], &["init-deep.xml"]);
    let huge = write("init-huge.urdf", &vec![b' '; 9 << 20]);
    fails(2, &["robot", "init", &huge], &["init-huge.urdf"]);
    fails(2, &["robot", "init", "/dev/zero"], &["/dev/zero"]);
}
