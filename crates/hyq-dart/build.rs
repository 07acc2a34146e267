//! Compiles the C++ side of the DART bridge and links Debian's DART 6.12.
//!
//! If DART's development files are missing, the build stops with one message that gives the
//! install line, rather than producing a crate that cannot work.

use std::path::Path;
use std::process::exit;

/// The one line that installs everything this crate needs on Debian 12 / Ubuntu.
const INSTALL: &str = "apt-get install -y libdart-dev libdart-collision-bullet-dev";

/// Headers whose presence proves the packages above are installed.
const REQUIRED_HEADERS: [&str; 3] = [
    "/usr/include/dart/config.hpp",
    "/usr/include/dart/collision/bullet/BulletCollisionDetector.hpp",
    "/usr/include/eigen3/Eigen/Core",
];

fn fail(reason: &str) -> ! {
    eprintln!(
        "\nerror: hyq-dart needs DART 6.12 with its Bullet collision detector: {reason}.\n\
         Install it with (as root, after `apt-get update`):\n\n    {INSTALL}\n\n\
         hyq-dart is optional: a plain `cargo build` of the workspace does not build it.\n"
    );
    exit(1);
}

fn main() {
    println!("cargo:rerun-if-changed=include/hyq_dart.h");
    println!("cargo:rerun-if-changed=src/hyq_dart.cc");
    for header in REQUIRED_HEADERS {
        println!("cargo:rerun-if-changed={header}");
        if !Path::new(header).exists() {
            fail(&format!("{header} not found"));
        }
    }
    let config = std::fs::read_to_string(REQUIRED_HEADERS[0])
        .unwrap_or_else(|e| fail(&format!("cannot read {}: {e}", REQUIRED_HEADERS[0])));
    let version = |name: &str| {
        config
            .lines()
            .find_map(|l| l.strip_prefix(&format!("#define {name} ")))
            .map(str::trim)
            .map(str::to_owned)
    };
    let (major, minor) = (version("DART_MAJOR_VERSION"), version("DART_MINOR_VERSION"));
    if major.as_deref() != Some("6") || minor.as_deref() != Some("12") {
        fail(&format!(
            "found DART {}.{} in /usr/include/dart, this crate is written and tested against 6.12",
            major.as_deref().unwrap_or("?"),
            minor.as_deref().unwrap_or("?")
        ));
    }

    cxx_build::bridge("src/bridge.rs")
        .file("src/hyq_dart.cc")
        .std("c++17")
        .include("/usr/include/eigen3")
        .include("/usr/include/bullet")
        // DART's own headers use APIs it has deprecated; those warnings are not ours to fix.
        .flag_if_supported("-Wno-deprecated-declarations")
        .compile("hyq_dart_bridge");

    // `LinearMath` resolves Bullet's aligned allocator, used by inline code in Bullet's headers.
    for lib in ["dart", "dart-collision-bullet", "LinearMath"] {
        println!("cargo:rustc-link-lib=dylib={lib}");
    }
}
