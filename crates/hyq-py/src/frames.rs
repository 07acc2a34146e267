//! `render_mode="rgb_array"`: a frame of an environment's current state from hyq-render's CPU
//! renderer, as a fresh `uint8` array of shape (height, width, 3).
//!
//! The scene is the state the last reset or step left, as `hyq_render::env_scene` builds it
//! for every front.

use hyq_env::Env;
use hyq_physics::Backend;
use hyq_render::{RenderConfig, Renderer, env_scene};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::prelude::*;

use crate::errors::render_error;

/// The frames of one env or of a vector env's envs (which share one robot model): the frame
/// size, checked at construction, and the renderer, built on the first frame.
pub struct FrameSource {
    config: RenderConfig,
    renderer: Option<Renderer>,
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
        })
    }

    /// The frame size (width, height).
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// The frame of `env`'s current state; `episode_return` is printed in the overlay.
    pub fn frame<'py, B: Backend>(
        &mut self,
        py: Python<'py>,
        env: &Env<B>,
        episode_return: f64,
    ) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let renderer = match &mut self.renderer {
            Some(r) => r,
            None => self
                .renderer
                .insert(Renderer::new(env.model().clone(), self.config).map_err(render_error)?),
        };
        let frame = renderer
            .render(&env_scene(env, episode_return))
            .map_err(render_error)?;
        let [h, w, c] = frame.shape();
        let array = Array3::from_shape_vec((h, w, c), frame.rgb)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("render: {e}")))?;
        Ok(array.into_pyarray(py))
    }
}
