//! A user's height file becomes the grid it describes, whatever its format: a NumPy `.npy`
//! array `a[i, j]` is the height at the i-th x and the j-th y (any float or integer dtype,
//! either byte order, C or Fortran order), a grayscale PNG is a map seen from above (its top
//! row the far edge, highest y), and both are scaled by the vertical scale. A file that cannot
//! be used is refused with one line naming the file and what is wrong: missing, unknown
//! extension, not what its extension says, not numeric, not finite, not 2-D, too small, too
//! large (the cap of 1024 × 1024 values), truncated, or coloured.

use std::path::{Path, PathBuf};

use hyq_physics::terrain::file::{Placement, read};
use hyq_physics::terrain::{HeightGrid, TerrainError};

fn placement(scale: f64) -> Placement {
    Placement {
        center: [0.0, 0.0],
        size: [2.0, 1.0],
        vertical_scale: scale,
    }
}

/// A `.npy` file of `shape` with `descr`, the header's dictionary as NumPy writes it.
fn npy(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut header = format!(
        "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
        if fortran { "True" } else { "False" }
    );
    // Pad to a multiple of 64 bytes with spaces and a newline, as NumPy does.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write a test file");
    path
}

/// A 3 × 2 array (3 along x, 2 along y): a[i, j] = 10 i + j.
const A: [[f64; 2]; 3] = [[0.0, 1.0], [10.0, 11.0], [20.0, 21.0]];

/// The grid's height at the i-th x and j-th y sample.
fn at(g: &HeightGrid, i: usize, j: usize) -> f64 {
    g.height(i, j)
}

#[test]
fn npy_arrays_run_x_then_y_in_every_dtype_and_order() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let c_order: Vec<f64> = A.iter().flatten().copied().collect();
    let f_order: Vec<f64> = (0..2).flat_map(|j| (0..3).map(move |i| A[i][j])).collect();
    let cases: Vec<(&str, bool, Vec<u8>)> = vec![
        (
            "<f8",
            false,
            c_order.iter().flat_map(|v| v.to_le_bytes()).collect(),
        ),
        (
            ">f8",
            false,
            c_order.iter().flat_map(|v| v.to_be_bytes()).collect(),
        ),
        (
            "<f4",
            false,
            c_order
                .iter()
                .flat_map(|v| (*v as f32).to_le_bytes())
                .collect(),
        ),
        (
            "<f8",
            true,
            f_order.iter().flat_map(|v| v.to_le_bytes()).collect(),
        ),
        (
            "<i2",
            false,
            c_order
                .iter()
                .flat_map(|v| (*v as i16).to_le_bytes())
                .collect(),
        ),
        ("|u1", false, c_order.iter().map(|v| *v as u8).collect()),
        (
            "<i8",
            false,
            c_order
                .iter()
                .flat_map(|v| (*v as i64).to_le_bytes())
                .collect(),
        ),
    ];
    for (descr, fortran, data) in cases {
        let path = write(dir.path(), "a.npy", &npy(descr, fortran, "(3, 2)", &data));
        let g = read(&path, &placement(0.01)).unwrap_or_else(|e| panic!("{descr}: {e}"));
        assert_eq!((g.columns(), g.rows()), (3, 2), "{descr}");
        for (i, row) in A.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!(
                    (at(&g, i, j) - 0.01 * v).abs() < 1e-12,
                    "{descr} fortran {fortran}: [{i}, {j}]"
                );
            }
        }
        // The first axis runs along +x: its last value sits on the rectangle's +x edge.
        assert!((g.height_at(1.0, -0.5) - 0.2).abs() < 1e-12, "{descr}");
    }
    // Negative integers keep their sign.
    let path = write(
        dir.path(),
        "neg.npy",
        &npy(
            "<i4",
            false,
            "(2, 2)",
            &[-3i32, 4, -5, 6]
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect::<Vec<_>>(),
        ),
    );
    let g = read(&path, &placement(1.0)).expect("valid");
    assert_eq!((at(&g, 0, 0), at(&g, 1, 0)), (-3.0, -5.0));
}

/// A grayscale PNG of `width` × `height` with `pixels` (row 0 at the top) at `depth` bits.
fn png(
    width: u32,
    height: u32,
    color: png::ColorType,
    depth: png::BitDepth,
    pixels: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(color);
        encoder.set_depth(depth);
        let mut writer = encoder.write_header().expect("png header");
        writer.write_image_data(pixels).expect("png data");
    }
    out
}

#[test]
fn png_images_are_maps_seen_from_above() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    // 3 wide, 2 high: top row black, grey, white; bottom row white, black, black.
    let eight = png(
        3,
        2,
        png::ColorType::Grayscale,
        png::BitDepth::Eight,
        &[0, 51, 255, 255, 0, 0],
    );
    let path = write(dir.path(), "map.PNG", &eight);
    let g = read(&path, &placement(0.5)).expect("valid");
    assert_eq!((g.columns(), g.rows()), (3, 2));
    // The top row is the far edge (highest y, row 1 of the grid).
    assert_eq!((at(&g, 0, 1), at(&g, 1, 1), at(&g, 2, 1)), (0.0, 0.1, 0.5));
    assert_eq!((at(&g, 0, 0), at(&g, 1, 0), at(&g, 2, 0)), (0.5, 0.0, 0.0));
    let sixteen: Vec<u8> = [0u16, 65535, 13107, 0, 0, 65535]
        .iter()
        .flat_map(|v| v.to_be_bytes())
        .collect();
    let path = write(
        dir.path(),
        "deep.png",
        &png(
            3,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &sixteen,
        ),
    );
    let g = read(&path, &placement(1.0)).expect("valid");
    assert_eq!((at(&g, 1, 1), at(&g, 2, 1)), (1.0, 0.2));
    // Gray pixels stored as RGB are gray.
    let rgb = png(
        2,
        2,
        png::ColorType::Rgb,
        png::BitDepth::Eight,
        &[9, 9, 9, 0, 0, 0, 255, 255, 255, 3, 3, 3],
    );
    let path = write(dir.path(), "rgb.png", &rgb);
    assert!(read(&path, &placement(1.0)).is_ok());
}

/// The one-line message of a refused file.
fn refused(path: &Path, placement: &Placement) -> String {
    let err = read(path, placement).expect_err("the file must be refused");
    assert!(matches!(err, TerrainError::File { .. }), "{err:?}");
    let text = err.to_string();
    assert!(
        text.contains(&path.display().to_string()),
        "the message names the file: {text}"
    );
    assert!(!text.contains('\n'), "one line: {text}");
    text
}

#[test]
fn unusable_files_are_refused_naming_the_file_and_the_fault() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let d = dir.path();
    let f8 = |values: &[f64]| {
        values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>()
    };
    let p = placement(1.0);
    let cases: Vec<(PathBuf, &str)> = vec![
        (d.join("missing.npy"), "cannot read it"),
        (write(d, "heights.csv", b"1,2\n3,4\n"), "unknown format"),
        (
            write(d, "text.npy", b"just some text, long enough"),
            "not a NumPy",
        ),
        (
            write(d, "strings.npy", &npy("<U3", false, "(2, 2)", &[0; 48])),
            "not numeric",
        ),
        (
            write(d, "bools.npy", &npy("|b1", false, "(2, 2)", &[0; 4])),
            "not numeric",
        ),
        (
            write(d, "half.npy", &npy("<f2", false, "(2, 2)", &[0; 8])),
            "not numeric",
        ),
        (
            write(
                d,
                "nan.npy",
                &npy("<f8", false, "(2, 2)", &f8(&[0.0, 1.0, f64::NAN, 0.0])),
            ),
            "not finite",
        ),
        (
            write(
                d,
                "inf.npy",
                &npy("<f8", false, "(2, 2)", &f8(&[0.0, f64::INFINITY, 0.0, 0.0])),
            ),
            "not finite",
        ),
        (
            write(d, "flat.npy", &npy("<f8", false, "(4,)", &f8(&[0.0; 4]))),
            "1 dimensions",
        ),
        (
            write(
                d,
                "cube.npy",
                &npy("<f8", false, "(2, 2, 2)", &f8(&[0.0; 8])),
            ),
            "3 dimensions",
        ),
        (
            write(d, "thin.npy", &npy("<f8", false, "(1, 5)", &f8(&[0.0; 5]))),
            "at least 2",
        ),
        (
            write(d, "short.npy", &npy("<f8", false, "(3, 3)", &f8(&[0.0; 5]))),
            "truncated",
        ),
        (
            write(d, "huge.npy", &npy("<f8", false, "(2048, 1024)", &[])),
            "too large",
        ),
        (
            write(
                d,
                "tall.npy",
                &npy("<f8", false, "(2, 2)", &f8(&[0.0, 0.0, 0.0, 500.0])),
            ),
            "beyond",
        ),
        (
            write(d, "garbage.png", b"\x89PNG\r\n\x1a\nnot really"),
            "not a readable PNG",
        ),
        (
            write(
                d,
                "colour.png",
                &png(
                    2,
                    2,
                    png::ColorType::Rgb,
                    png::BitDepth::Eight,
                    &[9, 9, 9, 200, 0, 0, 1, 1, 1, 3, 3, 3],
                ),
            ),
            "coloured",
        ),
        (
            write(
                d,
                "dot.png",
                &png(1, 1, png::ColorType::Grayscale, png::BitDepth::Eight, &[7]),
            ),
            "at least 2",
        ),
    ];
    for (path, fault) in &cases {
        let text = refused(path, &p);
        assert!(
            text.contains(fault),
            "{}: expected {fault:?} in {text}",
            path.display()
        );
    }
    // A header holding control bytes (as a cut or garbled file does) is quoted escaped, in one
    // printable line.
    let garbled = write(
        d,
        "garbled.npy",
        &npy("<f8", false, "(9, \u{1}\u{1b}[31m\0\0)", &[]),
    );
    let text = refused(&garbled, &p);
    assert!(
        text.contains("is not numbers") && !text.chars().any(char::is_control),
        "{text:?}"
    );
    let ok = write(d, "ok.npy", &npy("<f8", false, "(2, 2)", &f8(&[0.0; 4])));
    for scale in [0.0, -1.0, f64::NAN] {
        let text = refused(&ok, &placement(scale));
        assert!(text.contains("vertical scale"), "{text}");
    }
    // A file over the byte cap is refused before it is read.
    let big = d.join("big.npy");
    let file = std::fs::File::create(&big).expect("create");
    file.set_len(hyq_physics::terrain::file::MAX_FILE_BYTES + 1)
        .expect("grow");
    assert!(refused(&big, &p).contains("too large"));
}
