//! The per-step record: one JSON object per env step (the CLI's `--record` JSONL, the Python
//! binding's logs and the comparison tools all share this schema).
//!
//! The keys, their JSON types and meanings are [`RECORD_KEYS`], declared once beside the struct;
//! the README's step record table is generated from it (`cargo xtask codegen`), and a test checks
//! it against a record as written.
//!
//! Numbers are written with full f64 precision (shortest round-trip form): reading a record
//! back gives the same bits.
//!
//! `robot` was added after the other keys: a record written before it has none, and still reads
//! back (with [`StepRecord::robot`] `None`) and writes out again to the same bytes.
//!
//! With observation noise on (`randomize.obs_noise`), `obs` is what the policy saw, noise and
//! all, and `true_obs` beside it the observation of the simulated state, which is what the
//! reward was computed from (C^t is `true_obs`' trunk position rows then); without noise the
//! two are the same and only `obs` is written, so such records are as they always were.

use std::borrow::Cow;

use hyq_physics::Backend;
use hyq_spec::{TaskConfig, TermValues};
use hyq_tasks::ReportedRegularizers;
use serde::{Deserialize, Serialize};

use crate::env::Env;
use crate::info::{Reason, Reasons, StepInfo};
use crate::randomize::RandomizeInfo;

/// One key of the step record: its name, its JSON type and what it holds. In a type or a
/// meaning, `{obs}` stands for the robot's observation length, `{joints}` for its joint count,
/// `{terms}` for the reward terms' names, `{randomize}` for the names of
/// [`RANDOMIZE_INFO_KEYS`](crate::RANDOMIZE_INFO_KEYS), `{regularizers}` for hyq-tasks'
/// `REGULARIZER_NAMES` and `{velocity}` for the velocity task's
/// [`TERM_NAMES`](crate::velocity::TERM_NAMES) (the documents write them for HyQ).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RecordKey {
    /// The key.
    pub name: &'static str,
    /// Its JSON type.
    pub kind: &'static str,
    /// What it holds.
    pub meaning: &'static str,
    /// Whether it is written only when set (`#[serde(skip_serializing_if = ...)]`), so that
    /// records of a configuration that leaves it unset stay as they were before it existed.
    pub optional: bool,
}

/// The step record's keys, in the order written: its one schema ([`StepRecord`]'s fields).
pub const RECORD_KEYS: [RecordKey; 21] = [
    RecordKey {
        name: "robot",
        kind: "string",
        meaning: "the robot's name (`hyq`, `anymal_c`, or the profile's `name`); a record \
                  written before this key was added has none, and still reads",
        optional: false,
    },
    RecordKey {
        name: "episode",
        kind: "integer",
        meaning: "episode number, 1 for the first since the env was built",
        optional: false,
    },
    RecordKey {
        name: "t",
        kind: "integer",
        meaning: "env steps since reset, 1 after the first step",
        optional: false,
    },
    RecordKey {
        name: "obs",
        kind: "{obs} numbers",
        meaning: "the observation after the step: the §3 rows, then any observation.extra rows; \
                  with observation noise on, what the policy saw (noise included)",
        optional: false,
    },
    RecordKey {
        name: "true_obs",
        kind: "{obs} numbers",
        meaning: "only with observation noise on (`randomize.obs_noise`): the observation of the \
                  simulated state, without noise, which the reward and the rules used",
        optional: true,
    },
    RecordKey {
        name: "action",
        kind: "{joints} numbers",
        meaning: "the action as given (before clipping)",
        optional: false,
    },
    RecordKey {
        name: "joint_targets",
        kind: "{joints} numbers",
        meaning: "the joint targets the actuator tracked (rad)",
        optional: false,
    },
    RecordKey {
        name: "reward",
        kind: "number",
        meaning: "the step's reward: `terms` composed, plus `regularizers`' sum when they are on; \
                  under `task.kind = \"velocity\"`, the task's (`velocity.reward`)",
        optional: false,
    },
    RecordKey {
        name: "terms",
        kind: "object",
        meaning: "every reward term by name: {terms}",
        optional: false,
    },
    RecordKey {
        name: "yaw",
        kind: "number",
        meaning: "the trunk's yaw (rad, intrinsic Z-Y-X)",
        optional: false,
    },
    RecordKey {
        name: "pitch",
        kind: "number",
        meaning: "the trunk's pitch (rad)",
        optional: false,
    },
    RecordKey {
        name: "distance_to_goal",
        kind: "number",
        meaning: "D^t (m)",
        optional: false,
    },
    RecordKey {
        name: "d_n",
        kind: "number",
        meaning: "D_n^t = D^t / K (a goal closer than 10⁻⁶ m to the start is refused)",
        optional: false,
    },
    RecordKey {
        name: "goal",
        kind: "3 numbers",
        meaning: "G (m, world)",
        optional: false,
    },
    RecordKey {
        name: "initial_position",
        kind: "3 numbers",
        meaning: "C^0 (m, world): the trunk position after reset",
        optional: false,
    },
    RecordKey {
        name: "terminated",
        kind: "boolean",
        meaning: "Gymnasium's `terminated`",
        optional: false,
    },
    RecordKey {
        name: "truncated",
        kind: "boolean",
        meaning: "Gymnasium's `truncated`",
        optional: false,
    },
    RecordKey {
        name: "reasons",
        kind: "list of strings",
        meaning: "why the episode ended: a subset of `reached`, `joint_limit`, `fell`, \
                  `timeout`, `diverged`, in that order; empty while it goes on",
        optional: false,
    },
    RecordKey {
        name: "randomize",
        kind: "object",
        meaning: "`[randomize]`'s draws for the episode and the step's push, named as the info's \
                  `randomize.` keys: {randomize}",
        optional: true,
    },
    RecordKey {
        name: "velocity",
        kind: "object",
        meaning: "under `task.kind = \"velocity\"`: the `command` the step was judged by \
                  (v_x, v_y in m/s, ω_z in rad/s), every task term unscaled (`terms`: {velocity}), \
                  the task's `reward` and `measured`, the trunk's v_x, v_y (m/s) and ω_z \
                  (rad/s) in its frame that the command is compared with",
        optional: true,
    },
    RecordKey {
        name: "regularizers",
        kind: "object",
        meaning: "`[regularizers]`' terms that are on, unscaled, by name (any of {regularizers}); \
                  the step's reward is the spec's plus Σ scale · term · Δt_env over them",
        optional: true,
    },
];

/// One env step as written to a JSONL record (see the module docs for the schema). Borrows the
/// environment's buffers when written; owns them when read back.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepRecord<'a> {
    /// The robot's name; `None` only for a record written before records named their robot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<Cow<'a, str>>,
    /// Episode number (1 for the first).
    pub episode: u64,
    /// Env steps since reset (1 for the first step).
    pub t: u64,
    /// The observation after the step (as the policy saw it: with noise when it is on).
    pub obs: Cow<'a, [f64]>,
    /// The observation without its noise, when observation noise is on (else not written).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub true_obs: Option<Cow<'a, [f64]>>,
    /// The action as given.
    pub action: Cow<'a, [f64]>,
    /// The joint targets tracked (rad).
    pub joint_targets: Cow<'a, [f64]>,
    /// The reward.
    pub reward: f64,
    /// The reward's terms, by name (hyq-spec's [`TermValues`]: every term of
    /// `hyq_spec::REWARD_TERMS`, an opt-in one only when it is on).
    pub terms: TermValues,
    /// Yaw (rad).
    pub yaw: f64,
    /// Pitch (rad).
    pub pitch: f64,
    /// D^t (m).
    pub distance_to_goal: f64,
    /// D_n^t = D^t / K.
    pub d_n: f64,
    /// G (m).
    pub goal: [f64; 3],
    /// C^0 (m).
    pub initial_position: [f64; 3],
    /// Gymnasium's `terminated`.
    pub terminated: bool,
    /// Gymnasium's `truncated`.
    pub truncated: bool,
    /// Why the episode ended (empty while it goes on).
    pub reasons: Vec<Reason>,
    /// `[randomize]`'s draws and the step's push, when it is on (else not written).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub randomize: Option<Cow<'a, RandomizeInfo>>,
    /// The velocity task's command, terms and reward, under `task.kind = "velocity"` (else not
    /// written).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocityRecord>,
    /// The regularisers that are on, unscaled, when `[regularizers]` is on (else not written).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub regularizers: Option<ReportedRegularizers>,
}

/// The velocity task's part of a step's record (the info's `velocity`, less what the rest of the
/// record already holds).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VelocityRecord {
    /// The command the step was judged by, observation order: v_x, v_y (m/s), ω_z (rad/s).
    pub command: [f64; 3],
    /// Every term of the task, unscaled (hyq-tasks' `TERM_NAMES`).
    pub terms: hyq_tasks::TermValues,
    /// The task's reward (the record's `reward` too).
    pub reward: f64,
    /// What the command was compared with: the trunk's v_x, v_y (m/s) and ω_z (rad/s) in its
    /// own frame at the end of the step (the info's `lin_vel` and `ang_vel`). Absent from
    /// records written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<[f64; 3]>,
}

impl<'a> StepRecord<'a> {
    /// The record of a step of `robot` taken under `task` from its info, observation and
    /// action (`task` says which opt-in terms are on, and so written).
    pub fn new(
        robot: &'a str,
        info: &'a StepInfo,
        obs: &'a [f64],
        action: &'a [f64],
        task: &TaskConfig,
    ) -> Self {
        let r = &info.reward;
        Self {
            robot: Some(Cow::Borrowed(robot)),
            episode: info.episode,
            t: info.t,
            obs: Cow::Borrowed(obs),
            true_obs: None,
            action: Cow::Borrowed(action),
            joint_targets: Cow::Borrowed(&info.joint_targets),
            reward: info.total_reward(),
            terms: TermValues::reported(r, task),
            yaw: info.yaw,
            pitch: info.pitch,
            distance_to_goal: info.distance_to_goal,
            d_n: info.d_n,
            goal: info.goal,
            initial_position: info.initial_position,
            terminated: info.terminated(),
            truncated: info.truncated(),
            reasons: info.reasons.iter().collect(),
            randomize: info.randomize.as_ref().map(Cow::Borrowed),
            velocity: info.velocity.map(|v| VelocityRecord {
                command: v.command,
                terms: v.terms,
                reward: v.reward,
                measured: Some(v.measured()),
            }),
            regularizers: info.regularizers.map(|r| r.terms),
        }
    }

    /// The record of `env`'s last step, taken with `action`: with observation noise on, the
    /// noisy observation and the true one beside it.
    pub fn from_env<B: Backend>(env: &'a Env<B>, action: &'a [f64]) -> Self {
        Self {
            true_obs: env
                .observation_is_noisy()
                .then(|| Cow::Borrowed(env.true_observation())),
            ..Self::new(
                env.model().name(),
                env.info(),
                env.observation(),
                action,
                &env.config().task,
            )
        }
    }

    /// The reasons as a set.
    pub fn reason_set(&self) -> Reasons {
        self.reasons.iter().copied().collect()
    }

    /// The record as one line of JSON (no trailing newline), numbers in full precision.
    pub fn to_json_line(&self) -> String {
        match serde_json::to_string(self) {
            Ok(line) => line,
            // Every field is a number, string, boolean or a list or object of those; the env
            // emits no NaN or infinity, which JSON could not hold.
            Err(e) => unreachable!("a step record serialises to JSON: {e}"),
        }
    }

    /// Reads a record from one line of JSON; unknown keys are errors.
    pub fn from_json_line(line: &str) -> Result<StepRecord<'static>, serde_json::Error> {
        serde_json::from_str(line)
    }
}
