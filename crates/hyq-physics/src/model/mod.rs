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

//!
//! The build runs in phases, one file each: `profile_values.rs` (the profile alone),
//! `index.rs` (the URDF's names and root), `tree.rs` (the walk from the trunk, lumping fixed
//! links, with `parts.rs` converting each link's mass and shapes), `joints.rs` (the actuated
//! joints in profile order) and `tracked.rs` (feet and trunk).

mod gait;
mod index;
mod joints;
mod parts;
mod profile_values;
mod tracked;
mod tree;

use std::path::Path;

use nalgebra::{Isometry3, Matrix3, Unit, UnitQuaternion, Vector3};

use crate::bounds;
use crate::error::{ModelError, PhysicsError};
use crate::inertia::MassProperties;
use crate::input;
use crate::profile::{ObservationBounds, Profile};
pub use gait::{Gait, GaitLeg};
use index::UrdfIndex;
use profile_values::{check_observation_bounds, check_profile_values};

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
    /// The radius (m) of the smallest sphere about the shape's origin that holds it.
    pub fn bounding_radius(&self) -> f64 {
        match *self {
            Shape::Box { half_extents } => half_extents.norm(),
            Shape::Sphere { radius } => radius,
            Shape::Capsule {
                radius,
                half_length,
            } => radius + half_length,
            Shape::Cylinder {
                radius,
                half_length,
            } => radius.hypot(half_length),
        }
    }

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

/// A body under construction: what the tree walk (`tree.rs`) makes of a URDF link and the links
/// lumped into it, which `parts.rs` fills and `joints.rs` turns into a [`Link`].
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
    /// Coulomb joint friction (N·m, URDF `<dynamics friction>`), applied by the shared
    /// actuator (see [`crate::actuator`]), so identically on every backend.
    pub friction: f64,
    /// Armature (kg·m²): rotor inertia added to the joint's inertia about its axis. URDF has
    /// none (0); an MJCF robot's `armature` sets it ([`RobotModel::with_joint_armature`]).
    /// The MuJoCo backend honours it; rapier and DART have no such term and leave it out.
    pub armature: f64,
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
    observation_bounds: Option<ObservationBounds>,
    gait: Option<Gait>,
}

impl RobotModel {
    /// Loads a robot from its profile file; the URDF path inside is relative to the profile. A
    /// profile naming an MJCF (`.xml`) file is refused: `hyq_formats::robots::load_profile`
    /// reads those.
    /// Errors about the robot's content come wrapped in [`ModelError::InProfile`], naming the
    /// file ([`ModelError::innermost`] unwraps them).
    pub fn load(profile_path: impl AsRef<Path>) -> Result<Self, ModelError> {
        let profile_path = profile_path.as_ref();
        let profile_text =
            input::read_text(profile_path, &input::ROBOT_PROFILE).map_err(|source| {
                ModelError::Io {
                    what: "robot profile",
                    path: profile_path.to_owned(),
                    source,
                }
            })?;
        let profile = Profile::from_toml_str(&profile_text, &profile_path.display().to_string())?;
        let urdf_path = profile_path
            .parent()
            .unwrap_or_else(|| Path::new("."))
            .join(&profile.urdf);
        if urdf_path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
        {
            // This crate reads URDF only; hyq-formats reads MJCF and depends on this crate.
            return Err(ModelError::Urdf {
                origin: urdf_path.display().to_string(),
                message: "an .xml robot file is MJCF: load this profile through \
                          hyq_formats::robots::load_profile (the front ends do)"
                    .to_owned(),
            });
        }
        let urdf_text =
            input::read_text(&urdf_path, &input::URDF).map_err(|source| ModelError::Io {
                what: "URDF",
                path: urdf_path.clone(),
                source,
            })?;
        Self::from_urdf_str(&urdf_text, &urdf_path.display().to_string(), &profile).map_err(|e| {
            match e {
                // These already name the URDF file.
                ModelError::Urdf { .. } => e,
                other => ModelError::InProfile {
                    path: profile_path.to_owned(),
                    source: Box::new(other),
                },
            }
        })
    }

    /// Builds a robot from URDF text and a parsed profile (the profile's `urdf` path is not
    /// read). `urdf_origin` (a path or "bundled") appears in error messages.
    ///
    /// Before the XML parser sees the text, its size is held to [`input::URDF`]'s cap and its
    /// nesting to [`input::XML_MAX_DEPTH`] (a deeper text would overflow the parser's stack);
    /// after parsing, its links, joints and collision shapes are counted against
    /// [`crate::bounds`].
    pub fn from_urdf_str(
        urdf_text: &str,
        urdf_origin: &str,
        profile: &Profile,
    ) -> Result<Self, ModelError> {
        let robot = parse_urdf(urdf_text).map_err(|message| ModelError::Urdf {
            origin: urdf_origin.to_owned(),
            message,
        })?;
        check_counts(&robot)?;
        Self::from_urdf_robot(&robot, profile)
    }

    /// Builds a robot from an already parsed URDF description and a parsed profile: what a
    /// reader of another robot format (MJCF, in `hyq-formats`) hands over after converting its
    /// file. The description's links, joints and collision shapes are counted against
    /// [`crate::bounds`] first, as for URDF text.
    pub fn from_urdf_model(robot: &urdf_rs::Robot, profile: &Profile) -> Result<Self, ModelError> {
        check_counts(robot)?;
        Self::from_urdf_robot(robot, profile)
    }

    /// A copy with the given joints' armature (kg·m²) set, as `(joint index, armature)` pairs,
    /// each checked against [`bounds::JOINT_ARMATURE`].
    ///
    /// # Panics
    /// If a joint index is out of range.
    pub fn with_joint_armature(&self, armature: &[(usize, f64)]) -> Result<Self, ModelError> {
        let mut copy = self.clone();
        for &(j, a) in armature {
            let joint = &mut copy.joints[j];
            joint.armature =
                bounds::JOINT_ARMATURE
                    .check(a)
                    .map_err(|reason| ModelError::InvalidJoint {
                        joint: joint.urdf_name.clone(),
                        reason: format!("armature: {reason}"),
                    })?;
        }
        Ok(copy)
    }

    /// Builds the model phase by phase: the profile's own values, the URDF's index and root,
    /// the tree walk with fixed links lumped, the bodies' masses, the actuated joints in
    /// profile order, the standing pose, and the tracked bodies.
    fn from_urdf_robot(robot: &urdf_rs::Robot, profile: &Profile) -> Result<Self, ModelError> {
        check_profile_values(profile)?;
        let index = UrdfIndex::new(robot)?;
        let root = index.root(robot, &profile.trunk)?;
        let tree = tree::walk(robot, &index, root, &profile.trunk)?;
        tree::check_masses(&tree.bodies)?;
        let profile_index_of_urdf_joint = joints::resolve(robot, &index, profile)?;
        let (links, joints) =
            joints::assemble(robot, profile, tree.bodies, &profile_index_of_urdf_joint)?;
        joints::check_standing(profile, &joints)?;
        let tracked = tracked::tracked_bodies(profile, &links, &tree.placements)?;
        let observation_bounds = check_observation_bounds(profile)?;
        let gait = profile
            .gait
            .as_ref()
            .map(|g| Gait::resolve(g, profile, &joints))
            .transpose()?;

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
            observation_bounds,
            gait,
        })
    }

    /// The robot's name (from the profile): 1 to 64 ASCII letters, digits, `_`, `-`, `.`.
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

    /// The declared bounds of the trunk's observation rows, when the profile gives them
    /// (`[observation]`); environments use the spec's (HyQ's) bounds otherwise.
    pub fn observation_bounds(&self) -> Option<&ObservationBounds> {
        self.observation_bounds.as_ref()
    }

    /// The scripted trot's leg map and parameters (the profile's `[gait]`), if it has one.
    pub fn gait(&self) -> Option<&Gait> {
        self.gait.as_ref()
    }

    /// Total mass of the robot (kg).
    pub fn total_mass(&self) -> f64 {
        self.total_mass
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

    /// The inertia (kg·m²) of joint `j`'s child body about the joint's axis through the joint
    /// frame's origin (the child body frame's origin).
    ///
    /// # Panics
    /// If `j` is not a joint index.
    pub fn axis_inertia(&self, j: usize) -> f64 {
        let joint = &self.joints[j];
        let link = &self.links[joint.child];
        let c = link.com;
        let about_origin =
            link.inertia + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * link.mass;
        let a = joint.axis.into_inner();
        (a.transpose() * about_origin * a)[(0, 0)]
    }

    /// A copy with the given joints' damping (N·m·s/rad) replaced, as `(joint index, damping)`
    /// pairs: a robot whose URDF damps none of its joints, damped (the conformance kit's
    /// damping test uses it).
    ///
    /// # Panics
    /// If a joint index is out of range.
    pub fn with_joint_damping(&self, damping: &[(usize, f64)]) -> Self {
        let mut copy = self.clone();
        for &(j, d) in damping {
            copy.joints[j].damping = d;
        }
        copy
    }

    /// A copy with every body's mass properties and every joint's damping replaced (one per
    /// body, as in [`RobotModel::links`], and one per joint; extra entries are ignored): the
    /// conformance kit builds a world from the model a [`crate::Dynamics`] describes to check
    /// that a world given those dynamics in place behaves as one built with them.
    pub fn with_mass_properties(&self, bodies: &[MassProperties], joint_damping: &[f64]) -> Self {
        let mut copy = self.clone();
        for (link, body) in copy.links.iter_mut().zip(bodies) {
            link.mass = body.mass;
            link.com = body.com;
            link.inertia = body.inertia;
        }
        for (joint, &damping) in copy.joints.iter_mut().zip(joint_damping) {
            joint.damping = damping;
        }
        copy.total_mass = copy.links.iter().map(|l| l.mass).sum();
        copy
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

    /// The farthest (m) any collision shape reaches from the trunk frame's origin when the
    /// robot stands at its standing pose: the room it needs around its spawn point.
    pub fn standing_reach(&self) -> f64 {
        let mut poses = vec![Isometry3::identity(); self.links.len()];
        // One angle per joint and one pose per body: the call cannot fail.
        let _ = self.link_poses(&Isometry3::identity(), &self.standing, &mut poses);
        self.links
            .iter()
            .zip(&poses)
            .flat_map(|(l, p)| {
                l.collisions.iter().map(move |c| {
                    (p * c.origin).translation.vector.norm() + c.shape.bounding_radius()
                })
            })
            .fold(0.0, f64::max)
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

/// URDF text parsed into a description: refused (one line, the parser's message folded and
/// anything unprintable escaped, since it may quote the file) when larger than any URDF
/// ([`input::URDF`]), nested deeper than [`input::XML_MAX_DEPTH`] (a deeper text would
/// overflow the parser's stack) or not a URDF. What every reader of URDF text goes through.
pub fn parse_urdf(urdf_text: &str) -> Result<urdf_rs::Robot, String> {
    if urdf_text.len() as u64 > input::URDF.max_bytes {
        return Err(format!(
            "larger than {}, which no URDF is",
            input::size_text(input::URDF.max_bytes)
        ));
    }
    input::check_xml_depth(urdf_text, input::XML_MAX_DEPTH)?;
    urdf_rs::read_from_string(urdf_text).map_err(|e| {
        let folded = e
            .to_string()
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        crate::printable(&folded)
    })
}

/// Refuses a URDF with more links, joints or collision shapes than [`crate::bounds`] allows,
/// before anything is built from it (tens of thousands of shapes take minutes and gigabytes).
fn check_counts(robot: &urdf_rs::Robot) -> Result<(), ModelError> {
    let shapes: usize = robot.links.iter().map(|l| l.collision.len()).sum();
    for (what, bound, count) in [
        ("links", &bounds::LINK_COUNT, robot.links.len()),
        ("joints", &bounds::JOINT_COUNT, robot.joints.len()),
        ("collision shapes", &bounds::SHAPE_COUNT, shapes),
    ] {
        bound
            .check_count(count)
            .map_err(|reason| ModelError::Structure {
                reason: format!("the URDF's {what}: {reason}"),
            })?;
    }
    Ok(())
}
