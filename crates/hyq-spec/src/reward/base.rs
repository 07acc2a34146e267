//! Spec §4.1, eq. (2), as ruled (a **deviation**): the base reward is the change
//! of the distance to the goal, scaled by k_base,
//!
//! r_b^t = k_base · (D^{t−1} − D^t),   D^t = ‖G − C^t‖,
//!
//! positive when the trunk moves towards the goal and negative when it moves away. The printed
//! eq. (2), r_b^t = |C^t − C^{t−1}|, is the distance travelled in any direction and rewards
//! walking away from the goal (kept in [`crate::printed::base_reward`] to show why). Unset
//! `base_rew_scaling` turns r_b off (r_b = 0). Over an episode Σ r_b = k_base · (D^0 − D^T).

/// r_b = k_base · (D^{t−1} − D^t) for the distances to the goal before (`d_prev`) and after
/// (`d`) the step, in metres.
pub fn base_reward(d_prev: f64, d: f64, k_base: f64) -> f64 {
    k_base * (d_prev - d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_is_rewarded_and_retreat_punished() {
        assert_eq!(base_reward(5.0, 4.5, 2.0), 1.0);
        assert_eq!(base_reward(4.5, 5.0, 2.0), -1.0);
        assert_eq!(base_reward(4.5, 4.5, 2.0), 0.0);
    }
}
