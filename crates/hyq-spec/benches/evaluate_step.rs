//! The cost of the spec's rules per env step: `EpisodeRules::evaluate_step` (every reward term,
//! multiplier, penalty and termination for HyQ's twelve joints) and `ObservationLayout::write`
//! (39 rows as f32). The budget is 1% of an env step of about 200 µs, i.e. 2 µs; the aim is well
//! under 1 µs. Run: `cargo bench -p hyq-spec --bench evaluate_step`.

use criterion::{Criterion, criterion_group, criterion_main};
use hyq_spec::nalgebra::{Point3, UnitQuaternion, Vector3};
use hyq_spec::{
    Clipping, EpisodeRules, HeightPenalty, Observation, ObservationLayout, RobotDescription,
    StepSnapshot, TaskConfig,
};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let robot = RobotDescription::hyq_spec();
    let start = Point3::new(0.0, 0.0, 0.62);
    let config = TaskConfig {
        base_rew_scaling: Some(1.0),
        norm_rew_scaling: Some(10.0),
        height_penalty: Some(HeightPenalty {
            nominal_height_m: 0.62,
            tolerance_m: 0.1,
            rate_per_m: 2.0,
        }),
        ..TaskConfig::default()
    };
    let rules = match EpisodeRules::new(&config, start, Point3::new(5.0, 0.0, 0.62)) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    let angles: Vec<f64> = robot
        .joint_ranges()
        .iter()
        .map(|r| 0.5 * (r.lower() + r.upper()))
        .collect();
    let snapshot = StepSnapshot {
        step: 10,
        previous_position: Point3::new(0.10, 0.01, 0.61),
        position: Point3::new(0.11, 0.012, 0.60),
        orientation: UnitQuaternion::from_euler_angles(0.01, 0.05, 0.06),
        joint_angles: &angles,
        joint_ranges: robot.joint_ranges(),
        trunk_contact: false,
    };
    c.bench_function("evaluate_step (HyQ, all terms on)", |b| {
        b.iter(|| rules.evaluate_step(black_box(&snapshot)))
    });

    let layout = ObservationLayout::new(&robot);
    let speeds = [0.5; 12];
    let feet = [true, false, true, false];
    let observation = Observation {
        joint_angles: &angles,
        joint_speeds: &speeds,
        foot_contacts: &feet,
        trunk_contact: false,
        trunk_rotation: snapshot.orientation,
        trunk_acceleration: Vector3::new(0.1, -0.2, 0.3),
        trunk_position: snapshot.position,
    };
    let mut out = [0.0f32; 39];
    c.bench_function("ObservationLayout::write (HyQ, f32)", |b| {
        b.iter(|| layout.write(black_box(&observation), Clipping::Off, black_box(&mut out)))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
