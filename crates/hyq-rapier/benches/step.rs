//! Cost of one physics sub-step of the rapier backend (standing, and under random joint
//! targets) and of a reset, plain or randomised. `cargo bench -p hyq-rapier`; figures in the
//! crate's README.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use hyq_conformance::fixtures::{Rng, Robot, SubstepWorkloads};
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, bundled, pd_substep};
use hyq_rapier::{RapierBackend, RapierOptions};

fn backend(options: &RapierOptions) -> RapierBackend {
    // Benchmarks may panic on setup failure: there is no caller to report to.
    #[allow(clippy::expect_used)]
    RapierBackend::build(bundled::hyq(), &PhysicsParams::default(), options).expect("builds")
}

#[allow(clippy::expect_used)]
fn substep(c: &mut Criterion) {
    let model = bundled::hyq();
    let act = Actuator::new(&model);
    let standing = model.standing_pose().to_vec();
    let mut group = c.benchmark_group("rapier");

    for iterations in [4, 2, 1] {
        let options = RapierOptions {
            solver_iterations: iterations,
            ..RapierOptions::default()
        };

        // Standing: settled for 1 s first, then one PD sub-step per iteration.
        let mut b = backend(&options);
        let mut scratch = PdScratch::new(model.num_joints());
        for _ in 0..1000 {
            pd_substep(&mut b, &act, &standing, &mut scratch).expect("settles");
        }
        group.bench_function(
            format!("substep/standing/{iterations}_iterations"),
            |bench| bench.iter(|| pd_substep(&mut b, &act, black_box(&standing), &mut scratch)),
        );

        // Random targets inside the limits, redrawn every 10 sub-steps (one env step), reset
        // to the spawn state when the trunk touches the ground (rare; included).
        let mut b = backend(&options);
        let mut rng = Rng::new(0);
        let mut targets = standing.clone();
        let mut contacts = vec![false; model.tracked().len()];
        let trunk = model.trunk_tracked_index();
        let spawn = model.spawn_state();
        let mut n = 0u64;
        group.bench_function(
            format!("substep/random_targets/{iterations}_iterations"),
            |bench| {
                bench.iter(|| {
                    if n.is_multiple_of(10) {
                        rng.fill_joint_angles(&model, 0.0, &mut targets);
                    }
                    n += 1;
                    pd_substep(&mut b, &act, &targets, &mut scratch).expect("steps");
                    b.contacts(&mut contacts);
                    if contacts[trunk] {
                        b.set_state(&spawn).expect("resets");
                    }
                })
            },
        );
    }

    // Reset: restore the pristine world and place the robot at its spawn state.
    let mut b = backend(&RapierOptions::default());
    let spawn = model.spawn_state();
    for _ in 0..100 {
        pd_substep(
            &mut b,
            &act,
            &standing,
            &mut PdScratch::new(model.num_joints()),
        )
        .expect("steps");
    }
    group.bench_function("reset", |bench| {
        bench.iter(|| b.set_state(black_box(&spawn)).expect("resets"))
    });
    // The first sub-step after a reset re-detects every contact pair from scratch.
    let mut scratch = PdScratch::new(model.num_joints());
    group.bench_function("reset_and_first_substep", |bench| {
        bench.iter(|| {
            b.set_state(black_box(&spawn)).expect("resets");
            pd_substep(&mut b, &act, &standing, &mut scratch)
        })
    });
    // A randomised episode's reset: other masses, centre of mass, damping and friction, then
    // the spawn state (the fixtures' workload, which the DART and MuJoCo benches time too).
    let mut w = SubstepWorkloads::<RapierBackend>::new(
        &Robot::bundled("hyq"),
        &RapierOptions::default(),
        false,
    );
    group.bench_function("randomized_reset", |bench| {
        bench.iter(|| w.randomized_reset())
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_secs(1))
        .measurement_time(std::time::Duration::from_secs(4));
    targets = substep
}
criterion_main!(benches);
