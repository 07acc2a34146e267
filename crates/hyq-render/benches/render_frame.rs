//! Rendering speed: one 480×360 frame of HyQ standing with a goal and the overlay (the
//! `rgb_array` path), and encoding that frame as a GIF frame and as a PNG.
//!
//! `cargo bench -p hyq-render --bench render_frame`

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, criterion_group, criterion_main};
use hyq_physics::na::Point3;
use hyq_render::{Frame, GifWriter, Overlay, RenderConfig, Renderer, RobotPose, Scene, encode_png};

fn bench(c: &mut Criterion) {
    let model = hyq_physics::bundled::hyq();
    let state = model.spawn_state();
    let contacts = [true, false, false, true, false];
    let scene = Scene::new(
        RobotPose::Joints {
            trunk: &state.trunk.pose,
            q: &state.q,
        },
        &contacts,
    )
    .with_goal(Point3::new(5.0, 0.0, 0.6))
    .with_overlay(Overlay {
        time_s: 3.42,
        distance_to_goal_m: 4.31,
        episode_return: 12.61,
    });
    let mut renderer = Renderer::new(model.clone(), RenderConfig::default()).unwrap();
    let mut frame = Frame::new(480, 360);

    c.bench_function("render 480x360 (robot, goal, overlay)", |b| {
        b.iter(|| renderer.render_into(&scene, &mut frame).unwrap())
    });
    c.bench_function("gif frame 480x360 (NeuQuant speed 10)", |b| {
        let mut gif = GifWriter::new(std::io::sink(), 480, 360, 30.0).unwrap();
        b.iter(|| gif.push(&frame).unwrap())
    });
    c.bench_function("png frame 480x360", |b| {
        let mut out = Vec::with_capacity(1 << 20);
        b.iter(|| {
            out.clear();
            encode_png(&mut out, &frame).unwrap()
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
