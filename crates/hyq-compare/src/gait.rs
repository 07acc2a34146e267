//! Gait diagnostics: what a user looks at to see *why* a policy parts between engines, each a
//! pure function of one episode's recorded samples (sample 0 after reset, sample t after env
//! step t; the latched foot-contact flags, the foot collision spheres' centres as the engine
//! holds them, and the actions as fed).
//!
//! - **foot slip per stance step** (mm): over every env step on which a foot touched the ground
//!   on that step and on the one before, the horizontal distance its sphere's centre moved, on
//!   average. A foot that sticks while it carries load slips 0.
//! - **share of actions at their bounds**: the action components (every joint of every step)
//!   at or beyond the action space's low or high end; a policy that saturates its outputs
//!   drives the engine's actuators the hardest.
//! - **action change per step**: the mean of |a_t − a_{t−1}| over joints and steps t ≥ 2, in
//!   the action's unit (rad in the `absolute` mode, a share of the half-range otherwise).
//! - **stance duration** (s): the length of every complete stance phase (a run of steps with a
//!   foot's contact flag set, with a step without contact before and after it inside the
//!   episode), on average over all feet; the reset sample (no contact by construction) and a
//!   stance still going on at the episode's end are not complete phases.
//! - **foot-contact pattern agreement** between two engines' same episode (same seed, same
//!   policy): the share of the steps both lived through on which all feet's contact flags
//!   agree.
//!
//! Each returns `None` where the episode has nothing to measure (no stance step, no action, no
//! complete stance phase); every finite input gives a finite output. The report summarises each
//! figure over the episodes that have it with the mean's bootstrap interval (episodes, not
//! steps, are the independent units).

use serde::Serialize;

use crate::estimates::Stats;

/// One episode's gait figures (see the module docs); a figure the episode has nothing to
/// measure for is absent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct GaitEpisode {
    /// Mean horizontal foot travel per stance step (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub foot_slip_mm: Option<f64>,
    /// Share of action components at or beyond their bounds (0–1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub actions_at_bounds: Option<f64>,
    /// Mean |a_t − a_{t−1}| per joint and step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub action_change: Option<f64>,
    /// Mean complete stance phase (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stance_s: Option<f64>,
}

/// One episode's feet over time: `contacts` and `centres` hold `num_feet` entries per sample,
/// sample-major.
#[derive(Clone, Copy, Debug)]
pub struct Feet<'a> {
    /// Feet per sample.
    pub num_feet: usize,
    /// Latched ground contact of each foot at each sample.
    pub contacts: &'a [bool],
    /// Each foot sphere's centre in the world (m) at each sample.
    pub centres: &'a [[f64; 3]],
}

impl Feet<'_> {
    /// Samples recorded (the shorter of the two arrays' counts).
    fn samples(&self) -> usize {
        let n = self.num_feet.max(1);
        (self.contacts.len() / n).min(self.centres.len() / n)
    }

    fn contact(&self, t: usize, foot: usize) -> bool {
        self.contacts[t * self.num_feet + foot]
    }

    fn centre(&self, t: usize, foot: usize) -> [f64; 3] {
        self.centres[t * self.num_feet + foot]
    }
}

/// Mean horizontal travel (mm) of a foot per env step on which it touched the ground on that
/// step and the one before; `None` if no foot did.
pub fn foot_slip_mm(feet: &Feet<'_>) -> Option<f64> {
    let (mut total_m, mut foot_steps) = (0.0, 0u64);
    for t in 1..feet.samples() {
        for k in 0..feet.num_feet {
            if feet.contact(t, k) && feet.contact(t - 1, k) {
                let (a, b) = (feet.centre(t - 1, k), feet.centre(t, k));
                total_m += (b[0] - a[0]).hypot(b[1] - a[1]);
                foot_steps += 1;
            }
        }
    }
    (foot_steps > 0).then(|| 1000.0 * total_m / foot_steps as f64)
}

/// The share of `actions` (step-major, `low.len()` per step) at or beyond `low` or `high`;
/// `None` for no actions.
pub fn actions_at_bounds(actions: &[f64], low: &[f64], high: &[f64]) -> Option<f64> {
    let n = low.len().min(high.len());
    if n == 0 || actions.len() < n {
        return None;
    }
    let steps = actions.len() / n;
    let at = actions
        .chunks_exact(n)
        .flat_map(|a| a.iter().enumerate())
        .filter(|&(j, &v)| v <= low[j] || v >= high[j])
        .count();
    Some(at as f64 / (steps * n) as f64)
}

/// The mean of |a_t − a_{t−1}| over the `n` joints and the steps after the first; `None` for
/// fewer than two steps.
pub fn action_change(actions: &[f64], n: usize) -> Option<f64> {
    if n == 0 {
        return None;
    }
    let steps: Vec<&[f64]> = actions.chunks_exact(n).collect();
    if steps.len() < 2 {
        return None;
    }
    let total: f64 = steps
        .windows(2)
        .map(|w| {
            w[1].iter()
                .zip(w[0])
                .map(|(b, a)| (b - a).abs())
                .sum::<f64>()
        })
        .sum();
    Some(total / ((steps.len() - 1) * n) as f64)
}

/// The durations (s) of every complete stance phase of every foot (see the module docs), foot
/// by foot in order; `dt` is Δt_env.
pub fn stance_phases(feet: &Feet<'_>, dt: f64) -> Vec<f64> {
    let samples = feet.samples();
    let mut phases = Vec::new();
    for k in 0..feet.num_feet {
        // The run of contact steps under way, and whether a step without contact came first.
        let (mut run, mut after_swing) = (0u64, false);
        for t in 1..samples {
            if feet.contact(t, k) {
                run += 1;
            } else {
                if after_swing && run > 0 {
                    phases.push(run as f64 * dt);
                }
                run = 0;
                after_swing = true;
            }
        }
    }
    phases
}

/// The mean complete stance phase (s); `None` if there is none.
pub fn stance_s(feet: &Feet<'_>, dt: f64) -> Option<f64> {
    let phases = stance_phases(feet, dt);
    (!phases.is_empty()).then(|| phases.iter().sum::<f64>() / phases.len() as f64)
}

/// The share of the samples after reset that both episodes lived through on which every one
/// of the `num_feet` feet's contact flag is the same in `a` and `b` (each `num_feet` flags per
/// sample, sample-major); `None` if they share no such sample.
pub fn contact_agreement(num_feet: usize, a: &[bool], b: &[bool]) -> Option<f64> {
    let n = num_feet.max(1);
    let samples = (a.len() / n).min(b.len() / n);
    if samples < 2 {
        return None;
    }
    let agree = (1..samples)
        .filter(|&t| a[t * n..(t + 1) * n] == b[t * n..(t + 1) * n])
        .count();
    Some(agree as f64 / (samples - 1) as f64)
}

/// Every figure of one episode.
pub fn episode(
    feet: &Feet<'_>,
    dt: f64,
    actions: &[f64],
    low: &[f64],
    high: &[f64],
) -> GaitEpisode {
    GaitEpisode {
        foot_slip_mm: foot_slip_mm(feet),
        actions_at_bounds: actions_at_bounds(actions, low, high),
        action_change: action_change(actions, low.len()),
        stance_s: stance_s(feet, dt),
    }
}

/// A gait figure over an engine's episodes: the statistics of the episodes that have it (the
/// mean with its 95 % bootstrap interval, as every other figure) and how many those are.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Figure {
    /// Mean, 95 % interval, standard deviation, min and max over the episodes.
    #[serde(flatten)]
    pub stats: Stats,
    /// Episodes that had the figure.
    pub episodes: usize,
}

impl Figure {
    /// The statistics of the present `values`, resampled with `seed`; `None` if none is.
    pub(crate) fn of(values: impl Iterator<Item = Option<f64>>, seed: u64) -> Option<Self> {
        let values: Vec<f64> = values.flatten().collect();
        (!values.is_empty()).then(|| Self {
            stats: Stats::of(&values, seed),
            episodes: values.len(),
        })
    }
}

/// An engine's gait figures over its episodes; a figure no episode had is absent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct GaitStats {
    /// Foot slip per stance step (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub foot_slip_mm: Option<Figure>,
    /// Share of action components at or beyond their bounds (0–1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub actions_at_bounds: Option<Figure>,
    /// Mean |a_t − a_{t−1}| per joint and step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub action_change: Option<Figure>,
    /// Complete stance phase (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stance_s: Option<Figure>,
}

impl GaitStats {
    /// The figures of `episodes`, every interval resampled with `seed`.
    pub(crate) fn of(episodes: &[GaitEpisode], seed: u64) -> Self {
        let figure = |f: fn(&GaitEpisode) -> Option<f64>| Figure::of(episodes.iter().map(f), seed);
        Self {
            foot_slip_mm: figure(|g| g.foot_slip_mm),
            actions_at_bounds: figure(|g| g.actions_at_bounds),
            action_change: figure(|g| g.action_change),
            stance_s: figure(|g| g.stance_s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{
        Feet, GaitEpisode, GaitStats, action_change, actions_at_bounds, contact_agreement,
        foot_slip_mm, stance_phases, stance_s,
    };
    use proptest::prelude::*;

    /// One foot's samples: its contact flags and its centre's x (y and z 0).
    fn one_foot(contacts: &[bool], x: &[f64]) -> (Vec<bool>, Vec<[f64; 3]>) {
        (
            contacts.to_vec(),
            x.iter().map(|&x| [x, 0.0, 0.0]).collect(),
        )
    }

    #[test]
    fn slip_counts_horizontal_travel_only_while_touching_on_both_steps() {
        const T: bool = true;
        const F: bool = false;
        // Touching on samples 1-3: two stance steps (1→2, 2→3) of 1 mm and 3 mm; the swing's
        // 50 mm (3→4, 4→5) does not count, nor the step into contact (0→1).
        let (c, p) = one_foot(&[F, T, T, T, F, F], &[0.0, 0.1, 0.101, 0.104, 0.154, 0.2]);
        let feet = Feet {
            num_feet: 1,
            contacts: &c,
            centres: &p,
        };
        let slip = foot_slip_mm(&feet).unwrap_or(f64::NAN);
        assert!((slip - 2.0).abs() < 1e-9, "{slip}");
        // Vertical motion is not slip.
        let lifted: Vec<[f64; 3]> = p.iter().map(|q| [0.0, 0.0, q[0]]).collect();
        let feet = Feet {
            num_feet: 1,
            contacts: &c,
            centres: &lifted,
        };
        assert_eq!(foot_slip_mm(&feet), Some(0.0));
        // Never touching on two steps in a row: nothing to measure.
        let (c, p) = one_foot(&[F, T, F, T], &[0.0, 1.0, 2.0, 3.0]);
        assert_eq!(
            foot_slip_mm(&Feet {
                num_feet: 1,
                contacts: &c,
                centres: &p
            }),
            None
        );
    }

    #[test]
    fn bounds_and_changes_count_every_joint_of_every_step() {
        let (low, high) = ([-1.0, -1.0], [1.0, 1.0]);
        // 4 components, 2 at or beyond a bound (1.0 and -1.5).
        let a = [1.0, 0.5, -1.5, 0.0];
        assert_eq!(actions_at_bounds(&a, &low, &high), Some(0.5));
        assert_eq!(actions_at_bounds(&[0.2, 0.3], &low, &high), Some(0.0));
        assert_eq!(actions_at_bounds(&[], &low, &high), None);
        // |-1.5 - 1.0| = 2.5 and |0.0 - 0.5| = 0.5 over 2 joints × 1 step.
        assert_eq!(action_change(&a, 2), Some(1.5));
        assert_eq!(
            action_change(&[0.1, 0.2], 2),
            None,
            "one step has no change"
        );
        assert_eq!(action_change(&[0.3; 8], 2), Some(0.0));
    }

    #[test]
    fn only_complete_stance_phases_count() {
        const T: bool = true;
        const F: bool = false;
        // Sample 0 is the reset. The run from sample 1 has no swing before it, the run at the
        // end no swing after it: only the 3-step run between two swings is complete.
        let c = [F, T, T, F, T, T, T, F, T, T];
        let p = [[0.0; 3]; 10];
        let feet = Feet {
            num_feet: 1,
            contacts: &c,
            centres: &p,
        };
        assert_eq!(stance_phases(&feet, 0.01), vec![0.03]);
        // Two feet, sample-major: the second foot's complete phase is 1 step.
        let c2 = [F, F, T, F, F, T, F, F, F, F];
        let feet = Feet {
            num_feet: 2,
            contacts: &c2,
            centres: &p,
        };
        assert_eq!(stance_phases(&feet, 0.5), vec![0.5]);
        let always = [T; 6];
        let feet = Feet {
            num_feet: 1,
            contacts: &always,
            centres: &p[..6],
        };
        assert_eq!(
            stance_s(&feet, 0.01),
            None,
            "standing throughout: no complete phase"
        );
    }

    #[test]
    fn an_engine_summary_keeps_only_the_episodes_that_have_a_figure() {
        let e = |slip: Option<f64>| GaitEpisode {
            foot_slip_mm: slip,
            actions_at_bounds: Some(0.25),
            ..GaitEpisode::default()
        };
        let g = GaitStats::of(&[e(Some(2.0)), e(None), e(Some(4.0))], 1);
        let slip = g.foot_slip_mm.unwrap_or_else(|| panic!("a slip figure"));
        assert_eq!((slip.stats.mean, slip.episodes), (3.0, 2));
        let bounds = g
            .actions_at_bounds
            .unwrap_or_else(|| panic!("a bounds figure"));
        assert_eq!(
            (bounds.stats.ci95, bounds.episodes),
            (Some([0.25, 0.25]), 3)
        );
        assert_eq!((g.action_change, g.stance_s), (None, None));
        assert_eq!(g, GaitStats::of(&[e(Some(2.0)), e(None), e(Some(4.0))], 1));
        let json = serde_json::to_value(g).unwrap_or_default();
        assert_eq!(json["foot_slip_mm"]["mean"], 3.0);
        assert_eq!(json["foot_slip_mm"]["episodes"], 2);
        assert!(json["foot_slip_mm"]["ci95"].is_array() && json.get("stance_s").is_none());
    }

    fn feet_pattern() -> impl Strategy<Value = (usize, Vec<bool>, Vec<[f64; 3]>)> {
        (1usize..5, 2usize..40).prop_flat_map(|(feet, samples)| {
            let n = feet * samples;
            (
                Just(feet),
                prop::collection::vec(any::<bool>(), n),
                prop::collection::vec(prop::array::uniform3(-2.0f64..2.0), n),
            )
        })
    }

    proptest! {
        #[test]
        fn agreement_is_a_symmetric_share_and_one_with_itself(
            (n, a, p) in feet_pattern(),
            flips in prop::collection::vec(any::<bool>(), 200),
        ) {
            let b: Vec<bool> = a.iter().zip(flips.iter().cycle()).map(|(x, f)| x ^ f).collect();
            prop_assert_eq!(p.len(), a.len());
            prop_assert_eq!(contact_agreement(n, &a, &a), Some(1.0));
            let ab = contact_agreement(n, &a, &b).unwrap_or(f64::NAN);
            prop_assert!((0.0..=1.0).contains(&ab));
            prop_assert_eq!(Some(ab), contact_agreement(n, &b, &a));
            // Every flag inverted: no step agrees.
            let inverted: Vec<bool> = a.iter().map(|x| !x).collect();
            prop_assert_eq!(contact_agreement(n, &a, &inverted), Some(0.0));
            // A longer episode is compared over the steps both lived through.
            let longer: Vec<bool> = a.iter().chain(&inverted).copied().collect();
            prop_assert_eq!(contact_agreement(n, &a, &longer), Some(1.0));
        }

        #[test]
        fn slip_ignores_where_the_feet_are_and_scales_with_their_motion(
            (n, c, p) in feet_pattern(),
            shift in prop::array::uniform3(-100.0f64..100.0),
            scale in 0.1f64..10.0,
        ) {
            let moved: Vec<[f64; 3]> =
                p.iter().map(|q| [q[0] + shift[0], q[1] + shift[1], q[2] + shift[2]]).collect();
            let scaled: Vec<[f64; 3]> = p.iter().map(|q| q.map(|v| v * scale)).collect();
            let slip = |centres: &[[f64; 3]]| {
                foot_slip_mm(&Feet { num_feet: n, contacts: &c, centres })
            };
            match (slip(&p), slip(&moved), slip(&scaled)) {
                (Some(s), Some(m), Some(k)) => {
                    prop_assert!(s >= 0.0 && s.is_finite());
                    prop_assert!((s - m).abs() <= 1e-6 * (1.0 + s), "{} {}", s, m);
                    prop_assert!((s * scale - k).abs() <= 1e-9 * (1.0 + k), "{} {}", s, k);
                }
                (None, None, None) => {}
                other => prop_assert!(false, "present for some, not others: {:?}", other),
            }
            // Stance phases fit inside the episode and are whole steps.
            let feet = Feet { num_feet: n, contacts: &c, centres: &p };
            let samples = c.len() / n;
            for d in stance_phases(&feet, 0.01) {
                let steps = d / 0.01;
                prop_assert!((steps - steps.round()).abs() < 1e-9 && steps >= 1.0);
                prop_assert!(steps.round() as usize <= samples.saturating_sub(3));
            }
        }

        #[test]
        fn bounded_actions_give_shares_and_changes_in_range(
            a in prop::collection::vec(-2.0f64..2.0, 0..60),
        ) {
            let (low, high) = ([-1.0; 3], [1.0; 3]);
            let used = &a[..a.len() / 3 * 3];
            if let Some(s) = actions_at_bounds(used, &low, &high) {
                prop_assert!((0.0..=1.0).contains(&s));
                let clipped: Vec<f64> = used.iter().map(|v| v.clamp(-1.0, 1.0)).collect();
                prop_assert_eq!(actions_at_bounds(&clipped, &low, &high), Some(s));
            } else {
                prop_assert!(used.is_empty());
            }
            if let Some(d) = action_change(used, 3) {
                prop_assert!((0.0..=4.0).contains(&d));
            }
        }
    }
}
