//! The spec (`docs/spec.md`, the rules as the project implements them), section by
//! section, on the real simulators: one module per section, each test body run on every backend
//! that is built (`spec_tests::for_each_backend!`): rapier always, DART with `--features dart`.
//! Contracts about sub-steps that a real engine cannot stage exactly run on hyq-env's scripted
//! backend instead, and say so.

mod s3_observations;
mod s4_rewards;
mod s5_1_orientation;
mod s5_3_joint_limit_penalty;
mod s6_1_reach;
mod s6_3_fall;
mod s6_4_timeout;
