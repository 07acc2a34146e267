//! Reading a robot from MuJoCo's MJCF into the [`RobotModel`](hyq_physics::RobotModel) every
//! engine builds from.
//!
//! What is read: `<compiler>` (`angle`, `eulerseq`, `autolimits`), default classes (nested,
//! with `childclass`), `<include>` (relative to the including file, cycles refused), one robot
//! in the `<worldbody>`: a root body with a free joint, bodies with at most one hinge (`axis`,
//! `pos`, `range`, `limited`, `damping`, `armature`, `frictionloss`, `actuatorfrcrange`),
//! `<inertial>` (`diaginertia` or `fullinertia`), box, sphere, capsule and cylinder geoms
//! (`size`, or `fromto`), every orientation form (`quat`, `axisangle`, `euler`, `xyaxes`,
//! `zaxis`), `<position>` (`kp`, `kv`, `forcerange`, `ctrlrange`, `inheritrange`) and
//! `<motor>` actuators on hinges, and keyframes.
//!
//! What is left out, with a note ([`MjcfRobot::notes`]): visual-only geoms (contype and
//! conaffinity 0; mesh files are never read), world geoms (the floor: the project makes its
//! own ground), sites, cameras, lights, sensors, `<option>`, `<visual>`, `<asset>`,
//! `<statistic>`, `<custom>`, contact-solver attributes (`condim`, `solimp`, `friction`, …: the
//! engines use the project's contact settings), `<contact><exclude>` (no engine here collides a
//! robot with itself).
//!
//! What the model cannot represent is refused by name, with the file and line: other joint
//! types, two joints in a body, stiff joints, colliding meshes and other geom types, other
//! actuators, tendons, equality constraints, explicit contact pairs, any unknown element or
//! attribute. Bad input gives one line and never hangs: each file goes through the project's
//! size-capped reader, its nesting is checked before the XML parser runs, includes are capped
//! in number and refused in cycles, default classes cannot repeat, and every number must be
//! finite and of magnitude at most [`attrs::MAX_ABS`].
//!
//! The robot becomes a URDF description ([`MjcfRobot::robot`]) and then a model through the
//! same builder as a URDF ([`hyq_physics::RobotModel::from_urdf_model`]), with a profile as
//! any robot: [`MjcfRobot::model`].

mod actuators;
mod attrs;
mod bodies;
mod build;
mod defaults;
mod elem;
mod types;

use std::path::Path;

pub use elem::{MAX_ELEMENTS, MAX_FILES, MJCF, MjcfReadError};
pub use types::{Actuator, ActuatorKind, Keyframe, MjcfRobot};

/// Top-level elements with nothing of the robot's mechanics: skipped, with a note.
const TOP_SKIPPED: &[&str] = &[
    "option",
    "size",
    "visual",
    "statistic",
    "custom",
    "asset",
    "sensor",
];

/// Top-level elements whose content the model cannot represent: refused unless empty.
const TOP_REFUSED: &[&str] = &["equality", "tendon", "deformable", "extension", "flexcomp"];

/// Reads the MJCF file at `path` and the files it includes.
pub fn read_file(path: impl AsRef<Path>) -> Result<MjcfRobot, MjcfReadError> {
    read_tree(&elem::load_file(path.as_ref())?)
}

/// Reads MJCF text (`origin` names it in messages); an `<include>` is refused (there is no
/// directory to find it in).
pub fn read_str(text: &str, origin: &str) -> Result<MjcfRobot, MjcfReadError> {
    read_tree(&elem::load_str(text, origin, None)?)
}

/// Reads MJCF text whose `<include>` files are found relative to `dir`.
pub fn read_str_in(text: &str, origin: &str, dir: &Path) -> Result<MjcfRobot, MjcfReadError> {
    read_tree(&elem::load_str(text, origin, Some(dir))?)
}

fn read_tree(root: &elem::Elem) -> Result<MjcfRobot, MjcfReadError> {
    let mut compiler = attrs::Compiler::default();
    let mut notes = Vec::new();
    for e in &root.children {
        match e.tag.as_str() {
            "compiler" => attrs::compiler(e, &mut compiler)?,
            "default" | "worldbody" | "actuator" | "keyframe" => {}
            "contact" => contact(e, &mut notes)?,
            t if TOP_SKIPPED.contains(&t) => {
                notes.push(format!("{}: skipped (no robot mechanics in it)", e.at()));
            }
            t if TOP_REFUSED.contains(&t) && e.children.is_empty() => {}
            t if TOP_REFUSED.contains(&t) => {
                return Err(e.error("cannot be represented (no constraint of this kind here)"));
            }
            _ => return Err(e.error("is not an MJCF element read here")),
        }
    }
    let defaults = defaults::Defaults::read(&root.children)?;
    let of =
        |tag: &str| -> Vec<&elem::Elem> { root.children.iter().filter(|e| e.tag == tag).collect() };
    let name = root.get("model").map(str::to_owned);
    let mut walk = bodies::Walk::new(&defaults, compiler, name.as_deref().unwrap_or("mjcf"));
    let root_body = walk.worldbody(&of("worldbody"))?;
    let actuators = actuators::actuators(&of("actuator"), &defaults, &walk.joints, &walk.ranges)?;
    let keyframes = actuators::keyframes(&of("keyframe"), 7 + walk.joints.len(), actuators.len())?;
    notes.append(&mut walk.notes);
    Ok(MjcfRobot {
        name,
        robot: walk.robot,
        root: root_body,
        joints: walk.joints,
        armature: walk.armature,
        joint_force: walk.joint_force,
        actuators,
        keyframes,
        notes,
    })
}

/// `<contact>`: `<exclude>` pairs are redundant here (robots never collide with themselves);
/// explicit `<pair>`s cannot be represented.
fn contact(e: &elem::Elem, notes: &mut Vec<String>) -> Result<(), MjcfReadError> {
    for c in &e.children {
        if c.tag != "exclude" {
            return Err(c.error("cannot be represented (contacts are the ground's only)"));
        }
    }
    if !e.children.is_empty() {
        notes.push(format!(
            "{}: {} exclusions skipped: no engine here collides a robot with itself",
            e.at(),
            e.children.len()
        ));
    }
    Ok(())
}
