//! `render_mode="rgb_array"`: a frame of an environment's current state from hyq-render's CPU
//! renderer, as a fresh `uint8` array of shape (height, width, 3).
//!
//! The scene is the state the last reset or step left: the trunk pose and joint angles, the
//! contact flags of the observation (feet, then trunk: the flags latched over the step's
//! sub-steps, so a foot that touched the ground during the step is drawn in contact), the goal,
//! and the overlay (simulated time, D^t, the episode's return so far).

use hyq_physics::na::Point3;
use hyq_render::{Overlay, RenderConfig, Renderer, RobotPose, Scene};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::prelude::*;

use crate::engines::EnvView;
use crate::errors::render_error;

/// The frames of one env or of a vector env's envs (which share one robot model): the frame
/// size, checked at construction, and the renderer, built on the first frame.
pub struct FrameSource {
    config: RenderConfig,
    renderer: Option<Renderer>,
    /// The contact flags handed to the renderer, one per tracked body.
    contacts: Vec<bool>,
}

impl FrameSource {
    /// Frames of `width` × `height` pixels. The size is checked now (by hyq-render), so a bad
    /// one fails at construction, not at the first frame.
    pub fn new(width: u32, height: u32) -> PyResult<Self> {
        let config = RenderConfig {
            width,
            height,
            ..RenderConfig::default()
        };
        config.validate().map_err(render_error)?;
        Ok(Self {
            config,
            renderer: None,
            contacts: Vec::new(),
        })
    }

    /// The frame size (width, height).
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// The frame of `env`'s current state; `episode_return` is printed in the overlay.
    pub fn frame<'py>(
        &mut self,
        py: Python<'py>,
        env: &dyn EnvView,
        episode_return: f64,
    ) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let renderer = match &mut self.renderer {
            Some(r) => r,
            None => self
                .renderer
                .insert(Renderer::new(env.model().clone(), self.config).map_err(render_error)?),
        };
        let layout = env.observation_layout();
        let obs = env.observation();
        // The renderer takes one flag per tracked body in the model's order; the observation
        // holds the feet's flags (the first `num_feet` tracked bodies) and the trunk's.
        let model = env.model();
        self.contacts.clear();
        self.contacts.resize(model.tracked().len(), false);
        for (flag, v) in self.contacts.iter_mut().zip(&obs[layout.foot_contacts()]) {
            *flag = *v > 0.5;
        }
        if let Some(flag) = self.contacts.get_mut(model.trunk_tracked_index()) {
            *flag = obs[layout.trunk_contact()] > 0.5;
        }
        let info = env.info();
        let scene = Scene::new(
            RobotPose::Joints {
                trunk: &env.trunk().pose,
                q: env.joint_angles(),
            },
            &self.contacts,
        )
        .with_goal(Point3::from(info.goal))
        .with_overlay(Overlay {
            time_s: info.t as f64 * env.env_dt(),
            distance_to_goal_m: info.distance_to_goal,
            episode_return,
        });
        let frame = renderer.render(&scene).map_err(render_error)?;
        let [h, w, c] = frame.shape();
        let array = Array3::from_shape_vec((h, w, c), frame.rgb)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("render: {e}")))?;
        Ok(array.into_pyarray(py))
    }
}
