//! Invariant (docs/spec.md §7.12): `[regularizers]` adds Σ s·r·Δt_env over the terms that are
//! on to the spec's reward, after the spec's composition, on every step the rules judge
//! (terminating steps included), and changes nothing else. Off (the default, or every scale 0)
//! the environment is the spec's bit for bit and reports nothing of them. On rapier, and on DART
//! and MuJoCo with `--features dart` / `mujoco`, a trotting episode's every step has the reward
//! of the same episode without them plus the terms its record holds, scaled, and the terms the
//! record's own rows determine (action rate, joint acceleration, base height, orientation,
//! collision, feet air time, goal heading, line and approach) are recomputed from those rows bit
//! for bit.

mod common;

use std::sync::Arc;

use common::{reset, scripted};
use hyq_env::policy::{Policy, Trot, TrotParams};
use hyq_env::{Env, EnvConfig, Reason, ResetOptions, StepRecord, regularizer_info_keys};
use hyq_physics::na::{Quaternion, UnitQuaternion, Vector3};
use hyq_physics::{Backend, RobotModel, bundled};
use hyq_rapier::RapierBackend;
use hyq_spec::ObservationLayout;
use hyq_tasks::observation::projected_gravity;
use hyq_tasks::step::AirTime;
use hyq_tasks::{REGULARIZER_NAMES, RegularizerTerms, terms};

/// Every regulariser on: legged_gym's preset plus the six it leaves at 0.
const ALL_ON: &[(&str, &str)] = &[
    ("regularizers.preset", "legged_gym"),
    ("regularizers.foot_slip", "-0.1"),
    ("regularizers.base_height", "-1.0"),
    ("regularizers.goal_heading", "-0.5"),
    ("regularizers.goal_line", "-10.0"),
    ("regularizers.goal_line_approach", "60.0"),
    ("regularizers.orientation", "-5.0"),
];

fn config(pairs: &[(&str, &str)]) -> EnvConfig {
    EnvConfig::load(None, pairs).unwrap_or_else(|e| panic!("{e}"))
}

/// Σ s·v·Δt over the terms a record holds, in [`REGULARIZER_NAMES`]' order, from the empty
/// sum (−0.0, which adds nothing to any number).
fn scaled_sum(scales: &RegularizerTerms, record: &StepRecord<'_>, dt: f64) -> f64 {
    let written = record
        .regularizers
        .unwrap_or_else(|| panic!("a regularised record holds its terms"));
    let s = scales.to_array();
    REGULARIZER_NAMES
        .iter()
        .enumerate()
        .filter_map(|(k, name)| written.get(name).map(|v| s[k] * v * dt))
        .fold(-0.0, |a, x| a + x)
}

/// The terms a record's own rows determine (action rate, joint acceleration, base height,
/// orientation, collision, feet air time, and with the episode's start and goal the goal
/// heading, line and approach), recomputed from those rows and the previous records'.
struct FromRows {
    layout: ObservationLayout,
    /// The episode's start and goal (world x and y).
    start: [f64; 2],
    goal: [f64; 2],
    /// The previous record's distance off the start–goal line (0 after reset).
    previous_line: f64,
    previous_action: Vec<f64>,
    previous_qd: Vec<f64>,
    air: AirTime,
}

impl FromRows {
    fn new(model: &RobotModel, layout: ObservationLayout, start: [f64; 2], goal: [f64; 2]) -> Self {
        let n = model.num_joints();
        Self {
            layout,
            start,
            goal,
            previous_line: 0.0,
            previous_action: vec![0.0; n],
            previous_qd: vec![0.0; n],
            air: AirTime::new(model.num_feet()),
        }
    }

    /// Checks `record`'s terms against the recomputed ones, bit for bit; returns the two it
    /// cannot recompute (torques and foot slip), checked finite and not negative.
    fn check(
        &mut self,
        record: &StepRecord<'_>,
        model: &RobotModel,
        dt: f64,
        at: &str,
    ) -> (f64, f64) {
        let w = record.regularizers.unwrap_or_else(|| panic!("{at}: terms"));
        let obs = &record.obs;
        let qd = &obs[self.layout.joint_speeds()];
        let feet: Vec<bool> = obs[self.layout.foot_contacts()]
            .iter()
            .map(|f| *f == 1.0)
            .collect();
        let touchdown = self.air.update(&feet, dt);
        let position = &obs[self.layout.trunk_position()];
        let z = position[2];
        let trunk = [position[0], position[1]];
        let [qw, qx, qy, qz] = obs[self.layout.trunk_rotation()] else {
            panic!("{at}: four rotation rows")
        };
        let rotation = UnitQuaternion::new_unchecked(Quaternion::new(qw, qx, qy, qz));
        let heading = rotation * Vector3::x();
        let line = terms::goal_line(self.start, self.goal, trunk);
        let expected = [
            (
                "action_rate",
                terms::action_rate(&record.action, &self.previous_action),
            ),
            ("joint_acc", terms::joint_acc(qd, &self.previous_qd, dt)),
            (
                "base_height",
                terms::base_height(z, model.standing_height()),
            ),
            (
                "orientation",
                terms::orientation(projected_gravity(&rotation)),
            ),
            ("collision", obs[self.layout.trunk_contact()]),
            ("feet_air_time", terms::feet_air_time(touchdown, 0.5, true)),
            (
                "goal_heading",
                terms::goal_heading(trunk, [heading.x, heading.y], self.goal),
            ),
            ("goal_line", line),
            (
                "goal_line_approach",
                terms::goal_line_approach(self.previous_line, line, dt),
            ),
        ];
        for (name, value) in expected {
            let got = w
                .get(name)
                .unwrap_or_else(|| panic!("{at}: {name} written"));
            assert_eq!(got.to_bits(), value.to_bits(), "{at}: {name}");
        }
        self.previous_action.copy_from_slice(&record.action);
        self.previous_qd.copy_from_slice(qd);
        self.previous_line = line;
        let torques = w.get("torques").unwrap_or(f64::NAN);
        let slip = w.get("foot_slip").unwrap_or(f64::NAN);
        assert!(
            torques.is_finite() && torques >= 0.0 && slip.is_finite() && slip >= 0.0,
            "{at}"
        );
        (torques, slip)
    }
}

/// Trots `steps` steps of HyQ on `B` with and without every regulariser, checking each step.
fn reward_is_the_spec_reward_plus_the_recorded_terms<B: Backend>(steps: usize) {
    let model: Arc<RobotModel> = bundled::hyq();
    let mut plain =
        Env::<B>::new(Arc::clone(&model), config(&[])).unwrap_or_else(|e| panic!("{e}"));
    let mut reg =
        Env::<B>::new(Arc::clone(&model), config(ALL_ON)).unwrap_or_else(|e| panic!("{e}"));
    plain
        .reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let r0 = reg
        .reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r0.info.regularizers.map(|r| r.reward), Some(0.0));
    let xy = |p: [f64; 3]| [p[0], p[1]];
    let (start, goal) = (xy(r0.info.initial_position), xy(r0.info.goal));
    let scales = reg.config().regularizers.resolve(model.standing_height());
    assert!(scales.on().iter().all(|on| *on));
    let dt = reg.env_dt();
    let layout = reg.observation_layout().clone();
    let mut policy = Trot::new(&model, TrotParams::default()).unwrap_or_else(|e| panic!("{e}"));
    let mut a = vec![0.0; model.num_joints()];
    let mut rows = FromRows::new(&model, layout, start, goal);
    let (mut slipped, mut pushed) = (false, false);
    for t in 1..=steps {
        policy.act(&reg.policy_input(), &mut a);
        let p = plain.step(&a).unwrap_or_else(|e| panic!("{e}"));
        let (p_reward, p_breakdown, p_obs) = (p.reward, p.info.reward, p.observation.to_vec());
        let s = reg.step(&a).unwrap_or_else(|e| panic!("{e}"));
        // The physics and the spec's breakdown are the plain episode's, bit for bit.
        assert_eq!(s.observation, &p_obs[..], "{} t = {t}", B::NAME);
        assert_eq!(s.info.reward, p_breakdown, "{} t = {t}", B::NAME);
        let step_reward = s.reward;
        assert!(!s.terminated, "{} t = {t}: the trot does not fall", B::NAME);
        let keys = regularizer_info_keys(s.info).count();
        assert_eq!(keys, 1 + REGULARIZER_NAMES.len());
        let line = StepRecord::from_env(&reg, &a).to_json_line();
        let record = StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("{e}"));
        // The ruling: the spec's reward plus the recorded terms, scaled by s·Δt.
        let want = p_reward + scaled_sum(&scales.terms, &record, dt);
        assert_eq!(
            record.reward.to_bits(),
            want.to_bits(),
            "{} t = {t}",
            B::NAME
        );
        assert_eq!(step_reward.to_bits(), want.to_bits(), "{} t = {t}", B::NAME);
        let at = format!("{} t = {t}", B::NAME);
        let (torques, slip) = rows.check(&record, &model, dt, &at);
        pushed |= torques > 0.0;
        slipped |= slip > 0.0;
    }
    assert!(
        pushed && slipped,
        "{}: torques and slip were measured",
        B::NAME
    );
}

#[test]
fn reward_is_the_spec_reward_plus_the_recorded_terms_on_rapier() {
    reward_is_the_spec_reward_plus_the_recorded_terms::<RapierBackend>(120);
}

#[cfg(feature = "dart")]
#[test]
fn reward_is_the_spec_reward_plus_the_recorded_terms_on_dart() {
    reward_is_the_spec_reward_plus_the_recorded_terms::<hyq_dart::DartBackend>(120);
}

#[cfg(feature = "mujoco")]
#[test]
fn reward_is_the_spec_reward_plus_the_recorded_terms_on_mujoco() {
    reward_is_the_spec_reward_plus_the_recorded_terms::<hyq_mujoco::MujocoBackend>(120);
}

/// Off by default, and with every scale 0: the spec's environment, records byte for byte, no
/// regulariser info, nothing written.
#[test]
fn off_the_environment_is_the_spec_bit_for_bit() {
    let model: Arc<RobotModel> = bundled::hyq();
    let default = config(&[]);
    assert!(default.regularizers.is_off());
    assert!(!default.to_toml_string().contains("regularizers"));
    let zeros = config(&[
        ("regularizers.action_rate", "0.0"),
        ("regularizers.collision", "0"),
    ]);
    assert!(zeros.regularizers.is_off());
    let run = |config: EnvConfig| {
        let mut env =
            Env::<RapierBackend>::new(Arc::clone(&model), config).unwrap_or_else(|e| panic!("{e}"));
        let r = env
            .reset(Some(0), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(r.info.regularizers.is_none());
        let mut policy = Trot::new(&model, TrotParams::default()).unwrap_or_else(|e| panic!("{e}"));
        let mut a = vec![0.0; model.num_joints()];
        let mut lines = Vec::new();
        for _ in 0..60 {
            policy.act(&env.policy_input(), &mut a);
            let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
            assert!(s.info.regularizers.is_none());
            assert_eq!(regularizer_info_keys(s.info).count(), 0);
            assert_eq!(s.reward.to_bits(), s.info.reward.total.to_bits());
            lines.push(StepRecord::from_env(&env, &a).to_json_line());
        }
        lines
    };
    let a = run(default);
    assert!(a.iter().all(|l| !l.contains("regularizers")));
    assert_eq!(a, run(zeros));
}

/// The ruling on terminations: a terminating step gets the sum like any other, after the spec's
/// penalties (a fall pays `fall_penalty` and the collision term both: the trunk is the body
/// that touched); a diverged step's reward is 0 with every term 0.
#[test]
fn a_fall_pays_its_penalty_and_the_regularisers_and_a_divergence_pays_nothing() {
    let pairs = [
        ("task.fall_penalty", "2.5"),
        ("regularizers.collision", "-1.0"),
        ("regularizers.action_rate", "-0.01"),
    ];
    let mut env = scripted(&pairs);
    let mut plain = scripted(&pairs[..1]);
    reset(&mut env, 0);
    reset(&mut plain, 0);
    let trunk = env.model().trunk_tracked_index();
    for e in [&mut env, &mut plain] {
        e.backend_mut().set_script(move |w| {
            w.contacts[trunk] = w.substep == 15;
            Ok(())
        });
    }
    let dt = env.env_dt();
    let a = [0.5; 12];
    plain.step(&a).unwrap_or_else(|e| panic!("{e}"));
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    let first = s.info.regularizers.unwrap_or_else(|| panic!("on"));
    assert_eq!(first.terms.get("collision"), Some(0.0));
    assert_eq!(first.terms.get("action_rate"), Some(12.0 * 0.25));
    assert_eq!(
        first.terms.get("torques"),
        None,
        "an off term is not reported"
    );
    let b = [-0.5; 12];
    let p = plain.step(&b).unwrap_or_else(|e| panic!("{e}"));
    let p_total = p.reward;
    assert_eq!(p.info.reward.fall_penalty, 2.5);
    let s = env.step(&b).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.terminated && s.info.reasons.contains(Reason::Fell));
    assert_eq!(s.info.reward.fall_penalty, 2.5);
    let r = s.info.regularizers.unwrap_or_else(|| panic!("on"));
    assert_eq!(r.terms.get("collision"), Some(1.0));
    assert_eq!(r.terms.get("action_rate"), Some(12.0));
    let sum = -0.01 * 12.0 * dt + -dt; // collision's scale −1 times 1 times Δt
    assert_eq!(r.reward, sum);
    assert_eq!(s.reward, p_total + sum);

    // A divergence: reward 0, the terms that are on reported as 0.
    let mut env = scripted(&pairs);
    reset(&mut env, 0);
    env.backend_mut().set_script(|w| {
        if w.substep == 5 {
            w.qd[0] = f64::NAN;
        }
        Ok(())
    });
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.info.reasons.contains(Reason::Diverged));
    assert_eq!(s.reward, 0.0);
    let r = s.info.regularizers.unwrap_or_else(|| panic!("on"));
    assert_eq!((r.reward, r.terms.get("action_rate")), (0.0, Some(0.0)));
}

/// A term that overflows (a joint speed's change over a vanishing Δt_env) ends the episode as
/// `diverged`, naming the term, and nothing non-finite is emitted.
#[test]
fn a_term_that_overflows_ends_the_episode_as_diverged() {
    let mut env = scripted(&[
        ("physics.dt", "1e-200"),
        ("control.sim_steps_per_env_step", "1"),
        ("regularizers.joint_acc", "-2.5e-7"),
    ]);
    reset(&mut env, 0);
    env.backend_mut().set_script(|w| {
        w.qd[0] = 1.0e3;
        Ok(())
    });
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        s.info.reasons.contains(Reason::Diverged),
        "{:?}",
        s.info.reasons
    );
    assert_eq!(s.reward, 0.0);
    let why = s
        .info
        .divergence
        .as_ref()
        .map(ToString::to_string)
        .unwrap_or_default();
    assert!(why.contains("regularizers.joint_acc"), "{why}");
    let r = s.info.regularizers.unwrap_or_else(|| panic!("on"));
    assert!(r.reward == 0.0 && r.terms.iter().all(|(_, v)| v == 0.0));
}

/// The table's keys are checked and named; the velocity task refuses it (its regularisers are
/// `[velocity]`'s).
#[test]
fn bad_values_are_named_and_the_velocity_task_refuses_the_table() {
    for (key, value) in [
        ("regularizers.torques", "nan"),
        ("regularizers.joint_acc", "1e5"),
        ("regularizers.base_height_target_m", "-1"),
        ("regularizers.feet_air_time_threshold_s", "11"),
        ("regularizers.preset", "isaac_lab"),
        ("regularizers.dof_acc", "1"),
    ] {
        let e = EnvConfig::load(None, &[(key, value)])
            .err()
            .unwrap_or_else(|| panic!("{key} = {value} accepted"));
        let text = e.to_string();
        assert!(
            text.contains(key.rsplit('.').next().unwrap_or(key)),
            "{text}"
        );
        assert!(!text.contains('\n'), "{text}");
    }
    let e = EnvConfig::load(
        None,
        &[("task.kind", "velocity"), ("regularizers.torques", "-1e-5")],
    )
    .err()
    .unwrap_or_else(|| panic!("accepted"));
    assert!(e.to_string().contains("[regularizers]"), "{e}");
}
