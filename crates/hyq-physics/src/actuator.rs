//! The joint actuator shared by every backend, evaluated every physics sub-step.
//!
//! For joint `i` with target `q*ᵢ`, angle `qᵢ` and speed `q̇ᵢ`:
//!
//! 1. PD law: `τᵢ = kpᵢ (q*ᵢ − qᵢ) − kdᵢ q̇ᵢ`;
//! 2. velocity limit `vᵢ` (URDF `velocity`): if `q̇ᵢ > vᵢ` then `τᵢ = min(τᵢ, 0)`, and if
//!    `q̇ᵢ < −vᵢ` then `τᵢ = max(τᵢ, 0)`: a motor never pushes a joint that is already faster
//!    than its limit further in its direction of motion; braking is always allowed;
//! 3. effort limit `eᵢ` (URDF `effort`): `τᵢ = clamp(τᵢ, −eᵢ, eᵢ)`;
//! 4. Coulomb joint friction `fᵢ` (URDF `<dynamics friction>`), a passive torque outside the
//!    motor's limit: `τᵢ −= fᵢ · clamp(q̇ᵢ / ω_f, −1, 1)` with [`FRICTION_SMOOTHING`] `ω_f`.
//!    Below `ω_f` the friction grows linearly with speed, the usual regularisation of
//!    Coulomb friction for explicit torques (an exact sign function would chatter around
//!    q̇ = 0 at every sub-step); at rest it therefore holds nothing, unlike a static friction.
//!    It is skipped for frictionless joints, so their torques are bit for bit steps 1–3.
//!
//! Step 2 is the rule Gazebo classic applies to joint efforts (`Joint::CheckAndTruncateForce`),
//! where HyQ's upstream description was simulated. Its limits: it bounds the motor, not the
//! joint. A joint can still exceed its velocity limit by what one sub-step of full torque adds
//! before the rule cuts in, and by whatever gravity, contacts and the motion of the other links
//! impose (a falling leg is not held back). The conformance suite measures the overshoot.
//!
//! Passive joint damping (URDF `damping`) is not part of the actuator: backends apply it
//! (implicitly, where the engine can). Friction is here because no engine applies it the same
//! way, and every torque of an environment goes through this law.

use crate::backend::{Backend, check_finite_joint_values, check_joint_values};
use crate::dynamics::ActuatorScales;
use crate::error::PhysicsError;
use crate::model::RobotModel;

/// The speed (rad/s) below which joint friction is proportional to speed (step 4 of the law):
/// 0.01 rad/s is a thousandth of a walking joint's typical speed, so friction is at its full
/// value in any motion, and one 1 ms sub-step of full friction on a 0.01 kg·m² link changes its
/// speed by f · 0.1 rad/s per N·m, so the linear zone is crossed in a few sub-steps.
pub const FRICTION_SMOOTHING: f64 = 0.01;

/// Per-joint PD gains and limits; see the module documentation for the law.
#[derive(Debug, Clone, PartialEq)]
pub struct Actuator {
    kp: Vec<f64>,
    kd: Vec<f64>,
    effort: Vec<f64>,
    velocity: Vec<f64>,
    friction: Vec<f64>,
    velocity_limit: bool,
}

impl Actuator {
    /// The model's default gains (from the profile), its limits (the URDF's or the profile's
    /// overrides) and joint friction, velocity limit on.
    pub fn new(model: &RobotModel) -> Self {
        Self {
            kp: model.kp().to_vec(),
            kd: model.kd().to_vec(),
            effort: model.joints().iter().map(|j| j.effort).collect(),
            velocity: model.joints().iter().map(|j| j.velocity).collect(),
            friction: model.joints().iter().map(|j| j.friction).collect(),
            velocity_limit: true,
        }
    }

    /// The model's URDF limits with other gains (one finite, non-negative value per joint).
    pub fn with_gains(model: &RobotModel, kp: &[f64], kd: &[f64]) -> Result<Self, PhysicsError> {
        for (what, each, gains) in [("kp gains", "kp", kp), ("kd gains", "kd", kd)] {
            check_joint_values(model, what, each, gains)?;
            if let Some((i, v)) = gains.iter().enumerate().find(|(_, v)| **v < 0.0) {
                return Err(PhysicsError::InvalidState {
                    what: format!("{each} for joint {}", model.joints()[i].name),
                    reason: format!("{v} must be non-negative"),
                });
            }
        }
        Ok(Self {
            kp: kp.to_vec(),
            kd: kd.to_vec(),
            ..Self::new(model)
        })
    }

    /// Switches the velocity-limit rule (step 2 of the law) on or off; it is on by default.
    /// Off, only the effort limit bounds the motor (useful to compare against engines or
    /// environments without velocity limits).
    pub fn set_velocity_limit(&mut self, enabled: bool) {
        self.velocity_limit = enabled;
    }

    /// Is the velocity-limit rule on?
    pub fn velocity_limit(&self) -> bool {
        self.velocity_limit
    }

    /// Number of joints.
    pub fn num_joints(&self) -> usize {
        self.kp.len()
    }

    /// Makes this actuator `base` with its gains, effort limits and joint friction multiplied
    /// joint by joint by `scales` (a randomised episode's actuator); the velocity limits and
    /// the velocity-limit switch stay this actuator's. Allocates nothing.
    ///
    /// Errors, leaving the actuator unchanged, if `base` has another number of joints or a
    /// scale is invalid ([`ActuatorScales::validate`]: gains and efforts must stay positive).
    pub fn scale_from(
        &mut self,
        base: &Actuator,
        scales: &ActuatorScales,
    ) -> Result<(), PhysicsError> {
        let n = self.num_joints();
        if base.num_joints() != n {
            return Err(PhysicsError::WrongLength {
                what: "base actuator joints",
                expected: n,
                got: base.num_joints(),
            });
        }
        scales.validate(n)?;
        for i in 0..n {
            self.kp[i] = base.kp[i] * scales.kp[i];
            self.kd[i] = base.kd[i] * scales.kd[i];
            self.effort[i] = base.effort[i] * scales.effort[i];
            self.friction[i] = base.friction[i] * scales.friction[i];
        }
        Ok(())
    }

    /// Proportional gains (N·m/rad).
    pub fn kp(&self) -> &[f64] {
        &self.kp
    }

    /// Derivative gains (N·m·s/rad).
    pub fn kd(&self) -> &[f64] {
        &self.kd
    }

    /// Effort limits (N·m).
    pub fn effort(&self) -> &[f64] {
        &self.effort
    }

    /// Coulomb joint friction (N·m).
    pub fn friction(&self) -> &[f64] {
        &self.friction
    }

    /// The torque (N·m) of joint `i` for a target, angle and speed.
    ///
    /// # Panics
    /// If `i` is not a joint index.
    #[inline]
    pub fn torque(&self, i: usize, target: f64, q: f64, qd: f64) -> f64 {
        let mut tau = self.kp[i] * (target - q) - self.kd[i] * qd;
        if self.velocity_limit {
            let v = self.velocity[i];
            if qd > v {
                tau = tau.min(0.0);
            } else if qd < -v {
                tau = tau.max(0.0);
            }
        }
        let tau = tau.clamp(-self.effort[i], self.effort[i]);
        let friction = self.friction[i];
        if friction == 0.0 {
            return tau;
        }
        tau - friction * (qd / FRICTION_SMOOTHING).clamp(-1.0, 1.0)
    }

    /// The torques of every joint into `out`; all slices hold one value per joint.
    pub fn torques(
        &self,
        targets: &[f64],
        q: &[f64],
        qd: &[f64],
        out: &mut [f64],
    ) -> Result<(), PhysicsError> {
        let n = self.num_joints();
        for (what, got) in [
            ("joint targets", targets.len()),
            ("joint angles", q.len()),
            ("joint speeds", qd.len()),
            ("torque buffer", out.len()),
        ] {
            if got != n {
                return Err(PhysicsError::WrongLength {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        self.fill_torques(targets, q, qd, out);
        Ok(())
    }

    /// The law of every joint into `out`, for slices whose lengths the caller has checked.
    fn fill_torques(&self, targets: &[f64], q: &[f64], qd: &[f64], out: &mut [f64]) {
        for (i, tau) in out.iter_mut().enumerate() {
            *tau = self.torque(i, targets[i], q[i], qd[i]);
        }
    }
}

/// Caller-owned buffers for [`pd_substep`], so that a sub-step allocates nothing.
#[derive(Debug, Clone, PartialEq)]
pub struct PdScratch {
    q: Vec<f64>,
    qd: Vec<f64>,
    tau: Vec<f64>,
}

impl PdScratch {
    /// Buffers for a robot with `num_joints` joints.
    pub fn new(num_joints: usize) -> Self {
        Self {
            q: vec![0.0; num_joints],
            qd: vec![0.0; num_joints],
            tau: vec![0.0; num_joints],
        }
    }

    /// Joint angles read before the last sub-step.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// Joint speeds read before the last sub-step.
    pub fn qd(&self) -> &[f64] {
        &self.qd
    }

    /// Torques applied during the last sub-step.
    pub fn torques(&self) -> &[f64] {
        &self.tau
    }
}

/// The actuator half of a sub-step: reads `q` and `q̇`, computes the actuator torques for
/// `targets` (rad, profile order) and stores them in the backend for its next
/// [`Backend::step`]. Allocates nothing. [`pd_substep`] is this followed by the step; callers
/// that time the actuator and the physics apart (an environment's profiling) call the two
/// halves themselves.
///
/// Errors if `targets` is not one finite value per joint, if `scratch` or `actuator` was made
/// for another robot, or if a torque is not finite (see [`apply_pd_to_valid_targets`]).
pub fn apply_pd<B: Backend>(
    backend: &mut B,
    actuator: &Actuator,
    targets: &[f64],
    scratch: &mut PdScratch,
) -> Result<(), PhysicsError> {
    check_joint_values(backend.model(), "joint targets", "target", targets)?;
    let n = backend.model().num_joints();
    if scratch.q.len() != n || actuator.num_joints() != n {
        return Err(PhysicsError::WrongLength {
            what: "PD scratch / actuator joint count",
            expected: n,
            got: if scratch.q.len() != n {
                scratch.q.len()
            } else {
                actuator.num_joints()
            },
        });
    }
    apply_pd_to_valid_targets(backend, actuator, targets, scratch)
}

/// [`apply_pd`] for a caller that has already made sure of its inputs: `targets` holds one
/// finite value per joint (an environment's targets, mapped from a checked action and clamped
/// to the joint limits), and `scratch` and `actuator` were made for this robot. Only the
/// torques are checked, since the law can overflow to a non-finite torque under extreme gains
/// (the error names the joint, as [`Backend::set_joint_torques`]' would). Allocates nothing.
///
/// # Panics
/// If a slice is shorter than the robot's joints (a broken promise of the caller's).
pub fn apply_pd_to_valid_targets<B: Backend>(
    backend: &mut B,
    actuator: &Actuator,
    targets: &[f64],
    scratch: &mut PdScratch,
) -> Result<(), PhysicsError> {
    debug_assert_eq!(targets.len(), backend.model().num_joints());
    debug_assert_eq!(scratch.q.len(), targets.len());
    debug_assert_eq!(actuator.num_joints(), targets.len());
    backend.joint_positions(&mut scratch.q);
    backend.joint_velocities(&mut scratch.qd);
    actuator.fill_torques(targets, &scratch.q, &scratch.qd, &mut scratch.tau);
    check_finite_joint_values(backend.model(), "torque", &scratch.tau)?;
    backend.apply_joint_torques(&scratch.tau)
}

/// One actuated physics sub-step: reads `q` and `q̇`, computes the actuator torques for
/// `targets` (rad, profile order), applies them and steps the backend ([`apply_pd`], then
/// [`Backend::step`]). Allocates nothing.
///
/// Errors if `targets` is not one finite value per joint, if `scratch` or `actuator` was made
/// for another robot, or if the step diverged.
pub fn pd_substep<B: Backend>(
    backend: &mut B,
    actuator: &Actuator,
    targets: &[f64],
    scratch: &mut PdScratch,
) -> Result<(), PhysicsError> {
    apply_pd(backend, actuator, targets, scratch)?;
    backend.step()
}
