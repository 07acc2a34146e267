//! The loaders fuzzed, each fed through the path a user's file takes: written to disk and read
//! by the loader's own capped reader.

use std::io::Cursor;
use std::path::Path;

use hyq_env::{EnvConfig, MlpPolicy};
use hyq_formats::robots::{GO1_MJCF, GO1_PROFILE};
use hyq_physics::bundled::{ANYMAL_C_PROFILE, ANYMAL_C_URDF, HYQ_PROFILE, HYQ_URDF};
use rand_chacha::ChaCha8Rng;

use crate::check;
use crate::mutate::{self, Syntax};

/// A loader of user files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// `--config FILE` (TOML) and `--set KEY=VALUE` overrides (an input starting `#set`).
    Config,
    /// A robot profile (TOML), beside the bundled URDF it names.
    Profile,
    /// A URDF, beside the bundled profile of its robot.
    Urdf,
    /// An MJCF file, beside the bundled Go1's profile (which names it).
    Mjcf,
    /// A robot file (MJCF when it holds `<mujoco`, else URDF) drafted into a profile by
    /// `hyq robot init`; an MJCF one also resolved alone (`--robot ROBOT.xml`).
    Draft,
    /// A trained policy (`--policy mlp:FILE`, safetensors).
    Policy,
    /// Step records (JSON lines) that `hyq plot` reads and plots.
    Records,
    /// A comparison ledger (`hyq compare --ledger FILE`, TOML).
    Ledger,
    /// A terrain's height file (`terrain.file`, NumPy `.npy` or PNG).
    Heights,
}

/// A record of six steps from `hyq run`, the records target's seed.
const RECORD_SEED: &str = include_str!("../seeds/run.jsonl");

/// The committed trained policy, the policy target's seed.
const POLICY_SEED: &[u8] = include_bytes!("../../../assets/policies/hyq_walk.safetensors");

/// The built-in ledger, the ledger target's seed.
const LEDGER_SEED: &str = include_str!("../../hyq-compare/ledger.toml");

/// Height files, the heights target's seeds: float64 in C order, big-endian int16 in Fortran
/// order, 8- and 16-bit grayscale PNGs.
const HEIGHT_SEEDS: [&[u8]; 4] = [
    include_bytes!("../seeds/heights.npy"),
    include_bytes!("../seeds/heights_i2.npy"),
    include_bytes!("../seeds/heights.png"),
    include_bytes!("../seeds/heights16.png"),
];

/// A configuration setting a key of every table, the config target's seed.
const CONFIG_SEED: &str = include_str!("../seeds/config.toml");

/// `--set` overrides (one `KEY=VALUE` a line after `#set`), the config target's other seed.
const SET_SEED: &str = "#set\ntask.max_time_steps=5\nreset.spawn_xy_m=[1.5, -2]\n\
                        goal.mode=fixed\ngoal.position=[4, 1, 0.6]\naction.mode=offset\n";

impl Target {
    /// Every target, in the order the runs take them.
    pub const ALL: [Target; 9] = [
        Target::Config,
        Target::Profile,
        Target::Urdf,
        Target::Mjcf,
        Target::Draft,
        Target::Policy,
        Target::Records,
        Target::Ledger,
        Target::Heights,
    ];

    /// The target's name (`cargo xtask fuzz NAME`, `corpus/NAME/`).
    pub fn name(self) -> &'static str {
        match self {
            Target::Config => "config",
            Target::Profile => "profile",
            Target::Urdf => "urdf",
            Target::Mjcf => "mjcf",
            Target::Draft => "draft",
            Target::Policy => "policy",
            Target::Records => "records",
            Target::Ledger => "ledger",
            Target::Heights => "heights",
        }
    }

    /// The target named `name`, if any.
    pub fn by_name(name: &str) -> Option<Target> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// The valid files mutations start from.
    pub fn seeds(self) -> Vec<Vec<u8>> {
        let text = |s: &[&str]| s.iter().map(|t| t.as_bytes().to_vec()).collect();
        match self {
            Target::Config => text(&[CONFIG_SEED, SET_SEED, ""]),
            Target::Profile => text(&[HYQ_PROFILE, ANYMAL_C_PROFILE]),
            Target::Urdf => text(&[HYQ_URDF, ANYMAL_C_URDF]),
            Target::Mjcf => text(&[GO1_MJCF]),
            Target::Draft => text(&[GO1_MJCF, HYQ_URDF, ANYMAL_C_URDF]),
            Target::Policy => vec![POLICY_SEED.to_vec()],
            Target::Records => text(&[RECORD_SEED]),
            Target::Ledger => text(&[LEDGER_SEED]),
            Target::Heights => HEIGHT_SEEDS.iter().map(|s| s.to_vec()).collect(),
        }
    }

    /// A mutation of `seed` (see [`mutate`]).
    pub fn mutate(self, seed: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
        let text = String::from_utf8_lossy(seed);
        match self {
            Target::Config | Target::Profile | Target::Ledger => {
                mutate::mutate_text(&text, Syntax::Toml, rng)
            }
            Target::Urdf | Target::Mjcf | Target::Draft => {
                mutate::mutate_text(&text, Syntax::Xml, rng)
            }
            Target::Records => mutate::mutate_text(&text, Syntax::Jsonl, rng),
            Target::Policy => mutate::mutate_safetensors(seed, rng),
            Target::Heights => mutate::mutate_height_file(seed, rng),
        }
    }

    /// Feeds `input` to the loader and checks the verdict; `Ok(true)` if it was accepted,
    /// `Ok(false)` if refused with a good message, `Err` with what was wrong otherwise.
    pub fn check(self, input: &[u8], scratch: &Path) -> Result<bool, String> {
        match self {
            Target::Config => config(input, scratch),
            Target::Profile => robot(input, None, scratch),
            Target::Urdf => robot(HYQ_PROFILE.as_bytes(), Some(input), scratch),
            Target::Mjcf => mjcf(input, scratch),
            Target::Draft => draft(input, scratch),
            Target::Policy => policy(input, scratch),
            Target::Records => records(input, scratch),
            Target::Ledger => ledger(input, scratch),
            Target::Heights => heights(input, scratch),
        }
    }
}

/// An input that stands for a FIFO: the target puts a FIFO that no one writes to where its
/// loader looks for the file, and the loader must refuse it at once (opening one used to block
/// every loader but the height file's forever; a case still waiting after [`crate::HANG_LIMIT`]
/// is a hang). The corpus holds one for each target.
pub const FIFO_INPUT: &[u8] = b"#fifo\n";

/// A refusal: `Ok(false)` if its message is a good one.
fn refused(message: &str) -> Result<bool, String> {
    check::message(message).map(|()| false)
}

/// Writes `bytes` at `path`, or makes a FIFO there for [`FIFO_INPUT`]. The path is cleared
/// first: writing into a FIFO an earlier case left would wait for a reader.
fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let _ = std::fs::remove_file(path);
    if bytes == FIFO_INPUT {
        let made = std::process::Command::new("mkfifo")
            .arg(path)
            .status()
            .map_err(|e| format!("cannot run mkfifo: {e}"))?;
        return if made.success() {
            Ok(())
        } else {
            Err(format!("mkfifo {} failed", path.display()))
        };
    }
    std::fs::write(path, bytes).map_err(|e| format!("scratch file {}: {e}", path.display()))
}

/// Why an accepted policy file is unsound, if it holds a value that is not finite in a float
/// tensor: the reader must refuse every such file (a NaN weight makes every action NaN).
fn non_finite_tensor(input: &[u8]) -> Option<String> {
    let tensors = safetensors::SafeTensors::deserialize(input).ok()?;
    for (name, view) in tensors.tensors() {
        let data = view.data();
        let bad = match view.dtype() {
            safetensors::Dtype::F32 => data
                .chunks_exact(4)
                .any(|c| !f32::from_le_bytes([c[0], c[1], c[2], c[3]]).is_finite()),
            safetensors::Dtype::F64 => data.chunks_exact(8).any(|c| {
                !f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]).is_finite()
            }),
            _ => false,
        };
        if bad {
            return Some(format!(
                "an accepted policy's tensor `{name}` holds a non-finite value"
            ));
        }
    }
    None
}

fn config(input: &[u8], scratch: &Path) -> Result<bool, String> {
    let loaded = match input.strip_prefix(b"#set\n") {
        Some(rest) => {
            let text = String::from_utf8_lossy(rest);
            let pairs: Vec<(String, String)> = text
                .lines()
                .filter(|l| !l.is_empty())
                .map(|l| match l.split_once('=') {
                    Some((k, v)) => (k.to_owned(), v.to_owned()),
                    None => (l.to_owned(), String::new()),
                })
                .collect();
            EnvConfig::load(None, &pairs)
        }
        None => {
            let path = scratch.join("config.toml");
            write(&path, input)?;
            EnvConfig::load(Some(&path), &[] as &[(&str, &str)])
        }
    };
    match loaded {
        Err(e) => refused(&e.to_string()),
        Ok(config) => check::runs(hyq_physics::bundled::hyq(), config).map(|()| true),
    }
}

/// A robot from its profile (`profile`) and URDF (`urdf`, else the bundled one the profile
/// names) written to `scratch`.
fn robot(profile: &[u8], urdf: Option<&[u8]>, scratch: &Path) -> Result<bool, String> {
    // Both bundled URDFs sit beside the profile under their own names, so a mutated profile
    // of either robot finds its own; a fuzzed URDF replaces HyQ's.
    write(&scratch.join("anymal_c.urdf"), ANYMAL_C_URDF.as_bytes())?;
    write(
        &scratch.join("hyq.urdf"),
        urdf.unwrap_or(HYQ_URDF.as_bytes()),
    )?;
    let profile = match urdf {
        // A fuzzed ANYmal C URDF goes with ANYmal C's profile (its joints are upper case).
        Some(u) if u.windows(6).any(|w| w == b"LF_HAA") => ANYMAL_C_PROFILE
            .replace("anymal_c.urdf", "hyq.urdf")
            .into_bytes(),
        _ => profile.to_vec(),
    };
    let path = scratch.join("profile.toml");
    write(&path, &profile)?;
    match hyq_physics::resolve_robot(path.to_str().unwrap_or("profile.toml")) {
        Err(e) => refused(&e.to_string()),
        Ok(model) => check::model(&model).map(|()| true),
    }
}

/// A robot from an MJCF file written as `go1.xml` beside the bundled Go1's profile, resolved
/// as a front end resolves `--robot PROFILE` (an `<include>` of itself is a cycle).
fn mjcf(input: &[u8], scratch: &Path) -> Result<bool, String> {
    write(&scratch.join("go1.xml"), input)?;
    let path = scratch.join("go1_profile.toml");
    write(&path, GO1_PROFILE.as_bytes())?;
    match hyq_formats::robots::resolve(path.to_str().unwrap_or("go1_profile.toml")) {
        Err(e) => refused(&e.to_string()),
        Ok(model) => check::model(&model).map(|()| true),
    }
}

/// A robot file drafted into a profile as `hyq robot init` drafts it: accepted, the written
/// TOML must read back as the drafted profile and its model pass the model checks; an MJCF
/// file is also resolved alone, as `--robot ROBOT.xml` (without the settle run).
fn draft(input: &[u8], scratch: &Path) -> Result<bool, String> {
    let is_mjcf = input.windows(7).any(|w| w == b"<mujoco");
    let path = scratch.join(if is_mjcf { "robot.xml" } else { "robot.urdf" });
    write(&path, input)?;
    if is_mjcf && let Err(e) = hyq_formats::robots::resolve(path.to_str().unwrap_or("robot.xml")) {
        check::message(&e.to_string())?;
    }
    let drafted = match hyq_formats::draft::draft_file(&path, None, "robot") {
        Err(e) => return refused(&e.to_string()),
        Ok(d) => d,
    };
    let text = drafted.to_toml();
    let back = hyq_physics::Profile::from_toml_str(&text, "draft")
        .map_err(|e| format!("the drafted profile does not read back: {e}"))?;
    if &back != drafted.profile() {
        return Err("the drafted profile reads back as another profile".to_owned());
    }
    let model = drafted
        .model()
        .map_err(|e| format!("the drafted profile does not load: {e}"))?;
    check::model(&std::sync::Arc::new(model)).map(|()| true)
}

fn policy(input: &[u8], scratch: &Path) -> Result<bool, String> {
    let path = scratch.join("policy.safetensors");
    write(&path, input)?;
    let mut policy = match MlpPolicy::from_file(&path) {
        Err(e) => return refused(&e.to_string()),
        Ok(p) => p,
    };
    if let Some(unsound) = non_finite_tensor(input) {
        return Err(unsound);
    }
    let widths = policy.widths();
    let (inputs, outputs) = (widths[0], widths[widths.len() - 1]);
    let mut action = vec![0.0; outputs];
    // Observations at the spec's table bounds (HyQ's, the policy's robot) and zeros.
    let layout =
        hyq_env::observation_layout_of(&hyq_physics::bundled::hyq()).map_err(|e| e.to_string())?;
    let rows = layout.rows();
    for pick in [
        |_: f64, _: f64| 0.0,
        |lo: f64, _: f64| lo,
        |_: f64, hi: f64| hi,
    ] {
        let obs: Vec<f64> = (0..inputs)
            .map(|i| rows.get(i).map_or(0.0, |r| pick(r.min, r.max)))
            .collect();
        policy.forward(&obs, &mut action);
        if let Some(a) = action.iter().find(|a| !a.is_finite()) {
            return Err(format!(
                "an accepted policy's action is {a} for a finite observation"
            ));
        }
    }
    Ok(true)
}

fn records(input: &[u8], scratch: &Path) -> Result<bool, String> {
    let parsed = if input == FIFO_INPUT {
        // Through the file reader `hyq plot` uses, which must refuse the FIFO.
        let path = scratch.join("records.jsonl");
        write(&path, input)?;
        hyq_render::read_jsonl(&path)
    } else {
        hyq_render::parse_jsonl(Cursor::new(input), "fuzz.jsonl")
    };
    let read = match parsed {
        Err(e) => return refused(&e.to_string()),
        Ok(r) => r,
    };
    let episodes = hyq_render::split_episodes(&read.records);
    // Two episodes at most: each is two PNGs, and the plotting code is the same for every one.
    for (i, episode) in episodes.iter().take(2).enumerate() {
        let series = hyq_render::EpisodeSeries::from_records(episode);
        let options = hyq_render::PlotOptions {
            k_exp: Some(5.0),
            ..hyq_render::PlotOptions::default()
        };
        if let Err(e) =
            hyq_render::plot_episode(&series, &options, scratch.join("plots"), &format!("e{i}"))
        {
            return refused(&e.to_string());
        }
    }
    Ok(!episodes.is_empty())
}

fn ledger(input: &[u8], scratch: &Path) -> Result<bool, String> {
    let path = scratch.join("ledger.toml");
    write(&path, input)?;
    match hyq_compare::Ledger::from_file(&path) {
        Err(e) => refused(&e.to_string()),
        Ok(_) => Ok(true),
    }
}

/// A height file read as `terrain.file` (named `.png` when it starts as a PNG does, `.npy`
/// otherwise), laid over 4 × 3 m: refused in one line, or a grid of finite heights on which an
/// environment is built (or refused in one line, if the robot cannot be put down on it) and
/// runs.
fn heights(input: &[u8], scratch: &Path) -> Result<bool, String> {
    let extension = if input.starts_with(b"\x89PNG") {
        "png"
    } else {
        "npy"
    };
    let path = scratch.join(format!("heights.{extension}"));
    write(&path, input)?;
    let placement = hyq_physics::terrain::file::Placement {
        center: [0.0, 0.0],
        size: [4.0, 3.0],
        vertical_scale: 1.0,
    };
    let grid = match hyq_physics::terrain::file::read(&path, &placement) {
        Err(e) => return refused(&e.to_string()),
        Ok(grid) => grid,
    };
    for h in grid.heights() {
        check::finite("a height", *h)?;
    }
    for (x, y) in [(0.0, 0.0), (-2.0, -1.5), (2.0, 1.5), (0.3, -0.7)] {
        check::finite("the surface's height", grid.height_at(x, y))?;
    }
    let mut config = EnvConfig::default();
    let file = format!("{:?}", path.display().to_string());
    let set = [
        ("terrain.kind", "\"heightfield\""),
        ("terrain.file", file.as_str()),
        ("terrain.size_m", "[4.0, 3.0]"),
        // The goal on the field: a field not under the goal is refused.
        ("goal.distance_m", "1.5"),
        ("task.max_time_steps", "5"),
    ];
    if let Err(e) = config.set_all(&set) {
        return Err(format!(
            "the heights target's own configuration is refused: {e}"
        ));
    }
    check::runs(hyq_physics::bundled::hyq(), config).map(|()| true)
}
