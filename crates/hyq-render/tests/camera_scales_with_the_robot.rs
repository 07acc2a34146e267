//! Unless a camera distance is given, the camera stands off in proportion to the robot's
//! standing height (3.2 m for HyQ, exactly as before the scaling), so a smaller robot fills the
//! frame as HyQ does; a distance that is given is kept.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::sync::Arc;

use common::{differing_pixels, joints_scene};
use hyq_physics::RobotModel;
use hyq_physics::bundled;
use hyq_physics::na::Translation3;
use hyq_render::{CameraConfig, RenderConfig, Renderer};

fn distance(model: &Arc<RobotModel>, config: RenderConfig) -> Option<f64> {
    Renderer::new(Arc::clone(model), config)
        .unwrap()
        .config()
        .camera
        .distance_m
}

#[test]
fn default_distance_is_hyq_s_and_scales_with_standing_height() {
    assert_eq!(
        distance(&bundled::hyq(), RenderConfig::default()),
        Some(3.2)
    );
    let anymal = bundled::anymal_c();
    let d = distance(&anymal, RenderConfig::default()).unwrap();
    assert!((d - 3.2 * 0.5341 / 0.5895).abs() < 1e-12, "{d}");
    let given = RenderConfig {
        camera: CameraConfig {
            distance_m: Some(5.0),
            ..CameraConfig::default()
        },
        ..RenderConfig::default()
    };
    assert_eq!(distance(&anymal, given), Some(5.0));
}

/// The number of pixels the robot covers, standing at its spawn pose (robot against the same
/// view with the robot 100 m away).
fn robot_pixels(model: &Arc<RobotModel>, config: RenderConfig) -> usize {
    let mut r = Renderer::new(Arc::clone(model), config).unwrap();
    let s = model.spawn_state();
    let target = s.trunk.pose.translation.vector.into();
    let contacts = vec![false; model.tracked().len()];
    let mut frame = |dx: f64| {
        let trunk = Translation3::new(dx, 0.0, 0.0) * s.trunk.pose;
        let mut scene = joints_scene(&trunk, &s.q, &contacts);
        scene.camera_target = Some(target);
        r.render(&scene).unwrap()
    };
    let (with, without) = (frame(0.0), frame(100.0));
    differing_pixels(&with, &without, 30).len()
}

#[test]
fn a_smaller_robot_fills_more_of_the_frame_than_at_hyq_s_distance() {
    let anymal = bundled::anymal_c();
    let scaled = robot_pixels(&anymal, RenderConfig::default());
    let at_hyq_distance = robot_pixels(
        &anymal,
        RenderConfig {
            camera: CameraConfig {
                distance_m: Some(3.2),
                ..CameraConfig::default()
            },
            ..RenderConfig::default()
        },
    );
    let hyq = robot_pixels(&bundled::hyq(), RenderConfig::default());
    // The area grows as the inverse square of the distance: (0.5895 / 0.5341)² = 1.22.
    let ratio = scaled as f64 / at_hyq_distance as f64;
    assert!(
        (1.1..1.35).contains(&ratio),
        "{scaled} vs {at_hyq_distance}: {ratio}"
    );
    println!("robot pixels: HyQ {hyq}, ANYmal C {scaled} (scaled), {at_hyq_distance} (at 3.2 m)");
}
