//! Building the rapier world from a [`RobotModel`], phase by phase: the ground, the bodies with
//! their colliders, the multibody joints, and the lookup of each joint's multibody link and
//! degree of freedom. `RapierBackend::build` runs them in this order; the order of insertion
//! fixes rapier's handles, so it is part of the backend's determinism.

use hyq_physics::na::{Isometry3, Translation3, UnitQuaternion, Vector3};
use hyq_physics::{Backend, HeightGrid, PhysicsError, PhysicsParams, RobotModel, Shape, Terrain};
use rapier3d::parry::shape::HeightFieldFlags;
use rapier3d::prelude::*;

use crate::RapierOptions;
use crate::convert::{to_pose, to_vec, x_onto};

/// Everything rapier simulates: cloned whole to snapshot and restore a world.
#[derive(Clone)]
pub(crate) struct Sets {
    pub(crate) bodies: RigidBodySet,
    pub(crate) colliders: ColliderSet,
    pub(crate) impulse_joints: ImpulseJointSet,
    pub(crate) multibody_joints: MultibodyJointSet,
    pub(crate) islands: IslandManager,
    pub(crate) broad_phase: BroadPhaseBvh,
    pub(crate) narrow_phase: NarrowPhase,
    pub(crate) ccd: CCDSolver,
    pub(crate) soft_bodies: SoftBodySet,
}

impl Sets {
    /// An empty world.
    pub(crate) fn new() -> Self {
        Self {
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            ccd: CCDSolver::new(),
            soft_bodies: SoftBodySet::new(),
        }
    }
}

/// A world as built for a model on a terrain: the sets, and where the ground, the bodies and
/// the joints are in them.
pub(crate) struct Built {
    pub(crate) sets: Sets,
    pub(crate) ground: ColliderHandle,
    pub(crate) bodies: Bodies,
    pub(crate) joint_axes: Vec<Vector>,
    pub(crate) dofs: Dofs,
}

/// Builds the world phase by phase (ground, bodies with colliders, multibody joints, DoF
/// lookup), in the fixed order that fixes rapier's handles.
pub(crate) fn build_world(
    model: &RobotModel,
    friction: Real,
    terrain: &Terrain,
) -> Result<Built, PhysicsError> {
    let mut sets = Sets::new();
    let ground = add_ground(&mut sets, friction, terrain);
    let bodies = add_bodies(&mut sets, model, friction)?;
    let joint_axes = add_joints(&mut sets, model, &bodies.handles)?;
    let dofs = locate_dofs(&mut sets, model, &bodies.handles)?;
    Ok(Built {
        sets,
        ground,
        bodies,
        joint_axes,
        dofs,
    })
}

/// Robot shapes are in group 1 and meet only group 2, the ground: no self-collision.
fn robot_groups() -> InteractionGroups {
    InteractionGroups::new(Group::GROUP_1, Group::GROUP_2, InteractionTestMode::And)
}

/// The ground is in group 2 and meets only group 1, the robot.
fn ground_groups() -> InteractionGroups {
    InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And)
}

/// An engine failure, named as this backend's.
pub(crate) fn backend_error(message: String) -> PhysicsError {
    PhysicsError::Backend {
        backend: crate::RapierBackend::NAME,
        message,
    }
}

/// The ground: a fixed collider with Coulomb friction and no restitution, the half-space z ≤ 0
/// for flat terrain, else one height field of the whole grid ([`height_field`]).
pub(crate) fn add_ground(world: &mut Sets, friction: Real, terrain: &Terrain) -> ColliderHandle {
    let ground_body = world.bodies.insert(RigidBodyBuilder::fixed());
    let builder = match terrain {
        Terrain::Flat => ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Z)),
        Terrain::Field(grid) => height_field(grid),
    };
    world.colliders.insert_with_parent(
        builder
            .friction(friction)
            .restitution(0.0)
            .collision_groups(ground_groups()),
        ground_body,
        &mut world.bodies,
    )
}

/// One rapier height field of the whole grid, with internal-edge fixing on.
///
/// rapier's field lies in its local x–z plane with heights along +y: row `i` of its array runs
/// along local z, column `j` along local x, each from −½ to +½ of the scale. A quarter turn
/// about +x takes local y (height) onto world z and local z onto world −y, so local row `i` is
/// the grid's row `rows − 1 − i`; local column `j` is the grid's column `j`. rapier splits each
/// cell between its local corners (x₀, z₁) and (x₁, z₀), which the turn takes onto the grid's
/// (x₀, y₀)–(x₁, y₁) diagonal, the split every backend uses.
pub(crate) fn height_field(grid: &HeightGrid) -> ColliderBuilder {
    let (columns, rows) = (grid.columns(), grid.rows());
    let mut heights = Vec::with_capacity(columns * rows);
    // Column-major: all local rows of local column 0, then of column 1, ...
    for c in 0..columns {
        for i in 0..rows {
            heights.push(grid.height(c, rows - 1 - i) as Real);
        }
    }
    let [sx, sy] = grid.size();
    let [cx, cy] = grid.center();
    let pose = Isometry3::from_parts(
        Translation3::new(cx, cy, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
    );
    ColliderBuilder::heightfield_with_flags(
        Array2::new(rows, columns, heights),
        Vector::new(sx as Real, 1.0, sy as Real),
        HeightFieldFlags::FIX_INTERNAL_EDGES,
    )
    .position(to_pose(&pose))
}

/// The rigid body frame of model body `i` in its link frame: the trunk's is moved to its centre
/// of mass (see the crate documentation), every other body's is the link frame.
pub(crate) fn body_shift(i: usize, trunk_com: &Vector3<f64>) -> Isometry3<f64> {
    if i == 0 {
        Isometry3::from(Translation3::from(*trunk_com))
    } else {
        Isometry3::identity()
    }
}

/// The robot's rigid bodies, one per model body, each with its colliders.
pub(crate) struct Bodies {
    /// Rigid body of each model body (index as in `RobotModel::links`).
    pub(crate) handles: Vec<RigidBodyHandle>,
    /// Colliders of each model body, in its collision order.
    pub(crate) colliders: Vec<Vec<ColliderHandle>>,
}

/// Inserts every model body at the spawn configuration (the multibody overwrites their poses
/// from its coordinates anyway), the trunk's at its centre of mass, with its colliders.
pub(crate) fn add_bodies(
    world: &mut Sets,
    model: &RobotModel,
    friction: Real,
) -> Result<Bodies, PhysicsError> {
    let links = model.links();
    let spawn = model.spawn_state();
    let mut link_poses = vec![Isometry3::identity(); links.len()];
    model.link_poses(&spawn.trunk.pose, &spawn.q, &mut link_poses)?;
    let trunk_com = links[0].com;
    let mut handles = Vec::with_capacity(links.len());
    let mut colliders: Vec<Vec<ColliderHandle>> = Vec::with_capacity(links.len());
    for (i, link) in links.iter().enumerate() {
        let shift = body_shift(i, &trunk_com);
        let mass = body_mass(
            i,
            &hyq_physics::MassProperties {
                mass: link.mass,
                com: link.com,
                inertia: link.inertia,
            },
        );
        let handle = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .pose(to_pose(&(link_poses[i] * shift)))
                .additional_mass_properties(mass)
                .can_sleep(false)
                .ccd_enabled(false),
        );
        let mut body_colliders = Vec::with_capacity(link.collisions.len());
        for c in &link.collisions {
            let frame = collider_frame(i, &c.shape, &c.origin, &trunk_com);
            let builder = collider(&c.shape, frame).ok_or_else(|| {
                backend_error(format!(
                    "link {:?}: unsupported shape {:?}",
                    link.name, c.shape
                ))
            })?;
            body_colliders.push(
                world.colliders.insert_with_parent(
                    builder
                        .density(0.0)
                        .friction(friction)
                        .restitution(0.0)
                        .collision_groups(robot_groups()),
                    handle,
                    &mut world.bodies,
                ),
            );
        }
        // Mass properties are otherwise only folded in at the first step; the pristine
        // world and the multibody's kinematics need them now.
        world.bodies[handle].recompute_mass_properties_from_colliders(&world.colliders);
        handles.push(handle);
        colliders.push(body_colliders);
    }
    Ok(Bodies { handles, colliders })
}

/// rapier's mass properties of model body `i` with `props` (link frame): about the body frame's
/// origin, which for the trunk is its centre of mass (see [`body_shift`]).
pub(crate) fn body_mass(i: usize, props: &hyq_physics::MassProperties) -> MassProperties {
    let com = if i == 0 { Vector3::zeros() } else { props.com };
    let inertia = Matrix::from_cols(
        to_vec(&props.inertia.column(0).into_owned()),
        to_vec(&props.inertia.column(1).into_owned()),
        to_vec(&props.inertia.column(2).into_owned()),
    );
    MassProperties::with_inertia_matrix(to_vec(&com), props.mass as Real, inertia)
}

/// The pose of a collider of body `i` whose shape frame is `origin` (in the link frame) in
/// that body's rigid-body frame, for `shape`: rapier's cylinder lies along y, so a cylinder's
/// frame is turned to bring y onto the model's z.
pub(crate) fn collider_frame(
    i: usize,
    shape: &Shape,
    origin: &Isometry3<f64>,
    trunk_com: &Vector3<f64>,
) -> Pose {
    let in_body = body_shift(i, trunk_com).inverse() * origin;
    match shape {
        Shape::Cylinder { .. } => {
            let y_to_z =
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2);
            to_pose(&(in_body * y_to_z))
        }
        _ => to_pose(&in_body),
    }
}

/// A collider for `shape` at `frame` (its pose in the rigid body's frame, from
/// [`collider_frame`]), or `None` for a shape this backend does not know.
fn collider(shape: &Shape, frame: Pose) -> Option<ColliderBuilder> {
    let builder = match *shape {
        Shape::Box { half_extents } => ColliderBuilder::cuboid(
            half_extents.x as Real,
            half_extents.y as Real,
            half_extents.z as Real,
        ),
        Shape::Sphere { radius } => ColliderBuilder::ball(radius as Real),
        Shape::Capsule {
            radius,
            half_length,
        } => ColliderBuilder::capsule_z(half_length as Real, radius as Real),
        Shape::Cylinder {
            radius,
            half_length,
        } => ColliderBuilder::cylinder(half_length as Real, radius as Real),
        _ => return None,
    };
    Some(builder.position(frame))
}

/// Joins the bodies into one multibody, parents before children, and returns each joint's axis
/// in its parent body's frame (profile order). Body frame = link frame · shift, so the joint
/// frame on the parent is shift⁻¹ · origin · (x onto axis), and on the child (x onto axis).
pub(crate) fn add_joints(
    world: &mut Sets,
    model: &RobotModel,
    bodies: &[RigidBodyHandle],
) -> Result<Vec<Vector>, PhysicsError> {
    let links = model.links();
    let joints = model.joints();
    let trunk_com = links[0].com;
    let mut joint_axes = vec![Vector::ZERO; joints.len()];
    for (i, link) in links.iter().enumerate().skip(1) {
        let Some(j) = link.parent_joint else {
            return Err(backend_error(format!(
                "link {:?} has no parent joint",
                link.name
            )));
        };
        let joint = &joints[j];
        let a = x_onto(&joint.axis);
        let frame2 = body_shift(i, &trunk_com).inverse()
            * Isometry3::from_parts(Translation3::identity(), a);
        let data = GenericJointBuilder::new(JointAxesMask::LOCKED_REVOLUTE_AXES)
            .local_frame1(joint_parent_frame(joint, &trunk_com))
            .local_frame2(to_pose(&frame2))
            .limits(JointAxis::AngX, [joint.lower as Real, joint.upper as Real])
            .contacts_enabled(false)
            .build();
        world
            .multibody_joints
            .insert(bodies[joint.parent], bodies[i], data, true)
            .ok_or_else(|| backend_error(format!("rapier refused joint {:?}", joint.urdf_name)))?;
        joint_axes[j] = to_vec(&(joint.origin.rotation * joint.axis.into_inner()));
    }
    Ok(joint_axes)
}

/// A joint's frame in its parent's rigid-body frame (rapier's `local_frame1`): the joint
/// origin with x turned onto the axis, in a parent frame shifted as [`body_shift`] says.
pub(crate) fn joint_parent_frame(joint: &hyq_physics::Joint, trunk_com: &Vector3<f64>) -> Pose {
    to_pose(&(body_shift(joint.parent, trunk_com).inverse() * joint.origin * x_onto(&joint.axis)))
}

/// Where each joint lives in the multibody.
pub(crate) struct Dofs {
    /// The robot's multibody.
    pub(crate) multibody: MultibodyIndex,
    /// Multibody link id of each joint's child (profile order).
    pub(crate) joint_links: Vec<usize>,
    /// Index of each joint's DoF in the generalised velocity (profile order).
    pub(crate) joint_dofs: Vec<usize>,
}

/// Finds the multibody, each joint's link and DoF in it, and sets the per-DoF damping: the
/// model's joint damping, none on the free root (rapier puts 0.1 on its rotation). Also turns
/// the multibody's self-contacts off.
pub(crate) fn locate_dofs(
    world: &mut Sets,
    model: &RobotModel,
    bodies: &[RigidBodyHandle],
) -> Result<Dofs, PhysicsError> {
    let joints = model.joints();
    let root_link = world
        .multibody_joints
        .rigid_body_link(bodies[0])
        .ok_or_else(|| backend_error("the trunk is not in a multibody".into()))?;
    let multibody = root_link.multibody;
    let mut joint_links = vec![0; joints.len()];
    for (j, joint) in joints.iter().enumerate() {
        let link = world
            .multibody_joints
            .rigid_body_link(bodies[joint.child])
            .ok_or_else(|| {
                backend_error(format!(
                    "joint {:?} is not in the multibody",
                    joint.urdf_name
                ))
            })?;
        if link.multibody != multibody {
            return Err(backend_error(format!(
                "joint {:?} is in another multibody",
                joint.urdf_name
            )));
        }
        joint_links[j] = link.id;
    }
    let mb = world
        .multibody_joints
        .get_multibody_mut(multibody)
        .ok_or_else(|| backend_error("the robot's multibody vanished".into()))?;
    if mb.root().rigid_body_handle() != bodies[0] {
        return Err(backend_error(
            "the trunk is not the multibody's root".into(),
        ));
    }
    mb.set_self_contacts_enabled(false);
    let mut joint_dofs = vec![0; joints.len()];
    for (j, &id) in joint_links.iter().enumerate() {
        let link = mb
            .link(id)
            .ok_or_else(|| backend_error(format!("multibody link {id} missing")))?;
        joint_dofs[j] = link.assembly_id();
    }
    mb.damping_mut().fill(0.0);
    for (j, &dof) in joint_dofs.iter().enumerate() {
        mb.damping_mut()[dof] = joints[j].damping as Real;
    }
    Ok(Dofs {
        multibody,
        joint_links,
        joint_dofs,
    })
}

/// rapier's integration parameters for the physics parameters and options (see the crate
/// documentation for the settings that are not options).
pub(crate) fn integration_parameters(
    params: &PhysicsParams,
    options: &RapierOptions,
) -> IntegrationParameters {
    IntegrationParameters {
        dt: params.dt as Real,
        num_solver_iterations: options.solver_iterations,
        multibody_mass_matrix_once_per_step: options.mass_matrix_once_per_step,
        static_contact_softness: SpringCoefficients::new(
            options.ground_contact_frequency as Real,
            options.ground_contact_damping_ratio as Real,
        ),
        // rapier creates no contact beyond its prediction distance, so it is at least the
        // contact distance: a contact within that distance must be seen to count.
        normalized_prediction_distance: options.prediction_distance.max(params.contact_distance)
            as Real,
        contact_recycling: false,
        max_ccd_substeps: 0,
        ..IntegrationParameters::default()
    }
}
