//! The field's robots from example-robot-data 6.0.0 (`assets/{a1,go1_urdf,anymal_b,laikago}/`,
//! loaded from their profiles as a user's robot is) pass the backend conformance suite on
//! rapier, but the checks left out below (each with its reason and figures), and stand where
//! their profiles say: each module states the trunk frame's height 1 s and 10 s after spawn as
//! measured on this engine (within 0.5 mm), within 5 mm of the profile's standing height.
//! `docs/adding-a-robot.md` ("Robots tried") tabulates the figures of every engine.

use std::path::PathBuf;

use hyq_conformance::fixtures::Robot;

/// The robot of the profile `profile.toml` in `assets/NAME`.
fn asset(name: &str) -> Robot {
    Robot::from_profile(
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets")
            .join(name)
            .join("profile.toml"),
    )
}

/// Unitree A1.
mod a1 {
    use hyq_conformance::fixtures::Robot;

    fn a1() -> Robot {
        super::asset("a1")
    }

    hyq_conformance::conformance_tests_except! {
        engine: hyq_rapier::RapierBackend,
        robot: a1(),
        standing_m: (0.25533, 0.25485),
        left_out: {
            added_trunk_mass_lowers_the_standing_height => "calibrated on the 50-90 kg robots: a fixed +10 kg is 73 % of Unitree A1's 13.7 kg, beyond the kit's linear statics: it sinks 9.04 mm where the statics predicts 5.59 mm (within 5 % asked)",
        },
    }
}

/// Unitree Go1 from its URDF.
mod go1_urdf {
    use hyq_conformance::fixtures::Robot;

    fn go1_urdf() -> Robot {
        super::asset("go1_urdf")
    }

    hyq_conformance::conformance_tests_except! {
        engine: hyq_rapier::RapierBackend,
        robot: go1_urdf(),
        standing_m: (0.26128, 0.26132),
        left_out: {
            added_trunk_mass_lowers_the_standing_height => "calibrated on the 50-90 kg robots: a fixed +10 kg is 76 % of Unitree Go1's 13.1 kg, beyond the kit's linear statics: it sinks 11.90 mm where the statics predicts 6.71 mm (within 5 % asked)",
            velocity_limit_bounds_joint_speed => "the rule holds the speeds (99th percentile 1.55 of the limit, 2 allowed), but without it the percentile is 2.21, 1.43 times, where the check asks 1.5: this robot's high URDF speed limits are seldom what bounds its joints",
        },
    }
}

/// ANYbotics ANYmal B.
mod anymal_b {
    use hyq_conformance::fixtures::Robot;

    fn anymal_b() -> Robot {
        super::asset("anymal_b")
    }

    hyq_conformance::conformance_tests_except! {
        engine: hyq_rapier::RapierBackend,
        robot: anymal_b(),
        standing_m: (0.48470, 0.48470),
        left_out: {
            trunk_velocity_is_the_frame_origin_velocity => "tumbling freely with no torque, the trunk velocity jumps within one 1 ms step late in the 0.3 s run (step 265: 0.126 to 0.182 m/s, finite difference 0.206 m/s), which a smooth flight does not do: a leg reaching its stop (with every range widened to +-3 rad the check passes); DART and MuJoCo pass",
        },
    }
}

/// Unitree Laikago.
mod laikago {
    use hyq_conformance::fixtures::Robot;

    fn laikago() -> Robot {
        super::asset("laikago")
    }

    hyq_conformance::conformance_tests_except! {
        engine: hyq_rapier::RapierBackend,
        robot: laikago(),
        standing_m: (0.31637, 0.31732),
        left_out: {
            added_trunk_mass_lowers_the_standing_height => "calibrated on the 50-90 kg robots: a fixed +10 kg is 39 % of Unitree Laikago's 25.4 kg, beyond the kit's linear statics: it sinks 7.81 mm where the statics predicts 4.46 mm (within 5 % asked)",
            velocity_limit_bounds_joint_speed => "the rule holds the speeds (99th percentile 1.32 of the limit, 2 allowed), but without it the percentile is 1.71, 1.30 times, where the check asks 1.5: this robot's high URDF speed limits are seldom what bounds its joints",
            in_place_dynamics_match_a_world_built_with_them => "rapier holds a body's tensor as f32 principal moments and axes; the calf's two near-equal moments (8.33e-3 and 8.35e-3 kg m2, 0.2 % apart) make the f32 axes ill-conditioned, so the tensor reads back 1.3e-5 off relative where the check allows 1e-5 (DART and MuJoCo pass)",
        },
    }
}

/// Go1 from Unitree's URDF (`assets/go1_urdf/`) against Go1 from Playground's MJCF
/// (`assets/go1/`), both at the MJCF profile's pose, spawn and gains (its profile pointed at the
/// URDF: `urdf`, `trunk` and the feet renamed): as given they stand 6.5 mm apart at 1 s and
/// 12.8 mm at 10 s on this engine, because the files differ (foot spheres r 0.020 against
/// 0.023 m; joint damping 0.01 against 0.5 N m s/rad and Coulomb friction 0.2 against 0.3 / 0.3 /
/// 1.0 N m; the URDF's trunk carries the four hip rotors, 0.357 kg, that the MJCF leaves out:
/// `crates/hyq-formats/tests/go1_mjcf_and_urdf.rs`). Given the MJCF's feet and joint dynamics,
/// the URDF stands within 2 mm of the MJCF (-1.4 mm at 1 s, -1.1 mm at 10 s: the rotors'
/// 2.8 % of the weight, at kp 35, sags it about 1 mm).
mod go1_mjcf_and_urdf {
    hyq_conformance::go1_mjcf_and_urdf_tests! {
        engine: hyq_rapier::RapierBackend,
        as_given_mm: (-6.5, -13.0),
    }
}
