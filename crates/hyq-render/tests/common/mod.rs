//! Shared helpers for the rendering tests: the bundled robot standing, a renderer, frame
//! comparisons and scratch directories.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]
#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::Arc;

use hyq_physics::RobotModel;
use hyq_physics::na::{Isometry3, Translation3};
use hyq_render::{Frame, RenderConfig, Renderer, RobotPose, Scene};

pub fn model() -> Arc<RobotModel> {
    hyq_physics::bundled::hyq()
}

pub fn renderer() -> Renderer {
    Renderer::new(model(), RenderConfig::default()).expect("the default config is valid")
}

/// The spawn state's trunk pose moved by (dx, dy) and its standing joint angles.
pub fn standing_at(dx: f64, dy: f64) -> (Isometry3<f64>, Vec<f64>) {
    let s = model().spawn_state();
    let trunk = Translation3::new(dx, dy, 0.0) * s.trunk.pose;
    (trunk, s.q)
}

pub fn no_contacts() -> Vec<bool> {
    vec![false; model().tracked().len()]
}

/// A scene of the robot posed by its trunk pose and joint angles.
pub fn joints_scene<'a>(
    trunk: &'a Isometry3<f64>,
    q: &'a [f64],
    contacts: &'a [bool],
) -> Scene<'a> {
    Scene::new(RobotPose::Joints { trunk, q }, contacts)
}

/// Renders the robot standing at (dx, dy), the camera on `target` (its trunk by default).
pub fn render_standing(
    r: &mut Renderer,
    dx: f64,
    dy: f64,
    target: Option<hyq_physics::na::Point3<f64>>,
) -> Frame {
    let (trunk, q) = standing_at(dx, dy);
    let contacts = no_contacts();
    let mut scene = joints_scene(&trunk, &q, &contacts);
    scene.camera_target = target;
    r.render(&scene).expect("a valid scene renders")
}

/// Sum over channels of the absolute difference of two pixels.
pub fn pixel_diff(a: [u8; 3], b: [u8; 3]) -> u32 {
    a.iter().zip(b).map(|(x, y)| u32::from(x.abs_diff(y))).sum()
}

/// Pixels (x, y) where the two frames differ by more than `threshold`.
pub fn differing_pixels(a: &Frame, b: &Frame, threshold: u32) -> Vec<(u32, u32)> {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let mut out = Vec::new();
    for y in 0..a.height {
        for x in 0..a.width {
            let (pa, pb) = (a.pixel(x, y).unwrap(), b.pixel(x, y).unwrap());
            if pixel_diff(pa, pb) > threshold {
                out.push((x, y));
            }
        }
    }
    out
}

/// The mean position of a set of pixels.
pub fn centroid(pixels: &[(u32, u32)]) -> (f64, f64) {
    let n = pixels.len() as f64;
    let (sx, sy) = pixels.iter().fold((0.0, 0.0), |(sx, sy), &(x, y)| {
        (sx + f64::from(x), sy + f64::from(y))
    });
    (sx / n, sy / n)
}

/// A fresh, empty scratch directory for one test.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hyq-render-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("the temporary directory is writable");
    dir
}
