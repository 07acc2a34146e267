//! The environment's per-step records (one JSON object per line, "JSONL") and the per-episode
//! series the plots draw.
//!
//! The schema is `hyq-env`'s record (its `record` module); this crate reads the keys it plots
//! and ignores the others, so it needs no environment. The keys read: `t` (env steps since
//! reset, 1 for the first step), `reward` (the step's total reward),
//! `terms` (every reward term of `hyq_spec::REWARD_TERMS` by name, an opt-in one such as
//! `m_height` optional: the spec's per-term breakdown, penalties as the positive amounts
//! subtracted), `d_n` (D_n^t; `null` is read as unknown, as older records held it) and
//! `distance_to_goal` (D^t, m), `episode` (the episode's number; optional here) and
//! `regularizers` (the gait regularisers that were on, unscaled; optional) and `velocity` (the
//! velocity task's command, terms and reward; optional). Other keys
//! (`obs`, `action`, `goal`, …) are ignored, so the environment can log more without breaking
//! the plots.
//!
//! A file may hold several episodes: a record starts a new episode when its `episode` differs
//! from the previous record's, or, when neither has one, when its `t` is not after the previous
//! record's (the environment was reset).
//!
//! [`PlotRecord`] is a read view of `hyq_env::StepRecord`, not a copy of it: the environment's
//! type refuses unknown keys and requires every key (`obs`, `action`, `episode`, …), which is
//! right for its round-trip contract but would make the plots break whenever the log gains a
//! key, and refuse logs written by other tools with only the plotted keys. Reading that type
//! would also make this crate depend on the environment (and its random-number and thread-pool
//! dependencies) for six keys.

use std::io::BufRead;
use std::path::Path;

use hyq_physics::input::{self, Line};
use hyq_spec::{NUM_REWARD_TERMS, REWARD_TERMS, TermValues, terms::term_index};
use hyq_tasks::ReportedRegularizers;
use hyq_tasks::TermValues as TaskTerms;
use serde::{Deserialize, Serialize};

use crate::error::PlotError;

/// One line of the environment's JSONL log, as the plots read it (the keys they draw).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlotRecord {
    /// Env steps since reset, counting this one (1 for the first step).
    pub t: u64,
    /// The episode's number, if the log carries it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub episode: Option<u64>,
    /// The step's total reward.
    pub reward: f64,
    /// The step's reward terms by name (hyq-spec's [`TermValues`], read leniently: keys that
    /// name no term are ignored; an absent opt-in term such as `m_height` reads as its neutral
    /// value, 1).
    #[serde(deserialize_with = "TermValues::deserialize_lenient")]
    pub terms: TermValues,
    /// D_n^t, the distance to the goal over the start's (`None` for a `null`, which older
    /// records held when K was too small; records written now always hold a number).
    pub d_n: Option<f64>,
    /// D^t, the distance from the trunk to the goal (m).
    pub distance_to_goal: f64,
    /// The gait regularisers that were on, unscaled (`[regularizers]`; absent when off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub regularizers: Option<ReportedRegularizers>,
    /// The velocity task's part (`task.kind = "velocity"`; absent under the spec's task).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocityPlotRecord>,
}

/// The velocity task's part of a record (hyq-env's `VelocityRecord`), as the plots read it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VelocityPlotRecord {
    /// The command the step was judged by: v_x, v_y (m/s), ω_z (rad/s).
    pub command: [f64; 3],
    /// Every term of the task, unscaled (hyq-tasks' `TERM_NAMES`).
    pub terms: TaskTerms,
    /// The task's reward (the record's `reward` too).
    pub reward: f64,
    /// The trunk's v_x, v_y (m/s) and ω_z (rad/s) in its frame, what the command was compared
    /// with (absent from records written before it was recorded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<[f64; 3]>,
}

/// The names of the columns of the trunk's measured velocity beside the command
/// ([`EpisodeSeries::velocity_measured`]).
pub const VELOCITY_MEASURED_COLUMNS: [&str; 3] = [
    "measured_lin_vel_x",
    "measured_lin_vel_y",
    "measured_ang_vel_yaw",
];

/// The names of the velocity task's columns before its terms ([`EpisodeSeries::velocity`]).
pub const VELOCITY_COMMAND_COLUMNS: [&str; 3] = [
    "command_lin_vel_x",
    "command_lin_vel_y",
    "command_ang_vel_yaw",
];

/// The longest line of a JSONL record file read (bytes): 1 MiB, several hundred times a step
/// record, so that a wrong file (`/dev/zero`, a binary) is refused at once (hyq-physics'
/// [`input::RECORDS`], the cap of every user file's reader).
pub const MAX_RECORD_LINE_BYTES: usize = input::RECORDS.max_line_bytes as usize;

/// The records of a JSONL file, and the number of its last line if that line was left out
/// because it is torn (see [`parse_jsonl`]).
#[derive(Clone, Debug, PartialEq)]
pub struct JsonlRecords {
    /// Every whole record, in order.
    pub records: Vec<PlotRecord>,
    /// The 1-based number of a torn last line that was left out, if there was one.
    pub torn_last_line: Option<usize>,
}

/// Parses JSONL step records, skipping blank lines; `origin` names the input in errors.
///
/// A last line that ends without a newline and stops in the middle of a record (what a run cut
/// short by a full disk or a kill leaves) is left out and reported in
/// [`JsonlRecords::torn_last_line`], so the whole lines before it can still be read. Any other
/// bad line is an error naming it, and so is a line longer than [`MAX_RECORD_LINE_BYTES`]
/// (which is not read further).
pub fn parse_jsonl(mut reader: impl BufRead, origin: &str) -> Result<JsonlRecords, PlotError> {
    let mut records = Vec::new();
    let mut line = Vec::new();
    let mut total = 0;
    for number in 1.. {
        let read = input::read_line(&mut reader, &input::RECORDS, &mut line, &mut total).map_err(
            |source| PlotError::Read {
                path: origin.into(),
                source,
            },
        )?;
        let ended = match read {
            Line::End => break,
            Line::Read { ended } => ended,
            Line::TooLong => {
                return Err(PlotError::LineTooLong {
                    origin: origin.to_owned(),
                    line: number,
                    limit: MAX_RECORD_LINE_BYTES,
                });
            }
            Line::TooMuch => {
                return Err(PlotError::Read {
                    path: origin.into(),
                    source: std::io::Error::new(
                        std::io::ErrorKind::FileTooLarge,
                        format!(
                            "larger than {} at line {number}, more than any record plotted",
                            input::size_text(input::RECORDS.max_bytes)
                        ),
                    ),
                });
            }
        };
        let text = String::from_utf8_lossy(&line);
        if text.trim().is_empty() {
            continue;
        }
        match serde_json::from_str(&text) {
            Ok(record) => records.push(record),
            // The input ends inside this record: a torn last line.
            Err(e) if !ended && e.is_eof() => {
                return Ok(JsonlRecords {
                    records,
                    torn_last_line: Some(number),
                });
            }
            Err(source) => {
                return Err(PlotError::Json {
                    origin: origin.to_owned(),
                    line: number,
                    source,
                });
            }
        }
    }
    Ok(JsonlRecords {
        records,
        torn_last_line: None,
    })
}

/// Reads a JSONL file of step records (see [`parse_jsonl`]).
pub fn read_jsonl(path: impl AsRef<Path>) -> Result<JsonlRecords, PlotError> {
    let path = path.as_ref();
    // The one rule of every loader: only a regular file is opened (a FIFO would block).
    let file = input::open(path).map_err(|source| PlotError::Read {
        path: path.to_owned(),
        source,
    })?;
    parse_jsonl(std::io::BufReader::new(file), &path.display().to_string())
}

/// Splits records into episodes (see the module documentation for the rule).
pub fn split_episodes(records: &[PlotRecord]) -> Vec<&[PlotRecord]> {
    let mut episodes = Vec::new();
    let mut start = 0;
    for i in 1..records.len() {
        let (prev, cur) = (&records[i - 1], &records[i]);
        let new_episode = match (prev.episode, cur.episode) {
            (Some(a), Some(b)) => a != b,
            _ => cur.t <= prev.t,
        };
        if new_episode {
            episodes.push(&records[start..i]);
            start = i;
        }
    }
    if start < records.len() {
        episodes.push(&records[start..]);
    }
    episodes
}

/// One episode as columns, one value per step: what the plots draw.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EpisodeSeries {
    /// t, env steps since reset (1 for the first step), as numbers for the plots' x axis.
    pub t: Vec<f64>,
    /// Total reward per step.
    pub reward: Vec<f64>,
    /// Each reward term per step, one column per row of `hyq_spec::REWARD_TERMS` (penalties as
    /// the positive amounts subtracted); see [`EpisodeSeries::term`].
    pub terms: [Vec<f64>; NUM_REWARD_TERMS],
    /// D_n per step (`None` where unavailable).
    pub d_n: Vec<Option<f64>>,
    /// D per step (m).
    pub distance_to_goal: Vec<f64>,
    /// Each gait regulariser the records hold (`[regularizers]`, the terms that were on),
    /// unscaled, one value per step, in hyq-tasks' order; empty when they were off.
    pub regularizers: Vec<(&'static str, Vec<f64>)>,
    /// The velocity task's columns when the records hold it: the command
    /// ([`VELOCITY_COMMAND_COLUMNS`]), then every task term unscaled in hyq-tasks'
    /// `TERM_NAMES` order; empty under the spec's task.
    pub velocity: Vec<(&'static str, Vec<f64>)>,
    /// The trunk's measured velocity beside the command ([`VELOCITY_MEASURED_COLUMNS`]) when
    /// the records hold it; empty otherwise.
    pub velocity_measured: Vec<(&'static str, Vec<f64>)>,
}

/// Appends one step's named values to `columns` (`steps` counting this one): a name first
/// seen now starts at 0 for the earlier steps, a name the step lacks reads 0 there.
fn push_named(
    columns: &mut Vec<(&'static str, Vec<f64>)>,
    steps: usize,
    values: impl Iterator<Item = (&'static str, f64)>,
) {
    for (name, v) in values {
        match columns.iter_mut().find(|(n, _)| *n == name) {
            Some((_, column)) => column.push(v),
            None => {
                let mut column = vec![0.0; steps - 1];
                column.push(v);
                columns.push((name, column));
            }
        }
    }
    for (_, column) in columns.iter_mut() {
        column.resize(steps, 0.0);
    }
}

impl EpisodeSeries {
    /// An empty series.
    pub fn new() -> Self {
        Self::default()
    }

    /// The series of an episode's records.
    pub fn from_records(records: &[PlotRecord]) -> Self {
        let mut s = Self::new();
        for r in records {
            s.push(r);
        }
        s
    }

    /// Appends one step.
    pub fn push(&mut self, r: &PlotRecord) {
        // Step counts are far below 2^53, so the conversion is exact.
        self.t.push(r.t as f64);
        self.reward.push(r.reward);
        for (column, term) in self.terms.iter_mut().zip(&REWARD_TERMS) {
            column.push((term.get)(&r.terms.values));
        }
        self.d_n.push(r.d_n);
        self.distance_to_goal.push(r.distance_to_goal);
        let steps = self.t.len();
        let regularizers = r.regularizers.as_ref();
        push_named(
            &mut self.regularizers,
            steps,
            regularizers
                .into_iter()
                .flat_map(ReportedRegularizers::iter),
        );
        let velocity = r.velocity.iter().flat_map(|v| {
            let terms = hyq_tasks::TERM_NAMES
                .iter()
                .copied()
                .zip(v.terms.to_array());
            VELOCITY_COMMAND_COLUMNS
                .into_iter()
                .zip(v.command)
                .chain(terms)
        });
        push_named(&mut self.velocity, steps, velocity);
        let measured = r
            .velocity
            .iter()
            .filter_map(|v| v.measured)
            .flat_map(|m| VELOCITY_MEASURED_COLUMNS.into_iter().zip(m));
        push_named(&mut self.velocity_measured, steps, measured);
    }

    /// The column of the term named `name` (`None` for a name that is no term).
    pub fn term(&self, name: &str) -> Option<&[f64]> {
        term_index(name).map(|i| self.terms[i].as_slice())
    }

    /// Number of steps.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether the series holds no step.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The plain columns with their names.
    pub(crate) fn columns(&self) -> impl Iterator<Item = (&'static str, &[f64])> + Clone + '_ {
        [("t", &self.t), ("reward", &self.reward)]
            .into_iter()
            .chain(REWARD_TERMS.iter().map(|t| t.name).zip(&self.terms))
            .chain([("distance_to_goal", &self.distance_to_goal)])
            .map(|(name, column)| (name, column.as_slice()))
            .chain(self.regularizers.iter().map(|(n, c)| (*n, c.as_slice())))
            .chain(self.velocity.iter().map(|(n, c)| (*n, c.as_slice())))
            .chain(
                self.velocity_measured
                    .iter()
                    .map(|(n, c)| (*n, c.as_slice())),
            )
    }

    /// Checks that the series is non-empty, every column has one value per step and every
    /// value is finite (`d_n` may be `None`, not NaN).
    pub fn validate(&self) -> Result<(), PlotError> {
        if self.is_empty() {
            return Err(PlotError::Empty {
                what: "the episode".into(),
            });
        }
        let n = self.len();
        let d_n_len = self.d_n.len();
        for (field, len) in self
            .columns()
            .map(|(f, c)| (f, c.len()))
            .chain([("d_n", d_n_len)])
        {
            if len != n {
                return Err(PlotError::Length {
                    field,
                    expected: n,
                    got: len,
                });
            }
        }
        for (field, column) in self.columns() {
            if let Some((index, &value)) = column.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(PlotError::NonFinite {
                    field,
                    index,
                    value,
                });
            }
        }
        if let Some((index, value)) = self
            .d_n
            .iter()
            .enumerate()
            .find_map(|(i, v)| v.filter(|v| !v.is_finite()).map(|v| (i, v)))
        {
            return Err(PlotError::NonFinite {
                field: "d_n",
                index,
                value,
            });
        }
        Ok(())
    }
}

/// The running sum of `values` (the cumulative reward of a per-step series).
pub fn cumulative(values: &[f64]) -> Vec<f64> {
    values
        .iter()
        .scan(0.0, |sum, v| {
            *sum += v;
            Some(*sum)
        })
        .collect()
}
