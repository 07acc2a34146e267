//! Invariant: the MJCF generator's actuator styles compile in MuJoCo and mean what they say, so
//! a MuJoCo user (or a MuJoCo-from-Python benchmark) driving the generated model gets the
//! backend's physics:
//! - `<motor>` actuators driven with the shared actuator's torques as controls reproduce the
//!   backend's own trajectory (torques written as applied forces) bit for bit;
//! - `<position>` servos with the model's gains, driven with the standing pose as targets, stand
//!   HyQ where the shared PD actuator does (the same law, evaluated by MuJoCo inside its step).

use hyq_conformance::fixtures::Rng;
use hyq_formats::mjcf::{Actuators, MjcfOptions, to_mjcf};
use hyq_mujoco::raw::{World, layout};
use hyq_mujoco::{MujocoBackend, MujocoOptions};
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, bundled, pd_substep};

/// A world compiled from the generator's MJCF with `actuators`, at the spawn state, with the
/// backend's solver settings.
fn world(actuators: Actuators) -> World {
    let model = bundled::hyq();
    let options = MjcfOptions {
        actuators,
        solver: MujocoOptions::default(),
        ..MjcfOptions::from_params(&PhysicsParams::default())
    };
    let mjcf = to_mjcf(&model, &options).expect("the bundled HyQ has an MJCF");
    let mut w = World::new(&mjcf.xml, &layout(&model, &mjcf)).expect("MuJoCo compiles it");
    let s = model.spawn_state();
    let t = s.trunk.pose.translation.vector;
    let r = s.trunk.pose.rotation.quaternion();
    w.set_state(&[t.x, t.y, t.z, r.w, r.i, r.j, r.k], &[0.0; 6], &s.q, &s.qd)
        .expect("the spawn state is valid");
    w
}

#[test]
fn motors_driven_with_the_shared_torques_reproduce_the_backend_bitwise() {
    let model = bundled::hyq();
    let n = model.num_joints();
    let act = Actuator::new(&model);
    let mut backend = MujocoBackend::build(
        model.clone(),
        &PhysicsParams::default(),
        &MujocoOptions::default(),
    )
    .expect("builds");
    let mut motors = world(Actuators::Motor);
    let (mut scratch, mut q, mut qd, mut tau) =
        (PdScratch::new(n), vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut contacts = vec![0u8; model.tracked().len()];
    let mut flags = vec![false; model.tracked().len()];
    let mut rng = Rng::new(7);
    let mut targets = model.standing_pose().to_vec();
    for k in 0..2000 {
        if k % 10 == 0 {
            rng.fill_joint_angles(&model, 0.0, &mut targets);
        }
        pd_substep(&mut backend, &act, &targets, &mut scratch).expect("a backend step");
        motors.joint_positions(&mut q);
        motors.joint_velocities(&mut qd);
        act.torques(&targets, &q, &qd, &mut tau).expect("lengths");
        motors.set_controls(&tau);
        motors.step(&mut contacts).expect("a motor step");
        let (pose, vel) = motors.root_state();
        let b = backend.trunk();
        let bt = b.pose.translation.vector;
        let bq = b.pose.rotation.quaternion();
        assert_eq!(
            [pose[0], pose[1], pose[2]],
            [bt.x, bt.y, bt.z],
            "step {k}: trunk position"
        );
        assert_eq!(
            [vel[0], vel[1], vel[2]],
            [b.linvel.x, b.linvel.y, b.linvel.z]
        );
        // The backend's quaternion went through a normalisation: equal to rounding.
        let dq = (pose[3] - bq.w).abs()
            + (pose[4] - bq.i).abs()
            + (pose[5] - bq.j).abs()
            + (pose[6] - bq.k).abs();
        assert!(dq < 1e-14, "step {k}: orientation differs by {dq}");
        backend.joint_positions(&mut q);
        let mut q_motor = vec![0.0; n];
        motors.joint_positions(&mut q_motor);
        assert_eq!(q, q_motor, "step {k}: joint angles");
        let mut qd_motor = vec![0.0; n];
        backend.joint_velocities(&mut qd);
        motors.joint_velocities(&mut qd_motor);
        assert_eq!(qd, qd_motor, "step {k}: joint speeds");
        backend.contacts(&mut flags);
        let motor_flags: Vec<bool> = contacts.iter().map(|&c| c != 0).collect();
        assert_eq!(flags, motor_flags, "step {k}: contacts");
    }
}

#[test]
fn position_servos_stand_hyq_where_the_shared_actuator_does() {
    let model = bundled::hyq();
    let mut servos = world(Actuators::Position);
    servos.set_controls(model.standing_pose());
    let mut contacts = vec![0u8; model.tracked().len()];
    for _ in 0..2000 {
        servos.step(&mut contacts).expect("a servo step");
    }
    let mut backend = MujocoBackend::build(
        model.clone(),
        &PhysicsParams::default(),
        &MujocoOptions::default(),
    )
    .expect("builds");
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    for _ in 0..2000 {
        pd_substep(&mut backend, &act, model.standing_pose(), &mut scratch).expect("a step");
    }
    let z_servo = servos.root_state().0[2];
    let z_shared = backend.trunk().pose.translation.z;
    println!("standing after 2 s: servos {z_servo} m, shared actuator {z_shared} m");
    // The same law up to rounding (MuJoCo evaluates kp·q* − kp·q − kd·q̇ as one affine
    // function), so the two stand within a micrometre.
    assert!(
        (z_servo - z_shared).abs() < 1e-6,
        "servos {z_servo} m, shared actuator {z_shared} m"
    );
    assert!(contacts[..model.num_feet()].iter().all(|&c| c == 1));
    assert_eq!(contacts[model.trunk_tracked_index()], 0);
}
