//! Spec §5 (Penalties): penalties act after all rewards, multipliers first,
//! then fixed penalties:
//!
//! r_total = (r_b + r_n + r_e + r_reach) · m_yaw · m_pitch · m_height
//!           − reach_bounds_penalty · [§6.2 holds] − fall_penalty · [§6.3 holds]
//!
//! - [`orientation`] (§5.1): m_yaw and m_pitch, 1 within the angle limit, max(0, cos) beyond.
//! - [`height`] (§5.2, "TBD" in the spec): m_height, opt-in, 1 when off.
//! - [`fixed_penalty`] (§5.3, §5.4): the joint-limit and fall penalties, each subtracted once on
//!   the step its termination holds.

pub mod height;
pub mod orientation;

/// §5.3 / §5.4: the amount subtracted after the multipliers, `amount` on the step the
/// condition `holds`, else 0.
pub fn fixed_penalty(holds: bool, amount: f64) -> f64 {
    if holds { amount } else { 0.0 }
}
