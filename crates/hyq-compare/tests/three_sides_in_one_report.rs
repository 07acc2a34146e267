//! Invariant: three backends compare in one report. Every side runs the plan once, every pair
//! is compared as a two-backend comparison is (the pair of identical sides agrees exactly, the
//! pairs with the perturbed side are flagged), the report sets the sides and the pairs side by
//! side and names the robot, and writing it leaves the top-level report, its plot with every
//! side's trace, and each pair's full report in its own directory. A robot other than HyQ
//! gets its scenarios from its profile (the limit joint, the reach goal's height).

#![allow(clippy::unwrap_used)]

mod common;

use common::PERTURBED_GRAVITY;
use hyq_compare::{Ledger, Plan, Scenario, compare_all};
use hyq_rapier::RapierBackend;

#[test]
fn three_sides_give_every_pair_and_one_report() {
    let ledger = Ledger::built_in().unwrap();
    let spec = common::spec(Scenario::Stand, 0.5, 5, &[]);
    let plan = Plan::new(hyq_physics::bundled::hyq(), &spec).unwrap();
    let perturbed = vec![("physics.gravity".to_owned(), PERTURBED_GRAVITY.to_owned())];
    let mut sides = vec![
        plan.run_side::<RapierBackend>("a", &[]).unwrap(),
        plan.run_side::<RapierBackend>("b", &[]).unwrap(),
        plan.run_side::<RapierBackend>("c", &perturbed).unwrap(),
    ];
    let report = compare_all(&plan, &mut sides, &ledger).unwrap();
    assert_eq!(report.robot, "hyq");
    assert_eq!(report.sides.len(), 3);
    let pairs: Vec<[&str; 2]> = report
        .pairs
        .iter()
        .map(|p| [p.labels[0].as_str(), p.labels[1].as_str()])
        .collect();
    assert_eq!(pairs, [["a", "b"], ["a", "c"], ["b", "c"]]);
    assert_eq!(report.pairs[0].flagged, 0, "{:?}", report.pairs[0]);
    assert_eq!(report.pairs[0].trunk_position.max, 0.0);
    for p in &report.pairs[1..] {
        assert!(
            p.flagged_metrics
                .iter()
                .any(|m| m == "one_step_trunk_linvel_max_m_s"),
            "{p:?}"
        );
    }
    assert_eq!(
        report.flagged,
        report.pairs.iter().map(|p| p.flagged).sum::<usize>()
    );

    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("three-sides");
    let _ = std::fs::remove_dir_all(&dir);
    report.write(&dir, "hyq compare (test)").unwrap();
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(
        md.starts_with("# Comparison: a vs b vs c, scenario `stand`"),
        "{md}"
    );
    assert!(md.contains("Robot: `hyq`."), "{md}");
    for pair in ["a_vs_b", "a_vs_c", "b_vs_c"] {
        assert!(md.contains(pair), "{pair} not linked: {md}");
        let sub = std::fs::read_to_string(dir.join(pair).join("report.md")).unwrap();
        assert!(sub.contains("Robot: `hyq`."), "{sub}");
        assert!(dir.join(pair).join("trunk_x_z.png").is_file());
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    assert_eq!(json["pairs"].as_array().unwrap().len(), 3);
    assert_eq!(json["robot"], "hyq");
    let png = std::fs::read(dir.join("trunk_x_z.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn scenarios_take_the_robots_facts_from_its_profile() {
    let model = hyq_physics::bundled::anymal_c();
    let reach = Scenario::Reach.config(&model, 1.0).unwrap();
    let goal = reach.goal.position.unwrap();
    assert_eq!(goal[2], model.standing_height());
    assert_eq!(goal[2], 0.5341);
    let hyq = hyq_physics::bundled::hyq();
    let goal = Scenario::Reach
        .config(&hyq, 1.0)
        .unwrap()
        .goal
        .position
        .unwrap();
    assert_eq!(goal[2], hyq.standing_height());

    let j = Scenario::Limit.limit_joint(&model).unwrap();
    assert_eq!(model.joints()[j].name, "lf_hfe");
    assert!(
        Scenario::Limit.description(&model).contains("lf_hfe"),
        "{}",
        Scenario::Limit.description(&model)
    );
    // The ledger's entries were measured on HyQ: a comparison of ANYmal C names its robot and
    // its reach goal, and is held to the defaults.
    let spec = common::spec(Scenario::Limit, 0.3, 3, &[]);
    let r = hyq_compare::compare::<RapierBackend, RapierBackend>(
        model,
        &spec,
        ["rapier", "rapier (B)"],
        &Ledger::built_in().unwrap(),
    )
    .unwrap();
    assert_eq!(r.robot, "anymal_c");
    assert_eq!(r.flagged, 0, "a self-comparison agrees exactly");
}
