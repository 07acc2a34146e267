//! The drafted PD gains: an MJCF robot's `<position>` servos' own, else a rule from the
//! robot's mass and inertia (see [`rule`]).

use hyq_physics::RobotModel;
use hyq_physics::na::{Isometry3, Point3, Vector3};

use super::legs::standing_poses;
use super::types::Source;
use crate::mjcf_read::ActuatorKind;

/// The joint sag (rad) the rule's `kp` allows under the standing load.
pub(crate) const SAG: f64 = 0.05;

/// The damping ratio the rule's `kd` gives the heaviest leg swinging in the air about a joint
/// (its lighter lower parts are damped more): 0.6, which gives HyQ's and ANYmal C's chosen
/// gains' ratios within a factor 1.4.
pub(crate) const DAMPING_RATIO: f64 = 0.6;

/// Standard gravity (m/s²), as the environment's.
const G: f64 = 9.81;

/// The drafted gains: the `[gains]` table's, each joint's own where it differs, and why.
#[derive(Debug, Clone)]
pub(crate) struct Drafted {
    /// `gains.kp` (N·m/rad).
    pub(crate) kp: f64,
    /// `gains.kd` (N·m·s/rad).
    pub(crate) kd: f64,
    /// A joint's own `(kp, kd)` (profile order) where it differs from the table's.
    pub(crate) per_joint: Vec<Option<(f64, f64)>>,
    /// Where they came from.
    pub(crate) why: String,
}

/// The gains for `model` (profile order) built from `source`.
pub(crate) fn gains(source: &Source, model: &RobotModel) -> Drafted {
    let (rule_kp, rule_kd, rule_why) = rule(model);
    let servo = |urdf: &str| match source {
        Source::Mjcf(m) => m.actuators.iter().find_map(|a| match a.kind {
            ActuatorKind::Position { kp, kv } if a.joint == urdf => Some((kp, kv)),
            _ => None,
        }),
        Source::Urdf(_) => None,
    };
    let servos: Vec<Option<(f64, f64)>> =
        model.joints().iter().map(|j| servo(&j.urdf_name)).collect();
    if let Some(Some(first)) = servos.first()
        && servos.iter().all(|s| *s == Some(*first))
    {
        return Drafted {
            kp: first.0,
            kd: first.1,
            per_joint: vec![None; servos.len()],
            why: format!(
                "Every joint's <position> actuator in the MJCF: kp {} N m/rad, kv {} N m s/rad \
                     (a kv of 0 leaves the damping to the joints' own).",
                first.0, first.1
            ),
        };
    }
    let count = servos.iter().flatten().count();
    let per_joint = servos
        .iter()
        .map(|s| s.filter(|&(kp, kd)| (kp, kd) != (rule_kp, rule_kd)))
        .collect();
    let why = if count == 0 {
        rule_why
    } else {
        format!(
            "{count} joint(s) take their <position> actuator's kp and kv (given per joint); \
             the others: {rule_why}"
        )
    };
    Drafted {
        kp: rule_kp,
        kd: rule_kd,
        per_joint,
        why,
    }
}

/// The rule for a robot whose file gives no gains: each foot carries an equal share of the
/// weight, straight up, at the standing pose; `kp` holds the most loaded joint's static torque
/// within [`SAG`] rad, and `kd` damps the heaviest swinging leg at [`DAMPING_RATIO`]
/// (`2 ζ sqrt(kp I)`, `I` everything below a joint about its axis); both rounded up to two
/// significant figures. Returns `(kp, kd, why)`.
pub(crate) fn rule(model: &RobotModel) -> (f64, f64, String) {
    let poses = standing_poses(model);
    let feet = model.num_feet().max(1);
    let share = model.total_mass() * G / feet as f64;
    let mut torque: f64 = 0.0;
    let mut inertia: f64 = 0.0;
    for joint in model.joints() {
        let frame = poses[joint.parent] * joint.origin;
        let axis = frame.rotation * joint.axis.into_inner();
        let at = frame.translation.vector;
        let below = subtree(model, joint.child);
        for t in model.tracked().iter().take(model.num_feet()) {
            if below.contains(&t.link) {
                let foot = foot_point(model, t.link, t.shapes.first().copied(), &poses);
                let lever = foot - at;
                let tau = axis.dot(&lever.cross(&Vector3::new(0.0, 0.0, share)));
                torque = torque.max(tau.abs());
            }
        }
        let i: f64 = below
            .iter()
            .map(|&b| about_axis(model, b, &poses[b], &at, &axis))
            .sum();
        inertia = inertia.max(i);
    }
    let kp = round_up(torque / SAG).max(1.0);
    let kd = round_up(2.0 * DAMPING_RATIO * (kp * inertia).sqrt());
    let why = format!(
        "No gains in the file, so a rule: each of the {feet} feet carries an equal share of \
         the {:.2} kg robot's weight at the standing pose; the most loaded joint holds {:.1} N m, \
         and kp = that / {SAG} rad of sag, rounded up to two figures. kd = 2 x {DAMPING_RATIO} x \
         sqrt(kp I), rounded up, with I = {:.4} kg m^2 the largest inertia of a joint's leg \
         below it about its axis (a leg in the air, damped a little under critically).",
        model.total_mass(),
        torque,
        inertia
    );
    (kp, kd, why)
}

/// Body `root` and every body below it.
fn subtree(model: &RobotModel, root: usize) -> Vec<usize> {
    let links = model.links();
    // Parents come before children, so one pass collects the subtree.
    let mut out = vec![root];
    for (i, l) in links.iter().enumerate().skip(root + 1) {
        if l.parent.is_some_and(|p| out.contains(&p)) {
            out.push(i);
        }
    }
    out
}

/// The world point a foot presses on: its shape's centre, or the body's origin.
fn foot_point(
    model: &RobotModel,
    body: usize,
    shape: Option<usize>,
    poses: &[Isometry3<f64>],
) -> Vector3<f64> {
    let origin = shape
        .and_then(|s| model.links()[body].collisions.get(s))
        .map_or(Isometry3::identity(), |c| c.origin);
    (poses[body] * origin).translation.vector
}

/// Body `b`'s inertia about the line through `at` along `axis` (world frame, unit).
fn about_axis(
    model: &RobotModel,
    b: usize,
    pose: &Isometry3<f64>,
    at: &Vector3<f64>,
    axis: &Vector3<f64>,
) -> f64 {
    let link = &model.links()[b];
    let r = pose.rotation.to_rotation_matrix();
    let local = r.matrix().transpose() * axis;
    let own = (local.transpose() * link.inertia * local)[(0, 0)];
    let com = (pose * Point3::from(link.com)).coords - at;
    let off = com - axis * com.dot(axis);
    own + link.mass * off.norm_squared()
}

/// `x` rounded up to two significant figures (0 stays 0).
pub(crate) fn round_up(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 0.0;
    }
    let e = x.log10().floor() as i32 - 1;
    // Dividing by a power of ten (rather than multiplying by a fraction) keeps the result the
    // exact decimal: 0.23, not 0.22999999999999998.
    if e >= 0 {
        let s = 10f64.powi(e);
        (x / s - 1e-9).ceil() * s
    } else {
        let s = 10f64.powi(-e);
        (x * s - 1e-9).ceil() / s
    }
}
