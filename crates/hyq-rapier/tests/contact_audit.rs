//! The contact audit (hyq-conformance's `contact_audit`) on rapier, on the feet of both
//! bundled robots: rapier meets every rigid-body Coulomb answer within the stated tolerance.
//! Its contact is a soft constraint, but at the project's 240 Hz it sinks a loaded foot only
//! g/ω² = 4.3 µm, and rapier caps each contact's friction impulse by its magnitude (a round
//! cone), so sliding does not depend on its direction.
//!
//! `cargo test -p hyq-rapier --test contact_audit -- --nocapture` prints the figures that
//! docs/backend-comparison.md ("Contact audit") quotes.

use hyq_conformance::contact_audit::Expect;
use hyq_conformance::fixtures::Robot;

/// The tolerances every engine is held to where it meets the physics answer, each the size
/// of what a first-order integrator at 1 ms and a detection threshold leave: creep 0.01 mm/s
/// (1 cm in a quarter of an hour), sliding acceleration 2 %, breakaway force 2 % of μN,
/// bounce 0.05 mm, penetration 0.01 mm, spin torque 0.1 mN·m, spin-down 0.5 rad/s² (2 %).
macro_rules! rapier_audit {
    ($robot:expr) => {
        hyq_conformance::contact_audit_tests!(
            hyq_rapier::RapierBackend,
            hyq_rapier::RapierOptions::default(),
            $robot,
            {
                sled_sticks_below_atan_mu => Expect::Physics { tolerance: 0.01 },
                sled_slides_above_atan_mu => Expect::Physics { tolerance: 0.02 },
                sled_slides_along_the_diagonal => Expect::Physics { tolerance: 0.02 },
                sled_breaks_away_at_mu_n => Expect::Physics { tolerance: 0.02 },
                sled_breaks_away_along_the_diagonal => Expect::Physics { tolerance: 0.02 },
                dropped_foot_does_not_bounce => Expect::Physics { tolerance: 0.05 },
                foot_at_rest_does_not_penetrate => Expect::Physics { tolerance: 0.01 },
                loaded_foot_spins_freely => Expect::Physics { tolerance: 1e-4 },
                sled_spin_slows_at_mu_n_d => Expect::Physics { tolerance: 0.5 },
            }
        );
    };
}

mod hyq {
    use super::*;
    rapier_audit!(Robot::bundled("hyq"));
}

mod anymal_c {
    use super::*;
    rapier_audit!(Robot::bundled("anymal_c"));
}

/// Prints the audit's rows (robot, figure, unit, physics, rapier) for the docs' table.
#[test]
fn prints_the_contact_audit_table() {
    hyq_conformance::contact_audit::print_table::<hyq_rapier::RapierBackend>(&[(
        "",
        Default::default(),
    )]);
}

/// The audit notices a softer contact: at rapier's own 60 Hz ground contact (the project uses
/// 240 Hz) a loaded foot sinks g/ω² = 0.069 mm, beyond the 0.01 mm the audit allows.
#[test]
fn a_softer_contact_fails_the_penetration_audit() {
    let options = hyq_rapier::RapierOptions {
        ground_contact_frequency: 60.0,
        ..Default::default()
    };
    let figure = hyq_conformance::contact_audit::foot_at_rest_does_not_penetrate::<
        hyq_rapier::RapierBackend,
    >(&Robot::bundled("hyq"), &options);
    assert!(
        figure.measured > 0.05,
        "a 60 Hz contact sank only {:.4} mm",
        figure.measured
    );
}

/// `randomize.contact_stiffness_scale` on rapier (the contact spring's natural frequency times
/// √s): a stiffer contact sinks the loaded foot less, a softer one more, as k = m ω² says
/// (the sinking g/ω² goes as 1/s).
#[test]
fn a_stiffer_contact_penetrates_less_at_rest() {
    hyq_conformance::contact_audit::assert_stiffness_scales_penetration::<hyq_rapier::RapierBackend>(
        &Robot::bundled("hyq"),
        &Default::default(),
    );
}

/// `randomize.restitution` on rapier (every collider's coefficient, which rapier averages):
/// none gives no bounce, 0.5 bounces the foot dropped 20 cm e² h = 5 cm (within 10 %).
#[test]
fn restitution_raises_the_bounce() {
    hyq_conformance::contact_audit::assert_restitution_raises_the_bounce::<hyq_rapier::RapierBackend>(
        &Robot::bundled("hyq"),
        &Default::default(),
    );
}
