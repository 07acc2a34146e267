//! Drawing: an episode's variations at reset, a step's observation noise and pushes, each
//! option on a ChaCha8 stream of its own, so that turning one option on changes no other
//! draw, and the same seed gives the same values on every engine and every front.

use std::ops::Range as IndexRange;

use hyq_physics::na::Vector3;
use hyq_physics::{ActuatorScales, ContactDraw, DynamicsDraw, PhysicsParams, RobotModel};
use hyq_spec::ObservationLayout;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::ser::SerializeStruct;
use serde::{Deserialize, Serialize, Serializer};

use crate::config::{NoiseDistribution, RandomizeConfig};

/// The ChaCha stream of each per-episode option: [`FIRST_OPTION_STREAM`] + its index in
/// [`EpisodeOption`]'s order. (The goal stream is 0, the reset noise's 1.)
pub const FIRST_OPTION_STREAM: u64 = 16;
/// The observation noise's stream.
pub const OBS_NOISE_STREAM: u64 = 32;
/// The pushes' stream.
pub const PUSH_STREAM: u64 = 33;

/// The per-episode options, in stream order.
#[derive(Clone, Copy, Debug)]
enum EpisodeOption {
    GroundFriction,
    TrunkAddedMass,
    TrunkComOffset,
    LinkMassScale,
    KpScale,
    KdScale,
    EffortScale,
    JointDampingScale,
    JointFrictionScale,
    ActuatorDelay,
    ContactStiffnessScale,
    ContactDampingScale,
    Restitution,
}

/// How many options draw per episode: one past the last in stream order, so a new option
/// placed last in [`EpisodeOption`] gets its stream without a count kept by hand.
const OPTIONS: usize = EpisodeOption::Restitution as usize + 1;

/// One episode's drawn variations, as the info and the records report them: the values in
/// effect, the nominal ones (the configured friction, factors of 1, no added mass, offset,
/// delay or restitution) for options that are off.
///
/// Each drawn quantity is declared once, in the half that acts on it: hyq-physics's
/// [`DynamicsDraw`] (ground friction, the trunk's added mass and offset, the bodies' mass
/// factors, the joints' damping factors, the ground contact's factors and restitution in
/// [`ContactDraw`]), which it turns into an engine's dynamics, and [`ActuatorScales`] (kp,
/// kd, effort limit, joint friction), which scale the shared
/// actuator; the delay is the environment's own. Serialised flat, under the configuration
/// keys' names, in the order of [`RANDOMIZE_INFO_KEYS`](crate::RANDOMIZE_INFO_KEYS) (which
/// puts the joint factors together, so the order is written out in [`Serialize`] below).
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct EpisodeDraw {
    /// The physical half, for hyq-physics to turn into dynamics.
    #[serde(flatten)]
    pub dynamics: DynamicsDraw,
    /// The actuator's factors (action order).
    #[serde(flatten)]
    pub actuator: ActuatorScales,
    /// The actuator's delay (physics sub-steps).
    pub actuator_delay_substeps: u32,
}

impl Serialize for EpisodeDraw {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let (d, a) = (&self.dynamics, &self.actuator);
        let mut s = serializer.serialize_struct("EpisodeDraw", 13)?;
        s.serialize_field("ground_friction", &d.ground_friction)?;
        s.serialize_field("trunk_added_mass_kg", &d.trunk_added_mass_kg)?;
        s.serialize_field("trunk_com_offset_m", &d.trunk_com_offset_m)?;
        s.serialize_field("link_mass_scale", &d.link_mass_scale)?;
        s.serialize_field("kp_scale", &a.kp)?;
        s.serialize_field("kd_scale", &a.kd)?;
        s.serialize_field("effort_scale", &a.effort)?;
        s.serialize_field("joint_damping_scale", &d.joint_damping_scale)?;
        s.serialize_field("joint_friction_scale", &a.friction)?;
        s.serialize_field("actuator_delay_substeps", &self.actuator_delay_substeps)?;
        let c = &d.contact;
        s.serialize_field("contact_stiffness_scale", &c.contact_stiffness_scale)?;
        s.serialize_field("contact_damping_scale", &c.contact_damping_scale)?;
        s.serialize_field("restitution", &c.restitution)?;
        s.end()
    }
}

impl EpisodeDraw {
    /// No variation for `model` with `params`' friction.
    pub fn nominal(model: &RobotModel, params: &PhysicsParams) -> Self {
        Self {
            dynamics: DynamicsDraw::nominal(model, params),
            actuator: ActuatorScales::nominal(model.num_joints()),
            actuator_delay_substeps: 0,
        }
    }
}

fn stream(seed: u64, id: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(id);
    rng
}

/// Uniform in [lo, hi) from one draw (lo itself when lo = hi).
fn uniform(rng: &mut ChaCha8Rng, [lo, hi]: [f64; 2]) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// A standard normal value from two uniform draws in [0, 1) (Box–Muller): finite, at most 8.6
/// in magnitude, since 1 − u ≥ 2⁻⁵³.
fn normal(u: f64, u2: f64) -> f64 {
    (-2.0 * (1.0 - u).ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Draws the ground contact's options that are on into `contact`, each from its stream in `g`.
fn draw_contact(c: &RandomizeConfig, g: &mut [ChaCha8Rng; OPTIONS], contact: &mut ContactDraw) {
    for (o, r, out) in [
        (
            EpisodeOption::ContactStiffnessScale,
            c.contact_stiffness_scale,
            &mut contact.contact_stiffness_scale,
        ),
        (
            EpisodeOption::ContactDampingScale,
            c.contact_damping_scale,
            &mut contact.contact_damping_scale,
        ),
        (
            EpisodeOption::Restitution,
            c.restitution,
            &mut contact.restitution,
        ),
    ] {
        if let Some(r) = r {
            *out = uniform(&mut g[o as usize], r);
        }
    }
}

/// Draws an episode's variations, a step's noise and pushes (see the module docs).
#[derive(Clone, Debug)]
pub struct Randomizer {
    config: RandomizeConfig,
    options: [ChaCha8Rng; OPTIONS],
    noise: ChaCha8Rng,
    push: ChaCha8Rng,
    draw: EpisodeDraw,
    /// When the next push is due (s since reset).
    next_push_s: f64,
    /// The velocity added by this step's push (zeros when none).
    pushed: [f64; 3],
    /// Pushes this episode.
    pushes: u64,
}

impl Randomizer {
    /// A randomizer for `config` (already validated; its effective ranges are used), streams
    /// from `seed`, for `model` with `params`.
    pub fn new(
        config: &RandomizeConfig,
        seed: u64,
        model: &RobotModel,
        params: &PhysicsParams,
    ) -> Self {
        Self {
            config: config.effective(),
            options: std::array::from_fn(|i| stream(seed, FIRST_OPTION_STREAM + i as u64)),
            noise: stream(seed, OBS_NOISE_STREAM),
            push: stream(seed, PUSH_STREAM),
            draw: EpisodeDraw::nominal(model, params),
            next_push_s: f64::INFINITY,
            pushed: [0.0; 3],
            pushes: 0,
        }
    }

    /// The ranges in effect.
    pub fn config(&self) -> &RandomizeConfig {
        &self.config
    }

    /// Every stream restarted from `seed`.
    pub fn reseed(&mut self, seed: u64) {
        self.options = std::array::from_fn(|i| stream(seed, FIRST_OPTION_STREAM + i as u64));
        self.noise = stream(seed, OBS_NOISE_STREAM);
        self.push = stream(seed, PUSH_STREAM);
    }

    /// Draws a new episode: every option that is on from its own stream (the others
    /// nominal), and the first push's time; [`Randomizer::draw`] then holds it.
    pub fn begin_episode(&mut self, model: &RobotModel, params: &PhysicsParams) {
        let c = &self.config;
        let g = &mut self.options;
        let mut draw = EpisodeDraw::nominal(model, params);
        let (d, a) = (&mut draw.dynamics, &mut draw.actuator);
        if let Some(r) = c.ground_friction {
            d.ground_friction = uniform(&mut g[EpisodeOption::GroundFriction as usize], r);
        }
        if let Some(r) = c.trunk_added_mass_kg {
            d.trunk_added_mass_kg = uniform(&mut g[EpisodeOption::TrunkAddedMass as usize], r);
        }
        if let Some(axes) = c.trunk_com_offset_m {
            let rng = &mut g[EpisodeOption::TrunkComOffset as usize];
            d.trunk_com_offset_m = axes.map(|r| uniform(rng, r));
        }
        for (o, r, out) in [
            (
                EpisodeOption::LinkMassScale,
                c.link_mass_scale,
                &mut d.link_mass_scale,
            ),
            (EpisodeOption::KpScale, c.kp_scale, &mut a.kp),
            (EpisodeOption::KdScale, c.kd_scale, &mut a.kd),
            (EpisodeOption::EffortScale, c.effort_scale, &mut a.effort),
            (
                EpisodeOption::JointDampingScale,
                c.joint_damping_scale,
                &mut d.joint_damping_scale,
            ),
            (
                EpisodeOption::JointFrictionScale,
                c.joint_friction_scale,
                &mut a.friction,
            ),
        ] {
            if let Some(r) = r {
                let rng = &mut g[o as usize];
                out.iter_mut().for_each(|v| *v = uniform(rng, r));
            }
        }
        if let Some([lo, hi]) = c.actuator_delay_substeps {
            let u = g[EpisodeOption::ActuatorDelay as usize].random::<f64>();
            let span = f64::from(hi - lo + 1);
            draw.actuator_delay_substeps = (lo + (u * span) as u32).min(hi);
        }
        draw_contact(c, g, &mut draw.dynamics.contact);
        self.draw = draw;
        self.pushes = 0;
        self.pushed = [0.0; 3];
        self.next_push_s = match c.push_interval_s {
            Some(r) => uniform(&mut self.push, r),
            None => f64::INFINITY,
        };
    }

    /// The episode's draw.
    pub fn draw(&self) -> &EpisodeDraw {
        &self.draw
    }

    /// The push of the env step starting `time_s` after reset, if one is due: its velocity
    /// (m/s, world), drawn as a speed along the ground in a uniform direction plus a vertical
    /// speed (four draws per push, whatever is on, so turning the vertical speed on changes no
    /// other draw); the next push is due one drawn interval later.
    pub fn push_due(&mut self, time_s: f64) -> Option<Vector3<f64>> {
        self.pushed = [0.0; 3];
        // A push due within rounding of the step's start time is due now.
        if time_s + 1e-9 < self.next_push_s {
            return None;
        }
        let c = &self.config;
        let interval = c
            .push_interval_s
            .map_or(0.0, |r| uniform(&mut self.push, r));
        let speed = uniform(&mut self.push, c.push_velocity_xy_mps.unwrap_or([0.0; 2]));
        let angle = uniform(
            &mut self.push,
            [-std::f64::consts::PI, std::f64::consts::PI],
        );
        let vz = uniform(&mut self.push, c.push_velocity_z_mps.unwrap_or([0.0; 2]));
        self.next_push_s += interval;
        self.pushes += 1;
        self.pushed = [speed * angle.cos(), speed * angle.sin(), vz];
        Some(Vector3::from(self.pushed))
    }

    /// The velocity this step's push added (m/s, world; zeros when there was none).
    pub fn pushed(&self) -> [f64; 3] {
        self.pushed
    }

    /// Pushes so far this episode.
    pub fn pushes(&self) -> u64 {
        self.pushes
    }

    /// Whether observation noise is on.
    pub fn noisy(&self) -> bool {
        !self.config.obs_noise.is_off()
    }

    /// Writes into `seen` the observation `truth` as the policy sees it: each row of a group
    /// with a deviation plus its noise (two draws per row every step, whatever is on, so that
    /// turning a group on changes no other group's noise), the quaternion rows kept within
    /// [−1, 1], each contact flag flipped with its probability, and every value within the
    /// float32 range.
    pub fn observe(&mut self, layout: &ObservationLayout, truth: &[f64], seen: &mut [f64]) {
        let n = &self.config.obs_noise;
        let uniform_noise = n.distribution == Some(NoiseDistribution::Uniform);
        let task = task_rows(layout);
        let groups: [(IndexRange<usize>, Option<f64>); 9] = [
            (layout.joint_angles(), n.joint_angle),
            (layout.joint_speeds(), n.joint_speed),
            (layout.trunk_rotation(), n.quaternion),
            (layout.trunk_acceleration(), n.trunk_accel),
            (layout.trunk_position(), n.trunk_position),
            (task[0].clone(), n.base_lin_vel),
            (task[1].clone(), n.base_ang_vel),
            (task[2].clone(), n.projected_gravity),
            // q − q₀: the joint angles' noise, as the anchors give their offset rows.
            (task[3].clone(), n.joint_angle),
        ];
        let flags = layout.foot_contacts().start..layout.trunk_contact() + 1;
        seen.copy_from_slice(truth);
        for (i, value) in seen.iter_mut().enumerate() {
            let (u, u2) = (self.noise.random::<f64>(), self.noise.random::<f64>());
            let z = if uniform_noise {
                2.0 * u - 1.0
            } else {
                normal(u, u2)
            };
            if flags.contains(&i) {
                if n.contact_flip.is_some_and(|p| u < p) {
                    *value = 1.0 - *value;
                }
                continue;
            }
            if let Some((range, Some(d))) = groups.iter().find(|(r, _)| r.contains(&i)) {
                *value += d * z;
                if *range == layout.trunk_rotation() {
                    *value = value.clamp(-1.0, 1.0);
                }
                *value = value.clamp(-f64::from(f32::MAX), f64::from(f32::MAX));
            }
        }
    }
}

/// The velocity task's noisy rows in `layout` (its `velocity_task` group): the body-frame
/// linear and angular velocity, the projected gravity and the joint offsets; empty ranges when
/// the layout has no such group. The command and last-action rows are known exactly and get
/// none.
fn task_rows(layout: &ObservationLayout) -> [IndexRange<usize>; 4] {
    let Some(g) = layout
        .groups()
        .iter()
        .find(|g| g.name == crate::velocity::GROUP)
    else {
        return [0..0, 0..0, 0..0, 0..0];
    };
    let s = g.rows.start;
    let joints = layout.joint_angles().len();
    [
        s..s + 3,
        s + 3..s + 6,
        s + 6..s + 9,
        s + 12..s + 12 + joints,
    ]
}

#[cfg(test)]
mod tests {
    //! Streams per option, fixed draw counts, and noise that stays in bounds.
    #![allow(clippy::unwrap_used)]

    use super::*;
    use hyq_physics::bundled;

    fn on(f: impl FnOnce(&mut RandomizeConfig)) -> RandomizeConfig {
        let mut c = RandomizeConfig::default();
        f(&mut c);
        c
    }

    #[test]
    fn turning_one_option_on_changes_no_other_draw() {
        let model = bundled::hyq();
        let params = PhysicsParams::default();
        let friction_only = on(|c| c.ground_friction = Some([0.3, 1.2]));
        let both = on(|c| {
            c.ground_friction = Some([0.3, 1.2]);
            c.kp_scale = Some([0.8, 1.2]);
            c.push_interval_s = Some([1.0, 2.0]);
            c.push_velocity_xy_mps = Some([0.5, 0.5]);
        });
        let mut a = Randomizer::new(&friction_only, 7, &model, &params);
        let mut b = Randomizer::new(&both, 7, &model, &params);
        for _ in 0..5 {
            a.begin_episode(&model, &params);
            b.begin_episode(&model, &params);
            let (da, db) = (a.draw(), b.draw());
            let friction = da.dynamics.ground_friction;
            assert_eq!(friction, db.dynamics.ground_friction);
            assert!((0.3..1.2).contains(&friction));
            assert_eq!(da.actuator.kp, vec![1.0; 12], "off: nominal");
            assert!(db.actuator.kp.iter().all(|s| (0.8..1.2).contains(s)));
            assert!(
                db.actuator.kp.windows(2).any(|w| w[0] != w[1]),
                "drawn per joint"
            );
        }
    }

    #[test]
    fn pushes_come_at_drawn_intervals_with_the_drawn_speed() {
        let model = bundled::hyq();
        let params = PhysicsParams::default();
        let c = on(|c| {
            c.push_interval_s = Some([2.0, 4.0]);
            c.push_velocity_xy_mps = Some([0.5, 0.5]);
        });
        let mut r = Randomizer::new(&c, 3, &model, &params);
        r.begin_episode(&model, &params);
        let mut times = Vec::new();
        for step in 0..1000 {
            let t = f64::from(step) * 0.01;
            if let Some(v) = r.push_due(t) {
                times.push(t);
                assert!((v.xy().norm() - 0.5).abs() < 1e-12 && v.z == 0.0, "{v:?}");
                assert_eq!(r.pushed(), [v.x, v.y, v.z]);
            } else {
                assert_eq!(r.pushed(), [0.0; 3]);
            }
        }
        assert!(times.len() >= 2 && times.len() <= 5, "{times:?}");
        assert!(times[0] >= 2.0 && times[0] <= 4.01, "{times:?}");
        for w in times.windows(2) {
            assert!(w[1] - w[0] >= 1.99 && w[1] - w[0] <= 4.01, "{times:?}");
        }
        assert_eq!(r.pushes(), times.len() as u64);
    }

    #[test]
    fn noise_reaches_only_its_rows_and_keeps_them_in_bounds() {
        let model = bundled::hyq();
        let params = PhysicsParams::default();
        let layout = crate::env::observation_layout_of(&model).unwrap();
        let c = on(|c| {
            c.obs_noise.joint_angle = Some(0.5);
            c.obs_noise.quaternion = Some(10.0);
        });
        let mut r = Randomizer::new(&c, 1, &model, &params);
        let truth: Vec<f64> = (0..layout.len()).map(|i| (i % 2) as f64 * 0.5).collect();
        let mut seen = vec![0.0; truth.len()];
        r.observe(&layout, &truth, &mut seen);
        for (i, (t, s)) in truth.iter().zip(&seen).enumerate() {
            if layout.joint_angles().contains(&i) {
                assert_ne!(t, s, "row {i} is noisy");
            } else if layout.trunk_rotation().contains(&i) {
                assert!((-1.0..=1.0).contains(s), "row {i}: {s}");
            } else {
                assert_eq!(t, s, "row {i} has no noise");
            }
        }
    }
}
