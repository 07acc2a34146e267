//! The HyQ walk-to-goal environment: IIT's HyQ quadruped (87 kg, 12 joints) must walk its trunk
//! to a goal. The spec's rules (`hyq-spec`: rewards, penalties, terminations, the observation
//! layout) run on a physics backend (`hyq-physics`' `Backend`: rapier by default, DART as a
//! second engine), with actions, goals, resets, scripted policies, a vector env and one record
//! schema around them.
//!
//! # Quickstart
//!
//! ```
//! use hyq_env::policy::{Policy, Stand};
//! use hyq_env::{Env, EnvConfig, ResetOptions};
//! use hyq_rapier::RapierBackend;
//!
//! let mut env = Env::<RapierBackend>::new(hyq_physics::bundled::hyq(), EnvConfig::default())?;
//! env.reset(Some(42), &ResetOptions::default())?;
//! let (mut policy, mut action) = (Stand, vec![0.0; 12]);
//! for _ in 0..50 {
//!     policy.act(&env.policy_input(), &mut action);
//!     let step = env.step(&action)?;
//!     assert!(!step.terminated && step.observation_f32.len() == 39);
//! }
//! assert!(env.info().distance_to_goal > 4.9); // standing still, 5 m from the goal
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Env card
//!
//! **Task.** HyQ spawns standing at the spawn point (default: the origin, facing +x, trunk frame
//! 0.6003 m up, feet 1 mm above the flat ground). The goal G is by default 5 m along +x at the
//! nominal standing height (0.5895 m, the profile's `spawn.standing_height`); fixed and seeded
//! random goals are options ([`GoalConfig`]). The trunk centre C^t of the spec is the origin of
//! the trunk's URDF link frame.
//!
//! **Time.** One env step = `control.sim_steps_per_env_step` (10) physics sub-steps of
//! `physics.dt` (0.001 s): 100 env steps per simulated second.
//!
//! **Observation** (39 × f64, also as f32; spec §3, written through `hyq_spec`'s
//! `ObservationLayout`, not clipped):
//!
//! | rows | what | unit |
//! |---|---|---|
//! | 0–11 | joint angles, §1 order `lf_haa, lf_hfe, lf_kfe, lh_…, rf_…, rh_…` | rad |
//! | 12–23 | joint speeds | rad/s |
//! | 24–27 | foot contact flags `lf, lh, rf, rh`: 1 if the foot touched the ground in any sub-step of the step | 0/1 |
//! | 28 | trunk contact flag (the §6.3 fall fact), latched the same way | 0/1 |
//! | 29–32 | trunk orientation quaternion w, x, y, z (world) | — |
//! | 33–35 | trunk acceleration (v^t − v^{t−1}) / Δt_env, world, gravity not included, 0 after reset | m/s² |
//! | 36–38 | trunk position C^t (world) | m |
//!
//! **Action** (12 values, `f64` or `f32`, §1 joint order; [`ActionConfig`]): joint position
//! targets tracked by the shared PD actuator τ = kp (q* − q) − kd q̇ (kp 1000, kd 20 for HyQ),
//! with the URDF velocity rule and clamped to ±150 N·m, evaluated every sub-step.
//!
//! | mode | space | target q*_i |
//! |---|---|---|
//! | `normalized` (default) | [−1, 1] | lo_i + (a_i + 1)/2 · (hi_i − lo_i) |
//! | `absolute` | [lo_i, hi_i] rad | a_i |
//! | `delta` | [−1, 1] | clip(θ_i + a_i · `max_delta_rad`, lo_i, hi_i) |
//! | `offset` | [−1, 1] | clip(s_i + a_i · `max_offset_rad`, lo_i, hi_i), s_i standing |
//!
//! Finite values outside the space are clipped (reported in `info.action_clipped`) or refused
//! (`action.out_of_range = "error"`); a NaN, an infinity or a wrong length is always an error,
//! and a refused action changes nothing.
//!
//! **Reward** (spec §4–§5 as ruled; every term in [`StepInfo::reward`]):
//!
//! r = (r_b + r_n + r_e + r_reach) · m_yaw · m_pitch · m_height − joint_penalty − fall_penalty
//!
//! | term | definition | default |
//! |---|---|---|
//! | r_b | k_base · (D^{t−1} − D^t) | off (`base_rew_scaling` unset) |
//! | r_n | k_norm · (D^{t−1} − D^t) / K | off (`norm_rew_scaling` unset) |
//! | r_e | R_e(D_n^t) − R_e(D_n^{t−1}), R_e the continuous curve of spec §4.3 | k_exp = 5 |
//! | r_reach | `reach_target_bonus_reward` on the step the goal is reached | 0 |
//! | m_yaw, m_pitch | 1 within ±2.5°, else max(0, cos angle) | 2.5° |
//! | m_height | opt-in §5.2 multiplier | off (1) |
//! | joint_penalty | `reach_bounds_penalty` on a joint-limit step | 0 |
//! | fall_penalty | `fall_penalty` on a fall step | 0 |
//!
//! D^t = ‖G − C^t‖, K = ‖G − C^0‖, D_n = D / K.
//!
//! **Episode end** ([`Reason`]; all that hold are reported):
//!
//! | reason | condition | Gymnasium flag |
//! |---|---|---|
//! | `reached` | \|C_i − G_i\| ≤ ε_reach / 2 on x, y, z (ε_reach 1 mm) | terminated |
//! | `joint_limit` | some θ ≤ θ_min + ε_joint or θ ≥ θ_max − ε_joint (ε_joint 0.01 rad) | terminated |
//! | `fell` | the trunk touched the ground in any sub-step of the step | terminated |
//! | `diverged` | the physics produced a non-finite state (not a spec condition) | terminated |
//! | `timeout` | t ≥ `max_time_steps` (1000) | truncated (unless also terminated) |
//!
//! A step after the end, without reset, is an error. On `diverged` the observation is the last
//! finite one, the reward 0 (terms 0, multipliers 1) and nothing NaN is emitted
//! (see [`env`](mod@env)).
//!
//! **Reset** ([`Env::reset`]): the standing pose at the spawn point and height, at rest; optional
//! seeded noise on the yaw and the joint angles ([`ResetConfig`], off by default). All randomness
//! comes from the reset seed through ChaCha8 streams (one for goals, one for noise); an unseeded
//! reset continues the streams, and an env never seeded behaves as seeded with 0.
//!
//! # Configuration
//!
//! One TOML file ([`EnvConfig`]): `[task]` (the spec's user variables, `hyq_spec::TaskConfig`),
//! `[goal]`, `[action]`, `[control]`, `[physics]` with `[physics.rapier]` / `[physics.dart]`,
//! `[reset]`. Every key has a documented default, unknown keys are errors naming the key, and
//! [`EnvConfig::set_all`] overrides by dotted key (`"task.fall_penalty"`, `"1.5"`).
//!
//! # Modules
//!
//! | module | what |
//! |---|---|
//! | [`env`](mod@env) | [`Env`]: reset, step, the sub-step loop, divergence, timing |
//! | [`config`] | [`EnvConfig`] and its tables |
//! | [`action`] | [`ActionSpace`]: checking actions and mapping them to joint targets |
//! | [`goal`] | goal sampling and the reset state |
//! | [`info`] | [`StepInfo`], [`Reason`], [`Reasons`] |
//! | [`policy`] | [`Stand`], [`RandomPolicy`], [`Trot`] |
//! | [`vec_env`] | [`VecEnv`]: N envs on rayon into flat buffers, autoreset modes |
//! | [`record`] | [`StepRecord`]: the per-step JSONL schema |
//! | [`testing`] | [`testing::ScriptedBackend`]: a scripted backend for contract tests |
//!
//! # Measured
//!
//! **Trot** ([`Trot`] with its defaults, default configuration, seed 0): 1000 env steps (10 s)
//! without a fall or any termination on both engines.
//!
//! | engine | x after 10 s | y | yaw | trunk z |
//! |---|---|---|---|---|
//! | rapier | 4.32 m (0.43 m/s) | −0.48 m | 0.21 rad | 0.571 m |
//! | DART | 4.28 m | −0.46 m | 0.18 rad | 0.569 m |
//!
//! On rapier, with 1 or 4 solver iterations, or 0.02 rad of reset noise on the joints (seeds
//! 1–4), it ends between x = 4.28 and 4.33 m. It is open loop, so it curves slowly, and it does
//! not reach the 1 mm reach cube of the default goal. Tests
//! (`trot_walks_forward_for_ten_seconds_without_falling`, and `trot_walks_forward_on_dart_too`
//! with `--features dart`) assert no trunk contact, no termination before the timeout, more than
//! 3 m forward and less than 1.5 m sideways.
//!
//! **Speed** (`cargo bench -p hyq-env --bench env_step`, 2026-11-22: rapier with its default
//! options, random actions redrawn every step, reset on any episode end; AMD EPYC, 2 vCPUs
//! shared with other builds, so upper bounds): criterion mean 764 µs per env step at load
//! average 1.3–1.9 and 924 µs at 2.4–3.0 (about 1100–1300 env steps/s). The timed run of 3000
//! steps that follows (at load 3) split a 1045 µs step into physics 1041.9 µs (99.7 %: the
//! engine's ten sub-steps and their contact reads), actuator 1.25 µs (0.12 %), spec evaluation
//! 0.61 µs (0.06 %), observation 0.35 µs (0.03 %) and the rest 0.93 µs: the environment's own
//! code costs about 3 µs of a step. [`Env::set_timing`] gives the same split at run time.

pub mod action;
pub mod config;
pub mod env;
pub mod goal;
pub mod info;
pub mod mlp;
pub mod policy;
pub mod record;
pub mod testing;
pub mod vec_env;

pub use action::{ActionError, ActionScalar, ActionSpace};
pub use config::{
    ActionConfig, ActionMode, ConfigError, ControlConfig, EXP_REW_SCALING_MAX, EnvConfig, Gains,
    GoalConfig, GoalMode, JOINT_NOISE_MAX_RAD, OutOfRange, PhysicsConfig, REWARD_SCALE_MAX,
    ResetConfig, WORLD_HALF_EXTENT_M,
};
pub use env::{
    DEFAULT_SEED, Env, EnvError, Reset, ResetOptions, Step, StepTiming, observation_layout_of,
};
pub use info::{Reason, Reasons, StepInfo, TermSums};
pub use mlp::{MlpError, MlpMetadata, MlpPolicy};
pub use policy::{Policy, PolicyInput, RandomPolicy, Stand, Trot, TrotParams};
pub use record::{RecordTerms, StepRecord};
pub use vec_env::{AutoReset, MAX_ENVS, MAX_THREADS, VecEnv, VecEnvError, VecStepOut};

/// The repository README, whose Rust quickstart runs as a doctest of this crate so that it stays
/// true (only with `cargo test --doc`; nothing of it is compiled into the library).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeQuickstart;
