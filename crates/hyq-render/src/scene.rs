//! What one frame shows: the robot's pose, its contacts, the goal, the overlay numbers and the
//! velocity task's command.
//! Plain values only, so any environment, log or test can fill it.

use hyq_physics::Terrain;
use hyq_physics::na::{Isometry3, Point3};

/// Where the robot's bodies are.
#[derive(Clone, Copy, Debug)]
pub enum RobotPose<'a> {
    /// The world pose of every body frame, index as in `RobotModel::links` (e.g. from
    /// `Backend::link_poses` or `RobotModel::link_poses`).
    Links(&'a [Isometry3<f64>]),
    /// The trunk's world pose and the joint angles (rad, profile order); the renderer runs
    /// the model's forward kinematics into its own buffer (no allocation).
    Joints {
        /// The trunk frame's world pose.
        trunk: &'a Isometry3<f64>,
        /// Joint angles (rad), profile order.
        q: &'a [f64],
    },
}

/// The numbers printed in the frame's top-left corner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overlay {
    /// Simulated time since reset (s).
    pub time_s: f64,
    /// Distance from the trunk to the goal (m), as the environment measures it (D^t).
    pub distance_to_goal_m: f64,
    /// The sum of the rewards so far in this episode.
    pub episode_return: f64,
}

/// The velocity-command task's display (docs/velocity.md): the command and what the trunk does,
/// both in the trunk's heading frame (x forward, y to the left, ω_z about the vertical), as the
/// task's reward compares them.
///
/// The renderer draws it on the ground under the trunk: the command as a wide green arrow of
/// (v_x, v_y) and a green curved arrow around the trunk for ω_z (a quarter turn per rad/s,
/// counter-clockwise seen from above for a positive rate), the measured values likewise in
/// purple, narrower and on a smaller circle; and in the text overlay, three rows of command and
/// measured value side by side.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VelocityHud {
    /// The command: forward and sideways speed (m/s), yaw rate (rad/s).
    pub command: [f64; 3],
    /// The trunk's measured velocity in the same order and units (its frame's, as the task's
    /// info reports it).
    pub measured: [f64; 3],
}

/// Everything one frame shows.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// The robot's pose.
    pub pose: RobotPose<'a>,
    /// One flag per tracked body (`RobotModel::tracked`: the feet, then the trunk), true when
    /// it touches the ground, as `Backend::contacts` reports them. Feet in contact are drawn
    /// orange with a disc on the ground under them; a trunk in contact is drawn red.
    pub contacts: &'a [bool],
    /// The goal (world, m): a green ball on a pole with a ring on the ground, and a dashed line
    /// to it from under the trunk. `None` draws no goal.
    pub goal: Option<Point3<f64>>,
    /// The text overlay; `None` draws none. Its text has a fixed size (13 px), so a frame too
    /// small to hold it beside the robot (the panel would take more than 2/3 of the width or
    /// 1/2 of the height: under about 300 × 190 px) is drawn without it.
    pub overlay: Option<Overlay>,
    /// The point the camera looks at; `None` (the usual) follows the trunk frame's origin.
    pub camera_target: Option<Point3<f64>>,
    /// The ground: `None` or flat is the plane z = 0 with its grid; a height field is drawn
    /// shaded around the camera's target, the grid draped over it, shadows, discs and the goal's
    /// ring laid on it.
    pub terrain: Option<&'a Terrain>,
    /// The velocity-command task's arrows and numbers; `None` (the spec's task) draws none.
    pub velocity: Option<VelocityHud>,
}

impl<'a> Scene<'a> {
    /// A scene of the robot alone: no goal, no overlay, the camera following the trunk.
    pub fn new(pose: RobotPose<'a>, contacts: &'a [bool]) -> Self {
        Self {
            pose,
            contacts,
            goal: None,
            overlay: None,
            camera_target: None,
            terrain: None,
            velocity: None,
        }
    }

    /// The same scene with the velocity-command task's display.
    pub fn with_velocity(mut self, hud: VelocityHud) -> Self {
        self.velocity = Some(hud);
        self
    }

    /// The same scene with a goal marker at `goal`.
    pub fn with_goal(mut self, goal: Point3<f64>) -> Self {
        self.goal = Some(goal);
        self
    }

    /// The same scene with the text overlay.
    pub fn with_overlay(mut self, overlay: Overlay) -> Self {
        self.overlay = Some(overlay);
        self
    }

    /// The same scene on `terrain`.
    pub fn with_terrain(mut self, terrain: &'a Terrain) -> Self {
        self.terrain = Some(terrain);
        self
    }

    /// The same scene seen by a camera looking at `target` instead of following the trunk.
    pub fn with_camera_target(mut self, target: Point3<f64>) -> Self {
        self.camera_target = Some(target);
        self
    }
}
