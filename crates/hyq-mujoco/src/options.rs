//! `[physics.mujoco]`: the MuJoCo backend's settings, and why they are what they are.

use hyq_physics::PhysicsError;
use hyq_physics::mjcf::{Cone, Integrator, MjcfError, Solver, SolverSettings};
use serde::{Deserialize, Serialize};

/// MuJoCo-specific settings (`[physics.mujoco]` in an environment's TOML). Each maps to the
/// MJCF attribute of the same name; the defaults are the project's choice, measured in the
/// crate's README (settings table).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MujocoOptions {
    /// Integrator: `"euler"` (semi-implicit Euler, joint damping implicit) or `"implicitfast"`
    /// (default: euler, MuJoCo's).
    pub integrator: Integrator,
    /// Friction cone: `"pyramidal"` or `"elliptic"` (default: pyramidal, MuJoCo's).
    pub cone: Cone,
    /// Ratio of frictional to normal impedance, ≥ 1 (default: 1, MuJoCo's).
    pub impratio: f64,
    /// Constraint solver: `"newton"`, `"cg"` or `"pgs"` (default: newton, MuJoCo's).
    pub solver: Solver,
    /// Maximum solver iterations per step (default: 100, MuJoCo's).
    pub iterations: u32,
    /// Maximum line-search iterations (default: 50, MuJoCo's).
    pub ls_iterations: u32,
    /// Solver tolerance (default: 1e-8, MuJoCo's).
    pub tolerance: f64,
    /// No-slip post-solver iterations; 0 is off (default: 10; MuJoCo's is 0). Without it a
    /// standing HyQ's feet creep 6 mm in 9 s (14.9 mm with the stiff contacts below).
    pub noslip_iterations: u32,
    /// Ground-contact softness: time constant (s) and damping ratio (default: [0.002, 1]; MuJoCo's
    /// is [0.02, 1], at which a standing HyQ's feet sink 2.5 mm). MuJoCo raises a time constant
    /// below two time steps to two time steps.
    pub contact_solref: [f64; 2],
    /// Ground-contact impedance curve: d0, d_width, width (m), midpoint, power (default:
    /// [0.9, 0.95, 0.001, 0.5, 2], MuJoCo's).
    pub contact_solimp: [f64; 5],
    /// Joint-limit softness: time constant (s) and damping ratio (default: [0.002, 1]; MuJoCo's
    /// is [0.02, 1], at which joints driven at full torque overshoot their limits by 0.36 rad).
    pub limit_solref: [f64; 2],
    /// Joint-limit impedance curve (default: [0.9, 0.95, 0.001, 0.5, 2], MuJoCo's).
    pub limit_solimp: [f64; 5],
}

impl Default for MujocoOptions {
    /// MuJoCo's own defaults except three, each measured in the crate's README: stiff ground
    /// contacts and joint limits (time constant 2 ms, the shortest MuJoCo accepts at a 1 ms
    /// step) and 10 no-slip iterations, so that HyQ stands where the rigid-contact engines put
    /// it, does not creep, and its joints overshoot their limits no more than on rapier.
    fn default() -> Self {
        let s = SolverSettings::default();
        Self {
            integrator: s.integrator,
            cone: s.cone,
            impratio: s.impratio,
            solver: s.solver,
            iterations: s.iterations,
            ls_iterations: s.ls_iterations,
            tolerance: s.tolerance,
            noslip_iterations: 10,
            contact_solref: [0.002, 1.0],
            contact_solimp: s.contact_solimp,
            limit_solref: [0.002, 1.0],
            limit_solimp: s.limit_solimp,
        }
    }
}

impl MujocoOptions {
    /// The settings as the MJCF generator takes them.
    pub fn solver_settings(&self) -> SolverSettings {
        SolverSettings {
            integrator: self.integrator,
            cone: self.cone,
            impratio: self.impratio,
            solver: self.solver,
            iterations: self.iterations,
            ls_iterations: self.ls_iterations,
            tolerance: self.tolerance,
            noslip_iterations: self.noslip_iterations,
            contact_solref: self.contact_solref,
            contact_solimp: self.contact_solimp,
            limit_solref: self.limit_solref,
            limit_solimp: self.limit_solimp,
        }
    }

    /// Checks every field; the error names the first invalid one (`mujoco.<field>`).
    pub fn validate(&self) -> Result<(), PhysicsError> {
        self.solver_settings().validate().map_err(|e| match e {
            MjcfError::InvalidOption {
                field,
                value,
                reason,
            } => PhysicsError::InvalidParam {
                field: table_key(field),
                value,
                reason,
            },
            other => PhysicsError::Backend {
                backend: "mujoco",
                message: other.to_string(),
            },
        })
    }
}

/// `field` of [`SolverSettings`] as a key of `[physics.mujoco]`.
fn table_key(field: &'static str) -> &'static str {
    match field {
        "impratio" => "mujoco.impratio",
        "iterations" => "mujoco.iterations",
        "ls_iterations" => "mujoco.ls_iterations",
        "tolerance" => "mujoco.tolerance",
        "contact_solref" => "mujoco.contact_solref",
        "contact_solimp" => "mujoco.contact_solimp",
        "limit_solref" => "mujoco.limit_solref",
        "limit_solimp" => "mujoco.limit_solimp",
        other => other,
    }
}

#[cfg(test)]
mod tests {
    //! `[physics.mujoco]` parses from TOML: empty is the default, enums by their lowercase
    //! names, unknown keys and invalid values refused by name.
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn options_parse_from_toml_and_reject_unknown_keys() {
        assert_eq!(
            toml::from_str::<MujocoOptions>("").unwrap(),
            MujocoOptions::default()
        );
        let o: MujocoOptions =
            toml::from_str("cone = \"elliptic\"\nintegrator = \"implicitfast\"\nsolver = \"cg\"")
                .unwrap();
        assert_eq!(
            (o.cone, o.integrator, o.solver),
            (Cone::Elliptic, Integrator::Implicitfast, Solver::Cg)
        );
        let err = toml::from_str::<MujocoOptions>("timestep = 0.002")
            .unwrap_err()
            .to_string();
        assert!(err.contains("timestep"), "{err}");
        let err = toml::from_str::<MujocoOptions>("cone = \"round\"")
            .unwrap_err()
            .to_string();
        assert!(err.contains("round"), "{err}");
    }

    #[test]
    fn invalid_values_name_their_key() {
        let o = MujocoOptions {
            impratio: 0.0,
            ..MujocoOptions::default()
        };
        match o.validate() {
            Err(PhysicsError::InvalidParam { field, .. }) => assert_eq!(field, "mujoco.impratio"),
            other => panic!("{other:?}"),
        }
        let o = MujocoOptions {
            contact_solref: [-0.02, 1.0],
            ..MujocoOptions::default()
        };
        match o.validate() {
            Err(PhysicsError::InvalidParam { field, .. }) => {
                assert_eq!(field, "mujoco.contact_solref");
            }
            other => panic!("{other:?}"),
        }
        assert!(MujocoOptions::default().validate().is_ok());
    }
}
