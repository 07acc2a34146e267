//! Spec §4.2, eq. (3), as ruled (a **deviation** inherited from §4.1's eq. (2)):
//! the base reward's distance change divided by K = ‖G − C^0‖ and scaled by k_norm,
//!
//! r_n^t = k_norm · (D^{t−1} − D^t) / K,
//!
//! so that every goal, near or far, pays the same: Σ r_n over an episode telescopes to
//! k_norm · (1 − D_n^T), exactly k_norm at the goal (the spec's Figure 4 rises to its scale, 10).
//! Unset `norm_rew_scaling` turns r_n off. K comes as a [`StartGoalDistance`], which cannot be 0.

use crate::distance::StartGoalDistance;

/// r_n = k_norm · (D^{t−1} − D^t) / K for the distances to the goal before (`d_prev`) and after
/// (`d`) the step, in metres.
pub fn normalised_reward(d_prev: f64, d: f64, k: StartGoalDistance, k_norm: f64) -> f64 {
    k_norm * (d_prev - d) / k.metres()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_whole_walk_to_the_goal_pays_k_norm() {
        let Some(k) = StartGoalDistance::from_metres(4.0) else {
            panic!("4 m is a valid K")
        };
        assert_eq!(normalised_reward(4.0, 0.0, k, 10.0), 10.0);
        assert_eq!(normalised_reward(4.0, 5.0, k, 10.0), -2.5);
    }
}
