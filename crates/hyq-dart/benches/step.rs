//! Cost of one DART physics sub-step of HyQ, the way the environment takes it: shared PD
//! actuator (read q and q̇, compute 12 torques), set the torques, step DART, read back the
//! contact flags. Two workloads: standing still on four feet (settled for 1 s first), and
//! random joint targets redrawn every 10 sub-steps (feet landing and lifting, joints at their
//! limits), the cost of `set_state` (which installs a fresh collision detector), and of a
//! randomised episode's reset (`reset_with_dynamics`: other masses, damping and friction with
//! the spawn state). The workloads are hyq-conformance's `SubstepWorkloads`, which the MuJoCo
//! backend's bench times too.
//!
//! Run: `cargo bench -p hyq-dart --bench step`.

use criterion::{Criterion, criterion_group, criterion_main};
use hyq_conformance::fixtures::{Robot, SubstepWorkloads};
use hyq_dart::{DartBackend, DartOptions};

fn step(c: &mut Criterion) {
    let robot = Robot::bundled("hyq");
    let mut w = SubstepWorkloads::<DartBackend>::new(&robot, &DartOptions::default(), false);
    let mut group = c.benchmark_group("dart_substep");
    group.bench_function("standing", |bench| bench.iter(|| w.standing()));
    group.bench_function("random_targets", |bench| bench.iter(|| w.random_targets()));
    group.bench_function("set_state", |bench| bench.iter(|| w.set_state()));
    group.bench_function("randomized_reset", |bench| {
        bench.iter(|| w.randomized_reset())
    });
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
