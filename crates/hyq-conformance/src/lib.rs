//! The backend conformance kit: test bodies written once, generic over any
//! [`Backend`](hyq_physics::Backend), that every physics engine of the project must pass.
//!
//! A backend crate takes this crate as a dev-dependency and runs the whole suite with one line
//! in its `tests/conformance.rs`:
//!
//! ```text
//! hyq_conformance::conformance_tests!(hyq_rapier::RapierBackend);
//! // or, with engine options:
//! hyq_conformance::conformance_tests!(hyq_rapier::RapierBackend, hyq_rapier::RapierOptions::default());
//! // or on another robot, in its own module:
//! mod anymal_c {
//!     use hyq_conformance::fixtures::Robot;
//!     hyq_conformance::conformance_tests!(
//!         hyq_rapier::RapierBackend,
//!         hyq_rapier::RapierOptions::default(),
//!         Robot::bundled("anymal_c")
//!     );
//! }
//! ```
//!
//! Every test takes the robot ([`fixtures::Robot`], the bundled HyQ by default) and derives its
//! numbers from the model, the URDF text or physics, never from a particular engine or robot: a
//! second engine or robot passes the suite unchanged or has a real difference to explain. Where
//! a check depends on a robot property (a damped joint, how a limp robot comes to rest), the
//! test derives what to check from the model and says what it checked; nothing is skipped.
//!
//! Each `pub fn` below states the invariant it checks. Tolerances are stated where they are
//! used, with the reason for their size.
//!
//! The suite is split like the concerns it checks: `kinematics.rs`, `contacts.rs`,
//! `dynamics.rs`, `randomization.rs` (randomised dynamics, pushes, the actuator's scales and
//! delay) and `api_contract.rs` hold the tests; [`fixtures`] the shared helpers (also used by
//! the backends' own tests, benches and examples); `independent_fk.rs` a hand-written reading of
//! the URDF for the forward-kinematics test.
//!
//! The terrain tests ([`terrain`]: a ball and a block on height fields, the robot on a slope
//! and across a stair edge, changes of ground) have a macro of their own,
//! `terrain_conformance_tests!`, which each backend instantiates once, beside the suite.
//!
//! A robot on which some checks do not hold on an engine (Go1 at MuJoCo Playground's soft gains)
//! runs the suite through `conformance_tests_except!`, which takes the checks it leaves out with
//! the reason and figures of each, and the standing heights measured on that engine; the suite's
//! one list of tests is `__with_suite_tests!`, which both macros read.
//!
//! The contact audit ([`contact_audit`]: a sled on four of the robot's foot spheres and one
//! loaded foot, on inclines either side of atan μ, pushed sideways, dropped and spun, each
//! figure beside its rigid-body Coulomb answer) has a macro of its own,
//! `contact_audit_tests!`, which each backend instantiates per robot with what it holds each
//! figure to: the physics answer within a tolerance, or its known deviation and why.
//!
//! Beside the suite, [`determinism`] and [`threads`] hold longer runs (thousands of sub-steps
//! each, on several threads) that a backend crate calls from tests of its own
//! (`tests/determinism.rs`, `tests/threads.rs`: one `#[test]` per body, the file saying why its
//! engine keeps the contract) rather than through the macro, which runs once per robot: the
//! DART and MuJoCo crates run them on HyQ.
//!
//! The kit is a crate of its own, not a module of hyq-physics behind a cargo feature: the crate
//! that defines the trait stays one build for every user, and the kit depends on it like any
//! engine does.

/// The crate the kit tests against, re-exported for the macros (`$crate::hyq_physics::…`), so
/// a backend's test file needs no `use` of its own.
#[doc(hidden)]
pub use hyq_physics;

mod api_contract;
pub mod contact_audit;
mod contacts;
pub mod determinism;
mod dynamics;
pub mod fixtures;
pub mod go1_pair;
mod independent_fk;
mod kinematics;
mod randomization;
pub mod terrain;
pub mod threads;

pub use api_contract::{
    divergence_is_reported_and_recoverable, invalid_params_are_rejected,
    non_finite_inputs_are_rejected, reset_restores_trajectory_bitwise,
    same_inputs_give_bitwise_identical_trajectories, wrong_length_inputs_are_errors,
};
pub use contacts::{
    free_fall_matches_ballistic_until_contact, lifted_foot_reports_no_contact,
    limp_robot_collapses_onto_its_trunk, standing_heights, stands_in_nominal_pose_for_10_s,
};
pub use dynamics::{
    internal_torques_conserve_momentum, joint_damping_is_applied,
    joint_limits_hold_under_full_torque, velocity_limit_bounds_joint_speed,
};
pub use kinematics::{
    forward_kinematics_matches_independent_urdf_computation,
    joint_velocities_match_finite_differences, set_state_round_trips,
    state_read_back_continues_the_trajectory, total_mass_matches_urdf,
    trunk_velocity_is_the_frame_origin_velocity,
};
pub use randomization::{
    a_trunk_push_adds_to_its_velocity, actuator_delay_shifts_the_torque_trace_by_exactly_k,
    actuator_scales_scale_the_pd_torque, added_trunk_mass_lowers_the_standing_height,
    in_place_dynamics_match_a_world_built_with_them,
    lower_ground_friction_lets_a_pushed_robot_slide_further, unphysical_dynamics_are_refused,
};

pub use terrain::{
    a_new_ground_keeps_the_worlds_dynamics, ball_rests_on_rough_ground_at_the_grids_height,
    contacts_follow_the_grids_triangles, limp_robot_lands_its_trunk_on_rough_ground,
    robot_stands_across_a_stair_edge, robot_stands_on_a_10_degree_slope,
    terrain_changes_keep_the_state_and_reset_bitwise, the_fields_friction_is_the_ground_friction,
};

/// Instantiates the terrain tests ([`terrain`]) for a backend type, as `#[test]` functions in
/// the calling module, with the same three forms as [`conformance_tests!`] (backend; options;
/// robot). Their loose-shape tests bring their own probe robots, so one instantiation per
/// backend (on the bundled HyQ) covers them; the standing tests use the robot given.
#[macro_export]
macro_rules! terrain_conformance_tests {
    ($backend:ty) => {
        $crate::terrain_conformance_tests!(
            $backend,
            <$backend as $crate::hyq_physics::Backend>::Options::default()
        );
    };
    ($backend:ty, $options:expr) => {
        $crate::terrain_conformance_tests!(
            $backend,
            $options,
            $crate::fixtures::Robot::bundled($crate::hyq_physics::bundled::DEFAULT)
        );
    };
    ($backend:ty, $options:expr, $robot:expr) => {
        $crate::conformance_tests!(@each $backend, $options, $robot,
            ball_rests_on_rough_ground_at_the_grids_height,
            contacts_follow_the_grids_triangles,
            the_fields_friction_is_the_ground_friction,
            robot_stands_on_a_10_degree_slope,
            robot_stands_across_a_stair_edge,
            limp_robot_lands_its_trunk_on_rough_ground,
            terrain_changes_keep_the_state_and_reset_bitwise,
            a_new_ground_keeps_the_worlds_dynamics,
        );
    };
}

/// Instantiates every conformance test for a backend type, as `#[test]` functions in the
/// calling module:
///
/// - `conformance_tests!(Backend)`: the bundled HyQ with the backend's default options;
/// - `conformance_tests!(Backend, options)`: with engine options (an expression of the
///   backend's `Options` type, evaluated per test);
/// - `conformance_tests!(Backend, options, robot)`: on another robot, an expression of type
///   [`fixtures::Robot`] (e.g. `Robot::bundled("anymal_c")`, `Robot::from_profile(path)`),
///   evaluated per test.
///
/// Each test calls `hyq_conformance::<test>::<Backend>(&robot, &options)`; to run the
/// suite on two robots, instantiate it in two modules.
#[macro_export]
macro_rules! conformance_tests {
    ($backend:ty) => {
        $crate::conformance_tests!($backend, <$backend as $crate::hyq_physics::Backend>::Options::default());
    };
    ($backend:ty, $options:expr) => {
        $crate::conformance_tests!(
            $backend,
            $options,
            $crate::fixtures::Robot::bundled($crate::hyq_physics::bundled::DEFAULT)
        );
    };
    ($backend:ty, $options:expr, $robot:expr) => {
        $crate::__with_suite_tests!($crate::conformance_tests; @each $backend, $options, $robot,);
    };
    (@each $backend:ty, $options:expr, $robot:expr, $($name:ident),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                let options = $options;
                let robot = $robot;
                $crate::$name::<$backend>(&robot, &options);
            }
        )*
    };
}

/// The one list of the suite's tests: `__with_suite_tests!(MACRO; TOKENS)` calls `MACRO` (a
/// path) with `TOKENS` followed by every test's name, comma-separated. [`conformance_tests!`],
/// [`conformance_tests_except!`] and [`SUITE_TESTS`] read it, so a test is listed once.
#[doc(hidden)]
#[macro_export]
macro_rules! __with_suite_tests {
    ($($m:tt)::+ ; $($prefix:tt)*) => {
        $($m)::+! { $($prefix)*
            total_mass_matches_urdf,
            forward_kinematics_matches_independent_urdf_computation,
            set_state_round_trips,
            free_fall_matches_ballistic_until_contact,
            stands_in_nominal_pose_for_10_s,
            limp_robot_collapses_onto_its_trunk,
            joint_limits_hold_under_full_torque,
            lifted_foot_reports_no_contact,
            same_inputs_give_bitwise_identical_trajectories,
            reset_restores_trajectory_bitwise,
            internal_torques_conserve_momentum,
            trunk_velocity_is_the_frame_origin_velocity,
            joint_velocities_match_finite_differences,
            state_read_back_continues_the_trajectory,
            velocity_limit_bounds_joint_speed,
            joint_damping_is_applied,
            invalid_params_are_rejected,
            wrong_length_inputs_are_errors,
            non_finite_inputs_are_rejected,
            divergence_is_reported_and_recoverable,
            added_trunk_mass_lowers_the_standing_height,
            in_place_dynamics_match_a_world_built_with_them,
            lower_ground_friction_lets_a_pushed_robot_slide_further,
            a_trunk_push_adds_to_its_velocity,
            actuator_delay_shifts_the_torque_trace_by_exactly_k,
            actuator_scales_scale_the_pd_torque,
            unphysical_dynamics_are_refused,
        }
    };
}

/// The names as strings, for [`SUITE_TESTS`].
macro_rules! names {
    ($($name:ident),* $(,)?) => {
        &[$(stringify!($name)),*]
    };
}

/// The names of the suite's tests, in the order [`conformance_tests!`] instantiates them.
pub const SUITE_TESTS: &[&str] = __with_suite_tests!(names;);

/// Instantiates the conformance suite on one robot and engine, leaving out the checks named in
/// `left_out`, each with the reason and the figures why it does not hold there, and adds two
/// tests: one that every check left out is a test of the suite with a reason (a misspelt name
/// would leave out nothing), and one that the robot stands where this engine was measured to
/// hold it (the trunk frame's height 1 s and 10 s after spawn at the standing pose under the
/// default gains, within 0.5 mm) and within 5 mm of its profile's standing height. The suite's
/// tests are in a module `suite`, as `conformance_tests!` in a module would put them.
///
/// ```text
/// hyq_conformance::conformance_tests_except! {
///     engine: hyq_mujoco::MujocoBackend,
///     robot: go1(),
///     standing_m: (0.26293, 0.26543),
///     left_out: {
///         internal_torques_conserve_momentum => "13.3 mm off the line, 10 allowed: ...",
///     },
/// }
/// ```
///
/// `engine` is the backend type as a path from a crate root (its default options); `robot` a
/// function of the calling module returning a [`fixtures::Robot`], called per test.
#[macro_export]
macro_rules! conformance_tests_except {
    (
        engine: $backend:ty,
        robot: $robot:ident (),
        standing_m: ($at_1s:expr, $at_10s:expr),
        left_out: { $($left_out:ident => $why:literal),* $(,)? } $(,)?
    ) => {
        $crate::conformance_tests_except!(@with ($) $backend, $robot, ($at_1s, $at_10s),
            [$($left_out => $why),*]);
    };
    (@with ($d:tt) $backend:ty, $robot:ident, ($at_1s:expr, $at_10s:expr),
        [$($left_out:ident => $why:literal),*]) => {
        /// The suite's tests on this engine and robot, but the checks left out.
        mod suite {
            type Engine = $backend;
            macro_rules! each_test {
                $( (@one $left_out) => {}; )*
                (@one $d name:ident) => {
                    #[test]
                    fn $d name() {
                        let options =
                            <Engine as $crate::hyq_physics::Backend>::Options::default();
                        $crate::$d name::<Engine>(&super::$robot(), &options);
                    }
                };
                ($d ($d name:ident),* $d (,)?) => {
                    $d (each_test!(@one $d name);)*
                };
            }
            $crate::__with_suite_tests!(each_test;);
        }

        #[test]
        fn the_checks_left_out_are_suite_tests_with_reasons() {
            for (name, why) in [$((stringify!($left_out), $why)),*] {
                assert!(
                    $crate::SUITE_TESTS.contains(&name),
                    "{name} is left out but is no test of the suite"
                );
                assert!(why.len() > 20, "{name} is left out without a reason: {why:?}");
            }
        }

        #[test]
        fn stands_where_stated_and_near_its_profile_height() {
            let robot = $robot();
            let (at_1s, at_10s) = $crate::standing_heights::<$backend>(
                &robot,
                &<$backend as $crate::hyq_physics::Backend>::Options::default(),
            );
            println!(
                "{} {} standing: {at_1s:.5} m at 1 s, {at_10s:.5} m at 10 s",
                <$backend as $crate::hyq_physics::Backend>::NAME,
                robot.model.name()
            );
            assert!((at_1s - $at_1s).abs() < 5e-4, "{at_1s} m at 1 s");
            assert!((at_10s - $at_10s).abs() < 5e-4, "{at_10s} m at 10 s");
            let profile = robot.model.standing_height();
            assert!(
                (at_1s - profile).abs() < 5e-3,
                "{at_1s} m at 1 s, profile {profile} m"
            );
        }
    };
}
