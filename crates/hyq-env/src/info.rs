//! What a step reports besides the observation and the reward: every reward term, every
//! termination that fired (the spec's four, §6, plus the environment's own `diverged`), the
//! distances, the attitude, the goal, the start and the joint targets used.

use hyq_physics::RobotModel;
use hyq_spec::{JointLimitHit, LimitSide, RewardBreakdown, Termination, Terminations};

use crate::divergence::Divergence;
use crate::randomize::{EpisodeDraw, RandomizeInfo};
use crate::regularizers::RegularizerInfo;
use crate::velocity::VelocityInfo;
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// Why an episode ended: one of the spec's four conditions (§6.1–§6.4), or the environment's
/// own `diverged` (the physics produced a non-finite state). Serialised as its snake_case name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reason {
    /// §6.1: the trunk centre is inside the reach cube around the goal.
    Reached,
    /// §6.2: a joint is within ε_joint of a limit.
    JointLimit,
    /// §6.3: the trunk touched the ground in a sub-step of the step.
    Fell,
    /// §6.4: t ≥ t_max.
    Timeout,
    /// The physics diverged (a backend `Diverged` error or a non-finite reading): the episode
    /// cannot go on. Not a spec condition.
    Diverged,
}

impl Reason {
    /// Every reason, the spec's four in its order, then `diverged`.
    pub const ALL: [Reason; 5] = [
        Reason::Reached,
        Reason::JointLimit,
        Reason::Fell,
        Reason::Timeout,
        Reason::Diverged,
    ];

    /// The spec's condition this reason is, or `None` for `diverged`.
    pub const fn termination(self) -> Option<Termination> {
        match self {
            Reason::Reached => Some(Termination::Reached),
            Reason::JointLimit => Some(Termination::JointLimit),
            Reason::Fell => Some(Termination::Fell),
            Reason::Timeout => Some(Termination::Timeout),
            Reason::Diverged => None,
        }
    }

    /// The stable snake_case name used in JSON and logs (the spec's conditions by hyq-spec's
    /// names).
    pub const fn as_str(self) -> &'static str {
        match self.termination() {
            Some(t) => t.as_str(),
            None => "diverged",
        }
    }
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl From<Termination> for Reason {
    fn from(t: Termination) -> Self {
        match t {
            Termination::Reached => Reason::Reached,
            Termination::JointLimit => Reason::JointLimit,
            Termination::Fell => Reason::Fell,
            Termination::Timeout => Reason::Timeout,
        }
    }
}

/// The set of reasons that hold at the end of a step (any number): the spec's terminations
/// (hyq-spec's [`Terminations`]) and whether the physics diverged. Serialised as a list of names
/// in [`Reason::ALL`]'s order, e.g. `["joint_limit", "fell"]`.
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Reasons {
    spec: Terminations,
    diverged: bool,
}

impl Reasons {
    /// No reason: the episode goes on.
    pub const NONE: Reasons = Reasons {
        spec: Terminations::NONE,
        diverged: false,
    };

    /// The spec's terminations that hold.
    pub const fn from_spec(spec: Terminations) -> Self {
        Reasons {
            spec,
            diverged: false,
        }
    }

    /// The spec's terminations among the reasons.
    pub const fn spec(self) -> Terminations {
        self.spec
    }

    /// Adds a reason.
    pub fn insert(&mut self, r: Reason) {
        match r.termination() {
            Some(t) => self.spec.insert(t),
            None => self.diverged = true,
        }
    }

    /// Whether `r` holds.
    pub const fn contains(self, r: Reason) -> bool {
        match r.termination() {
            Some(t) => self.spec.contains(t),
            None => self.diverged,
        }
    }

    /// Whether no reason holds.
    pub const fn is_empty(self) -> bool {
        self.spec.is_empty() && !self.diverged
    }

    /// Gymnasium's `terminated`: reached, joint limit, fell or diverged.
    pub const fn terminated(self) -> bool {
        self.spec.terminated() || self.diverged
    }

    /// Gymnasium's `truncated`: timeout and not terminated.
    pub const fn truncated(self) -> bool {
        self.contains(Reason::Timeout) && !self.terminated()
    }

    /// Whether the episode is over.
    pub const fn done(self) -> bool {
        !self.is_empty()
    }

    /// The reasons that hold, in [`Reason::ALL`]'s order.
    pub fn iter(self) -> impl Iterator<Item = Reason> {
        Reason::ALL.into_iter().filter(move |r| self.contains(*r))
    }

    /// The names of the reasons that hold joined by `+`, in [`Reason::ALL`]'s order
    /// (`"joint_limit+fell"`; `""` while the episode goes on): the Python info's `reasons`.
    pub fn joined(self) -> String {
        self.iter()
            .map(Reason::as_str)
            .collect::<Vec<_>>()
            .join("+")
    }
}

impl FromIterator<Reason> for Reasons {
    fn from_iter<I: IntoIterator<Item = Reason>>(iter: I) -> Self {
        let mut s = Reasons::NONE;
        for r in iter {
            s.insert(r);
        }
        s
    }
}

impl fmt::Debug for Reasons {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_set().entries(self.iter()).finish()
    }
}

impl Serialize for Reasons {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.iter())
    }
}

/// Everything a step (or a reset) reports besides the observation.
///
/// Owned by the environment and updated in place every step (no allocation once the joint
/// target buffer exists); clone it to keep it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepInfo {
    /// Episodes started since the environment was built, counting this one (1 in the first).
    pub episode: u64,
    /// t, env steps taken since reset (0 after reset, 1 after the first step).
    pub t: u64,
    /// The step's reward and each of its terms (hyq-spec's breakdown; `total` is the reward).
    /// After reset, and on a diverged step, every term is 0, the multipliers 1 and the total 0.
    pub reward: RewardBreakdown,
    /// Every reason that holds at the end of the step (empty while the episode goes on).
    pub reasons: Reasons,
    /// The first joint at a limit when `joint_limit` holds.
    pub joint_at_limit: Option<JointLimitHit>,
    /// What diverged, when `diverged` holds; its text (`Display`) is the Python info's
    /// `divergence`.
    pub divergence: Option<Divergence>,
    /// D^t = ‖G − C^t‖ (m).
    pub distance_to_goal: f64,
    /// D_n^t = D^t / K (K is at least `hyq_spec::MIN_START_GOAL_DISTANCE` in every episode).
    pub d_n: f64,
    /// The trunk's roll (rad, intrinsic Z-Y-X, spec §1).
    pub roll: f64,
    /// The trunk's pitch (rad).
    pub pitch: f64,
    /// The trunk's yaw (rad).
    pub yaw: f64,
    /// G, the goal (m, world).
    pub goal: [f64; 3],
    /// C^0, the trunk position after reset (m, world).
    pub initial_position: [f64; 3],
    /// The joint targets (rad, action order) the actuator tracked during the step; after reset,
    /// the joint angles at reset.
    pub joint_targets: Vec<f64>,
    /// Whether any action value was outside the action space and clipped.
    pub action_clipped: bool,
    /// When `[randomize]` is on: the episode's drawn values and the step's push (absent
    /// otherwise, and then not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub randomize: Option<RandomizeInfo>,
    /// Under `task.kind = "velocity"`: the command, the task's terms and its reward, which is
    /// then the step's (the spec's breakdown is neutral). Absent otherwise, and then not
    /// written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocityInfo>,
    /// When `[regularizers]` is on: the terms that are on and their scaled sum, which the
    /// step's reward adds to the spec's (absent otherwise, and then not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub regularizers: Option<RegularizerInfo>,
}

impl StepInfo {
    /// The step's reward: the velocity task's under `task.kind = "velocity"`, else
    /// [`StepInfo::goal_reward`].
    pub fn total_reward(&self) -> f64 {
        self.velocity
            .map_or_else(|| self.goal_reward(), |v| v.reward)
    }

    /// The goal task's reward: the spec's `reward.total`, plus the regularisers' sum when
    /// `[regularizers]` is on (docs/spec.md §7.12; off, the spec's total itself, bit for bit).
    pub fn goal_reward(&self) -> f64 {
        self.regularizers
            .map_or(self.reward.total, |r| self.reward.total + r.reward)
    }

    /// The name of the first joint at a limit when `joint_limit` holds (`model` names the
    /// joints), else `""`.
    pub fn joint_at_limit_name(&self, model: &RobotModel) -> String {
        self.joint_at_limit
            .as_ref()
            .and_then(|hit| model.joints().get(hit.joint))
            .map_or_else(String::new, |j| j.name.clone())
    }

    /// Which limit that joint is at, `"lower"` or `"upper"`, else `""`.
    pub fn joint_at_limit_side(&self) -> &'static str {
        match self.joint_at_limit.as_ref().map(|hit| hit.side) {
            Some(LimitSide::Lower) => "lower",
            Some(LimitSide::Upper) => "upper",
            None => "",
        }
    }

    /// Gymnasium's `terminated`.
    pub fn terminated(&self) -> bool {
        self.reasons.terminated()
    }

    /// Gymnasium's `truncated`.
    pub fn truncated(&self) -> bool {
        self.reasons.truncated()
    }
}

/// How a front reads the value of an info key from a step's [`StepInfo`] (and the robot, which
/// names the joints), and so the key's one type.
#[derive(Clone, Copy)]
pub enum InfoValue {
    /// An integer (Python `int`, int64 in a vector env).
    Int(fn(&StepInfo) -> u64),
    /// A number (`float`, float64).
    Float(fn(&StepInfo) -> f64),
    /// A flag (`bool`).
    Bool(fn(&StepInfo) -> bool),
    /// Text (`str`, an object array of str); the robot names the joints.
    Text(fn(&StepInfo, &RobotModel) -> String),
    /// A vector of numbers (a float64 array (k,), (N, k) in a vector env).
    Vector(fn(&StepInfo) -> &[f64], VectorLen),
    /// Every reward term of hyq-spec's table, each a number under its own name.
    Terms,
    /// Every end reason of [`Reason::ALL`], each a flag under its own name.
    ReasonFlags,
    /// A flag the front sets itself, since it does the work (Python's observation clipping).
    FrontFlag,
    /// The name of the engine the env runs on (`Env::engine_name`), which the front reads from
    /// the env: in a vector env whose envs run on different engines, each env's own.
    Engine,
}

/// The length of a vector info value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VectorLen {
    /// A point in space.
    Three,
    /// One value per actuated joint.
    Joints,
    /// One value per body of the model ([`RobotModel::links`]).
    Links,
}

/// One key (or, for [`InfoValue::Terms`] and [`InfoValue::ReasonFlags`], one family of keys) of
/// the info a front reports on every step and reset.
#[derive(Clone, Copy)]
pub struct InfoKey {
    /// The key (for a family, what the documents call it).
    pub name: &'static str,
    /// How its value is read, and so its type.
    pub value: InfoValue,
    /// What it holds.
    pub meaning: &'static str,
}

impl InfoKey {
    /// The keys this row stands for: its name, or a family's names.
    pub fn names(&self) -> Vec<&'static str> {
        match self.value {
            InfoValue::Terms => hyq_spec::TERM_NAMES.to_vec(),
            InfoValue::ReasonFlags => Reason::ALL.iter().map(|r| r.as_str()).collect(),
            _ => vec![self.name],
        }
    }

    /// Its type as Python sees it (`"int"`, `"float"`, `"bool"`, `"str"`, `"float64 array
    /// (k,)"`), `joints` and `links` being the robot's joint and body counts.
    pub fn kind(&self, joints: usize, links: usize) -> String {
        match self.value {
            InfoValue::Int(_) => "int".into(),
            InfoValue::Float(_) | InfoValue::Terms => "float".into(),
            InfoValue::Bool(_) | InfoValue::ReasonFlags | InfoValue::FrontFlag => "bool".into(),
            InfoValue::Text(_) | InfoValue::Engine => "str".into(),
            InfoValue::Vector(_, VectorLen::Three) => "float64 array (3,)".into(),
            InfoValue::Vector(_, VectorLen::Joints) => format!("float64 array ({joints},)"),
            InfoValue::Vector(_, VectorLen::Links) => format!("float64 array ({links},)"),
        }
    }
}

/// The info's keys, in the order a front writes them: its one schema. The Python info dicts
/// (single and vector), `hyq.INFO_SCHEMA` and the README's info table are made from it, so a
/// key is added here alone.
pub const INFO_KEYS: [InfoKey; 20] = [
    InfoKey {
        name: "t",
        value: InfoValue::Int(|i| i.t),
        meaning: "env steps since reset (0 after reset)",
    },
    InfoKey {
        name: "terms",
        value: InfoValue::Terms,
        meaning: "every reward term by name (hyq-spec's `REWARD_TERMS`)",
    },
    InfoKey {
        name: "reward",
        value: InfoValue::Float(StepInfo::total_reward),
        meaning: "the step's reward, the number `step` returns",
    },
    InfoKey {
        name: "distance_to_goal",
        value: InfoValue::Float(|i| i.distance_to_goal),
        meaning: "D^t (m)",
    },
    InfoKey {
        name: "d_n",
        value: InfoValue::Float(|i| i.d_n),
        meaning: "D_n^t = D^t / K",
    },
    InfoKey {
        name: "roll",
        value: InfoValue::Float(|i| i.roll),
        meaning: "the trunk's roll (rad, intrinsic Z-Y-X)",
    },
    InfoKey {
        name: "pitch",
        value: InfoValue::Float(|i| i.pitch),
        meaning: "the trunk's pitch (rad)",
    },
    InfoKey {
        name: "yaw",
        value: InfoValue::Float(|i| i.yaw),
        meaning: "the trunk's yaw (rad)",
    },
    InfoKey {
        name: "reasons",
        value: InfoValue::Text(|i, _| i.reasons.joined()),
        meaning: "the reasons that hold, joined by `+` in the order below (`\"joint_limit+fell\"`); \
                  `\"\"` while the episode goes on",
    },
    InfoKey {
        name: "reason flags",
        value: InfoValue::ReasonFlags,
        meaning: "the same reasons as flags",
    },
    InfoKey {
        name: "goal",
        value: InfoValue::Vector(|i| &i.goal, VectorLen::Three),
        meaning: "G (m, world)",
    },
    InfoKey {
        name: "initial_position",
        value: InfoValue::Vector(|i| &i.initial_position, VectorLen::Three),
        meaning: "C^0 (m, world; C^t is the observation's trunk position)",
    },
    InfoKey {
        name: "joint_targets",
        value: InfoValue::Vector(|i| &i.joint_targets, VectorLen::Joints),
        meaning: "the joint targets the actuator tracked (rad)",
    },
    InfoKey {
        name: "action_clipped",
        value: InfoValue::Bool(|i| i.action_clipped),
        meaning: "an action value was outside the space and clipped",
    },
    InfoKey {
        name: "observation_clipped",
        value: InfoValue::FrontFlag,
        meaning: "an observation value was clipped to the table (`clip_observations=True`)",
    },
    InfoKey {
        name: "joint_at_limit",
        value: InfoValue::Text(|i, model| i.joint_at_limit_name(model)),
        meaning: "the first joint at a limit when `joint_limit` holds, else `\"\"`",
    },
    InfoKey {
        name: "joint_at_limit_angle",
        value: InfoValue::Float(|i| i.joint_at_limit.as_ref().map_or(0.0, |hit| hit.angle)),
        meaning: "its angle (rad), else 0.0",
    },
    InfoKey {
        name: "joint_at_limit_side",
        value: InfoValue::Text(|i, _| i.joint_at_limit_side().to_owned()),
        meaning: "`\"lower\"` or `\"upper\"`, else `\"\"`",
    },
    InfoKey {
        name: "divergence",
        value: InfoValue::Text(|i, _| {
            i.divergence
                .as_ref()
                .map(ToString::to_string)
                .unwrap_or_default()
        }),
        meaning: "what diverged when `diverged` holds, else `\"\"`",
    },
    InfoKey {
        name: "backend",
        value: InfoValue::Engine,
        meaning: "the engine this env runs on (`backend=`; in a vector env given a list of engines, this env's)",
    },
];

// `[randomize]`'s keys: declared here beside `INFO_KEYS`, so that the info's schema is one file
// and `randomize/` needs nothing of the info.

/// The draw of `info`'s episode. Only read for an info that has one (a front writes these keys
/// only then); the empty fallbacks keep the readers total.
fn draw(info: &StepInfo) -> Option<&EpisodeDraw> {
    info.randomize.as_ref().map(|r| &r.draw)
}

/// A per-joint or per-body factor of `info`'s draw.
fn factors(info: &StepInfo, read: fn(&EpisodeDraw) -> &[f64]) -> &[f64] {
    draw(info).map_or(&[], read)
}

/// The info keys an environment whose `[randomize]` is on adds to [`INFO_KEYS`](crate::INFO_KEYS),
/// on every step and reset, in the order a front writes them (an environment with it off has
/// none of them). The names after [`RANDOMIZE_PREFIX`](crate::randomize::RANDOMIZE_PREFIX) are the configuration keys that drew
/// each value.
pub const RANDOMIZE_INFO_KEYS: [InfoKey; 15] = [
    InfoKey {
        name: "randomize.ground_friction",
        value: InfoValue::Float(|i| draw(i).map_or(0.0, |d| d.dynamics.ground_friction)),
        meaning: "the episode's ground friction coefficient",
    },
    InfoKey {
        name: "randomize.trunk_added_mass_kg",
        value: InfoValue::Float(|i| draw(i).map_or(0.0, |d| d.dynamics.trunk_added_mass_kg)),
        meaning: "mass added to the trunk (kg)",
    },
    InfoKey {
        name: "randomize.trunk_com_offset_m",
        value: InfoValue::Vector(
            |i| draw(i).map_or(&[], |d| &d.dynamics.trunk_com_offset_m),
            VectorLen::Three,
        ),
        meaning: "offset of the trunk's centre of mass (m, trunk frame)",
    },
    InfoKey {
        name: "randomize.link_mass_scale",
        value: InfoValue::Vector(
            |i| factors(i, |d| &d.dynamics.link_mass_scale),
            VectorLen::Links,
        ),
        meaning: "factor of each body's mass and inertia (model order)",
    },
    InfoKey {
        name: "randomize.kp_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.actuator.kp), VectorLen::Joints),
        meaning: "factor of each joint's kp (action order)",
    },
    InfoKey {
        name: "randomize.kd_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.actuator.kd), VectorLen::Joints),
        meaning: "factor of each joint's kd",
    },
    InfoKey {
        name: "randomize.effort_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.actuator.effort), VectorLen::Joints),
        meaning: "factor of each joint's effort limit",
    },
    InfoKey {
        name: "randomize.joint_damping_scale",
        value: InfoValue::Vector(
            |i| factors(i, |d| &d.dynamics.joint_damping_scale),
            VectorLen::Joints,
        ),
        meaning: "factor of each joint's damping",
    },
    InfoKey {
        name: "randomize.joint_friction_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.actuator.friction), VectorLen::Joints),
        meaning: "factor of each joint's Coulomb friction",
    },
    InfoKey {
        name: "randomize.actuator_delay_substeps",
        value: InfoValue::Int(|i| draw(i).map_or(0, |d| u64::from(d.actuator_delay_substeps))),
        meaning: "the actuator's delay (physics sub-steps)",
    },
    InfoKey {
        name: "randomize.contact_stiffness_scale",
        value: InfoValue::Float(|i| {
            draw(i).map_or(1.0, |d| d.dynamics.contact.contact_stiffness_scale)
        }),
        meaning: "factor of the engine's own ground-contact stiffness",
    },
    InfoKey {
        name: "randomize.contact_damping_scale",
        value: InfoValue::Float(|i| {
            draw(i).map_or(1.0, |d| d.dynamics.contact.contact_damping_scale)
        }),
        meaning: "factor of the engine's own ground-contact damping",
    },
    InfoKey {
        name: "randomize.restitution",
        value: InfoValue::Float(|i| draw(i).map_or(0.0, |d| d.dynamics.contact.restitution)),
        meaning: "the ground contact's restitution coefficient",
    },
    InfoKey {
        name: "randomize.push_velocity_mps",
        value: InfoValue::Vector(
            |i| i.randomize.as_ref().map_or(&[], |r| &r.push_velocity_mps),
            VectorLen::Three,
        ),
        meaning: "the velocity the step's push added to the trunk (m/s, world; zeros when none)",
    },
    InfoKey {
        name: "randomize.pushes",
        value: InfoValue::Int(|i| i.randomize.as_ref().map_or(0, |r| r.pushes)),
        meaning: "pushes so far this episode",
    },
];

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::randomize::RANDOMIZE_PREFIX;

    #[test]
    fn reasons_are_the_spec_terminations_plus_diverged() {
        for flags in 0u8..32 {
            let holds = |i: u8| flags & (1 << i) != 0;
            let reasons: Reasons = Reason::ALL
                .into_iter()
                .enumerate()
                .filter(|(i, _)| holds(*i as u8))
                .map(|(_, r)| r)
                .collect();
            let spec = Terminations::from_flags(holds(0), holds(1), holds(2), holds(3));
            assert_eq!(reasons.spec(), spec);
            assert_eq!(reasons.contains(Reason::Diverged), holds(4));
            assert_eq!(reasons.terminated(), spec.terminated() || holds(4));
            assert_eq!(reasons.truncated(), holds(3) && !reasons.terminated());
            assert_eq!(reasons.done(), flags != 0);
            assert_eq!(reasons.iter().count(), flags.count_ones() as usize);
            let json = serde_json::to_string(&reasons).unwrap_or_else(|e| panic!("{e}"));
            let names: Vec<&str> = reasons.iter().map(Reason::as_str).collect();
            assert_eq!(json, serde_json::to_string(&names).unwrap_or_default());
        }
        let names: Vec<&str> = Reason::ALL.iter().map(|r| r.as_str()).collect();
        assert_eq!(
            names,
            ["reached", "joint_limit", "fell", "timeout", "diverged"]
        );
    }

    /// The serialised names are the key list's without its prefix, in its order, so the record
    /// and the Python info cannot name a value differently (the record's test checks each key
    /// reads what the record holds).
    #[test]
    fn serialised_names_follow_the_key_list() {
        let model = hyq_physics::bundled::hyq();
        let randomize = RandomizeInfo::at_reset(&EpisodeDraw::nominal(
            &model,
            &hyq_physics::PhysicsParams::default(),
        ));
        let json = serde_json::to_value(&randomize).unwrap();
        // serde_json's map is sorted by key, so the order is the record test's to check.
        let serialised: Vec<&str> = json
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut names: Vec<&str> = RANDOMIZE_INFO_KEYS
            .iter()
            .map(|k| k.name.strip_prefix(RANDOMIZE_PREFIX).unwrap())
            .collect();
        names.sort_unstable();
        assert_eq!(serialised, names);
        let back: RandomizeInfo = serde_json::from_value(json).unwrap();
        assert_eq!(back, randomize);
    }
}
