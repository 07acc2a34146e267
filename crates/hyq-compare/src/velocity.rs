//! The velocity-command task's figures in a policy comparison (`task.kind = "velocity"`,
//! docs/velocity.md): how well each engine's episodes follow the command, and whether a robot
//! told to stand stands.
//!
//! Per episode, over its steps t = 1..T (each judged by the command its policy saw, c^t, and
//! the trunk's velocity in its own frame after the step, v^t and ω^t, as the task tracks them):
//!
//! - forward-speed error: (1/T) Σ |c_x^t − v_x^t| (m/s);
//! - yaw-rate error: (1/T) Σ |c_yaw^t − ω_z^t| (rad/s);
//! - when the command was zero on every step (a commanded stand): the feet's mean speed,
//!   (1/(T·F)) Σ_t Σ_f ‖p_f^t − p_f^{t−1}‖ / Δt_env over the F feet's collision-sphere centres
//!   (m/s; a robot stepping in place moves its feet, one standing does not), and the trunk's
//!   drift, the horizontal distance from its position after reset to its last (m).
//!
//! Per engine, each figure's mean over the episodes that have it with its 95 % bootstrap
//! interval (hyq-stats, seeded with the run's seed, as every other figure of the report); the
//! fall rate is the report's `fell` rate with its Wilson interval.

use serde::Serialize;

use crate::gait::Figure;
use crate::run::Trajectory;

/// One episode's velocity figures.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct VelocityEpisode {
    /// Mean |c_x − v_x| over the steps (m/s).
    pub forward_error_mps: f64,
    /// Mean |c_yaw − ω_z| over the steps (rad/s).
    pub yaw_error_radps: f64,
    /// The commanded stand's figures, when the command was zero on every step (else not
    /// written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub standing: Option<Standing>,
}

/// What a commanded stand did.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Standing {
    /// The feet's mean speed over the steps (m/s).
    pub feet_speed_mps: f64,
    /// The trunk's horizontal distance from its start to its end (m).
    pub drift_m: f64,
}

impl VelocityEpisode {
    /// The figures of `t`, or `None` when it is not of the velocity task or took no step.
    pub(crate) fn of(t: &Trajectory) -> Option<Self> {
        let steps = &t.velocity;
        if steps.is_empty() {
            return None;
        }
        let n = steps.len() as f64;
        let forward = steps.iter().map(|v| (v.command[0] - v.lin_vel[0]).abs());
        let yaw = steps.iter().map(|v| (v.command[2] - v.ang_vel[2]).abs());
        let standing = steps
            .iter()
            .all(|v| v.command == [0.0; 3])
            .then(|| Standing {
                feet_speed_mps: feet_speed(&t.foot_centres, t.num_feet, t.env_dt),
                drift_m: drift(&t.positions),
            });
        Some(Self {
            forward_error_mps: forward.sum::<f64>() / n,
            yaw_error_radps: yaw.sum::<f64>() / n,
            standing,
        })
    }
}

/// The feet's mean speed (m/s): `centres` holds `num_feet` points per sample, one sample per
/// `dt`; each foot's distance between consecutive samples over `dt`, averaged over feet and
/// steps; 0 with fewer than two samples.
pub fn feet_speed(centres: &[[f64; 3]], num_feet: usize, dt: f64) -> f64 {
    let samples = centres.len() / num_feet.max(1);
    if samples < 2 || num_feet == 0 {
        return 0.0;
    }
    let mut sum = 0.0;
    for t in 1..samples {
        for f in 0..num_feet {
            let (a, b) = (centres[(t - 1) * num_feet + f], centres[t * num_feet + f]);
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            sum += (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / dt;
        }
    }
    sum / ((samples - 1) * num_feet) as f64
}

/// The horizontal distance from the first to the last of `positions` (m); 0 when empty.
pub fn drift(positions: &[[f64; 3]]) -> f64 {
    match (positions.first(), positions.last()) {
        (Some(a), Some(b)) => (b[0] - a[0]).hypot(b[1] - a[1]),
        _ => 0.0,
    }
}

/// An engine's velocity figures over its episodes; a figure no episode had is absent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct VelocityStats {
    /// Forward-speed error (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub forward_error_mps: Option<Figure>,
    /// Yaw-rate error (rad/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yaw_error_radps: Option<Figure>,
    /// The feet's mean speed over the commanded stands (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub standing_feet_speed_mps: Option<Figure>,
    /// The trunk's drift over the commanded stands (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub standing_drift_m: Option<Figure>,
}

impl VelocityStats {
    /// The figures of `episodes` (their intervals' resampling seeded with `seed`), or `None`
    /// when no episode is of the velocity task.
    pub(crate) fn of(episodes: &[Option<VelocityEpisode>], seed: u64) -> Option<Self> {
        let v: Vec<&VelocityEpisode> = episodes.iter().flatten().collect();
        if v.is_empty() {
            return None;
        }
        let stands = || v.iter().filter_map(|e| e.standing);
        Some(Self {
            forward_error_mps: Figure::of(v.iter().map(|e| Some(e.forward_error_mps)), seed),
            yaw_error_radps: Figure::of(v.iter().map(|e| Some(e.yaw_error_radps)), seed),
            standing_feet_speed_mps: Figure::of(stands().map(|s| Some(s.feet_speed_mps)), seed),
            standing_drift_m: Figure::of(stands().map(|s| Some(s.drift_m)), seed),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{drift, feet_speed};

    #[test]
    fn the_feet_speed_is_each_feet_distance_per_step_over_dt() {
        // Two feet, three samples 0.01 s apart: foot 0 moves 1 mm then 2 mm, foot 1 stays.
        let c = [
            [0.0, 0.0, 0.0],
            [5.0, 0.0, 0.0],
            [0.001, 0.0, 0.0],
            [5.0, 0.0, 0.0],
            [0.001, 0.0, 0.002],
            [5.0, 0.0, 0.0],
        ];
        let s = feet_speed(&c, 2, 0.01);
        assert!((s - (0.1 + 0.2) / 4.0).abs() < 1e-12, "{s}");
        assert_eq!(feet_speed(&c[..2], 2, 0.01), 0.0);
        assert_eq!(feet_speed(&[], 0, 0.01), 0.0);
    }

    #[test]
    fn the_drift_is_horizontal() {
        assert_eq!(
            drift(&[[1.0, 1.0, 0.5], [9.0, 9.0, 0.0], [4.0, 5.0, 3.0]]),
            5.0
        );
        assert_eq!(drift(&[]), 0.0);
    }
}
