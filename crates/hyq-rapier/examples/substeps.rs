//! A fixed, deterministic sub-step workload for profilers (callgrind, perf) and for checking
//! that a change to the backend keeps trajectories bit-identical.
//!
//! ```sh
//! cargo build --profile profiling -p hyq-rapier --example substeps
//! valgrind --tool=callgrind target/profiling/examples/substeps random 2 2000
//! target/profiling/examples/substeps stand 2 2000   # prints the trajectory hash
//! ```
//!
//! Arguments: scenario (`stand` or `random`), solver iterations, number of PD sub-steps, and
//! optionally `--mass-matrix-once-per-step` (`RapierOptions::mass_matrix_once_per_step`).
//! `stand` first settles for 1000 sub-steps and then measures; `random` draws targets inside
//! the limits every 10 sub-steps (one environment step) and resets to the spawn state when the
//! trunk touches the ground, as the criterion benchmark does. Both print the mean wall time
//! per measured sub-step and a hash of every joint angle, joint speed, trunk pose and contact
//! flag after each measured sub-step.

use std::collections::hash_map::DefaultHasher;
use std::hash::Hasher;
use std::time::Instant;

use hyq_conformance::fixtures::Rng;
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsError, PhysicsParams, bundled, pd_substep};
use hyq_rapier::{RapierBackend, RapierOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: substeps <stand|random> <solver iterations> <sub-steps> [--mass-matrix-once-per-step]";
    let (Some(scenario), Some(iterations), Some(steps)) = (args.get(1), args.get(2), args.get(3))
    else {
        return Err(usage.into());
    };
    let random = match scenario.as_str() {
        "stand" => false,
        "random" => true,
        other => return Err(format!("unknown scenario {other:?}; {usage}").into()),
    };
    let mass_matrix_once_per_step = match args.get(4).map(String::as_str) {
        None => false,
        Some("--mass-matrix-once-per-step") => true,
        Some(other) => return Err(format!("unknown option {other:?}; {usage}").into()),
    };
    let options = RapierOptions {
        solver_iterations: iterations.parse()?,
        mass_matrix_once_per_step,
        ..RapierOptions::default()
    };
    let steps: u64 = steps.parse()?;

    let model = bundled::hyq();
    let mut b = RapierBackend::build(model.clone(), &PhysicsParams::default(), &options)?;
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let standing = model.standing_pose().to_vec();
    let mut targets = standing.clone();
    let mut contacts = vec![false; model.tracked().len()];
    let trunk = model.trunk_tracked_index();
    let spawn = model.spawn_state();
    // The criterion benchmark's stream, so both draw the same targets.
    let mut rng = Rng::new(0);
    if !random {
        for _ in 0..1000 {
            pd_substep(&mut b, &act, &standing, &mut scratch)?;
        }
    }

    let mut hasher = DefaultHasher::new();
    let mut q = vec![0.0; model.num_joints()];
    let mut qd = vec![0.0; model.num_joints()];
    let mut resets = 0u64;
    let start = Instant::now();
    for n in 0..steps {
        if random && n % 10 == 0 {
            rng.fill_joint_angles(&model, 0.0, &mut targets);
        }
        pd_substep(&mut b, &act, &targets, &mut scratch)?;
        b.contacts(&mut contacts);
        b.joint_positions(&mut q);
        b.joint_velocities(&mut qd);
        let t = b.trunk();
        for v in q.iter().chain(&qd).chain(t.pose.translation.vector.iter()) {
            hasher.write_u64(v.to_bits());
        }
        for v in t
            .pose
            .rotation
            .coords
            .iter()
            .chain(t.linvel.iter())
            .chain(t.angvel.iter())
        {
            hasher.write_u64(v.to_bits());
        }
        for &c in &contacts {
            hasher.write_u8(u8::from(c));
        }
        if contacts[trunk] {
            b.set_state(&spawn)
                .map_err(|e: PhysicsError| e.to_string())?;
            resets += 1;
        }
    }
    let elapsed = start.elapsed();
    println!(
        "{scenario} {iterations} iterations: {steps} sub-steps, {resets} resets, {:.2} µs per sub-step, hash {:016x}",
        elapsed.as_secs_f64() * 1e6 / steps as f64,
        hasher.finish()
    );
    Ok(())
}
