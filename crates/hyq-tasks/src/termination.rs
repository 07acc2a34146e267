//! When the velocity task's episode ends early (besides the time limit, which is the
//! environment's `task.max_time_steps`):
//!
//! - upside down (Playground's only rule: the trunk's up axis points below the horizon,
//!   `up_z < 0`), always on; with g = Rᵀ(0, 0, −1) the projected gravity, up_z = −g_z, so the
//!   rule is g_z > 0;
//! - the trunk touched the ground (legged_gym's `terminate_after_contacts_on = [base]`), only
//!   with `velocity.terminate_on_trunk_contact = true` (off by default: whether a body
//!   touches differs between contact models, while the up axis does not).

/// Whether the trunk is upside down: its up axis below the horizon (g_z > 0).
pub fn upside_down(projected_gravity: [f64; 3]) -> bool {
    projected_gravity[2] > 0.0
}

/// Whether the step ends the episode: upside down, or the trunk touched the ground when
/// `trunk_contact_ends`.
pub fn terminated(
    projected_gravity: [f64; 3],
    trunk_contact: bool,
    trunk_contact_ends: bool,
) -> bool {
    upside_down(projected_gravity) || (trunk_contact_ends && trunk_contact)
}
