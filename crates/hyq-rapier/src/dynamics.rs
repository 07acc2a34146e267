//! Changing a built world's dynamics in place ([`Backend::apply_dynamics`]): the same formulas
//! `build` uses, so a world given dynamics here is bit for bit one built with them.
//!
//! [`Backend::apply_dynamics`]: hyq_physics::Backend::apply_dynamics

use hyq_physics::na::{Matrix3, Vector3};
use hyq_physics::{ContactDraw, Dynamics, MassProperties, RobotModel};
use rapier3d::prelude::*;

use crate::build::{Sets, body_mass, collider_frame, joint_parent_frame};
use crate::convert::from_vec;

/// The handles of a world's robot that its dynamics touch.
pub(crate) struct Handles<'a> {
    /// Rigid body of each model body.
    pub(crate) bodies: &'a [RigidBodyHandle],
    /// The trunk's colliders, in its collision order.
    pub(crate) trunk_colliders: &'a [ColliderHandle],
    /// The robot's multibody.
    pub(crate) multibody: MultibodyIndex,
    /// Multibody link id of each joint's child (profile order).
    pub(crate) joint_links: &'a [usize],
    /// Index of each joint's DoF in the generalised velocity (profile order).
    pub(crate) joint_dofs: &'a [usize],
}

/// Gives `world` the dynamics `d` (validated): every collider's friction and restitution (the
/// ground's, whatever its shape, and the robot's, so that rapier's average of the two is
/// `d`'s), every
/// body's mass properties, the per-DoF damping, and, since the trunk's rigid body sits at its
/// centre of mass, the trunk's collider and child-joint frames for its centre of mass. The
/// bodies' poses follow at the next `apply_state`.
pub(crate) fn apply(world: &mut Sets, model: &RobotModel, h: &Handles<'_>, d: &Dynamics) {
    let friction = d.ground_friction as Real;
    let restitution = d.contact.restitution as Real;
    for (_, collider) in world.colliders.iter_mut() {
        collider.set_friction(friction);
        // rapier averages a contact's two coefficients, so both sides hold the drawn one.
        collider.set_restitution(restitution);
    }
    let trunk_com = d.bodies[0].com;
    for (i, (&handle, props)) in h.bodies.iter().zip(&d.bodies).enumerate() {
        let body = &mut world.bodies[handle];
        body.set_additional_mass_properties(body_mass(i, props), false);
        body.recompute_mass_properties_from_colliders(&world.colliders);
    }
    for (&handle, c) in h.trunk_colliders.iter().zip(&model.links()[0].collisions) {
        if let Some(collider) = world.colliders.get_mut(handle) {
            collider.set_position_wrt_parent(collider_frame(0, &c.shape, &c.origin, &trunk_com));
        }
    }
    let Some(mb) = world.multibody_joints.get_multibody_mut(h.multibody) else {
        return;
    };
    for (j, joint) in model.joints().iter().enumerate() {
        if joint.parent == 0
            && let Some(link) = mb.link_mut(h.joint_links[j])
        {
            link.joint.data.local_frame1 = joint_parent_frame(joint, &trunk_com);
        }
    }
    for (&dof, &damping) in h.joint_dofs.iter().zip(&d.joint_damping) {
        mb.damping_mut()[dof] = damping as Real;
    }
}

/// Body `i`'s mass properties as rapier holds them, in the link frame (`trunk_com`: where the
/// trunk's rigid body sits in its link frame).
pub(crate) fn read(body: &RigidBody, i: usize, trunk_com: &Vector3<f64>) -> MassProperties {
    let m = body.mass_properties().local_mprops;
    let inertia = m.reconstruct_inertia_matrix();
    let cols = [inertia.x_axis, inertia.y_axis, inertia.z_axis].map(from_vec);
    let mut com = from_vec(m.local_com);
    if i == 0 {
        com += trunk_com;
    }
    MassProperties {
        mass: f64::from(m.mass()),
        com,
        inertia: Matrix3::from_columns(&cols),
    }
}

/// The ground contact's spring for `contact`'s factors on the options' nominal one (natural
/// frequency ω₀, damping ratio ζ₀). rapier's soft contact is a spring k = m ω² and a damper
/// c = 2 m ζ ω on the contact's effective mass m, so a stiffness factor s and a damping
/// factor d give ω = ω₀ √s and ζ = ζ₀ d / √s; factors of 1 give the options' values exactly.
pub(crate) fn contact_softness(
    frequency: f64,
    damping_ratio: f64,
    contact: &ContactDraw,
) -> SpringCoefficients<Real> {
    let root = contact.contact_stiffness_scale.sqrt();
    SpringCoefficients::new(
        (frequency * root) as Real,
        (damping_ratio * contact.contact_damping_scale / root) as Real,
    )
}
