//! The robot model: a URDF plus a robot profile, built once and shared by every backend.
//!
//! Building a [`RobotModel`] turns the URDF's links and joints into the bodies a simulator
//! moves:
//! - the profile's trunk must be the URDF's root link; it becomes a free-floating body;
//! - every revolute joint must be listed in the profile and becomes an actuated joint, in the
//!   profile's order (the order of observations and actions);
//! - links attached by fixed joints are lumped into their parent body (parallel-axis theorem,
//!   see [`crate::inertia`]), their collision shapes re-expressed in the parent body's frame;
//! - collision shapes are primitives: box, sphere, capsule (URDF `<capsule>`: `length` is the
//!   distance between the cap centres, along the shape's local z) and cylinder.
//!
//! Body frames are the URDF link frames (for a lumped body: the frame of its first link).
//! [`RobotModel::link_poses`] is the forward kinematics of these frames:
//! `X_child = X_parent · X_origin · Rot(axis, q)` for every actuated joint.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use nalgebra::{Isometry3, Matrix3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::backend::{RobotState, TrunkState};
use crate::error::{ModelError, PhysicsError};
use crate::inertia::{MassProperties, check_inertia};
use crate::profile::Profile;

/// A primitive collision shape, in the frame given by its [`Collision::origin`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Shape {
    /// A box centred on the origin.
    Box {
        /// Half of the box's size along x, y, z (m).
        half_extents: Vector3<f64>,
    },
    /// A sphere centred on the origin.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// A capsule along the local z axis, centred on the origin: the set of points within
    /// `radius` of the segment from `-half_length` to `+half_length` on z.
    Capsule {
        /// Radius (m).
        radius: f64,
        /// Half the distance between the two cap centres (m).
        half_length: f64,
    },
    /// A cylinder along the local z axis, centred on the origin.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Half the cylinder's length (m).
        half_length: f64,
    },
}

impl Shape {
    /// The lowest world z reached by this shape when its frame is at `pose` (world frame, z up).
    ///
    /// Used to measure a shape's clearance above flat ground without a simulator.
    pub fn lowest_z(&self, pose: &Isometry3<f64>) -> f64 {
        let centre = pose.translation.vector.z;
        // Row z of the rotation: how much each local axis points up or down.
        let r = pose.rotation.to_rotation_matrix();
        let up = r.matrix().row(2);
        match *self {
            Shape::Sphere { radius } => centre - radius,
            Shape::Capsule {
                radius,
                half_length,
            } => centre - up[2].abs() * half_length - radius,
            Shape::Cylinder {
                radius,
                half_length,
            } => {
                let az = up[2].abs().min(1.0);
                centre - az * half_length - radius * (1.0 - az * az).sqrt()
            }
            Shape::Box { half_extents } => {
                centre
                    - up[0].abs() * half_extents.x
                    - up[1].abs() * half_extents.y
                    - up[2].abs() * half_extents.z
            }
        }
    }
}

/// A collision shape attached to a body.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Collision {
    /// The `<collision name="…">` attribute, if any.
    pub name: Option<String>,
    /// The URDF link the shape was declared on (differs from the body when lumped).
    pub urdf_link: String,
    /// The shape's frame in the body frame.
    pub origin: Isometry3<f64>,
    /// The shape.
    pub shape: Shape,
}

/// A rigid body of the simulated robot: one URDF link plus any links fixed to it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Link {
    /// The URDF link name (of the first link, when fixed links were lumped into it).
    pub name: String,
    /// Index of the parent body in [`RobotModel::links`]; `None` for the trunk (the root).
    pub parent: Option<usize>,
    /// Index of the actuated joint connecting this body to its parent in
    /// [`RobotModel::joints`]; `None` for the trunk.
    pub parent_joint: Option<usize>,
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the body frame (m).
    pub com: Vector3<f64>,
    /// Inertia tensor about the centre of mass, body-frame axes (kg·m²).
    pub inertia: Matrix3<f64>,
    /// Collision shapes, in URDF order.
    pub collisions: Vec<Collision>,
    /// URDF links lumped into this body through fixed joints.
    pub lumped: Vec<String>,
}

/// An actuated revolute joint.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Joint {
    /// The profile's short name (e.g. `lf_haa`).
    pub name: String,
    /// The URDF joint name.
    pub urdf_name: String,
    /// Index of the parent body in [`RobotModel::links`].
    pub parent: usize,
    /// Index of the child body in [`RobotModel::links`].
    pub child: usize,
    /// The joint frame in the parent body frame (the URDF `<origin>`, composed with any fixed
    /// joints lumped on the way).
    pub origin: Isometry3<f64>,
    /// Rotation axis in the joint frame (unit).
    pub axis: Unit<Vector3<f64>>,
    /// Lower position limit (rad).
    pub lower: f64,
    /// Upper position limit (rad).
    pub upper: f64,
    /// Effort limit (N·m): the actuator never exceeds it.
    pub effort: f64,
    /// Velocity limit (rad/s), honoured by the shared actuator (see [`crate::actuator`]).
    pub velocity: f64,
    /// Viscous joint damping (N·m·s/rad), applied by the backend as passive joint damping.
    pub damping: f64,
}

/// A set of collision shapes whose ground contact is reported (a foot, or the trunk).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct TrackedBody {
    /// The profile's short name (a foot's name, or the trunk link's name).
    pub name: String,
    /// Index of the body in [`RobotModel::links`].
    pub link: usize,
    /// Indices into that body's [`Link::collisions`].
    pub shapes: Vec<usize>,
}

/// A robot ready for simulation; see the module documentation.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotModel {
    name: String,
    links: Vec<Link>,
    joints: Vec<Joint>,
    tracked: Vec<TrackedBody>,
    num_feet: usize,
    standing: Vec<f64>,
    spawn_height: f64,
    standing_height: f64,
    kp: Vec<f64>,
    kd: Vec<f64>,
    total_mass: f64,
}

/// URDF rpy (fixed axes x, then y, then z: `R = Rz(yaw) Ry(pitch) Rx(roll)`) and xyz to an
/// isometry.
fn urdf_pose(pose: &urdf_rs::Pose) -> Isometry3<f64> {
    let [x, y, z] = pose.xyz.0;
    let [roll, pitch, yaw] = pose.rpy.0;
    Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_euler_angles(roll, pitch, yaw),
    )
}

fn pose_is_finite(pose: &urdf_rs::Pose) -> bool {
    pose.xyz
        .0
        .iter()
        .chain(pose.rpy.0.iter())
        .all(|v| v.is_finite())
}

/// A body under construction.
struct BodyBuild {
    name: String,
    parent: Option<usize>,
    /// Index of the URDF joint attaching the body to its parent.
    urdf_joint: Option<usize>,
    /// The joint frame in the parent body's frame.
    joint_origin: Isometry3<f64>,
    mass: MassProperties,
    collisions: Vec<Collision>,
    lumped: Vec<String>,
}

impl RobotModel {
    /// Loads a robot from its profile file; the URDF path inside is relative to the profile.
    pub fn load(profile_path: impl AsRef<Path>) -> Result<Self, ModelError> {
        let profile_path = profile_path.as_ref();
        let profile_text =
            std::fs::read_to_string(profile_path).map_err(|source| ModelError::Io {
                what: "robot profile",
                path: profile_path.to_owned(),
                source,
            })?;
        let profile = Profile::from_toml_str(&profile_text, &profile_path.display().to_string())?;
        let urdf_path = profile_path
            .parent()
            .unwrap_or_else(|| Path::new("."))
            .join(&profile.urdf);
        let urdf_text = std::fs::read_to_string(&urdf_path).map_err(|source| ModelError::Io {
            what: "URDF",
            path: urdf_path.clone(),
            source,
        })?;
        Self::from_urdf_str(&urdf_text, &urdf_path.display().to_string(), &profile)
    }

    /// Builds a robot from URDF text and a parsed profile (the profile's `urdf` path is not
    /// read). `urdf_origin` (a path or "bundled") appears in error messages.
    pub fn from_urdf_str(
        urdf_text: &str,
        urdf_origin: &str,
        profile: &Profile,
    ) -> Result<Self, ModelError> {
        let robot = urdf_rs::read_from_string(urdf_text).map_err(|e| ModelError::Urdf {
            origin: urdf_origin.to_owned(),
            message: e.to_string(),
        })?;
        Self::from_urdf_robot(&robot, profile)
    }

    fn from_urdf_robot(robot: &urdf_rs::Robot, profile: &Profile) -> Result<Self, ModelError> {
        check_profile_values(profile)?;

        // Index links and joints by name, refusing duplicates.
        let mut link_by_name: HashMap<&str, usize> = HashMap::new();
        for (i, link) in robot.links.iter().enumerate() {
            if link_by_name.insert(link.name.as_str(), i).is_some() {
                return Err(ModelError::Structure {
                    reason: format!("link {:?} is defined twice", link.name),
                });
            }
        }
        let mut joint_by_name: HashMap<&str, usize> = HashMap::new();
        let mut parent_joint_of: HashMap<&str, usize> = HashMap::new();
        let mut children_of: HashMap<&str, Vec<usize>> = HashMap::new();
        for (i, joint) in robot.joints.iter().enumerate() {
            if joint_by_name.insert(joint.name.as_str(), i).is_some() {
                return Err(ModelError::Structure {
                    reason: format!("joint {:?} is defined twice", joint.name),
                });
            }
            for (role, link) in [("parent", &joint.parent.link), ("child", &joint.child.link)] {
                if !link_by_name.contains_key(link.as_str()) {
                    return Err(ModelError::Structure {
                        reason: format!(
                            "joint {:?} names {role} link {link:?}, which is not defined",
                            joint.name
                        ),
                    });
                }
            }
            if let Some(other) = parent_joint_of.insert(joint.child.link.as_str(), i) {
                return Err(ModelError::Structure {
                    reason: format!(
                        "link {:?} is the child of two joints, {:?} and {:?}",
                        joint.child.link, robot.joints[other].name, joint.name
                    ),
                });
            }
            children_of
                .entry(joint.parent.link.as_str())
                .or_default()
                .push(i);
        }

        // The trunk must be the one root.
        if !link_by_name.contains_key(profile.trunk.as_str()) {
            return Err(ModelError::MissingLink {
                link: profile.trunk.clone(),
                referenced_by: "trunk".into(),
            });
        }
        if let Some(&j) = parent_joint_of.get(profile.trunk.as_str()) {
            return Err(ModelError::Structure {
                reason: format!(
                    "the trunk {:?} must be the URDF's root link, but it is the child of joint {:?}",
                    profile.trunk, robot.joints[j].name
                ),
            });
        }

        // Walk the tree from the trunk, depth first with children in URDF order, making a body
        // per movable joint (when it is reached, so bodies are numbered in that order) and
        // lumping links attached by fixed joints into their parent's body.
        enum Target {
            /// Lump into an existing body, at this frame in it.
            Lump(usize, Isometry3<f64>),
            /// Start a body below `parent`, attached by URDF joint `joint` at `origin`.
            New {
                parent: usize,
                joint: usize,
                origin: Isometry3<f64>,
            },
        }
        let mut bodies: Vec<BodyBuild> = Vec::new();
        // The body each URDF link ended up in.
        let mut placements: HashMap<String, usize> = HashMap::new();
        let mut visited: HashSet<usize> = HashSet::new();
        let mut stack: Vec<(usize, Target)> = vec![(
            link_by_name[profile.trunk.as_str()],
            Target::New {
                parent: usize::MAX,
                joint: usize::MAX,
                origin: Isometry3::identity(),
            },
        )];
        while let Some((li, target)) = stack.pop() {
            let link = &robot.links[li];
            if !visited.insert(li) {
                return Err(ModelError::Structure {
                    reason: format!("link {:?} is reached twice", link.name),
                });
            }
            let (body, in_body) = match target {
                Target::Lump(body, in_body) => (body, in_body),
                Target::New {
                    parent,
                    joint,
                    origin,
                } => {
                    // The trunk is the only body pushed with the usize::MAX sentinels.
                    let is_root = parent == usize::MAX;
                    bodies.push(BodyBuild {
                        name: link.name.clone(),
                        parent: (!is_root).then_some(parent),
                        urdf_joint: (!is_root).then_some(joint),
                        joint_origin: origin,
                        mass: MassProperties::zero(),
                        collisions: Vec::new(),
                        lumped: Vec::new(),
                    });
                    (bodies.len() - 1, Isometry3::identity())
                }
            };
            add_link_to_body(&mut bodies[body], link, &in_body)?;
            placements.insert(link.name.clone(), body);

            let children = children_of.get(link.name.as_str()).map_or(&[][..], |v| v);
            // Pushed in reverse so that children are visited in URDF order.
            for &ji in children.iter().rev() {
                let joint = &robot.joints[ji];
                let child = link_by_name[joint.child.link.as_str()];
                if !pose_is_finite(&joint.origin) {
                    return Err(ModelError::InvalidJoint {
                        joint: joint.name.clone(),
                        reason: "non-finite <origin>".into(),
                    });
                }
                let origin = in_body * urdf_pose(&joint.origin);
                match joint.joint_type {
                    urdf_rs::JointType::Fixed => {
                        bodies[body].lumped.push(joint.child.link.clone());
                        stack.push((child, Target::Lump(body, origin)));
                    }
                    urdf_rs::JointType::Revolute => {
                        stack.push((
                            child,
                            Target::New {
                                parent: body,
                                joint: ji,
                                origin,
                            },
                        ));
                    }
                    ref other => {
                        return Err(ModelError::InvalidJoint {
                            joint: joint.name.clone(),
                            reason: format!(
                                "type {other:?} is not supported (revolute and fixed joints only)"
                            ),
                        });
                    }
                }
            }
        }
        if let Some(orphan) = robot
            .links
            .iter()
            .enumerate()
            .find(|(i, _)| !visited.contains(i))
        {
            return Err(ModelError::Structure {
                reason: format!(
                    "link {:?} is not connected to the trunk {:?}",
                    orphan.1.name, profile.trunk
                ),
            });
        }

        // Bodies must have a usable mass.
        for body in &bodies {
            if body.mass.mass <= 0.0 {
                return Err(ModelError::InvalidInertia {
                    link: body.name.clone(),
                    reason: format!(
                        "total mass {} kg of a moving body must be positive",
                        body.mass.mass
                    ),
                });
            }
            check_inertia(&body.mass.inertia, true).map_err(|reason| {
                ModelError::InvalidInertia {
                    link: body.name.clone(),
                    reason,
                }
            })?;
        }

        // Actuated joints in profile order.
        let mut profile_index_of_urdf_joint: HashMap<usize, usize> = HashMap::new();
        let mut short_names: HashSet<&str> = HashSet::new();
        for (pi, entry) in profile.joints.iter().enumerate() {
            let field = format!("joints[{pi}].urdf");
            let ji = *joint_by_name.get(entry.urdf.as_str()).ok_or_else(|| {
                ModelError::MissingJoint {
                    joint: entry.urdf.clone(),
                    referenced_by: field.clone(),
                }
            })?;
            if robot.joints[ji].joint_type != urdf_rs::JointType::Revolute {
                return Err(ModelError::InvalidProfile {
                    field,
                    reason: format!(
                        "joint {:?} is {:?}; only revolute joints can be actuated",
                        entry.urdf, robot.joints[ji].joint_type
                    ),
                });
            }
            if profile_index_of_urdf_joint.insert(ji, pi).is_some() {
                return Err(ModelError::InvalidProfile {
                    field,
                    reason: format!("joint {:?} is listed twice", entry.urdf),
                });
            }
            if !short_names.insert(entry.name.as_str()) {
                return Err(ModelError::InvalidProfile {
                    field: format!("joints[{pi}].name"),
                    reason: format!("short name {:?} is used twice", entry.name),
                });
            }
        }

        let mut joints: Vec<Option<Joint>> = vec![None; profile.joints.len()];
        let mut links = Vec::with_capacity(bodies.len());
        for (bi, body) in bodies.into_iter().enumerate() {
            let parent_joint = match body.urdf_joint {
                None => None,
                Some(ji) => {
                    let urdf_joint = &robot.joints[ji];
                    let pi = *profile_index_of_urdf_joint.get(&ji).ok_or_else(|| {
                        ModelError::InvalidJoint {
                            joint: urdf_joint.name.clone(),
                            reason: "is movable but not listed in the robot profile's joints"
                                .into(),
                        }
                    })?;
                    let parent = body.parent.ok_or_else(|| ModelError::Structure {
                        reason: format!("joint {:?} has no parent body", urdf_joint.name),
                    })?;
                    joints[pi] = Some(make_joint(
                        urdf_joint,
                        &profile.joints[pi].name,
                        parent,
                        bi,
                        body.joint_origin,
                    )?);
                    Some(pi)
                }
            };
            links.push(Link {
                name: body.name,
                parent: body.parent,
                parent_joint,
                mass: body.mass.mass,
                com: body.mass.com,
                inertia: body.mass.inertia,
                collisions: body.collisions,
                lumped: body.lumped,
            });
        }
        let joints: Vec<Joint> = joints
            .into_iter()
            .enumerate()
            .map(|(pi, j)| {
                // Every profile joint was resolved to a revolute URDF joint above, and every
                // revolute joint reached from the trunk created a body; a revolute joint not
                // reached means its links are disconnected, which was refused above.
                j.ok_or_else(|| ModelError::Structure {
                    reason: format!(
                        "joint {:?} (joints[{pi}]) is not below the trunk",
                        profile.joints[pi].urdf
                    ),
                })
            })
            .collect::<Result<_, _>>()?;

        // Standing pose within the limits.
        for (pi, (entry, joint)) in profile.joints.iter().zip(&joints).enumerate() {
            if !(joint.lower..=joint.upper).contains(&entry.standing) {
                return Err(ModelError::InvalidProfile {
                    field: format!("joints[{pi}].standing"),
                    reason: format!(
                        "{} rad is outside joint {:?}'s limits [{}, {}]",
                        entry.standing, entry.urdf, joint.lower, joint.upper
                    ),
                });
            }
        }

        // Tracked bodies: the feet in profile order, then the trunk.
        let mut tracked = Vec::with_capacity(profile.feet.len() + 1);
        let mut foot_names: HashSet<&str> = HashSet::new();
        for (fi, foot) in profile.feet.iter().enumerate() {
            if !foot_names.insert(foot.name.as_str()) {
                return Err(ModelError::InvalidProfile {
                    field: format!("feet[{fi}].name"),
                    reason: format!("foot name {:?} is used twice", foot.name),
                });
            }
            let field = format!("feet[{fi}]");
            let body_index =
                *placements
                    .get(&foot.link)
                    .ok_or_else(|| ModelError::MissingLink {
                        link: foot.link.clone(),
                        referenced_by: format!("{field}.link"),
                    })?;
            let body = &links[body_index];
            let shapes: Vec<usize> = body
                .collisions
                .iter()
                .enumerate()
                .filter(|(_, c)| {
                    c.urdf_link == foot.link
                        && foot
                            .collision
                            .as_ref()
                            .is_none_or(|name| c.name.as_ref() == Some(name))
                })
                .map(|(i, _)| i)
                .collect();
            if shapes.is_empty() {
                return Err(match &foot.collision {
                    Some(name) => ModelError::MissingCollision {
                        link: foot.link.clone(),
                        collision: name.clone(),
                        referenced_by: format!("{field}.collision"),
                    },
                    None => ModelError::InvalidProfile {
                        field: format!("{field}.link"),
                        reason: format!("link {:?} has no collision shape", foot.link),
                    },
                });
            }
            tracked.push(TrackedBody {
                name: foot.name.clone(),
                link: body_index,
                shapes,
            });
        }
        if links[0].collisions.is_empty() {
            return Err(ModelError::InvalidProfile {
                field: "trunk".into(),
                reason: format!(
                    "trunk link {:?} has no collision shape, so its ground contact could never be seen",
                    profile.trunk
                ),
            });
        }
        tracked.push(TrackedBody {
            name: profile.trunk.clone(),
            link: 0,
            shapes: (0..links[0].collisions.len()).collect(),
        });

        let kp = profile
            .joints
            .iter()
            .map(|j| j.kp.unwrap_or(profile.gains.kp))
            .collect();
        let kd = profile
            .joints
            .iter()
            .map(|j| j.kd.unwrap_or(profile.gains.kd))
            .collect();
        let total_mass = links.iter().map(|l| l.mass).sum();
        Ok(Self {
            name: profile.name.clone(),
            links,
            joints,
            tracked,
            num_feet: profile.feet.len(),
            standing: profile.joints.iter().map(|j| j.standing).collect(),
            spawn_height: profile.spawn.height,
            standing_height: profile
                .spawn
                .standing_height
                .unwrap_or(profile.spawn.height),
            kp,
            kd,
            total_mass,
        })
    }

    /// The robot's name (from the profile).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The bodies, parents before children; index 0 is the trunk.
    pub fn links(&self) -> &[Link] {
        &self.links
    }

    /// The actuated joints in profile order (the order of observations and actions).
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Number of actuated joints.
    pub fn num_joints(&self) -> usize {
        self.joints.len()
    }

    /// Number of bodies.
    pub fn num_links(&self) -> usize {
        self.links.len()
    }

    /// Tracked bodies whose ground contact backends report: the feet in profile order, then
    /// the trunk (last).
    pub fn tracked(&self) -> &[TrackedBody] {
        &self.tracked
    }

    /// Number of tracked feet (the tracked bodies before the trunk).
    pub fn num_feet(&self) -> usize {
        self.num_feet
    }

    /// Index of the trunk in [`RobotModel::tracked`] (it is the last one).
    pub fn trunk_tracked_index(&self) -> usize {
        self.num_feet
    }

    /// Index of an actuated joint by its short name.
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    /// Index of a body by its URDF link name.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    /// Nominal standing joint angles (rad), profile order.
    pub fn standing_pose(&self) -> &[f64] {
        &self.standing
    }

    /// Height (m) of the trunk frame at spawn.
    pub fn spawn_height(&self) -> f64 {
        self.spawn_height
    }

    /// Nominal standing height (m) of the trunk frame: where it settles standing at the
    /// standing pose (the profile's `spawn.standing_height`, else the spawn height).
    pub fn standing_height(&self) -> f64 {
        self.standing_height
    }

    /// Default proportional gains (N·m/rad), profile order.
    pub fn kp(&self) -> &[f64] {
        &self.kp
    }

    /// Default derivative gains (N·m·s/rad), profile order.
    pub fn kd(&self) -> &[f64] {
        &self.kd
    }

    /// Total mass of the robot (kg).
    pub fn total_mass(&self) -> f64 {
        self.total_mass
    }

    /// The spawn state: trunk level at the spawn height above the world origin, joints at the
    /// standing pose, everything at rest.
    pub fn spawn_state(&self) -> RobotState {
        RobotState {
            trunk: TrunkState {
                pose: Isometry3::translation(0.0, 0.0, self.spawn_height),
                linvel: Vector3::zeros(),
                angvel: Vector3::zeros(),
            },
            q: self.standing.clone(),
            qd: vec![0.0; self.joints.len()],
        }
    }

    /// Forward kinematics: the world pose of every body frame (index as in
    /// [`RobotModel::links`]) for a trunk pose and joint angles (profile order). No allocation.
    ///
    /// Errors if `q` has the wrong length or `out` is not one pose per body.
    pub fn link_poses(
        &self,
        trunk: &Isometry3<f64>,
        q: &[f64],
        out: &mut [Isometry3<f64>],
    ) -> Result<(), PhysicsError> {
        if q.len() != self.joints.len() {
            return Err(PhysicsError::WrongLength {
                what: "joint angles",
                expected: self.joints.len(),
                got: q.len(),
            });
        }
        if out.len() != self.links.len() {
            return Err(PhysicsError::WrongLength {
                what: "link pose buffer (one per body, not per joint)",
                expected: self.links.len(),
                got: out.len(),
            });
        }
        out[0] = *trunk;
        for (i, link) in self.links.iter().enumerate().skip(1) {
            // Bodies are stored parents first, and every non-root body has a parent joint.
            if let (Some(parent), Some(j)) = (link.parent, link.parent_joint) {
                let joint = &self.joints[j];
                out[i] =
                    out[parent] * joint.origin * UnitQuaternion::from_axis_angle(&joint.axis, q[j]);
            }
        }
        Ok(())
    }

    /// The whole robot's centre of mass (world) for body poses from [`RobotModel::link_poses`].
    ///
    /// # Panics
    /// If `link_poses` does not hold one pose per body.
    pub fn centre_of_mass(&self, link_poses: &[Isometry3<f64>]) -> Vector3<f64> {
        assert_eq!(
            link_poses.len(),
            self.links.len(),
            "one pose per body is needed"
        );
        let weighted: Vector3<f64> = self
            .links
            .iter()
            .zip(link_poses)
            .map(|(l, p)| (p * nalgebra::Point3::from(l.com)).coords * l.mass)
            .sum();
        weighted / self.total_mass
    }

    /// The lowest world z of a tracked body's shapes for body poses from
    /// [`RobotModel::link_poses`]: its clearance above flat ground at z = 0.
    ///
    /// # Panics
    /// If `tracked` is out of range or `link_poses` does not hold one pose per body.
    pub fn tracked_lowest_z(&self, tracked: usize, link_poses: &[Isometry3<f64>]) -> f64 {
        assert_eq!(
            link_poses.len(),
            self.links.len(),
            "one pose per body is needed"
        );
        let t = &self.tracked[tracked];
        let link = &self.links[t.link];
        t.shapes
            .iter()
            .map(|&s| {
                let c = &link.collisions[s];
                c.shape.lowest_z(&(link_poses[t.link] * c.origin))
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The lowest world z of all the robot's collision shapes for body poses from
    /// [`RobotModel::link_poses`].
    ///
    /// # Panics
    /// If `link_poses` does not hold one pose per body.
    pub fn lowest_z(&self, link_poses: &[Isometry3<f64>]) -> f64 {
        assert_eq!(
            link_poses.len(),
            self.links.len(),
            "one pose per body is needed"
        );
        self.links
            .iter()
            .zip(link_poses)
            .flat_map(|(l, p)| {
                l.collisions
                    .iter()
                    .map(move |c| c.shape.lowest_z(&(p * c.origin)))
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Checks the profile's own values (those that need no URDF).
fn check_profile_values(profile: &Profile) -> Result<(), ModelError> {
    let invalid = |field: String, reason: String| ModelError::InvalidProfile { field, reason };
    if profile.joints.is_empty() {
        return Err(invalid("joints".into(), "lists no joint".into()));
    }
    if !(profile.spawn.height.is_finite() && profile.spawn.height > 0.0) {
        return Err(invalid(
            "spawn.height".into(),
            format!("{} m must be finite and positive", profile.spawn.height),
        ));
    }
    if let Some(h) = profile.spawn.standing_height
        && !(h.is_finite() && h > 0.0)
    {
        return Err(invalid(
            "spawn.standing_height".into(),
            format!("{h} m must be finite and positive"),
        ));
    }
    let gain = |field: String, v: f64| {
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(invalid(
                field,
                format!("{v} must be finite and non-negative"),
            ))
        }
    };
    gain("gains.kp".into(), profile.gains.kp)?;
    gain("gains.kd".into(), profile.gains.kd)?;
    for (i, j) in profile.joints.iter().enumerate() {
        if !j.standing.is_finite() {
            return Err(invalid(
                format!("joints[{i}].standing"),
                format!("{} is not finite", j.standing),
            ));
        }
        if let Some(kp) = j.kp {
            gain(format!("joints[{i}].kp"), kp)?;
        }
        if let Some(kd) = j.kd {
            gain(format!("joints[{i}].kd"), kd)?;
        }
    }
    Ok(())
}

/// Adds one URDF link (its mass and collision shapes) to a body, at `in_body`.
fn add_link_to_body(
    body: &mut BodyBuild,
    link: &urdf_rs::Link,
    in_body: &Isometry3<f64>,
) -> Result<(), ModelError> {
    let inertial = &link.inertial;
    let invalid = |reason: String| ModelError::InvalidInertia {
        link: link.name.clone(),
        reason,
    };
    let m = inertial.mass.value;
    if !m.is_finite() || m < 0.0 {
        return Err(invalid(format!(
            "mass {m} kg must be finite and non-negative"
        )));
    }
    if !pose_is_finite(&inertial.origin) {
        return Err(invalid("non-finite inertial <origin>".into()));
    }
    let i = &inertial.inertia;
    let tensor = Matrix3::new(
        i.ixx, i.ixy, i.ixz, //
        i.ixy, i.iyy, i.iyz, //
        i.ixz, i.iyz, i.izz,
    );
    check_inertia(&tensor, false).map_err(invalid)?;
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
        let label = c.name.clone().unwrap_or_else(|| format!("#{ci}"));
        let invalid = |reason: String| ModelError::InvalidGeometry {
            link: link.name.clone(),
            collision: label.clone(),
            reason,
        };
        if !pose_is_finite(&c.origin) {
            return Err(invalid("non-finite <origin>".into()));
        }
        let positive = |what: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(invalid(format!("{what} {v} m must be finite and positive")))
            }
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
                if !(length.is_finite() && *length >= 0.0) {
                    return Err(invalid(format!(
                        "capsule length {length} m must be finite and non-negative"
                    )));
                }
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
                    "mesh {filename:?} is not supported; use box, sphere, capsule or cylinder"
                )));
            }
        };
        body.collisions.push(Collision {
            name: c.name.clone(),
            urdf_link: link.name.clone(),
            origin: in_body * urdf_pose(&c.origin),
            shape,
        });
    }
    Ok(())
}

/// Validates a revolute URDF joint and turns it into an actuated [`Joint`].
fn make_joint(
    joint: &urdf_rs::Joint,
    short_name: &str,
    parent: usize,
    child: usize,
    origin: Isometry3<f64>,
) -> Result<Joint, ModelError> {
    let invalid = |reason: String| ModelError::InvalidJoint {
        joint: joint.name.clone(),
        reason,
    };
    let axis = Vector3::from(joint.axis.xyz.0);
    if !axis.iter().all(|v| v.is_finite()) || axis.norm() < 1e-9 {
        return Err(invalid(format!(
            "axis {:?} must be finite and non-zero",
            joint.axis.xyz.0
        )));
    }
    let l = &joint.limit;
    if !(l.lower.is_finite() && l.upper.is_finite() && l.lower < l.upper) {
        return Err(invalid(format!(
            "position limits [{}, {}] must be finite with lower < upper",
            l.lower, l.upper
        )));
    }
    if !(l.effort.is_finite() && l.effort > 0.0) {
        return Err(invalid(format!(
            "effort limit {} N·m must be finite and positive",
            l.effort
        )));
    }
    if !(l.velocity.is_finite() && l.velocity > 0.0) {
        return Err(invalid(format!(
            "velocity limit {} rad/s must be finite and positive",
            l.velocity
        )));
    }
    let (damping, friction) = joint
        .dynamics
        .as_ref()
        .map_or((0.0, 0.0), |d| (d.damping, d.friction));
    if !(damping.is_finite() && damping >= 0.0) {
        return Err(invalid(format!(
            "damping {damping} N·m·s/rad must be finite and non-negative"
        )));
    }
    if friction != 0.0 {
        return Err(invalid(format!(
            "Coulomb joint friction {friction} N·m is not supported (must be 0)"
        )));
    }
    Ok(Joint {
        name: short_name.to_owned(),
        urdf_name: joint.name.clone(),
        parent,
        child,
        origin,
        axis: Unit::new_normalize(axis),
        lower: l.lower,
        upper: l.upper,
        effort: l.effort,
        velocity: l.velocity,
        damping,
    })
}
