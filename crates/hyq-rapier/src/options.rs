//! The rapier-specific settings, `[physics.rapier]` in an environment's TOML.

use hyq_physics::PhysicsError;
use serde::{Deserialize, Serialize};

/// rapier-specific settings (`[physics.rapier]` in an environment's TOML).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RapierOptions {
    /// Internal solver substeps per physics step (rapier's `num_solver_iterations`)
    /// (default: 2; rapier's own default is 4). The main cost knob: a HyQ sub-step costs about
    /// 310, 480 and 820 thousand instructions at 1, 2 and 4 (random targets; see the crate's
    /// README). The conformance suite passes at all three; fewer make joint limits softer under
    /// full torque (worst overshoot 0.087 rad at 1, 0.032 at 2, 0.015 at 4) and free-floating
    /// momentum drift larger (5.3, 2.3, 1.4 mm in a violent second). Standing is the same at 1
    /// to 4.
    pub solver_iterations: usize,
    /// Natural frequency (Hz) of the ground-contact constraint (rapier's
    /// `static_contact_softness`) (default: 240; rapier's own default is 60). A standing HyQ's
    /// feet sink 0.2–0.3 mm at 240 Hz and 3–4.5 mm at 60 Hz; at 240 Hz its trunk settles at
    /// the height DART's rigid contacts give (0.5895 m against 0.5897 m), so the engines
    /// compare.
    pub ground_contact_frequency: f64,
    /// Damping ratio of the ground-contact constraint (default: 10, rapier's).
    pub ground_contact_damping_ratio: f64,
    /// Distance (m) within which rapier creates speculative contacts
    /// (`normalized_prediction_distance`) (default: 0.02, rapier's). They keep fast feet from
    /// tunnelling; they never count as contact flags. Raised to `physics.contact_distance` when
    /// that is larger, since rapier reports no contact beyond it.
    pub prediction_distance: f64,
    /// Build the multibody's mass matrices and their factorizations once per physics sub-step,
    /// at its first internal substep, and reuse them at the later ones (rapier's
    /// `multibody_mass_matrix_once_per_step`) (default: false, rapier's: rebuilt at every
    /// internal substep). At the default 2 internal substeps it saves one of the two builds, about
    /// a fifth of a sub-step's instructions; it changes results (the second substep uses the
    /// matrices of the sub-step's start), and with it the `fall` comparison against DART leaves the
    /// ledger (return difference 1.38e-3 > 1e-3), so it is off (the crate's README, Performance).
    pub mass_matrix_once_per_step: bool,
}

impl Default for RapierOptions {
    fn default() -> Self {
        Self {
            solver_iterations: 2,
            ground_contact_frequency: 240.0,
            ground_contact_damping_ratio: 10.0,
            prediction_distance: 0.02,
            mass_matrix_once_per_step: false,
        }
    }
}

impl RapierOptions {
    /// Checks every field; the error names the first invalid one.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        let bad = |field: &'static str, value: String, reason: &'static str| {
            Err(PhysicsError::InvalidParam {
                field,
                value,
                reason,
            })
        };
        if !(1..=64).contains(&self.solver_iterations) {
            return bad(
                "rapier.solver_iterations",
                self.solver_iterations.to_string(),
                "must be in 1..=64",
            );
        }
        if !(self.ground_contact_frequency.is_finite() && self.ground_contact_frequency > 0.0) {
            return bad(
                "rapier.ground_contact_frequency",
                self.ground_contact_frequency.to_string(),
                "must be finite and positive (Hz)",
            );
        }
        if !(self.ground_contact_damping_ratio.is_finite()
            && self.ground_contact_damping_ratio > 0.0)
        {
            return bad(
                "rapier.ground_contact_damping_ratio",
                self.ground_contact_damping_ratio.to_string(),
                "must be finite and positive",
            );
        }
        if !(self.prediction_distance.is_finite() && self.prediction_distance >= 0.0) {
            return bad(
                "rapier.prediction_distance",
                self.prediction_distance.to_string(),
                "must be finite and non-negative (m)",
            );
        }
        Ok(())
    }
}
