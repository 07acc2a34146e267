//! `<actuator>` (`<position>` and `<motor>` on hinge joints) and `<keyframe>`.

use std::collections::HashMap;

use super::attrs::Attrs;
use super::defaults::{Defaults, MAIN};
use super::elem::{Elem, MjcfReadError};
use super::types::{Actuator, ActuatorKind, Keyframe};

/// Actuator attributes that change nothing the model holds.
const ACTUATOR_IGNORED: &[&str] = &["group", "user", "actdim", "actlimited", "actrange"];

/// The actuators of the `<actuator>` elements, each on a hinge of `ranges` (joint name to its
/// range, rad) or of `hinges` (every hinge).
pub(crate) fn actuators(
    sections: &[&Elem],
    defaults: &Defaults,
    hinges: &[String],
    ranges: &HashMap<String, [f64; 2]>,
) -> Result<Vec<Actuator>, MjcfReadError> {
    let mut out: Vec<Actuator> = Vec::new();
    for section in sections {
        if let Some((k, _)) = section.attrs.first() {
            return Err(section.error(format!("attribute `{k}` is not understood")));
        }
        for e in &section.children {
            let actuator = actuator(e, defaults, out.len(), hinges, ranges)?;
            if let Some(other) = out.iter().find(|o| o.joint == actuator.joint) {
                return Err(e.error(format!(
                    "joint {:?} already has actuator {:?}: one actuator per joint",
                    actuator.joint, other.name
                )));
            }
            out.push(actuator);
        }
    }
    Ok(out)
}

fn actuator(
    e: &Elem,
    defaults: &Defaults,
    index: usize,
    hinges: &[String],
    ranges: &HashMap<String, [f64; 2]>,
) -> Result<Actuator, MjcfReadError> {
    if e.tag != "position" && e.tag != "motor" {
        return Err(e.error("this actuator cannot be represented (<position> and <motor> only)"));
    }
    let class = defaults.class_of(e, MAIN)?;
    let a = Attrs::new(e, &defaults.template(class, &e.tag));
    let mut read = vec![
        "name",
        "joint",
        "gear",
        "forcerange",
        "forcelimited",
        "ctrlrange",
        "ctrllimited",
    ];
    if e.tag == "position" {
        read.extend(["kp", "kv", "inheritrange"]);
    }
    a.check_known(&read, ACTUATOR_IGNORED)?;
    let joint = a
        .get("joint")
        .ok_or_else(|| a.error("no `joint`: only actuators on a hinge joint are read"))?
        .to_owned();
    if !hinges.contains(&joint) {
        return Err(a.error(format!("no hinge joint named {joint:?}")));
    }
    let gear = a.nums("gear", None)?.unwrap_or_else(|| vec![1.0]);
    if gear.first().is_none_or(|g| *g == 0.0) || gear.iter().skip(1).any(|g| *g != 0.0) {
        return Err(a.error("attribute `gear`: one non-zero ratio is read"));
    }
    let force_range = limited_range(&a, "forcerange", "forcelimited")?;
    let mut ctrl_range = limited_range(&a, "ctrlrange", "ctrllimited")?;
    let kind = if e.tag == "position" {
        if gear[0] != 1.0 {
            return Err(a.error("attribute `gear`: a position servo is read with gear 1 only"));
        }
        let inherit = a.num("inheritrange", 0.0)?;
        if inherit > 0.0 {
            let [lo, hi] = *ranges.get(&joint).ok_or_else(|| {
                a.error(format!("`inheritrange`, but joint {joint:?} has no range"))
            })?;
            let (mid, half) = ((lo + hi) / 2.0, (hi - lo) / 2.0 * inherit);
            ctrl_range = Some([mid - half, mid + half]);
        }
        let (kp, kv) = (a.num("kp", 1.0)?, a.num("kv", 0.0)?);
        if kp <= 0.0 || kv < 0.0 {
            return Err(a.error("`kp` must be positive and `kv` not negative"));
        }
        ActuatorKind::Position { kp, kv }
    } else {
        ActuatorKind::Motor { gear: gear[0] }
    };
    Ok(Actuator {
        name: a
            .get("name")
            .map_or_else(|| format!("actuator{index}"), str::to_owned),
        joint,
        kind,
        force_range,
        ctrl_range,
    })
}

/// A range attribute and its `…limited` switch (`auto`: limited when the range is given).
fn limited_range(
    a: &Attrs<'_>,
    name: &str,
    limited: &str,
) -> Result<Option<[f64; 2]>, MjcfReadError> {
    let r = a.nums(name, Some(2))?.map(|r| [r[0], r[1]]);
    let on = a.tristate(limited)?.unwrap_or(r.is_some());
    match (on, r) {
        (false, _) => Ok(None),
        (true, None) => Err(a.error(format!("`{limited}` but no `{name}`"))),
        (true, Some([lo, hi])) if lo >= hi => Err(a.error(format!(
            "attribute `{name}`: lower {lo} is not below upper {hi}"
        ))),
        (true, r) => Ok(r),
    }
}

/// The `<key>`s of the `<keyframe>` elements; `nq` and `nu` are the lengths of a full `qpos`
/// (7 + hinges) and `ctrl` (actuators).
pub(crate) fn keyframes(
    sections: &[&Elem],
    nq: usize,
    nu: usize,
) -> Result<Vec<Keyframe>, MjcfReadError> {
    let mut out = Vec::new();
    for section in sections {
        for k in &section.children {
            if k.tag != "key" {
                return Err(k.error("is not read in a <keyframe>"));
            }
            let a = Attrs::new(k, &[]);
            a.check_known(
                &["name", "qpos", "ctrl"],
                &["time", "qvel", "act", "mpos", "mquat"],
            )?;
            let qpos = a.nums("qpos", None)?.unwrap_or_default();
            let ctrl = a.nums("ctrl", None)?.unwrap_or_default();
            if !qpos.is_empty() && qpos.len() != nq {
                return Err(a.error(format!(
                    "attribute `qpos`: {} numbers, expected {nq} (7 for the free joint, one per hinge)",
                    qpos.len()
                )));
            }
            if !ctrl.is_empty() && ctrl.len() != nu {
                return Err(a.error(format!(
                    "attribute `ctrl`: {} numbers, expected {nu} (one per actuator)",
                    ctrl.len()
                )));
            }
            out.push(Keyframe {
                name: k
                    .get("name")
                    .map_or_else(|| format!("key{}", out.len()), str::to_owned),
                qpos,
                ctrl,
            });
        }
    }
    Ok(out)
}
