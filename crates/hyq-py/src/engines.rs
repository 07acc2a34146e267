//! The robot and the physics backend a Python environment runs: the choice by name
//! (`robot="anymal_c"`, `backend="mujoco"`), and the environments behind object-safe views
//! ([`EnvView`], [`VecView`]) so that one Python class serves every backend the package was
//! built with. A backend is compiled in by the crate feature of its name (`mujoco`, `dart`);
//! rapier always is.
//!
//! The views cost one indirect call per env step, nothing per sub-step: the physics loop
//! inside `Env::step` is monomorphised per backend as in Rust.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use hyq_engines::{AnyBackend, AnyOptions};
use hyq_env::{
    ActionSpace, AutoReset, Env, EnvConfig, EnvError, ResetOptions, StepInfo, VecEnv, VecEnvError,
    VecStepOut,
};
use hyq_physics::{Backend, RobotModel};
use hyq_spec::ObservationLayout;
use pyo3::PyResult;
use pyo3::exceptions::PyValueError;

use crate::errors::{env_error, vec_env_error};

/// The backends this build has, the default first (hyq-engines' table order).
pub fn built_backends() -> Vec<&'static str> {
    hyq_engines::built().map(|e| e.name).collect()
}

/// The error for a backend this build lacks or does not know.
fn backend_error(name: &str) -> pyo3::PyErr {
    let built = built_backends().join(", ");
    match hyq_engines::find(name) {
        None => PyValueError::new_err(format!(
            "backend={name:?}: unknown backend (this package was built with: {built}; \
             the project's backends are {})",
            hyq_engines::all_names()
        )),
        Some(engine) => {
            let needs = engine.needs.map_or_else(String::new, |n| {
                format!(" (needs {}: `{}` first)", n.what, n.install)
            });
            PyValueError::new_err(format!(
                "backend={name:?}: this hyq package was built without the {} backend (built: \
                 {built}); rebuild it with `maturin develop --release --features {}` in \
                 crates/hyq-py{needs}",
                engine.title,
                engine.feature.unwrap_or(engine.name)
            ))
        }
    }
}

/// The robot chosen by name or profile path, the profile's robot file a URDF or an MJCF
/// file, or an MJCF file alone (its profile drafted in memory, its standing height measured
/// as `hyq robot init` and the command line measure it: [`settle_height`]) (`None`: the
/// default, HyQ).
pub fn robot(choice: Option<&str>) -> PyResult<Arc<RobotModel>> {
    let choice = choice.unwrap_or(hyq_physics::bundled::DEFAULT);
    hyq_formats::robots::resolve_with(choice, Some(&settle_height)).map_err(|e| {
        PyValueError::new_err(format!("robot: {}", hyq_physics::one_line(&e.to_string())))
    })
}

/// An environment (or vector env) inside a Python object. A Python class must be `Sync`, and
/// the MuJoCo and DART backends are `Send` but not `Sync` (their C/C++ state is used by one
/// thread at a time), so the object holds it behind a mutex: calls that change it (`reset`,
/// `step`, `render`) hold `&mut` and reach it without locking; the read-only getters lock it,
/// uncontended (the guard module already keeps a second thread out of an env in use).
pub struct Held<T: ?Sized>(Mutex<Box<T>>);

impl<T: ?Sized> Held<T> {
    /// Holds `inner`.
    pub fn new(inner: Box<T>) -> Self {
        Self(Mutex::new(inner))
    }

    /// Shared access (locks; one guard at a time per object).
    pub fn get(&self) -> MutexGuard<'_, Box<T>> {
        // A panic inside a call retires the env (see `guard`), so a poisoned lock only serves
        // the calls that report that.
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Exclusive access, without locking.
    pub fn get_mut(&mut self) -> &mut T {
        self.0.get_mut().unwrap_or_else(PoisonError::into_inner)
    }
}

/// What the Python classes read from one environment, whatever its backend.
pub trait EnvView: Send {
    fn model(&self) -> &Arc<RobotModel>;
    /// The name of the engine this env runs on.
    fn engine_name(&self) -> &'static str;
    fn observation_f32(&self) -> &[f32];
    fn observation_layout(&self) -> &ObservationLayout;
    fn action_space(&self) -> &ActionSpace;
    fn config(&self) -> &EnvConfig;
    fn env_dt(&self) -> f64;
    fn info(&self) -> &StepInfo;
    fn needs_reset(&self) -> bool;
    /// The scene of the current state for the renderer (`hyq_render::env_scene`).
    fn scene(&self, episode_return: f64) -> hyq_render::Scene<'_>;
    fn reset(&mut self, seed: Option<u64>, options: &ResetOptions) -> Result<(), EnvError>;
    /// One step: (reward, terminated, truncated).
    fn step(&mut self, action: &[f64]) -> Result<(f64, bool, bool), EnvError>;
}

impl<B: Backend> EnvView for Env<B> {
    fn model(&self) -> &Arc<RobotModel> {
        Env::model(self)
    }
    fn engine_name(&self) -> &'static str {
        Env::engine_name(self)
    }
    fn observation_f32(&self) -> &[f32] {
        Env::observation_f32(self)
    }
    fn observation_layout(&self) -> &ObservationLayout {
        Env::observation_layout(self)
    }
    fn action_space(&self) -> &ActionSpace {
        Env::action_space(self)
    }
    fn config(&self) -> &EnvConfig {
        Env::config(self)
    }
    fn env_dt(&self) -> f64 {
        Env::env_dt(self)
    }
    fn info(&self) -> &StepInfo {
        Env::info(self)
    }
    fn needs_reset(&self) -> bool {
        Env::needs_reset(self)
    }
    fn scene(&self, episode_return: f64) -> hyq_render::Scene<'_> {
        hyq_render::env_scene(self, episode_return)
    }
    fn reset(&mut self, seed: Option<u64>, options: &ResetOptions) -> Result<(), EnvError> {
        Env::reset(self, seed, options).map(|_| ())
    }
    fn step(&mut self, action: &[f64]) -> Result<(f64, bool, bool), EnvError> {
        Env::step(self, action).map(|s| (s.reward, s.terminated, s.truncated))
    }
}

/// What the Python classes use of a vector env, whatever its backend.
pub trait VecView: Send {
    fn num_envs(&self) -> usize;
    fn observation_len(&self) -> usize;
    fn action_len(&self) -> usize;
    fn autoreset(&self) -> AutoReset;
    fn env(&self, i: usize) -> &dyn EnvView;
    fn info(&self, i: usize) -> &StepInfo;
    fn final_observation(&self, i: usize) -> Option<&[f32]>;
    fn final_info(&self, i: usize) -> Option<&StepInfo>;
    fn reset(&mut self, seed: Option<u64>, observations: &mut [f32]) -> Result<(), VecEnvError>;
    fn reset_env(
        &mut self,
        i: usize,
        seed: Option<u64>,
        options: &ResetOptions,
    ) -> Result<(), VecEnvError>;
    fn step(&mut self, actions: &[f64], out: VecStepOut<'_>) -> Result<(), VecEnvError>;
}

impl<B: Backend> VecView for VecEnv<B> {
    fn num_envs(&self) -> usize {
        VecEnv::num_envs(self)
    }
    fn observation_len(&self) -> usize {
        VecEnv::observation_len(self)
    }
    fn action_len(&self) -> usize {
        VecEnv::action_len(self)
    }
    fn autoreset(&self) -> AutoReset {
        VecEnv::autoreset(self)
    }
    fn env(&self, i: usize) -> &dyn EnvView {
        VecEnv::env(self, i)
    }
    fn info(&self, i: usize) -> &StepInfo {
        VecEnv::info(self, i)
    }
    fn final_observation(&self, i: usize) -> Option<&[f32]> {
        VecEnv::final_observation(self, i)
    }
    fn final_info(&self, i: usize) -> Option<&StepInfo> {
        VecEnv::final_info(self, i)
    }
    fn reset(&mut self, seed: Option<u64>, observations: &mut [f32]) -> Result<(), VecEnvError> {
        VecEnv::reset(self, seed, observations)
    }
    fn reset_env(
        &mut self,
        i: usize,
        seed: Option<u64>,
        options: &ResetOptions,
    ) -> Result<(), VecEnvError> {
        VecEnv::reset_env(self, i, seed, options).map(|_| ())
    }
    fn step(&mut self, actions: &[f64], out: VecStepOut<'_>) -> Result<(), VecEnvError> {
        VecEnv::step(self, actions, out)
    }
}

/// Evaluates `$body` with the type alias `$b` bound to the backend named `$name`
/// (`hyq_engines::with_engine!`); a name this build lacks is a `ValueError` naming the build
/// option.
macro_rules! with_backend {
    ($name:expr, $b:ident => $body:expr) => {{
        let name: &str = $name;
        hyq_engines::with_engine!(name, $b => $body).unwrap_or_else(|| Err(backend_error(name)))
    }};
}

/// One environment of `model` on the backend named `backend`.
pub fn make_env(
    backend: &str,
    model: Arc<RobotModel>,
    config: EnvConfig,
) -> PyResult<Box<dyn EnvView>> {
    with_backend!(backend, B => {
        Env::<B>::new(model, config)
            .map(|e| Box::new(e) as Box<dyn EnvView>)
            .map_err(env_error)
    })
}

/// `num_envs` environments of `model` on the backends named `backends`, assigned round-robin
/// (env i on the (i mod length)-th), on a pool of `threads` threads if given. One engine, even
/// listed several times, is a vector env of its own backend type; several are one
/// `VecEnv<AnyBackend>`. Each name must be built in, and there must be an env per name.
pub fn make_vec(
    backends: &[String],
    model: Arc<RobotModel>,
    config: EnvConfig,
    num_envs: usize,
    mode: AutoReset,
    threads: Option<usize>,
) -> PyResult<Box<dyn VecView>> {
    let Some(first) = backends.first() else {
        return Err(PyValueError::new_err(
            "backend = []: expected a backend's name or a non-empty list of them",
        ));
    };
    for name in backends {
        if !hyq_engines::find(name).is_some_and(|e| e.built) {
            return Err(backend_error(name));
        }
    }
    if backends.iter().all(|b| b == first) {
        return with_backend!(first, B => {
            let vec = VecEnv::<B>::new(model, config, num_envs, mode).map_err(vec_env_error)?;
            with_pool(vec, threads)
        });
    }
    if num_envs < backends.len() {
        return Err(PyValueError::new_err(format!(
            "backend = {backends:?} lists {} engines but num_envs = {num_envs}: give at least \
             one env per listed engine",
            backends.len()
        )));
    }
    let physics = config.physics.clone();
    let vec = VecEnv::<AnyBackend>::with_options(model, config, num_envs, mode, |i| {
        // Every name was checked to be built above, so each reads to Some.
        Ok(AnyOptions::read(&backends[i % backends.len()], &physics)?.unwrap_or_default())
    })
    .map_err(vec_env_error)?;
    with_pool(vec, threads)
}

/// `vec` on a pool of `threads` threads if given, boxed as a view.
fn with_pool<B: Backend>(vec: VecEnv<B>, threads: Option<usize>) -> PyResult<Box<dyn VecView>> {
    let vec = match threads {
        Some(threads) => vec.with_threads(threads).map_err(vec_env_error)?,
        None => vec,
    };
    Ok(Box::new(vec) as Box<dyn VecView>)
}

/// The trunk frame's height (m) after holding the standing pose on the default engine
/// (rapier), as the command line's `hyq robot init` measures it ([`hyq_env::settle`]).
fn settle_height(model: Arc<RobotModel>) -> Result<f64, String> {
    let engine = hyq_engines::DEFAULT.name;
    hyq_engines::with_engine!(engine, B => hyq_env::settle::settle_height::<B>(model))
        .unwrap_or_else(|| {
            Err(format!(
                "this package was built without the {engine} engine"
            ))
        })
}
