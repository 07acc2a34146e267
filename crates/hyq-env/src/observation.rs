//! The observation's rows beyond the spec's (`observation.extra`), a project extension ruled in
//! docs/spec.md ("Observation beyond §3"): named, bounded and written after the §3 rows, always
//! in this order, each group only when asked for.
//!
//! | group | rows | value | unit | bounds (estimated) |
//! |---|---|---|---|---|
//! | `height_scan` | `height_scan_<i>_<j>`, i back to front, j right to left | h(p) − z_C: the ground's height at the point p, `observation.height_scan_*` around the trunk in its heading frame (x along its yaw, y to its left), minus the trunk's height; legged_gym's `measured_heights` | m | ±2 |
//! | `goal_vector` | `goal_vector_x`, `_y`, `_z` | Rᵀ (G − C): the goal from the trunk centre in the trunk's frame | m | ±20 |
//! | `trunk_velocity` | `<trunk>_linvel_x` … `_z`, `<trunk>_angvel_x` … `_z` | Rᵀ v and Rᵀ ω: the trunk frame origin's linear and angular velocity in the trunk's frame | m/s, rad/s | ±5, ±10 |
//!
//! Values are not clipped (as the spec's rows are not): the bounds are estimates, which
//! `clip_observations` in Python clips to.

use hyq_physics::na::{Point3, UnitQuaternion, Vector3};
use hyq_physics::{Terrain, TrunkState};
use hyq_spec::ObservationLayout;

use crate::config::{ObservationConfig, ObservationExtra};

/// The estimated bound (m) of a height-scan row.
pub const SCAN_BOUND_M: f64 = 2.0;
/// The estimated bound (m) of a goal-vector row.
pub const GOAL_BOUND_M: f64 = 20.0;
/// The estimated bounds of the trunk's linear (m/s) and angular (rad/s) velocity rows.
pub const VELOCITY_BOUNDS: [f64; 2] = [5.0, 10.0];

/// `layout` with the groups of `config` appended (see the module docs); `trunk` names the
/// trunk in the velocity rows.
pub fn extend(
    layout: ObservationLayout,
    config: &ObservationConfig,
    trunk: &str,
) -> ObservationLayout {
    let mut layout = layout;
    for group in config.groups() {
        layout = match group {
            ObservationExtra::HeightScan => {
                let (xs, ys) = config.scan_axes();
                let rows = (0..xs.len()).flat_map(|i| {
                    (0..ys.len()).map(move |j| {
                        (
                            format!("height_scan_{i:02}_{j:02}"),
                            -SCAN_BOUND_M,
                            SCAN_BOUND_M,
                        )
                    })
                });
                layout.with_group(group.as_str(), "m", rows.collect::<Vec<_>>())
            }
            ObservationExtra::GoalVector => layout.with_group(
                group.as_str(),
                "m",
                ["x", "y", "z"].map(|a| (format!("goal_vector_{a}"), -GOAL_BOUND_M, GOAL_BOUND_M)),
            ),
            ObservationExtra::TrunkVelocity => {
                let [lin, ang] = VELOCITY_BOUNDS;
                let rows = ["x", "y", "z"]
                    .map(|a| (format!("{trunk}_linvel_{a}"), -lin, lin))
                    .into_iter()
                    .chain(["x", "y", "z"].map(|a| (format!("{trunk}_angvel_{a}"), -ang, ang)));
                layout.with_group(group.as_str(), "m/s, rad/s", rows.collect::<Vec<_>>())
            }
        };
    }
    layout
}

/// Writes the groups `extras` (layout order) into `out`, the rows after the §3 ones, for the
/// trunk `trunk`, the goal `goal` and the ground `terrain`; `scan` holds the height scan's
/// points in the heading frame. Allocates nothing.
pub fn write_extras(
    extras: &[ObservationExtra],
    scan: &[[f64; 2]],
    trunk: &TrunkState,
    goal: &Point3<f64>,
    terrain: &Terrain,
    out: &mut [f64],
) {
    let centre = trunk.pose.translation.vector;
    let to_trunk = trunk.pose.rotation.inverse();
    let mut at = 0;
    let mut put = |v: f64| {
        if let Some(slot) = out.get_mut(at) {
            *slot = v;
        }
        at += 1;
    };
    for group in extras {
        match group {
            ObservationExtra::HeightScan => {
                let (_, _, yaw) = trunk.pose.rotation.euler_angles();
                let heading = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw);
                for &[x, y] in scan {
                    let p = heading * Vector3::new(x, y, 0.0);
                    put(terrain.height_at(centre.x + p.x, centre.y + p.y) - centre.z);
                }
            }
            ObservationExtra::GoalVector => {
                let g = to_trunk * (goal.coords - centre);
                g.iter().for_each(|v| put(*v));
            }
            ObservationExtra::TrunkVelocity => {
                let v = to_trunk * trunk.linvel;
                let w = to_trunk * trunk.angvel;
                v.iter().chain(w.iter()).for_each(|x| put(*x));
            }
        }
    }
}
