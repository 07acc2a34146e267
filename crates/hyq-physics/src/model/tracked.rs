//! Phase 4 of building a model: the tracked bodies whose ground contact backends report, the
//! profile's feet in its order, then the trunk.

use std::collections::{HashMap, HashSet};

use super::{Link, TrackedBody};
use crate::error::ModelError;
use crate::profile::Profile;

/// The feet (each the named collision shapes of one URDF link, or all of them) in profile
/// order, then the trunk (every shape of body 0, which must have one).
pub(super) fn tracked_bodies(
    profile: &Profile,
    links: &[Link],
    placements: &HashMap<String, usize>,
) -> Result<Vec<TrackedBody>, ModelError> {
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
        let body_index = *placements
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
                    available: collision_names(body, &foot.link),
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
    Ok(tracked)
}

/// The names of the collisions declared on URDF link `link` (now in `body`), unnamed ones as
/// `#i` (their index on the link), comma-separated; "none" if it has none.
fn collision_names(body: &Link, link: &str) -> String {
    let names: Vec<String> = body
        .collisions
        .iter()
        .filter(|c| c.urdf_link == link)
        .enumerate()
        .map(|(i, c)| {
            c.name
                .as_ref()
                .map_or_else(|| format!("#{i}"), |n| crate::printable(n))
        })
        .collect();
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}
