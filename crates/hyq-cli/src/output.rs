//! What the subcommands write besides their tables: text and JSON lines on stdout, warnings and
//! the progress bar on stderr, and output files that replace their target only when complete.
//!
//! stdout: a closed pipe (`hyq run | head -1`: the reader has gone) ends the command quietly
//! with status 0, as ripgrep does ([`Failure::closed_stdout`]); any other write failure (a full
//! disk, `> /dev/full`) is a one-line error.
//!
//! Files ([`OutputFile`], [`StagedDir`]): written to a hidden temporary file or directory beside
//! the target and renamed onto it when the command has finished, so that a usage error, a
//! failure or an interrupted run leaves the target as it was. A target that exists and is not a
//! regular file (a device such as `/dev/full`, a FIFO) is written in place instead, and never
//! replaced. A regular file the user could not write (write-protected) is refused, as the
//! shell's `>` refuses it, rather than replaced by the rename.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;

use crate::Failure;

/// A failed write to stdout as the command's failure: quiet for a closed pipe.
fn stdout_failure(e: &io::Error) -> Failure {
    if e.kind() == io::ErrorKind::BrokenPipe {
        Failure::closed_stdout()
    } else {
        Failure {
            status: 1,
            message: format!("cannot write to stdout: {e}"),
        }
    }
}

/// Prints `text` on stdout as it is, and flushes it.
pub fn print(text: &str) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| stdout_failure(&e))
}

/// Prints `text` and a newline on stdout.
pub fn print_line(text: &str) -> Result<(), Failure> {
    print(&format!("{text}\n"))
}

/// Prints `value` as one line of JSON on stdout; `what` names it in the (unreachable) failure.
pub fn print_json_line(value: &impl Serialize, what: &str) -> Result<(), Failure> {
    match serde_json::to_string(value) {
        Ok(line) => print_line(&line),
        // Every report and summary is made of finite numbers (the environment never emits NaN,
        // and its bounds keep every sum finite), strings, booleans and lists and objects of
        // those, all of which JSON holds.
        Err(e) => Err(Failure {
            status: 1,
            message: format!("{what} cannot be written as JSON: {e}"),
        }),
    }
}

/// Prints `message` as one warning line on stderr, `hyq: warning: …` (nothing if stderr is
/// closed: a warning must not stop a command).
pub fn warn(message: &str) {
    let _ = writeln!(io::stderr().lock(), "hyq: warning: {message}");
}

/// A progress bar of `total` env steps.
pub fn progress_bar(total: u64) -> ProgressBar {
    // Drawn on stderr only when it is a terminal (indicatif hides it otherwise), so piped and
    // captured output stays clean.
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} steps ({per_sec}) {msg}",
    ) {
        bar.set_style(style);
    }
    bar
}

/// The directory `target` is in (`.` for a bare file name).
fn parent_of(target: &Path) -> &Path {
    match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Whether `target` exists and is something other than a regular file or a directory (a
/// device, a FIFO, a socket), which is written in place. Symbolic links are followed.
fn is_special(target: &Path) -> bool {
    std::fs::metadata(target).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// `target` with a symbolic link resolved, so that the finished file replaces what the link
/// points to, not the link.
fn resolved(target: &Path) -> PathBuf {
    match std::fs::symlink_metadata(target) {
        Ok(m) if m.file_type().is_symlink() => {
            std::fs::canonicalize(target).unwrap_or_else(|_| target.to_owned())
        }
        _ => target.to_owned(),
    }
}

/// `e` without the temporary file's path that `tempfile` adds to its errors (`… at path
/// "dir/.name.x1y2z3.partial"`): the messages name the output the user asked for, not the hidden
/// file it is staged in. (`tempfile`'s error type is private, so its text is cut where the path
/// begins.)
fn without_temp_path(e: io::Error) -> io::Error {
    let text = e.to_string();
    match text.rfind(" at path ") {
        Some(at) if text[at..].contains(".partial") => io::Error::new(e.kind(), &text[..at]),
        _ => e,
    }
}

enum Sink {
    Staged(BufWriter<tempfile::NamedTempFile>),
    Direct(BufWriter<File>),
}

/// A file written whole or not at all (see the module docs): dropped without
/// [`OutputFile::finish`], its temporary file is removed and the target is untouched.
pub struct OutputFile {
    target: PathBuf,
    sink: Sink,
}

impl OutputFile {
    /// Starts writing `target`: creates the temporary file beside it (or opens a device in
    /// place). Fails when the directory does not exist or cannot be written, or `target` is a
    /// directory.
    pub fn create(target: &Path) -> io::Result<Self> {
        let target = resolved(target);
        if is_special(&target) {
            let file = File::options().write(true).open(&target)?;
            return Ok(Self {
                target,
                sink: Sink::Direct(BufWriter::new(file)),
            });
        }
        if target.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::IsADirectory,
                "is a directory",
            ));
        }
        if target.is_file() {
            // A file the user could not overwrite in place (write-protected, mode 444) is not
            // replaced by a rename either, as the shell's `>` would refuse it: opening it for
            // writing, without truncating, asks the operating system the same question and
            // changes nothing.
            File::options().write(true).open(&target).map_err(|e| {
                if e.kind() == io::ErrorKind::PermissionDenied {
                    io::Error::new(
                        e.kind(),
                        "is write-protected (not writable by you): make it writable, or choose \
                         another file",
                    )
                } else {
                    e
                }
            })?;
        }
        let name = target
            .file_name()
            .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
        let temp = tempfile::Builder::new()
            .prefix(&format!(".{name}."))
            .suffix(".partial")
            .tempfile_in(parent_of(&target))
            .map_err(without_temp_path)?;
        // A new file gets the permissions a plain create gives under the usual umask (022),
        // not the temporary file's owner-only ones.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&target).map_or(0o644, |m| m.permissions().mode());
            temp.as_file()
                .set_permissions(std::fs::Permissions::from_mode(mode))?;
        }
        Ok(Self {
            target,
            sink: Sink::Staged(BufWriter::new(temp)),
        })
    }

    /// Flushes the bytes and puts the file in place of the target.
    pub fn finish(self) -> io::Result<()> {
        match self.sink {
            Sink::Direct(mut w) => w.flush(),
            Sink::Staged(w) => {
                let temp = w
                    .into_inner()
                    .map_err(|e| without_temp_path(e.into_error()))?;
                temp.as_file().sync_all()?;
                temp.persist(&self.target)
                    .map(|_| ())
                    .map_err(|e| without_temp_path(e.error))
            }
        }
    }
}

impl Write for OutputFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.sink {
            Sink::Staged(w) => w.write(buf).map_err(without_temp_path),
            Sink::Direct(w) => w.write(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match &mut self.sink {
            Sink::Staged(w) => w.flush().map_err(without_temp_path),
            Sink::Direct(w) => w.flush(),
        }
    }
}

/// Files for a directory, written to a hidden temporary directory inside it and moved into it
/// by [`StagedDir::publish`]; dropped unpublished, the temporary directory is removed, and so is
/// the directory itself if this created it.
pub struct StagedDir {
    dir: PathBuf,
    /// Whether `dir` did not exist before.
    created: bool,
    /// Always `Some` until dropped or published.
    staging: Option<tempfile::TempDir>,
}

impl StagedDir {
    /// Creates `dir` (with its parents) if missing, and the temporary directory in it.
    pub fn create(dir: &Path) -> io::Result<Self> {
        let created = !dir.exists();
        std::fs::create_dir_all(dir)?;
        let staging = tempfile::Builder::new()
            .prefix(".hyq-")
            .suffix(".partial")
            .tempdir_in(dir)
            .map_err(without_temp_path);
        let staging = match staging {
            Ok(s) => s,
            Err(e) => {
                if created {
                    let _ = std::fs::remove_dir(dir);
                }
                return Err(e);
            }
        };
        Ok(Self {
            dir: dir.to_owned(),
            created,
            staging: Some(staging),
        })
    }

    /// Where the files are written until they are published.
    pub fn path(&self) -> &Path {
        self.staging.as_ref().map_or(&self.dir, |s| s.path())
    }

    /// Moves every file written so far into the directory (replacing files of the same name);
    /// returns their final paths, by name.
    pub fn publish(mut self) -> io::Result<Vec<PathBuf>> {
        let Some(staging) = self.staging.take() else {
            return Ok(Vec::new());
        };
        let mut names: Vec<_> = std::fs::read_dir(staging.path())?
            .map(|e| e.map(|e| e.file_name()))
            .collect::<io::Result<_>>()?;
        names.sort();
        let mut published = Vec::with_capacity(names.len());
        for name in names {
            let to = self.dir.join(&name);
            std::fs::rename(staging.path().join(&name), &to)?;
            published.push(to);
        }
        self.created = false;
        Ok(published)
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if let Some(staging) = self.staging.take() {
            let _ = staging.close();
            if self.created {
                // Only an empty directory is removed: nothing else was put there.
                let _ = std::fs::remove_dir(&self.dir);
            }
        }
    }
}
