//! Ground contact: free fall until a foot lands, standing, collapsing, and contact flags that
//! follow the true clearance.

use std::sync::Arc;

use nalgebra::{Isometry3, UnitQuaternion};

use super::fixtures::{
    Robot, build, clearances, read_contacts, set, standing_at, step_pd, step_zero, steps_for,
};
use hyq_physics::actuator::{Actuator, PdScratch};
use hyq_physics::model::RobotModel;
use hyq_physics::{Backend, PhysicsParams, RobotState};

/// Dropped level from rest with zero torques, the trunk follows z₀ − g t²/2 until a foot
/// touches (within the O(dt) term of a first-order integrator, g·dt·t/2), does not drift or
/// turn, and contact flags follow the true clearance: never set while a shape is more than
/// `contact_distance` + 0.5 mm above the ground before and after the step (no speculative
/// contacts), always set once a shape starts a step touching or penetrating it.
pub fn free_fall_matches_ballistic_until_contact<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    let drop = 0.1;
    let start = standing_at(&model, model.spawn_height() + drop);
    set(&mut b, &start);
    let g = -params.gravity[2];
    let z0 = start.trunk.pose.translation.z;
    let clearance0 = clearances(&b);
    let foot_clearance0 = clearance0[..model.num_feet()]
        .iter()
        .fold(f64::INFINITY, |a, &c| a.min(c));
    let touch_time = (2.0 * foot_clearance0 / g).sqrt();
    let steps = steps_for(&params, touch_time + 0.05);
    let cd = params.contact_distance;
    let mut before = clearance0;
    let mut touched = vec![false; model.tracked().len()];
    let mut in_flight = true;
    for n in 1..=steps {
        step_zero(&mut b);
        let after = clearances(&b);
        let flags = read_contacts(&b);
        for (t, tracked) in model.tracked().iter().enumerate() {
            if before[t] > cd + 5e-4 && after[t] > cd + 5e-4 {
                assert!(
                    !flags[t],
                    "step {n}: {} reported in contact {:.2} mm above the ground",
                    tracked.name,
                    1e3 * after[t].min(before[t])
                );
            }
            if before[t] <= 0.0 {
                assert!(
                    flags[t],
                    "step {n}: {} started the step touching the ground ({:.3} mm) but no contact",
                    tracked.name,
                    1e3 * before[t]
                );
            }
            touched[t] |= flags[t];
        }
        in_flight &= !flags.iter().any(|&f| f);
        if in_flight {
            let t = n as f64 * params.dt;
            let trunk = b.trunk();
            let z = trunk.pose.translation.z;
            let expected = z0 - g * t * t / 2.0;
            let tol = g * params.dt * t / 2.0 + 1e-5;
            assert!(
                (z - expected).abs() <= tol,
                "t = {t} s: trunk z {z}, ballistic {expected} (tolerance {tol})"
            );
            let vz = trunk.linvel.z;
            assert!(
                (vz + g * t).abs() <= g * params.dt + 1e-5,
                "t = {t} s: trunk vz {vz}, ballistic {}",
                -g * t
            );
            let drift = (trunk.pose.translation.vector.xy()
                - start.trunk.pose.translation.vector.xy())
            .norm();
            assert!(drift < 1e-5, "t = {t} s: trunk drifted {drift} m sideways");
            let turn = trunk.pose.rotation.angle_to(&start.trunk.pose.rotation);
            assert!(turn < 1e-5, "t = {t} s: trunk turned {turn} rad");
        }
        before = after;
    }
    for (t, foot) in model.tracked()[..model.num_feet()].iter().enumerate() {
        assert!(
            touched[t],
            "foot {} never touched the ground after the drop",
            foot.name
        );
    }
}

/// The trunk frame's height (m) 1 s and 10 s after spawn, the PD actuator holding the standing
/// pose under the default gains: what a robot's standing-height ledger states per engine.
pub fn standing_heights<B: Backend>(robot: &Robot, options: &B::Options) -> (f64, f64) {
    let params = PhysicsParams::default();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &model.spawn_state());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = model.standing_pose().to_vec();
    let at_1s_step = steps_for(&params, 1.0);
    let mut at_1s = f64::NAN;
    for n in 1..=steps_for(&params, 10.0) {
        step_pd(&mut b, &act, &targets, &mut scratch);
        if n == at_1s_step {
            at_1s = b.trunk().pose.translation.z;
        }
    }
    (at_1s, b.trunk().pose.translation.z)
}

/// Under the default PD gains with the standing pose as target, the robot stands for 10 s from
/// its spawn state: over the last 5 s the trunk height varies by at most 1 mm, every foot is in
/// contact at every step, and the trunk never touches the ground.
pub fn stands_in_nominal_pose_for_10_s<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &model.spawn_state());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = model.standing_pose().to_vec();
    let steps = steps_for(&params, 10.0);
    let settle = steps / 2;
    let trunk_index = model.trunk_tracked_index();
    let (mut z_min, mut z_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for n in 1..=steps {
        step_pd(&mut b, &act, &targets, &mut scratch);
        let flags = read_contacts(&b);
        assert!(
            !flags[trunk_index],
            "t = {} s: trunk touched the ground",
            n as f64 * params.dt
        );
        if n > settle {
            let z = b.trunk().pose.translation.z;
            z_min = z_min.min(z);
            z_max = z_max.max(z);
            for (t, tracked) in model.tracked()[..model.num_feet()].iter().enumerate() {
                assert!(
                    flags[t],
                    "t = {} s: foot {} not in contact while standing",
                    n as f64 * params.dt,
                    tracked.name
                );
            }
        }
    }
    assert!(
        z_max - z_min <= 1e-3,
        "trunk height varied by {:.3} mm over the last 5 s ({z_min} .. {z_max})",
        1e3 * (z_max - z_min)
    );
    // Standing means the trunk stays up: well above half its spawn height.
    assert!(
        z_min > 0.5 * model.spawn_height(),
        "trunk sank to {z_min} m (spawn {} m)",
        model.spawn_height()
    );
    let (roll, pitch, _) = b.trunk().pose.rotation.euler_angles();
    assert!(
        roll.abs() < 0.05 && pitch.abs() < 0.05,
        "trunk not level: roll {roll}, pitch {pitch}"
    );
}

/// With zero joint torques the robot cannot hold itself up: from its spawn state it sinks to
/// less than half its spawn height within 1 s. Laid limp just above the ground with its trunk
/// lowest (on its side, or else upside down: the first orientation where the trunk is at least
/// 1 cm below every other part), its trunk lands and is reported in contact within 0.5 s, and
/// not before it is within `contact_distance` + 1 mm of the ground.
///
/// (A limp robot left standing may come to rest on legs folded against their joint limits with
/// its trunk off the ground: HyQ does, its trunk 8 cm up; tipped sideways it ends 3 cm up. On
/// their sides, HyQ's and ANYmal C's legs reach below their trunks, ANYmal C's hip drives
/// propping it 12 cm up, so both are laid upside down.)
pub fn limp_robot_collapses_onto_its_trunk<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &model.spawn_state());
    for _ in 0..steps_for(&params, 1.0) {
        step_zero(&mut b);
    }
    let z = b.trunk().pose.translation.z;
    assert!(
        z < 0.5 * model.spawn_height(),
        "a limp robot still holds its trunk at {z} m after 1 s (spawn {} m)",
        model.spawn_height()
    );

    // Laid limp with the trunk 2 cm above the ground, in the first orientation (on its side,
    // upside down, on its other side) where the trunk is the robot's lowest part by at least
    // 1 cm, so that it lands first.
    let trunk_index = model.trunk_tracked_index();
    let (roll, mut side) = [
        std::f64::consts::FRAC_PI_2,
        std::f64::consts::PI,
        -std::f64::consts::FRAC_PI_2,
    ]
    .into_iter()
    .map(|roll| {
        let mut s = model.spawn_state();
        s.trunk.pose.rotation = UnitQuaternion::from_euler_angles(roll, 0.0, 0.0);
        (roll, s)
    })
    .find(|(_, s)| {
        let (trunk, rest) = trunk_and_rest_clearance(&model, s);
        trunk + 0.01 <= rest
    })
    .unwrap_or_else(|| {
        panic!(
            "{}: no orientation (side, upside down, other side) puts the trunk below the legs",
            model.name()
        )
    });
    println!(
        "{}: {} laid limp rolled {roll:.2} rad, trunk 2 cm above the ground",
        B::NAME,
        model.name()
    );
    set(&mut b, &side);
    side.trunk.pose.translation.z -= clearances(&b)[trunk_index] - 0.02;
    set(&mut b, &side);
    let mut touched = false;
    for n in 1..=steps_for(&params, 0.5) {
        let before = clearances(&b)[trunk_index];
        step_zero(&mut b);
        let after = clearances(&b)[trunk_index];
        if read_contacts(&b)[trunk_index] {
            assert!(
                before.min(after) <= params.contact_distance + 1e-3,
                "trunk reported in contact at step {n} with {} m clearance",
                before.min(after)
            );
            touched = true;
            break;
        }
    }
    assert!(
        touched,
        "a limp robot on its side never put its trunk on the ground (clearance {} m)",
        clearances(&b)[trunk_index]
    );
}

/// The lowest world z of the trunk's shapes and of every other body's shapes, for a state (by
/// the model's forward kinematics).
fn trunk_and_rest_clearance(model: &RobotModel, state: &RobotState) -> (f64, f64) {
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&state.trunk.pose, &state.q, &mut poses)
        .expect("forward kinematics of a valid state");
    let trunk = model.tracked_lowest_z(model.trunk_tracked_index(), &poses);
    let rest = model
        .links()
        .iter()
        .zip(&poses)
        .skip(1)
        .flat_map(|(l, p)| {
            l.collisions
                .iter()
                .map(move |c| c.shape.lowest_z(&(p * c.origin)))
        })
        .fold(f64::INFINITY, f64::min);
    (trunk, rest)
}

/// A foot held 5 mm above the ground, while the other feet stand on it, is not in contact
/// (an engine's speculative contact at that distance does not count); the feet on the ground
/// are.
pub fn lifted_foot_reports_no_contact<B: Backend>(robot: &Robot, options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(robot, &params, options);
    let model = Arc::clone(b.model());
    let lifted = 0;
    let foot = &model.tracked()[lifted];
    let state = with_foot_lifted(&model, lifted, 5e-3);
    set(&mut b, &state);
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = state.q.clone();
    // 10 ms: the robot settles by well under the 4 mm left above the contact distance.
    for n in 1..=10 {
        step_pd(&mut b, &act, &targets, &mut scratch);
        let flags = read_contacts(&b);
        assert!(
            !flags[lifted],
            "step {n}: foot {} reported in contact {:.2} mm above the ground",
            foot.name,
            1e3 * clearances(&b)[lifted]
        );
        for t in (0..model.num_feet()).filter(|&t| t != lifted) {
            assert!(
                flags[t],
                "step {n}: foot {} on the ground not in contact",
                model.tracked()[t].name
            );
        }
    }
}

/// The spawn state with tracked foot `lifted` raised `lift` m above the other feet, which stand
/// exactly on the ground: the last joint on the foot's chain (e.g. the knee) is turned by a
/// secant search, and must stay within its limits.
fn with_foot_lifted(model: &RobotModel, lifted: usize, lift: f64) -> RobotState {
    let foot = &model.tracked()[lifted];
    let joint = model.links()[foot.link]
        .parent_joint
        .expect("a foot hangs from a joint");
    let mut state = model.spawn_state();
    // Height of the lifted foot above the lowest of the other feet, minus the height wanted.
    let heights = |s: &RobotState| -> Vec<f64> {
        let mut poses = vec![Isometry3::identity(); model.num_links()];
        model
            .link_poses(&s.trunk.pose, &s.q, &mut poses)
            .expect("forward kinematics");
        (0..model.num_feet())
            .map(|t| model.tracked_lowest_z(t, &poses))
            .collect()
    };
    let others = |h: &[f64]| {
        h.iter()
            .enumerate()
            .filter(|&(t, _)| t != lifted)
            .fold(f64::INFINITY, |a, (_, &z)| a.min(z))
    };
    let goal = |s: &RobotState| {
        let h = heights(s);
        h[lifted] - others(&h) - lift
    };
    // Secant search on that joint's angle.
    let (mut a, mut b_angle) = (state.q[joint], state.q[joint] + 0.01);
    let mut fa = goal(&state);
    for _ in 0..50 {
        state.q[joint] = b_angle;
        let fb = goal(&state);
        if fb.abs() < 1e-9 {
            break;
        }
        let next = b_angle - fb * (b_angle - a) / (fb - fa);
        (a, fa, b_angle) = (b_angle, fb, next);
    }
    let j = &model.joints()[joint];
    assert!(
        (j.lower..=j.upper).contains(&state.q[joint]),
        "lifting the foot needs {} = {} rad, outside its limits",
        j.name,
        state.q[joint]
    );
    // Put the standing feet exactly on the ground.
    state.trunk.pose.translation.z -= others(&heights(&state));
    let foot_height = heights(&state)[lifted];
    assert!(
        (foot_height - lift).abs() < 1e-6,
        "foot placed at {foot_height} m"
    );
    state
}
