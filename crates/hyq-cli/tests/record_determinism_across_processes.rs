//! Invariant: the same seed and the same actions give bit-identical results (the project's
//! determinism rule), across processes: two separate `hyq run` processes with the same seed,
//! policy and configuration write byte-identical JSONL records (every number in full
//! precision); a different seed gives a different record.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, scratch};

fn record(name: &str, seed: &str, policy: &str) -> Vec<u8> {
    let path = scratch(name);
    hyq_ok(&[
        "run",
        "--policy",
        policy,
        "--episodes",
        "2",
        "--seed",
        seed,
        "--set",
        "task.max_time_steps=150",
        "--set",
        "reset.joint_noise_rad=0.05",
        "--set",
        "goal.mode=random",
        "--record",
        path.to_str().unwrap(),
    ]);
    std::fs::read(&path).unwrap()
}

#[test]
fn two_processes_with_the_same_seed_write_identical_records() {
    for policy in ["random", "trot"] {
        let a = record(&format!("det_a_{policy}.jsonl"), "11", policy);
        let b = record(&format!("det_b_{policy}.jsonl"), "11", policy);
        assert!(!a.is_empty());
        assert_eq!(
            a.iter().filter(|c| **c == b'\n').count(),
            300,
            "{policy}: two episodes of 150 steps"
        );
        assert!(a == b, "{policy}: the two records differ");
        let c = record(&format!("det_c_{policy}.jsonl"), "12", policy);
        assert!(a != c, "{policy}: another seed, another record");
    }
}
