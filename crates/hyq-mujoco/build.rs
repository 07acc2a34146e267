//! Compiles the C shim against MuJoCo 4.0.0's own headers and records where the library is.
//!
//! MuJoCo comes from `cargo xtask setup mujoco`, which unpacks the library and headers into
//! `mujoco` in the target directory (or `$MUJOCO_DIR`). If they are missing, or are another version, the build
//! stops with one message that gives that command, rather than producing a crate that cannot
//! work. The library is not linked: the shim opens it at run time (see `src/world.rs`), from
//! the path recorded here unless `MUJOCO_DIR` is set when the program runs.

use std::path::{Path, PathBuf};
use std::process::exit;

/// The version the shim is written against, as `mjVERSION_HEADER` and as a name.
const VERSION_HEADER: u32 = 4_000_000;
const VERSION: &str = "4.0.0";
const LIBRARY: &str = "libmujoco.so.4.0.0";
const SETUP: &str = "cargo xtask setup mujoco";

fn fail(reason: &str) -> ! {
    eprintln!(
        "\nerror: hyq-mujoco needs MuJoCo {VERSION}'s C library and headers: {reason}.\n\
         Get them (from the package index, into target/mujoco or $MUJOCO_DIR) with:\n\n    \
         {SETUP}\n\n\
         hyq-mujoco is optional: a plain `cargo build` of the workspace does not build it.\n"
    );
    exit(1);
}

/// `$MUJOCO_DIR`, else `mujoco` in the workspace's target directory (`$CARGO_TARGET_DIR`,
/// relative to the workspace root as cargo reads it, else `target/`): where `cargo xtask setup
/// mujoco` puts it.
fn mujoco_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("MUJOCO_DIR").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir);
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    match std::env::var_os("CARGO_TARGET_DIR").filter(|d| !d.is_empty()) {
        Some(target) => root.join(target).join("mujoco"),
        None => root.join("target/mujoco"),
    }
}

fn main() {
    println!("cargo:rerun-if-env-changed=MUJOCO_DIR");
    println!("cargo:rerun-if-env-changed=CARGO_TARGET_DIR");
    println!("cargo:rerun-if-changed=csrc/hyq_mujoco.c");
    println!("cargo:rerun-if-changed=csrc/hyq_mujoco.h");
    println!("cargo:rerun-if-changed=csrc/testing/mujoco_3_3_7.c");
    let dir = mujoco_dir();
    let header = dir.join("include/mujoco/mujoco.h");
    let library = dir.join("lib").join(LIBRARY);
    println!("cargo:rerun-if-changed={}", header.display());
    println!("cargo:rerun-if-changed={}", library.display());
    let text = std::fs::read_to_string(&header)
        .unwrap_or_else(|e| fail(&format!("cannot read {} ({e})", header.display())));
    let found = text
        .lines()
        .find_map(|l| {
            l.trim()
                .strip_prefix("#define mjVERSION_HEADER")
                .and_then(|v| v.trim().parse::<u32>().ok())
        })
        .unwrap_or_else(|| fail(&format!("{} defines no mjVERSION_HEADER", header.display())));
    if found != VERSION_HEADER {
        fail(&format!(
            "{} is MuJoCo {}.{}.{}, this crate is written and tested against {VERSION}",
            header.display(),
            found / 1_000_000,
            found / 1000 % 1000,
            found % 1000
        ));
    }
    if !library.is_file() {
        fail(&format!("{} is missing", library.display()));
    }
    let library = library
        .canonicalize()
        .unwrap_or_else(|e| fail(&format!("cannot resolve {} ({e})", library.display())));

    cc::Build::new()
        .file("csrc/hyq_mujoco.c")
        .include("csrc")
        .include(dir.join("include"))
        .flag_if_supported("-std=gnu11")
        .warnings(true)
        .extra_warnings(true)
        .compile("hyq_mujoco_shim");
    build_other_version();
    // dlopen and dlsym (part of the C library itself since glibc 2.34; a stub library before).
    println!("cargo:rustc-link-lib=dylib=dl");
    println!("cargo:rustc-env=HYQ_MUJOCO_LIBRARY={}", library.display());
}

/// Builds the stand-in for MuJoCo 3.3.7's library (`csrc/testing/mujoco_3_3_7.c`) as a MuJoCo
/// directory in `OUT_DIR`, for the tests of the version check (`HYQ_MUJOCO_OTHER_VERSION_DIR`).
fn build_other_version() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").unwrap_or_else(|| fail("OUT_DIR unset")));
    let dir = out.join("mujoco-3.3.7");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib)
        .unwrap_or_else(|e| fail(&format!("cannot create {} ({e})", lib.display())));
    let compiler = cc::Build::new().get_compiler();
    let status = compiler
        .to_command()
        .args(["-shared", "-fPIC", "-o"])
        .arg(lib.join(LIBRARY))
        .arg("csrc/testing/mujoco_3_3_7.c")
        .status()
        .unwrap_or_else(|e| fail(&format!("cannot run the C compiler ({e})")));
    if !status.success() {
        fail("the C compiler could not build csrc/testing/mujoco_3_3_7.c");
    }
    println!(
        "cargo:rustc-env=HYQ_MUJOCO_OTHER_VERSION_DIR={}",
        dir.display()
    );
}
