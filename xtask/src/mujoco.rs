//! `cargo xtask setup mujoco`: puts MuJoCo 4.0.0's C library and headers where the MuJoCo
//! backend (`crates/hyq-mujoco`) finds them, taken from the package index only.
//!
//! MuJoCo's C library ships inside the Python package `mujoco-core` (the `mujoco` package on
//! PyPI is a thin wrapper that depends on it). Its Linux x86-64 wheel holds
//! `mujoco/libmujoco.so.4.0.0` (no other runtime dependency than the C library) and
//! `mujoco/include/mujoco/*.h`. This command:
//! 1. downloads that one wheel with pip (`pip download --no-deps` for a fixed platform tag, so
//!    the same file is fetched whatever Python runs pip), pip checking it against the sha256
//!    pinned here (`--require-hashes`);
//! 2. unpacks the library, the headers and the licence files into the MuJoCo directory:
//!    `$MUJOCO_DIR` if set, else `mujoco` in the workspace's target directory
//!    (`$CARGO_TARGET_DIR` or `target/`), laid out as MuJoCo's own
//!    release archives are (`lib/libmujoco.so.4.0.0`, `include/mujoco/mujoco.h`), so a
//!    directory unpacked from an official release works too;
//! 3. checks the result the way the backend's build script does (header version 4.0.0).
//!
//! Nothing is installed system-wide; deleting the directory undoes it.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::workspace::workspace_root;

/// The MuJoCo version the backend is written against.
pub const VERSION: &str = "4.0.0";

/// `mjVERSION_HEADER` of that version, as `mujoco.h` defines it.
pub const VERSION_HEADER: u32 = 4_000_000;

/// The wheel holding the C library: its pip requirement and the sha256 pip must find.
const REQUIREMENT: &str = "mujoco-core==4.0.0";
const WHEEL_SHA256: &str = "885bd9b9cc0a6b5ba1114923eb954027652a6a0c115fa46b3218b83bae72ac4f";

/// The wheel's platform and interpreter tags (the library inside does not depend on Python;
/// the tags only pick one file).
const PIP_TAGS: [&str; 8] = [
    "--platform",
    "manylinux_2_28_x86_64",
    "--python-version",
    "3.11",
    "--implementation",
    "cp",
    "--abi",
    "cp311",
];

/// The library's file name inside `lib/`.
pub const LIBRARY: &str = "libmujoco.so.4.0.0";

/// The line that installs pip when it is missing.
const PIP_INSTALL: &str = "sudo apt-get install -y python3 python3-pip";

/// The command that sets MuJoCo up.
pub const SETUP_COMMAND: &str = "cargo xtask setup mujoco";

/// The MuJoCo directory: `$MUJOCO_DIR`, else `mujoco` in the workspace's target directory.
pub fn mujoco_dir(root: &Path) -> PathBuf {
    match std::env::var_os("MUJOCO_DIR") {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir),
        _ => crate::workspace::target_dir(root).join("mujoco"),
    }
}

/// Ok when `dir` holds MuJoCo 4.0.0's header and library; else why not, in one line.
pub fn check(dir: &Path) -> Result<(), String> {
    let header = dir.join("include").join("mujoco").join("mujoco.h");
    let text = std::fs::read_to_string(&header)
        .map_err(|e| format!("cannot read {}: {e}", header.display()))?;
    let found = header_version(&text)
        .ok_or_else(|| format!("{} defines no mjVERSION_HEADER", header.display()))?;
    if found != VERSION_HEADER {
        return Err(format!(
            "{} is MuJoCo {}, the backend needs {VERSION}",
            header.display(),
            version_name(found)
        ));
    }
    let library = dir.join("lib").join(LIBRARY);
    if !library.is_file() {
        return Err(format!("{} is missing", library.display()));
    }
    Ok(())
}

/// `mjVERSION_HEADER` as defined in the text of `mujoco.h`.
pub fn header_version(text: &str) -> Option<u32> {
    text.lines().find_map(|l| {
        l.trim()
            .strip_prefix("#define mjVERSION_HEADER")
            .and_then(|v| v.trim().parse().ok())
    })
}

/// `4000000` → `4.0.0` (MuJoCo numbers versions as major·10⁶ + minor·10³ + patch).
pub fn version_name(header: u32) -> String {
    format!(
        "{}.{}.{}",
        header / 1_000_000,
        header / 1000 % 1000,
        header % 1000
    )
}

/// `cargo xtask setup <what>`.
pub fn setup(args: &[String]) -> Result<(), String> {
    match args {
        [what] if what == "mujoco" => setup_mujoco(),
        [what, ..] if what == "mujoco" => Err(format!(
            "`{SETUP_COMMAND}` takes no further argument (got {:?}); set MUJOCO_DIR to choose \
             the directory",
            &args[1..]
        )),
        _ => Err("`cargo xtask setup` needs what to set up: `cargo xtask setup mujoco`".into()),
    }
}

fn setup_mujoco() -> Result<(), String> {
    let root = workspace_root();
    let dir = mujoco_dir(&root);
    if check(&dir).is_ok() {
        println!("MuJoCo {VERSION} is already set up in {}", dir.display());
        return Ok(());
    }
    if !(cfg!(target_os = "linux") && cfg!(target_arch = "x86_64")) {
        return Err(format!(
            "`{SETUP_COMMAND}` fetches the Linux x86-64 build; on this platform unpack MuJoCo \
             {VERSION}'s release archive and set MUJOCO_DIR to its directory"
        ));
    }
    let python = pip_python()?;
    let (work, wheel) = download_wheel(&python, &dir)?;
    unpack_wheel(&python, &wheel, &dir)?;
    let _ = std::fs::remove_dir_all(&work);
    check(&dir).map_err(|e| format!("after unpacking: {e}"))?;
    println!(
        "MuJoCo {VERSION} is set up in {} (library, headers, licences)",
        dir.display()
    );
    Ok(())
}

/// The Python whose pip downloads the wheel (`$HYQ_PYTHON`, else `python3`), once its pip runs.
fn pip_python() -> Result<String, String> {
    let python = std::env::var("HYQ_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let pip_ok = Command::new(&python)
        .args(["-m", "pip", "--version"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !pip_ok {
        return Err(format!(
            "`{python} -m pip` cannot run; pip downloads MuJoCo from the package index: \
             {PIP_INSTALL}"
        ));
    }
    Ok(python)
}

/// Downloads the pinned wheel with `python`'s pip into `dir/.download`, checked against its
/// sha256; returns that directory and the wheel's path.
fn download_wheel(python: &str, dir: &Path) -> Result<(PathBuf, PathBuf), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let work = dir.join(".download");
    // A previous, interrupted run may have left files here.
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).map_err(|e| format!("cannot create {}: {e}", work.display()))?;
    let requirements = work.join("requirements.txt");
    std::fs::write(
        &requirements,
        format!("{REQUIREMENT} --hash=sha256:{WHEEL_SHA256}\n"),
    )
    .map_err(|e| format!("cannot write {}: {e}", requirements.display()))?;

    let mut pip = Command::new(python);
    pip.args(["-m", "pip", "download", "--no-deps", "--only-binary=:all:"])
        .args(PIP_TAGS)
        .arg("--dest")
        .arg(&work)
        .arg("--requirement")
        .arg(&requirements)
        .env("PIP_DISABLE_PIP_VERSION_CHECK", "1");
    println!("$ {python} -m pip download {REQUIREMENT} (sha256 {WHEEL_SHA256})");
    let status = pip.status().map_err(|e| format!("cannot run pip: {e}"))?;
    if !status.success() {
        return Err(format!(
            "pip could not download {REQUIREMENT} with the pinned sha256 ({status}); see pip's \
             message above"
        ));
    }
    let wheel = std::fs::read_dir(&work)
        .map_err(|e| format!("cannot list {}: {e}", work.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .find(|p| p.extension().is_some_and(|x| x == "whl"))
        .ok_or_else(|| {
            format!(
                "pip reported success but left no wheel in {}",
                work.display()
            )
        })?;
    Ok((work, wheel))
}

/// Unpacks MuJoCo's library, headers and licences from `wheel` into `dir` with `python`.
fn unpack_wheel(python: &str, wheel: &Path, dir: &Path) -> Result<(), String> {
    // Unpack with Python's own zip reader (pip's Python is there by now): the library, the
    // headers and the licences, nothing else.
    let unpack = r#"
import pathlib, shutil, sys, zipfile
wheel, out = sys.argv[1], pathlib.Path(sys.argv[2])
wanted = {}
with zipfile.ZipFile(wheel) as z:
    for name in z.namelist():
        if name == "mujoco/libmujoco.so.4.0.0":
            wanted[name] = out / "lib" / "libmujoco.so.4.0.0"
        elif name.startswith("mujoco/include/mujoco/") and name.endswith(".h"):
            wanted[name] = out / "include" / "mujoco" / pathlib.Path(name).name
        elif name.startswith("mujoco_core-") and ".dist-info/licenses" in name and not name.endswith("/"):
            wanted[name] = out / pathlib.Path(name).name
    if not any(p.name == "libmujoco.so.4.0.0" for p in wanted.values()):
        sys.exit("the wheel holds no mujoco/libmujoco.so.4.0.0")
    for name, target in wanted.items():
        target.parent.mkdir(parents=True, exist_ok=True)
        with z.open(name) as src, open(target, "wb") as dst:
            shutil.copyfileobj(src, dst)
print(f"unpacked {len(wanted)} files")
"#;
    let status = Command::new(python)
        .args(["-c", unpack])
        .arg(wheel)
        .arg(dir)
        .status()
        .map_err(|e| format!("cannot run {python}: {e}"))?;
    if !status.success() {
        return Err(format!("unpacking {} failed ({status})", wheel.display()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_versions_are_read_and_named() {
        let text = "// c\n#define mjVERSION_HEADER 4000000\n\n#define X 1\n";
        assert_eq!(header_version(text), Some(4_000_000));
        assert_eq!(header_version("#define mjVERSION_HEADER\n"), None);
        assert_eq!(version_name(4_000_000), "4.0.0");
        assert_eq!(version_name(3_003_007), "3.3.7");
    }

    #[test]
    fn a_directory_without_mujoco_or_with_another_version_is_refused_by_name() {
        let dir = std::env::temp_dir().join(format!("xtask-mujoco-check-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let err = check(&dir).expect_err("an empty directory holds no MuJoCo");
        assert!(err.contains("mujoco.h"), "{err}");

        let include = dir.join("include").join("mujoco");
        std::fs::create_dir_all(&include).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(
            include.join("mujoco.h"),
            "#define mjVERSION_HEADER 3003007\n",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let err = check(&dir).expect_err("3.3.7 is not 4.0.0");
        assert!(err.contains("3.3.7") && err.contains("4.0.0"), "{err}");

        std::fs::write(
            include.join("mujoco.h"),
            "#define mjVERSION_HEADER 4000000\n",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let err = check(&dir).expect_err("the library is missing");
        assert!(err.contains(LIBRARY), "{err}");

        std::fs::create_dir_all(dir.join("lib")).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(dir.join("lib").join(LIBRARY), b"").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(check(&dir), Ok(()));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn setup_names_what_it_sets_up() {
        use crate::cli::strings;
        let err = setup(&[]).expect_err("nothing named");
        assert!(err.contains("cargo xtask setup mujoco"), "{err}");
        let err = setup(&strings(&["dart"])).expect_err("only mujoco");
        assert!(err.contains("cargo xtask setup mujoco"), "{err}");
        let err = setup(&strings(&["mujoco", "--force"])).expect_err("no extra arguments");
        assert!(err.contains("--force"), "{err}");
    }
}
