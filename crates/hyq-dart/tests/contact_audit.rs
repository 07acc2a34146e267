//! The contact audit (hyq-conformance's `contact_audit`) on DART, on the feet of both bundled
//! robots. DART's contacts are rigid (an exact boxed LCP): it meets the answers that depend on
//! the normal force alone (no creep, no bounce, under a micrometre of penetration, a free
//! spin on a point contact). Its friction is not a round cone: the LCP bounds the friction
//! along two tangent directions separately (a pyramid), and DART builds those directions from
//! the contact normal, which for a sphere on the ground is tilted by rounding in a direction
//! that varies from contact to contact. So the friction a sliding foot feels lies between μN
//! and √2 μN depending on how its direction falls in that basis: the sled sticks 5° above
//! atan μ (its effective μ there is about 1.3 μ; it slides at 40° as if μ were 0.65), breaks
//! away at about 1.2 μN whichever way it is pushed, and spins down 28 % faster than Coulomb
//! friction allows. These are the engine's nature, not a setting the project exposes
//! (docs/backend-comparison.md, "Contact audit"); the tests hold each to its measured value so
//! that a change is seen.
//!
//! `cargo test -p hyq-dart --test contact_audit -- --nocapture` prints the figures.

use hyq_conformance::contact_audit::Expect;
use hyq_conformance::fixtures::Robot;

const PYRAMID: &str = "DART's friction pyramid, its basis built from the contact normal";

mod hyq {
    use super::*;
    hyq_conformance::contact_audit_tests!(
        hyq_dart::DartBackend,
        hyq_dart::DartOptions::default(),
        Robot::bundled("hyq"),
        {
            sled_sticks_below_atan_mu => Expect::Physics { tolerance: 0.01 },
            sled_slides_above_atan_mu =>
                Expect::Deviates { value: 0.0, tolerance: 0.02, why: PYRAMID },
            sled_slides_along_the_diagonal =>
                Expect::Deviates { value: 0.058, tolerance: 0.02, why: PYRAMID },
            sled_breaks_away_at_mu_n =>
                Expect::Deviates { value: 1.259, tolerance: 0.02, why: PYRAMID },
            sled_breaks_away_along_the_diagonal =>
                Expect::Deviates { value: 1.223, tolerance: 0.02, why: PYRAMID },
            dropped_foot_does_not_bounce => Expect::Physics { tolerance: 0.05 },
            foot_at_rest_does_not_penetrate => Expect::Physics { tolerance: 0.01 },
            loaded_foot_spins_freely => Expect::Physics { tolerance: 1e-4 },
            sled_spin_slows_at_mu_n_d =>
                Expect::Deviates { value: 29.56, tolerance: 0.3, why: PYRAMID },
        }
    );
}

mod anymal_c {
    use super::*;
    hyq_conformance::contact_audit_tests!(
        hyq_dart::DartBackend,
        hyq_dart::DartOptions::default(),
        Robot::bundled("anymal_c"),
        {
            sled_sticks_below_atan_mu => Expect::Physics { tolerance: 0.01 },
            sled_slides_above_atan_mu =>
                Expect::Deviates { value: 0.0, tolerance: 0.02, why: PYRAMID },
            sled_slides_along_the_diagonal =>
                Expect::Deviates { value: 0.0, tolerance: 0.02, why: PYRAMID },
            sled_breaks_away_at_mu_n =>
                Expect::Deviates { value: 1.216, tolerance: 0.02, why: PYRAMID },
            sled_breaks_away_along_the_diagonal =>
                Expect::Deviates { value: 1.188, tolerance: 0.02, why: PYRAMID },
            dropped_foot_does_not_bounce => Expect::Physics { tolerance: 0.05 },
            foot_at_rest_does_not_penetrate => Expect::Physics { tolerance: 0.01 },
            loaded_foot_spins_freely => Expect::Physics { tolerance: 1e-4 },
            sled_spin_slows_at_mu_n_d =>
                Expect::Deviates { value: 29.84, tolerance: 0.3, why: PYRAMID },
        }
    );
}

/// Prints the audit's rows (robot, figure, unit, physics, DART) for the docs' table.
#[test]
fn prints_the_contact_audit_table() {
    for name in ["hyq", "anymal_c"] {
        let rows = hyq_conformance::contact_audit::table::<hyq_dart::DartBackend>(
            &Robot::bundled(name),
            &Default::default(),
        );
        for r in &rows {
            println!("{r}");
        }
        assert_eq!(rows.len(), 9, "one row per audit");
    }
}
