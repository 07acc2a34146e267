//! Invariant: the environment runs any robot its profile describes, on every engine. ANYmal C
//! (bundled) settles at its profile's standing height, and its scripted trot, from its
//! profile's `[gait]`, walks at least 1 m toward the default goal in 10 s without falling or
//! any other termination, on rapier and (with `--features dart` / `mujoco`) on DART and
//! MuJoCo. A third robot from a fixture profile (ANYmal C with its hip abduction joints fixed:
//! 8 joints, two tracked feet, joint names unlike HyQ's, its own trunk observation bounds) goes
//! through `Env` on rapier: the spaces, row names and bounds follow the profile, it stands, it
//! trots forward, and the same seed and actions repeat bit for bit.

mod common;

use std::path::PathBuf;
use std::sync::Arc;

use hyq_env::policy::{Policy, Stand, Trot};
use hyq_env::{Env, EnvConfig, Reason, ResetOptions};
use hyq_physics::{Backend, RobotModel, bundled};
use hyq_rapier::RapierBackend;

fn make_env<B: Backend>(model: &Arc<RobotModel>) -> Env<B> {
    let mut env =
        Env::<B>::new(Arc::clone(model), EnvConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    env
}

/// The trunk height after 1 s of holding the standing pose.
fn standing_height<B: Backend>(model: &Arc<RobotModel>) -> f64 {
    let mut env = make_env::<B>(model);
    let mut a = vec![0.0; model.num_joints()];
    for _ in 0..100 {
        Stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        assert!(!s.terminated, "standing ended: {:?}", s.info.reasons);
    }
    let layout = env.observation_layout().clone();
    let obs = env.observation();
    assert!(
        obs[layout.foot_contacts()].iter().all(|&c| c == 1.0),
        "every tracked foot down"
    );
    obs[layout.trunk_position()][2]
}

/// Runs the profile's trot for the default episode (10 s), asserting that only the time limit
/// ends it; returns how much closer the trunk got to the goal (K − D, m).
fn trot_progress<B: Backend>(model: &Arc<RobotModel>) -> f64 {
    let mut env = make_env::<B>(model);
    let mut trot = Trot::from_profile(model).unwrap_or_else(|e| panic!("{e}"));
    let mut a = vec![0.0; model.num_joints()];
    let start = env.info().distance_to_goal;
    loop {
        trot.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        if s.terminated || s.truncated {
            assert!(
                !s.terminated && s.info.reasons.contains(Reason::Timeout),
                "{} on {}: ended at t = {} by {:?}",
                model.name(),
                B::NAME,
                s.info.t,
                s.info.reasons
            );
            assert_eq!(s.info.t, 1000);
            break;
        }
    }
    let progress = start - env.info().distance_to_goal;
    println!(
        "{} on {}: trot progress {progress:.3} m toward the goal in 10 s",
        model.name(),
        B::NAME
    );
    progress
}

#[test]
fn anymal_c_stands_at_its_profile_height_on_rapier() {
    let model = bundled::anymal_c();
    let z = standing_height::<RapierBackend>(&model);
    assert!(
        (z - model.standing_height()).abs() < 5e-4,
        "settled at {z}, profile says {}",
        model.standing_height()
    );
}

#[test]
fn anymal_c_trot_walks_a_metre_toward_the_goal_on_rapier() {
    // Measured 3.49 m (the profile's comment); 1 m is the contract.
    assert!(trot_progress::<RapierBackend>(&bundled::anymal_c()) >= 1.0);
}

#[cfg(feature = "dart")]
#[test]
fn anymal_c_stands_at_its_profile_height_on_dart() {
    let model = bundled::anymal_c();
    let z = standing_height::<hyq_dart::DartBackend>(&model);
    assert!(
        (z - model.standing_height()).abs() < 5e-4,
        "settled at {z}, profile says {}",
        model.standing_height()
    );
}

#[cfg(feature = "dart")]
#[test]
fn anymal_c_trot_walks_a_metre_toward_the_goal_on_dart() {
    // Measured 3.27 m (the profile's comment); 1 m is the contract.
    assert!(trot_progress::<hyq_dart::DartBackend>(&bundled::anymal_c()) >= 1.0);
}

#[cfg(feature = "mujoco")]
#[test]
fn anymal_c_stands_at_its_profile_height_on_mujoco() {
    let model = bundled::anymal_c();
    let z = standing_height::<hyq_mujoco::MujocoBackend>(&model);
    assert!(
        (z - model.standing_height()).abs() < 5e-4,
        "settled at {z}, profile says {}",
        model.standing_height()
    );
}

#[cfg(feature = "mujoco")]
#[test]
fn anymal_c_trot_walks_a_metre_toward_the_goal_on_mujoco() {
    assert!(trot_progress::<hyq_mujoco::MujocoBackend>(&bundled::anymal_c()) >= 1.0);
}

/// The fixture robot, loaded through the front ends' resolver from a profile path: its URDF
/// (the bundled ANYmal C with the HAA joints fixed) is written next to a copy of the profile.
fn eight_joint_robot() -> Arc<RobotModel> {
    let fixture = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/anymal_c_8dof");
    let dir = std::env::temp_dir().join(format!("hyq-env-8dof-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut urdf = bundled::ANYMAL_C_URDF.to_owned();
    for leg in ["LF", "LH", "RF", "RH"] {
        let revolute = format!("<joint name=\"{leg}_HAA\" type=\"revolute\">");
        assert!(urdf.contains(&revolute), "{revolute}");
        urdf = urdf.replace(
            &revolute,
            &format!("<joint name=\"{leg}_HAA\" type=\"fixed\">"),
        );
    }
    std::fs::write(dir.join("anymal_c_8dof.urdf"), urdf).expect("write URDF");
    let profile = dir.join("profile.toml");
    std::fs::copy(fixture.join("profile.toml"), &profile).expect("copy profile");
    let model = hyq_physics::resolve_robot(profile.to_str().expect("utf-8 path"));
    std::fs::remove_dir_all(&dir).ok();
    model.unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_robot_with_eight_joints_and_two_feet_runs_through_the_env_on_rapier() {
    let model = eight_joint_robot();
    assert_eq!((model.num_joints(), model.num_feet()), (8, 2));
    // The fixture's spawn height leaves the feet about 1 mm up, as the bundled robots do.
    let spawn = model.spawn_state();
    let mut poses = vec![hyq_physics::na::Isometry3::identity(); model.num_links()];
    model
        .link_poses(&spawn.trunk.pose, &spawn.q, &mut poses)
        .expect("forward kinematics");
    let clearance = (0..model.num_feet())
        .map(|t| model.tracked_lowest_z(t, &poses))
        .fold(f64::INFINITY, f64::min);
    assert!((0.0005..0.002).contains(&clearance), "{clearance}");

    let env = make_env::<RapierBackend>(&model);
    // 2·8 joint rows + 2 foot flags + 11 trunk rows.
    assert_eq!(env.observation().len(), 29);
    assert_eq!(env.action_space().len(), 8);
    let layout = env.observation_layout().clone();
    let names: Vec<String> = layout.rows().iter().map(|r| r.name.to_string()).collect();
    for expected in [
        "fl_hip_angle",
        "hr_knee_speed",
        "front_left_contact_flag",
        "hind_right_contact_flag",
        "base_contact_flag",
        "base_position_z",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "no row {expected} in {names:?}"
        );
    }
    // The trunk rows' declared bounds are the profile's, not the spec's.
    let z_row = &layout.rows()[layout.trunk_position().end - 1];
    assert_eq!((z_row.min, z_row.max), (0.0, 0.8));
    let ax_row = &layout.rows()[layout.trunk_acceleration().start];
    assert_eq!((ax_row.min, ax_row.max), (-80.0, 80.0));

    let z = standing_height::<RapierBackend>(&model);
    assert!((0.45..0.56).contains(&z), "stands at {z} m");
    let progress = trot_progress::<RapierBackend>(&model);
    assert!(progress >= 1.0, "trotted {progress} m toward the goal");

    // Same seed, same actions: the same bits.
    let run = || {
        let mut env = make_env::<RapierBackend>(&model);
        let mut trot = Trot::from_profile(&model).unwrap_or_else(|e| panic!("{e}"));
        let mut a = vec![0.0; 8];
        let mut bits = Vec::new();
        for _ in 0..200 {
            trot.act(&env.policy_input(), &mut a);
            let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
            bits.extend(s.observation.iter().map(|v| v.to_bits()));
        }
        bits
    };
    assert_eq!(run(), run());
}
