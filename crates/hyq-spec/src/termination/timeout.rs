//! Spec §6.4 (Timeout): the episode times out when
//!
//! t ≥ t_max,
//!
//! t the number of env steps taken since reset (1 after the first step), t_max
//! `max_time_steps`. With t_max = 1 the episode ends after its first step. No reward or penalty
//! goes with it; it is Gymnasium's truncation, not termination.

/// Whether `step` (t, env steps since reset) has reached `max_time_steps` (t_max).
pub fn timed_out(step: u64, max_time_steps: u64) -> bool {
    step >= max_time_steps
}
