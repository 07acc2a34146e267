//! The robot as URDF text, generated from a [`RobotModel`]: for engines and tools outside the
//! project that read URDF (DART's loader, PyBullet, Pinocchio...), so they simulate the bodies
//! every backend simulates rather than a hand-kept copy.
//!
//! What is written is the model after loading, not the source URDF:
//! - one `<link>` per body of [`RobotModel::links`], in model order (parents first), with its
//!   `<inertial>`: the centre of mass as the origin (no rotation), the mass and the full tensor
//!   about the centre of mass in the body's axes. Links that the loader lumped into their parent
//!   through fixed joints (HyQ's `trunk_imu`) are already inside that mass and do not appear;
//! - one `<collision>` per shape, with its URDF name when it has one, its origin (`xyz` and
//!   `rpy`) in the body frame and its primitive: `<box size>` (full sizes), `<sphere radius>`,
//!   `<cylinder radius length>`, and capsules as chosen by [`CapsuleAs`];
//! - one `revolute` `<joint>` per actuated joint, with its URDF name, parent and child links,
//!   origin, axis, `<limit lower upper effort velocity>` and `<dynamics damping>`.
//!
//! No visuals, no `<transmission>`, no `<gazebo>`: only what the dynamics reads. The root link
//! (the trunk) is the robot's free body; URDF has no way to say so, and loaders that need a
//! floating root give it one themselves (DART does).
//!
//! Numbers are written in Rust's shortest round-trip form; rotations as URDF `rpy` (fixed axes
//! x, y, z), which a loader turns back into the same rotation matrix to within 1e-15.

use std::fmt::Write as _;

use nalgebra::{Isometry3, Rotation3, UnitQuaternion, Vector3};

use crate::xml::{attr, nums};
use hyq_physics::{Joint, Link, RobotModel, Shape};

/// How a capsule shape is written: URDF's schema has no capsule element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CapsuleAs {
    /// `<capsule radius length>` (`length`: the distance between the cap centres), the
    /// element MuJoCo, PyBullet and this project's loader read, though it is not in the ROS
    /// URDF schema.
    Capsule,
    /// `<cylinder radius length>` spanning the capsule's whole length, caps included
    /// (`length` = cap-centre distance + 2 × radius): for loaders built on urdfdom (DART), which
    /// drop an unknown `<capsule>` element. A caller that wants the capsule back replaces the
    /// cylinder after loading.
    Cylinder,
}

/// What to generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UrdfOptions {
    /// How capsules are written.
    pub capsules: CapsuleAs,
}

impl Default for UrdfOptions {
    fn default() -> Self {
        Self {
            capsules: CapsuleAs::Capsule,
        }
    }
}

/// Why a model could not be written as URDF.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum UrdfExportError {
    /// The model holds something this writer does not support.
    #[error("cannot write the model as URDF: {0}")]
    Unsupported(String),
}

/// URDF `rpy` (R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation, accurate near pitch = ±π/2
/// too, where HyQ's hip frames sit: yaw first from the first column, then pitch and roll from
/// what remains once that yaw is taken out (`Rz(−yaw) R = Ry(pitch) Rx(roll)`), whose entries
/// are well conditioned whatever yaw was chosen.
fn rpy(rotation: &UnitQuaternion<f64>) -> [f64; 3] {
    let r = rotation.to_rotation_matrix();
    let r = r.matrix();
    let yaw = r[(1, 0)].atan2(r[(0, 0)]);
    let m = Rotation3::from_axis_angle(&Vector3::z_axis(), -yaw).matrix() * r;
    let pitch = (-m[(2, 0)]).atan2(m[(0, 0)]);
    let roll = (-m[(1, 2)]).atan2(m[(1, 1)]);
    [roll, pitch, yaw]
}

/// `<origin xyz rpy/>` of a pose.
fn origin(pose: &Isometry3<f64>) -> String {
    let t = pose.translation.vector;
    format!(
        "<origin xyz=\"{}\" rpy=\"{}\"/>",
        nums(&[t.x, t.y, t.z]),
        nums(&rpy(&pose.rotation))
    )
}

/// Writes `model` as a URDF document (see the module documentation for what it contains).
pub fn to_urdf(model: &RobotModel, options: &UrdfOptions) -> Result<String, UrdfExportError> {
    let mut x = String::with_capacity(16 * 1024);
    // Writing to a String cannot fail: every `write!` result below is ignored for that reason.
    let _ = writeln!(
        x,
        "<?xml version=\"1.0\"?>\n<!-- Generated from the robot model (URDF + robot profile): fixed \
         links lumped into their parents, primitive collision shapes only; do not edit. -->\n\
         <robot name=\"{}\">",
        attr(model.name())
    );
    for link in model.links() {
        write_link(&mut x, link, options)?;
    }
    for joint in model.joints() {
        write_joint(&mut x, model, joint);
    }
    x.push_str("</robot>\n");
    Ok(x)
}

/// Writes one `<link>`: its inertial and each collision shape.
fn write_link(x: &mut String, link: &Link, options: &UrdfOptions) -> Result<(), UrdfExportError> {
    let _ = writeln!(x, "  <link name=\"{}\">", attr(&link.name));
    let c = link.com;
    let i = link.inertia;
    let _ = writeln!(
        x,
        "    <inertial>\n      <origin xyz=\"{}\" rpy=\"0 0 0\"/>\n      <mass value=\"{}\"/>\n      \
         <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n    </inertial>",
        nums(&[c.x, c.y, c.z]),
        nums(&[link.mass]),
        nums(&[i[(0, 0)]]),
        nums(&[i[(0, 1)]]),
        nums(&[i[(0, 2)]]),
        nums(&[i[(1, 1)]]),
        nums(&[i[(1, 2)]]),
        nums(&[i[(2, 2)]]),
    );
    for collision in &link.collisions {
        let geometry = geometry(&collision.shape, options).ok_or_else(|| {
            UrdfExportError::Unsupported(format!(
                "link {}: collision shape {:?}",
                link.name, collision.shape
            ))
        })?;
        let name = match &collision.name {
            Some(name) => format!(" name=\"{}\"", attr(name)),
            None => String::new(),
        };
        let _ = writeln!(
            x,
            "    <collision{name}>\n      {}\n      <geometry>{geometry}</geometry>\n    </collision>",
            origin(&collision.origin)
        );
    }
    x.push_str("  </link>\n");
    Ok(())
}

/// The `<geometry>` element of `shape` (a capsule as `options` says), or `None` for a shape
/// URDF cannot hold.
fn geometry(shape: &Shape, options: &UrdfOptions) -> Option<String> {
    Some(match *shape {
        Shape::Box { half_extents } => format!(
            "<box size=\"{}\"/>",
            nums(&[
                2.0 * half_extents.x,
                2.0 * half_extents.y,
                2.0 * half_extents.z
            ])
        ),
        Shape::Sphere { radius } => format!("<sphere radius=\"{}\"/>", nums(&[radius])),
        Shape::Cylinder {
            radius,
            half_length,
        } => format!(
            "<cylinder radius=\"{}\" length=\"{}\"/>",
            nums(&[radius]),
            nums(&[2.0 * half_length])
        ),
        Shape::Capsule {
            radius,
            half_length,
        } => match options.capsules {
            CapsuleAs::Capsule => format!(
                "<capsule radius=\"{}\" length=\"{}\"/>",
                nums(&[radius]),
                nums(&[2.0 * half_length])
            ),
            CapsuleAs::Cylinder => format!(
                "<cylinder radius=\"{}\" length=\"{}\"/>",
                nums(&[radius]),
                nums(&[2.0 * (half_length + radius)])
            ),
        },
        // `Shape` is non-exhaustive: a shape added to the model later must be mapped here
        // before it can be written.
        _ => return None,
    })
}

/// Writes one revolute `<joint>` of `model`.
fn write_joint(x: &mut String, model: &RobotModel, joint: &Joint) {
    let links = model.links();
    let a = joint.axis;
    let _ = writeln!(
        x,
        "  <joint name=\"{}\" type=\"revolute\">\n    <parent link=\"{}\"/>\n    \
         <child link=\"{}\"/>\n    {}\n    <axis xyz=\"{}\"/>\n    \
         <limit lower=\"{}\" upper=\"{}\" effort=\"{}\" velocity=\"{}\"/>\n    \
         <dynamics damping=\"{}\" friction=\"0\"/>\n  </joint>",
        attr(&joint.urdf_name),
        attr(&links[joint.parent].name),
        attr(&links[joint.child].name),
        origin(&joint.origin),
        nums(&[a.x, a.y, a.z]),
        nums(&[joint.lower]),
        nums(&[joint.upper]),
        nums(&[joint.effort]),
        nums(&[joint.velocity]),
        nums(&[joint.damping]),
    );
}

#[cfg(test)]
mod tests {
    //! The written URDF is the model: loaded back with the same profile it gives the same
    //! bodies, masses, inertias, joints and shapes (rotation matrices to within 1e-15,
    //! the Euler-angle round trip), and the cylinder form of a capsule covers the capsule's whole length.
    #![allow(clippy::unwrap_used)]

    use super::*;
    use hyq_physics::Profile;
    use hyq_physics::bundled;

    fn reload(text: &str) -> RobotModel {
        let profile = Profile::from_toml_str(bundled::HYQ_PROFILE, "bundled profile").unwrap();
        RobotModel::from_urdf_str(text, "generated", &profile).unwrap_or_else(|e| panic!("{e}"))
    }

    fn close(a: &Isometry3<f64>, b: &Isometry3<f64>) -> bool {
        let (ra, rb) = (
            a.rotation.to_rotation_matrix(),
            b.rotation.to_rotation_matrix(),
        );
        (a.translation.vector - b.translation.vector).norm() < 1e-15
            && (ra.matrix() - rb.matrix()).amax() < 1e-15
    }

    #[test]
    fn the_written_urdf_loads_back_into_the_same_model() {
        let model = bundled::hyq();
        let text = to_urdf(&model, &UrdfOptions::default()).unwrap();
        let back = reload(&text);
        assert_eq!(back.num_links(), model.num_links());
        assert_eq!(back.num_joints(), model.num_joints());
        assert_eq!(back.total_mass(), model.total_mass());
        for (a, b) in model.links().iter().zip(back.links()) {
            assert_eq!(a.name, b.name);
            assert_eq!(a.parent, b.parent);
            assert_eq!(a.parent_joint, b.parent_joint);
            assert_eq!(a.mass, b.mass, "{}", a.name);
            assert_eq!(a.com, b.com, "{}", a.name);
            assert_eq!(a.inertia, b.inertia, "{}", a.name);
            assert_eq!(a.collisions.len(), b.collisions.len(), "{}", a.name);
            for (ca, cb) in a.collisions.iter().zip(&b.collisions) {
                assert_eq!(ca.name, cb.name);
                assert_eq!(ca.shape, cb.shape, "{}", a.name);
                assert!(close(&ca.origin, &cb.origin), "{}: {:?}", a.name, ca.name);
            }
        }
        for (a, b) in model.joints().iter().zip(back.joints()) {
            assert_eq!(
                (&a.name, &a.urdf_name, a.parent, a.child),
                (&b.name, &b.urdf_name, b.parent, b.child)
            );
            assert_eq!(
                (a.lower, a.upper, a.effort, a.velocity, a.damping),
                (b.lower, b.upper, b.effort, b.velocity, b.damping)
            );
            assert_eq!(a.axis, b.axis);
            assert!(close(&a.origin, &b.origin), "{}", a.name);
        }
        assert_eq!(back.tracked(), model.tracked());
        // Lumped links are inside their parent already: none is written again.
        for link in model.links() {
            for lumped in &link.lumped {
                assert!(
                    !text.contains(&format!("<link name=\"{lumped}\"")),
                    "{lumped}"
                );
            }
        }
    }

    #[test]
    fn capsules_as_cylinders_span_the_capsule_caps_included() {
        let model = bundled::hyq();
        let text = to_urdf(
            &model,
            &UrdfOptions {
                capsules: CapsuleAs::Cylinder,
            },
        )
        .unwrap();
        assert!(!text.contains("<capsule"), "{text}");
        let back = reload(&text);
        let mut capsules = 0;
        for (a, b) in model.links().iter().zip(back.links()) {
            for (ca, cb) in a.collisions.iter().zip(&b.collisions) {
                match (&ca.shape, &cb.shape) {
                    (
                        Shape::Capsule {
                            radius,
                            half_length,
                        },
                        Shape::Cylinder {
                            radius: r,
                            half_length: h,
                        },
                    ) => {
                        capsules += 1;
                        assert_eq!(r, radius);
                        assert!((h - (half_length + radius)).abs() < 1e-15);
                    }
                    (sa, sb) => assert_eq!(sa, sb),
                }
            }
        }
        // HyQ: a thigh and a shin per leg.
        assert_eq!(capsules, 8);
    }

    #[test]
    fn rpy_gives_back_the_rotation_at_and_near_gimbal_lock() {
        let half_pi = std::f64::consts::FRAC_PI_2;
        for (roll, pitch, yaw) in [
            (0.3, -1.1, 2.9),
            (0.0, half_pi, std::f64::consts::PI),
            (1.0, half_pi - 3e-12, -2.0),
            (-0.7, -half_pi, 0.4),
            (std::f64::consts::FRAC_PI_2, 0.0, 0.0),
        ] {
            let q = UnitQuaternion::from_euler_angles(roll, pitch, yaw);
            let [r, p, y] = rpy(&q);
            let back = UnitQuaternion::from_euler_angles(r, p, y);
            let err = (q.to_rotation_matrix().matrix() - back.to_rotation_matrix().matrix()).amax();
            assert!(err < 1e-15, "({roll}, {pitch}, {yaw}): {err}");
        }
    }

    #[test]
    fn names_are_escaped() {
        assert_eq!(attr("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&apos;");
    }
}
