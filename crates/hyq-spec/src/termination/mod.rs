//! Spec §6 (Termination): four conditions, each checked at the end of every env
//! step, independently of the others:
//!
//! 1. reached ([`reach`], §6.1): |C_i − G_i| ≤ ε_reach / 2 on every axis;
//! 2. joint limit ([`joint_limit`], §6.2): θ ≤ θ_min + ε_joint or θ ≥ θ_max − ε_joint, any joint;
//! 3. fell ([`fall`], §6.3): the trunk touched the ground in any physics sub-step of the step;
//! 4. timeout ([`timeout`], §6.4): t ≥ t_max.
//!
//! Every condition that holds is reported ([`Terminations`]) and adds its own reward or penalty.
//! In Gymnasium's terms: `terminated` = reached ∨ joint limit ∨ fell; `truncated` = timeout ∧
//! ¬terminated.

pub mod fall;
pub mod joint_limit;
pub mod reach;
pub mod timeout;

use serde::{Deserialize, Serialize, Serializer, ser::SerializeSeq};
use std::fmt;

/// One of the spec's four termination conditions (§6.1–§6.4). Serialised (and displayed) as its
/// stable snake_case name: `reached`, `joint_limit`, `fell`, `timeout`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// §6.1: the trunk centre is inside the cube of side ε_reach centred on the goal.
    Reached,
    /// §6.2: some joint is within ε_joint of one of its limits.
    JointLimit,
    /// §6.3: the trunk touched the ground during the step.
    Fell,
    /// §6.4: t ≥ t_max.
    Timeout,
}

impl Termination {
    /// The four conditions in the spec's order (§6.1–§6.4).
    pub const ALL: [Termination; 4] = [
        Termination::Reached,
        Termination::JointLimit,
        Termination::Fell,
        Termination::Timeout,
    ];

    /// The stable snake_case name used in JSON and logs.
    pub const fn as_str(self) -> &'static str {
        match self {
            Termination::Reached => "reached",
            Termination::JointLimit => "joint_limit",
            Termination::Fell => "fell",
            Termination::Timeout => "timeout",
        }
    }

    /// Whether this condition ends the episode as a true terminal state (Gymnasium's
    /// `terminated`); only the timeout does not.
    pub const fn is_terminal(self) -> bool {
        !matches!(self, Termination::Timeout)
    }

    const fn bit(self) -> u8 {
        1 << self as u8
    }
}

impl fmt::Display for Termination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The set of termination conditions that hold at the end of a step (any number of the four).
///
/// Serialised as a list of names in the spec's order, e.g. `["joint_limit", "fell"]`.
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Terminations(u8);

impl Terminations {
    /// The empty set: the episode goes on.
    pub const NONE: Terminations = Terminations(0);

    /// The set holding each condition whose flag is true.
    pub const fn from_flags(reached: bool, joint_limit: bool, fell: bool, timeout: bool) -> Self {
        let mut bits = 0;
        if reached {
            bits |= Termination::Reached.bit();
        }
        if joint_limit {
            bits |= Termination::JointLimit.bit();
        }
        if fell {
            bits |= Termination::Fell.bit();
        }
        if timeout {
            bits |= Termination::Timeout.bit();
        }
        Terminations(bits)
    }

    /// Adds `condition` to the set.
    pub fn insert(&mut self, condition: Termination) {
        self.0 |= condition.bit();
    }

    /// Whether `condition` holds.
    pub const fn contains(self, condition: Termination) -> bool {
        self.0 & condition.bit() != 0
    }

    /// Whether no condition holds.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Gymnasium's `terminated`: reached, joint limit or fell holds.
    pub const fn terminated(self) -> bool {
        self.0 & !Termination::Timeout.bit() != 0
    }

    /// Gymnasium's `truncated`: the timeout holds and no terminal condition does.
    pub const fn truncated(self) -> bool {
        self.contains(Termination::Timeout) && !self.terminated()
    }

    /// Whether the episode is over (terminated or truncated).
    pub const fn done(self) -> bool {
        !self.is_empty()
    }

    /// The conditions that hold, in the spec's order.
    pub fn iter(self) -> impl Iterator<Item = Termination> {
        Termination::ALL
            .into_iter()
            .filter(move |c| self.contains(*c))
    }
}

impl fmt::Debug for Terminations {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_set().entries(self.iter()).finish()
    }
}

impl FromIterator<Termination> for Terminations {
    fn from_iter<I: IntoIterator<Item = Termination>>(iter: I) -> Self {
        let mut set = Terminations::NONE;
        for condition in iter {
            set.insert(condition);
        }
        set
    }
}

impl Serialize for Terminations {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_seq(Some(self.0.count_ones() as usize))?;
        for condition in self.iter() {
            seq.serialize_element(&condition)?;
        }
        seq.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn names_are_stable_snake_case() {
        let names: Vec<_> = Termination::ALL.iter().map(|c| c.as_str()).collect();
        assert_eq!(names, ["reached", "joint_limit", "fell", "timeout"]);
        for c in Termination::ALL {
            assert_eq!(c.to_string(), c.as_str());
        }
    }

    proptest! {
        #[test]
        fn set_semantics_match_the_rulings(reached: bool, joint_limit: bool, fell: bool, timeout: bool) {
            let set = Terminations::from_flags(reached, joint_limit, fell, timeout);
            let flags = [reached, joint_limit, fell, timeout];
            for (c, flag) in Termination::ALL.into_iter().zip(flags) {
                prop_assert_eq!(set.contains(c), flag);
            }
            let terminated = reached || joint_limit || fell;
            prop_assert_eq!(set.terminated(), terminated);
            prop_assert_eq!(set.truncated(), timeout && !terminated);
            prop_assert_eq!(set.done(), terminated || timeout);
            prop_assert_eq!(set.iter().collect::<Terminations>(), set);
            prop_assert_eq!(set.iter().count(), flags.iter().filter(|f| **f).count());
        }
    }
}
