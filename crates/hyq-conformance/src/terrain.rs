//! The ground as a height field: every engine builds the surface [`HeightGrid`] describes (its
//! heights, its place, its one diagonal per cell), puts contacts where that surface is, gives
//! it the ground friction, stands the robot on slopes and stairs, and keeps the API contract
//! (state kept across a change of ground, resets bitwise).
//!
//! Two one-body probe robots stand in for a loose shape: a 5 cm ball ([`ball`]) and a
//! 20 × 20 × 10 cm block ([`block`]), each 1 kg (plus a 5 mm sphere on a free hinge at its
//! centre, which never touches the ground: a robot profile needs a foot and a joint).

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};

use super::fixtures::{
    Rng, Robot, build, build_default, first_difference, random_pd_trajectory, read_contacts, set,
    step_pd, step_zero, steps_for,
};
use hyq_physics::actuator::{Actuator, PdScratch};
use hyq_physics::model::RobotModel;
use hyq_physics::terrain::generate::{Climb, Extent, Relief, Rough, Slope, Stairs, generate};
use hyq_physics::terrain::placement::place;
use hyq_physics::terrain::{HeightGrid, Terrain};
use hyq_physics::{Backend, PhysicsParams, RobotState};

/// The probe robots' URDF, with `SHAPE` and `INERTIA` to fill in.
const PROBE_URDF: &str = r#"<?xml version="1.0"?>
<robot name="probe">
  <link name="body">
    <inertial><origin xyz="0 0 0"/><mass value="1"/>INERTIA</inertial>
    <collision name="body"><origin xyz="0 0 0"/><geometry>SHAPE</geometry></collision>
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
"#;

/// The probe robots' profile.
const PROBE_PROFILE: &str = r#"
name = "probe"
urdf = "probe.urdf"
trunk = "body"
feet = [{ name = "bob", link = "bob", collision = "bob" }]
joints = [{ name = "spin", urdf = "spin", standing = 0.0 }]
[spawn]
height = 1.0
[gains]
kp = 1.0
kd = 0.1
"#;

/// The ball probe's radius (m).
pub const BALL_RADIUS: f64 = 0.05;

fn probe(shape: &str, inertia: &str) -> Robot {
    let urdf = PROBE_URDF
        .replace("SHAPE", shape)
        .replace("INERTIA", inertia);
    Robot::from_text(&urdf, PROBE_PROFILE, "terrain probe")
}

/// A 1 kg ball of radius [`BALL_RADIUS`] (solid-sphere inertia).
pub fn ball() -> Robot {
    probe(
        &format!(r#"<sphere radius="{BALL_RADIUS}"/>"#),
        r#"<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>"#,
    )
}

/// A 1 kg block of 20 × 20 × 10 cm (solid-box inertia).
pub fn block() -> Robot {
    probe(
        r#"<box size="0.2 0.2 0.1"/>"#,
        r#"<inertia ixx="0.0041667" ixy="0" ixz="0" iyy="0.0041667" iyz="0" izz="0.0066667"/>"#,
    )
}

/// Rough ground 3 × 3 m around the origin: bumps of ±4 cm, 25 cm across, at 5 cm resolution.
pub fn rough_ground() -> Terrain {
    let extent = Extent {
        center: [0.0, 0.0],
        size: [3.0, 3.0],
        resolution: 0.05,
    };
    let relief = Relief::Rough(Rough {
        amplitude: 0.04,
        feature: 0.25,
    });
    Terrain::field(generate(&extent, &relief, [0.0, 0.0], 11).expect("valid rough ground"))
}

/// A 3 × 3 m plane through the origin rising at `angle_deg` towards `direction_deg`.
pub fn slope(angle_deg: f64, direction_deg: f64) -> Terrain {
    let extent = Extent {
        center: [0.0, 0.0],
        size: [3.0, 3.0],
        resolution: 0.1,
    };
    let relief = Relief::Slope(Slope {
        angle_deg,
        direction_deg,
    });
    Terrain::field(generate(&extent, &relief, [0.0, 0.0], 0).expect("valid slope"))
}

/// A 2 × 2 m grid at 10 cm whose every height is drawn independently in ±5 cm: each cell is
/// warped, so splitting a cell along its other diagonal would move the surface by up to
/// centimetres.
pub fn warped_ground() -> Terrain {
    let mut rng = Rng::new(21);
    let n = 21;
    let heights = (0..n * n).map(|_| rng.range(-0.05, 0.05)).collect();
    Terrain::field(
        HeightGrid::new([0.0, 0.0], [2.0, 2.0], n, n, heights).expect("valid warped ground"),
    )
}

/// `robot` on `B` with `terrain`.
fn on<B: Backend>(robot: &Robot, params: &PhysicsParams, options: &B::Options, t: &Terrain) -> B {
    let mut b: B = build(robot, params, options);
    b.set_terrain(t)
        .unwrap_or_else(|e| panic!("{} refused a terrain: {e}", B::NAME));
    b
}

/// A probe's state with its centre at `centre`, level, at rest.
fn probe_at(robot: &Robot, centre: Point3<f64>) -> RobotState {
    let mut s = robot.model.spawn_state();
    s.trunk.pose = Isometry3::translation(centre.x, centre.y, centre.z);
    s
}

/// The height above (x, y) where a point is `distance` from the surface (bisection between
/// the surface and 1 m above it).
fn height_at_distance(grid: &HeightGrid, x: f64, y: f64, distance: f64) -> f64 {
    let base = grid.height_at(x, y);
    let (mut lo, mut hi) = (base - 0.2, base + 1.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if grid.point_distance(&Point3::new(x, y, mid)) < distance {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// A ball dropped 5 cm onto rough ground comes to lie on it: over its last second (of two),
/// while it rolls wherever the bumps take it, its centre stays one radius from the grid's
/// triangulated surface to ±1 mm at every step; and its contact flag follows its true distance
/// all the way: never set while it is more than `contact_distance` + 0.5 mm away before and
/// after a step, always set when a step starts with it touching.
pub fn ball_rests_on_rough_ground_at_the_grids_height<B: Backend>(
    _robot: &Robot,
    options: &B::Options,
) {
    let ball = ball();
    let terrain = rough_ground();
    let grid = terrain.grid().expect("a field");
    let params = PhysicsParams::default();
    let mut b: B = on(&ball, &params, options, &terrain);
    let (x, y) = (0.23, -0.41);
    let start = Point3::new(x, y, height_at_distance(grid, x, y, BALL_RADIUS + 0.05));
    set(&mut b, &probe_at(&ball, start));
    let trunk = ball.model.trunk_tracked_index();
    let cd = params.contact_distance;
    let gap = |b: &B| grid.point_distance(&b.trunk().pose.translation.vector.into()) - BALL_RADIUS;
    let mut before = gap(&b);
    let steps = steps_for(&params, 2.0);
    let (mut worst, mut rolled, mut last) = (0.0f64, 0.0, b.trunk().pose.translation.vector);
    for n in 1..=steps {
        step_zero(&mut b);
        let after = gap(&b);
        let flag = read_contacts(&b)[trunk];
        if before > cd + 5e-4 && after > cd + 5e-4 {
            assert!(
                !flag,
                "step {n}: ball reported in contact {:.2} mm away",
                1e3 * after
            );
        }
        if before <= 0.0 {
            assert!(
                flag,
                "step {n}: ball started the step touching ({:.3} mm) but no contact",
                1e3 * before
            );
        }
        before = after;
        if 2 * n > steps {
            worst = worst.max(after.abs());
            let now = b.trunk().pose.translation.vector;
            rolled += (now - last).norm();
            last = now;
        } else {
            last = b.trunk().pose.translation.vector;
        }
    }
    println!(
        "{}: ball dropped at ({x}, {y}) rolled {:.3} m over its last second to ({:.4}, {:.4}), \
         its centre at most {:.3} mm from one radius off the grid's surface",
        B::NAME,
        rolled,
        last.x,
        last.y,
        1e3 * worst
    );
    assert!(
        worst <= 1e-3,
        "the ball lay up to {:.3} mm from one radius off the grid's surface",
        1e3 * worst
    );
}

/// On a grid whose every cell is warped, a ball set still (no gravity) 0.75 mm into the
/// surface is in contact after one step, and one set `contact_distance` + 0.75 mm above it is
/// not, at 48 places on both sides of the cells' diagonals: the engine's surface is the
/// grid's, split along the same diagonals, to within a millimetre.
pub fn contacts_follow_the_grids_triangles<B: Backend>(_robot: &Robot, options: &B::Options) {
    let ball = ball();
    let terrain = warped_ground();
    let grid = terrain.grid().expect("a field");
    let params = super::fixtures::zero_gravity();
    let mut b: B = on(&ball, &params, options, &terrain);
    let trunk = ball.model.trunk_tracked_index();
    let mut checked = 0;
    for cell in 0..24 {
        let (c, k) = (6 + cell % 6, 6 + cell / 6);
        for (u, v) in [(0.3, 0.7), (0.7, 0.3)] {
            let [dx, dy] = grid.spacing();
            let p = grid.point(c, k);
            let (x, y) = (p.x + u * dx, p.y + v * dy);
            for (distance, expected) in [
                (BALL_RADIUS - 7.5e-4, true),
                (BALL_RADIUS + params.contact_distance + 7.5e-4, false),
            ] {
                let z = height_at_distance(grid, x, y, distance);
                set(&mut b, &probe_at(&ball, Point3::new(x, y, z)));
                step_zero(&mut b);
                let flag = read_contacts(&b)[trunk];
                assert_eq!(
                    flag,
                    expected,
                    "ball at ({x:.3}, {y:.3}), {:.2} mm from one radius off the grid's surface: \
                     contact {flag}, expected {expected}",
                    1e3 * (distance - BALL_RADIUS)
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 96);
}

/// How the block of [`the_fields_friction_is_the_ground_friction`] gets its friction.
#[derive(Clone, Copy, Debug)]
enum FrictionFrom {
    /// [`PhysicsParams::ground_friction`] at build.
    Params,
    /// [`Backend::set_dynamics`] before the ground is given.
    DynamicsFirst,
    /// [`Backend::set_dynamics`] after the ground is given.
    DynamicsAfter,
}

/// The block resting on `terrain` (10° slope rising along +x) with `friction` given as
/// `from` says: how far it moves in 1 s after settling for 0.2 s (m).
fn block_slide<B: Backend>(
    options: &B::Options,
    terrain: &Terrain,
    friction: f64,
    from: FrictionFrom,
) -> f64 {
    let block = block();
    let params = PhysicsParams {
        ground_friction: if matches!(from, FrictionFrom::Params) {
            friction
        } else {
            1.0
        },
        ..PhysicsParams::default()
    };
    let dynamics = hyq_physics::dynamics::Dynamics {
        ground_friction: friction,
        ..hyq_physics::dynamics::Dynamics::nominal(&block.model, &params)
    };
    let mut b: B = build(&block, &params, options);
    let give = |b: &mut B| {
        b.set_dynamics(&dynamics)
            .unwrap_or_else(|e| panic!("{} refused dynamics: {e}", B::NAME));
    };
    if matches!(from, FrictionFrom::DynamicsFirst) {
        give(&mut b);
    }
    b.set_terrain(terrain)
        .unwrap_or_else(|e| panic!("{} refused a terrain: {e}", B::NAME));
    if matches!(from, FrictionFrom::DynamicsAfter) {
        give(&mut b);
    }
    // Resting flat on the slope, its bottom face 0.5 mm above it.
    let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -10f64.to_radians());
    let centre = Point3::origin() + tilt * Vector3::z() * (0.05 + 5e-4);
    let mut s = probe_at(&block, centre);
    s.trunk.pose.rotation = tilt;
    set(&mut b, &s);
    for _ in 0..steps_for(&params, 0.2) {
        step_zero(&mut b);
    }
    let settled = b.trunk().pose.translation.vector;
    for _ in 0..steps_for(&params, 1.0) {
        step_zero(&mut b);
    }
    (b.trunk().pose.translation.vector - settled).norm()
}

/// The field has the ground friction, from the physics parameters or from the dynamics given
/// ([`Backend::set_dynamics`], before or after the field): a block on a 10° slope stays put
/// with friction 1 (within 1 mm over 1 s) and slides down with friction 0.1 (below
/// tan 10° = 0.176: at least 25 cm in 1 s, where Coulomb's law gives 37 cm from rest).
pub fn the_fields_friction_is_the_ground_friction<B: Backend>(
    _robot: &Robot,
    options: &B::Options,
) {
    let terrain = slope(10.0, 0.0);
    for from in [
        FrictionFrom::Params,
        FrictionFrom::DynamicsFirst,
        FrictionFrom::DynamicsAfter,
    ] {
        for (friction, holds) in [(1.0, true), (0.1, false)] {
            let moved = block_slide::<B>(options, &terrain, friction, from);
            println!(
                "{}: block on a 10° slope with friction {friction} ({from:?}) moved {:.2} mm \
                 in 1 s",
                B::NAME,
                1e3 * moved
            );
            if holds {
                assert!(
                    moved < 1e-3,
                    "friction {friction} ({from:?}): the block slid {:.2} mm",
                    1e3 * moved
                );
            } else {
                assert!(
                    moved > 0.25,
                    "friction {friction} ({from:?}): the block slid only {moved:.3} m"
                );
            }
        }
    }
}

/// A new ground keeps the dynamics the world was given: every body's mass properties read back
/// the same after `set_terrain` as before, and the world runs bitwise as one given the ground
/// first and the dynamics after.
pub fn a_new_ground_keeps_the_worlds_dynamics<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = Arc::clone(&robot.model);
    let params = PhysicsParams::default();
    let mut dynamics = hyq_physics::dynamics::Dynamics::nominal(&model, &params);
    dynamics.ground_friction = 0.6;
    dynamics.bodies[0].mass += 7.5;
    dynamics.bodies[0].com.x += 0.02;
    for d in &mut dynamics.joint_damping {
        *d += 0.3;
    }
    let terrain = rough_ground();
    let mut start = model.spawn_state();
    start.trunk.pose.translation.z += terrain.height_at(0.0, 0.0) + 0.05;

    let mut first: B = build_default(robot, options);
    first
        .set_dynamics(&dynamics)
        .unwrap_or_else(|e| panic!("{} refused dynamics: {e}", B::NAME));
    let before: Vec<_> = (0..model.num_links())
        .map(|i| first.body_mass_properties(i))
        .collect();
    first
        .set_terrain(&terrain)
        .unwrap_or_else(|e| panic!("{} refused a terrain: {e}", B::NAME));
    for (i, b) in before.iter().enumerate() {
        assert_eq!(
            *b,
            first.body_mass_properties(i),
            "body {i}'s mass properties changed with the ground"
        );
    }
    set(&mut first, &start);
    let a = random_pd_trajectory(&mut first, 6, 300);

    let mut second: B = on(robot, &params, options, &terrain);
    second
        .set_dynamics(&dynamics)
        .unwrap_or_else(|e| panic!("{} refused dynamics: {e}", B::NAME));
    set(&mut second, &start);
    let b = random_pd_trajectory(&mut second, 6, 300);
    assert_eq!(
        first_difference(&a, &b),
        None,
        "dynamics then ground differs from ground then dynamics"
    );
}

/// `state` put down on `terrain` with its trunk tilted to the ground under its feet, the
/// lowest foot 1 mm up; panics if another part of the robot would be in the ground.
fn stand_on(model: &RobotModel, terrain: &Terrain, state: &RobotState) -> RobotState {
    let placed = place(model, terrain, state, true, 1e-3);
    assert!(
        placed.other_clearance > 0.0,
        "{} cannot stand there: a part other than a foot is {:.1} mm in the ground",
        model.name(),
        -1e3 * placed.other_clearance
    );
    placed.state
}

/// How far the feet slid and the trunk moved while standing (m).
struct Drift {
    /// The largest horizontal movement of any foot.
    feet: f64,
    /// The largest movement of the trunk.
    trunk: f64,
}

/// Each tracked body's first shape's centre with the bodies at `poses`: a foot sphere's centre
/// moves only if the foot slides or rolls.
fn shape_centres(model: &RobotModel, poses: &[Isometry3<f64>]) -> Vec<Vector3<f64>> {
    model
        .tracked()
        .iter()
        .map(|t| {
            let origin = model.links()[t.link].collisions[t.shapes[0]].origin;
            (poses[t.link] * origin).translation.vector
        })
        .collect()
}

/// Holds the standing pose for 4 s from `start` on `terrain` and checks the last 2 s: every
/// foot in contact at every step, the trunk never, no foot sliding more than 1 mm sideways
/// and the trunk moving no more than 3 mm (its legs settle under the PD law). Returns both.
fn stands<B: Backend>(
    robot: &Robot,
    options: &B::Options,
    terrain: &Terrain,
    start: &RobotState,
    what: &str,
) -> Drift {
    let params = PhysicsParams::default();
    let mut b: B = on(robot, &params, options, terrain);
    let model = Arc::clone(&robot.model);
    set(&mut b, start);
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = model.standing_pose().to_vec();
    let trunk = model.trunk_tracked_index();
    let steps = steps_for(&params, 4.0);
    let settle = steps / 2;
    let mut reference: Option<Vec<Vector3<f64>>> = None;
    let mut drift = Drift {
        feet: 0.0,
        trunk: 0.0,
    };
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    for n in 1..=steps {
        step_pd(&mut b, &act, &targets, &mut scratch);
        let flags = read_contacts(&b);
        assert!(
            !flags[trunk],
            "{what}: the trunk touched the ground at step {n}"
        );
        if n <= settle {
            continue;
        }
        for (t, foot) in model.tracked()[..model.num_feet()].iter().enumerate() {
            assert!(
                flags[t],
                "{what}: foot {} not in contact at step {n}",
                foot.name
            );
        }
        b.link_poses(&mut poses);
        let points = shape_centres(&model, &poses);
        let first = reference.get_or_insert_with(|| points.clone());
        for (t, (p, q)) in points.iter().zip(first.iter()).enumerate() {
            let d = p - q;
            if t == trunk {
                drift.trunk = drift.trunk.max(d.norm());
            } else {
                drift.feet = drift.feet.max(d.xy().norm());
            }
        }
    }
    println!(
        "{}: {} {what}: over the last 2 s the feet slid at most {:.3} mm, the trunk moved at \
         most {:.3} mm",
        B::NAME,
        model.name(),
        1e3 * drift.feet,
        1e3 * drift.trunk
    );
    assert!(
        drift.feet <= 1e-3,
        "{what}: a foot slid {:.2} mm over the last 2 s",
        1e3 * drift.feet
    );
    assert!(
        drift.trunk <= 3e-3,
        "{what}: the trunk moved {:.2} mm over the last 2 s",
        1e3 * drift.trunk
    );
    drift
}

/// Standing on a 10° slope (rising towards 0° and towards 120°, the robot heading 30°), trunk
/// tilted to the slope at the start, the robot holds its standing pose: over the last 2 of
/// 4 s every foot touches the ground at every step, the trunk never, no foot slides more than
/// 1 mm (friction 1 is well above tan 10° = 0.18) and the trunk moves no more than 3 mm.
pub fn robot_stands_on_a_10_degree_slope<B: Backend>(robot: &Robot, options: &B::Options) {
    for direction in [0.0, 120.0] {
        let terrain = slope(10.0, direction);
        let mut start = robot.model.spawn_state();
        start.trunk.pose.rotation =
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians());
        let start = stand_on(&robot.model, &terrain, &start);
        stands::<B>(
            robot,
            options,
            &terrain,
            &start,
            &format!("on a 10° slope rising towards {direction}°"),
        );
    }
}

/// Standing across a stair edge (8 cm steps 40 cm deep, the front feet 4 cm past the riser of
/// the step above the hind feet), the robot holds its standing pose as on the slope: every foot
/// in contact, the trunk never, no foot sliding more than 1 mm and the trunk moving no more
/// than 3 mm over the last 2 of 4 s.
pub fn robot_stands_across_a_stair_edge<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = &robot.model;
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    let spawn = model.spawn_state();
    model
        .link_poses(&spawn.trunk.pose, &spawn.q, &mut poses)
        .expect("forward kinematics of the spawn state");
    let front = (0..model.num_feet())
        .map(|t| poses[model.tracked()[t].link].translation.x)
        .fold(f64::NEG_INFINITY, f64::max);
    let extent = Extent {
        center: [0.0, 0.0],
        size: [3.0, 3.0],
        resolution: 0.02,
    };
    let relief = Relief::Stairs(Stairs {
        step_height: 0.08,
        step_depth: 0.4,
        direction_deg: 0.0,
        climb: Climb::Up,
        start: front - 0.04,
    });
    let terrain = Terrain::field(generate(&extent, &relief, [0.0, 0.0], 0).expect("valid stairs"));
    let start = stand_on(model, &terrain, &spawn);
    stands::<B>(robot, options, &terrain, &start, "across a stair edge");
}

/// Laid limp upside down 2 cm above the highest point of rough ground under its trunk, the
/// robot lands on its trunk, which is then reported in contact within 0.5 s, and not while
/// its trunk is surely more than `contact_distance` + 1 mm from the ground.
pub fn limp_robot_lands_its_trunk_on_rough_ground<B: Backend>(robot: &Robot, options: &B::Options) {
    let terrain = rough_ground();
    let params = PhysicsParams::default();
    let mut b: B = on(robot, &params, options, &terrain);
    let model = Arc::clone(&robot.model);
    let trunk = model.trunk_tracked_index();
    let mut s = model.spawn_state();
    s.trunk.pose.rotation = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let lowest_trunk = |b: &B| trunk_clearance(&model, &terrain, b);
    set(&mut b, &s);
    let lower = lowest_trunk(&b).0;
    s.trunk.pose.translation.z -= lower - 0.02;
    set(&mut b, &s);
    let mut touched = false;
    for n in 1..=steps_for(&params, 0.5) {
        let (lower_before, _) = lowest_trunk(&b);
        step_zero(&mut b);
        let (lower_after, _) = lowest_trunk(&b);
        if read_contacts(&b)[trunk] {
            assert!(
                lower_before.min(lower_after) <= params.contact_distance + 1e-3,
                "step {n}: trunk in contact while at least {:.2} mm from the ground",
                1e3 * lower_before.min(lower_after)
            );
            touched = true;
            break;
        }
    }
    assert!(
        touched,
        "the limp robot's trunk never touched the rough ground"
    );
}

/// The trunk's clearance bounds (lower, upper) above `terrain`, from the backend's poses.
fn trunk_clearance<B: Backend>(model: &RobotModel, terrain: &Terrain, b: &B) -> (f64, f64) {
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    b.link_poses(&mut poses);
    let t = &model.tracked()[model.trunk_tracked_index()];
    let link = &model.links()[t.link];
    t.shapes
        .iter()
        .map(|&s| {
            let c = &link.collisions[s];
            terrain.clearance(&c.shape, &(poses[t.link] * c.origin))
        })
        .fold((f64::INFINITY, f64::INFINITY), |(lo, hi), c| {
            (lo.min(c.lower), hi.min(c.upper))
        })
}

/// Changing the ground keeps the robot's state and clears the rest, bitwise: after
/// `set_terrain`, a world runs as a fresh world given the same terrain and state; a reset on
/// the field repeats the trajectory; and going back to flat ground gives a world that runs
/// bitwise as one that never left it.
pub fn terrain_changes_keep_the_state_and_reset_bitwise<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let terrain = rough_ground();
    let model = Arc::clone(&robot.model);
    let mut start = model.spawn_state();
    start.trunk.pose.translation.z += terrain.height_at(0.0, 0.0) + 0.05;

    let mut changed: B = build_default(robot, options);
    set(&mut changed, &start);
    changed
        .set_terrain(&terrain)
        .unwrap_or_else(|e| panic!("{} refused a terrain: {e}", B::NAME));
    // Kept to the engine's precision (rapier holds single precision).
    let kept = changed.state();
    let turned = kept
        .q
        .iter()
        .zip(&start.q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(turned < 1e-6, "set_terrain turned a joint by {turned} rad");
    let drift = (kept.trunk.pose.translation.vector - start.trunk.pose.translation.vector).norm();
    assert!(drift < 1e-6, "set_terrain moved the trunk by {drift} m");
    let first = random_pd_trajectory(&mut changed, 4, 300);

    let mut fresh: B = on(robot, &PhysicsParams::default(), options, &terrain);
    set(&mut fresh, &start);
    let fresh_run = random_pd_trajectory(&mut fresh, 4, 300);
    assert_eq!(
        first_difference(&first, &fresh_run),
        None,
        "a fresh world on the field differs"
    );

    set(&mut fresh, &start);
    let again = random_pd_trajectory(&mut fresh, 4, 300);
    assert_eq!(
        first_difference(&first, &again),
        None,
        "a reset on the field differs"
    );

    let flat_start = model.spawn_state();
    fresh
        .set_terrain(&Terrain::Flat)
        .unwrap_or_else(|e| panic!("{} refused flat ground: {e}", B::NAME));
    set(&mut fresh, &flat_start);
    let back = random_pd_trajectory(&mut fresh, 4, 300);
    let mut never: B = build_default(robot, options);
    set(&mut never, &flat_start);
    let never_run = random_pd_trajectory(&mut never, 4, 300);
    assert_eq!(
        first_difference(&back, &never_run),
        None,
        "back on flat ground, the world differs from one that never left it"
    );
}
