//! Dynamics: momentum under internal torques, joint limits under full torque, the actuator's
//! velocity-limit rule, and passive joint damping.

use std::sync::Arc;

use nalgebra::Vector3;

use super::fixtures::{
    Rng, Robot, build, engine_poses, fk_poses, read_contacts, read_q, read_qd, set, standing_at,
    step_pd, step_zero, steps_for, zero_gravity,
};
use hyq_physics::actuator::{Actuator, PdScratch};
use hyq_physics::model::RobotModel;
use hyq_physics::{Backend, PhysicsParams};

/// In zero gravity, away from the ground, internal joint torques cannot move the centre of
/// mass: it keeps its initial velocity (straight line) while the robot tumbles and flails for
/// 1 s. This catches a floating root whose velocity is integrated at the wrong point.
pub fn internal_torques_conserve_momentum<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = zero_gravity();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    let mut start = standing_at(&model, 3.0);
    start.trunk.linvel = Vector3::new(1.0, -0.3, 0.5);
    start.trunk.angvel = Vector3::new(0.5, -0.8, 4.0);
    set(&mut b, &start);
    let com = |b: &B| model.centre_of_mass(&fk_poses(b));
    let c0 = com(&b);
    step_zero(&mut b);
    let c1 = com(&b);
    let v = (c1 - c0) / params.dt;
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(17);
    let mut targets = model.standing_pose().to_vec();
    let mut worst: f64 = 0.0;
    for n in 2..=steps_for(&params, 1.0) {
        if n % 50 == 0 {
            targets = rng.joint_angles(&model, 0.1);
        }
        step_pd(&mut b, &act, &targets, &mut scratch);
        let t = (n - 1) as f64 * params.dt;
        let err = (com(&b) - (c1 + v * t)).norm();
        worst = worst.max(err);
    }
    // A first-order integrator at 1 kHz drifts by millimetres in this violent second (rapier:
    // 1.4 mm at 4 solver iterations, 5.3 mm at 1); a root integrated at its frame origin
    // instead of its centre of mass is off by decimetres (0.3 m).
    println!(
        "{}: centre of mass left its straight line by {worst:.2e} m in 1 s",
        B::NAME
    );
    assert!(
        worst < 1e-2,
        "centre of mass left its straight line by {worst} m"
    );
    assert!(
        read_contacts(&b).iter().all(|c| !c),
        "the robot must stay clear of the ground in this test"
    );
}

/// Every joint driven into its limits at full torque (targets 0.5 rad past alternate limits,
/// stiff gains saturating at the effort limit) stays within 0.1 rad of its range, and no
/// joint comes apart: the engine's body poses stay within 1 mm of the forward kinematics of its
/// trunk pose and joint angles. First floating in zero gravity, where every joint must reach
/// each limit (within 0.1 rad by the end of each 0.5 s phase), then on the ground under the
/// robot's weight, where every joint must reach at least one of its limits in 2 s (the ground
/// may block the other: HyQ reaches all of them; on rapier and DART, ANYmal C's front hips do
/// not swing back to horizontal while its feet push on the ground). The count reached is
/// printed.
pub fn joint_limits_hold_under_full_torque<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = Arc::clone(&robot.model);
    let n = model.num_joints();
    let act = Actuator::with_gains(&model, &vec![3000.0; n], &vec![30.0; n]).expect("gains");
    let mut worst_overshoot: f64 = 0.0;
    let mut worst_separation: f64 = 0.0;
    for (params, start, in_air) in [
        (zero_gravity(), standing_at(&model, 3.0), true),
        (PhysicsParams::default(), model.spawn_state(), false),
    ] {
        let mut b: B = build(robot, &params, options);
        set(&mut b, &start);
        let mut scratch = PdScratch::new(n);
        let phase = steps_for(&params, 0.5);
        let mut saturated = vec![false; n];
        // Closest approach to each joint's [lower, upper] limit over the run.
        let mut closest = vec![[f64::INFINITY; 2]; n];
        for p in 0..4 {
            let upper = p % 2 == 0;
            let targets: Vec<f64> = model
                .joints()
                .iter()
                .map(|j| if upper { j.upper + 0.5 } else { j.lower - 0.5 })
                .collect();
            for _ in 0..phase {
                step_pd(&mut b, &act, &targets, &mut scratch);
                for (i, tau) in scratch.torques().iter().enumerate() {
                    saturated[i] |= tau.abs() >= model.joints()[i].effort;
                }
                let over = check_within_range(&b, &model, in_air, &mut closest);
                worst_overshoot = worst_overshoot.max(over);
                worst_separation = worst_separation.max(check_joined(&b, &model, in_air));
            }
            if in_air {
                let q = read_q(&b);
                for (i, j) in model.joints().iter().enumerate() {
                    let limit = if upper { j.upper } else { j.lower };
                    assert!(
                        (q[i] - limit).abs() <= 0.1,
                        "joint {} at {} rad did not reach its limit {limit} rad in the air",
                        j.name,
                        q[i]
                    );
                }
            }
        }
        for (i, j) in model.joints().iter().enumerate() {
            assert!(
                saturated[i],
                "joint {} never saturated: the test must drive every joint at full torque",
                j.name
            );
            let reached = closest[i].iter().filter(|&&d| d <= 0.1).count();
            assert!(
                reached == 2 || (!in_air && reached == 1),
                "joint {} came only within {:?} rad of its limits (in the air: {in_air})",
                j.name,
                closest[i]
            );
        }
        let reached = closest.iter().flatten().filter(|&&d| d <= 0.1).count();
        println!(
            "{}: {} reached {reached} of its {} joint limits (in the air: {in_air})",
            B::NAME,
            model.name(),
            2 * n
        );
    }
    // Both figures are part of the report of this test.
    println!(
        "{}: worst limit overshoot {worst_overshoot:.4} rad, worst joint separation {worst_separation:.2e} m",
        B::NAME
    );
}

/// Checks that every joint of `b` is within 0.1 rad of its range and records in `closest` its
/// closest approach to its [lower, upper] limits; returns the largest overshoot.
fn check_within_range<B: Backend>(
    b: &B,
    model: &RobotModel,
    in_air: bool,
    closest: &mut [[f64; 2]],
) -> f64 {
    let q = read_q(b);
    let mut worst: f64 = 0.0;
    for (i, j) in model.joints().iter().enumerate() {
        let over = (j.lower - q[i]).max(q[i] - j.upper).max(0.0);
        worst = worst.max(over);
        assert!(
            over <= 0.1,
            "joint {} at {} rad, {over} rad past its range [{}, {}] (in the air: {in_air})",
            j.name,
            q[i],
            j.lower,
            j.upper
        );
        closest[i][0] = closest[i][0].min((q[i] - j.lower).abs());
        closest[i][1] = closest[i][1].min((q[i] - j.upper).abs());
    }
    worst
}

/// Checks that no joint of `b` came apart: every body within 1 mm of where the forward
/// kinematics of its trunk pose and joint angles put it; returns the largest distance.
fn check_joined<B: Backend>(b: &B, model: &RobotModel, in_air: bool) -> f64 {
    let fk = fk_poses(b);
    let engine = engine_poses(b);
    let mut worst: f64 = 0.0;
    for (l, (a, e)) in fk.iter().zip(&engine).enumerate() {
        let sep = (a.translation.vector - e.translation.vector).norm();
        worst = worst.max(sep);
        assert!(
            sep <= 1e-3,
            "body {} is {sep} m away from where its joints put it (in the air: {in_air})",
            model.links()[l].name
        );
    }
    worst
}

/// The actuator's velocity-limit rule keeps joint speeds near their URDF limits in the
/// learning workload (default gains, random targets redrawn every 10 sub-steps, on the ground,
/// reset when the trunk touches): the 99th percentile of |q̇| / limit stays at most 2 and the
/// peak at most 4.5. Without the rule the 99th percentile is at least 1.5 times higher, so the
/// bound is the rule's doing. (The rule cannot do more: joints whipped by their neighbours or
/// stopped by a limit exceed it with no motor torque at all; see `hyq_physics::actuator`.)
pub fn velocity_limit_bounds_joint_speed<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = PhysicsParams::default();
    let model = Arc::clone(&robot.model);
    let n = model.num_joints();
    let run = |limit: bool| -> (f64, f64) {
        let mut b: B = build(robot, &params, options);
        let mut act = Actuator::new(&model);
        act.set_velocity_limit(limit);
        let mut scratch = PdScratch::new(n);
        let mut rng = Rng::new(37);
        let mut targets = model.standing_pose().to_vec();
        let mut ratios = Vec::new();
        let trunk = model.trunk_tracked_index();
        for i in 0..4000 {
            if i % 10 == 0 {
                targets = rng.joint_angles(&model, 0.0);
            }
            step_pd(&mut b, &act, &targets, &mut scratch);
            for (qd, j) in read_qd(&b).iter().zip(model.joints()) {
                ratios.push(qd.abs() / j.velocity);
            }
            if read_contacts(&b)[trunk] {
                set(&mut b, &model.spawn_state());
            }
        }
        ratios.sort_by(f64::total_cmp);
        let p99 = ratios[(ratios.len() - 1) * 99 / 100];
        (p99, ratios[ratios.len() - 1])
    };
    let (p99, peak) = run(true);
    let (p99_off, peak_off) = run(false);
    println!(
        "{}: |joint speed| / limit, 99th percentile and peak: {p99:.2}, {peak:.2} with the rule; {p99_off:.2}, {peak_off:.2} without",
        B::NAME
    );
    assert!(
        p99 <= 2.0,
        "99th percentile of |q̇| / limit is {p99} with the rule"
    );
    assert!(peak <= 4.5, "peak |q̇| / limit is {peak} with the rule");
    assert!(
        p99_off >= 1.5 * p99,
        "without the rule the 99th percentile is {p99_off}, with it {p99}: the rule does not matter?"
    );
}

/// The backend applies the model's passive joint damping: in zero gravity with no torque, the
/// joints carrying only a leaf body, set spinning at 1 rad/s, lose more than half their speed
/// within 0.5 s (the URDF damping against the leaf's inertia; without damping the speed would
/// barely change). A robot whose URDF damps none of its leaf joints (ANYmal C) is checked on a
/// copy of its model with each leaf joint damped at 8 ln 2 times the leaf's inertia about the
/// joint axis (1/16 of the speed would be left after 0.5 s about a fixed axis, less on a free
/// robot), and the undamped original must keep more than half the speed (no damping the model
/// does not have).
pub fn joint_damping_is_applied<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = zero_gravity();
    let model = Arc::clone(&robot.model);
    let leaves: Vec<usize> = (0..model.num_joints())
        .filter(|&j| {
            let child = model.joints()[j].child;
            model.links().iter().all(|l| l.parent != Some(child))
        })
        .collect();
    assert!(!leaves.is_empty(), "a tree of joints has a leaf joint");
    let damped: Vec<usize> = leaves
        .iter()
        .copied()
        .filter(|&j| model.joints()[j].damping > 0.0)
        .collect();
    let spin = |model: &Arc<RobotModel>, joints: &[usize]| -> Vec<f64> {
        let mut b: B = B::build(Arc::clone(model), &params, options)
            .unwrap_or_else(|e| panic!("{} backend failed to build: {e}", B::NAME));
        let mut start = standing_at(model, 3.0);
        for &j in joints {
            let joint = &model.joints()[j];
            start.q[j] = 0.5 * (joint.lower + joint.upper);
            start.qd[j] = 1.0;
        }
        set(&mut b, &start);
        for _ in 0..steps_for(&params, 0.5) {
            step_zero(&mut b);
        }
        let qd = read_qd(&b);
        joints.iter().map(|&j| qd[j]).collect()
    };
    let (tested, joints) = if damped.is_empty() {
        let undamped = spin(&model, &leaves);
        for (&j, qd) in leaves.iter().zip(&undamped) {
            assert!(
                qd.abs() > 0.5,
                "undamped joint {} slowed to {qd} rad/s within 0.5 s (started at 1 rad/s)",
                model.joints()[j].name
            );
        }
        let damping: Vec<(usize, f64)> = leaves
            .iter()
            .map(|&j| (j, 8.0 * std::f64::consts::LN_2 * model.axis_inertia(j)))
            .collect();
        println!(
            "{}: {} has no damped leaf joint; testing a copy damped at {:?} N·m·s/rad",
            B::NAME,
            model.name(),
            damping
        );
        (Arc::new(model.with_joint_damping(&damping)), leaves)
    } else {
        (model, damped)
    };
    let qd = spin(&tested, &joints);
    for (&j, qd) in joints.iter().zip(&qd) {
        assert!(
            qd.abs() < 0.5,
            "joint {} (damping {} N·m·s/rad) still turns at {qd} rad/s after 0.5 s (started at \
             1 rad/s)",
            tested.joints()[j].name,
            tested.joints()[j].damping
        );
    }
}
