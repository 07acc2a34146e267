//! The measurements behind the MuJoCo backend's settings table (crate README): one row per run.
//!
//! ```sh
//! cargo run --release -p hyq-mujoco --example settings -- [key=value ...]
//! ```
//!
//! Keys are `[physics.mujoco]` options in TOML syntax (e.g. `cone='"elliptic"'`,
//! `limit_solref=[0.005,1]`, `noslip_iterations=10`). Prints, for those settings:
//! - `stand_z`: trunk height after 10 s of the standing PD from the spawn state (m);
//! - `sink_mm`: how far the feet sink into the ground at that point (lowest foot clearance, mm);
//! - `slide_mm`: how far the feet slide on the ground between 1 s and 10 s (largest horizontal
//!   foot displacement, mm);
//! - `overshoot`: worst joint-limit overshoot with every joint driven into its limits at full
//!   torque (kp 3000, kd 30), floating in zero gravity and standing on the ground (rad);
//! - `drift_mm`: how far the centre of mass leaves its straight line in 1 s of free tumbling
//!   and flailing in zero gravity (mm);
//! - `us_random`: CPU time per PD sub-step under random targets redrawn every 10 sub-steps,
//!   reset when the trunk touches the ground (µs), and `resets` in that run.

use std::sync::Arc;
use std::time::Instant;

use cpu_time::ProcessTime;
use hyq_conformance::fixtures::Rng;
use hyq_mujoco::{MujocoBackend, MujocoOptions};
use hyq_physics::na::{Isometry3, Vector3};
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, RobotModel, pd_substep};

fn build(params: &PhysicsParams, options: &MujocoOptions) -> MujocoBackend {
    MujocoBackend::build(hyq_physics::bundled::hyq(), params, options)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn poses(b: &MujocoBackend) -> Vec<Isometry3<f64>> {
    let model = b.model();
    let mut q = vec![0.0; model.num_joints()];
    b.joint_positions(&mut q);
    let mut out = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&b.trunk().pose, &q, &mut out)
        .unwrap_or_else(|e| panic!("{e}"));
    out
}

fn foot_centres(model: &RobotModel, poses: &[Isometry3<f64>]) -> Vec<Vector3<f64>> {
    model.tracked()[..model.num_feet()]
        .iter()
        .map(|t| {
            (poses[t.link] * model.links()[t.link].collisions[t.shapes[0]].origin)
                .translation
                .vector
        })
        .collect()
}

fn stand(options: &MujocoOptions) -> (f64, f64, f64) {
    let params = PhysicsParams::default();
    let mut b = build(&params, options);
    let model = Arc::clone(b.model());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = model.standing_pose().to_vec();
    let mut at_1s = Vec::new();
    for n in 1..=10_000 {
        pd_substep(&mut b, &act, &targets, &mut scratch).unwrap_or_else(|e| panic!("{e}"));
        if n == 1000 {
            at_1s = foot_centres(&model, &poses(&b));
        }
    }
    let p = poses(&b);
    let sink = (0..model.num_feet())
        .map(|t| model.tracked_lowest_z(t, &p))
        .fold(f64::INFINITY, f64::min);
    let slide = foot_centres(&model, &p)
        .iter()
        .zip(&at_1s)
        .map(|(a, b)| (a - b).xy().norm())
        .fold(0.0, f64::max);
    (b.trunk().pose.translation.z, -sink, slide)
}

fn overshoot(options: &MujocoOptions) -> f64 {
    let model = hyq_physics::bundled::hyq();
    let n = model.num_joints();
    let act = Actuator::with_gains(&model, &vec![3000.0; n], &vec![30.0; n])
        .unwrap_or_else(|e| panic!("{e}"));
    let mut worst: f64 = 0.0;
    let zero_g = PhysicsParams {
        gravity: [0.0; 3],
        ..PhysicsParams::default()
    };
    let mut air = model.spawn_state();
    air.trunk.pose.translation.z = 3.0;
    for (params, start) in [
        (zero_g, air),
        (PhysicsParams::default(), model.spawn_state()),
    ] {
        let mut b = build(&params, options);
        b.set_state(&start).unwrap_or_else(|e| panic!("{e}"));
        let mut scratch = PdScratch::new(n);
        let mut q = vec![0.0; n];
        for phase in 0..4 {
            let targets: Vec<f64> = model
                .joints()
                .iter()
                .map(|j| {
                    if phase % 2 == 0 {
                        j.upper + 0.5
                    } else {
                        j.lower - 0.5
                    }
                })
                .collect();
            for _ in 0..500 {
                pd_substep(&mut b, &act, &targets, &mut scratch).unwrap_or_else(|e| panic!("{e}"));
                b.joint_positions(&mut q);
                for (qi, j) in q.iter().zip(model.joints()) {
                    worst = worst.max((j.lower - qi).max(qi - j.upper));
                }
            }
        }
    }
    worst
}

fn drift(options: &MujocoOptions) -> f64 {
    let params = PhysicsParams {
        gravity: [0.0; 3],
        ..PhysicsParams::default()
    };
    let mut b = build(&params, options);
    let model = Arc::clone(b.model());
    let mut start = model.spawn_state();
    start.trunk.pose.translation.z = 3.0;
    start.trunk.linvel = Vector3::new(1.0, -0.3, 0.5);
    start.trunk.angvel = Vector3::new(0.5, -0.8, 4.0);
    b.set_state(&start).unwrap_or_else(|e| panic!("{e}"));
    let zeros = vec![0.0; model.num_joints()];
    let c0 = model.centre_of_mass(&poses(&b));
    b.set_joint_torques(&zeros)
        .unwrap_or_else(|e| panic!("{e}"));
    b.step().unwrap_or_else(|e| panic!("{e}"));
    let c1 = model.centre_of_mass(&poses(&b));
    let v = (c1 - c0) / params.dt;
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(17);
    let mut targets = model.standing_pose().to_vec();
    let mut worst: f64 = 0.0;
    for n in 2..=1000 {
        if n % 50 == 0 {
            targets = rng.joint_angles(&model, 0.1);
        }
        pd_substep(&mut b, &act, &targets, &mut scratch).unwrap_or_else(|e| panic!("{e}"));
        let t = (n - 1) as f64 * params.dt;
        worst = worst.max((model.centre_of_mass(&poses(&b)) - (c1 + v * t)).norm());
    }
    worst
}

fn speed(options: &MujocoOptions) -> (f64, f64, usize) {
    let params = PhysicsParams::default();
    let mut b = build(&params, options);
    let model = Arc::clone(b.model());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(37);
    let mut targets = model.standing_pose().to_vec();
    let trunk = model.trunk_tracked_index();
    let mut flags = vec![false; model.tracked().len()];
    let spawn = model.spawn_state();
    let steps = 40_000;
    let mut resets = 0;
    let (wall, cpu) = (Instant::now(), ProcessTime::now());
    for i in 0..steps {
        if i % 10 == 0 {
            targets = rng.joint_angles(&model, 0.0);
        }
        pd_substep(&mut b, &act, &targets, &mut scratch).unwrap_or_else(|e| panic!("{e}"));
        b.contacts(&mut flags);
        if flags[trunk] {
            b.set_state(&spawn).unwrap_or_else(|e| panic!("{e}"));
            resets += 1;
        }
    }
    let per = |s: f64| 1e6 * s / steps as f64;
    (
        per(cpu.elapsed().as_secs_f64()),
        per(wall.elapsed().as_secs_f64()),
        resets,
    )
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let options: MujocoOptions =
        toml::from_str(&args.join("\n")).unwrap_or_else(|e| panic!("options {args:?}: {e}"));
    let (z, sink, slide) = stand(&options);
    let over = overshoot(&options);
    let drift = drift(&options);
    let (cpu_us, wall_us, resets) = speed(&options);
    println!(
        "{:<48} stand_z {z:.5} sink_mm {:.3} slide_mm {:.2} overshoot {over:.4} drift_mm {:.2} \
         us_random {cpu_us:.2} (wall {wall_us:.2}) resets {resets}",
        if args.is_empty() {
            "defaults".to_owned()
        } else {
            args.join(" ")
        },
        1e3 * sink,
        1e3 * slide,
        1e3 * drift
    );
}
