//! Randomised dynamics, pushes and the actuator's variations: each option acts, and acts as
//! physics says it should, so that every engine draws the same robot from the same numbers.
//! Expected values come from the model and from statics, never from an engine.

use std::sync::Arc;

use nalgebra::{Matrix3, Vector3};

use super::fixtures::{
    Robot, build, build_default, read_contacts, read_q, set, step_pd, steps_for, varied_dynamics,
};
use hyq_physics::actuator::{Actuator, PdScratch, apply_pd};
use hyq_physics::dynamics::{ActuatorScales, Dynamics, DynamicsDraw, TargetDelay};
use hyq_physics::model::RobotModel;
use hyq_physics::{Backend, PhysicsParams, RobotState};

/// The gravity the suite's worlds use (m/s²).
const G: f64 = 9.81;

/// Runs PD sub-steps holding the standing pose for `seconds`, returning the mean trunk height
/// over its last fifth and the joint angles at its end.
fn stand<B: Backend>(b: &mut B, seconds: f64) -> (f64, Vec<f64>) {
    let model = Arc::clone(b.model());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = model.standing_pose().to_vec();
    let steps = steps_for(b.params(), seconds);
    let (mut sum, mut count) = (0.0, 0);
    for n in 0..steps {
        step_pd(b, &act, &targets, &mut scratch);
        if n >= steps * 4 / 5 {
            sum += b.trunk().pose.translation.z;
            count += 1;
        }
    }
    (sum / f64::from(count), read_q(b))
}

/// The robot's vertical stiffness (N/m) standing at joint angles `q` on feet that do not slip,
/// each joint a torsion spring of stiffness `kp`: per foot, the compliance of its point seen
/// from the trunk is `C = Σⱼ Jⱼ Jⱼᵀ / kpⱼ` over the joints of its leg (`Jⱼ` the point's motion
/// per radian of joint j, by central differences of the model's kinematics), its stiffness
/// `S = C⁻¹`, and a trunk lowered by δ without tilting meets `Σ_feet S_zz · δ` more push from
/// the ground. The foot point is its first tracked shape's centre.
fn standing_vertical_stiffness(model: &RobotModel, q: &[f64], kp: &[f64]) -> f64 {
    let trunk = nalgebra::Isometry3::identity();
    let mut poses = vec![nalgebra::Isometry3::identity(); model.num_links()];
    let mut foot_point = |q: &[f64], foot: usize| {
        model
            .link_poses(&trunk, q, &mut poses)
            .expect("kinematics of valid angles");
        let t = &model.tracked()[foot];
        let origin = model.links()[t.link].collisions[t.shapes[0]].origin;
        (poses[t.link] * origin).translation.vector
    };
    let h = 1e-6;
    let mut stiffness = 0.0;
    for foot in 0..model.num_feet() {
        let mut compliance = Matrix3::zeros();
        let mut link = model.tracked()[foot].link;
        while let Some(j) = model.links()[link].parent_joint {
            let (mut up, mut down) = (q.to_vec(), q.to_vec());
            up[j] += h;
            down[j] -= h;
            let column: Vector3<f64> =
                (foot_point(&up, foot) - foot_point(&down, foot)) / (2.0 * h);
            compliance += column * column.transpose() / kp[j];
            link = model.joints()[j].parent;
        }
        let s = compliance
            .try_inverse()
            .expect("a leg of three or more joints has an invertible compliance");
        stiffness += s[(2, 2)];
    }
    stiffness
}

/// +10 kg on the trunk raises the engine's total mass by 10 kg (within 1e-4 kg: rapier holds
/// masses in f32) and lowers the standing height by what statics predicts from the PD gains
/// and the legs' geometry ([`standing_vertical_stiffness`]) within 5 %, the same number for
/// every engine (measured: 1.2–2.6 % above it on rapier, DART and MuJoCo, HyQ and ANYmal C): ground contacts' own compliance (a few hundredths of a millimetre more
/// sinking) and the trunk's slight tilt (its centre of mass is not above the feet's centre) are
/// what the prediction leaves out.
pub fn added_trunk_mass_lowers_the_standing_height<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let model = Arc::clone(&robot.model);
    let params = PhysicsParams::default();
    let mut b: B = build(robot, &params, options);
    set(&mut b, &model.spawn_state());
    let (h0, q0) = stand(&mut b, 1.5);
    let mass0 = b.total_mass();
    let mut draw = DynamicsDraw::nominal(&model, &params);
    draw.trunk_added_mass_kg = 10.0;
    let heavier = draw.dynamics(&model).expect("10 kg more is physical");
    b.set_dynamics(&heavier).expect("valid dynamics");
    set(&mut b, &model.spawn_state());
    let (h1, _) = stand(&mut b, 1.5);
    let added = b.total_mass() - mass0;
    let drop = h0 - h1;
    let expected = 10.0 * G / standing_vertical_stiffness(&model, &q0, model.kp());
    println!(
        "{}: +10 kg: total mass +{added:.6} kg, standing height {h0:.5} -> {h1:.5} m (drop \
         {:.3} mm, statics {:.3} mm, ratio {:.3})",
        B::NAME,
        1e3 * drop,
        1e3 * expected,
        drop / expected
    );
    assert!((added - 10.0).abs() < 1e-4, "total mass grew by {added} kg");
    assert!(
        (drop / expected - 1.0).abs() <= 0.05,
        "standing height dropped {drop} m, statics says {expected} m"
    );
}

/// A world given dynamics in place ([`varied_dynamics`]: every body's mass scaled, the trunk
/// heavier and its centre of mass moved, damping tripled, friction 0.6) follows the trajectory of a world built from
/// a model with those values, within 1e-6 (rad, m, m/s, rad/s) over 0.3 s of random PD
/// targets (rapier and DART agree bit for bit; MuJoCo, which diagonalised the tensors when it
/// compiled the model and does it again in place, to rounding). The engine reads back every
/// body's mass properties as given (relative 1e-5: rapier's f32), so tensors did follow their
/// masses. And the dynamics depend only on the last values given: a world given other
/// dynamics first, or given the model's own back, runs bit for bit as a world given only
/// the last ones; and `reset_with_dynamics` (dynamics and state in one change) is
/// `set_dynamics` then `set_state`, bit for bit.
pub fn in_place_dynamics_match_a_world_built_with_them<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let model = Arc::clone(&robot.model);
    let params = PhysicsParams::default();
    let draw = |seed: u64, friction: f64| varied_dynamics(&model, seed, friction);
    let dynamics = draw(5, 0.6);
    let run = |b: &mut B| {
        set(b, &model.spawn_state());
        super::fixtures::random_pd_trajectory(b, 9, 300)
    };

    let mut in_place: B = build_default(robot, options);
    in_place.set_dynamics(&dynamics).expect("valid dynamics");
    check_read_back(&in_place, &dynamics);
    let built_params = PhysicsParams {
        ground_friction: dynamics.ground_friction,
        ..params.clone()
    };
    let mut built = B::build(
        Arc::new(model.with_mass_properties(&dynamics.bodies, &dynamics.joint_damping)),
        &built_params,
        options,
    )
    .unwrap_or_else(|e| panic!("{} failed to build the varied model: {e}", B::NAME));
    let (a, b) = (run(&mut in_place), run(&mut built));
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (f64::from_bits(*x) - f64::from_bits(*y)).abs())
        .fold(0.0, f64::max);
    println!(
        "{}: in place vs built: bitwise {}, largest difference {worst:e}",
        B::NAME,
        a == b
    );
    assert!(
        worst <= 1e-6,
        "in-place dynamics drift {worst} from a built world"
    );

    let mut at_once: B = build_default(robot, options);
    at_once
        .reset_with_dynamics(&dynamics, &model.spawn_state())
        .expect("valid dynamics and state");
    assert!(
        super::fixtures::random_pd_trajectory(&mut at_once, 9, 300) == a,
        "{}: reset_with_dynamics differs from set_dynamics and set_state",
        B::NAME
    );

    let mut history: B = build_default(robot, options);
    history.set_dynamics(&draw(6, 0.9)).expect("valid dynamics");
    history.set_dynamics(&dynamics).expect("valid dynamics");
    assert!(
        run(&mut history) == a,
        "{}: earlier dynamics leaked into later ones",
        B::NAME
    );
    let nominal = Dynamics::nominal(&model, &params);
    history.set_dynamics(&nominal).expect("valid dynamics");
    let mut fresh: B = build_default(robot, options);
    assert!(
        run(&mut history) == run(&mut fresh),
        "{}: the model's own dynamics given back differ from a fresh world",
        B::NAME
    );
}

/// Every body's mass properties and the total mass, read back from the engine, are those
/// given (relative 1e-5).
fn check_read_back<B: Backend>(b: &B, d: &Dynamics) {
    let close = |x: f64, y: f64, scale: f64| (x - y).abs() <= 1e-5 * scale.max(1e-12);
    for (i, given) in d.bodies.iter().enumerate() {
        let held = b.body_mass_properties(i);
        let name = &b.model().links()[i].name;
        assert!(
            close(held.mass, given.mass, given.mass),
            "{}: body {name} holds mass {} kg, given {}",
            B::NAME,
            held.mass,
            given.mass
        );
        assert!(
            (held.com - given.com).norm() <= 1e-5,
            "{}: body {name} holds centre of mass {:?}, given {:?}",
            B::NAME,
            held.com,
            given.com
        );
        let scale = given.inertia.abs().max();
        assert!(
            (held.inertia - given.inertia).abs().max() <= 1e-5 * scale,
            "{}: body {name} holds inertia {:?}, given {:?} (not recomputed?)",
            B::NAME,
            held.inertia,
            given.inertia
        );
    }
    assert!(
        close(b.total_mass(), d.total_mass(), d.total_mass()),
        "{}: total mass {} kg, given {}",
        B::NAME,
        b.total_mass(),
        d.total_mass()
    );
}

/// Standing, then pushed forward at 1.5 m/s: at ground friction 0.3 the trunk travels further
/// in the next 0.7 s than at 1.0 (by more than 2 cm), and at 0.3 it slides the distance
/// Coulomb's law gives a block, v²/(2μg) = 0.38 m, within 0.6–1.2 times (the legs, flexing
/// under the push, keep the feet from sliding from the first instant: measured 0.71–0.96 on
/// rapier, DART and MuJoCo, HyQ and ANYmal C). The friction given acts on the ground,
/// whatever its shape.
pub fn lower_ground_friction_lets_a_pushed_robot_slide_further<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let model = Arc::clone(&robot.model);
    let params = PhysicsParams::default();
    let slide = |friction: f64| {
        let mut b: B = build(robot, &params, options);
        let mut d = Dynamics::nominal(&model, &params);
        d.ground_friction = friction;
        b.set_dynamics(&d).expect("valid dynamics");
        set(&mut b, &model.spawn_state());
        stand(&mut b, 0.5);
        let x0 = b.trunk().pose.translation.x;
        b.push_trunk(&Vector3::new(1.5, 0.0, 0.0))
            .expect("a finite push");
        let (_, _) = stand(&mut b, 0.7);
        b.trunk().pose.translation.x - x0
    };
    let (slippery, grippy) = (slide(0.3), slide(1.0));
    println!(
        "{}: pushed at 1.5 m/s, the trunk travelled {slippery:.3} m at friction 0.3, \
         {grippy:.3} m at 1.0",
        B::NAME
    );
    assert!(
        slippery > grippy + 0.02,
        "friction 0.3: {slippery} m, friction 1.0: {grippy} m"
    );
    let block = 1.5_f64.powi(2) / (2.0 * 0.3 * G);
    assert!(
        (0.6..=1.2).contains(&(slippery / block)),
        "friction 0.3: slid {slippery} m, a block slides {block} m"
    );
}

/// A push of 1 m/s along x on a standing robot shows in the trunk's velocity after the next
/// sub-step within 5 % (the feet's friction and the legs take a little of it back), leaves
/// the other components within 0.05 m/s of where they were, and is not a reset: the contact
/// flags of the last step still read the feet on the ground right after it, and the next step
/// finds them there.
pub fn a_trunk_push_adds_to_its_velocity<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = Arc::clone(&robot.model);
    let mut b: B = build_default(robot, options);
    set(&mut b, &model.spawn_state());
    stand(&mut b, 0.5);
    let feet = model.num_feet();
    assert!(
        read_contacts(&b)[..feet].iter().all(|&c| c),
        "{}: the feet must be down before the push",
        B::NAME
    );
    let v0 = b.trunk().linvel;
    b.push_trunk(&Vector3::new(1.0, 0.0, 0.0))
        .expect("a finite push");
    assert!(
        read_contacts(&b)[..feet].iter().all(|&c| c),
        "{}: a push cleared the contact flags (a reset?)",
        B::NAME
    );
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    step_pd(&mut b, &act, model.standing_pose(), &mut scratch);
    let dv = b.trunk().linvel - v0;
    println!(
        "{}: after a 1 m/s push and one sub-step the trunk's velocity changed by {:.4?} m/s",
        B::NAME,
        dv.as_slice()
    );
    assert!((dv.x - 1.0).abs() <= 0.05, "velocity change {dv:?}");
    assert!(
        dv.y.abs() <= 0.05 && dv.z.abs() <= 0.05,
        "velocity change {dv:?}"
    );
    assert!(
        read_contacts(&b)[..feet].iter().all(|&c| c),
        "{}: the feet left the ground in the sub-step after the push",
        B::NAME
    );
    let err = b
        .push_trunk(&Vector3::new(f64::NAN, 0.0, 0.0))
        .expect_err("a NaN push");
    assert!(err.to_string().contains("trunk velocity change"), "{err}");
}

/// With an actuator delay of k sub-steps, a change of targets at an env step reaches the PD
/// law exactly k sub-steps later: the torque trace of a run whose targets change at sub-step
/// 10 (the second env step of 10 sub-steps) first leaves the trace of a run whose targets never
/// change at sub-step 10 + k, by exactly kp · Δtarget (the states are bitwise the same up to
/// there), for k = 0, 3 and 10.
pub fn actuator_delay_shifts_the_torque_trace_by_exactly_k<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let model = Arc::clone(&robot.model);
    let n = model.num_joints();
    let act = Actuator::new(&model);
    let standing = model.standing_pose().to_vec();
    let moved: Vec<f64> = standing.iter().map(|q| q + 0.02).collect();
    // Torques of 4 env steps of 10 sub-steps: targets `first` in env step 0, `later` after.
    let trace = |delay_substeps: u32, later: &[f64]| {
        let mut b: B = build_default(robot, options);
        set(&mut b, &model.spawn_state());
        let mut delay = TargetDelay::new(n);
        delay
            .set_substeps(delay_substeps, 10)
            .expect("within a step");
        delay.reset(&model.spawn_state().q);
        let mut scratch = PdScratch::new(n);
        let mut torques = Vec::new();
        for step in 0..4 {
            let current = if step == 0 { &standing[..] } else { later };
            for s in 0..10 {
                apply_pd(&mut b, &act, delay.seen(s, current), &mut scratch)
                    .expect("valid targets");
                torques.push(scratch.torques().to_vec());
                b.step()
                    .unwrap_or_else(|e| panic!("{} failed a step: {e}", B::NAME));
            }
            delay.end_step(current);
        }
        torques
    };
    for k in [0u32, 3, 10] {
        let unchanged = trace(k, &standing);
        let changed = trace(k, &moved);
        let first = unchanged
            .iter()
            .zip(&changed)
            .position(|(a, b)| a != b)
            .expect("the change of targets reaches the torques");
        assert_eq!(
            first,
            10 + k as usize,
            "{}: delay {k}: the torques changed at sub-step {first}",
            B::NAME
        );
        for (i, (a, b)) in unchanged[first].iter().zip(&changed[first]).enumerate() {
            let expected = act.kp()[i] * 0.02;
            assert!(
                ((b - a) - expected).abs() <= 1e-9 * expected.max(1.0),
                "{}: delay {k}: joint {i}'s torque changed by {} N·m, kp·Δ is {expected}",
                B::NAME,
                b - a
            );
        }
    }
}

/// Each actuator scale acts on the torque the engine's state gives (joint friction scaled to 0
/// throughout, so the torque is the PD law's): from a state at rest with
/// every joint 0.01 rad from its target, kp × 0.5 halves the PD torque exactly; from a state
/// on target with every joint at 0.2 rad/s, kd × 0.5 halves it exactly; and effort × 0.01
/// caps it at a hundredth of the effort limit.
pub fn actuator_scales_scale_the_pd_torque<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = Arc::clone(&robot.model);
    let n = model.num_joints();
    let base = Actuator::new(&model);
    let mut b: B = build_default(robot, options);
    let first_torques = |b: &mut B, scales: &ActuatorScales, state: &RobotState, error: f64| {
        let mut act = base.clone();
        act.scale_from(&base, scales).expect("valid scales");
        set(b, state);
        let targets: Vec<f64> = read_q(b).iter().map(|q| q + error).collect();
        let mut scratch = PdScratch::new(n);
        apply_pd(b, &act, &targets, &mut scratch).expect("valid targets");
        scratch.torques().to_vec()
    };
    let at_rest = model.spawn_state();
    let mut moving = model.spawn_state();
    moving.qd.fill(0.2);
    // Joint friction off in every run, so that the torque is the PD law's and its limits'.
    let mut nominal = ActuatorScales::nominal(n);
    nominal.friction.fill(0.0);
    let half = |pick: fn(&mut ActuatorScales) -> &mut Vec<f64>, value: f64| {
        let mut s = nominal.clone();
        pick(&mut s).fill(value);
        s
    };
    let kp = (
        first_torques(&mut b, &nominal, &at_rest, 0.01),
        first_torques(&mut b, &half(|s| &mut s.kp, 0.5), &at_rest, 0.01),
    );
    let kd = (
        first_torques(&mut b, &nominal, &moving, 0.0),
        first_torques(&mut b, &half(|s| &mut s.kd, 0.5), &moving, 0.0),
    );
    for (what, (full, halved)) in [("kp", kp), ("kd", kd)] {
        for i in 0..n {
            assert!(full[i] != 0.0, "{what}: joint {i} has no torque to halve");
            assert_eq!(
                halved[i],
                0.5 * full[i],
                "{}: {what} × 0.5 on joint {i}",
                B::NAME
            );
        }
    }
    let capped = first_torques(&mut b, &half(|s| &mut s.effort, 0.01), &at_rest, 0.5);
    for (i, tau) in capped.iter().enumerate() {
        let cap = 0.01 * model.joints()[i].effort;
        assert!(
            (tau.abs() - cap).abs() <= 1e-12 * cap,
            "{}: effort × 0.01 on joint {i}: torque {tau}, cap {cap}",
            B::NAME
        );
    }
}

/// Dynamics the model cannot simulate are refused by name before the world changes (it then
/// runs exactly as before): a non-positive mass, a tensor that is not positive definite, a
/// negative friction or damping, a wrong count.
pub fn unphysical_dynamics_are_refused<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = Arc::clone(&robot.model);
    let params = PhysicsParams::default();
    let nominal = Dynamics::nominal(&model, &params);
    let mut b: B = build_default(robot, options);
    let mut cases: Vec<(Dynamics, &str)> = Vec::new();
    let mut d = nominal.clone();
    d.bodies[1].mass = 0.0;
    cases.push((d, "mass 0 must be finite and in [1e-4, 1e6] kg"));
    let mut d = nominal.clone();
    d.bodies[0].inertia = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
    cases.push((d, "positive semi-definite"));
    let mut d = nominal.clone();
    d.ground_friction = f64::NAN;
    cases.push((d, "ground friction"));
    let mut d = nominal.clone();
    d.joint_damping[0] = -0.1;
    cases.push((d, "damping of joint"));
    let mut d = nominal.clone();
    d.bodies.pop();
    cases.push((d, "one per body"));
    for (d, says) in cases {
        let err = b
            .set_dynamics(&d)
            .expect_err("unphysical dynamics")
            .to_string();
        assert!(
            err.contains(says),
            "{}: {err:?} should say {says:?}",
            B::NAME
        );
    }
    set(&mut b, &model.spawn_state());
    let after = super::fixtures::random_pd_trajectory(&mut b, 3, 50);
    let mut fresh: B = build_default(robot, options);
    set(&mut fresh, &model.spawn_state());
    assert!(
        after == super::fixtures::random_pd_trajectory(&mut fresh, 3, 50),
        "{}: a refused change altered the world",
        B::NAME
    );
}
