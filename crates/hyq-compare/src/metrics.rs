//! The quantities a comparison measures, as pure functions of two recorded runs.
//!
//! Over the steps both runs lived through (samples 0..=min(end_A, end_B)):
//! - trunk position divergence e_p(t) = ‖C_A^t − C_B^t‖ (m);
//! - trunk orientation divergence e_R(t) = the angle of q_A^t⁻¹ q_B^t (rad, in [0, π]);
//! - joint-angle divergence e_q(t) = max_i |θ_A,i^t − θ_B,i^t| (rad), and per joint the RMS over
//!   time;
//!
//! each summarised as RMS over time, √(mean_t e(t)²), and max over time. Contact-flag agreement
//! per tracked body is the share of steps t ≥ 1 whose latched flags (rows 24–28) are equal.
//!
//! The one-step comparison compares, for each shared state, the two backends' states one
//! physics sub-step later: ‖q_A − q_B‖∞, ‖q̇_A − q̇_B‖∞, the trunk position distance, the trunk
//! orientation angle, and the trunk linear and angular velocity distances.

use hyq_physics::RobotState;
use hyq_physics::na::UnitQuaternion;
use serde::Serialize;

use crate::run::{OneStepResult, Trajectory};

/// Whether `value` replaces `max` as the maximum: it is larger, or it is NaN (so that a
/// non-finite difference is never hidden behind a finite one).
fn exceeds(value: f64, max: f64) -> bool {
    value > max || value.is_nan()
}

/// The angle (rad, in [0, π]) of the rotation taking `a` to `b`: 2 atan2(‖v‖, |w|) of a⁻¹ b.
/// Equal quaternions give exactly 0: the product a⁻¹ a leaves rounding noise of ~1e-17 rad,
/// which would hide that two runs agree bit for bit.
pub fn rotation_angle(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> f64 {
    if a.coords == b.coords {
        return 0.0;
    }
    let d = a.inverse() * b;
    2.0 * d.imag().norm().atan2(d.w.abs())
}

/// A divergence summarised over time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Divergence {
    /// √(mean e(t)²).
    pub rms: f64,
    /// max e(t).
    pub max: f64,
    /// The first step at which the max is reached.
    pub max_at_step: u64,
}

impl Divergence {
    fn from_series(series: &[f64]) -> Self {
        if series.is_empty() {
            return Self::default();
        }
        let mut max = f64::NEG_INFINITY;
        let mut at = 0;
        let mut sq = 0.0;
        for (t, e) in series.iter().enumerate() {
            sq += e * e;
            if exceeds(*e, max) {
                max = *e;
                at = t;
            }
        }
        Self {
            rms: (sq / series.len() as f64).sqrt(),
            max,
            max_at_step: at as u64,
        }
    }
}

/// Agreement of one tracked body's contact flags.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactAgreement {
    /// The tracked body (e.g. `lf_foot`, `trunk`).
    pub link: String,
    /// Share of compared steps with equal flags (%).
    pub agreement_pct: f64,
    /// Steps with the flag set, per backend.
    pub steps_in_contact: [u64; 2],
}

/// Everything measured between two runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrajectoryComparison {
    /// Samples compared (steps both lived through + the reset sample).
    pub samples: usize,
    /// Trunk position divergence (m).
    pub trunk_position: Divergence,
    /// Trunk orientation divergence (rad).
    pub trunk_orientation: Divergence,
    /// Joint-angle divergence, the worst joint at each step (rad).
    pub joint_angles: Divergence,
    /// Per joint, the RMS over time of the angle difference (rad), joint order.
    pub joint_rms: Vec<f64>,
    /// Per tracked body, flag agreement over steps 1..samples.
    pub contacts: Vec<ContactAgreement>,
    /// e_p(t), e_R(t), e_q(t) per sample.
    #[serde(skip)]
    pub series: [Vec<f64>; 3],
}

/// Compares two runs over the steps both lived through.
pub fn compare_trajectories(a: &Trajectory, b: &Trajectory) -> TrajectoryComparison {
    let samples = a.len().min(b.len());
    let n = a.num_joints.min(b.num_joints);
    let mut e_p = Vec::with_capacity(samples);
    let mut e_r = Vec::with_capacity(samples);
    let mut e_q = Vec::with_capacity(samples);
    let mut joint_sq = vec![0.0; n];
    for t in 0..samples {
        let (pa, pb) = (a.positions[t], b.positions[t]);
        e_p.push(
            ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2) + (pa[2] - pb[2]).powi(2)).sqrt(),
        );
        e_r.push(rotation_angle(&a.orientations[t], &b.orientations[t]));
        let mut worst: f64 = 0.0;
        for (i, (qa, qb)) in a.q(t).iter().zip(b.q(t)).enumerate() {
            let d = (qa - qb).abs();
            joint_sq[i] += d * d;
            worst = if d.is_nan() { d } else { worst.max(d) };
        }
        e_q.push(worst);
    }
    let joint_rms = joint_sq
        .iter()
        .map(|s| (s / samples.max(1) as f64).sqrt())
        .collect();
    let contacts = a
        .tracked
        .iter()
        .enumerate()
        .map(|(k, link)| {
            let mut equal = 0u64;
            let mut on = [0u64; 2];
            for t in 1..samples {
                let (ca, cb) = (a.contacts_at(t)[k], b.contacts_at(t)[k]);
                equal += u64::from(ca == cb);
                on[0] += u64::from(ca);
                on[1] += u64::from(cb);
            }
            let compared = samples.saturating_sub(1);
            ContactAgreement {
                link: link.clone(),
                agreement_pct: if compared == 0 {
                    100.0
                } else {
                    100.0 * equal as f64 / compared as f64
                },
                steps_in_contact: on,
            }
        })
        .collect();
    TrajectoryComparison {
        samples,
        trunk_position: Divergence::from_series(&e_p),
        trunk_orientation: Divergence::from_series(&e_r),
        joint_angles: Divergence::from_series(&e_q),
        joint_rms,
        contacts,
        series: [e_p, e_r, e_q],
    }
}

/// The one-step differences for one shared state.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OneStepErrors {
    /// The reference run's sample the state came from.
    pub step: u64,
    /// Whether either backend had a tracked body (a foot or the trunk) on the ground during the
    /// sub-step.
    pub in_contact: bool,
    /// ‖q_A − q_B‖∞ (rad).
    pub q: f64,
    /// ‖q̇_A − q̇_B‖∞ (rad/s).
    pub qd: f64,
    /// Trunk position distance (m).
    pub trunk_position: f64,
    /// Trunk orientation angle (rad).
    pub trunk_orientation: f64,
    /// Trunk linear velocity distance (m/s).
    pub trunk_linvel: f64,
    /// Trunk angular velocity distance (rad/s).
    pub trunk_angvel: f64,
}

impl OneStepErrors {
    /// The quantities as (name, unit, value), in a fixed order.
    pub fn quantities(&self) -> [(&'static str, &'static str, f64); 6] {
        [
            ("q", "rad", self.q),
            ("qd", "rad/s", self.qd),
            ("trunk_position", "m", self.trunk_position),
            ("trunk_orientation", "rad", self.trunk_orientation),
            ("trunk_linvel", "m/s", self.trunk_linvel),
            ("trunk_angvel", "rad/s", self.trunk_angvel),
        ]
    }
}

fn inf_norm(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m: f64, (x, y)| {
        let d = (x - y).abs();
        if d.is_nan() { d } else { m.max(d) }
    })
}

/// The differences between two backends' states after the same sub-step from the same state.
pub fn one_step_errors(a: &OneStepResult, b: &OneStepResult) -> OneStepErrors {
    let (sa, sb): (&RobotState, &RobotState) = (&a.after, &b.after);
    let (ta, tb) = (&sa.trunk, &sb.trunk);
    OneStepErrors {
        step: a.step,
        in_contact: a.in_contact || b.in_contact,
        q: inf_norm(&sa.q, &sb.q),
        qd: inf_norm(&sa.qd, &sb.qd),
        trunk_position: (ta.pose.translation.vector - tb.pose.translation.vector).norm(),
        trunk_orientation: rotation_angle(&ta.pose.rotation, &tb.pose.rotation),
        trunk_linvel: (ta.linvel - tb.linvel).norm(),
        trunk_angvel: (ta.angvel - tb.angvel).norm(),
    }
}

/// One quantity of the one-step comparison summarised over the shared states.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OneStepSummary {
    /// `q`, `qd`, `trunk_position`, `trunk_orientation`, `trunk_linvel`, `trunk_angvel`.
    pub quantity: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// The largest difference over all states.
    pub max: f64,
    /// The state (reference sample) where it occurs.
    pub max_at_step: u64,
    /// The median difference.
    pub median: f64,
    /// The largest difference over states where neither backend had a tracked body (a foot or
    /// the trunk) on the ground during the sub-step (`None` when there was none). Untracked
    /// links (shins, thighs) are not seen by the contact flags and may still touch the ground.
    pub max_without_contact: Option<f64>,
}

/// Summarises the per-state errors quantity by quantity.
pub fn summarise_one_step(errors: &[OneStepErrors]) -> Vec<OneStepSummary> {
    let Some(first) = errors.first() else {
        return Vec::new();
    };
    (0..first.quantities().len())
        .map(|k| {
            let (quantity, unit, _) = first.quantities()[k];
            let mut values: Vec<(f64, u64, bool)> = errors
                .iter()
                .map(|e| (e.quantities()[k].2, e.step, e.in_contact))
                .collect();
            let (max, max_at_step) = values.iter().fold((f64::NEG_INFINITY, 0), |acc, v| {
                if exceeds(v.0, acc.0) { (v.0, v.1) } else { acc }
            });
            let max_without_contact = values
                .iter()
                .filter(|v| !v.2)
                .map(|v| v.0)
                .reduce(|m, v| if exceeds(v, m) { v } else { m });
            values.sort_by(|x, y| x.0.total_cmp(&y.0));
            let median = values[values.len() / 2].0;
            OneStepSummary {
                quantity,
                unit,
                max,
                max_at_step,
                median,
                max_without_contact,
            }
        })
        .collect()
}

/// Picks up to `count` samples of a run, evenly spread over samples 0..len−1 (the last sample
/// has no step after it), skipping states with a non-finite value.
pub fn sample_indices(traj: &Trajectory, count: usize) -> Vec<usize> {
    let usable = traj.len().saturating_sub(1);
    if usable == 0 || count == 0 {
        return Vec::new();
    }
    let count = count.min(usable);
    let mut picked: Vec<usize> = (0..count).map(|k| k * usable / count).collect();
    picked.dedup();
    picked.retain(|&t| {
        let s = &traj.states[t];
        s.q.iter().chain(&s.qd).all(|v| v.is_finite())
            && s.trunk
                .pose
                .translation
                .vector
                .iter()
                .all(|v| v.is_finite())
            && s.trunk
                .linvel
                .iter()
                .chain(s.trunk.angvel.iter())
                .all(|v| v.is_finite())
    });
    picked
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn divergence_is_rms_and_first_max_and_never_hides_a_nan() {
        let d = Divergence::from_series(&[0.0, 3.0, 4.0, 4.0]);
        assert_eq!(d.max, 4.0);
        assert_eq!(d.max_at_step, 2);
        assert!((d.rms - (41.0f64 / 4.0).sqrt()).abs() < 1e-15);
        let d = Divergence::from_series(&[1.0, f64::NAN, 2.0]);
        assert!(d.max.is_nan() && d.rms.is_nan());
        assert_eq!(Divergence::from_series(&[]), Divergence::default());
    }

    #[test]
    fn rotation_angle_is_the_angle_between_orientations() {
        let a = UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3);
        assert_eq!(rotation_angle(&a, &a), 0.0);
        let b = a * UnitQuaternion::from_euler_angles(0.0, 0.0, 0.25);
        assert!((rotation_angle(&a, &b) - 0.25).abs() < 1e-12);
        // q and −q are the same orientation.
        let neg = UnitQuaternion::new_unchecked(-b.into_inner());
        assert!((rotation_angle(&a, &neg) - 0.25).abs() < 1e-12);
    }
}
