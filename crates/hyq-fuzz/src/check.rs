//! The checks a target's verdict must pass: a refusal is a good one-line message; an accepted
//! model or configuration keeps every quantity derived from it finite, and runs.

use std::sync::Arc;

use hyq_env::testing::ScriptedBackend;
use hyq_env::{ActionConfig, ActionMode, ActionSpace, Env, EnvConfig, Policy, RandomPolicy};
use hyq_physics::RobotModel;
use hyq_physics::na::{Isometry3, Point3};

/// The check's failure: what was wrong, in words.
pub type Verdict = Result<(), String>;

/// A refusal's message must be one non-empty line with no control character (a name echoed raw
/// could move the cursor or forge a line) and no number printed in full (hundreds of digits).
pub fn message(text: &str) -> Verdict {
    if text.trim().is_empty() {
        return Err("an empty error message".into());
    }
    if let Some(c) = text.chars().find(|c| c.is_control()) {
        return Err(format!(
            "the error message holds the control character {c:?}: {text:?}"
        ));
    }
    if text.chars().count() > 10_000 {
        return Err(format!(
            "an error message of {} characters",
            text.chars().count()
        ));
    }
    let digits = text
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0);
    if digits >= 30 {
        return Err(format!("a number printed with {digits} digits: {text}"));
    }
    Ok(())
}

/// `value` (named `what`) must be finite in f64 and in f32.
pub fn finite(what: &str, value: f64) -> Verdict {
    if value.is_finite() && (value as f32).is_finite() {
        Ok(())
    } else {
        Err(format!(
            "{what} = {value:e} is not finite (in f64, or in f32)"
        ))
    }
}

fn all_finite(what: &str, values: &[f64]) -> Verdict {
    values.iter().try_for_each(|v| finite(what, *v))
}

/// Every quantity derived from an accepted model: joints, bodies, the spawn state and its
/// kinematics, the observation bounds, every action mode's space and targets, the trot, the
/// exports and a rendered frame; then a few env steps in two action modes.
pub fn model(model: &Arc<RobotModel>) -> Verdict {
    for j in model.joints() {
        let name = &j.name;
        for (what, v) in [
            ("lower", j.lower),
            ("upper", j.upper),
            ("span", j.upper - j.lower),
            ("midpoint", 0.5 * (j.lower + j.upper)),
            ("effort", j.effort),
            ("velocity", j.velocity),
            ("damping", j.damping),
            ("friction", j.friction),
        ] {
            finite(&format!("joint {name} {what}"), v)?;
        }
    }
    for l in model.links() {
        finite(&format!("link {} mass", l.name), l.mass)?;
        if l.mass > 0.0 && (l.mass as f32) <= 0.0 {
            return Err(format!("link {} mass {:e} kg is 0 in f32", l.name, l.mass));
        }
        all_finite(&format!("link {} inertia", l.name), l.inertia.as_slice())?;
        all_finite(&format!("link {} centre of mass", l.name), l.com.as_slice())?;
    }
    finite("total mass", model.total_mass())?;
    kinematics(model)?;
    spaces(model)?;
    trot(model)?;
    exports(model)?;
    frame(model)?;
    for mode in [ActionMode::Normalized, ActionMode::Absolute] {
        let mut config = EnvConfig::default();
        config.action.mode = mode;
        runs(model.clone(), config)?;
    }
    Ok(())
}

fn kinematics(model: &RobotModel) -> Verdict {
    let spawn = model.spawn_state();
    all_finite(
        "spawn trunk position",
        spawn.trunk.pose.translation.vector.as_slice(),
    )?;
    all_finite("spawn joint angles", &spawn.q)?;
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&spawn.trunk.pose, &spawn.q, &mut poses)
        .map_err(|e| format!("forward kinematics at spawn: {e}"))?;
    for p in &poses {
        all_finite("a link position at spawn", p.translation.vector.as_slice())?;
    }
    all_finite(
        "centre of mass at spawn",
        model.centre_of_mass(&poses).as_slice(),
    )?;
    finite("lowest point at spawn", model.lowest_z(&poses))
}

/// The observation rows' bounds (finite in f32, min < max) and every action mode's space: its
/// bounds, float32 bounds rounded inward still ordered, and the joint targets of its corners,
/// middle and the standing pose finite and within the limits.
fn spaces(model: &RobotModel) -> Verdict {
    let layout = hyq_env::observation_layout_of(model)
        .map_err(|e| format!("the observation layout of an accepted model: {e}"))?;
    for r in layout.rows() {
        finite(&format!("observation row {} min", r.name), r.min)?;
        finite(&format!("observation row {} max", r.name), r.max)?;
        if !(r.min < r.max && (r.min as f32) < (r.max as f32)) {
            return Err(format!(
                "observation row {}: [{}, {}]",
                r.name, r.min, r.max
            ));
        }
    }
    let standing = model.standing_pose();
    for mode in [
        ActionMode::Normalized,
        ActionMode::Absolute,
        ActionMode::Delta,
        ActionMode::Offset,
    ] {
        let space = ActionSpace::new(
            model,
            &ActionConfig {
                mode,
                ..ActionConfig::default()
            },
        );
        let (low, high) = (space.low(), space.high());
        all_finite("action space low", low)?;
        all_finite("action space high", high)?;
        for (l, h) in low.iter().zip(high) {
            // The float32 Box rounds inward (see hyq-py's spaces): still low <= high.
            let (lo, hi) = (inward_up(*l), inward_down(*h));
            if !(l < h && lo <= hi) {
                return Err(format!(
                    "action space [{l}, {h}] ({mode:?}) in float32 [{lo}, {hi}]"
                ));
            }
        }
        let mid: Vec<f64> = low.iter().zip(high).map(|(l, h)| 0.5 * (l + h)).collect();
        let mut targets = vec![0.0; space.len()];
        for action in [low, high, &mid[..]] {
            space.targets(action, standing, &mut targets);
            all_finite(&format!("joint targets ({mode:?})"), &targets)?;
            for (t, j) in targets.iter().zip(model.joints()) {
                if !(j.lower..=j.upper).contains(t) {
                    return Err(format!(
                        "target {t} outside joint {} [{}, {}]",
                        j.name, j.lower, j.upper
                    ));
                }
            }
        }
        let mut action = vec![0.0; space.len()];
        space.action_for_targets(standing, standing, &mut action);
        all_finite(&format!("the standing action ({mode:?})"), &action)?;
    }
    Ok(())
}

/// The smallest f32 at or above `v`.
fn inward_up(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) < v { f.next_up() } else { f }
}

/// The largest f32 at or below `v`.
fn inward_down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v { f.next_down() } else { f }
}

fn trot(model: &RobotModel) -> Verdict {
    if model.gait().is_none() {
        return Ok(());
    }
    let mut trot = hyq_env::Trot::from_profile(model).map_err(|e| e.to_string())?;
    for t in [0.0, 0.013, 1.0, 1e3, 1e6] {
        all_finite(
            &format!("trot targets at {t} s"),
            trot.targets_at(t, model.standing_pose()),
        )?;
    }
    Ok(())
}

fn exports(model: &RobotModel) -> Verdict {
    let mjcf = hyq_formats::mjcf::to_mjcf(model, &hyq_formats::mjcf::MjcfOptions::default())
        .map_err(|e| format!("MJCF of an accepted model: {e}"))?;
    let urdf = hyq_formats::urdf::to_urdf(model, &Default::default())
        .map_err(|e| format!("URDF of an accepted model: {e}"))?;
    for (what, text) in [("MJCF", &mjcf.xml), ("URDF", &urdf)] {
        if text
            .split(|c: char| c == '"' || c.is_whitespace())
            .any(|w| matches!(w.to_ascii_lowercase().as_str(), "nan" | "inf" | "-inf"))
        {
            return Err(format!("the {what} export holds a non-finite number"));
        }
    }
    Ok(())
}

fn frame(model: &Arc<RobotModel>) -> Verdict {
    let config = hyq_render::RenderConfig {
        width: 64,
        height: 48,
        ..hyq_render::RenderConfig::default()
    };
    let mut renderer =
        hyq_render::Renderer::new(model.clone(), config).map_err(|e| format!("renderer: {e}"))?;
    let spawn = model.spawn_state();
    let contacts = vec![true; model.tracked().len()];
    let scene = hyq_render::Scene::new(
        hyq_render::RobotPose::Joints {
            trunk: &spawn.trunk.pose,
            q: &spawn.q,
        },
        &contacts,
    )
    .with_goal(Point3::new(5.0, 0.0, model.standing_height()));
    renderer
        .render(&scene)
        .map(|_| ())
        .map_err(|e| format!("rendering the spawn pose: {e}"))
}

/// An env of `model` under `config` on the scripted backend: building it may be refused (with
/// a good message), but once built, reset must succeed and a few random steps must emit only
/// finite numbers without diverging (the scripted backend has no physics to diverge).
pub fn runs(model: Arc<RobotModel>, config: EnvConfig) -> Verdict {
    let mut env = match Env::<ScriptedBackend>::new(model, config) {
        Ok(env) => env,
        Err(e) => return message(&e.to_string()),
    };
    env.reset(Some(1), &Default::default())
        .map_err(|e| format!("reset fails after the configuration was accepted: {e}"))?;
    let mut policy = RandomPolicy::new(1);
    let mut action = vec![0.0; env.action_space().len()];
    for _ in 0..4 {
        policy.act(&env.policy_input(), &mut action);
        let step = env
            .step(&action)
            .map_err(|e| format!("a step of an action in the space fails: {e}"))?;
        all_finite("observation", step.observation)?;
        finite("reward", step.reward)?;
        all_finite("joint targets", &step.info.joint_targets)?;
        finite("D_n", step.info.d_n)?;
        if let Some(d) = &step.info.divergence {
            return Err(format!("diverged on the scripted backend: {d}"));
        }
        if step.terminated || step.truncated {
            break;
        }
    }
    Ok(())
}
