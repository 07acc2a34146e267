//! N environments stepped together with rayon into caller-owned flat buffers (the shape the
//! Python binding hands to NumPy): observations N × obs_len f32, rewards N f64, terminated and
//! truncated N bool.
//!
//! Each environment is independent: the results are those of N single [`Env`]s given the same
//! seeds and actions, bit for bit, whatever the number of threads. Env i of a reset with seed s
//! is seeded s + i (wrapping), as Gymnasium's vector envs do.
//!
//! Threads: every env is its own rayon task (`with_max_len(1)`), so an idle thread steals the
//! next env rather than wait for a fixed half of the batch. Envs of one engine cost about the
//! same per step, but envs on different engines (a `VecEnv<hyq_engines::AnyBackend>`) differ
//! several-fold, and a coarse split would leave the thread with the cheap envs idle.
//!
//! Autoreset ([`AutoReset`]), for an env whose episode ended on step k:
//! - `NextStep` (Gymnasium 1.x's default): step k reports the final observation, reward and
//!   flags; on step k + 1 its action is ignored and it is reset (unseeded: its streams continue),
//!   reporting the reset observation, reward 0 and both flags false;
//! - `SameStep`: step k reports the reward and flags of the final step but the observation of
//!   the reset that follows at once; the final observation and info are kept
//!   ([`VecEnv::final_observation`], [`VecEnv::final_info`]) until the next step;
//! - `Disabled`: nothing is reset; stepping an env whose episode ended is an error until
//!   [`VecEnv::reset_env`].

use std::sync::Arc;

use hyq_physics::{Backend, RobotModel};
use rayon::prelude::*;
use thiserror::Error;

use crate::action::ActionScalar;
use crate::config::EnvConfig;
use crate::env::{Env, ResetOptions};
use crate::error::EnvError;
use crate::info::StepInfo;

/// The most envs a [`VecEnv`] holds (`hyq bench --num-envs`, Python's `num_envs`): 4096 HyQ
/// envs on rapier take about 0.4 GB, and a count beyond it is far more likely a mistake than a
/// wish (a machine steps 4096 envs at a few hundred vector steps per second at best).
pub const MAX_ENVS: usize = 4096;

/// The most threads a [`VecEnv`]'s own pool may have (`hyq bench --threads`, Python's
/// `threads`).
pub const MAX_THREADS: usize = 4096;

/// When a vector env resets an env whose episode ended (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AutoReset {
    /// On the step after the end; that step's action is ignored (Gymnasium's default).
    #[default]
    NextStep,
    /// At once, in the step that ended the episode; its final observation and info are kept.
    SameStep,
    /// Never: the caller resets ended envs.
    Disabled,
}

/// Why a vector env refused a call.
#[derive(Debug, Error)]
pub enum VecEnvError {
    /// Env `index` refused (e.g. its action, or a step after its episode ended with autoreset
    /// disabled). Checked for every env before any steps, so nothing changed.
    #[error("env {index}: {source}")]
    Env {
        /// The env's index.
        index: usize,
        /// What it refused.
        #[source]
        source: EnvError,
    },
    /// A buffer of the wrong length.
    #[error("{what} has {got} values, expected {expected}")]
    Buffer {
        /// Which buffer.
        what: &'static str,
        /// The length needed.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// No environment (N = 0), or the thread pool could not be built.
    #[error("vector env: {0}")]
    Setup(String),
}

/// The caller-owned output buffers of one [`VecEnv::step`].
#[derive(Debug)]
pub struct VecStepOut<'a> {
    /// N × obs_len observations, env-major.
    pub observations: &'a mut [f32],
    /// N rewards.
    pub rewards: &'a mut [f64],
    /// N `terminated` flags.
    pub terminated: &'a mut [bool],
    /// N `truncated` flags.
    pub truncated: &'a mut [bool],
}

/// One env and its autoreset state.
struct Slot<B: Backend> {
    env: Env<B>,
    /// NextStep: the episode ended on the last step; reset on this one.
    pending_reset: bool,
    /// SameStep: the last step ended an episode and these hold its final observation and info.
    has_final: bool,
    final_observation: Vec<f32>,
    final_info: StepInfo,
}

/// N environments stepped in parallel (see the module docs).
pub struct VecEnv<B: Backend> {
    slots: Vec<Slot<B>>,
    autoreset: AutoReset,
    pool: Option<rayon::ThreadPool>,
    obs_len: usize,
    action_len: usize,
}

impl<B: Backend> VecEnv<B> {
    /// `num_envs` environments of `model` with `config` (each validated and built as
    /// [`Env::new`]), run on rayon's global thread pool. `num_envs` is from 1 to [`MAX_ENVS`],
    /// checked before any env is built.
    pub fn new(
        model: Arc<RobotModel>,
        config: EnvConfig,
        num_envs: usize,
        autoreset: AutoReset,
    ) -> Result<Self, VecEnvError> {
        Self::from_fn(num_envs, autoreset, |_| {
            Env::new(model.clone(), config.clone())
        })
    }

    /// As [`VecEnv::new`], env i built with the backend options `options(i)` ([`Env::with_options`]):
    /// a backend that wraps several engines (hyq-engines' `AnyBackend`) runs env i on the
    /// engine its options name. An error of `options(i)` is env i's.
    pub fn with_options(
        model: Arc<RobotModel>,
        config: EnvConfig,
        num_envs: usize,
        autoreset: AutoReset,
        mut options: impl FnMut(usize) -> Result<B::Options, EnvError>,
    ) -> Result<Self, VecEnvError> {
        Self::from_fn(num_envs, autoreset, |i| {
            Env::with_options(model.clone(), config.clone(), options(i)?)
        })
    }

    /// `num_envs` envs, env i `make(i)`, after checking the count.
    fn from_fn(
        num_envs: usize,
        autoreset: AutoReset,
        mut make: impl FnMut(usize) -> Result<Env<B>, EnvError>,
    ) -> Result<Self, VecEnvError> {
        if !(1..=MAX_ENVS).contains(&num_envs) {
            return Err(VecEnvError::Setup(format!(
                "num_envs = {num_envs}: must be from 1 to {MAX_ENVS}"
            )));
        }
        let slots = (0..num_envs)
            .map(|index| {
                let env = make(index).map_err(|source| VecEnvError::Env { index, source })?;
                Ok(Slot {
                    final_observation: vec![0.0; env.observation().len()],
                    final_info: env.info().clone(),
                    env,
                    pending_reset: false,
                    has_final: false,
                })
            })
            .collect::<Result<Vec<_>, VecEnvError>>()?;
        let obs_len = slots[0].env.observation().len();
        let action_len = slots[0].env.action_space().len();
        Ok(Self {
            slots,
            autoreset,
            pool: None,
            obs_len,
            action_len,
        })
    }

    /// Runs the envs on a dedicated pool of `threads` threads (1 to [`MAX_THREADS`]) instead of
    /// rayon's global pool (results are the same whatever the count).
    pub fn with_threads(mut self, threads: usize) -> Result<Self, VecEnvError> {
        if !(1..=MAX_THREADS).contains(&threads) {
            return Err(VecEnvError::Setup(format!(
                "threads = {threads}: must be from 1 to {MAX_THREADS}"
            )));
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| VecEnvError::Setup(format!("thread pool of {threads}: {e}")))?;
        self.pool = Some(pool);
        Ok(self)
    }

    /// N.
    pub fn num_envs(&self) -> usize {
        self.slots.len()
    }

    /// Values per observation (39 for HyQ).
    pub fn observation_len(&self) -> usize {
        self.obs_len
    }

    /// Values per action (12 for HyQ).
    pub fn action_len(&self) -> usize {
        self.action_len
    }

    /// The autoreset mode.
    pub fn autoreset(&self) -> AutoReset {
        self.autoreset
    }

    /// Env `i`.
    ///
    /// # Panics
    /// If `i` ≥ N.
    pub fn env(&self, i: usize) -> &Env<B> {
        &self.slots[i].env
    }

    /// Env `i`, mutably (e.g. to script a test backend).
    ///
    /// # Panics
    /// If `i` ≥ N.
    pub fn env_mut(&mut self, i: usize) -> &mut Env<B> {
        &mut self.slots[i].env
    }

    /// The info of env `i`'s last step or reset (after a same-step autoreset, the reset's; see
    /// [`VecEnv::final_info`]).
    ///
    /// # Panics
    /// If `i` ≥ N.
    pub fn info(&self, i: usize) -> &StepInfo {
        self.slots[i].env.info()
    }

    /// With [`AutoReset::SameStep`]: the final observation of env `i` if its episode ended in
    /// the last step.
    ///
    /// # Panics
    /// If `i` ≥ N.
    pub fn final_observation(&self, i: usize) -> Option<&[f32]> {
        let s = &self.slots[i];
        s.has_final.then_some(s.final_observation.as_slice())
    }

    /// With [`AutoReset::SameStep`]: the final step's info of env `i` if its episode ended in
    /// the last step.
    ///
    /// # Panics
    /// If `i` ≥ N.
    pub fn final_info(&self, i: usize) -> Option<&StepInfo> {
        let s = &self.slots[i];
        s.has_final.then_some(&s.final_info)
    }

    fn run<F: FnOnce() -> R + Send, R: Send>(&self, f: F) -> R {
        match &self.pool {
            Some(pool) => pool.install(f),
            None => f(),
        }
    }

    /// Resets every env: with `Some(s)`, env i is seeded s + i; with `None` each continues its
    /// streams. Writes the N first observations into `observations`.
    pub fn reset(
        &mut self,
        seed: Option<u64>,
        observations: &mut [f32],
    ) -> Result<(), VecEnvError> {
        check_len(
            "observations",
            self.slots.len() * self.obs_len,
            observations.len(),
        )?;
        let obs_len = self.obs_len;
        let mut slots = std::mem::take(&mut self.slots);
        let result = self.run(|| {
            slots
                .par_iter_mut()
                .zip(observations.par_chunks_mut(obs_len))
                .enumerate()
                .with_max_len(1)
                .try_for_each(|(index, (slot, out))| {
                    let seed = seed.map(|s| s.wrapping_add(index as u64));
                    let r = slot
                        .env
                        .reset(seed, &ResetOptions::default())
                        .map_err(|source| VecEnvError::Env { index, source })?;
                    out.copy_from_slice(r.observation_f32);
                    slot.pending_reset = false;
                    slot.has_final = false;
                    Ok(())
                })
        });
        self.slots = slots;
        result
    }

    /// Resets env `i` alone (e.g. with autoreset disabled) and returns its first observation.
    ///
    /// # Panics
    /// If `i` ≥ N.
    pub fn reset_env(
        &mut self,
        i: usize,
        seed: Option<u64>,
        options: &ResetOptions,
    ) -> Result<&[f32], VecEnvError> {
        let slot = &mut self.slots[i];
        slot.pending_reset = false;
        slot.has_final = false;
        let r = slot
            .env
            .reset(seed, options)
            .map_err(|source| VecEnvError::Env { index: i, source })?;
        Ok(r.observation_f32)
    }

    /// Steps every env with its action (`actions` is N × action_len, env-major, `f32` or `f64`)
    /// and writes the results into `out`. Every action and every env's state is checked first:
    /// on an error nothing changed.
    pub fn step<A: ActionScalar + Sync>(
        &mut self,
        actions: &[A],
        out: VecStepOut<'_>,
    ) -> Result<(), VecEnvError> {
        let n = self.slots.len();
        check_len("actions", n * self.action_len, actions.len())?;
        check_len("observations", n * self.obs_len, out.observations.len())?;
        check_len("rewards", n, out.rewards.len())?;
        check_len("terminated", n, out.terminated.len())?;
        check_len("truncated", n, out.truncated.len())?;
        for (index, (slot, action)) in self
            .slots
            .iter()
            .zip(actions.chunks(self.action_len))
            .enumerate()
        {
            let env = &slot.env;
            let fail = |source| Err(VecEnvError::Env { index, source });
            if let Err(e) = env.action_space().check(action) {
                return fail(EnvError::Action(e));
            }
            let will_reset = slot.pending_reset && self.autoreset == AutoReset::NextStep;
            if env.needs_reset() && !will_reset {
                return fail(if env.info().episode == 0 {
                    EnvError::NotReset
                } else {
                    EnvError::EpisodeOver {
                        episode: env.info().episode,
                        t: env.info().t,
                        reasons: env.info().reasons,
                    }
                });
            }
        }

        let (obs_len, action_len, mode) = (self.obs_len, self.action_len, self.autoreset);
        let VecStepOut {
            observations,
            rewards,
            terminated,
            truncated,
        } = out;
        let mut slots = std::mem::take(&mut self.slots);
        let result = self.run(|| {
            (
                slots.par_iter_mut(),
                actions.par_chunks(action_len),
                observations.par_chunks_mut(obs_len),
                rewards.par_iter_mut(),
                terminated.par_iter_mut(),
                truncated.par_iter_mut(),
            )
                .into_par_iter()
                .enumerate()
                .with_max_len(1)
                .try_for_each(|(index, (slot, action, obs, reward, term, trunc))| {
                    step_slot(slot, mode, action, obs, reward, term, trunc)
                        .map_err(|source| VecEnvError::Env { index, source })
                })
        });
        self.slots = slots;
        result
    }
}

/// One env's part of a vector step.
fn step_slot<B: Backend, A: ActionScalar>(
    slot: &mut Slot<B>,
    mode: AutoReset,
    action: &[A],
    obs: &mut [f32],
    reward: &mut f64,
    terminated: &mut bool,
    truncated: &mut bool,
) -> Result<(), EnvError> {
    slot.has_final = false;
    if slot.pending_reset {
        slot.pending_reset = false;
        let r = slot.env.reset(None, &ResetOptions::default())?;
        obs.copy_from_slice(r.observation_f32);
        *reward = 0.0;
        *terminated = false;
        *truncated = false;
        return Ok(());
    }
    let s = slot.env.step(action)?;
    *reward = s.reward;
    *terminated = s.terminated;
    *truncated = s.truncated;
    obs.copy_from_slice(s.observation_f32);
    if s.terminated || s.truncated {
        match mode {
            AutoReset::NextStep => slot.pending_reset = true,
            AutoReset::SameStep => {
                slot.final_observation.copy_from_slice(s.observation_f32);
                slot.final_info.clone_from(s.info);
                slot.has_final = true;
                let r = slot.env.reset(None, &ResetOptions::default())?;
                obs.copy_from_slice(r.observation_f32);
            }
            AutoReset::Disabled => {}
        }
    }
    Ok(())
}

fn check_len(what: &'static str, expected: usize, got: usize) -> Result<(), VecEnvError> {
    if expected == got {
        Ok(())
    } else {
        Err(VecEnvError::Buffer {
            what,
            expected,
            got,
        })
    }
}
