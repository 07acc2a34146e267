//! The HyQ walk-to-goal spec's rules as pure functions and types: what the environment observes,
//! how it rewards and penalises a step, and when an episode ends.
//!
//! This crate does no I/O and knows no simulator. The environment steps the physics, then hands
//! the rules a small typed snapshot ([`StepSnapshot`]); the rules return every reward term and
//! every termination that holds ([`StepOutcome`]). Nothing here assumes HyQ's twelve joints or
//! four feet: a robot enters only through its description ([`RobotDescription`], slices of
//! joint angles and ranges), so other robots reuse the same rules.
//!
//! The rules are the repository's `docs/spec.md`, which these docs include as [`spec_page`]: the
//! original spec's sections §1–§6 as the project implements them, with each ruling on a place
//! where the original is ambiguous or contradicts itself, its reason and the test that shows it.
//!
//! # Modules and spec sections
//!
//! | module | spec | contents |
//! |---|---|---|
//! | [`nomenclature`] | §1, Table 2 | HyQ's legs, joint kinds, joints in spec order |
//! | [`attitude`] | §1, Figure 2 | roll, pitch, yaw from a quaternion (intrinsic Z-Y-X) |
//! | [`distance`] | §1 Table 1, §4.2 | D^t, K, D_n^t |
//! | [`config`] | §2 | [`TaskConfig`]: the user variables, validated |
//! | [`observation`] | §3 | [`ObservationLayout`], [`Observation`] |
//! | [`table`] | §3 | [`SPEC_TABLE`]: the spec's observation table verbatim |
//! | [`robot`] | (§3, §6.2) | [`RobotDescription`]: joints, feet, trunk bounds |
//! | [`reward`] | §4, eqs. (1)–(5) | r_b, r_n, r_e (continuous R_e), r_reach |
//! | [`penalty`] | §5 | m_yaw, m_pitch, opt-in m_height, fixed penalties |
//! | [`termination`] | §6 | reached, joint limit, fell, timeout; [`Terminations`] |
//! | [`terms`] | §4 eq. (1), §5 | [`REWARD_TERMS`]: every reward term, its kind and section |
//! | [`step`] | §4–§6 composed | [`EpisodeRules::evaluate_step`] |
//! | [`printed`] | eqs. (2), (4), §6.2 | the printed forms the rulings replace (tests only) |
//! | [`spec_page`] | all | the rules as implemented, every ruling, why, and its test |
//!
//! # Example
//!
//! ```
//! use hyq_spec::nalgebra::{Point3, UnitQuaternion};
//! use hyq_spec::{EpisodeRules, RobotDescription, StepSnapshot, TaskConfig, Termination};
//!
//! // HyQ as the spec's §3 table describes it, the §2 defaults, and a goal 5 m ahead.
//! let robot = RobotDescription::hyq_spec();
//! let config = TaskConfig { norm_rew_scaling: Some(10.0), ..TaskConfig::default() };
//! let start = Point3::new(0.0, 0.0, 0.62);
//! let rules = EpisodeRules::new(&config, start, Point3::new(5.0, 0.0, 0.62))?;
//!
//! // One env step that moved the trunk 1 m straight towards the goal, level, joints mid-range.
//! let angles: Vec<f64> = robot.joint_ranges().iter().map(|r| 0.5 * (r.lower() + r.upper())).collect();
//! let outcome = rules.evaluate_step(&StepSnapshot {
//!     step: 1,
//!     previous_position: start,
//!     position: Point3::new(1.0, 0.0, 0.62),
//!     orientation: UnitQuaternion::identity(),
//!     joint_angles: &angles,
//!     joint_ranges: robot.joint_ranges(),
//!     trunk_contact: false,
//! })?;
//!
//! assert_eq!(outcome.reward.r_n, 2.0); // k_norm · (5 − 4) / 5
//! assert!(outcome.reward.r_e > 0.0); // R_e(0.8) − R_e(1)
//! assert_eq!(outcome.reward.total, outcome.reward.compose());
//! assert!(outcome.terminations.is_empty() && !outcome.terminated() && !outcome.truncated());
//! assert!(!outcome.terminations.contains(Termination::Reached));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod attitude;
pub mod config;
pub mod distance;
pub mod nomenclature;
pub mod observation;
pub mod penalty;
pub mod printed;
pub mod reward;
pub mod robot;
pub mod step;
pub mod table;
pub mod termination;
pub mod terms;

/// The spec as the project implements it (`docs/spec.md`), included here so that it reads beside
/// the code it describes.
#[doc = include_str!("../../../docs/spec.md")]
pub mod spec_page {}

/// The linear-algebra crate of this API's positions and orientations, re-exported so that
/// callers use the same version.
pub use nalgebra;

pub use attitude::{RollPitchYaw, roll_pitch_yaw};
pub use config::{ConfigError, EXP_REW_SCALING_MAX, HeightPenalty, REWARD_SCALE_MAX, TaskConfig};
pub use observation::{
    Clipping, Observation, ObservationError, ObservationLayout, ObservationRow, RowGroup,
    SPEC_TABLE,
};
pub use robot::{JointDescription, RobotDescription, RobotError, TrunkDescription};
pub use step::{EpisodeError, EpisodeRules, RewardBreakdown, StepError, StepOutcome, StepSnapshot};
pub use termination::joint_limit::{JointLimitHit, JointRange, LimitSide};
pub use termination::{Termination, Terminations};
pub use terms::{
    NUM_REWARD_TERMS, REWARD_TERMS, RewardTerm, TERM_NAMES, TermKind, TermSums, TermValues,
};
