//! The standing pose a draft starts from: an SRDF's `<group_state name="standing">`, an MJCF
//! robot's `home` keyframe (else its first), or zeros.

use std::collections::HashMap;
use std::path::Path;

use hyq_physics::input;

use super::types::{DraftError, Source};
use crate::mjcf_read::MjcfRobot;

/// The group state an SRDF's standing pose is read from.
pub(crate) const SRDF_STATE: &str = "standing";

/// Standing angles (rad) by joint name, and where they came from (a sentence for the comment).
#[derive(Debug, Clone, Default)]
pub(crate) struct Standing {
    /// Angle by the robot file's joint name; joints not here stand at 0.
    pub(crate) angles: HashMap<String, f64>,
    /// Where the angles came from.
    pub(crate) source: String,
}

/// The standing pose of `source` (hinge names `hinges`): from `srdf` when given, else an MJCF
/// robot's keyframe, else zeros.
pub(crate) fn standing(
    source: &Source,
    hinges: &[String],
    srdf: Option<&Path>,
) -> Result<Standing, DraftError> {
    if let Some(path) = srdf {
        return read_srdf(path, hinges);
    }
    if let Source::Mjcf(m) = source
        && let Some(s) = keyframe(m)?
    {
        return Ok(s);
    }
    let how = match source {
        Source::Urdf(_) => "a URDF holds no standing pose and no SRDF was given (--srdf)",
        Source::Mjcf(_) => "the MJCF file has no keyframe with joint positions",
    };
    Ok(Standing {
        angles: HashMap::new(),
        source: format!(
            "Standing angles: all 0, or the nearer end of a joint's range where 0 is outside it \
             ({how}): EDIT THEM to a pose with every foot on the ground."
        ),
    })
}

/// The `home` keyframe's hinge positions (else the first keyframe's), if any keyframe gives
/// joint positions.
fn keyframe(m: &MjcfRobot) -> Result<Option<Standing>, DraftError> {
    let key = m
        .keyframes
        .iter()
        .find(|k| k.name == "home")
        .or_else(|| m.keyframes.first());
    let Some(key) = key.filter(|k| !k.qpos.is_empty()) else {
        return Ok(None);
    };
    let hinges = key.qpos.get(7..).unwrap_or_default();
    if hinges.len() != m.joints.len() {
        return Err(DraftError(format!(
            "keyframe {:?}: {} joint positions after the free joint's 7, for {} hinges",
            key.name,
            hinges.len(),
            m.joints.len()
        )));
    }
    let which = if key.name == "home" {
        "the MJCF's `home` keyframe".to_owned()
    } else {
        format!(
            "the MJCF's first keyframe ({:?}; there is no `home`)",
            hyq_physics::printable(&key.name)
        )
    };
    Ok(Some(Standing {
        angles: m
            .joints
            .iter()
            .cloned()
            .zip(hinges.iter().copied())
            .collect(),
        source: format!("Standing angles: {which}."),
    }))
}

/// The SRDF's `<group_state name="standing">` joint values (every such group state, merged),
/// each naming one of `hinges`.
fn read_srdf(path: &Path, hinges: &[String]) -> Result<Standing, DraftError> {
    let origin = path.display().to_string();
    let text = input::read_text(path, &input::URDF)
        .map_err(|e| DraftError::at(&origin, format_args!("SRDF: {e}")))?;
    input::check_xml_depth(&text, input::XML_MAX_DEPTH).map_err(|e| DraftError::at(&origin, e))?;
    let doc = roxmltree::Document::parse(&text)
        .map_err(|e| DraftError::at(&origin, format_args!("not XML: {e}")))?;
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        return Err(DraftError::at(
            &origin,
            format_args!(
                "not an SRDF: the root element is <{}>, not <robot>",
                root.tag_name().name()
            ),
        ));
    }
    let states: Vec<_> = root
        .children()
        .filter(|n| n.has_tag_name("group_state"))
        .collect();
    let standing: Vec<_> = states
        .iter()
        .filter(|n| n.attribute("name") == Some(SRDF_STATE))
        .collect();
    if standing.is_empty() {
        let names: Vec<&str> = states.iter().filter_map(|n| n.attribute("name")).collect();
        return Err(DraftError::at(
            &origin,
            format_args!(
                "no <group_state name=\"{SRDF_STATE}\"> (it has: {})",
                if names.is_empty() {
                    "none".to_owned()
                } else {
                    names.join(", ")
                }
            ),
        ));
    }
    let angles = joint_values(&doc, &standing, &origin, hinges)?;
    let missing = hinges.iter().filter(|h| !angles.contains_key(*h)).count();
    let rest = if missing > 0 {
        format!(
            " It gives no angle for {missing} joint(s): those stand at 0, or the nearer end of their range (check them)."
        )
    } else {
        String::new()
    };
    let file = path
        .file_name()
        .map_or(origin.clone(), |n| n.to_string_lossy().into_owned());
    Ok(Standing {
        angles,
        source: format!(
            "Standing angles: the SRDF's group state \"{SRDF_STATE}\" ({}).{rest}",
            hyq_physics::printable(&file)
        ),
    })
}

/// The joint values of the `standing` group states, each naming one of `hinges`, finite.
fn joint_values(
    doc: &roxmltree::Document<'_>,
    standing: &[&roxmltree::Node<'_, '_>],
    origin: &str,
    hinges: &[String],
) -> Result<HashMap<String, f64>, DraftError> {
    let mut angles = HashMap::new();
    for state in standing {
        for j in state.children().filter(|n| n.has_tag_name("joint")) {
            let line = doc.text_pos_at(j.range().start).row;
            let at = |m: String| DraftError::at(&format!("{origin}:{line}"), m);
            let name = j
                .attribute("name")
                .ok_or_else(|| at("<joint> without a name".into()))?;
            if !hinges.iter().any(|h| h == name) {
                return Err(at(format!(
                    "<joint name={:?}> names no hinge joint of the robot",
                    hyq_physics::printable(name)
                )));
            }
            let value = j
                .attribute("value")
                .and_then(|v| v.trim().parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    at(format!(
                        "<joint name={name:?}>: `value` is not a finite number"
                    ))
                })?;
            angles.insert(name.to_owned(), value);
        }
    }
    Ok(angles)
}
