//! The velocity-command task's display: without it a frame is drawn as before; with it the
//! command's arrow on the ground points the way of the command in the trunk's heading frame,
//! the yaw arc turns the way of the rate, command and measured velocity have their colours,
//! the overlay prints them, and a non-finite value is refused with an error naming it.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use hyq_physics::na::{Isometry3, Point3, UnitQuaternion};
use hyq_render::{Camera, Frame, Overlay, RenderError, Renderer, Scene, VelocityHud};

fn hud(command: [f64; 3], measured: [f64; 3]) -> VelocityHud {
    VelocityHud { command, measured }
}

/// The robot standing at the origin, turned by `yaw` (rad) about the vertical.
fn turned(yaw: f64) -> (Isometry3<f64>, Vec<f64>) {
    let (mut trunk, q) = standing_at(0.0, 0.0);
    trunk.rotation = UnitQuaternion::from_euler_angles(0.0, 0.0, yaw) * trunk.rotation;
    (trunk, q)
}

/// A frame of the robot turned by `yaw` with `velocity` (no overlay, so that only the ground
/// display differs between two of them).
fn frame(r: &mut Renderer, yaw: f64, velocity: Option<VelocityHud>) -> Frame {
    let (trunk, q) = turned(yaw);
    let contacts = no_contacts();
    let mut scene = joints_scene(&trunk, &q, &contacts);
    scene.velocity = velocity;
    r.render(&scene).unwrap()
}

/// Where the ground point at (x, y) shows in the image of the robot turned by `yaw`.
fn ground_px(r: &Renderer, yaw: f64, x: f64, y: f64) -> [f64; 2] {
    let cam: Camera = r.camera(&turned(yaw).0, None);
    cam.project(&Point3::new(x, y, 0.0)).unwrap()
}

/// The unit image direction from the point under the trunk to the centroid of what `with`
/// adds to `without`, and how many pixels it adds.
fn drawn_direction(r: &Renderer, yaw: f64, without: &Frame, with: &Frame) -> ([f64; 2], usize) {
    let changed = differing_pixels(without, with, 40);
    let (cx, cy) = centroid(&changed);
    let o = ground_px(r, yaw, 0.0, 0.0);
    let d = [cx - o[0], cy - o[1]];
    let n = d[0].hypot(d[1]);
    ([d[0] / n, d[1] / n], changed.len())
}

fn unit_between(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let d = [b[0] - a[0], b[1] - a[1]];
    let n = d[0].hypot(d[1]);
    [d[0] / n, d[1] / n]
}

#[test]
fn a_zero_display_draws_nothing_on_the_ground_and_none_draws_the_frame_as_before() {
    let mut r = renderer();
    let plain = frame(&mut r, 0.0, None);
    let (trunk, q) = turned(0.0);
    let contacts = no_contacts();
    assert_eq!(
        plain,
        r.render(&joints_scene(&trunk, &q, &contacts)).unwrap()
    );
    // A zero command and a robot at rest: no arrow, no arc.
    assert_eq!(plain, frame(&mut r, 0.0, Some(hud([0.0; 3], [0.0; 3]))));
    let moving = frame(&mut r, 0.0, Some(hud([0.5, 0.0, 0.0], [0.0; 3])));
    assert!(differing_pixels(&plain, &moving, 40).len() > 200);
}

#[test]
fn the_command_arrow_points_the_way_of_the_command_in_the_heading_frame() {
    let mut r = renderer();
    // Facing +x, then turned a quarter turn to face +y: the same command points along the
    // trunk's heading, not along a world axis.
    for yaw in [0.0, std::f64::consts::FRAC_PI_2] {
        let without = frame(&mut r, yaw, Some(hud([0.0; 3], [0.0; 3])));
        let (c, s) = (f64::cos(yaw), f64::sin(yaw));
        for command in [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0], [0.7, 0.7]] {
            let with = frame(
                &mut r,
                yaw,
                Some(hud([command[0], command[1], 0.0], [0.0; 3])),
            );
            let (drawn, n) = drawn_direction(&r, yaw, &without, &with);
            // The command in the world: the heading frame turned by yaw.
            let world = [
                c * command[0] - s * command[1],
                s * command[0] + c * command[1],
            ];
            let expected = unit_between(
                ground_px(&r, yaw, 0.0, 0.0),
                ground_px(&r, yaw, world[0] * 0.6, world[1] * 0.6),
            );
            let cos = drawn[0] * expected[0] + drawn[1] * expected[1];
            assert!(
                n > 200 && cos > 0.9,
                "yaw {yaw}, command {command:?}: {n} pixels towards {drawn:?}, expected {expected:?}"
            );
        }
    }
}

#[test]
fn a_larger_command_draws_a_longer_arrow() {
    let mut r = renderer();
    let zero = frame(&mut r, 0.0, Some(hud([0.0; 3], [0.0; 3])));
    let slow = frame(&mut r, 0.0, Some(hud([0.0, 0.3, 0.0], [0.0; 3])));
    let fast = frame(&mut r, 0.0, Some(hud([0.0, 1.0, 0.0], [0.0; 3])));
    let (a, b) = (
        differing_pixels(&zero, &slow, 40).len(),
        differing_pixels(&zero, &fast, 40).len(),
    );
    assert!(b > a + a / 2, "0.3 m/s: {a} pixels, 1 m/s: {b} pixels");
}

#[test]
fn the_yaw_arc_turns_counter_clockwise_for_a_positive_rate() {
    let mut r = renderer();
    let without = frame(&mut r, 0.0, Some(hud([0.0; 3], [0.0; 3])));
    // A quarter turn per rad/s from straight ahead: +1 rad/s ends at the trunk's left, so its
    // pixels lie towards the front-left; −1 rad/s towards the front-right.
    let front_left = ground_px(&r, 0.0, 0.5, 0.5);
    let front_right = ground_px(&r, 0.0, 0.5, -0.5);
    let o = ground_px(&r, 0.0, 0.0, 0.0);
    for (rate, towards, away) in [
        (1.0, front_left, front_right),
        (-1.0, front_right, front_left),
    ] {
        let with = frame(&mut r, 0.0, Some(hud([0.0, 0.0, rate], [0.0; 3])));
        let (drawn, n) = drawn_direction(&r, 0.0, &without, &with);
        let (t, a) = (unit_between(o, towards), unit_between(o, away));
        let cos_t = drawn[0] * t[0] + drawn[1] * t[1];
        let cos_a = drawn[0] * a[0] + drawn[1] * a[1];
        assert!(
            n > 100 && cos_t > cos_a + 0.3,
            "rate {rate}: {n} pixels towards {drawn:?}; cos {cos_t} to its side, {cos_a} to the other"
        );
    }
}

#[test]
fn the_command_is_green_and_the_measured_velocity_purple() {
    let mut r = renderer();
    // Sideways, so that the trunk does not hide the arrow's middle from the camera.
    let command = frame(&mut r, 0.0, Some(hud([0.0, -1.0, 0.0], [0.0; 3])));
    let measured = frame(&mut r, 0.0, Some(hud([0.0; 3], [0.0, -1.0, 0.0])));
    let [u, v] = ground_px(&r, 0.0, 0.0, -0.9);
    let (u, v) = (u.round() as u32, v.round() as u32);
    let g = command.pixel(u, v).unwrap();
    let p = measured.pixel(u, v).unwrap();
    assert!(g[1] > g[0] + 40 && g[1] > g[2] + 20, "command pixel {g:?}");
    assert!(p[0] > p[1] + 30 && p[2] > p[1] + 40, "measured pixel {p:?}");
}

#[test]
fn the_overlay_prints_the_command_and_the_measured_velocity_instead_of_the_goal_distance() {
    let mut r = renderer();
    let (trunk, q) = turned(0.0);
    let contacts = no_contacts();
    let overlay = Overlay {
        time_s: 1.0,
        distance_to_goal_m: 4.0,
        episode_return: 1.5,
    };
    let scene = joints_scene(&trunk, &q, &contacts).with_overlay(overlay);
    let goal_panel = r.render(&scene).unwrap();
    let at = |v: f64| hud([0.0, 0.0, 0.0], [v, 0.0, 0.0]);
    let a = r.render(&scene.with_velocity(at(0.01))).unwrap();
    let b = r.render(&scene.with_velocity(at(-0.01))).unwrap();
    // The panel has two more rows (five and the feet instead of three and the feet): it
    // reaches further down than the goal task's.
    let bottom = |f: &Frame, over: &Frame| {
        differing_pixels(f, over, 30)
            .iter()
            .filter(|&&(x, _)| x < 200)
            .map(|&(_, y)| y)
            .max()
            .unwrap()
    };
    let plain = r.render(&joints_scene(&trunk, &q, &contacts)).unwrap();
    let (goal_bottom, velocity_bottom) = (bottom(&plain, &goal_panel), bottom(&plain, &a));
    assert!(
        velocity_bottom >= goal_bottom + 30,
        "goal panel to row {goal_bottom}, velocity panel to row {velocity_bottom}"
    );
    // A measured 0.01 against −0.01 m/s changes the printed sign in the panel's forward row
    // (the fourth line, after the time and the return), beside the 12 mm arrows' few pixels.
    let in_panel: Vec<_> = differing_pixels(&a, &b, 30)
        .into_iter()
        .filter(|&(x, y)| x < 260 && y <= velocity_bottom)
        .collect();
    assert!(in_panel.len() > 3, "{} pixels", in_panel.len());
    assert!(
        in_panel
            .iter()
            .all(|&(_, y)| (8 + 2 * 18..8 + 4 * 18).contains(&y)),
        "{in_panel:?}"
    );
}

#[test]
fn a_non_finite_velocity_is_refused_with_an_error_naming_it() {
    let mut r = renderer();
    let (trunk, q) = turned(0.0);
    let contacts = no_contacts();
    for bad in [
        hud([f64::NAN, 0.0, 0.0], [0.0; 3]),
        hud([0.0; 3], [0.0, 0.0, f64::INFINITY]),
    ] {
        let scene: Scene<'_> = joints_scene(&trunk, &q, &contacts).with_velocity(bad);
        let err = r.render(&scene).unwrap_err();
        assert!(matches!(err, RenderError::NonFinite { .. }), "{err:?}");
        let text = err.to_string();
        assert!(
            text.contains("velocity display") && !text.contains('\n'),
            "{text}"
        );
    }
}

#[test]
fn the_taller_velocity_panel_is_drawn_from_about_355_by_260_pixels() {
    let (trunk, q) = turned(0.0);
    let contacts = no_contacts();
    let overlay = Overlay {
        time_s: 1.0,
        distance_to_goal_m: 4.0,
        episode_return: 1.5,
    };
    let scene = joints_scene(&trunk, &q, &contacts).with_velocity(hud([0.0; 3], [0.0; 3]));
    let drawn = |width, height| {
        let config = hyq_render::RenderConfig {
            width,
            height,
            ..hyq_render::RenderConfig::default()
        };
        let mut r = Renderer::new(model(), config).unwrap();
        r.render(&scene).unwrap() != r.render(&scene.with_overlay(overlay)).unwrap()
    };
    // The goal task's panel fits 320 × 240; this one, two rows taller, does not.
    assert!(!drawn(320, 240));
    assert!(!drawn(350, 300));
    assert!(!drawn(400, 255));
    assert!(drawn(355, 260));
    assert!(drawn(360, 270));
    assert!(drawn(400, 300));
}
