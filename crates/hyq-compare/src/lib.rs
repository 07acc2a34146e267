//! Cross-backend comparison runs: the same action sequence on two physics backends, how far
//! their results drift apart over time, how they differ one physics sub-step after a shared
//! state, and which of those differences are known (the ledger) and which are not.
//!
//! A comparison ([`compare`]) of backends A and B in a [`Scenario`]:
//!
//! 1. builds the scenario's configuration and its open-loop action script once, and feeds the
//!    identical script to an environment on each backend (same seed, same robot model);
//! 2. records each run and measures ([`metrics`]): termination reasons and steps, the trunk
//!    position and orientation divergence and the joint-angle divergence over time (RMS and
//!    max), contact-flag agreement per tracked body, reward-term sums, and the standing height
//!    of each backend (2 s holding the standing pose);
//! 3. the one-step comparison, as Brax tests its backends: states sampled evenly from A's run
//!    are set on both backends, the same joint torques applied, one physics sub-step taken, and
//!    q, q̇ and the trunk state compared;
//! 4. checks every [`Metric`] against the [`Ledger`]: known divergences between two engines,
//!    each with its reason and tolerance; anything outside is flagged.
//!
//! The [`Report`] is written as `report.md`, `report.json` and a PNG plot of trunk x and z over
//! time for both backends ([`Report::write`]). `hyq compare` (hyq-cli) is the command-line
//! front; `docs/backend-comparison.md` has the figures for rapier vs DART.
//!
//! A trained policy is compared closed loop instead ([`policy`]): each engine's own
//! observations drive it, so the runs part by nature; that report states the sim-to-sim gap
//! (per-engine episode outcomes, per-pair divergence, and the first engine's actions replayed
//! open loop on every engine), with each engine's gait diagnostics ([`gait`]: foot slip,
//! actions at their bounds, action changes, stance duration, and per pair the agreement of the
//! foot-contact patterns), and is not judged against the ledger. Under the velocity-command
//! task ([`velocity`]) it also gives each engine's tracking errors and, for commanded stands,
//! the feet's speed and the trunk's drift.
//!
//! The library is generic over `hyq_physics::Backend` and names no engine. Its tests compare
//! rapier with itself (exact agreement) and with a perturbed rapier (gravity 10 % stronger:
//! flagged); with the cargo feature `dart` they also run the real rapier-vs-DART comparison of
//! every scenario against the shipped ledger.

mod compare;
mod error;
mod estimates;
pub mod gait;
pub mod ledger;
pub mod metrics;
mod multi;
mod plot;
pub mod policy;
mod randomized;
mod report;
pub mod run;
mod scenario;
pub mod velocity;

pub use compare::{ComparisonSpec, DEFAULT_ONE_STEP_STATES, Plan, Side, compare, parse_override};
pub use error::CompareError;
pub use estimates::{PairRatios, Rates, Stats, rate_text, ratio_text};
/// The estimate shapes the reports' rates and ratios are given in (from hyq-stats).
pub use hyq_stats::{Rate, Ratio};
pub use ledger::{Known, Ledger, Metric, ScenarioScope, ToleranceSource};
pub use multi::{MultiReport, PairSummary, compare_all, plot_many};
pub use plot::PLOT_SIZE;
pub use policy::{PolicyPlan, PolicyReport, PolicySpec, plot_policy};
pub use randomized::RandomizedSide;
pub use report::{
    Check, JSON_FILE, MARKDOWN_FILE, OneStepReport, PLOT_FILE, Report, SERIES_POINTS, Series,
    SideReport, plot_trunk_x_z, prepare_output_dir,
};
pub use scenario::{
    LIMIT_ACTION, MAX_SECONDS, REACH_ACCEPTED_ERROR_M, REACH_AHEAD_M, REACH_BONUS, REACH_LATERAL_M,
    Scenario, check_seconds, reach_goal,
};
