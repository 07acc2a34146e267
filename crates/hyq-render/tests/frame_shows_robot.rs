//! A rendered frame is a `height × width × 3` byte image that shows the robot: the trunk covers
//! the pixel its centre projects to, a fallen robot looks different from a standing one, a foot
//! in contact changes colour, the overlay prints its numbers, rendering is deterministic, and
//! bad input is refused with an error naming what was wrong. A value that rounds to zero prints as
//! `0.00`, never `-0.00`; a frame too small for the overlay is drawn without it.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use hyq_physics::na::{Isometry3, Point3, Translation3, UnitQuaternion};
use hyq_render::{
    CameraConfig, Frame, Overlay, RenderConfig, RenderError, Renderer, RobotPose, Scene,
};

#[test]
fn renderer_and_frames_can_move_between_threads() {
    // A Python env (PyO3) or a vector env keeps a renderer per environment on worker threads.
    fn send<T: Send + 'static>() {}
    send::<Renderer>();
    send::<Frame>();
}

#[test]
fn frame_has_the_configured_shape_and_one_byte_per_channel() {
    let config = RenderConfig {
        width: 320,
        height: 200,
        ..RenderConfig::default()
    };
    let mut r = Renderer::new(model(), config).unwrap();
    let (trunk, q) = standing_at(0.0, 0.0);
    let contacts = no_contacts();
    let frame: Frame = r.render(&joints_scene(&trunk, &q, &contacts)).unwrap();
    assert_eq!((frame.width, frame.height), (320, 200));
    assert_eq!(frame.shape(), [200, 320, 3]);
    let bytes: &Vec<u8> = &frame.rgb;
    assert_eq!(bytes.len(), 200 * 320 * 3);
    assert!(frame.is_consistent());
}

#[test]
fn trunk_centre_pixel_differs_from_the_background() {
    let mut r = renderer();
    let target = standing_at(0.0, 0.0).0.translation.vector.into();
    let with_robot = render_standing(&mut r, 0.0, 0.0, Some(target));
    // The same view with the robot 100 m away: what lies behind the trunk.
    let background = render_standing(&mut r, 100.0, 0.0, Some(target));
    let cam = r.camera(&standing_at(0.0, 0.0).0, None);
    let [u, v] = cam.project(&target).unwrap();
    let (u, v) = (u.round() as u32, v.round() as u32);
    let robot_px = with_robot.pixel(u, v).unwrap();
    let ground_px = background.pixel(u, v).unwrap();
    assert!(
        pixel_diff(robot_px, ground_px) > 60,
        "trunk pixel {robot_px:?} vs background {ground_px:?}"
    );
    // The trunk is blue: more blue than red.
    assert!(robot_px[2] > robot_px[0] + 30, "{robot_px:?}");
    // And the robot covers a sizeable part of the image.
    let robot_area = differing_pixels(&with_robot, &background, 30).len();
    let total = (with_robot.width * with_robot.height) as usize;
    assert!(robot_area > total / 20, "{robot_area} of {total} pixels");
}

#[test]
fn fallen_robot_frame_differs_from_standing() {
    let mut r = renderer();
    let (trunk, q) = standing_at(0.0, 0.0);
    let mut contacts = no_contacts();
    let standing = r.render(&joints_scene(&trunk, &q, &contacts)).unwrap();
    // On its side, low, with the trunk touching the ground.
    let fallen_pose = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 0.32),
        UnitQuaternion::from_euler_angles(1.45, 0.0, 0.0),
    );
    let trunk_index = model().trunk_tracked_index();
    contacts[trunk_index] = true;
    let fallen = r
        .render(&joints_scene(&fallen_pose, &q, &contacts))
        .unwrap();
    let changed = differing_pixels(&standing, &fallen, 40).len();
    let total = (standing.width * standing.height) as usize;
    assert!(
        changed > total / 20,
        "only {changed} of {total} pixels changed"
    );
    // A trunk touching the ground is drawn red: the image centre (the trunk frame's origin)
    // turns from blue to red.
    let (cx, cy) = (standing.width / 2, standing.height / 2);
    let before = standing.pixel(cx, cy).unwrap();
    let after = fallen.pixel(cx, cy).unwrap();
    assert!(before[2] > before[0], "{before:?}");
    assert!(after[0] > after[2] + 40, "{after:?}");
}

#[test]
fn foot_in_contact_changes_colour() {
    let mut r = renderer();
    let m = model();
    let (trunk, q) = standing_at(0.0, 0.0);
    let mut poses = vec![Isometry3::identity(); m.num_links()];
    m.link_poses(&trunk, &q, &mut poses).unwrap();
    let cam = r.camera(&trunk, None);
    // The foot nearest the camera, so that nothing hides it.
    let (foot, centre) = (0..m.num_feet())
        .map(|f| {
            let t = &m.tracked()[f];
            let c = poses[t.link] * m.links()[t.link].collisions[t.shapes[0]].origin;
            (f, Point3::from(c.translation.vector))
        })
        .min_by(|a, b| cam.depth(&a.1).total_cmp(&cam.depth(&b.1)))
        .unwrap();
    let [u, v] = cam.project(&centre).unwrap();
    let (u, v) = (u.round() as u32, v.round() as u32);

    let mut contacts = no_contacts();
    let air = r
        .render(&Scene::new(RobotPose::Links(&poses), &contacts))
        .unwrap();
    contacts[foot] = true;
    let ground = r
        .render(&Scene::new(RobotPose::Links(&poses), &contacts))
        .unwrap();
    let (a, g) = (air.pixel(u, v).unwrap(), ground.pixel(u, v).unwrap());
    assert!(
        pixel_diff(a, g) > 80,
        "foot {foot}: in the air {a:?}, in contact {g:?}"
    );
    // In contact the foot is orange: red well above blue.
    assert!(g[0] > g[2] + 60, "{g:?}");
    // Only the foot, its ground disc and the overlay-free rest of the image near it change.
    let changed = differing_pixels(&air, &ground, 30);
    assert!(
        !changed.is_empty() && changed.len() < 2000,
        "{} pixels",
        changed.len()
    );
}

#[test]
fn overlay_prints_its_numbers_in_the_top_left_corner() {
    let mut r = renderer();
    let (trunk, q) = standing_at(0.0, 0.0);
    let contacts = no_contacts();
    let scene = joints_scene(&trunk, &q, &contacts);
    let overlay = |time_s| Overlay {
        time_s,
        distance_to_goal_m: 4.0,
        episode_return: 1.5,
    };
    let plain = r.render(&scene).unwrap();
    let one = r.render(&scene.with_overlay(overlay(1.0))).unwrap();
    let two = r.render(&scene.with_overlay(overlay(2.0))).unwrap();
    let panel = differing_pixels(&plain, &one, 30);
    assert!(
        panel.len() > 2000,
        "the panel changed {} pixels",
        panel.len()
    );
    assert!(panel.iter().all(|&(x, y)| x < 240 && y < 120));
    // Another time changes a few pixels of text, inside the panel only.
    let text = differing_pixels(&one, &two, 30);
    assert!(text.len() > 10, "{} pixels", text.len());
    assert!(text.iter().all(|&(x, y)| x < 240 && y < 40));
}

#[test]
fn small_frames_leave_the_overlay_out_so_that_the_robot_shows() {
    let contacts = no_contacts();
    let (trunk, q) = standing_at(0.0, 0.0);
    let scene = joints_scene(&trunk, &q, &contacts);
    let overlay = Overlay {
        time_s: 1.0,
        distance_to_goal_m: 4.0,
        episode_return: 1.5,
    };
    let drawn = |width, height| {
        let config = RenderConfig {
            width,
            height,
            ..RenderConfig::default()
        };
        let mut r = Renderer::new(model(), config).unwrap();
        r.render(&scene).unwrap() != r.render(&scene.with_overlay(overlay)).unwrap()
    };
    // An 84 × 84 rgb_array (pixel-based learning) and a small GIF: the panel would cover the
    // robot, so it is left out.
    assert!(!drawn(84, 84));
    assert!(!drawn(240, 180));
    // From 320 × 240 on it fits.
    assert!(drawn(320, 240));
    assert!(drawn(480, 360));
}

#[test]
fn overlay_shows_a_tiny_negative_return_as_zero_not_minus_zero() {
    let mut r = renderer();
    let (trunk, q) = standing_at(0.0, 0.0);
    let contacts = no_contacts();
    let scene = joints_scene(&trunk, &q, &contacts);
    let overlay = |episode_return| Overlay {
        time_s: 0.2,
        distance_to_goal_m: 5.0,
        episode_return,
    };
    let zero = r.render(&scene.with_overlay(overlay(0.0))).unwrap();
    let tiny = r.render(&scene.with_overlay(overlay(-0.0004))).unwrap();
    let small = r.render(&scene.with_overlay(overlay(-0.01))).unwrap();
    // "-0.00" would be a different picture from "0.00"; "-0.01" must still show its sign.
    assert_eq!(zero, tiny);
    assert_ne!(zero, small);
}

#[test]
fn same_scene_renders_identically_and_both_pose_forms_agree() {
    let mut r = renderer();
    let m = model();
    let (trunk, q) = standing_at(0.4, -0.2);
    let mut poses = vec![Isometry3::identity(); m.num_links()];
    m.link_poses(&trunk, &q, &mut poses).unwrap();
    let contacts = [true, false, false, true, false];
    let goal = Point3::new(3.0, 1.0, 0.6);
    let overlay = Overlay {
        time_s: 0.5,
        distance_to_goal_m: 2.5,
        episode_return: -0.25,
    };
    let by_joints = joints_scene(&trunk, &q, &contacts)
        .with_goal(goal)
        .with_overlay(overlay);
    let a = r.render(&by_joints).unwrap();
    let b = r.render(&by_joints).unwrap();
    assert_eq!(a, b);
    let by_links = Scene::new(RobotPose::Links(&poses), &contacts)
        .with_goal(goal)
        .with_overlay(overlay);
    let mut c = Frame::new(a.width, a.height);
    r.render_into(&by_links, &mut c).unwrap();
    assert_eq!(a, c);
}

#[test]
fn goal_marker_is_drawn_where_the_goal_projects() {
    let mut r = renderer();
    let (trunk, q) = standing_at(0.0, 0.0);
    let contacts = no_contacts();
    let scene = joints_scene(&trunk, &q, &contacts);
    // A goal the default camera sees beside the robot.
    let goal = Point3::new(3.0, 0.0, 0.6);
    let without = r.render(&scene).unwrap();
    let with = r.render(&scene.with_goal(goal)).unwrap();
    let [u, v] = r.camera(&trunk, None).project(&goal).unwrap();
    let px = with.pixel(u.round() as u32, v.round() as u32).unwrap();
    let bg = without.pixel(u.round() as u32, v.round() as u32).unwrap();
    assert!(pixel_diff(px, bg) > 60, "goal {px:?} vs {bg:?}");
    assert!(
        px[1] > px[0] + 30 && px[1] > px[2],
        "the goal ball is green: {px:?}"
    );
}

#[test]
fn bad_scenes_are_refused_by_name() {
    let mut r = renderer();
    let (trunk, q) = standing_at(0.0, 0.0);
    let contacts = no_contacts();

    let short = [false; 4];
    let err = r.render(&joints_scene(&trunk, &q, &short)).unwrap_err();
    assert!(
        matches!(
            err,
            RenderError::WrongLength {
                expected: 5,
                got: 4,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("contact flags"), "{err}");

    let mut bad_q = q.clone();
    bad_q[4] = f64::NAN;
    let err = r
        .render(&joints_scene(&trunk, &bad_q, &contacts))
        .unwrap_err();
    assert!(err.to_string().contains("lh_hfe"), "{err}");

    let err = r
        .render(&joints_scene(&trunk, &q[..11], &contacts))
        .unwrap_err();
    assert!(err.to_string().contains("joint angles"), "{err}");

    let err = r
        .render(&Scene::new(
            RobotPose::Links(&[Isometry3::identity(); 3]),
            &contacts,
        ))
        .unwrap_err();
    assert!(err.to_string().contains("link poses"), "{err}");

    let nan_trunk = Translation3::new(f64::INFINITY, 0.0, 0.0) * trunk;
    let err = r
        .render(&joints_scene(&nan_trunk, &q, &contacts))
        .unwrap_err();
    assert!(err.to_string().contains("body trunk"), "{err}");

    let err = r
        .render(&joints_scene(&trunk, &q, &contacts).with_goal(Point3::new(f64::NAN, 0.0, 0.0)))
        .unwrap_err();
    assert!(err.to_string().starts_with("goal"), "{err}");

    let mut small = Frame::new(10, 10);
    let err = r
        .render_into(&joints_scene(&trunk, &q, &contacts), &mut small)
        .unwrap_err();
    assert!(
        matches!(err, RenderError::FrameSize { got_width: 10, .. }),
        "{err}"
    );
}

#[test]
fn bad_settings_are_refused_by_name() {
    for (config, field) in [
        (
            RenderConfig {
                width: 8,
                ..RenderConfig::default()
            },
            "width",
        ),
        (
            RenderConfig {
                grid_spacing_m: 0.0,
                ..RenderConfig::default()
            },
            "grid_spacing_m",
        ),
        (
            RenderConfig {
                camera: CameraConfig {
                    elevation_deg: 90.0,
                    ..CameraConfig::default()
                },
                ..RenderConfig::default()
            },
            "camera.elevation_deg",
        ),
        (
            RenderConfig {
                camera: CameraConfig {
                    distance_m: Some(f64::NAN),
                    ..CameraConfig::default()
                },
                ..RenderConfig::default()
            },
            "camera.distance_m",
        ),
    ] {
        let err = Renderer::new(model(), config).unwrap_err();
        assert!(
            matches!(&err, RenderError::InvalidConfig { field: f, .. } if *f == field),
            "{err}"
        );
    }
}
