//! Phase 2 of building a model: walk the URDF tree from the trunk, making one body per movable
//! joint and lumping links attached by fixed joints into their parent's body; then check that
//! every body can move (positive mass, invertible inertia).

use std::collections::{HashMap, HashSet};

use nalgebra::Isometry3;

use super::BodyBuild;
use super::index::UrdfIndex;
use super::joints::is_movable;
use super::parts::{add_link_to_body, check_pose, urdf_pose};
use crate::bounds;
use crate::error::ModelError;
use crate::inertia::{MassProperties, check_inertia};

/// The bodies of the tree, parents before children, and where each URDF link went.
pub(super) struct Tree {
    pub(super) bodies: Vec<BodyBuild>,
    /// The body each URDF link ended up in.
    pub(super) placements: HashMap<String, usize>,
}

/// Where a link reached by the walk goes.
enum Target {
    /// Lump into an existing body, at this frame in it.
    Lump(usize, Isometry3<f64>),
    /// Start a body below `parent` (`None` for the root), attached by URDF joint `joint` at
    /// `origin`.
    New {
        parent: Option<usize>,
        joint: Option<usize>,
        origin: Isometry3<f64>,
    },
}

/// Walks the tree from `root` depth first, children in URDF order, making a body per movable
/// joint (when it is reached, so bodies are numbered in that order) and lumping links attached
/// by fixed joints into their parent's body. Every link must be reached exactly once.
pub(super) fn walk(
    robot: &urdf_rs::Robot,
    index: &UrdfIndex<'_>,
    root: usize,
    trunk: &str,
) -> Result<Tree, ModelError> {
    let mut bodies: Vec<BodyBuild> = Vec::new();
    let mut placements: HashMap<String, usize> = HashMap::new();
    let mut visited: HashSet<usize> = HashSet::new();
    let mut stack: Vec<(usize, Target)> = vec![(
        root,
        Target::New {
            parent: None,
            joint: None,
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
        let (body, in_body) = place(&mut bodies, link, target);
        add_link_to_body(&mut bodies[body], link, &in_body)?;
        placements.insert(link.name.clone(), body);

        let children = index
            .children_of
            .get(link.name.as_str())
            .map_or(&[][..], |v| v);
        // Pushed in reverse so that children are visited in URDF order.
        for &ji in children.iter().rev() {
            let joint = &robot.joints[ji];
            let child = index.link_by_name[joint.child.link.as_str()];
            let target = child_target(joint, ji, &mut bodies[body], body, &in_body)?;
            stack.push((child, target));
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
                "link {:?} is not connected to the trunk {trunk:?}",
                orphan.1.name
            ),
        });
    }
    Ok(Tree { bodies, placements })
}

/// The body `link` goes into and its pose in that body's frame: for [`Target::New`] a new body,
/// numbered next, with the link at its origin.
fn place(
    bodies: &mut Vec<BodyBuild>,
    link: &urdf_rs::Link,
    target: Target,
) -> (usize, Isometry3<f64>) {
    match target {
        Target::Lump(body, in_body) => (body, in_body),
        Target::New {
            parent,
            joint,
            origin,
        } => {
            bodies.push(BodyBuild {
                name: link.name.clone(),
                parent,
                urdf_joint: joint,
                joint_origin: origin,
                mass: MassProperties::zero(),
                collisions: Vec::new(),
                lumped: Vec::new(),
            });
            (bodies.len() - 1, Isometry3::identity())
        }
    }
}

/// Where URDF joint `joint` (number `ji`) puts its child link, whose parent link sits at
/// `in_body` in `parent` (body number `body`): lumped into `parent` for a fixed joint (which
/// `parent` records), a new body for a movable one; any other joint type is refused.
fn child_target(
    joint: &urdf_rs::Joint,
    ji: usize,
    parent: &mut BodyBuild,
    body: usize,
    in_body: &Isometry3<f64>,
) -> Result<Target, ModelError> {
    check_pose(&joint.origin).map_err(|reason| ModelError::InvalidJoint {
        joint: joint.name.clone(),
        reason,
    })?;
    let origin = in_body * urdf_pose(&joint.origin);
    match joint.joint_type {
        urdf_rs::JointType::Fixed => {
            parent.lumped.push(joint.child.link.clone());
            Ok(Target::Lump(body, origin))
        }
        ref kind if is_movable(kind) => Ok(Target::New {
            parent: Some(body),
            joint: Some(ji),
            origin,
        }),
        ref other => Err(ModelError::InvalidJoint {
            joint: joint.name.clone(),
            reason: format!(
                "type {other:?} is not supported (revolute, continuous and fixed \
                 joints only); make it fixed, or revolute with limits, in the URDF"
            ),
        }),
    }
}

/// Checks that every body has a usable mass: positive, with a physically valid, invertible
/// tensor. The check is on the body, after lumping, not on each URDF link: a fixed link's
/// placeholder tensor that is invalid on its own is fine inside a valid body.
pub(super) fn check_masses(bodies: &[BodyBuild]) -> Result<(), ModelError> {
    for body in bodies {
        let whole = if body.lumped.is_empty() {
            String::new()
        } else {
            format!(
                "the body of link {:?} and the links fixed to it ({}) ",
                body.name,
                body.lumped
                    .iter()
                    .map(|l| crate::printable(l))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let invalid = |reason: String| ModelError::InvalidInertia {
            link: body.name.clone(),
            reason: format!("{whole}{reason}"),
        };
        if body.mass.mass <= 0.0 {
            return Err(invalid(format!(
                "has total mass {} kg; a moving body's mass must be positive: give the link \
                 (or a link fixed to it) an <inertial> with a mass",
                bounds::short(body.mass.mass)
            )));
        }
        bounds::BODY_MASS.check(body.mass.mass).map_err(|reason| {
            invalid(format!(
                "total mass: {reason} (an f32 engine cannot hold it faithfully)"
            ))
        })?;
        check_inertia(&body.mass.inertia, true).map_err(invalid)?;
        let mut moments: [f64; 3] = body.mass.inertia.symmetric_eigenvalues().into();
        moments.sort_by(f64::total_cmp);
        for m in moments {
            bounds::BODY_MOMENT.check(m).map_err(|reason| {
                invalid(format!(
                    "principal moment of inertia: {reason} (an f32 engine cannot hold it \
                     faithfully)"
                ))
            })?;
        }
    }
    Ok(())
}
