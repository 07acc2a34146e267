//! Conversions between the model's f64 nalgebra types and rapier's f32 (glam) types.

use hyq_physics::na::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;

/// An f64 vector in rapier's precision.
pub(crate) fn to_vec(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x as Real, v.y as Real, v.z as Real)
}

/// A rapier vector in f64.
pub(crate) fn from_vec(v: Vector) -> Vector3<f64> {
    Vector3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// An f64 isometry as a rapier pose (its rotation renormalised in f32).
pub(crate) fn to_pose(p: &Isometry3<f64>) -> Pose {
    let q = p.rotation.quaternion();
    let rotation = Rotation::from_xyzw(q.i as Real, q.j as Real, q.k as Real, q.w as Real);
    Pose::from_parts(to_vec(&p.translation.vector), rotation.normalize())
}

/// A rapier pose as an f64 isometry (its rotation renormalised in f64).
pub(crate) fn from_pose(p: &Pose) -> Isometry3<f64> {
    let r = p.rotation;
    Isometry3::from_parts(
        Translation3::from(from_vec(p.translation)),
        UnitQuaternion::new_normalize(Quaternion::new(
            f64::from(r.w),
            f64::from(r.x),
            f64::from(r.y),
            f64::from(r.z),
        )),
    )
}

/// The shortest rotation taking the x axis onto `axis` (rapier's revolute DoF is about x).
pub(crate) fn x_onto(axis: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::rotation_between(&Vector3::x(), axis).unwrap_or_else(|| {
        // `axis` is -x: any half turn about an axis orthogonal to x.
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI)
    })
}
