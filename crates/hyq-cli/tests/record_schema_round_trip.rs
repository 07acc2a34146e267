//! Invariant: `hyq run --record FILE` writes one JSON object per env step in hyq-env's
//! `StepRecord` schema, with exactly the documented keys, and full f64 precision: every line
//! reads back as a `StepRecord` (unknown keys are errors) and writes out again to the same
//! bytes; `t` counts 1, 2, … within each episode, only an episode's last record is done, and
//! the records agree with the run's summary (the robot, steps per episode, return = Σ reward).

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, scratch};
use hyq_env::StepRecord;
use serde_json::Value;

const KEYS: [&str; 17] = [
    "robot",
    "episode",
    "t",
    "obs",
    "action",
    "joint_targets",
    "reward",
    "terms",
    "yaw",
    "pitch",
    "distance_to_goal",
    "d_n",
    "goal",
    "initial_position",
    "terminated",
    "truncated",
    "reasons",
];
const TERMS: [&str; 8] = [
    "r_b",
    "r_n",
    "r_e",
    "r_reach",
    "m_yaw",
    "m_pitch",
    "joint_penalty",
    "fall_penalty",
];

#[test]
fn every_step_is_one_record_that_round_trips_bit_for_bit() {
    let path = scratch("round_trip.jsonl");
    let summary = hyq_ok(&[
        "run",
        "--policy",
        "random",
        "--episodes",
        "2",
        "--seed",
        "5",
        "--json",
        "--set",
        "task.max_time_steps=30",
        "--set",
        "task.norm_rew_scaling=10",
        "--record",
        path.to_str().unwrap(),
    ]);
    let summaries: Vec<Value> = summary
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let text = std::fs::read_to_string(&path).unwrap();
    let mut per_episode = vec![(0u64, 0.0f64); 2];
    let mut expected_t = 0;
    let mut previous_episode = 0;
    for line in text.lines() {
        let value: Value = serde_json::from_str(line).unwrap();
        let object = value.as_object().unwrap();
        let mut keys: Vec<&str> = object.keys().map(String::as_str).collect();
        keys.sort_unstable();
        let mut want = KEYS.to_vec();
        want.sort_unstable();
        assert_eq!(keys, want, "{line}");
        let mut terms: Vec<&str> = object["terms"]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        terms.sort_unstable();
        let mut want = TERMS.to_vec();
        want.sort_unstable();
        assert_eq!(terms, want);

        let record = StepRecord::from_json_line(line).unwrap_or_else(|e| panic!("{e}: {line}"));
        assert_eq!(
            record.to_json_line(),
            line,
            "full precision: the same bytes back"
        );
        assert_eq!(
            record.robot.as_deref(),
            summaries[0]["robot"].as_str(),
            "the record names the summary's robot"
        );
        assert_eq!(
            (
                record.obs.len(),
                record.action.len(),
                record.joint_targets.len()
            ),
            (39, 12, 12)
        );
        if record.episode != previous_episode {
            previous_episode = record.episode;
            expected_t = 0;
        }
        expected_t += 1;
        assert_eq!(record.t, expected_t);
        let done = record.terminated || record.truncated;
        assert_eq!(done, !record.reasons.is_empty());
        let slot = &mut per_episode[(record.episode - 1) as usize];
        slot.0 = record.t;
        slot.1 += record.reward;
    }
    for (s, (steps, ret)) in summaries.iter().zip(&per_episode) {
        assert_eq!(s["steps"].as_u64(), Some(*steps));
        assert_eq!(
            s["return"].as_f64(),
            Some(*ret),
            "the summary's return is Σ reward"
        );
    }
    let last = StepRecord::from_json_line(text.lines().last().unwrap()).unwrap();
    assert!(
        last.terminated || last.truncated,
        "the file ends with an episode's end"
    );
}
