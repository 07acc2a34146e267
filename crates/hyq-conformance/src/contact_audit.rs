//! The contact audit: what an engine's ground contact does, measured against the rigid-body
//! Coulomb answer, on probes built from a robot's feet.
//!
//! Two probes stand in for a robot's feet ([`sled`], [`foot`]), each built from the robot's
//! first foot sphere (its radius) and its total mass:
//!
//! - the **sled**: one rigid body on four of the robot's foot spheres at (±15 cm, ±15 cm) with
//!   the robot's whole mass, its centre of mass at the spheres' centres: a robot whose legs are
//!   locked, loaded like the robot on its four feet. It cannot roll, so it sticks or slides.
//! - the **foot**: one of the robot's foot spheres carrying a quarter of the robot's mass, a
//!   foot's share when it stands on four.
//!
//! Both carry a 5 mm sphere on a free hinge at their centre, which never touches the ground (a
//! robot profile needs a joint). An incline is gravity tilted by θ over flat ground, which is
//! the same physics as the ground tilted by θ under vertical gravity, without a height field's
//! triangles. A sideways push is a force ramp applied as a velocity change `F·dt/m` on the
//! body each sub-step ([`Backend::push_trunk`]), which is what a force does to a body over one
//! step of a first-order integrator.
//!
//! The physics answers are those of rigid bodies under Coulomb friction with the audit's
//! coefficient μ = [`AUDIT_FRICTION`] and no restitution (spec: "contacts are inelastic"):
//!
//! | figure | physics answer |
//! |---|---|
//! | creep of the sled on an incline at atan μ − 5° | 0 (it sticks) |
//! | sliding acceleration at atan μ + 5°, downhill along x, and along the diagonal | g (sin θ − μ cos θ) |
//! | push (along x, and along the diagonal) at which the loaded sled starts to slide | μ N |
//! | bounce of the foot dropped 5 cm | 0 |
//! | penetration of the foot at rest | 0 |
//! | torque resisting the loaded foot spinning about the vertical | 0 (a point contact) |
//! | angular deceleration of the sled spinning about the vertical | μ N d / I_z, each foot at d |
//!
//! Each figure is a [`Figure`] (name, unit, physics answer, measured value). An engine's test
//! file holds each figure to the physics answer within a stated tolerance where the engine can
//! meet it, else to the engine's known deviation ([`Expect`]), through
//! [`contact_audit_tests!`](crate::contact_audit_tests), and prints the table
//! ([`table`]) that docs/backend-comparison.md quotes.

use std::f64::consts::SQRT_2;

use nalgebra::{Isometry3, Vector3};

use super::fixtures::{Robot, build, read_contacts, set, step_zero, steps_for};
use hyq_physics::model::Shape;
use hyq_physics::{Backend, ContactDraw, Dynamics, PhysicsError, PhysicsParams, RobotState};

/// The friction coefficient of every audit (a legged-robot floor's typical value; the
/// environment's default, 1.0, would put the stick-slip angle at 45°).
pub const AUDIT_FRICTION: f64 = 0.5;

/// Half the distance between the sled's feet along x and along y (m).
pub const SLED_HALF_SPAN: f64 = 0.15;

/// The incline angles' distance from the stick-slip angle atan μ (degrees).
const INCLINE_MARGIN_DEG: f64 = 5.0;

/// Gravity's magnitude (m/s²), the default parameters'.
const G: f64 = 9.81;

/// One measured figure beside its physics answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// What was measured, as the table names it.
    pub name: &'static str,
    /// The unit of both values.
    pub unit: &'static str,
    /// The rigid-body Coulomb answer.
    pub physics: f64,
    /// What the engine did.
    pub measured: f64,
}

/// What an engine's test holds a [`Figure`] to.
#[derive(Debug, Clone, PartialEq)]
pub enum Expect {
    /// The physics answer, within `tolerance` (absolute, in the figure's unit).
    Physics {
        /// The allowed |measured − physics|.
        tolerance: f64,
    },
    /// A known deviation: the engine cannot meet the physics answer (`why` says why) and
    /// measures `value` within `tolerance`, so that a change is noticed.
    Deviates {
        /// The measured value the engine is known to give.
        value: f64,
        /// The allowed |measured − value|.
        tolerance: f64,
        /// Why the engine differs from the physics answer.
        why: &'static str,
    },
}

impl Figure {
    /// Panics, naming the backend, the robot and both values, unless the figure meets
    /// `expect`; prints the figure either way.
    pub fn check(&self, backend: &str, robot: &str, expect: &Expect) {
        println!(
            "{backend} {robot}: {} = {:.4} {} (physics {:.4})",
            self.name, self.measured, self.unit, self.physics
        );
        assert!(
            self.measured.is_finite(),
            "{backend} {robot}: {} is not finite",
            self.name
        );
        match expect {
            Expect::Physics { tolerance } => assert!(
                (self.measured - self.physics).abs() <= *tolerance,
                "{backend} {robot}: {} = {:.5} {}, physics says {:.5} ± {tolerance}",
                self.name,
                self.measured,
                self.unit,
                self.physics
            ),
            Expect::Deviates {
                value,
                tolerance,
                why,
            } => assert!(
                (self.measured - value).abs() <= *tolerance,
                "{backend} {robot}: {} = {:.5} {}, its known deviation is {value} ± {tolerance} \
                 ({why}; physics says {:.5}): the engine's contact changed",
                self.name,
                self.measured,
                self.unit,
                self.physics
            ),
        }
    }
}

/// The robot's foot radius (m): its first foot's first shape, which must be a sphere.
pub fn foot_radius(robot: &Robot) -> f64 {
    let model = &robot.model;
    let foot = &model.tracked()[0];
    match model.links()[foot.link].collisions[foot.shapes[0]].shape {
        Shape::Sphere { radius } => radius,
        ref other => panic!(
            "{}: the audit needs sphere feet, not {other:?}",
            model.name()
        ),
    }
}

/// A one-body probe: `mass` (kg) with inertia diagonal `inertia` (kg·m²) and `shapes` (URDF
/// `<collision>` elements), plus the never-touching bob on a free hinge.
fn probe(name: &str, mass: f64, inertia: [f64; 3], shapes: &str) -> Robot {
    let [ixx, iyy, izz] = inertia;
    let urdf = format!(
        r#"<?xml version="1.0"?>
<robot name="{name}">
  <link name="body">
    <inertial><origin xyz="0 0 0"/><mass value="{mass}"/>
      <inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/></inertial>
    {shapes}
  </link>
  <joint name="spin" type="revolute">
    <origin xyz="0 0 0"/><parent link="body"/><child link="bob"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="10"/>
  </joint>
  <link name="bob">
    <inertial><origin xyz="0 0 0"/><mass value="0.05"/>
      <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>
    <collision name="bob"><origin xyz="0 0 0"/><geometry><sphere radius="0.005"/></geometry></collision>
  </link>
</robot>
"#
    );
    let profile = format!(
        r#"
name = "{name}"
urdf = "{name}.urdf"
trunk = "body"
feet = [{{ name = "bob", link = "bob", collision = "bob" }}]
joints = [{{ name = "spin", urdf = "spin", standing = 0.0 }}]
[spawn]
height = 1.0
[gains]
kp = 1.0
kd = 0.1
"#
    );
    Robot::from_text(&urdf, &profile, &format!("contact-audit {name}"))
}

/// The sled for `robot`: four of its foot spheres at (±[`SLED_HALF_SPAN`], ±[`SLED_HALF_SPAN`])
/// on one body of the robot's mass (less the bob's 50 g), its inertia that of four point
/// masses at the feet.
pub fn sled(robot: &Robot) -> Robot {
    let r = foot_radius(robot);
    let a = SLED_HALF_SPAN;
    let mass = robot.model.total_mass() - 0.05;
    let shapes: String = [(a, a), (a, -a), (-a, a), (-a, -a)]
        .iter()
        .enumerate()
        .map(|(i, (x, y))| {
            format!(
                r#"<collision name="foot{i}"><origin xyz="{x} {y} 0"/><geometry><sphere radius="{r}"/></geometry></collision>"#
            )
        })
        .collect();
    let i = mass * a * a;
    probe("sled", mass, [i, i, 2.0 * i], &shapes)
}

/// The foot for `robot`: one of its foot spheres carrying a quarter of its mass (less the
/// bob's 50 g), the inertia of a solid sphere.
pub fn foot(robot: &Robot) -> Robot {
    let r = foot_radius(robot);
    let mass = robot.model.total_mass() / 4.0 - 0.05;
    let i = 0.4 * mass * r * r;
    let shape = format!(
        r#"<collision name="foot"><origin xyz="0 0 0"/><geometry><sphere radius="{r}"/></geometry></collision>"#
    );
    probe("foot", mass, [i, i, i], &shape)
}

/// The audit's physics parameters with gravity tilted by `theta_deg` towards azimuth
/// `azimuth_deg` (downhill is that direction on the flat ground).
fn params(theta_deg: f64, azimuth_deg: f64) -> PhysicsParams {
    let (t, a) = (theta_deg.to_radians(), azimuth_deg.to_radians());
    PhysicsParams {
        gravity: [G * t.sin() * a.cos(), G * t.sin() * a.sin(), -G * t.cos()],
        ground_friction: AUDIT_FRICTION,
        ..PhysicsParams::default()
    }
}

/// A horizontal unit vector at `azimuth_deg`.
fn heading(azimuth_deg: f64) -> Vector3<f64> {
    let a = azimuth_deg.to_radians();
    Vector3::new(a.cos(), a.sin(), 0.0)
}

/// `probe` on `B` under `params`, level at rest with its centre one foot radius above the
/// ground (its spheres just touching), after `settle` seconds of zero-torque steps.
fn settled<B: Backend>(
    probe: &Robot,
    radius: f64,
    params: &PhysicsParams,
    options: &B::Options,
    settle: f64,
) -> B {
    let mut b: B = build(probe, params, options);
    let mut s = probe.model.spawn_state();
    s.trunk.pose = Isometry3::translation(0.0, 0.0, radius);
    set(&mut b, &s);
    run(&mut b, steps_for(params, settle));
    b
}

fn run<B: Backend>(b: &mut B, steps: usize) {
    for _ in 0..steps {
        step_zero(b);
    }
}

fn position<B: Backend>(b: &B) -> Vector3<f64> {
    b.trunk().pose.translation.vector
}

/// The stick-slip angle atan μ (degrees).
pub fn stick_slip_angle_deg() -> f64 {
    AUDIT_FRICTION.atan().to_degrees()
}

/// The sled on an incline 5° below atan μ: its mean downhill speed (mm/s) over one second,
/// after half a second to settle. Physics: 0, it sticks.
pub fn sled_sticks_below_atan_mu<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    let theta = stick_slip_angle_deg() - INCLINE_MARGIN_DEG;
    let p = params(theta, 0.0);
    let mut b: B = settled(&sled(robot), foot_radius(robot), &p, options, 0.5);
    let p0 = position(&b);
    run(&mut b, steps_for(&p, 1.0));
    Figure {
        name: "creep at atan μ − 5°",
        unit: "mm/s",
        physics: 0.0,
        measured: 1e3 * (position(&b) - p0).dot(&heading(0.0)),
    }
}

/// The sled's downhill acceleration (m/s²) on an incline 5° above atan μ falling towards
/// `azimuth_deg`, from its speed at 0.5 s and 1.5 s.
fn sliding_acceleration<B: Backend>(robot: &Robot, options: &B::Options, azimuth: f64) -> Figure {
    let theta = stick_slip_angle_deg() + INCLINE_MARGIN_DEG;
    let p = params(theta, azimuth);
    let mut b: B = settled(&sled(robot), foot_radius(robot), &p, options, 0.5);
    let down = heading(azimuth);
    let v0 = b.trunk().linvel.dot(&down);
    run(&mut b, steps_for(&p, 1.0));
    let v1 = b.trunk().linvel.dot(&down);
    let t = theta.to_radians();
    Figure {
        name: if azimuth == 0.0 {
            "sliding acceleration at atan μ + 5°, along x"
        } else {
            "sliding acceleration at atan μ + 5°, along the diagonal"
        },
        unit: "m/s²",
        physics: G * (t.sin() - AUDIT_FRICTION * t.cos()),
        measured: v1 - v0,
    }
}

/// The sled on an incline 5° above atan μ, downhill along x: its acceleration (m/s²).
/// Physics: g (sin θ − μ cos θ).
pub fn sled_slides_above_atan_mu<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    sliding_acceleration::<B>(robot, options, 0.0)
}

/// As [`sled_slides_above_atan_mu`], downhill along the diagonal of x and y (azimuth 45°): a
/// Coulomb cone is round, so the answer is the same; a friction pyramid's is not.
pub fn sled_slides_along_the_diagonal<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    sliding_acceleration::<B>(robot, options, 45.0)
}

/// The ramp's time to reach μ N (s).
const PUSH_RAMP: f64 = 2.0;
/// The speed (m/s) that counts as sliding.
const SLIDE_SPEED: f64 = 1e-3;

/// How far (m) the pushed sled may slide before the ramp stops.
const PUSH_TRAVEL: f64 = 0.2;

/// The sled, settled on flat ground for 0.3 s, pushed along `azimuth_deg` by a force rising
/// from 0 at μ N per [`PUSH_RAMP`] seconds: the force at which it starts to slide for good,
/// over μ N.
///
/// The ramp runs until the sled has slid [`PUSH_TRAVEL`] or the force reaches 2.5 μ N (a
/// sled still stuck then reads 2.5). Sliding starts for good at the last moment the speed
/// along the push rose past [`SLIDE_SPEED`]: an engine whose sled slips and sticks again
/// before it slides is judged by the slide. That moment comes a little after the start:
/// under Coulomb friction the speed is k (t − t*)² / 2m after the start t* (k the ramp's
/// rate), so the force then is √(2 k m v) above the start's, which is subtracted.
fn breakaway<B: Backend>(robot: &Robot, options: &B::Options, azimuth: f64) -> Figure {
    let p = params(0.0, 0.0);
    let mut b: B = settled(&sled(robot), foot_radius(robot), &p, options, 0.3);
    let m = b.total_mass();
    let limit = AUDIT_FRICTION * m * G;
    let rate = limit / PUSH_RAMP;
    let dir = heading(azimuth);
    let start = position(&b);
    let (mut sliding, mut ratio) = (false, 2.5);
    for n in 1..=steps_for(&p, 2.5 * PUSH_RAMP) {
        let force = rate * n as f64 * p.dt;
        b.push_trunk(&(dir * (force * p.dt / m)))
            .unwrap_or_else(|e| panic!("{} refused a push: {e}", B::NAME));
        step_zero(&mut b);
        let now = b.trunk().linvel.dot(&dir) > SLIDE_SPEED;
        if now && !sliding {
            ratio = (force - (2.0 * rate * m * SLIDE_SPEED).sqrt()) / limit;
        }
        sliding = now;
        if (position(&b) - start).dot(&dir) > PUSH_TRAVEL {
            break;
        }
    }
    if !sliding {
        ratio = 2.5;
    }
    Figure {
        name: if azimuth == 0.0 {
            "push at which it slides, along x, over μN"
        } else {
            "push at which it slides, along the diagonal, over μN"
        },
        unit: "",
        physics: 1.0,
        measured: ratio,
    }
}

/// The sled pushed along x under its load: the force where it starts to slide, over μ N.
/// Physics: 1.
pub fn sled_breaks_away_at_mu_n<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    breakaway::<B>(robot, options, 0.0)
}

/// As [`sled_breaks_away_at_mu_n`], pushed along the diagonal of x and y. Physics: 1 (a
/// round cone).
pub fn sled_breaks_away_along_the_diagonal<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) -> Figure {
    breakaway::<B>(robot, options, 45.0)
}

/// What a dropped foot did: the heights (m) of its centre at the top of its first rebound, and
/// where it lies a second after it was let go.
struct Drop {
    /// The highest the centre got after its first lowest point following the first contact,
    /// before it fell again out of contact (a foot that never leaves the contact has no such
    /// fall: its highest point over the rest of the second).
    peak: f64,
    /// The centre's height a second after the drop began.
    rest: f64,
}

/// The foot dropped from rest with its bottom 5 cm above flat ground, followed for a second:
/// (the top of its first rebound above where it lies at the end (mm); how far its bottom is
/// below the ground at the end (mm)).
fn drop_foot<B: Backend>(robot: &Robot, options: &B::Options) -> (f64, f64) {
    let r = foot_radius(robot);
    let d = drop_foot_under::<B>(robot, options, &ContactDraw::NOMINAL, 0.05)
        .unwrap_or_else(|e| panic!("{} refused the nominal contact: {e}", B::NAME));
    (1e3 * (d.peak - d.rest), 1e3 * (r - d.rest))
}

/// As [`drop_foot`], from `height` (m) above the ground, the engine's contact given
/// `contact`'s factors and restitution first ([`Backend::set_dynamics`]; not given when
/// nominal, so the nominal figures are the audit's own); the engine's refusal as the error.
fn drop_foot_under<B: Backend>(
    robot: &Robot,
    options: &B::Options,
    contact: &ContactDraw,
    height: f64,
) -> Result<Drop, PhysicsError> {
    let r = foot_radius(robot);
    let probe = foot(robot);
    let p = params(0.0, 0.0);
    let mut b: B = build(&probe, &p, options);
    if !contact.is_nominal() {
        b.set_dynamics(&Dynamics {
            contact: *contact,
            ..Dynamics::nominal(&probe.model, &p)
        })?;
    }
    let mut s: RobotState = probe.model.spawn_state();
    s.trunk.pose = Isometry3::translation(0.0, 0.0, r + height);
    set(&mut b, &s);
    let trunk = probe.model.trunk_tracked_index();
    let (mut touched, mut rebounding, mut falling_again) = (false, false, false);
    let mut peak = f64::NEG_INFINITY;
    for _ in 0..steps_for(&p, 1.0) {
        step_zero(&mut b);
        let touching = read_contacts(&b)[trunk];
        touched |= touching;
        let (z, vz) = (position(&b).z, b.trunk().linvel.z);
        rebounding |= touched && vz >= 0.0;
        falling_again |= rebounding && !touching && vz < 0.0 && z < peak;
        if rebounding && !falling_again {
            peak = peak.max(z);
        }
    }
    assert!(rebounding, "{}: the dropped foot never landed", B::NAME);
    Ok(Drop {
        peak,
        rest: position(&b).z,
    })
}

/// The drawn contact's stiffness factor in action: the foot dropped 5 cm, a second later, how
/// deep its bottom is below the ground (mm) with the engine's contact stiffness times
/// `stiffness_scale` (damping as the engine's own); the engine's refusal as the error. A
/// stiffer contact sinks less under the same load.
pub fn penetration_at_rest_with_stiffness<B: Backend>(
    robot: &Robot,
    options: &B::Options,
    stiffness_scale: f64,
) -> Result<f64, PhysicsError> {
    let contact = ContactDraw {
        contact_stiffness_scale: stiffness_scale,
        ..ContactDraw::NOMINAL
    };
    let d = drop_foot_under::<B>(robot, options, &contact, 0.05)?;
    Ok(1e3 * (foot_radius(robot) - d.rest))
}

/// Under any drawn contact `contact`: the foot set down just touching the ground at rest, a
/// second later, how deep its bottom is below the ground (mm); the engine's refusal as the
/// error. Set down, not dropped, so that a drawn restitution has no impact to give back: a
/// dropped foot with e > 0 keeps bouncing by micrometres where the spring lets go of it.
pub fn penetration_at_rest_under<B: Backend>(
    robot: &Robot,
    options: &B::Options,
    contact: &ContactDraw,
) -> Result<f64, PhysicsError> {
    let d = drop_foot_under::<B>(robot, options, contact, 0.0)?;
    Ok(1e3 * (foot_radius(robot) - d.rest))
}

/// The drop height of [`bounce_with_restitution`] (m): an impact at 1.98 m/s, well above
/// the engines' thresholds for applying restitution (DART's 0.1 m/s, rapier's none).
pub const RESTITUTION_DROP_M: f64 = 0.2;

/// The drawn restitution in action: the foot dropped [`RESTITUTION_DROP_M`], how high its
/// bottom gets above the ground at the top of its first rebound (mm) with the contact's
/// restitution coefficient `restitution`; the engine's refusal as the error. Physics: e² times
/// the drop height. (Measured from the ground, not from where the foot lies a second later:
/// with e near 1 it is still bouncing then.)
pub fn bounce_with_restitution<B: Backend>(
    robot: &Robot,
    options: &B::Options,
    restitution: f64,
) -> Result<f64, PhysicsError> {
    let contact = ContactDraw {
        restitution,
        ..ContactDraw::NOMINAL
    };
    let d = drop_foot_under::<B>(robot, options, &contact, RESTITUTION_DROP_M)?;
    Ok(1e3 * (d.peak - foot_radius(robot)))
}

/// Checks, for an engine that maps `randomize.contact_stiffness_scale`, that a stiffer contact
/// sinks the loaded foot less as k = s · k₀ says: the depth at rest goes as 1/s, so a factor 4
/// stiffer is a quarter as deep (within 10 %), at ×0.25, ×1 and ×4; panics with the figures.
pub fn assert_stiffness_scales_penetration<B: Backend>(robot: &Robot, options: &B::Options) {
    let depth = |s: f64| {
        penetration_at_rest_with_stiffness::<B>(robot, options, s)
            .unwrap_or_else(|e| panic!("{} refused a stiffness factor of {s}: {e}", B::NAME))
    };
    let (soft, nominal, stiff) = (depth(0.25), depth(1.0), depth(4.0));
    println!(
        "{} penetration at rest: ×0.25 {soft:.5} mm, ×1 {nominal:.5} mm, ×4 {stiff:.5} mm",
        B::NAME
    );
    assert!(
        nominal > 0.0,
        "{}: a soft contact sinks: {nominal}",
        B::NAME
    );
    for ratio in [nominal / stiff, soft / nominal] {
        assert!(
            (ratio - 4.0).abs() < 0.4,
            "{}: ×0.25 {soft}, ×1 {nominal}, ×4 {stiff} mm",
            B::NAME
        );
    }
}

/// Checks, for an engine that maps `randomize.restitution`, that none gives no bounce (under
/// 0.5 mm) and 0.5 bounces the foot dropped [`RESTITUTION_DROP_M`] e² h (within 10 %); panics
/// with the figures.
pub fn assert_restitution_raises_the_bounce<B: Backend>(robot: &Robot, options: &B::Options) {
    let none = bounce_with_restitution::<B>(robot, options, 0.0)
        .unwrap_or_else(|err| panic!("{} refused no restitution: {err}", B::NAME));
    println!("{} bounce from 20 cm: e = 0 {none:.3} mm", B::NAME);
    assert!(
        none < 0.5,
        "{}: no restitution, no bounce: {none} mm",
        B::NAME
    );
    assert_bounce_follows_restitution::<B>(robot, options, &[0.5], 0.1);
}

/// Checks, for an engine that maps `randomize.restitution`, that each of `restitutions` (in
/// (0, 1], rising) bounces the foot dropped [`RESTITUTION_DROP_M`] to e² h within
/// `relative_tolerance` of it, each higher than the last; panics with the figures.
pub fn assert_bounce_follows_restitution<B: Backend>(
    robot: &Robot,
    options: &B::Options,
    restitutions: &[f64],
    relative_tolerance: f64,
) {
    let mut last = f64::NEG_INFINITY;
    for &e in restitutions {
        let bounce = bounce_with_restitution::<B>(robot, options, e)
            .unwrap_or_else(|err| panic!("{} refused a restitution of {e}: {err}", B::NAME));
        let physics = e * e * 1e3 * RESTITUTION_DROP_M;
        let error = bounce / physics - 1.0;
        println!(
            "{} bounce from 20 cm: e = {e} {bounce:.3} mm (e²h {physics:.3} mm, {:+.1} %)",
            B::NAME,
            100.0 * error
        );
        assert!(
            error.abs() <= relative_tolerance,
            "{}: e = {e} bounced {bounce} mm, e²h = {physics} mm ± {} %",
            B::NAME,
            100.0 * relative_tolerance
        );
        assert!(
            bounce > last,
            "{}: e = {e} bounced {bounce} mm, not higher than {last} mm",
            B::NAME
        );
        last = bounce;
    }
}

/// The foot dropped 5 cm: how high it bounces above where it comes to rest (mm).
/// Physics: 0, contacts are inelastic.
pub fn dropped_foot_does_not_bounce<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    Figure {
        name: "bounce of the foot dropped 5 cm",
        unit: "mm",
        physics: 0.0,
        measured: drop_foot::<B>(robot, options).0,
    }
}

/// The foot dropped 5 cm, a second later: how deep its bottom is below the ground (mm).
/// Physics: 0, rigid bodies do not interpenetrate.
pub fn foot_at_rest_does_not_penetrate<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    Figure {
        name: "penetration of the foot at rest",
        unit: "mm",
        physics: 0.0,
        measured: drop_foot::<B>(robot, options).1,
    }
}

/// `probe` settled on flat ground for 0.3 s, then set spinning at `spin` rad/s about the
/// vertical (from its settled state) and run for `seconds`: its angular deceleration (rad/s²).
fn spin_down<B: Backend>(
    probe: &Robot,
    radius: f64,
    options: &B::Options,
    spin: f64,
    seconds: f64,
) -> f64 {
    let p = params(0.0, 0.0);
    let mut b: B = settled(probe, radius, &p, options, 0.3);
    let mut s = b.state();
    s.trunk.angvel = Vector3::new(0.0, 0.0, spin);
    set(&mut b, &s);
    run(&mut b, steps_for(&p, seconds));
    (spin - b.trunk().angvel.z) / seconds
}

/// The loaded foot set spinning at 2 rad/s about the vertical: the torque (N·m) that slows it
/// over half a second, its angular deceleration times its moment of inertia. Physics: 0, a
/// sphere touches the ground at a point, and a point has no arm for friction to act on.
pub fn loaded_foot_spins_freely<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    let r = foot_radius(robot);
    let probe = foot(robot);
    let izz = probe.model.links()[0].inertia[(2, 2)];
    let decel = spin_down::<B>(&probe, r, options, 2.0, 0.5);
    Figure {
        name: "torque resisting the loaded foot's spin",
        unit: "N·m",
        physics: 0.0,
        measured: izz * decel,
    }
}

/// The sled set spinning at 10 rad/s about the vertical: its angular deceleration over
/// 0.2 s (rad/s²). Physics: each foot, at d = √2 · [`SLED_HALF_SPAN`] from the centre, slides
/// with friction μ N / 4 against its motion, so the deceleration is μ N d / I_z.
pub fn sled_spin_slows_at_mu_n_d<B: Backend>(robot: &Robot, options: &B::Options) -> Figure {
    let probe = sled(robot);
    let body = &probe.model.links()[0];
    let izz = body.inertia[(2, 2)];
    let load = probe.model.total_mass() * G;
    let d = SQRT_2 * SLED_HALF_SPAN;
    let decel = spin_down::<B>(&probe, foot_radius(robot), options, 10.0, 0.2);
    Figure {
        name: "spin-down of the sled",
        unit: "rad/s²",
        physics: AUDIT_FRICTION * load * d / izz,
        measured: decel,
    }
}

/// Every audit, in the table's order.
pub fn audits<B: Backend>() -> [fn(&Robot, &B::Options) -> Figure; 9] {
    [
        sled_sticks_below_atan_mu::<B>,
        sled_slides_above_atan_mu::<B>,
        sled_slides_along_the_diagonal::<B>,
        sled_breaks_away_at_mu_n::<B>,
        sled_breaks_away_along_the_diagonal::<B>,
        dropped_foot_does_not_bounce::<B>,
        foot_at_rest_does_not_penetrate::<B>,
        loaded_foot_spins_freely::<B>,
        sled_spin_slows_at_mu_n_d::<B>,
    ]
}

/// Prints [`table`]'s rows for both bundled robots (HyQ and ANYmal C) under each labelled set of
/// options, each row after its label (none when the label is empty), for the docs' table; panics
/// unless every robot gives one row per audit (9).
pub fn print_table<B: Backend>(variants: &[(&str, B::Options)]) {
    for (label, options) in variants {
        for name in ["hyq", "anymal_c"] {
            let rows = table::<B>(&Robot::bundled(name), options);
            for r in &rows {
                if label.is_empty() {
                    println!("{r}");
                } else {
                    println!("{label} {r}");
                }
            }
            assert_eq!(rows.len(), 9, "one row per audit");
        }
    }
}

/// Every audit of `robot` on `B`, as Markdown table rows
/// `| robot | figure | unit | physics | measured |`.
pub fn table<B: Backend>(robot: &Robot, options: &B::Options) -> Vec<String> {
    audits::<B>()
        .iter()
        .map(|audit| {
            let f = audit(robot, options);
            format!(
                "| {} | {} | {} | {:.4} | {:.4} |",
                robot.model.name(),
                f.name,
                f.unit,
                f.physics,
                f.measured
            )
        })
        .collect()
}

/// Instantiates the contact audit for a backend on one robot, as `#[test]` functions in the
/// calling module: `contact_audit_tests!(Backend, options, robot, { audit => expect, … })`,
/// each `audit` a function of [`contact_audit`](crate::contact_audit) and each `expect` an
/// [`Expect`].
#[macro_export]
macro_rules! contact_audit_tests {
    ($backend:ty, $options:expr, $robot:expr, { $($name:ident => $expect:expr),* $(,)? }) => {
        $(
            #[test]
            fn $name() {
                let options = $options;
                let robot = $robot;
                let figure = $crate::contact_audit::$name::<$backend>(&robot, &options);
                figure.check(
                    <$backend as $crate::hyq_physics::Backend>::NAME,
                    robot.model.name(),
                    &$expect,
                );
            }
        )*
    };
}
