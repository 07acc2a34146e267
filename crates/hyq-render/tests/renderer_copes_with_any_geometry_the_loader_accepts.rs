//! The renderer draws any geometry the loader accepts, wherever the camera is: shapes at the
//! bounds table's largest size (100 m), seen from outside, from inside and edge-on, project to
//! coordinates of millions of pixels, which the rasteriser's fixed point cannot take (a 1e6 m
//! box made it panic, and Python's env unusable after). The loader refuses shapes over 100 m
//! (the bounds table), and the renderer cuts every path to the rasteriser's safe range besides
//! (`clip`). Every frame finishes.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

use std::sync::Arc;

use hyq_physics::bundled::{HYQ_PROFILE, HYQ_URDF};
use hyq_physics::na::{Isometry3, Point3, Translation3, UnitQuaternion};
use hyq_physics::{Profile, RobotModel};
use hyq_render::{RenderConfig, Renderer, RobotPose, Scene};

/// HyQ with its trunk box and every foot sphere at the table's largest size.
fn huge_robot() -> Arc<RobotModel> {
    let urdf = HYQ_URDF
        .replacen(
            "<box size=\"1.2898 0.5954 0.3737\"/>",
            "<box size=\"100 100 100\"/>",
            1,
        )
        .replace("<sphere radius=\"0.02175\"/>", "<sphere radius=\"100\"/>");
    let profile = Profile::from_toml_str(HYQ_PROFILE, "test").unwrap();
    Arc::new(RobotModel::from_urdf_str(&urdf, "test", &profile).unwrap())
}

#[test]
fn shapes_of_the_largest_accepted_size_render_from_every_side() {
    let model = huge_robot();
    let spawn = model.spawn_state();
    let contacts = vec![true; model.tracked().len()];
    for (width, height) in [(480, 360), (4096, 16)] {
        let config = RenderConfig {
            width,
            height,
            ..RenderConfig::default()
        };
        let mut renderer = Renderer::new(model.clone(), config).unwrap();
        // The camera follows the trunk from its usual offset (inside the box), then looks at
        // the robot from fixed points beside, above and just off a face of the box.
        let targets = [
            None,
            Some(Point3::new(0.0, 0.0, 0.0)),
            Some(Point3::new(49.9, 0.0, 0.6)),
            Some(Point3::new(-60.0, 45.0, 80.0)),
        ];
        for yaw in [0.0, std::f64::consts::FRAC_PI_4] {
            let trunk: Isometry3<f64> = Translation3::new(0.0, 0.0, 0.6)
                * UnitQuaternion::from_euler_angles(0.3, -0.2, yaw);
            for target in targets {
                let mut scene = Scene::new(
                    RobotPose::Joints {
                        trunk: &trunk,
                        q: &spawn.q,
                    },
                    &contacts,
                )
                .with_goal(Point3::new(1.0, 0.0, 0.5));
                scene.camera_target = target;
                let frame = renderer.render(&scene).unwrap();
                assert!(frame.is_consistent() && (frame.width, frame.height) == (width, height));
            }
        }
    }
}
