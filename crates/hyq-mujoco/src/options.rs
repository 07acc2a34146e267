//! `[physics.mujoco]`: the MuJoCo backend's settings ([`MujocoOptions`], defined beside the MJCF
//! generator in hyq-physics so that `hyq model --format mjcf` writes the same settings without
//! building MuJoCo), and why they are what they are (the crate's README, settings table).

pub use hyq_formats::mjcf::MujocoOptions;

#[cfg(test)]
mod tests {
    //! `[physics.mujoco]` parses from TOML: empty is the default, enums by their lowercase
    //! names, unknown keys and invalid values refused by name.
    #![allow(clippy::unwrap_used)]

    use super::*;
    use hyq_formats::mjcf::{Cone, Integrator, Solver};
    use hyq_physics::PhysicsError;

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
