//! The ground in a frame is the scene's terrain: flat terrain draws exactly the frame without
//! one (byte for byte), a height field is drawn with its relief shaded (many ground shades
//! where flat ground has one), stairs show their steps, and the goal's pole stands on the
//! ground under it.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use hyq_physics::Terrain;
use hyq_physics::na::{Point3, Translation3};
use hyq_physics::terrain::generate::{Climb, Extent, Relief, Rough, Stairs, generate};
use hyq_render::Frame;

fn field(relief: Relief) -> Terrain {
    let extent = Extent {
        center: [0.0, 0.0],
        size: [16.0, 16.0],
        resolution: 0.05,
    };
    Terrain::field(generate(&extent, &relief, [0.0, 0.0], 4).unwrap())
}

/// The robot standing at the origin, lifted by `lift` (m), on `terrain`, with a goal 3 m ahead.
fn frame_on(terrain: Option<&Terrain>, lift: f64) -> Frame {
    let mut r = renderer();
    let (trunk, q) = standing_at(0.0, 0.0);
    let trunk = Translation3::new(0.0, 0.0, lift) * trunk;
    let contacts = no_contacts();
    let mut scene = joints_scene(&trunk, &q, &contacts).with_goal(Point3::new(3.0, 0.0, 0.9));
    if let Some(t) = terrain {
        scene = scene.with_terrain(t);
    }
    r.render(&scene).unwrap()
}

/// Distinct colours in the bottom quarter of the frame (ground, below the robot's feet).
fn ground_shades(f: &Frame) -> usize {
    let mut seen = std::collections::HashSet::new();
    for y in 3 * f.height / 4..f.height {
        for x in 0..f.width {
            seen.insert(f.pixel(x, y).unwrap());
        }
    }
    seen.len()
}

#[test]
fn flat_terrain_draws_the_frame_without_terrain() {
    let plain = frame_on(None, 0.0);
    let flat = frame_on(Some(&Terrain::Flat), 0.0);
    assert_eq!(plain.rgb, flat.rgb);
}

#[test]
fn a_height_field_is_drawn_with_its_relief() {
    let rough = field(Relief::Rough(Rough {
        amplitude: 0.08,
        feature: 0.3,
    }));
    let stairs = field(Relief::Stairs(Stairs {
        step_height: 0.12,
        step_depth: 0.4,
        direction_deg: 0.0,
        climb: Climb::Up,
        start: 0.8,
    }));
    let flat = frame_on(None, 0.0);
    let on_rough = frame_on(Some(&rough), 0.05);
    let on_stairs = frame_on(Some(&stairs), 0.0);
    if let Ok(dir) = std::env::var("HYQ_RENDER_TERRAIN_OUT") {
        for (name, f) in [
            ("flat", &flat),
            ("rough", &on_rough),
            ("stairs", &on_stairs),
        ] {
            hyq_render::write_png(format!("{dir}/{name}.png"), f).unwrap();
        }
    }
    let (plain, bumpy, stepped) = (
        ground_shades(&flat),
        ground_shades(&on_rough),
        ground_shades(&on_stairs),
    );
    assert!(
        bumpy > 4 * plain,
        "rough ground: {bumpy} shades, flat: {plain}"
    );
    assert!(stepped > plain, "stairs: {stepped} shades, flat: {plain}");
    // The relief changes most of the ground.
    let changed = differing_pixels(&flat, &on_rough, 12).len();
    let total = (flat.width * flat.height) as usize;
    assert!(
        changed > total / 4,
        "only {changed} of {total} pixels changed"
    );
}

/// A field of one cell 16 m across (2 × 2 heights), flat, `below` metres under the camera's
/// eye, around the robot at the origin.
fn plateau(eye_z: f64, below: f64) -> Terrain {
    let heights = vec![eye_z - below; 4];
    Terrain::field(hyq_physics::HeightGrid::new([0.0, 0.0], [16.0, 16.0], 2, 2, heights).unwrap())
}

/// A tall field whose one cell holds the camera, its surface 5 cm under the eye: the cell
/// crosses the near plane, and its part just past it projects to tens of thousands of pixels.
/// It is clipped at the near plane and cut to the rasteriser's range, not dropped: the bottom
/// row of the frame, where the view meets the surface 6.6 cm in front of the eye, is drawn as
/// the same surface seen from 0.5 m above, not left as the ground plane beneath.
#[test]
fn a_tall_field_just_past_the_near_plane_is_drawn_clipped() {
    let (trunk, _) = standing_at(0.0, 0.0);
    let eye = renderer().camera(&trunk, None).eye();
    let near = frame_on(Some(&plateau(eye.z, 0.05)), 0.0);
    let far = frame_on(Some(&plateau(eye.z, 0.5)), 0.0);
    let under = frame_on(Some(&plateau(eye.z, 50.0)), 0.0);
    if let Ok(dir) = std::env::var("HYQ_RENDER_TERRAIN_OUT") {
        for (name, f) in [("near", &near), ("far", &far), ("under", &under)] {
            hyq_render::write_png(format!("{dir}/plateau-{name}.png"), f).unwrap();
        }
    }
    let bottom = |f: &Frame| -> Vec<_> { (0..f.width).map(|x| f.pixel(x, f.height - 1)).collect() };
    let (near, far, under) = (bottom(&near), bottom(&far), bottom(&under));
    let same = near.iter().zip(&far).filter(|(a, b)| a == b).count();
    let as_under = near.iter().zip(&under).filter(|(a, b)| a == b).count();
    assert!(
        same * 10 >= near.len() * 9,
        "{same} of {} bottom pixels are the surface's",
        near.len()
    );
    assert!(
        as_under * 10 < near.len(),
        "{as_under} bottom pixels show what lies beneath the surface"
    );
}
