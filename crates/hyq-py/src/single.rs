//! `hyq._core.Core`: one environment of a robot on a backend, for `hyq.HyQEnv`.

use hyq_env::ResetOptions;
use numpy::{IntoPyArray, PyArray1, PyArray3, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::config;
use crate::engines::{self, EnvView, Held};
use crate::errors::env_error;
use crate::frames::FrameSource;
use crate::guard::{Retirable, call, call_mut};
use crate::info::info_dict;
use crate::spaces::{
    Bounds, clip_in_place, declared_bounds, high_inward, low_inward, table_bounds,
};

/// One environment (a robot on a backend). Built by `hyq.HyQEnv`, which adds the Gymnasium API.
#[pyclass(module = "hyq._core")]
pub struct Core {
    env: Held<dyn EnvView>,
    /// The observation's declared bounds (f32) when observations are clipped to them.
    clip: Option<Bounds>,
    /// The frames of `render` (the renderer is built on the first).
    frames: FrameSource,
    /// Σ reward since the last reset, for the frame overlay.
    episode_return: f64,
    /// The last action, copied out of NumPy (reused: no allocation per step).
    action: Vec<f64>,
    /// Why the env was retired (after an internal error), if it was.
    retired: Option<String>,
}

impl Retirable for Core {
    fn retired(&self) -> Option<&str> {
        self.retired.as_deref()
    }

    fn retire(&mut self, why: String) {
        self.retired = Some(why);
    }
}

impl Core {
    /// The current observation (clipped if configured) and the info, which says whether the
    /// observation was clipped.
    fn observation_and_info<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyArray1<f32>>, Bound<'py, PyDict>)> {
        // The one copy: the fresh array handed to Python, clipped where it lies.
        let env = self.env.get();
        let mut obs = env.observation_f32().to_vec();
        let clipped = clip_in_place(&mut obs, self.clip.as_ref());
        let info = info_dict(py, env.info(), env.model(), clipped, env.engine_name())?;
        Ok((obs.into_pyarray(py), info))
    }
}

#[pymethods]
impl Core {
    /// Builds the environment from an optional TOML file and dotted `(key, TOML value)` pairs
    /// (`("task.fall_penalty", "1.5")`); errors name the key and value. `robot` is a bundled
    /// robot's name or a profile path (default HyQ), `backend` one this build has.
    #[new]
    #[pyo3(signature = (pairs, config_file=None, clip_observations=crate::CLIP_OBSERVATIONS_DEFAULT, render_width=hyq_render::DEFAULT_WIDTH_PX, render_height=hyq_render::DEFAULT_HEIGHT_PX, robot=None, backend=hyq_engines::DEFAULT.name))]
    fn new(
        pairs: Vec<(String, String)>,
        config_file: Option<String>,
        clip_observations: bool,
        render_width: u32,
        render_height: u32,
        robot: Option<String>,
        backend: &str,
    ) -> PyResult<Self> {
        let model = engines::robot(robot.as_deref())?;
        let config = config::build(config_file.as_deref(), &pairs)?;
        let env = engines::make_env(backend, model, config)?;
        let clip = clip_observations.then(|| table_bounds(&*env));
        let frames = FrameSource::new(render_width, render_height)?;
        Ok(Self {
            env: Held::new(env),
            clip,
            frames,
            episode_return: 0.0,
            action: Vec::new(),
            retired: None,
        })
    }

    /// Starts an episode: `seed` reseeds the goal and reset-noise streams (None continues
    /// them), `goal` overrides this episode's goal. Returns (observation, info).
    #[pyo3(signature = (seed=None, goal=None))]
    fn reset<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        seed: Option<u64>,
        goal: Option<[f64; 3]>,
    ) -> PyResult<(Bound<'py, PyArray1<f32>>, Bound<'py, PyDict>)> {
        call_mut(slf, "reset", |this| {
            let options = ResetOptions {
                goal,
                ..ResetOptions::default()
            };
            let env = this.env.get_mut();
            py.detach(|| env.reset(seed, &options)).map_err(env_error)?;
            this.episode_return = 0.0;
            this.observation_and_info(py)
        })
    }

    /// One env step with `action` (float64, one value per joint). Returns (observation,
    /// reward, terminated, truncated, info).
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        action: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f32>>,
        f64,
        bool,
        bool,
        Bound<'py, PyDict>,
    )> {
        call_mut(slf, "step", |this| {
            // Copied while the GIL is held: another Python thread may write to the array while
            // the env steps.
            let given = action
                .as_slice()
                .map_err(|e| PyValueError::new_err(format!("action: {e}")))?;
            this.action.clear();
            this.action.extend_from_slice(given);
            let (env, action) = (this.env.get_mut(), &this.action);
            let (reward, terminated, truncated) =
                py.detach(|| env.step(action)).map_err(env_error)?;
            this.episode_return += reward;
            let (obs, info) = this.observation_and_info(py)?;
            Ok((obs, reward, terminated, truncated, info))
        })
    }

    /// Panics inside a call, with the GIL released as in `step`: for the test that shows a
    /// panic reaches Python as a `RuntimeError` and retires the env.
    #[pyo3(name = "_panic_for_tests")]
    fn panic_for_tests(slf: &Bound<'_, Self>, py: Python<'_>) -> PyResult<()> {
        call_mut(slf, "_panic_for_tests", |_| {
            py.detach(|| -> PyResult<()> { panic!("a panic asked for by a test") })
        })
    }

    /// A frame of the current state: uint8, (height, width, 3). Before the first reset it
    /// shows the robot at its spawn pose without goal or overlay.
    fn render<'py>(slf: &Bound<'py, Self>, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        call_mut(slf, "render", |this| {
            this.frames
                .frame(py, this.env.get_mut(), this.episode_return)
        })
    }

    /// The observation space's lower bounds (float32; see `spaces`).
    fn observation_low<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "observation_low", |this| {
            Ok(declared_bounds(&**this.env.get(), this.clip.is_some())
                .0
                .into_pyarray(py))
        })
    }

    /// The observation space's upper bounds (float32).
    fn observation_high<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "observation_high", |this| {
            Ok(declared_bounds(&**this.env.get(), this.clip.is_some())
                .1
                .into_pyarray(py))
        })
    }

    /// The action space's lower bounds (float32; −1 in the normalized, delta and offset modes, the
    /// joints' lower limits in the absolute mode).
    fn action_low<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "action_low", |this| {
            Ok(low_inward(this.env.get().action_space().low()).into_pyarray(py))
        })
    }

    /// The action space's upper bounds (float32).
    fn action_high<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "action_high", |this| {
            Ok(high_inward(this.env.get().action_space().high()).into_pyarray(py))
        })
    }

    /// The observation rows' names, in order (`lf_haa_angle`, …, `trunk_position_z`).
    fn observation_names<'py>(slf: &Bound<'py, Self>) -> PyResult<Vec<String>> {
        call(slf, "observation_names", |this| {
            Ok(this
                .env
                .get()
                .observation_layout()
                .rows()
                .iter()
                .map(|r| r.name.to_string())
                .collect())
        })
    }

    /// This env's observation table: its robot's §3 rows, then the rows of
    /// `observation.extra` (see `spaces::table_rows`).
    fn observation_table<'py>(slf: &Bound<'py, Self>) -> PyResult<Vec<crate::spaces::TableRow>> {
        call(slf, "observation_table", |this| {
            Ok(crate::spaces::table_rows(
                this.env.get().observation_layout(),
            ))
        })
    }

    /// The joints' names in action order.
    fn joint_names<'py>(slf: &Bound<'py, Self>) -> PyResult<Vec<String>> {
        call(slf, "joint_names", |this| {
            Ok(this
                .env
                .get()
                .model()
                .joints()
                .iter()
                .map(|j| j.name.clone())
                .collect())
        })
    }

    /// t_max (`task.max_time_steps`).
    #[getter]
    fn max_time_steps<'py>(slf: &Bound<'py, Self>) -> PyResult<u64> {
        call(slf, "max_time_steps", |this| {
            Ok(this.env.get().config().task.max_time_steps)
        })
    }

    /// Δt_env = sub-steps × dt (s).
    #[getter]
    fn env_dt<'py>(slf: &Bound<'py, Self>) -> PyResult<f64> {
        call(slf, "env_dt", |this| Ok(this.env.get().env_dt()))
    }

    /// The action mode (`normalized`, `absolute`, `delta` or `offset`).
    #[getter]
    fn action_mode<'py>(slf: &Bound<'py, Self>) -> PyResult<&'static str> {
        call(slf, "action_mode", |this| {
            Ok(config::action_mode_name(
                this.env.get().config().action.mode,
            ))
        })
    }

    /// Whether observations are clipped to the declared bounds.
    #[getter]
    fn clip_observations<'py>(slf: &Bound<'py, Self>) -> PyResult<bool> {
        call(slf, "clip_observations", |this| Ok(this.clip.is_some()))
    }

    /// The frame size (width, height) of `render`.
    #[getter]
    fn render_size<'py>(slf: &Bound<'py, Self>) -> PyResult<(u32, u32)> {
        call(slf, "render_size", |this| Ok(this.frames.size()))
    }

    /// The whole validated configuration as TOML text.
    fn config_toml<'py>(slf: &Bound<'py, Self>) -> PyResult<String> {
        call(slf, "config_toml", |this| {
            Ok(this.env.get().config().to_toml_string())
        })
    }

    /// The robot's name (its profile's `name`).
    #[getter]
    fn robot<'py>(slf: &Bound<'py, Self>) -> PyResult<String> {
        call(slf, "robot", |this| {
            Ok(this.env.get().model().name().to_owned())
        })
    }

    /// Whether the next call must be `reset` (no episode started, or it ended).
    fn needs_reset<'py>(slf: &Bound<'py, Self>) -> PyResult<bool> {
        call(slf, "needs_reset", |this| Ok(this.env.get().needs_reset()))
    }
}
