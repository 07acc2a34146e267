//! Spec §4, eq. (1): the reward of one env step before penalties is the sum of four terms,
//!
//! r = r_b + r_n + r_e + r_reach,
//!
//! the base reward ([`base`], §4.1), the normalised reward ([`normalised`], §4.2), the
//! exponential reward ([`exponential`], §4.3) and the reach bonus ([`reach`], §4.4). A term
//! whose scaling is unset in [`crate::TaskConfig`] is 0. The penalties of §5 apply afterwards
//! (see [`crate::penalty`]).

pub mod base;
pub mod exponential;
pub mod normalised;
pub mod reach;

/// Eq. (1): r = r_b + r_n + r_e + r_reach, summed left to right in that order (the order
/// [`crate::RewardBreakdown::compose`] uses, so that the two agree to the bit).
pub fn reward_before_penalties(r_b: f64, r_n: f64, r_e: f64, r_reach: f64) -> f64 {
    r_b + r_n + r_e + r_reach
}
