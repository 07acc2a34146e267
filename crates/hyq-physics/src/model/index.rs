//! Phase 1 of building a model: index the URDF's links and joints by name, and check that the
//! profile's trunk is the tree's root.

use std::collections::HashMap;

use crate::error::ModelError;

/// The URDF's links and joints by name, and the tree's parent/child relations.
pub(super) struct UrdfIndex<'a> {
    /// Index in `robot.links` of each link.
    pub(super) link_by_name: HashMap<&'a str, usize>,
    /// Index in `robot.joints` of each joint.
    pub(super) joint_by_name: HashMap<&'a str, usize>,
    /// The joint (index in `robot.joints`) whose child each link is.
    pub(super) parent_joint_of: HashMap<&'a str, usize>,
    /// The joints (indices in `robot.joints`, URDF order) whose parent each link is.
    pub(super) children_of: HashMap<&'a str, Vec<usize>>,
}

impl<'a> UrdfIndex<'a> {
    /// Indexes `robot`, refusing duplicate names, joints naming undefined links, and links with
    /// two parent joints.
    pub(super) fn new(robot: &'a urdf_rs::Robot) -> Result<Self, ModelError> {
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
        Ok(Self {
            link_by_name,
            joint_by_name,
            parent_joint_of,
            children_of,
        })
    }

    /// The trunk link's index, checking that it exists and is the root (no parent joint).
    pub(super) fn root(&self, robot: &urdf_rs::Robot, trunk: &str) -> Result<usize, ModelError> {
        let Some(&root) = self.link_by_name.get(trunk) else {
            return Err(ModelError::MissingLink {
                link: trunk.to_owned(),
                referenced_by: "trunk".into(),
            });
        };
        if let Some(&j) = self.parent_joint_of.get(trunk) {
            return Err(ModelError::Structure {
                reason: format!(
                    "the trunk {trunk:?} must be the URDF's root link, but it is the child of joint {:?}",
                    robot.joints[j].name
                ),
            });
        }
        Ok(root)
    }
}
