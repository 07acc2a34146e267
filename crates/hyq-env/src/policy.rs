//! Policies for demos, tests and benchmarks (not learned): [`Stand`] holds the standing pose,
//! [`RandomPolicy`] draws uniformly from the action space with its own seed, and [`Trot`] is a
//! scripted open-loop trot, described by the robot profile's `[gait]` table, that carries HyQ
//! (or another legged robot with such a table) forward along +x.
//!
//! Policies act in the environment's action space whatever its mode: the scripted ones think in
//! joint targets and convert them with [`ActionSpace::action_for_targets`].

use hyq_physics::{Gait, RobotModel};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use thiserror::Error;

use crate::action::ActionSpace;

/// What a policy sees at each step.
#[derive(Clone, Copy, Debug)]
pub struct PolicyInput<'a> {
    /// Env steps taken since reset (0 for the first action of an episode).
    pub t: u64,
    /// Δt_env (s): the policy's clock is `t · env_dt`.
    pub env_dt: f64,
    /// The current observation (§3 order).
    pub observation: &'a [f64],
    /// The current joint angles (rad, action order).
    pub joint_angles: &'a [f64],
    /// The robot's standing pose (rad, action order).
    pub standing: &'a [f64],
    /// The action space to act in.
    pub space: &'a ActionSpace,
}

/// A policy: observation in, action out (one value per joint, written into `action`).
pub trait Policy: Send {
    /// A short name (`"stand"`, `"random"`, `"trot"`).
    fn name(&self) -> &'static str;
    /// The action for `input`; allocates nothing.
    fn act(&mut self, input: &PolicyInput<'_>, action: &mut [f64]);
}

/// Holds the standing pose: targets = the profile's standing angles.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stand;

impl Policy for Stand {
    fn name(&self) -> &'static str {
        "stand"
    }

    fn act(&mut self, input: &PolicyInput<'_>, action: &mut [f64]) {
        input
            .space
            .action_for_targets(input.standing, input.joint_angles, action);
    }
}

/// Uniform random actions in the action space, from its own ChaCha8 stream: the same seed gives
/// the same actions, whatever the environment does.
#[derive(Clone, Debug)]
pub struct RandomPolicy {
    rng: ChaCha8Rng,
}

/// The random policy's ChaCha stream number. An environment reset with seed s draws its goals
/// from stream 0 and its reset noise from stream 1 of the same key, so a policy given the same
/// s (as `hyq run --seed s` does) must use another stream, or its actions would repeat the goal
/// draws.
const POLICY_STREAM: u64 = 2;

impl RandomPolicy {
    /// A random policy seeded with `seed` (independent of an environment's streams for the same
    /// seed).
    pub fn new(seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(POLICY_STREAM);
        Self { rng }
    }
}

impl Policy for RandomPolicy {
    fn name(&self) -> &'static str {
        "random"
    }

    fn act(&mut self, input: &PolicyInput<'_>, action: &mut [f64]) {
        for ((a, lo), hi) in action
            .iter_mut()
            .zip(input.space.low())
            .zip(input.space.high())
        {
            *a = self.rng.random_range(*lo..=*hi);
        }
    }
}

/// A robot the trot cannot drive: its profile has no `[gait]` table.
#[derive(Clone, Debug, PartialEq, Error)]
#[error(
    "the trot policy needs a [gait] table in the robot profile of {robot} (each leg's hip and \
     knee joint and phase, the frequency and amplitudes; see assets/hyq/profile.toml)"
)]
pub struct TrotError {
    /// The robot's name.
    pub robot: String,
}

/// Parameters of [`Trot`]. `Default` is HyQ's gait (its profile's `[gait]` table); a robot's
/// own are [`TrotParams::from_model`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrotParams {
    /// Gait frequency (Hz): one full cycle of both diagonal pairs.
    pub frequency_hz: f64,
    /// Hip flexion/extension swing amplitude (rad) about the standing angle.
    pub hip_amplitude: f64,
    /// Extra knee flexion (rad) at the middle of a leg's swing, lifting the foot.
    pub knee_lift: f64,
    /// Time (s) over which the gait's amplitudes ramp up from standing.
    pub ramp_s: f64,
}

impl Default for TrotParams {
    fn default() -> Self {
        Self {
            frequency_hz: 3.0,
            hip_amplitude: 0.1,
            knee_lift: 0.4,
            ramp_s: 1.0,
        }
    }
}

impl TrotParams {
    /// The parameters of `model`'s profile (`[gait]`).
    pub fn from_model(model: &RobotModel) -> Result<Self, TrotError> {
        let gait = gait_of(model)?;
        Ok(Self {
            frequency_hz: gait.frequency_hz,
            hip_amplitude: gait.hip_amplitude,
            knee_lift: gait.knee_lift,
            ramp_s: gait.ramp_s,
        })
    }
}

fn gait_of(model: &RobotModel) -> Result<&Gait, TrotError> {
    model.gait().ok_or_else(|| TrotError {
        robot: model.name().to_owned(),
    })
}

/// One leg's joints for the trot.
#[derive(Clone, Copy, Debug)]
struct LegJoints {
    hfe: usize,
    kfe: usize,
    /// The leg's phase (rad): 2π times the profile's fraction of a cycle.
    phase: f64,
    /// The sign that flexes the knee further from standing (lifting the foot).
    knee_flex: f64,
}

/// A scripted open-loop trot along +x, driven by the robot profile's `[gait]` table: each leg
/// (its hip and knee joints) swings with its phase, diagonal pairs half a cycle apart for a
/// trot. For each leg, with φ = 2π (f t + its phase) and r(t) a ramp from 0 to 1 over
/// `ramp_s`:
///
/// - hip target = standing − r · A_hip · sin φ: the foot swings forward while cos φ > 0 and
///   pushes back (stance) while cos φ < 0 (for hips whose positive angle swings the foot back,
///   as HyQ's and ANYmal C's do);
/// - knee target = standing + r · flex · A_knee · max(0, cos φ), flex the sign of the standing
///   knee angle (bending further from straight): the foot lifts during the swing only;
/// - every other joint stays at standing.
///
/// Open loop: it reads neither the observation nor the goal, so it walks straight only as far
/// as the simulation stays symmetric. Measured figures are in the crate docs.
#[derive(Clone, Debug)]
pub struct Trot {
    params: TrotParams,
    legs: Vec<LegJoints>,
    targets: Vec<f64>,
}

impl Trot {
    /// The trot for `model` with `params`; the legs come from the profile's `[gait]` table.
    pub fn new(model: &RobotModel, params: TrotParams) -> Result<Self, TrotError> {
        let gait = gait_of(model)?;
        let legs = gait
            .legs
            .iter()
            .map(|leg| LegJoints {
                hfe: leg.hip,
                kfe: leg.knee,
                phase: std::f64::consts::TAU * leg.phase,
                // Flexing bends the knee further from straight (0 rad): further from 0.
                knee_flex: if model.standing_pose()[leg.knee] < 0.0 {
                    -1.0
                } else {
                    1.0
                },
            })
            .collect();
        Ok(Self {
            params,
            legs,
            targets: model.standing_pose().to_vec(),
        })
    }

    /// The trot for `model` with its profile's parameters ([`TrotParams::from_model`]).
    pub fn from_profile(model: &RobotModel) -> Result<Self, TrotError> {
        Self::new(model, TrotParams::from_model(model)?)
    }

    /// The parameters.
    pub fn params(&self) -> &TrotParams {
        &self.params
    }

    /// The joint targets (rad) at time `time_s` after reset, from the standing pose.
    pub fn targets_at(&mut self, time_s: f64, standing: &[f64]) -> &[f64] {
        let p = &self.params;
        let ramp = if p.ramp_s > 0.0 {
            (time_s / p.ramp_s).clamp(0.0, 1.0)
        } else {
            1.0
        };
        self.targets.copy_from_slice(standing);
        for leg in &self.legs {
            let phi = std::f64::consts::TAU * p.frequency_hz * time_s + leg.phase;
            self.targets[leg.hfe] = standing[leg.hfe] - ramp * p.hip_amplitude * phi.sin();
            self.targets[leg.kfe] =
                standing[leg.kfe] + ramp * leg.knee_flex * p.knee_lift * phi.cos().max(0.0);
        }
        &self.targets
    }
}

impl Policy for Trot {
    fn name(&self) -> &'static str {
        "trot"
    }

    fn act(&mut self, input: &PolicyInput<'_>, action: &mut [f64]) {
        // The targets of the step about to run are those at its end time.
        let time_s = (input.t + 1) as f64 * input.env_dt;
        let space = input.space;
        let targets = self.targets_at(time_s, input.standing);
        space.action_for_targets(targets, input.joint_angles, action);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    /// HyQ's profile states the gait `TrotParams::default()` has always been, so front ends
    /// that pass the defaults and those that read the profile drive HyQ identically.
    #[test]
    fn hyq_profile_gait_is_the_default_trot() {
        let hyq = hyq_physics::bundled::hyq();
        assert_eq!(TrotParams::from_model(&hyq), Ok(TrotParams::default()));
        let legs: Vec<(String, String, f64)> = Trot::from_profile(&hyq)
            .expect("HyQ has a gait")
            .legs
            .iter()
            .map(|l| {
                (
                    hyq.joints()[l.hfe].name.clone(),
                    hyq.joints()[l.kfe].name.clone(),
                    l.phase,
                )
            })
            .collect();
        let pi = std::f64::consts::PI;
        let expected = [("lf", 0.0), ("lh", pi), ("rf", pi), ("rh", 0.0)]
            .map(|(leg, phase)| (format!("{leg}_hfe"), format!("{leg}_kfe"), phase));
        assert_eq!(legs, expected);
    }

    /// A robot whose profile has no `[gait]` cannot trot, and the error says what to add.
    #[test]
    fn a_robot_without_a_gait_table_is_refused_by_name() {
        let text = hyq_physics::bundled::HYQ_PROFILE
            .split("\n[gait]")
            .next()
            .expect("text");
        let profile = hyq_physics::Profile::from_toml_str(text, "test").expect("profile");
        let model = RobotModel::from_urdf_str(hyq_physics::bundled::HYQ_URDF, "test", &profile)
            .expect("loads");
        let e = Trot::from_profile(&model).expect_err("no gait");
        assert!(
            e.to_string().contains("[gait]") && e.to_string().contains("hyq"),
            "{e}"
        );
    }

    /// The policy's numbers are not those of an environment's goal or noise stream (ChaCha
    /// streams 0 and 1 of the same seed), so a shared seed does not correlate actions and goals.
    #[test]
    fn random_policy_stream_differs_from_the_env_streams_of_the_same_seed() {
        for seed in [0, 7, u64::MAX] {
            let mut policy = RandomPolicy::new(seed).rng;
            let drawn: Vec<u64> = (0..4).map(|_| policy.next_u64()).collect();
            for stream in [0, 1] {
                let mut env_rng = ChaCha8Rng::seed_from_u64(seed);
                env_rng.set_stream(stream);
                let env_drawn: Vec<u64> = (0..4).map(|_| env_rng.next_u64()).collect();
                assert_ne!(drawn, env_drawn, "seed {seed}, stream {stream}");
            }
            let mut again = RandomPolicy::new(seed).rng;
            assert_eq!(drawn, (0..4).map(|_| again.next_u64()).collect::<Vec<_>>());
        }
    }
}
