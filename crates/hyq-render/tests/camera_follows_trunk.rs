//! The camera follows the trunk: wherever the robot stands, its trunk frame's origin projects to
//! the image centre and the robot's pixels stay around it; with a fixed camera target instead,
//! the same move carries the robot across the image (so following is what keeps it centred).

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use hyq_physics::na::Point3;

/// The robot's pixels at (dx, dy): those that differ from the same view without the robot.
fn robot_pixels(dx: f64, dy: f64, target: Option<Point3<f64>>) -> Vec<(u32, u32)> {
    let mut r = renderer();
    // `None` lets the renderer follow the trunk; the view without the robot is then taken
    // from where the trunk was.
    let with = render_standing(&mut r, dx, dy, target);
    let seen_from = target.unwrap_or_else(|| standing_at(dx, dy).0.translation.vector.into());
    let without = render_standing(&mut r, dx + 100.0, dy, Some(seen_from));
    differing_pixels(&with, &without, 30)
}

#[test]
fn trunk_origin_projects_to_the_image_centre_wherever_it_is() {
    let r = renderer();
    for (dx, dy) in [(0.0, 0.0), (3.0, 0.0), (2.0, -2.0), (-7.5, 4.0)] {
        let trunk = standing_at(dx, dy).0;
        let cam = r.camera(&trunk, None);
        let [u, v] = cam.project(&trunk.translation.vector.into()).unwrap();
        assert!(
            (u - 240.0).abs() < 1e-9 && (v - 180.0).abs() < 1e-9,
            "({u}, {v})"
        );
    }
}

#[test]
fn robot_stays_near_the_image_centre_when_the_trunk_moves_3_m() {
    let (w, h) = (480.0, 360.0);
    let mut centroids = Vec::new();
    for (dx, dy) in [(0.0, 0.0), (3.0, 0.0), (0.0, 3.0), (2.0, -2.0)] {
        let pixels = robot_pixels(dx, dy, None);
        assert!(
            pixels.len() > 5000,
            "the robot covers {} pixels",
            pixels.len()
        );
        let (cx, cy) = centroid(&pixels);
        assert!(
            (cx - w / 2.0).abs() < 0.12 * w && (cy - h / 2.0).abs() < 0.15 * h,
            "robot at ({dx}, {dy}) is centred at ({cx:.0}, {cy:.0})"
        );
        centroids.push((cx, cy));
    }
    // Moving the robot on flat ground with the camera following does not move it in the image.
    for &(cx, cy) in &centroids[1..] {
        assert!((cx - centroids[0].0).abs() < 3.0 && (cy - centroids[0].1).abs() < 3.0);
    }
}

#[test]
fn with_a_fixed_target_the_same_move_carries_the_robot_across_the_image() {
    let origin_trunk: Point3<f64> = standing_at(0.0, 0.0).0.translation.vector.into();
    let here = centroid(&robot_pixels(0.0, 0.0, Some(origin_trunk)));
    let moved = centroid(&robot_pixels(3.0, 0.0, Some(origin_trunk)));
    let shift = ((moved.0 - here.0).powi(2) + (moved.1 - here.1).powi(2)).sqrt();
    assert!(
        shift > 60.0,
        "the robot moved only {shift:.1} px in the image"
    );
}
