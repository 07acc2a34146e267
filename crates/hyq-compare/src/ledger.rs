//! The ledger of known divergences: the tolerance of every checked metric, and the known
//! divergences between two engines that widen it, each with its reason.
//!
//! Known divergences are measured on one robot and hold for it alone: every entry names its
//! robot (the profile's `name`). A metric's tolerance for a comparison of engines {E1, E2} on
//! robot R in scenario S is, in this order: the `[[known]]` entry for R, {E1, E2} (either
//! order), S and that metric; else the entry for R, {E1, E2}, scenario `"all"` and that
//! metric; else `[default]`'s value. An entry holds on one ground: its `terrain`, a
//! `terrain.kind` (`"flat"` when not given, the ground of every entry measured before terrain
//! existed), so a comparison on rough ground is judged by the entries measured there. `[default]` says how
//! closely two backends simulating the same model must agree when nothing is known: two runs of
//! the same engine with the same inputs agree exactly, so it is the strict claim a new engine
//! pair has to earn entries against. A metric passes when its value ≤ its tolerance (a NaN never
//! passes); anything else is flagged as a divergence outside the ledger.
//!
//! ```toml
//! [default]
//! trunk_position_max_m = 0.001        # every metric of `Metric::ALL`, exactly once
//! # ...
//!
//! [[known]]
//! robot = "hyq"
//! backends = ["rapier", "dart"]
//! scenario = "trot"                    # a scenario name, or "all"
//! metric = "trunk_position_max_m"
//! tolerance = 0.1
//! reason = "why the engines differ here, with the measured value"
//! # terrain = "rough"                 # the ground it was measured on (default "flat")
//! ```

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;
use std::str::FromStr;

use hyq_env::TerrainKind;
use hyq_physics::input;
use serde::{Deserialize, Serialize};

use crate::error::CompareError;
use crate::scenario::Scenario;

/// The ledger shipped with the crate (`crates/hyq-compare/ledger.toml`).
pub const BUILT_IN: &str = include_str!("../ledger.toml");

/// A checked metric. Every value is a non-negative number where smaller means closer
/// agreement; see the crate docs for definitions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Metric {
    /// 1 if the two runs ended for different reasons, else 0.
    TerminationReasonMismatch,
    /// |end step A − end step B| (env steps).
    TerminationStepDiff,
    /// RMS over time of the trunk position distance (m).
    TrunkPositionRms,
    /// Max over time of the trunk position distance (m).
    TrunkPositionMax,
    /// RMS over time of the trunk orientation angle (rad).
    TrunkOrientationRms,
    /// Max over time of the trunk orientation angle (rad).
    TrunkOrientationMax,
    /// RMS over time of the worst joint's angle difference (rad).
    JointAngleRms,
    /// Max over time of the worst joint's angle difference (rad).
    JointAngleMax,
    /// 100 − the worst tracked body's contact-flag agreement (%).
    ContactDisagreementMax,
    /// |return A − return B|.
    ReturnDiff,
    /// |standing height A − standing height B| (m).
    StandingHeightDiff,
    /// One-step: max over states of ‖q_A − q_B‖∞ (rad).
    OneStepQ,
    /// One-step: max over states of ‖q̇_A − q̇_B‖∞ (rad/s).
    OneStepQd,
    /// One-step: max over states of the trunk position distance (m).
    OneStepTrunkPosition,
    /// One-step: max over states of the trunk orientation angle (rad).
    OneStepTrunkOrientation,
    /// One-step: max over states of the trunk linear velocity distance (m/s).
    OneStepTrunkLinvel,
    /// One-step: max over states of the trunk angular velocity distance (rad/s).
    OneStepTrunkAngvel,
}

impl Metric {
    /// Every metric, in report order.
    pub const ALL: [Metric; 17] = [
        Metric::TerminationReasonMismatch,
        Metric::TerminationStepDiff,
        Metric::TrunkPositionRms,
        Metric::TrunkPositionMax,
        Metric::TrunkOrientationRms,
        Metric::TrunkOrientationMax,
        Metric::JointAngleRms,
        Metric::JointAngleMax,
        Metric::ContactDisagreementMax,
        Metric::ReturnDiff,
        Metric::StandingHeightDiff,
        Metric::OneStepQ,
        Metric::OneStepQd,
        Metric::OneStepTrunkPosition,
        Metric::OneStepTrunkOrientation,
        Metric::OneStepTrunkLinvel,
        Metric::OneStepTrunkAngvel,
    ];

    /// The metric's name in the ledger and the reports (its unit is the suffix).
    pub const fn name(self) -> &'static str {
        match self {
            Metric::TerminationReasonMismatch => "termination_reason_mismatch",
            Metric::TerminationStepDiff => "termination_step_diff",
            Metric::TrunkPositionRms => "trunk_position_rms_m",
            Metric::TrunkPositionMax => "trunk_position_max_m",
            Metric::TrunkOrientationRms => "trunk_orientation_rms_rad",
            Metric::TrunkOrientationMax => "trunk_orientation_max_rad",
            Metric::JointAngleRms => "joint_angle_rms_rad",
            Metric::JointAngleMax => "joint_angle_max_rad",
            Metric::ContactDisagreementMax => "contact_disagreement_max_pct",
            Metric::ReturnDiff => "return_diff",
            Metric::StandingHeightDiff => "standing_height_diff_m",
            Metric::OneStepQ => "one_step_q_max_rad",
            Metric::OneStepQd => "one_step_qd_max_rad_s",
            Metric::OneStepTrunkPosition => "one_step_trunk_position_max_m",
            Metric::OneStepTrunkOrientation => "one_step_trunk_orientation_max_rad",
            Metric::OneStepTrunkLinvel => "one_step_trunk_linvel_max_m_s",
            Metric::OneStepTrunkAngvel => "one_step_trunk_angvel_max_rad_s",
        }
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Metric {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Metric::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("unknown metric {s:?}"))
    }
}

impl Serialize for Metric {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// Which scenarios a known divergence covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScenarioScope {
    /// Every scenario (written `"all"`).
    All,
    /// One scenario.
    One(Scenario),
}

/// A known divergence between two engines: a metric's widened tolerance and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Known {
    /// The robot it was measured on (its profile's `name`).
    pub robot: String,
    /// The two engines (`Backend::NAME`), in either order.
    pub backends: [String; 2],
    /// The scenarios it covers.
    pub scenario: ScenarioScope,
    /// The metric.
    pub metric: Metric,
    /// The ground it was measured on: a `terrain.kind` (`"flat"` by default).
    pub terrain: String,
    /// The widened tolerance.
    pub tolerance: f64,
    /// Why the engines differ here (one reason).
    pub reason: String,
}

impl Known {
    fn covers(&self, robot: &str, engines: [&str; 2], scenario: Scenario, terrain: &str) -> bool {
        let pair = self.robot == robot
            && self.terrain == terrain
            && ((self.backends[0] == engines[0] && self.backends[1] == engines[1])
                || (self.backends[0] == engines[1] && self.backends[1] == engines[0]));
        pair && match self.scenario {
            ScenarioScope::All => true,
            ScenarioScope::One(s) => s == scenario,
        }
    }
}

/// Where a tolerance came from.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "source", rename_all = "snake_case")]
pub enum ToleranceSource {
    /// `[default]`: no known divergence applies.
    Default,
    /// A `[[known]]` entry.
    Known {
        /// Its reason.
        reason: String,
        /// `"all"` or the scenario's name.
        scenario: String,
    },
}

/// The ledger: default tolerances and known divergences (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Ledger {
    /// Where it came from (a path, or "built-in").
    pub origin: String,
    /// The default tolerance of every metric.
    pub default: BTreeMap<Metric, f64>,
    /// The known divergences.
    pub known: Vec<Known>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLedger {
    default: BTreeMap<String, f64>,
    #[serde(default)]
    known: Vec<RawKnown>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawKnown {
    robot: String,
    backends: [String; 2],
    scenario: String,
    metric: String,
    #[serde(default = "flat")]
    terrain: String,
    tolerance: f64,
    reason: String,
}

/// The ground of an entry that names none.
fn flat() -> String {
    "flat".to_owned()
}

/// The grounds an entry may name: `terrain.kind`'s values, from the configuration's own list.
fn terrains() -> impl Iterator<Item = &'static str> {
    TerrainKind::ALL.into_iter().map(TerrainKind::as_str)
}

/// The TOML parser's own words and the line, without the excerpt of the file it draws (which
/// holds whatever the file holds), control characters escaped.
fn parser_message(text: &str, e: &toml::de::Error) -> String {
    let line = e
        .span()
        .and_then(|s| text.get(..s.start))
        .map(|before| format!("line {}: ", 1 + before.matches('\n').count()));
    format!(
        "{}{}",
        line.unwrap_or_default(),
        hyq_physics::printable(e.message())
    )
}

fn check_tolerance(value: f64) -> Result<(), String> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(format!(
            "tolerance {} must be finite and ≥ 0",
            hyq_physics::bounds::short(value)
        ))
    }
}

impl Ledger {
    /// The ledger shipped with the crate.
    pub fn built_in() -> Result<Self, CompareError> {
        Self::parse(BUILT_IN, "built-in")
    }

    /// Reads a ledger file of at most hyq-physics' [`input::LEDGER`] cap.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, CompareError> {
        let path = path.as_ref();
        let text =
            input::read_text(path, &input::LEDGER).map_err(|e| CompareError::LedgerRead {
                path: path.to_owned(),
                message: e.to_string(),
            })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and checks a ledger: `[default]` names every metric once with a finite,
    /// non-negative tolerance; every `[[known]]` entry names two engines, a known scenario or
    /// `"all"`, a known metric, a finite non-negative tolerance and a non-empty reason, and no
    /// two entries cover the same engines, scenario and metric. Errors name the entry and key.
    pub fn parse(text: &str, origin: &str) -> Result<Self, CompareError> {
        let bad = |message: String| CompareError::Ledger {
            origin: origin.to_owned(),
            message,
        };
        let raw: RawLedger = toml::from_str(text).map_err(|e| bad(parser_message(text, &e)))?;
        let mut default = BTreeMap::new();
        for (name, value) in &raw.default {
            let metric: Metric = name.parse().map_err(|e| bad(format!("[default]: {e}")))?;
            check_tolerance(*value).map_err(|e| bad(format!("[default] {name:?}: {e}")))?;
            default.insert(metric, *value);
        }
        if let Some(missing) = Metric::ALL.iter().find(|m| !default.contains_key(m)) {
            return Err(bad(format!("[default] has no tolerance for {missing}")));
        }
        let mut known: Vec<Known> = Vec::with_capacity(raw.known.len());
        for (i, k) in raw.known.into_iter().enumerate() {
            // Quoted with escapes: the names are the file's, whatever they hold.
            let at = format!(
                "[[known]] entry {} ({:?} {:?} {:?} {:?})",
                i + 1,
                k.robot,
                k.backends.join(","),
                k.scenario,
                k.metric
            );
            let metric: Metric = k.metric.parse().map_err(|e| bad(format!("{at}: {e}")))?;
            let scenario = if k.scenario == "all" {
                ScenarioScope::All
            } else {
                ScenarioScope::One(k.scenario.parse().map_err(|e| bad(format!("{at}: {e}")))?)
            };
            check_tolerance(k.tolerance).map_err(|e| bad(format!("{at}: {e}")))?;
            if k.reason.trim().is_empty() {
                return Err(bad(format!("{at}: the reason is empty")));
            }
            if k.robot.trim().is_empty() {
                return Err(bad(format!("{at}: the robot name is empty")));
            }
            if k.backends.iter().any(|b| b.trim().is_empty()) {
                return Err(bad(format!("{at}: a backend name is empty")));
            }
            if !terrains().any(|t| t == k.terrain) {
                return Err(bad(format!(
                    "{at}: unknown terrain {:?} (one of {})",
                    k.terrain,
                    terrains().collect::<Vec<_>>().join(", ")
                )));
            }
            let entry = Known {
                robot: k.robot,
                backends: k.backends,
                scenario,
                metric,
                terrain: k.terrain,
                tolerance: k.tolerance,
                reason: k.reason.split_whitespace().collect::<Vec<_>>().join(" "),
            };
            let pair = |b: &[String; 2]| {
                let mut p = b.clone();
                p.sort();
                p
            };
            if known.iter().any(|o| {
                o.metric == entry.metric
                    && o.robot == entry.robot
                    && o.terrain == entry.terrain
                    && o.scenario == entry.scenario
                    && pair(&o.backends) == pair(&entry.backends)
            }) {
                return Err(bad(format!("{at}: duplicates an earlier entry")));
            }
            known.push(entry);
        }
        Ok(Self {
            origin: origin.to_owned(),
            default,
            known,
        })
    }

    /// The tolerance of `metric` for engines `engines` on `robot` in `scenario` on flat
    /// ground, and where it came from.
    pub fn tolerance(
        &self,
        robot: &str,
        engines: [&str; 2],
        scenario: Scenario,
        metric: Metric,
    ) -> (f64, ToleranceSource) {
        self.tolerance_on(robot, engines, scenario, "flat", metric)
    }

    /// The tolerance of `metric` for engines `engines` on `robot` in `scenario` on the ground
    /// `terrain` (a `terrain.kind`), and where it came from.
    pub fn tolerance_on(
        &self,
        robot: &str,
        engines: [&str; 2],
        scenario: Scenario,
        terrain: &str,
        metric: Metric,
    ) -> (f64, ToleranceSource) {
        let find = |want: ScenarioScope| {
            self.known.iter().find(|k| {
                k.metric == metric
                    && k.scenario == want
                    && k.covers(robot, engines, scenario, terrain)
            })
        };
        match find(ScenarioScope::One(scenario)).or_else(|| find(ScenarioScope::All)) {
            Some(k) => (
                k.tolerance,
                ToleranceSource::Known {
                    reason: k.reason.clone(),
                    scenario: match k.scenario {
                        ScenarioScope::All => "all".into(),
                        ScenarioScope::One(s) => s.name().into(),
                    },
                },
            ),
            // `parse` guarantees a default for every metric; 0 is the strictest stand-in.
            None => (
                self.default.get(&metric).copied().unwrap_or(0.0),
                ToleranceSource::Default,
            ),
        }
    }
}
