//! The drafted profile written as TOML a user reads: every part under a comment saying where
//! its values came from, every foot and joint on its own line with a note beside it.

use std::fmt::Write as _;

use hyq_physics::Profile;

use super::legs::Legs;
use super::types::{DEFAULT_VELOCITY, Notes, Source, TROT};

/// The most MJCF reader's notes listed in the comment on the robot file.
const MAX_NOTES: usize = 12;

/// The width comments are folded to.
const WIDTH: usize = 96;

/// `name` with every character a profile name does not allow replaced by `_`, at most 64.
pub(crate) fn clean_name(name: &str) -> String {
    name.chars()
        .take(64)
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `name` if a profile allows it as it is, else `fallback`.
pub(crate) fn name_or(name: &str, fallback: &str) -> String {
    match hyq_physics::bounds::check_name(name) {
        Ok(_) => name.to_owned(),
        Err(_) => fallback.to_owned(),
    }
}

/// Fills the comments that depend on the whole draft: the header, the robot file, the trunk,
/// the feet, the joints and the gains.
pub(crate) fn describe(
    source: &Source,
    origin: &str,
    standing: &str,
    legs: &Legs,
    gains: &str,
    notes: &mut Notes,
) {
    let file = hyq_physics::printable(origin);
    let format = source.format();
    notes.header = vec![format!(
        "Robot profile drafted by `hyq robot init` from {file} ({format}). Every value says \
             where it came from: check each, edit what is wrong, then try it with `hyq run \
             --robot THIS_FILE.toml`. docs/adding-a-robot.md explains every key. Units: SI, \
             radians."
    )];
    let skipped = match source {
        Source::Mjcf(m) if !m.notes.is_empty() => {
            let shown: Vec<&str> = m.notes.iter().take(MAX_NOTES).map(String::as_str).collect();
            let more = m.notes.len().saturating_sub(MAX_NOTES);
            let more = if more > 0 {
                format!("; and {more} more")
            } else {
                String::new()
            };
            format!(" The MJCF reader left out: {}{more}.", shown.join("; "))
        }
        _ => String::new(),
    };
    notes.robot_file = format!(
        "The robot file, relative to this profile ({} for a .xml file, URDF otherwise).{skipped}",
        "MJCF"
    );
    notes.trunk = match source {
        Source::Mjcf(_) => "The root body, whose <freejoint> makes it free: the trunk.".to_owned(),
        Source::Urdf(_) => "The URDF's root link (no joint's child): the free trunk.".to_owned(),
    };
    notes.feet = format!(
        "Tracked feet, in observation order: each leaf body (after fixed links are lumped into \
         their parents) ends a leg, and its foot is the shape named beside it. Names: {}.",
        if legs.named {
            format!("lf, lh, rf, rh ({})", legs.why)
        } else {
            format!(
                "the file's link names ({}; no project names inferred)",
                legs.why
            )
        }
    );
    let order = if legs.named {
        "Actuated joints in leg-major order (lf, lh, rf, rh; each haa, hfe, kfe: abduction, hip \
         flexion, knee flexion along each leg from the trunk), named as the feet are."
    } else {
        "Actuated joints in the file's order with the file's names (the project's leg names \
         could not be inferred; see the feet)."
    };
    let limits = match source {
        Source::Urdf(_) => "lower, upper and velocity are the URDF's, written out to edit (a \
             URDF's placeholder range, e.g. several turns, is better replaced by the real one)."
            .to_owned(),
        Source::Mjcf(_) => format!(
            "lower and upper are the MJCF's ranges; MJCF has no velocity limit, so velocity is a \
             default, {DEFAULT_VELOCITY} rad/s: replace it with the robot's figure."
        ),
    };
    notes.joints =
        format!("{order} {standing} {limits} The note beside each names its joint in the file.");
    notes.gains = format!(
        "Default joint PD gains for tau = kp (q* - q) - kd qdot, clamped to the effort limit. {gains}"
    );
    notes.gait = if legs.named {
        format!(
            "The scripted trot (hyq-env's `Trot`): diagonal pairs lf + rh (phase 0) and rf + lh \
             (phase 0.5) alternate; each hip (hfe) swings about its standing angle and each knee \
             (kfe) flexes during its swing. {} Hz, {} rad, {} rad, {} s ramp are ANYmal C's tuned \
             figures, a start, not tuned for this robot: try `hyq run` and adjust.",
            TROT[0], TROT[1], TROT[2], TROT[3]
        )
    } else {
        "No [gait]: the legs were not named, so no trot was drafted (the trot policy refuses \
         this robot until one is written)."
            .to_owned()
    };
}

/// The profile as commented TOML.
pub(crate) fn write(p: &Profile, n: &Notes) -> String {
    let mut out = String::new();
    for h in &n.header {
        comment(&mut out, h);
    }
    out.push('\n');
    comment(
        &mut out,
        "Name of the robot, used in messages: the file's own, or its file name.",
    );
    let _ = writeln!(out, "name = {}", q(&p.name));
    comment(&mut out, &n.robot_file);
    let _ = writeln!(out, "urdf = {}", q(&p.urdf));
    comment(&mut out, &n.trunk);
    let _ = writeln!(out, "trunk = {}\n", q(&p.trunk));
    comment(&mut out, &n.feet);
    out.push_str("feet = [\n");
    for (f, note) in p.feet.iter().zip(&n.foot) {
        let collision = f
            .collision
            .as_ref()
            .map_or(String::new(), |c| format!(", collision = {}", q(c)));
        let _ = writeln!(
            out,
            "    {{ name = {}, link = {}{collision} }},  # {}",
            q(&f.name),
            q(&f.link),
            line(note)
        );
    }
    out.push_str("]\n\n");
    joints(&mut out, p, n);
    out.push_str("[spawn]\n");
    comment(&mut out, &n.spawn_height);
    let _ = writeln!(out, "height = {}", num(p.spawn.height));
    comment(&mut out, &n.standing_height);
    match p.spawn.standing_height {
        Some(h) => {
            let _ = writeln!(out, "standing_height = {}", num(h));
        }
        None => out.push_str("# standing_height = (measure it: `hyq robot init` does on rapier)\n"),
    }
    out.push_str("\n[gains]\n");
    comment(&mut out, &n.gains);
    let _ = writeln!(out, "kp = {}\nkd = {}", num(p.gains.kp), num(p.gains.kd));
    out.push('\n');
    gait(&mut out, p, n);
    out
}

/// The `joints` array, each entry with its note.
fn joints(out: &mut String, p: &Profile, n: &Notes) {
    comment(out, &n.joints);
    out.push_str("joints = [\n");
    for (j, note) in p.joints.iter().zip(&n.joint) {
        let mut entry = format!(
            "name = {}, urdf = {}, standing = {}",
            q(&j.name),
            q(&j.urdf),
            num(j.standing)
        );
        for (key, v) in [
            ("lower", j.lower),
            ("upper", j.upper),
            ("velocity", j.velocity),
            ("kp", j.kp),
            ("kd", j.kd),
        ] {
            if let Some(v) = v {
                let _ = write!(entry, ", {key} = {}", num(v));
            }
        }
        let _ = writeln!(out, "    {{ {entry} }},  # {}", line(note));
    }
    out.push_str("]\n\n");
}

/// The `[gait]` table, or the comment saying why there is none.
fn gait(out: &mut String, p: &Profile, n: &Notes) {
    match &p.gait {
        Some(g) => {
            out.push_str("[gait]\n");
            comment(out, &n.gait);
            let _ = writeln!(
                out,
                "frequency_hz = {}\nhip_amplitude = {}\nknee_lift = {}\nramp_s = {}\nlegs = [",
                num(g.frequency_hz),
                num(g.hip_amplitude),
                num(g.knee_lift),
                num(g.ramp_s)
            );
            for l in &g.legs {
                let _ = writeln!(
                    out,
                    "    {{ hip = {}, knee = {}, phase = {} }},",
                    q(&l.hip),
                    q(&l.knee),
                    num(l.phase)
                );
            }
            out.push_str("]\n");
        }
        None => comment(out, &n.gait),
    }
}

/// A TOML string, quoted and escaped.
fn q(s: &str) -> String {
    toml::Value::String(s.to_owned()).to_string()
}

/// A TOML float in Rust's shortest round-trip form, always with a point or exponent.
fn num(v: f64) -> String {
    format!("{v:?}")
}

/// `text` on one line, anything unprintable escaped.
fn line(text: &str) -> String {
    hyq_physics::printable(&hyq_physics::one_line(text))
}

/// `text` as `# ` comment lines folded at [`WIDTH`].
fn comment(out: &mut String, text: &str) {
    let mut current = String::from("#");
    for word in line(text).split_whitespace() {
        if current.len() + 1 + word.len() > WIDTH && current.len() > 1 {
            out.push_str(&current);
            out.push('\n');
            current = String::from("#");
        }
        current.push(' ');
        current.push_str(word);
    }
    out.push_str(&current);
    out.push('\n');
}
