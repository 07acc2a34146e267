//! Spec §4.4: the reach reward is the user's bonus on the step where the goal is reached (§6.1),
//!
//! r_reach = reach_target_bonus_reward if §6.1 holds at the end of the step, else 0,
//!
//! added before the penalties, so the orientation multipliers of §5.1 scale it.

/// r_reach: `bonus` when `reached`, else 0.
pub fn reach_reward(reached: bool, bonus: f64) -> f64 {
    if reached { bonus } else { 0.0 }
}
