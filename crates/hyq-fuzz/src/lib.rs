//! Fuzzing every loader of a user's file: the configuration (TOML and `--set` overrides), the
//! robot profile, the URDF, the trained policy (safetensors), the step records `hyq plot` reads,
//! the comparison ledger and a terrain's height file (`.npy` or PNG).
//!
//! Each [`Target`] takes its seed files (the bundled and committed ones), mutates them
//! ([`mutate`]: awkward numbers, odd strings, deleted, repeated and deeply nested parts, cut
//! files), feeds each input to the loader through the same path a user's file takes (a file on
//! disk, read by the capped reader), and checks the verdict ([`check`]):
//!
//! - no panic (caught and reported with the input), no abort (the process would die: the run
//!   prints its seed first, so `hyq-fuzz --seed S --cases N TARGET` replays it), no hang (a
//!   watchdog ends the process, naming the input, when one case runs past [`HANG_LIMIT`]);
//! - a refusal is one line, non-empty, with no control character;
//! - an accepted input gives a model, configuration, policy, plot or ledger whose every derived
//!   quantity is finite: joint spans, midpoints and targets in every action mode, observation
//!   bounds in f32, masses and inertias in f32, the trot's targets, the spawn state, the MJCF
//!   and URDF exports, a rendered frame, and a few env steps on the scripted backend (reset
//!   must succeed: a configuration the loader accepted must run).
//!
//! Inputs that ever failed are kept in `corpus/<target>/` and replayed by the crate's tests;
//! `cargo xtask fuzz` runs the targets for as long as asked.

pub mod check;
pub mod mutate;
pub mod targets;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

pub use targets::Target;

/// The longest one input may take before the run counts it as a hang: far beyond any loader's
/// time on the largest accepted file (a debug build loads a 1000-link URDF in well under a
/// second).
pub const HANG_LIMIT: Duration = Duration::from_secs(60);

/// What a case's input did wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Finding {
    /// The target.
    pub target: &'static str,
    /// What went wrong (a panic's message, a bad error message, a non-finite quantity).
    pub what: String,
    /// The input.
    pub input: Vec<u8>,
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {} ({} bytes of input)",
            self.target,
            self.what,
            self.input.len()
        )
    }
}

/// What a run did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Inputs tried.
    pub cases: u64,
    /// Of those, the ones the loader accepted (the rest it refused with a good message).
    pub accepted: u64,
}

/// Checks one input against `target` (see the crate docs), catching a panic as a finding.
/// `scratch` is a directory the target may write its files in.
pub fn run_case(target: Target, input: &[u8], scratch: &Path) -> Result<bool, Finding> {
    let finding = |what: String| Finding {
        target: target.name(),
        what,
        input: input.to_vec(),
    };
    match catch_unwind(AssertUnwindSafe(|| target.check(input, scratch))) {
        Ok(Ok(accepted)) => Ok(accepted),
        Ok(Err(what)) => Err(finding(what)),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic".into());
            Err(finding(format!("panicked: {message}")))
        }
    }
}

/// A watchdog over the cases of one run: if a case runs past [`HANG_LIMIT`], it saves the
/// input to `hang_file` and ends the process, naming the file.
struct Watchdog {
    origin: Instant,
    /// Milliseconds since `origin` at which the current case began; `u64::MAX` between cases.
    began_ms: Arc<AtomicU64>,
    input: Arc<Mutex<Vec<u8>>>,
    stop: Arc<AtomicBool>,
}

impl Watchdog {
    fn start(target: &'static str, hang_file: PathBuf) -> Self {
        let origin = Instant::now();
        let began_ms = Arc::new(AtomicU64::new(u64::MAX));
        let input = Arc::new(Mutex::new(Vec::new()));
        let stop = Arc::new(AtomicBool::new(false));
        let (began, bytes, stopped) = (began_ms.clone(), input.clone(), stop.clone());
        std::thread::spawn(move || {
            while !stopped.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(200));
                let at = began.load(Ordering::Relaxed);
                let now = origin.elapsed().as_millis() as u64;
                if at != u64::MAX && now.saturating_sub(at) > HANG_LIMIT.as_millis() as u64 {
                    let input = bytes.lock().map(|b| b.clone()).unwrap_or_default();
                    let _ = std::fs::write(&hang_file, input);
                    eprintln!(
                        "hyq-fuzz: {target}: one input ran for more than {HANG_LIMIT:?}: a hang; \
                         the input is in {}",
                        hang_file.display()
                    );
                    std::process::exit(3);
                }
            }
        });
        Self {
            origin,
            began_ms,
            input,
            stop,
        }
    }

    /// A case with `input` begins.
    fn begin(&self, input: &[u8]) {
        if let Ok(mut slot) = self.input.lock() {
            slot.clear();
            slot.extend_from_slice(input);
        }
        let now = self.origin.elapsed().as_millis() as u64;
        self.began_ms.store(now, Ordering::Relaxed);
    }

    /// The case has ended.
    fn end(&self) {
        self.began_ms.store(u64::MAX, Ordering::Relaxed);
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

/// How a run chooses its inputs and when it stops.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The seed of the mutation streams (case `k` uses stream `k`).
    pub seed: u64,
    /// At most this many cases.
    pub cases: u64,
    /// And no longer than this.
    pub time: Option<Duration>,
}

/// Runs `plan` on `target`: the seed files first, then a FIFO in the file's place, then mutated
/// ones. Returns the tally, or the first finding.
pub fn run(target: Target, plan: &Plan, scratch: &Path) -> Result<Tally, Finding> {
    let seeds = target.seeds();
    let origin = Instant::now();
    let watchdog = Watchdog::start(
        target.name(),
        scratch.join(format!("{}.hang", target.name())),
    );
    let mut tally = Tally::default();
    for case in 0..plan.cases {
        if plan.time.is_some_and(|t| origin.elapsed() >= t) {
            break;
        }
        let input = match (case as usize).cmp(&seeds.len()) {
            std::cmp::Ordering::Less => seeds[case as usize].clone(),
            // Once a run, after the seeds: a FIFO no one writes to where the loader looks for
            // its file, which every loader must refuse at once (it used to block them forever).
            std::cmp::Ordering::Equal => targets::FIFO_INPUT.to_vec(),
            std::cmp::Ordering::Greater => {
                let mut rng = mutate::case_rng(plan.seed, case);
                let seed = &seeds[(case as usize) % seeds.len()];
                target.mutate(seed, &mut rng)
            }
        };
        watchdog.begin(&input);
        let accepted = run_case(target, &input, scratch)?;
        watchdog.end();
        tally.cases += 1;
        tally.accepted += u64::from(accepted);
    }
    Ok(tally)
}

/// The corpus directory of `target` (`corpus/<name>/` in this crate).
pub fn corpus_dir(target: Target) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target.name())
}

/// The inputs kept in `target`'s corpus, with their file names, sorted by name.
pub fn corpus(target: Target) -> std::io::Result<Vec<(String, Vec<u8>)>> {
    let dir = corpus_dir(target);
    let mut out = Vec::new();
    if !dir.is_dir() {
        return Ok(out);
    }
    for entry in std::fs::read_dir(&dir)? {
        let entry = entry?;
        if entry.file_type()?.is_file() {
            let name = entry.file_name().to_string_lossy().into_owned();
            out.push((name, std::fs::read(entry.path())?));
        }
    }
    out.sort();
    Ok(out)
}
