//! Converting one URDF link's parts: its pose conventions, its mass properties and its
//! collision shapes, added to the body the link belongs to.

use nalgebra::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};

use super::{BodyBuild, Collision, Shape};
use crate::bounds;
use crate::error::ModelError;
use crate::inertia::MassProperties;

/// URDF rpy (fixed axes x, then y, then z: `R = Rz(yaw) Ry(pitch) Rx(roll)`) and xyz to an
/// isometry.
pub(super) fn urdf_pose(pose: &urdf_rs::Pose) -> Isometry3<f64> {
    let [x, y, z] = pose.xyz.0;
    let [roll, pitch, yaw] = pose.rpy.0;
    Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_euler_angles(roll, pitch, yaw),
    )
}

/// Checks every number of a URDF `<origin>` against its bound ([`bounds::ORIGIN_OFFSET`] for
/// xyz, [`bounds::ORIGIN_ANGLE`] for rpy); the reason names the attribute.
pub(super) fn check_pose(pose: &urdf_rs::Pose) -> Result<(), String> {
    for v in pose.xyz.0 {
        bounds::ORIGIN_OFFSET
            .check(v)
            .map_err(|reason| format!("<origin xyz {:?}>: {reason}", pose.xyz.0))?;
    }
    for v in pose.rpy.0 {
        bounds::ORIGIN_ANGLE
            .check(v)
            .map_err(|reason| format!("<origin rpy {:?}>: {reason}", pose.rpy.0))?;
    }
    Ok(())
}

/// Adds one URDF link (its mass and collision shapes) to a body, at `in_body`.
pub(super) fn add_link_to_body(
    body: &mut BodyBuild,
    link: &urdf_rs::Link,
    in_body: &Isometry3<f64>,
) -> Result<(), ModelError> {
    let inertial = &link.inertial;
    let invalid = |reason: String| ModelError::InvalidInertia {
        link: link.name.clone(),
        reason,
    };
    let m = bounds::LINK_MASS
        .check(inertial.mass.value)
        .map_err(|reason| invalid(format!("mass: {reason}")))?;
    check_pose(&inertial.origin).map_err(|reason| invalid(format!("inertial {reason}")))?;
    let i = &inertial.inertia;
    let tensor = Matrix3::new(
        i.ixx, i.ixy, i.ixz, //
        i.ixy, i.iyy, i.iyz, //
        i.ixz, i.iyz, i.izz,
    );
    // Only the entries' range is checked per link: a link fixed to others is part of one rigid
    // body, and it is that body's tensor that must be physically valid (see
    // `tree::check_masses`). Upstream URDFs give sensor links placeholder tensors that are
    // invalid on their own.
    for v in tensor.iter() {
        bounds::INERTIA_ENTRY
            .check(*v)
            .map_err(|reason| invalid(format!("tensor entry: {reason}")))?;
    }
    // The tensor is given in the inertial frame; rotate it into the body frame.
    let frame = in_body * urdf_pose(&inertial.origin);
    let r = frame.rotation.to_rotation_matrix();
    let part = MassProperties {
        mass: m,
        com: frame.translation.vector,
        inertia: r.matrix() * tensor * r.matrix().transpose(),
    };
    body.mass = body.mass.combine(&part);

    for (ci, c) in link.collision.iter().enumerate() {
        body.collisions.push(collision(link, ci, c, in_body)?);
    }
    Ok(())
}

/// Converts collision element `ci` of `link` into a primitive shape at `in_body`.
fn collision(
    link: &urdf_rs::Link,
    ci: usize,
    c: &urdf_rs::Collision,
    in_body: &Isometry3<f64>,
) -> Result<Collision, ModelError> {
    // Escaped: the name is the file's, whatever it holds.
    let label = c
        .name
        .as_ref()
        .map_or_else(|| format!("#{ci}"), |n| crate::printable(n));
    let invalid = |reason: String| ModelError::InvalidGeometry {
        link: link.name.clone(),
        collision: label.clone(),
        reason,
    };
    check_pose(&c.origin).map_err(invalid)?;
    let positive = |what: &str, v: f64| {
        bounds::SHAPE_SIZE
            .check(v)
            .map_err(|reason| invalid(format!("{what}: {reason}")))
    };
    let shape = match &c.geometry {
        urdf_rs::Geometry::Box { size } => {
            let [x, y, z] = size.0;
            Shape::Box {
                half_extents: Vector3::new(
                    positive("box size x", x)? / 2.0,
                    positive("box size y", y)? / 2.0,
                    positive("box size z", z)? / 2.0,
                ),
            }
        }
        urdf_rs::Geometry::Sphere { radius } => Shape::Sphere {
            radius: positive("sphere radius", *radius)?,
        },
        urdf_rs::Geometry::Capsule { radius, length } => {
            let length = bounds::CAPSULE_LENGTH
                .check(*length)
                .map_err(|reason| invalid(format!("capsule length: {reason}")))?;
            Shape::Capsule {
                radius: positive("capsule radius", *radius)?,
                half_length: length / 2.0,
            }
        }
        urdf_rs::Geometry::Cylinder { radius, length } => Shape::Cylinder {
            radius: positive("cylinder radius", *radius)?,
            half_length: positive("cylinder length", *length)? / 2.0,
        },
        urdf_rs::Geometry::Mesh { filename, .. } => {
            return Err(invalid(format!(
                "mesh {filename:?} is not supported (the rapier and DART backends take box, \
                 sphere, capsule and cylinder collisions); replace it in the URDF by primitives \
                 that bound the mesh"
            )));
        }
    };
    Ok(Collision {
        name: c.name.clone(),
        urdf_link: link.name.clone(),
        origin: in_body * urdf_pose(&c.origin),
        shape,
    })
}
