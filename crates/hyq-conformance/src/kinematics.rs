//! Kinematics and state: mass and body frames from the URDF, states set and read back, and
//! reported velocities that are the time derivatives of the reported positions.

use std::sync::Arc;

use nalgebra::{Isometry3, Translation3, Vector3};

use super::fixtures::{
    Rng, Robot, build, build_default, engine_poses, fk_poses, read_contacts, read_q, read_qd, set,
    standing_at, step_pd, step_zero, zero_gravity,
};
use super::independent_fk::{foot_centres_from, independent_foot_centres, max_distance};
use hyq_physics::actuator::{Actuator, PdScratch};
use hyq_physics::{Backend, RobotState, TrunkState};

/// The robot's mass is the sum of every URDF link's mass (read independently from the URDF
/// text), in the model and in the engine.
pub fn total_mass_matches_urdf<B: Backend>(robot: &Robot, options: &B::Options) {
    let urdf = urdf_rs::read_from_string(&robot.urdf).expect("the robot's URDF parses");
    let urdf_mass: f64 = urdf.links.iter().map(|l| l.inertial.mass.value).sum();
    let b: B = build_default(robot, options);
    let model = b.model();
    assert!(
        (model.total_mass() - urdf_mass).abs() < 1e-9,
        "model mass {} kg, URDF {urdf_mass} kg",
        model.total_mass()
    );
    // Engines may store masses in f32: a relative 1e-6 is far below any physical effect.
    assert!(
        (b.total_mass() - urdf_mass).abs() < 1e-6 * urdf_mass,
        "{} holds {} kg, URDF {urdf_mass} kg",
        B::NAME,
        b.total_mass()
    );
}

/// Foot positions agree three ways for random configurations (trunk anywhere, any
/// orientation, joints anywhere in their limits): composed by hand from the URDF text, from
/// the model's forward kinematics, and from the engine's own body poses.
pub fn forward_kinematics_matches_independent_urdf_computation<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let mut b: B = build(robot, &zero_gravity(), options);
    let model = Arc::clone(b.model());
    let mut rng = Rng::new(7);
    for _ in 0..8 {
        let state = RobotState {
            trunk: TrunkState::at_rest(Isometry3::from_parts(
                Translation3::from(rng.vector(2.0) + Vector3::new(0.0, 0.0, 4.0)),
                rng.rotation(),
            )),
            q: rng.joint_angles(&model, 0.0),
            qd: vec![0.0; model.num_joints()],
        };
        let expected = independent_foot_centres(robot, &state);

        let mut poses = vec![Isometry3::identity(); model.num_links()];
        model
            .link_poses(&state.trunk.pose, &state.q, &mut poses)
            .expect("forward kinematics");
        let from_model = foot_centres_from(&model, &poses);
        // Both in f64 from the same figures: only rounding differs.
        let err = max_distance(&expected, &from_model);
        assert!(err < 1e-9, "model forward kinematics off by {err} m");

        set(&mut b, &state);
        let from_engine = foot_centres_from(&model, &engine_poses(&b));
        // Engines may compute in f32 (about 1e-7 relative per operation, over a four-joint
        // chain a few metres from the origin): 1e-5 m is ample and far below any geometry error.
        let err = max_distance(&expected, &from_engine);
        assert!(
            err < 1e-5,
            "{} body poses put the feet {err} m off",
            B::NAME
        );
        let from_engine_fk = foot_centres_from(&model, &fk_poses(&b));
        let err = max_distance(&expected, &from_engine_fk);
        assert!(
            err < 1e-5,
            "{} trunk pose and joint angles put the feet {err} m off",
            B::NAME
        );
    }
}

/// A state set is the state read back (within f32 rounding), and contacts read false until
/// the first step.
pub fn set_state_round_trips<B: Backend>(robot: &Robot, options: &B::Options) {
    let mut b: B = build_default(robot, options);
    let model = Arc::clone(b.model());
    let mut rng = Rng::new(11);
    for _ in 0..8 {
        let state = RobotState {
            trunk: TrunkState {
                pose: Isometry3::from_parts(
                    Translation3::from(rng.vector(2.0) + Vector3::new(0.0, 0.0, 3.0)),
                    rng.rotation(),
                ),
                linvel: rng.vector(2.0),
                angvel: rng.vector(3.0),
            },
            q: rng.joint_angles(&model, 0.0),
            qd: (0..model.num_joints())
                .map(|_| rng.range(-5.0, 5.0))
                .collect(),
        };
        set(&mut b, &state);
        let back = b.state();
        let t = &back.trunk;
        let close = |a: f64, e: f64, tol: f64, what: &str| {
            assert!((a - e).abs() <= tol, "{what}: set {e}, read {a}");
        };
        for i in 0..3 {
            close(
                t.pose.translation.vector[i],
                state.trunk.pose.translation.vector[i],
                1e-5,
                "trunk position",
            );
            close(
                t.linvel[i],
                state.trunk.linvel[i],
                1e-4,
                "trunk linear velocity",
            );
            close(
                t.angvel[i],
                state.trunk.angvel[i],
                1e-4,
                "trunk angular velocity",
            );
        }
        let angle = t.pose.rotation.angle_to(&state.trunk.pose.rotation);
        assert!(angle < 1e-5, "trunk orientation off by {angle} rad");
        for (i, j) in model.joints().iter().enumerate() {
            close(back.q[i], state.q[i], 1e-5, &format!("angle of {}", j.name));
            close(
                back.qd[i],
                state.qd[i],
                1e-4,
                &format!("speed of {}", j.name),
            );
        }
        assert!(
            read_contacts(&b).iter().all(|c| !c),
            "contacts must read false before the first step"
        );
    }
}

/// How far a finite difference over one step may be from the mean of the velocities reported
/// before and after it: an integrator with internal substeps moves by the mean of its substep
/// velocities, which lies between the two (monotonic change within the step) up to this slack;
/// the constant covers f32 rounding of the positions (a few 1e-7 over 1e-3 s). `turn` is how
/// much the per-step velocity change itself changes next to this step (a second difference;
/// 0 where the velocity is known to change evenly): where the velocity curves within the step
/// (an acceleration that changes, up to a turning point), the mean of a velocity quadratic in
/// time lies `turn / 12` off the mean of its ends, which an integrator with several internal
/// substeps resolves.
fn fd_slack(v0: f64, v1: f64, turn: f64) -> f64 {
    0.75 * (v1 - v0).abs() + turn / 12.0 + 3e-3
}

/// The reported trunk velocity is that of the trunk frame's origin and the angular velocity is
/// the world-frame one: finite differences of the trunk pose over each step agree with the
/// velocities reported before and after it, while the robot tumbles freely in zero gravity
/// (where the origin's and the centre of mass's velocities differ by ω × r ≈ 0.2 m/s).
pub fn trunk_velocity_is_the_frame_origin_velocity<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let params = zero_gravity();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    let mut start = standing_at(&model, 3.0);
    start.trunk.linvel = Vector3::new(0.2, 0.1, -0.1);
    start.trunk.angvel = Vector3::new(1.0, -2.0, 3.0);
    set(&mut b, &start);
    for n in 0..300 {
        let before = b.trunk();
        step_zero(&mut b);
        let after = b.trunk();
        let fd_v = (after.pose.translation.vector - before.pose.translation.vector) / params.dt;
        let fd_w = (after.pose.rotation * before.pose.rotation.inverse()).scaled_axis() / params.dt;
        for k in 0..3 {
            let (v0, v1) = (before.linvel[k], after.linvel[k]);
            assert!(
                (fd_v[k] - 0.5 * (v0 + v1)).abs() <= fd_slack(v0, v1, 0.0),
                "step {n}: trunk velocity[{k}] {v0} -> {v1}, finite difference {}",
                fd_v[k]
            );
            let (w0, w1) = (before.angvel[k], after.angvel[k]);
            assert!(
                (fd_w[k] - 0.5 * (w0 + w1)).abs() <= fd_slack(w0, w1, 0.0),
                "step {n}: trunk angular velocity[{k}] {w0} -> {w1}, finite difference {}",
                fd_w[k]
            );
        }
    }
}

/// Reported joint speeds are the time derivative of the reported angles (units, sign): they
/// agree with finite differences over each step (see the trunk test for the criterion) while
/// the legs flail in zero gravity, away from the ground and the joint limits. (Contacts and
/// limit stops change velocities within a step non-monotonically, so they are left out.)
pub fn joint_velocities_match_finite_differences<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = zero_gravity();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &standing_at(&model, 3.0));
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(29);
    let mut targets = model.standing_pose().to_vec();
    let steps = 500;
    let (mut q, mut v) = (vec![read_q(&b)], vec![read_qd(&b)]);
    for n in 0..steps {
        if n % 50 == 0 {
            targets = rng.joint_angles(&model, 0.4);
        }
        step_pd(&mut b, &act, &targets, &mut scratch);
        q.push(read_q(&b));
        v.push(read_qd(&b));
    }
    for n in 0..steps {
        for (i, j) in model.joints().iter().enumerate() {
            let (v0, v1) = (v[n][i], v[n + 1][i]);
            let fd = (q[n + 1][i] - q[n][i]) / params.dt;
            // The second differences of the reported speeds on either side of this step.
            let change = v1 - v0;
            let before = n
                .checked_sub(1)
                .map_or(0.0, |p| (change - (v0 - v[p][i])).abs());
            let after = v.get(n + 2).map_or(0.0, |v2| ((v2[i] - v1) - change).abs());
            assert!(
                (fd - 0.5 * (v0 + v1)).abs() <= fd_slack(v0, v1, before.max(after)),
                "step {n}: joint {} speed {v0} -> {v1}, finite difference {fd}",
                j.name,
            );
        }
    }
}

/// The state read back is the state: a run that is stopped every 10 steps, read with
/// [`Backend::state`] and put back with [`Backend::set_state`] follows the uninterrupted run
/// (flailing in zero gravity, away from the ground and the joint limits). Stale or misplaced
/// velocities would make it veer off within a few round trips.
pub fn state_read_back_continues_the_trajectory<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = zero_gravity();
    let model = Arc::clone(&robot.model);
    let mut start = standing_at(&model, 3.0);
    start.trunk.linvel = Vector3::new(0.3, -0.2, 0.1);
    start.trunk.angvel = Vector3::new(0.5, 1.0, -1.5);
    let act = Actuator::new(&model);
    let run = |round_trip: bool| -> RobotState {
        let mut b: B = build(robot, &params, options);
        set(&mut b, &start);
        let mut scratch = PdScratch::new(model.num_joints());
        let mut rng = Rng::new(31);
        let mut targets = model.standing_pose().to_vec();
        for n in 0..200 {
            if n % 20 == 0 {
                targets = rng.joint_angles(&model, 0.4);
            }
            if round_trip && n % 10 == 0 {
                let s = b.state();
                set(&mut b, &s);
            }
            step_pd(&mut b, &act, &targets, &mut scratch);
        }
        b.state()
    };
    let plain = run(false);
    let interrupted = run(true);
    let dq = plain
        .q
        .iter()
        .zip(&interrupted.q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let dqd = plain
        .qd
        .iter()
        .zip(&interrupted.qd)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let dp =
        (plain.trunk.pose.translation.vector - interrupted.trunk.pose.translation.vector).norm();
    let dr = plain
        .trunk
        .pose
        .rotation
        .angle_to(&interrupted.trunk.pose.rotation);
    println!(
        "{}: after 20 round trips: joint angles {dq:.2e} rad, speeds {dqd:.2e} rad/s, trunk {dp:.2e} m, {dr:.2e} rad",
        B::NAME
    );
    // f32 rounding at each round trip, amplified by 0.2 s of flailing, stays below these; a
    // velocity stale by one solver substep is off by rad/s at once.
    assert!(dq < 1e-3, "joint angles differ by {dq} rad");
    assert!(dqd < 3e-2, "joint speeds differ by {dqd} rad/s");
    assert!(dp < 1e-4, "trunk position differs by {dp} m");
    assert!(dr < 1e-3, "trunk orientation differs by {dr} rad");
}
