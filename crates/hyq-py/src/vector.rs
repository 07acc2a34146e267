//! `hyq._core.VecCore`: N environments stepped together on rayon with the GIL released, for
//! `hyq.HyQVectorEnv` (Gymnasium) and `hyq.sb3.HyQVecEnv` (Stable-Baselines3).
//!
//! The autoreset modes are hyq-env's [`AutoReset`]: `next_step` (Gymnasium's default),
//! `same_step` (what Stable-Baselines3 expects, with the final observation and info kept until
//! the next step) and `disabled`.

use hyq_env::{AutoReset, ResetOptions, VecStepOut};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray2};
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::config;
use crate::engines::{self, Held, VecView};
use crate::errors::vec_env_error;
use crate::frames::FrameSource;
use crate::guard::{Retirable, call, call_mut};
use crate::info::{info_dict, vector_info_dict};
use crate::spaces::{
    Bounds, clip_in_place, declared_bounds, high_inward, low_inward, table_bounds, would_clip,
};

/// N environments (a robot on a backend) stepped in parallel.
#[pyclass(module = "hyq._core")]
pub struct VecCore {
    vec: Held<dyn VecView>,
    clip: Option<Bounds>,
    /// Σ reward of each env's current episode, for the frame overlay.
    returns: Vec<f64>,
    frames: FrameSource,
    /// The last step's actions, copied out of NumPy (reused: no allocation per step).
    actions: Vec<f64>,
    /// Why the env was retired (after an internal error), if it was.
    retired: Option<String>,
}

impl Retirable for VecCore {
    fn retired(&self) -> Option<&str> {
        self.retired.as_deref()
    }

    fn retire(&mut self, why: String) {
        self.retired = Some(why);
    }
}

/// The autoreset mode named as in Gymnasium's `AutoresetMode` values.
fn autoreset_mode(name: &str) -> PyResult<AutoReset> {
    match name {
        "next_step" | "NextStep" => Ok(AutoReset::NextStep),
        "same_step" | "SameStep" => Ok(AutoReset::SameStep),
        "disabled" | "Disabled" => Ok(AutoReset::Disabled),
        other => Err(PyValueError::new_err(format!(
            "autoreset_mode = {other:?}: expected \"next_step\", \"same_step\" or \"disabled\""
        ))),
    }
}

type StepArrays<'py> = (
    Bound<'py, PyArray2<f32>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyDict>,
);

impl VecCore {
    fn check_index(&self, i: usize) -> PyResult<()> {
        let n = self.vec.get().num_envs();
        if i < n {
            Ok(())
        } else {
            Err(PyIndexError::new_err(format!(
                "env index {i} out of range: there are {n} envs"
            )))
        }
    }

    /// (N, obs_len) observations from a flat buffer (clipped if configured) and the vector
    /// info, with each env's `observation_clipped` flag.
    fn observations_and_infos<'py>(
        &self,
        py: Python<'py>,
        mut flat: Vec<f32>,
    ) -> PyResult<(Bound<'py, PyArray2<f32>>, Bound<'py, PyDict>)> {
        let vec = self.vec.get();
        // Clipped where they lie: the buffer becomes the NumPy array without another copy.
        let clipped: Vec<bool> = flat
            .chunks_mut(vec.observation_len())
            .map(|o| clip_in_place(o, self.clip.as_ref()))
            .collect();
        let array = Array2::from_shape_vec((vec.num_envs(), vec.observation_len()), flat)
            .map_err(|e| PyValueError::new_err(format!("observations: {e}")))?;
        let infos: Vec<_> = (0..vec.num_envs()).map(|i| vec.info(i)).collect();
        let engines: Vec<&str> = (0..vec.num_envs())
            .map(|i| vec.env(i).engine_name())
            .collect();
        let info = vector_info_dict(py, &infos, vec.env(0).model(), &clipped, &engines)?;
        Ok((array.into_pyarray(py), info))
    }

    fn current_observations(&self) -> Vec<f32> {
        let vec = self.vec.get();
        (0..vec.num_envs())
            .flat_map(|i| vec.env(i).observation_f32().iter().copied())
            .collect()
    }
}

#[pymethods]
impl VecCore {
    /// `num_envs` environments of one configuration (as `Core`), with the autoreset mode
    /// `"next_step"`, `"same_step"` or `"disabled"`, on rayon's global pool or on a pool of
    /// `threads` threads; on `backend`, or on the engines of `backends` assigned round-robin
    /// (env i on the (i mod length)-th).
    #[new]
    #[pyo3(signature = (pairs, num_envs, autoreset_mode="next_step", config_file=None, threads=None, clip_observations=crate::CLIP_OBSERVATIONS_DEFAULT, render_width=hyq_render::DEFAULT_WIDTH_PX, render_height=hyq_render::DEFAULT_HEIGHT_PX, robot=None, backend=hyq_engines::DEFAULT.name, backends=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        pairs: Vec<(String, String)>,
        num_envs: usize,
        autoreset_mode: &str,
        config_file: Option<String>,
        threads: Option<usize>,
        clip_observations: bool,
        render_width: u32,
        render_height: u32,
        robot: Option<String>,
        backend: &str,
        backends: Option<Vec<String>>,
    ) -> PyResult<Self> {
        let mode = self::autoreset_mode(autoreset_mode)?;
        let backends = backends.unwrap_or_else(|| vec![backend.to_owned()]);
        let model = engines::robot(robot.as_deref())?;
        let config = config::build(config_file.as_deref(), &pairs)?;
        let vec = engines::make_vec(&backends, model, config, num_envs, mode, threads)?;
        let clip = clip_observations.then(|| table_bounds(vec.env(0)));
        let frames = FrameSource::new(render_width, render_height)?;
        Ok(Self {
            returns: vec![0.0; vec.num_envs()],
            vec: Held::new(vec),
            clip,
            frames,
            actions: Vec::new(),
            retired: None,
        })
    }

    /// Resets envs; returns ((N, obs_len) observations, vector info).
    ///
    /// `seed`: env i is seeded `seed + i`; `seeds`: one seed (or None) per env instead; `goal`:
    /// this episode's goal for every env reset; `mask`: reset only the envs whose flag is true
    /// (the others keep their state and report their current observation).
    #[pyo3(signature = (seed=None, seeds=None, goal=None, mask=None))]
    fn reset<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        seed: Option<u64>,
        seeds: Option<Vec<Option<u64>>>,
        goal: Option<[f64; 3]>,
        mask: Option<Vec<bool>>,
    ) -> PyResult<(Bound<'py, PyArray2<f32>>, Bound<'py, PyDict>)> {
        call_mut(slf, "reset", |this| {
            let n = this.vec.get_mut().num_envs();
            for (what, len) in [
                ("seeds", seeds.as_ref().map(Vec::len)),
                ("mask", mask.as_ref().map(Vec::len)),
            ] {
                if let Some(len) = len
                    && len != n
                {
                    return Err(PyValueError::new_err(format!(
                        "{what} has {len} values, expected one per env ({n})"
                    )));
                }
            }
            if seeds.is_none() && goal.is_none() && mask.is_none() {
                let vec = this.vec.get_mut();
                let mut flat = vec![0.0f32; n * vec.observation_len()];
                py.detach(|| vec.reset(seed, &mut flat))
                    .map_err(vec_env_error)?;
                this.returns.fill(0.0);
                return this.observations_and_infos(py, flat);
            }
            let options = ResetOptions {
                goal,
                ..ResetOptions::default()
            };
            for i in 0..n {
                if mask.as_ref().is_some_and(|m| !m[i]) {
                    continue;
                }
                let seed_i = match &seeds {
                    Some(s) => s[i],
                    None => seed.map(|s| s.wrapping_add(i as u64)),
                };
                this.vec
                    .get_mut()
                    .reset_env(i, seed_i, &options)
                    .map_err(vec_env_error)?;
                this.returns[i] = 0.0;
            }
            let flat = this.current_observations();
            this.observations_and_infos(py, flat)
        })
    }

    /// Steps every env with its row of `actions` ((N, action_len) float64); returns
    /// (observations, rewards, terminated, truncated, vector info).
    fn step<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        actions: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<StepArrays<'py>> {
        call_mut(slf, "step", |this| {
            let vec = this.vec.get_mut();
            let (n, width) = (vec.num_envs(), vec.action_len());
            let shape = actions.as_array().dim();
            if shape != (n, width) {
                return Err(PyValueError::new_err(format!(
                    "actions have shape {shape:?}, expected ({n}, {width})"
                )));
            }
            // Copied while the GIL is held: another Python thread may write to the array while
            // the envs step.
            this.actions.clear();
            this.actions.extend(actions.as_array().iter().copied());
            let mut observations = vec![0.0f32; n * this.vec.get_mut().observation_len()];
            let mut rewards = vec![0.0f64; n];
            let mut terminated = vec![false; n];
            let mut truncated = vec![false; n];
            let (vec, actions) = (this.vec.get_mut(), &this.actions);
            py.detach(|| {
                vec.step(
                    actions,
                    VecStepOut {
                        observations: &mut observations,
                        rewards: &mut rewards,
                        terminated: &mut terminated,
                        truncated: &mut truncated,
                    },
                )
            })
            .map_err(vec_env_error)?;
            for (i, r) in rewards.iter().enumerate() {
                // t = 0: the env was reset in this step (an autoreset), so a new episode began.
                this.returns[i] = if this.vec.get_mut().info(i).t == 0 {
                    0.0
                } else {
                    this.returns[i] + r
                };
            }
            let (observations, infos) = this.observations_and_infos(py, observations)?;
            Ok((
                observations,
                rewards.into_pyarray(py),
                terminated.into_pyarray(py),
                truncated.into_pyarray(py),
                infos,
            ))
        })
    }

    /// Env `i`'s info of its last step or reset, as the single env's dict.
    fn env_info<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        i: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        call(slf, "env_info", |this| {
            this.check_index(i)?;
            let vec = this.vec.get();
            let clipped = would_clip(vec.env(i).observation_f32(), this.clip.as_ref());
            info_dict(
                py,
                vec.info(i),
                vec.env(i).model(),
                clipped,
                vec.env(i).engine_name(),
            )
        })
    }

    /// With `same_step` autoreset: env `i`'s final observation if its episode ended in the
    /// last step, else None.
    fn final_observation<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        i: usize,
    ) -> PyResult<Option<Bound<'py, PyArray1<f32>>>> {
        call(slf, "final_observation", |this| {
            this.check_index(i)?;
            Ok(this.vec.get().final_observation(i).map(|o| {
                let mut o = o.to_vec();
                clip_in_place(&mut o, this.clip.as_ref());
                o.into_pyarray(py)
            }))
        })
    }

    /// With `same_step` autoreset: env `i`'s final step's info if its episode ended in the last
    /// step, else None.
    fn final_info<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        i: usize,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        call(slf, "final_info", |this| {
            this.check_index(i)?;
            let vec = this.vec.get();
            let (Some(info), Some(obs)) = (vec.final_info(i), vec.final_observation(i)) else {
                return Ok(None);
            };
            let clipped = would_clip(obs, this.clip.as_ref());
            info_dict(
                py,
                info,
                vec.env(i).model(),
                clipped,
                vec.env(i).engine_name(),
            )
            .map(Some)
        })
    }

    /// A frame of env `i`'s current state (uint8, (height, width, 3)).
    fn render<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
        i: usize,
    ) -> PyResult<Bound<'py, PyArray3<u8>>> {
        call_mut(slf, "render", |this| {
            this.check_index(i)?;
            let vec = this.vec.get_mut();
            this.frames.frame(py, vec.env(i), this.returns[i])
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

    /// N.
    #[getter]
    fn num_envs<'py>(slf: &Bound<'py, Self>) -> PyResult<usize> {
        call(slf, "num_envs", |this| Ok(this.vec.get().num_envs()))
    }

    /// The envs' observation table (the same for every env): its robot's §3 rows, then the
    /// rows of `observation.extra` (see `spaces::table_rows`).
    fn observation_table<'py>(slf: &Bound<'py, Self>) -> PyResult<Vec<crate::spaces::TableRow>> {
        call(slf, "observation_table", |this| {
            Ok(crate::spaces::table_rows(
                this.vec.get().env(0).observation_layout(),
            ))
        })
    }

    /// The observation space's lower bounds (float32; see `spaces`).
    fn observation_low<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "observation_low", |this| {
            Ok(declared_bounds(this.vec.get().env(0), this.clip.is_some())
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
            Ok(declared_bounds(this.vec.get().env(0), this.clip.is_some())
                .1
                .into_pyarray(py))
        })
    }

    /// The action space's lower bounds (float32).
    fn action_low<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "action_low", |this| {
            Ok(low_inward(this.vec.get().env(0).action_space().low()).into_pyarray(py))
        })
    }

    /// The action space's upper bounds (float32).
    fn action_high<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        call(slf, "action_high", |this| {
            Ok(high_inward(this.vec.get().env(0).action_space().high()).into_pyarray(py))
        })
    }

    /// t_max (`task.max_time_steps`).
    #[getter]
    fn max_time_steps<'py>(slf: &Bound<'py, Self>) -> PyResult<u64> {
        call(slf, "max_time_steps", |this| {
            Ok(this.vec.get().env(0).config().task.max_time_steps)
        })
    }

    /// Δt_env (s).
    #[getter]
    fn env_dt<'py>(slf: &Bound<'py, Self>) -> PyResult<f64> {
        call(slf, "env_dt", |this| Ok(this.vec.get().env(0).env_dt()))
    }

    /// The action mode.
    #[getter]
    fn action_mode<'py>(slf: &Bound<'py, Self>) -> PyResult<&'static str> {
        call(slf, "action_mode", |this| {
            Ok(config::action_mode_name(
                this.vec.get().env(0).config().action.mode,
            ))
        })
    }

    /// Each env's engine, in env order.
    fn backends<'py>(slf: &Bound<'py, Self>) -> PyResult<Vec<&'static str>> {
        call(slf, "backends", |this| {
            let vec = this.vec.get();
            Ok((0..vec.num_envs())
                .map(|i| vec.env(i).engine_name())
                .collect())
        })
    }

    /// The robot's name (its profile's `name`).
    #[getter]
    fn robot<'py>(slf: &Bound<'py, Self>) -> PyResult<String> {
        call(slf, "robot", |this| {
            Ok(this.vec.get().env(0).model().name().to_owned())
        })
    }

    /// The autoreset mode (`next_step`, `same_step` or `disabled`).
    #[getter]
    fn autoreset_mode<'py>(slf: &Bound<'py, Self>) -> PyResult<&'static str> {
        call(slf, "autoreset_mode", |this| {
            Ok(match this.vec.get().autoreset() {
                AutoReset::NextStep => "next_step",
                AutoReset::SameStep => "same_step",
                AutoReset::Disabled => "disabled",
            })
        })
    }
}
