//! Cost of one MuJoCo physics sub-step of HyQ, the way the environment takes it: shared PD
//! actuator (read q and q̇, compute 12 torques), set the torques, step MuJoCo, read back the
//! contact flags. Two workloads: standing still on four feet (settled for 1 s first), and
//! random joint targets redrawn every 10 sub-steps (feet landing and lifting, joints at their
//! limits; reset to the spawn state when the trunk touches the ground, as an episode would
//! end), and the cost of `set_state` (which resets all of MuJoCo's data).
//!
//! Run: `cargo bench -p hyq-mujoco --bench step`.

use criterion::{Criterion, criterion_group, criterion_main};
use hyq_mujoco::{MujocoBackend, MujocoOptions};
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, bundled, pd_substep};

fn hyq() -> MujocoBackend {
    MujocoBackend::build(
        bundled::hyq(),
        &PhysicsParams::default(),
        &MujocoOptions::default(),
    )
    .expect("the bundled HyQ builds on MuJoCo")
}

/// xorshift64*, uniform in [0, 1).
fn unit(state: &mut u64) -> f64 {
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
}

fn step(c: &mut Criterion) {
    let model = bundled::hyq();
    let n = model.num_joints();
    let act = Actuator::new(&model);
    let mut contacts = vec![false; model.tracked().len()];
    let mut group = c.benchmark_group("mujoco_substep");

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
    let spawn = model.spawn_state();
    let trunk = model.trunk_tracked_index();
    let mut targets = standing.clone();
    let mut rng = 0x9E37_79B9_7F4A_7C15_u64;
    let mut k = 0_u64;
    group.bench_function("random_targets", |bench| {
        bench.iter(|| {
            if k.is_multiple_of(10) {
                for (t, j) in targets.iter_mut().zip(model.joints()) {
                    *t = j.lower + unit(&mut rng) * (j.upper - j.lower);
                }
            }
            k += 1;
            pd_substep(&mut b, &act, &targets, &mut scratch).expect("random targets stay finite");
            b.contacts(&mut contacts);
            if contacts[trunk] {
                b.set_state(&spawn).expect("the spawn state is valid");
            }
        });
    });

    let mut b = hyq();
    group.bench_function("set_state", |bench| {
        bench.iter(|| b.set_state(&spawn).expect("the spawn state is valid"));
    });
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
