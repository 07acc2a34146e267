//! Cost of one DART physics sub-step of HyQ, the way the environment takes it: shared PD
//! actuator (read q and q̇, compute 12 torques), set the torques, step DART, read back the
//! contact flags. Two workloads: standing still on four feet (settled for 1 s first), and
//! random joint targets redrawn every 10 sub-steps (feet landing and lifting, joints at their
//! limits), and the cost of `set_state` (which installs a fresh collision detector).
//!
//! Run: `cargo bench -p hyq-dart --bench step`.

use criterion::{Criterion, criterion_group, criterion_main};
use hyq_dart::{DartBackend, DartOptions};
use hyq_physics::conformance::fixtures::Rng;
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, bundled, pd_substep};

fn hyq() -> DartBackend {
    DartBackend::build(
        bundled::hyq(),
        &PhysicsParams::default(),
        &DartOptions::default(),
    )
    .expect("the bundled HyQ builds on DART")
}

fn step(c: &mut Criterion) {
    let model = bundled::hyq();
    let n = model.num_joints();
    let act = Actuator::new(&model);
    let mut contacts = vec![false; model.tracked().len()];
    let mut group = c.benchmark_group("dart_substep");

    let mut b = hyq();
    let mut scratch = PdScratch::new(n);
    let standing = model.standing_pose().to_vec();
    for _ in 0..1000 {
        pd_substep(&mut b, &act, &standing, &mut scratch).expect("standing stays finite");
    }
    group.bench_function("standing", |bench| {
        bench.iter(|| {
            pd_substep(&mut b, &act, &standing, &mut scratch).expect("standing stays finite");
            b.contacts(&mut contacts);
        });
    });

    let mut b = hyq();
    let mut targets = standing.clone();
    let mut rng = Rng::new(0);
    let mut k = 0_u64;
    group.bench_function("random_targets", |bench| {
        bench.iter(|| {
            if k.is_multiple_of(10) {
                rng.fill_joint_angles(&model, 0.0, &mut targets);
            }
            k += 1;
            pd_substep(&mut b, &act, &targets, &mut scratch).expect("random targets stay finite");
            b.contacts(&mut contacts);
        });
    });

    let mut b = hyq();
    let spawn = model.spawn_state();
    group.bench_function("set_state", |bench| {
        bench.iter(|| b.set_state(&spawn).expect("the spawn state is valid"));
    });
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
