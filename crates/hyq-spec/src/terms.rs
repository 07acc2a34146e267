//! Spec §4 eq. (1) and §5: the reward terms as one table.
//!
//! r = (Σ rewards) · Π multipliers − Σ penalties
//!
//! Every term of a step's [`RewardBreakdown`] is one row of [`REWARD_TERMS`]: its name (the key
//! of the info, the record, the plots, the summaries and the comparison report), its
//! [`TermKind`] (which says how it enters the composition above and whether its sum over an
//! episode means anything) and its spec section. The composition itself
//! ([`RewardBreakdown::compose`]) iterates the table, and so does everything that reports terms:
//! the environment's episode sums ([`TermSums`]) and records ([`TermValues`]), the plots, the
//! command line's summary and soak check, the Python info and the comparison report. A new term
//! is a field of [`RewardBreakdown`], its value in [`crate::EpisodeRules::evaluate_step`] and a
//! row here; the repository's ARCHITECTURE.md lists the steps.

use serde::de::{self, IgnoredAny, MapAccess, Visitor};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Deserializer, Serialize};
use std::fmt;

use crate::config::TaskConfig;
use crate::step::RewardBreakdown;

/// How a term enters a step's reward (spec §4 eq. (1), §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TermKind {
    /// Added before the multipliers (§4): r_b, r_n, r_e, r_reach. 0 when off.
    Reward,
    /// Multiplies the sum of the rewards (§5.1, §5.2), in [0, 1]. 1 when off.
    Multiplier,
    /// Subtracted after the multipliers, as the positive amount subtracted (§5.3, §5.4). 0 when
    /// off.
    Penalty,
}

impl TermKind {
    /// Every kind, in the order the terms are reported.
    pub const ALL: [TermKind; 3] = [TermKind::Reward, TermKind::Multiplier, TermKind::Penalty];

    /// What the terms of this kind are, as the documents' tables say it.
    pub const fn meaning(self) -> &'static str {
        match self {
            TermKind::Reward => "the reward terms (§4)",
            TermKind::Multiplier => "the multipliers (§5.1, §5.2)",
            TermKind::Penalty => "the penalties subtracted (§5.3, §5.4)",
        }
    }

    /// The value of a term of this kind that changes nothing: 0, or 1 for a multiplier. Every
    /// term has it after reset and on a diverged step.
    pub const fn neutral(self) -> f64 {
        match self {
            TermKind::Multiplier => 1.0,
            TermKind::Reward | TermKind::Penalty => 0.0,
        }
    }

    /// Whether a sum of this kind's values over steps means something (a part of the return):
    /// true for rewards and penalties, false for multipliers. Summaries report sums of these and
    /// means of multipliers.
    pub const fn is_summed(self) -> bool {
        !matches!(self, TermKind::Multiplier)
    }
}

/// One reward term: a row of [`REWARD_TERMS`].
#[derive(Clone, Copy, Debug)]
pub struct RewardTerm {
    /// The term's name, the key it has everywhere it is reported (`"r_b"`, `"m_yaw"`, …).
    pub name: &'static str,
    /// How it enters the reward.
    pub kind: TermKind,
    /// The spec section that defines it (`"§4.1"`).
    pub section: &'static str,
    /// The spec's name for the term's sum over an episode where it names one (Σ r_n is R_n,
    /// §4.2; Σ r_e is R_e(D_n), §4.3).
    pub sum_name: Option<&'static str>,
    /// For an opt-in term (off unless configured, and then written in records only when on):
    /// whether a configuration switches it on. `None` for a term every record carries.
    pub opt_in: Option<fn(&TaskConfig) -> bool>,
    /// The term's value in a breakdown.
    pub get: fn(&RewardBreakdown) -> f64,
    /// The term's place in a breakdown.
    pub get_mut: fn(&mut RewardBreakdown) -> &mut f64,
}

impl RewardTerm {
    /// Whether a step under `task` reports this term in its record: always, unless the term is
    /// opt-in and `task` leaves it off.
    pub fn is_reported(&self, task: &TaskConfig) -> bool {
        self.opt_in.is_none_or(|on| on(task))
    }
}

/// The number of reward terms.
pub const NUM_REWARD_TERMS: usize = 9;

/// Writes [`REWARD_TERMS`] and [`RewardBreakdown::NEUTRAL`] from one list of rows, each a
/// field of [`RewardBreakdown`] with its kind, section, sum name and opt-in switch: the row's
/// name, value and place are its field's, and the neutral breakdown puts every term at its
/// kind's [`TermKind::neutral`]. A field without a row, or a row without a field, does not
/// compile (`NEUTRAL` names every field).
macro_rules! reward_terms {
    ($($field:ident {
        kind: $kind:ident,
        section: $section:literal,
        sum_name: $sum:expr,
        opt_in: $opt:expr,
    },)*) => {
        /// Every reward term, in the order they are reported: the rewards (§4), the multipliers
        /// (§5.1, §5.2), the penalties (§5.3, §5.4).
        pub const REWARD_TERMS: [RewardTerm; NUM_REWARD_TERMS] = [$(
            RewardTerm {
                name: stringify!($field),
                kind: TermKind::$kind,
                section: $section,
                sum_name: $sum,
                opt_in: $opt,
                get: |b| b.$field,
                get_mut: |b| &mut b.$field,
            },
        )*];

        impl RewardBreakdown {
            /// The breakdown where no reward is given (after reset, on a diverged step): every
            /// term at its kind's neutral value ([`TermKind::neutral`]: rewards and penalties 0,
            /// multipliers 1), total 0.
            pub const NEUTRAL: RewardBreakdown = RewardBreakdown {
                $($field: TermKind::$kind.neutral(),)*
                total: 0.0,
            };
        }
    };
}

reward_terms! {
    r_b {
        kind: Reward,
        section: "§4.1",
        sum_name: None,
        opt_in: None,
    },
    r_n {
        kind: Reward,
        section: "§4.2",
        sum_name: Some("R_n"),
        opt_in: None,
    },
    r_e {
        kind: Reward,
        section: "§4.3",
        sum_name: Some("R_e(D_n)"),
        opt_in: None,
    },
    r_reach {
        kind: Reward,
        section: "§4.4",
        sum_name: None,
        opt_in: None,
    },
    m_yaw {
        kind: Multiplier,
        section: "§5.1.1",
        sum_name: None,
        opt_in: None,
    },
    m_pitch {
        kind: Multiplier,
        section: "§5.1.2",
        sum_name: None,
        opt_in: None,
    },
    m_height {
        kind: Multiplier,
        section: "§5.2",
        sum_name: None,
        opt_in: Some(|task| task.height_penalty.is_some()),
    },
    joint_penalty {
        kind: Penalty,
        section: "§5.3",
        sum_name: None,
        opt_in: None,
    },
    fall_penalty {
        kind: Penalty,
        section: "§5.4",
        sum_name: None,
        opt_in: None,
    },
}

/// The terms' names, in the table's order.
pub const TERM_NAMES: [&str; NUM_REWARD_TERMS] = {
    let mut names = [""; NUM_REWARD_TERMS];
    let mut i = 0;
    while i < NUM_REWARD_TERMS {
        names[i] = REWARD_TERMS[i].name;
        i += 1;
    }
    names
};

/// The index in [`REWARD_TERMS`] of the term named `name`.
pub fn term_index(name: &str) -> Option<usize> {
    REWARD_TERMS.iter().position(|t| t.name == name)
}

/// The terms of `kind`, in the table's order.
pub fn terms_of(kind: TermKind) -> impl Iterator<Item = &'static RewardTerm> {
    REWARD_TERMS.iter().filter(move |t| t.kind == kind)
}

/// The sums of every term over an episode or a run, one per row of [`REWARD_TERMS`].
///
/// Serialised as an object of the summed terms (rewards and penalties, [`TermKind::is_summed`])
/// by name, in the table's order; [`TermSums::mean`] gives a multiplier's mean.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TermSums {
    sums: [f64; NUM_REWARD_TERMS],
    steps: u64,
}

impl TermSums {
    /// Adds one step's terms.
    pub fn add(&mut self, b: &RewardBreakdown) {
        for (sum, term) in self.sums.iter_mut().zip(&REWARD_TERMS) {
            *sum += (term.get)(b);
        }
        self.steps += 1;
    }

    /// Σ of the term named `name` (`None` for a name that is no term).
    pub fn get(&self, name: &str) -> Option<f64> {
        term_index(name).map(|i| self.sums[i])
    }

    /// Every term with its sum, in the table's order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static RewardTerm, f64)> + '_ {
        REWARD_TERMS.iter().zip(self.sums.iter().copied())
    }

    /// The steps added.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The mean of the term named `name` over the steps added (for a multiplier; 0 before any
    /// step, `None` for a name that is no term).
    pub fn mean(&self, name: &str) -> Option<f64> {
        // Step counts are far below 2^53, so the conversion is exact.
        self.get(name).map(|s| s / self.steps.max(1) as f64)
    }
}

impl Serialize for TermSums {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let count = REWARD_TERMS.iter().filter(|t| t.kind.is_summed()).count();
        let mut map = s.serialize_map(Some(count))?;
        for (term, sum) in self.iter().filter(|(t, _)| t.kind.is_summed()) {
            map.serialize_entry(term.name, &sum)?;
        }
        map.end()
    }
}

/// A step's reward terms as a record holds them: an object keyed by term name, in the table's
/// order, an opt-in term ([`RewardTerm::opt_in`]) only where it was on.
///
/// Reading one (serde) is strict: every term that is not opt-in is required, and an unknown or
/// repeated key is an error; [`TermValues::deserialize_lenient`] ignores unknown keys instead.
/// A term absent from what was read holds its neutral value in [`TermValues::values`], whose
/// `total` is their composition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TermValues {
    /// Every term's value; a term that is not present holds its neutral value.
    pub values: RewardBreakdown,
    present: [bool; NUM_REWARD_TERMS],
}

impl TermValues {
    /// The terms of a step taken under `task`: every term, an opt-in one only when `task`
    /// switches it on.
    pub fn reported(values: &RewardBreakdown, task: &TaskConfig) -> Self {
        Self {
            values: *values,
            present: REWARD_TERMS.map(|t| t.is_reported(task)),
        }
    }

    /// Every term of `values`, opt-in ones included.
    pub fn all(values: &RewardBreakdown) -> Self {
        Self {
            values: *values,
            present: [true; NUM_REWARD_TERMS],
        }
    }

    /// The value of the term named `name` if it is present.
    pub fn get(&self, name: &str) -> Option<f64> {
        term_index(name)
            .filter(|&i| self.present[i])
            .map(|i| (REWARD_TERMS[i].get)(&self.values))
    }

    /// The present terms with their values, in the table's order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static RewardTerm, f64)> + '_ {
        REWARD_TERMS
            .iter()
            .zip(&self.present)
            .filter(|(_, present)| **present)
            .map(|(t, _)| (t, (t.get)(&self.values)))
    }

    /// Reads terms as [`Deserialize`] does, but ignores keys that name no term (for readers of
    /// records written by other tools, which may carry more). For `#[serde(deserialize_with)]`.
    pub fn deserialize_lenient<'de, D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(TermsVisitor { strict: false })
    }
}

impl Serialize for TermValues {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.present.iter().filter(|p| **p).count()))?;
        for (term, value) in self.iter() {
            map.serialize_entry(term.name, &value)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for TermValues {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(TermsVisitor { strict: true })
    }
}

/// Reads an object of terms; `strict` refuses keys that name no term.
struct TermsVisitor {
    strict: bool,
}

impl<'de> Visitor<'de> for TermsVisitor {
    type Value = TermValues;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object of reward terms by name")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<TermValues, A::Error> {
        let mut values = RewardBreakdown::NEUTRAL;
        let mut present = [false; NUM_REWARD_TERMS];
        while let Some(key) = map.next_key::<String>()? {
            let Some(i) = term_index(&key) else {
                if self.strict {
                    return Err(de::Error::unknown_field(&key, &TERM_NAMES));
                }
                map.next_value::<IgnoredAny>()?;
                continue;
            };
            if present[i] {
                return Err(de::Error::duplicate_field(REWARD_TERMS[i].name));
            }
            *(REWARD_TERMS[i].get_mut)(&mut values) = map.next_value()?;
            present[i] = true;
        }
        if let Some(i) =
            (0..NUM_REWARD_TERMS).find(|&i| !present[i] && REWARD_TERMS[i].opt_in.is_none())
        {
            return Err(de::Error::missing_field(REWARD_TERMS[i].name));
        }
        values.total = values.compose();
        Ok(TermValues { values, present })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A breakdown whose every term holds a different value (term i holds i + 2).
    fn distinct() -> RewardBreakdown {
        let mut b = RewardBreakdown::NEUTRAL;
        for (i, t) in REWARD_TERMS.iter().enumerate() {
            *(t.get_mut)(&mut b) = i as f64 + 2.0;
        }
        b.total = b.compose();
        b
    }

    #[test]
    fn every_row_reads_and_writes_its_own_field_of_the_breakdown() {
        let b = distinct();
        for (i, t) in REWARD_TERMS.iter().enumerate() {
            assert_eq!((t.get)(&b), i as f64 + 2.0, "{}", t.name);
        }
        let names: Vec<&str> = REWARD_TERMS.iter().map(|t| t.name).collect();
        assert_eq!(names, TERM_NAMES);
        let serialised = serde_json::to_value(b).unwrap_or_else(|e| panic!("{e}"));
        for t in &REWARD_TERMS {
            assert_eq!(serialised[t.name].as_f64(), Some((t.get)(&b)), "{}", t.name);
        }
        assert_eq!(
            serialised.as_object().map(|o| o.len()),
            Some(NUM_REWARD_TERMS + 1)
        );
    }

    #[test]
    fn the_neutral_breakdown_holds_each_kinds_neutral_value() {
        for (t, v) in RewardBreakdown::NEUTRAL.terms() {
            assert_eq!(v, t.kind.neutral(), "{}", t.name);
        }
        assert_eq!(RewardBreakdown::NEUTRAL.compose(), 0.0);
        assert_eq!(RewardBreakdown::NEUTRAL.total, 0.0);
    }

    #[test]
    fn composition_follows_the_kinds_in_the_tables_order() {
        let b = distinct();
        let (mut sum, mut product, mut penalties) = (None, 1.0, 0.0);
        for (t, v) in b.terms() {
            match t.kind {
                TermKind::Reward => sum = Some(sum.map_or(v, |s: f64| s + v)),
                TermKind::Multiplier => product *= v,
                TermKind::Penalty => penalties += v,
            }
        }
        let expected = sum.unwrap_or(0.0) * product - penalties;
        assert!((b.compose() - expected).abs() <= 1e-12 * expected.abs());
        let minus_zero = RewardBreakdown {
            r_b: -0.0,
            r_n: -0.0,
            r_e: -0.0,
            r_reach: -0.0,
            ..RewardBreakdown::NEUTRAL
        };
        assert!(
            minus_zero.compose().is_sign_negative(),
            "−0.0 summed stays −0.0"
        );
    }

    #[test]
    fn sums_add_every_term_and_serialise_the_summed_ones_in_order() {
        let mut sums = TermSums::default();
        sums.add(&distinct());
        sums.add(&distinct());
        for (i, (t, s)) in sums.iter().enumerate() {
            assert_eq!(s, 2.0 * (i as f64 + 2.0), "{}", t.name);
        }
        assert_eq!(sums.mean("m_yaw"), Some(6.0));
        assert_eq!(sums.get("no_such_term"), None);
        let json = serde_json::to_string(&sums).unwrap_or_else(|e| panic!("{e}"));
        let summed: Vec<&str> = REWARD_TERMS
            .iter()
            .filter(|t| t.kind.is_summed())
            .map(|t| t.name)
            .collect();
        let keys: Vec<String> = json
            .trim_matches(['{', '}'])
            .split(',')
            .map(|kv| {
                kv.split(':')
                    .next()
                    .unwrap_or("")
                    .trim_matches('"')
                    .to_owned()
            })
            .collect();
        assert_eq!(keys, summed);
    }

    #[test]
    fn recorded_terms_round_trip_and_leave_out_an_opt_in_term_that_is_off() {
        let off = TaskConfig::default();
        let b = distinct();
        let terms = TermValues::reported(&b, &off);
        let json = serde_json::to_string(&terms).unwrap_or_else(|e| panic!("{e}"));
        assert!(!json.contains("m_height"), "{json}");
        for t in REWARD_TERMS.iter().filter(|t| t.opt_in.is_none()) {
            assert!(json.contains(&format!("\"{}\":", t.name)), "{json}");
        }
        let back: TermValues = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back.get("m_height"), None);
        assert_eq!(
            back.values.m_height, 1.0,
            "an absent opt-in term reads neutral"
        );
        assert_eq!(back.get("r_e"), Some(b.r_e));
        assert_eq!(back.values.total, back.values.compose());

        let all = serde_json::to_string(&TermValues::all(&b)).unwrap_or_else(|e| panic!("{e}"));
        let back: TermValues = serde_json::from_str(&all).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back, TermValues::all(&b));
    }

    #[test]
    fn strict_reading_refuses_unknown_repeated_and_missing_terms_and_lenient_ignores_unknown() {
        let json =
            serde_json::to_string(&TermValues::all(&distinct())).unwrap_or_else(|e| panic!("{e}"));
        let extra = json.replacen('{', "{\"r_x\":1.0,", 1);
        let err = serde_json::from_str::<TermValues>(&extra).err();
        assert!(err.is_some_and(|e| e.to_string().contains("r_x")));
        let repeated = json.replacen('{', "{\"r_b\":1.0,", 1);
        assert!(serde_json::from_str::<TermValues>(&repeated).is_err());
        let missing = json.replacen("\"r_n\":3.0,", "", 1);
        assert_ne!(missing, json);
        let err = serde_json::from_str::<TermValues>(&missing).err();
        assert!(err.is_some_and(|e| e.to_string().contains("r_n")));

        let mut d = serde_json::Deserializer::from_str(&extra);
        let lenient = TermValues::deserialize_lenient(&mut d).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(lenient, TermValues::all(&distinct()));
    }
}
