//! Height grids read from a user's file: a NumPy `.npy` array or a grayscale PNG image, laid over
//! a rectangle of the world and scaled vertically.
//!
//! Orientation (so that a file means the same ground whichever format it is in):
//! - `.npy`: a 2-D array `a[i, j]` is the height at the i-th x and the j-th y (legged_gym's and
//!   Isaac Gym's `height_field_raw` convention): the first axis runs along +x, the second along
//!   +y. Any float or integer dtype, either byte order, C or Fortran order. Heights (m) are the
//!   values times the vertical scale.
//! - PNG: a map seen from above: the image's columns run along +x (left to right) and its rows
//!   along −y (the top row is the far edge, highest y: MuJoCo's reading of a PNG height field).
//!   Grayscale, 8 or 16 bits, with or without alpha (an RGB image is accepted when every pixel
//!   is gray). Heights (m) are the intensities scaled to [0, 1] (black 0, white 1) times the
//!   vertical scale.
//!
//! Refused with one line naming the file: a missing or unreadable file, a file larger than
//! [`MAX_FILE_BYTES`], an unknown extension, a file that is not what its extension says, a
//! non-numeric dtype, a value that is not finite, an array that is not 2-D or has fewer than 2
//! values along a side, and more than [`super::MAX_GRID_POINTS`] values (1024 × 1024).

use std::path::Path;

use super::{HeightGrid, MAX_GRID_POINTS, TerrainError};

/// The largest height file read (bytes): a grid at the cap in `f64` plus room for a header
/// ([`crate::input::HEIGHT_FILE`]).
pub const MAX_FILE_BYTES: u64 = crate::input::HEIGHT_FILE.max_bytes;

/// Where a file's grid lies and how its values scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The rectangle's centre (m, world x and y).
    pub center: [f64; 2],
    /// The rectangle's side lengths (m, along x and y): the first and last values along each
    /// axis sit on its edges.
    pub size: [f64; 2],
    /// Metres per unit of the file's values (`.npy`), or the height of white (PNG). Finite
    /// and > 0.
    pub vertical_scale: f64,
}

/// A file's values: `values[k * columns + c]` at the c-th x and the k-th y.
struct Values {
    columns: usize,
    rows: usize,
    values: Vec<f64>,
}

/// Reads the height file at `path` (`.npy` or `.png`, by extension) and lays it over
/// `placement`.
pub fn read(path: &Path, placement: &Placement) -> Result<HeightGrid, TerrainError> {
    let fail = |reason: String| TerrainError::File {
        path: path.to_owned(),
        reason,
    };
    let scale = placement.vertical_scale;
    if !(scale.is_finite() && scale > 0.0) {
        return Err(fail(format!(
            "vertical scale {scale} must be finite and > 0"
        )));
    }
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let parse: fn(&[u8]) -> Result<Values, String> = match extension.as_deref() {
        Some("npy") => parse_npy,
        Some("png") => parse_png,
        _ => {
            return Err(fail(
                "unknown format: the name must end in .npy (NumPy) or .png".into(),
            ));
        }
    };
    let bytes = read_capped(path).map_err(fail)?;
    let Values {
        columns,
        rows,
        values,
    } = parse(&bytes).map_err(fail)?;
    let heights = values.iter().map(|v| v * scale).collect();
    HeightGrid::new(placement.center, placement.size, columns, rows, heights).map_err(|e| {
        fail(match e {
            TerrainError::Invalid { what, reason } => format!("{what}: {reason}"),
            other => other.to_string(),
        })
    })
}

/// The file's bytes, through the capped reader every user file goes through
/// ([`crate::input::read_bytes`]), under its rule: only a regular file is opened (opening a
/// FIFO would wait for a writer forever), a file over [`MAX_FILE_BYTES`] is refused from its
/// size before it is read, and one that grows past the cap while it is read stops one byte
/// past it.
fn read_capped(path: &Path) -> Result<Vec<u8>, String> {
    crate::input::read_bytes(path, &crate::input::HEIGHT_FILE).map_err(|e| match e.kind() {
        std::io::ErrorKind::FileTooLarge => {
            let bytes = std::fs::metadata(path).map_or(0, |m| m.len());
            let size = if bytes > MAX_FILE_BYTES {
                format!("{bytes} bytes")
            } else {
                "the file, grown while read,".into()
            };
            format!(
                "{size} is too large (the cap is {MAX_FILE_BYTES} bytes, a grid of \
                 {MAX_GRID_POINTS} heights)"
            )
        }
        std::io::ErrorKind::InvalidInput => e.to_string(),
        _ => format!("cannot read it: {e}"),
    })
}

/// Checks a grid's counts against the cap and the minimum of 2 per side.
fn check_counts(columns: usize, rows: usize) -> Result<(), String> {
    if columns < 2 || rows < 2 {
        return Err(format!(
            "{columns} × {rows} values: at least 2 are needed along each side"
        ));
    }
    if columns
        .checked_mul(rows)
        .is_none_or(|n| n > MAX_GRID_POINTS)
    {
        return Err(format!(
            "{columns} × {rows} values is too large (the cap is {MAX_GRID_POINTS} values, \
             1024 × 1024)"
        ));
    }
    Ok(())
}

/// The first non-finite value, as an error naming where it is.
fn check_finite(v: &Values, describe: impl Fn(usize, usize) -> String) -> Result<(), String> {
    match v.values.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(format!(
            "value {} at {} is not finite",
            v.values[i],
            describe(i % v.columns, i / v.columns)
        )),
        None => Ok(()),
    }
}

/// A NumPy element type this reader converts.
#[derive(Clone, Copy)]
struct Dtype {
    kind: u8,
    size: usize,
    big_endian: bool,
}

impl Dtype {
    /// Parses a simple `descr` such as `<f8` or `|u1`.
    fn parse(descr: &str) -> Result<Self, String> {
        let b = descr.as_bytes();
        let numeric = b.len() >= 3
            && matches!(b[0], b'<' | b'>' | b'|' | b'=')
            && matches!(b[1], b'f' | b'i' | b'u');
        let size = descr.get(2..).and_then(|s| s.parse::<usize>().ok());
        match (numeric, size) {
            (true, Some(size @ (1 | 2 | 4 | 8))) if !(b[1] == b'f' && size < 4) => Ok(Self {
                kind: b[1],
                size,
                big_endian: b[0] == b'>',
            }),
            _ => Err(format!(
                "dtype {} is not numeric (expected float32, float64 or an integer type)",
                excerpt(descr)
            )),
        }
    }

    /// The element in `bytes` (exactly `size` of them) as f64.
    fn value(self, bytes: &[u8]) -> f64 {
        let mut le = [0u8; 8];
        le[..self.size].copy_from_slice(bytes);
        if self.big_endian {
            le[..self.size].reverse();
        }
        let bits = u64::from_le_bytes(le);
        // Sign-extend integers from their width.
        let shift = 64 - 8 * self.size as u32;
        match (self.kind, self.size) {
            (b'f', 4) => f64::from(f32::from_bits(bits as u32)),
            (b'f', _) => f64::from_bits(bits),
            (b'i', _) => (((bits << shift) as i64) >> shift) as f64,
            _ => bits as f64,
        }
    }
}

/// A header's text as a message quotes it: escaped (it may hold any byte a file holds) and cut
/// to 40 characters.
fn excerpt(text: &str) -> String {
    let cut: String = text.chars().take(40).collect();
    if cut.len() < text.len() {
        format!("{cut:?}…")
    } else {
        format!("{cut:?}")
    }
}

/// The value of `key` in a `.npy` header's dictionary text: the text after `'key':` up to the
/// next top-level comma or the closing brace.
fn header_field<'a>(header: &'a str, key: &str) -> Result<&'a str, String> {
    let tag = format!("'{key}':");
    let start = header
        .find(&tag)
        .ok_or_else(|| format!("the .npy header has no {key:?} entry"))?
        + tag.len();
    let rest = &header[start..];
    let mut depth = 0i32;
    for (i, ch) in rest.char_indices() {
        match ch {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | '}' if depth == 0 => return Ok(rest[..i].trim()),
            _ => {}
        }
    }
    Ok(rest.trim())
}

/// Parses a `.npy` file: header, dtype, 2-D shape, values.
fn parse_npy(bytes: &[u8]) -> Result<Values, String> {
    if !bytes.starts_with(b"\x93NUMPY") || bytes.len() < 10 {
        return Err("not a NumPy .npy file (no \\x93NUMPY magic)".into());
    }
    let (header_len, data_at) = match bytes[6] {
        1 => (usize::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10),
        2 | 3 if bytes.len() >= 12 => {
            let n = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]);
            (n as usize, 12)
        }
        v => return Err(format!("unsupported .npy format version {v}")),
    };
    let header = bytes
        .get(data_at..data_at + header_len)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or("the .npy header is truncated or not text")?;
    let descr = header_field(header, "descr")?;
    let dtype = Dtype::parse(descr.trim_matches(|c| c == '\'' || c == '"'))?;
    let fortran = match header_field(header, "fortran_order")? {
        "True" => true,
        "False" => false,
        other => {
            return Err(format!(
                "fortran_order {} is not True or False",
                excerpt(other)
            ));
        }
    };
    let shape_text = header_field(header, "shape")?;
    let shape: Vec<usize> = shape_text
        .trim_matches(|c| c == '(' || c == ')')
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<usize>()
                .map_err(|_| format!("shape {} is not numbers", excerpt(shape_text)))
        })
        .collect::<Result<_, _>>()?;
    let [nx, ny] = shape[..] else {
        return Err(format!(
            "shape {} has {} dimensions: a 2-D array (x, y) is needed",
            excerpt(shape_text),
            shape.len()
        ));
    };
    check_counts(nx, ny)?;
    let data = &bytes[data_at + header_len..];
    let needed = nx * ny * dtype.size;
    if data.len() < needed {
        return Err(format!(
            "truncated: shape {} needs {needed} bytes of data, the file has {}",
            excerpt(shape_text),
            data.len()
        ));
    }
    let mut values = vec![0.0; nx * ny];
    for i in 0..nx {
        for j in 0..ny {
            let element = if fortran { j * nx + i } else { i * ny + j };
            let at = element * dtype.size;
            values[j * nx + i] = dtype.value(&data[at..at + dtype.size]);
        }
    }
    let v = Values {
        columns: nx,
        rows: ny,
        values,
    };
    check_finite(&v, |c, k| format!("index [{c}, {k}]"))?;
    Ok(v)
}

/// Parses a grayscale PNG: row 0 is the far edge (highest y).
fn parse_png(bytes: &[u8]) -> Result<Values, String> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder
        .read_info()
        .map_err(|e| format!("not a readable PNG image ({e})"))?;
    let (width, height) = reader.info().size();
    let (columns, rows) = (width as usize, height as usize);
    check_counts(columns, rows)?;
    let size = reader
        .output_buffer_size()
        .ok_or("the PNG image is too large to decode")?;
    let mut buffer = vec![0u8; size];
    let frame = reader
        .next_frame(&mut buffer)
        .map_err(|e| format!("not a readable PNG image ({e})"))?;
    let channels = frame.color_type.samples();
    let (bytes_per_sample, full) = match frame.bit_depth {
        png::BitDepth::Sixteen => (2, 65535.0),
        _ => (1, 255.0),
    };
    let sample = |at: usize| -> f64 {
        if bytes_per_sample == 2 {
            f64::from(u16::from_be_bytes([buffer[at], buffer[at + 1]]))
        } else {
            f64::from(buffer[at])
        }
    };
    let colour = matches!(frame.color_type, png::ColorType::Rgb | png::ColorType::Rgba);
    let mut values = vec![0.0; columns * rows];
    for r in 0..rows {
        for c in 0..columns {
            let at = r * frame.line_size + c * channels * bytes_per_sample;
            let gray = sample(at);
            if colour
                && (sample(at + bytes_per_sample) != gray
                    || sample(at + 2 * bytes_per_sample) != gray)
            {
                return Err(format!(
                    "pixel (column {c}, row {r}) is coloured: heights come from a grayscale \
                     image"
                ));
            }
            values[(rows - 1 - r) * columns + c] = gray / full;
        }
    }
    Ok(Values {
        columns,
        rows,
        values,
    })
}
