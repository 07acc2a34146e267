//! Invariant: `hyq render` writes an episode as an animated GIF (a path ending in `.gif`) or as
//! numbered PNG frames (a directory), every frame of the requested size, one frame per 1/fps
//! simulated seconds from the reset on, each showing a scene (not one flat colour) with the
//! trunk at the image centre, changing as the robot moves; the same seed writes the same frames; and bad `--out`, `--width`,
//! `--fps` or `--seconds` values are refused with one error line naming them; the printed summary
//! ends with the distance to the goal, or under the velocity task with the command and the trunk's
//! velocity.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::Path;

use common::{hyq_ok, scratch, usage_error_naming};

/// A fresh scratch directory (removed first if it exists).
fn scratch_dir(name: &str) -> std::path::PathBuf {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Decodes an RGB PNG: (width, height, bytes).
fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb, "{}", path.display());
    assert_eq!(info.bit_depth, png::BitDepth::Eight, "{}", path.display());
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// How many distinct RGB colours an image holds.
fn colours(rgb: &[u8]) -> usize {
    let mut set: Vec<[u8; 3]> = rgb.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    set.sort_unstable();
    set.dedup();
    set.len()
}

fn png_frames(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
}

#[test]
fn gif_has_one_frame_per_period_at_the_requested_size() {
    let out = scratch("render_trot.gif");
    // 0.4 s at 10 fps: frames at 0, 0.1, 0.2, 0.3 and 0.4 s.
    let stdout = hyq_ok(&[
        "render",
        "--seconds",
        "0.4",
        "--fps",
        "10",
        "--width",
        "96",
        "--height",
        "64",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(stdout.contains("wrote 5 frames"), "{stdout}");
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(&out).unwrap())
        .unwrap();
    assert_eq!((decoder.width(), decoder.height()), (96, 64));
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(
            frame.delay, 10,
            "10 fps is 10 hundredths of a second per frame"
        );
        assert_eq!((frame.width, frame.height), (96, 64));
        frames.push(frame.buffer.to_vec());
    }
    assert_eq!(frames.len(), 5);
    for f in &frames {
        assert_eq!(f.len(), 96 * 64 * 4);
        let rgb: Vec<u8> = f.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        assert!(colours(&rgb) > 20, "a frame of {} colours", colours(&rgb));
    }
    // The trot moves the robot and the overlay's clock runs: no two frames are the same.
    for pair in frames.windows(2) {
        assert_ne!(pair[0], pair[1]);
    }
}

#[test]
fn png_directory_gets_numbered_frames_and_the_same_seed_gives_the_same_bytes() {
    let args = |dir: &str| {
        vec![
            "render".to_owned(),
            "--policy".into(),
            "random".into(),
            "--seed".into(),
            "3".into(),
            "--seconds".into(),
            "0.1".into(),
            "--fps".into(),
            "50".into(),
            "--width".into(),
            "80".into(),
            "--height".into(),
            "60".into(),
            "--out".into(),
            dir.to_owned(),
        ]
    };
    let a = scratch_dir("render_pngs_a");
    let b = scratch_dir("render_pngs_b");
    // A path ending in `/` is a directory, created if missing.
    let a_arg = format!("{}/", a.display());
    let args_a = args(&a_arg);
    hyq_ok(&args_a.iter().map(String::as_str).collect::<Vec<_>>());
    // An existing directory without the trailing `/` is a directory too.
    std::fs::create_dir_all(&b).unwrap();
    let args_b = args(b.to_str().unwrap());
    hyq_ok(&args_b.iter().map(String::as_str).collect::<Vec<_>>());

    let files = png_frames(&a);
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    // 0.1 s at 50 fps: frames at 0, 0.02, …, 0.1 s.
    assert_eq!(
        names,
        (0..6)
            .map(|i| format!("frame_{i:06}.png"))
            .collect::<Vec<_>>()
    );
    for f in &files {
        let (w, h, rgb) = decode_png(f);
        assert_eq!((w, h), (80, 60));
        assert_eq!(rgb.len(), 80 * 60 * 3);
        assert!(
            colours(&rgb) > 20,
            "{}: {} colours",
            f.display(),
            colours(&rgb)
        );
        // The camera follows the trunk, whose centre projects to the image centre: that pixel
        // is the trunk's steel blue, not the pale ground or sky.
        let i = (30 * 80 + 40) * 3;
        let [r, g, b] = [rgb[i], rgb[i + 1], rgb[i + 2]];
        assert!(
            b > r + 30 && b < 220,
            "{}: centre pixel {:?} is not the trunk",
            f.display(),
            [r, g, b]
        );
    }
    let files_b = png_frames(&b);
    assert_eq!(files.len(), files_b.len());
    for (fa, fb) in files.iter().zip(&files_b) {
        assert_eq!(std::fs::read(fa).unwrap(), std::fs::read(fb).unwrap());
    }
}

#[test]
fn bad_render_options_are_one_line_errors_naming_them() {
    let mp4 = scratch("render_out.mp4");
    usage_error_naming(
        &["render", "--seconds", "0.1", "--out", mp4.to_str().unwrap()],
        &["--out", "render_out.mp4", ".gif"],
    );
    assert!(!mp4.exists(), "nothing is written for a refused --out");
    usage_error_naming(
        &["render", "--width", "0", "--out", "x.gif"],
        &["--width", "0"],
    );
    usage_error_naming(
        &["render", "--fps", "60", "--out", "x.gif"],
        &["--fps", "60", "50"],
    );
    usage_error_naming(
        &["render", "--fps", "200", "--out", "frames/"],
        &["--fps", "200", "100"],
    );
    usage_error_naming(
        &["render", "--seconds=-1", "--out", "x.gif"],
        &["--seconds", "-1"],
    );
    usage_error_naming(
        &["render", "--out", "/nonexistent-dir/sub/x.gif"],
        &["--out", "/nonexistent-dir/sub/x.gif"],
    );
}

#[test]
fn the_summary_ends_with_the_command_and_velocity_under_the_velocity_task_and_the_goal_otherwise() {
    let run = |name: &str, extra: &[&str]| {
        let out = scratch(name);
        let mut args = vec![
            "render",
            "--seconds",
            "0.1",
            "--fps",
            "10",
            "--width",
            "400",
            "--height",
            "300",
        ];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", out.to_str().unwrap()]);
        hyq_ok(&args)
    };
    let goal = run("render_goal_summary.gif", &[]);
    assert!(goal.contains("distance to goal"), "{goal}");
    let fixed = [
        "--set",
        "task.kind=\"velocity\"",
        "--set",
        "command.lin_vel_x=[0.4, 0.4]",
        "--set",
        "command.lin_vel_y=[0.0, 0.0]",
        "--set",
        "command.ang_vel_yaw=[0.0, 0.0]",
    ];
    let velocity = run("render_velocity_summary.gif", &fixed);
    assert!(!velocity.contains("distance to goal"), "{velocity}");
    assert!(
        velocity.contains("command v_x 0.400 m/s, v_y 0.000 m/s, yaw rate 0.000 rad/s, trunk v_x "),
        "{velocity}"
    );
}
