//! Switching off the limit constraints of joints that cannot reach a limit within the step
//! (`RapierBackend::gate_limit_constraints`) changes nothing: a world stepped with the gate
//! and one stepped with every limit constraint always on follow bitwise-identical trajectories
//! while every joint is driven into its limits at full torque (floating in zero gravity, then
//! standing on the ground) and under random targets; and the gate did switch limits both off
//! and on along the way.

use hyq_physics::na::Vector3;
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, RobotState, bundled, pd_substep};
use rapier3d::prelude::JointAxesMask;

use crate::{RapierBackend, RapierOptions};

/// Every quantity a caller can read after a step, as bits.
fn snapshot(b: &RapierBackend, out: &mut Vec<u64>) {
    let n = b.model().num_joints();
    let (mut q, mut qd) = (vec![0.0; n], vec![0.0; n]);
    b.joint_positions(&mut q);
    b.joint_velocities(&mut qd);
    let t = b.trunk();
    let mut contacts = vec![false; b.model().tracked().len()];
    b.contacts(&mut contacts);
    out.clear();
    out.extend(q.iter().chain(&qd).map(|v| v.to_bits()));
    out.extend(t.pose.translation.vector.iter().map(|v| v.to_bits()));
    out.extend(t.pose.rotation.coords.iter().map(|v| v.to_bits()));
    out.extend(t.linvel.iter().chain(t.angvel.iter()).map(|v| v.to_bits()));
    out.extend(contacts.iter().map(|&c| u64::from(c)));
}

/// How many joints have their limit constraint on.
fn limits_on(b: &RapierBackend) -> usize {
    let mb = b.multibody();
    b.joint_links
        .iter()
        .filter(|&&id| {
            mb.link(id)
                .is_some_and(|l| l.joint().data.limit_axes.contains(JointAxesMask::ANG_X))
        })
        .count()
}

/// Steps `gated` and `always_on` alike through `phases` (targets, sub-steps) and asserts that
/// they never differ; returns (sub-steps with some limit off, sub-steps with some limit on) in
/// the gated world.
fn compare(
    params: &PhysicsParams,
    start: &RobotState,
    actuator: &Actuator,
    phases: &[(Vec<f64>, usize)],
) -> (usize, usize) {
    let model = bundled::hyq();
    let options = RapierOptions::default();
    let mut gated = RapierBackend::build(model.clone(), params, &options).expect("builds");
    let mut always_on = RapierBackend::build(model.clone(), params, &options).expect("builds");
    always_on.gate_limits = false;
    gated.set_state(start).expect("valid state");
    always_on.set_state(start).expect("valid state");
    let mut scratch = [
        PdScratch::new(model.num_joints()),
        PdScratch::new(model.num_joints()),
    ];
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let (mut some_off, mut some_on) = (0, 0);
    let mut n = 0;
    for (targets, steps) in phases {
        for _ in 0..*steps {
            n += 1;
            pd_substep(&mut gated, actuator, targets, &mut scratch[0]).expect("steps");
            pd_substep(&mut always_on, actuator, targets, &mut scratch[1]).expect("steps");
            let on = limits_on(&gated);
            some_off += usize::from(on < model.num_joints());
            some_on += usize::from(on > 0);
            snapshot(&gated, &mut a);
            snapshot(&always_on, &mut b);
            assert_eq!(a, b, "sub-step {n}: the gated world left the always-on one");
        }
    }
    (some_off, some_on)
}

#[test]
fn gated_limits_follow_the_always_on_trajectory_bitwise() {
    let model = bundled::hyq();
    let n = model.num_joints();
    // Stiff gains saturate every joint at its effort limit, as in the conformance suite.
    let stiff = Actuator::with_gains(&model, &vec![3000.0; n], &vec![30.0; n]).expect("gains");
    let past_limits = |upper: bool| -> Vec<f64> {
        model
            .joints()
            .iter()
            .map(|j| if upper { j.upper + 0.5 } else { j.lower - 0.5 })
            .collect()
    };
    let hammer: Vec<(Vec<f64>, usize)> = (0..4).map(|p| (past_limits(p % 2 == 0), 400)).collect();

    let zero_gravity = PhysicsParams {
        gravity: [0.0; 3],
        ..PhysicsParams::default()
    };
    let mut floating = model.spawn_state();
    floating.trunk.pose.translation.z = 3.0;
    floating.trunk.angvel = Vector3::new(0.5, -0.8, 2.0);
    let (off_air, on_air) = compare(&zero_gravity, &floating, &stiff, &hammer);
    let (off_ground, on_ground) = compare(
        &PhysicsParams::default(),
        &model.spawn_state(),
        &stiff,
        &hammer,
    );

    // Random targets inside the limits under the default gains, redrawn every 10 sub-steps.
    let mut state = 0x9E37_79B9_7F4A_7C15_u64;
    let random: Vec<(Vec<f64>, usize)> = (0..80)
        .map(|_| {
            let targets = model
                .joints()
                .iter()
                .map(|j| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    j.lower + (j.upper - j.lower) * ((state >> 11) as f64 / (1u64 << 53) as f64)
                })
                .collect();
            (targets, 10)
        })
        .collect();
    let (off_random, _) = compare(
        &PhysicsParams::default(),
        &model.spawn_state(),
        &Actuator::new(&model),
        &random,
    );

    // The comparison means something only if the gate acted both ways.
    for (what, off, on) in [
        ("floating", off_air, on_air),
        ("on the ground", off_ground, on_ground),
    ] {
        assert!(
            off > 0 && on > 0,
            "{what}: limits off in {off} sub-steps, on in {on}"
        );
    }
    assert!(
        off_random > 0,
        "random targets: no limit was ever switched off"
    );
}
