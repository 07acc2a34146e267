//! N environments stepped together with rayon into caller-owned flat buffers (the shape the
//! Python binding hands to NumPy): observations N × obs_len f32, rewards N f64, terminated and
//! truncated N bool.
//!
//! Each environment is independent: the results are those of N single [`Env`]s given the same
//! seeds and actions, bit for bit, whatever the number of threads. Env i of a reset with seed s
//! is seeded s + i (wrapping), as Gymnasium's vector envs do.
//!
//! Threads: the calling thread and T − 1 pool threads each step a contiguous block of the envs,
//! the blocks of about equal cost by each env's last step time and each ordered most costly
//! first, and then take the envs left at the back of the others' blocks (`Blocks`): the calling
//! thread steps envs instead of sleeping while a pool does (one thread fewer to wake per step,
//! and none at all on one thread), each env stays on one thread while the costs hold, and what
//! is left to share at a step's end is the cheap envs (envs on different engines, a
//! `VecEnv<hyq_engines::AnyBackend>`, differ several-fold in cost).
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

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use hyq_physics::{Backend, RobotModel};
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
    workers: Workers,
    /// Nanoseconds of each env's last step or reset, which the threads' blocks balance.
    costs: Vec<AtomicU64>,
    obs_len: usize,
    action_len: usize,
}

/// The threads that step a vector env's envs, besides the calling thread.
enum Workers {
    /// rayon's global pool, all but one of its threads (the calling thread is the other).
    Global,
    /// None: one thread, the calling thread.
    Caller,
    /// A dedicated pool ([`VecEnv::with_threads`]).
    Pool(rayon::ThreadPool),
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
            workers: Workers::Global,
            costs: (0..num_envs).map(|_| AtomicU64::new(0)).collect(),
            obs_len,
            action_len,
        })
    }

    /// Runs the envs on `threads` threads (1 to [`MAX_THREADS`]), the calling thread and a
    /// dedicated pool of `threads` − 1, instead of rayon's global pool (results are the same
    /// whatever the count).
    pub fn with_threads(mut self, threads: usize) -> Result<Self, VecEnvError> {
        if !(1..=MAX_THREADS).contains(&threads) {
            return Err(VecEnvError::Setup(format!(
                "threads = {threads}: must be from 1 to {MAX_THREADS}"
            )));
        }
        self.workers = if threads == 1 {
            Workers::Caller
        } else {
            let helpers = threads - 1;
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(helpers)
                .build()
                .map_err(|e| VecEnvError::Setup(format!("thread pool of {helpers}: {e}")))?;
            Workers::Pool(pool)
        };
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

    /// Runs `work(index, item)` on each of `items` on the calling thread and the workers'
    /// threads ([`Blocks`]). On errors, the lowest index's.
    fn share_out<T: Send>(
        &self,
        items: impl Iterator<Item = T>,
        work: impl Fn(usize, T) -> Result<(), VecEnvError> + Sync,
    ) -> Result<(), VecEnvError> {
        let helpers = match &self.workers {
            // One thread: the items in turn, with nothing to share or balance.
            Workers::Caller => {
                let mut first_error = None;
                for (index, item) in items.enumerate() {
                    if let Err(e) = work(index, item) {
                        first_error.get_or_insert(e);
                    }
                }
                return first_error.map_or(Ok(()), Err);
            }
            Workers::Pool(pool) => pool.current_num_threads(),
            Workers::Global => rayon::current_num_threads().saturating_sub(1),
        };
        let cost_cells = &self.costs;
        let costs: Vec<u64> = cost_cells
            .iter()
            .map(|c| c.load(Ordering::Relaxed))
            .collect();
        let items: Vec<Mutex<Option<T>>> = items.map(|t| Mutex::new(Some(t))).collect();
        let blocks = Blocks::new(&costs, helpers + 1);
        let finished = AtomicUsize::new(0);
        let first_error: Mutex<Option<(usize, VecEnvError)>> = Mutex::new(None);
        let drain = |part: usize| {
            while let Some(index) = blocks.next(part) {
                // Counted finished even if `work` panics, so that the caller's wait below ends
                // and the scope passes the panic on instead of hanging.
                let _counted = Finished(&finished);
                let item = lock(&items[index]).take();
                let start = Instant::now();
                let result = item.map(|item| work(index, item));
                let nanos = u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX);
                cost_cells[index].store(nanos, Ordering::Relaxed);
                if let Some(Err(e)) = result {
                    let mut first = lock(&first_error);
                    if first.as_ref().is_none_or(|(i, _)| index < *i) {
                        *first = Some((index, e));
                    }
                }
            }
        };
        // The calling thread, once nothing is left to take, yields until the items others took
        // are finished rather than sleep at the scope's end and be woken (tens of microseconds
        // on a virtual machine's idle core, at every step).
        let drain_and_wait = || {
            drain(0);
            while finished.load(Ordering::Acquire) < items.len() {
                std::thread::yield_now();
            }
        };
        let drain = &drain;
        if let Workers::Pool(pool) = &self.workers {
            pool.in_place_scope(|s| {
                (1..=helpers).for_each(|part| s.spawn(move |_| drain(part)));
                drain_and_wait();
            });
        } else {
            rayon::in_place_scope(|s| {
                (1..=helpers).for_each(|part| s.spawn(move |_| drain(part)));
                drain_and_wait();
            });
        }
        match lock(&first_error).take() {
            Some((_, e)) => Err(e),
            None => Ok(()),
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
        let items = slots.iter_mut().zip(observations.chunks_mut(obs_len));
        let result = self.share_out(items, |index, (slot, out)| {
            let seed = seed.map(|s| s.wrapping_add(index as u64));
            let r = slot
                .env
                .reset(seed, &ResetOptions::default())
                .map_err(|source| VecEnvError::Env { index, source })?;
            out.copy_from_slice(r.observation_f32);
            slot.pending_reset = false;
            slot.has_final = false;
            Ok(())
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
        let items = slots
            .iter_mut()
            .zip(actions.chunks(action_len))
            .zip(observations.chunks_mut(obs_len))
            .zip(rewards.iter_mut().zip(terminated.iter_mut().zip(truncated)));
        let result = self.share_out(
            items,
            |index, (((slot, action), obs), (reward, (term, trunc)))| {
                step_slot(slot, mode, action, obs, reward, term, trunc)
                    .map_err(|source| VecEnvError::Env { index, source })
            },
        );
        self.slots = slots;
        result
    }
}

/// The indices 0..n split into one contiguous block per thread ([`Blocks::new`]): a thread takes
/// its own block's indices from the front and, when it is empty, the last index of the block with
/// the most left. Each env thus stays on the same thread from step to step (its state in that
/// core's caches) while the costs hold, and a thread that finishes early takes the cheapest
/// envs left rather than wait.
struct Blocks(Mutex<Vec<Block>>);

/// One thread's envs, most costly first, and how far they are taken from either end.
struct Block {
    order: Vec<usize>,
    front: usize,
    back: usize,
}

impl Blocks {
    /// Blocks of about equal cost by `costs` (each env's last step, any unit; a cost of 0 counts
    /// as 1, so that without figures the blocks are of about equal size), contiguous in index,
    /// each ordered most costly first so that what is left to take at a step's end is cheap.
    fn new(costs: &[u64], parts: usize) -> Self {
        let costs: Vec<u128> = costs.iter().map(|c| u128::from((*c).max(1))).collect();
        let total: u128 = costs.iter().sum::<u128>().max(1);
        let parts_wide = parts as u128;
        let mut blocks: Vec<Vec<usize>> = vec![Vec::new(); parts];
        let mut before = 0u128;
        for (i, c) in costs.iter().enumerate() {
            // The part whose share of the total holds the middle of env i's cost.
            let part = ((2 * before + c) * parts_wide / (2 * total)) as usize;
            blocks[part.min(parts - 1)].push(i);
            before += c;
        }
        let blocks = blocks
            .into_iter()
            .map(|mut order| {
                order.sort_by_key(|i| std::cmp::Reverse(costs[*i]));
                let back = order.len();
                Block {
                    order,
                    front: 0,
                    back,
                }
            })
            .collect();
        Self(Mutex::new(blocks))
    }

    /// The next index for thread `part`, if any is left.
    fn next(&self, part: usize) -> Option<usize> {
        let mut blocks = lock(&self.0);
        let own = &mut blocks[part];
        if own.front < own.back {
            own.front += 1;
            return Some(own.order[own.front - 1]);
        }
        let fullest = blocks.iter_mut().max_by_key(|b| b.back - b.front)?;
        (fullest.front < fullest.back).then(|| {
            fullest.back -= 1;
            fullest.order[fullest.back]
        })
    }
}

/// Adds one to its counter when dropped, also while unwinding.
struct Finished<'a>(&'a AtomicUsize);

impl Drop for Finished<'_> {
    fn drop(&mut self) {
        self.0.fetch_add(1, Ordering::Release);
    }
}

/// `m`'s guard, whether or not another thread panicked while holding it.
fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
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

#[cfg(test)]
mod tests {
    use super::Blocks;

    /// The indices `Blocks` hands out when the parts ask in `order` (repeated until all are
    /// empty), as (part, index) pairs.
    fn hand_out(costs: &[u64], parts: usize, order: &[usize]) -> Vec<(usize, usize)> {
        let blocks = Blocks::new(costs, parts);
        let mut taken = vec![];
        let mut done = vec![false; parts];
        while !done.iter().all(|d| *d) {
            for &part in order {
                match blocks.next(part) {
                    Some(i) => taken.push((part, i)),
                    None => done[part] = true,
                }
            }
        }
        taken
    }

    #[test]
    fn every_index_is_handed_out_once_whatever_the_costs_and_the_order_of_asking() {
        for n in 0..20 {
            for parts in 1..7 {
                let orders: [Vec<usize>; 3] = [
                    (0..parts).collect(),
                    (0..parts).rev().collect(),
                    // One part asks three times as often as the others.
                    (0..parts)
                        .flat_map(|p| vec![p; if p == 0 { 3 } else { 1 }])
                        .collect(),
                ];
                let costs: [Vec<u64>; 4] = [
                    vec![0; n],
                    vec![1; n],
                    (0..n as u64)
                        .map(|i| [700, 400, 100][i as usize % 3])
                        .collect(),
                    (0..n as u64)
                        .map(|i| if i == 0 { u64::MAX } else { i })
                        .collect(),
                ];
                for (order, costs) in orders
                    .iter()
                    .flat_map(|o| costs.iter().map(move |c| (o, c)))
                {
                    let mut indices: Vec<usize> = hand_out(costs, parts, order)
                        .iter()
                        .map(|(_, i)| *i)
                        .collect();
                    indices.sort_unstable();
                    assert_eq!(
                        indices,
                        (0..n).collect::<Vec<_>>(),
                        "n {n}, {order:?}, {costs:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn equal_costs_give_contiguous_blocks_of_about_equal_size() {
        // 10 envs on 3 threads asking in turn: blocks 0..3, 3..7, 7..10, each taken in index
        // order; part 0, out of envs first, then takes the last of the fullest block.
        let taken = hand_out(&[5; 10], 3, &[0, 1, 2]);
        let blocks = [0..3, 3..7, 7..10];
        for (part, i) in &taken[..9] {
            assert!(blocks[*part].contains(i), "part {part} took {i}");
        }
        assert_eq!(taken[9], (0, 6));
        assert_eq!(taken.len(), 10);
    }

    #[test]
    fn blocks_balance_cost_and_leave_the_cheap_envs_to_the_end() {
        // Envs 0-3 cost 9 each, 4-11 cost 1 (44 in all): two threads get 0-1 (18) and 2-11
        // (26), each env going to the half that holds the middle of its cost...
        let costs = [9, 9, 9, 9, 1, 1, 1, 1, 1, 1, 1, 1];
        let blocks = Blocks::new(&costs, 2);
        // ...part 0 the first two expensive envs, part 1 the other two, then its cheap ones.
        assert_eq!((blocks.next(0), blocks.next(0)), (Some(0), Some(1)));
        assert_eq!((blocks.next(1), blocks.next(1)), (Some(2), Some(3)));
        // Part 0, out of envs, takes from the back of part 1's: the cheapest.
        assert_eq!(blocks.next(0), Some(11));
        // A block is ordered most costly first, whatever the indices' order.
        let blocks = Blocks::new(&[1, 5, 3, 9], 1);
        let order: Vec<_> = std::iter::from_fn(|| blocks.next(0)).collect();
        assert_eq!(order, [3, 1, 2, 0]);
    }

    #[test]
    fn a_part_that_runs_out_takes_from_the_back_of_the_fullest_block() {
        let blocks = Blocks::new(&[0; 8], 2);
        assert_eq!(
            (0..4).map(|_| blocks.next(0)).collect::<Vec<_>>(),
            [Some(0), Some(1), Some(2), Some(3)]
        );
        assert_eq!(blocks.next(1), Some(4));
        assert_eq!(blocks.next(0), Some(7));
        assert_eq!(blocks.next(0), Some(6));
        assert_eq!(blocks.next(1), Some(5));
        assert_eq!((blocks.next(0), blocks.next(1)), (None, None));
    }
}
